"""Shift+A > Mesh > Banyan menu and the View3D sidebar tab "Banyan"."""
import textwrap

import bpy

from ..engine import hosts as H
from ..core import presets as PR
from . import state


class VIEW3D_MT_banyan_add(bpy.types.Menu):
    bl_idname = "VIEW3D_MT_banyan_add"
    bl_label = "Banyan"

    def draw(self, context):
        layout = self.layout
        layout.operator_context = 'INVOKE_REGION_WIN'
        for idname, label in state.operator_entries():
            layout.operator(idname, text=label)


class VIEW3D_PT_banyan(bpy.types.Panel):
    bl_idname = "VIEW3D_PT_banyan"
    bl_label = "Banyan"
    bl_space_type = 'VIEW_3D'
    bl_region_type = 'UI'
    bl_category = "Banyan"

    def draw(self, context):
        layout = self.layout
        col = layout.column(align=True)
        for idname, label in state.operator_entries():
            col.operator(idname, text=label)
        if not any(o.type in H.SURFACE_TYPES for o in getattr(context, "selected_objects", None) or ()):
            # Why Roots and Ivy are greyed out (their tooltips say it too).
            layout.label(text="Select the objects to grow on", icon='INFO')
        broken = PR.broken_presets()
        if broken:
            box = layout.box()
            box.label(text="Broken presets", icon='ERROR')
            for key, path, err in broken:
                col = box.column(align=True)
                col.label(text=key)
                for line in textwrap.wrap(err, 40):  # a label does not wrap
                    col.label(text=line)
        box = layout.box()
        box.label(text="libbanyan %s" % state.VERSION)
        if state.ERRORS:
            for e in state.ERRORS:
                box.label(text=e, icon='ERROR')


def menu_func(self, context):
    self.layout.menu(VIEW3D_MT_banyan_add.bl_idname, icon='OUTLINER_OB_MESH')


class VIEW3D_PT_banyan_error(bpy.types.Panel):
    """Shown instead of everything else when the library failed to load."""
    bl_idname = "VIEW3D_PT_banyan_error"
    bl_label = "Banyan"
    bl_space_type = 'VIEW_3D'
    bl_region_type = 'UI'
    bl_category = "Banyan"

    def draw(self, context):
        for line in state.LOAD_ERROR.split("; "):
            self.layout.label(text=line, icon='ERROR')


def _kind(package):
    return "the 4.2+ extension" if package.startswith("bl_ext.") else "the legacy add-on"


def other_copy_message(other, folder, mine):
    """What a second enabled copy of the add-on says (register())."""
    return ("Banyan is already enabled as %s '%s' (%s); this copy, %s '%s', is not. Keep one: disable and "
            "remove the other in Edit > Preferences > %s, then restart Blender"
            % (_kind(other), other, folder, _kind(mine), mine,
               "Get Extensions" if other.startswith("bl_ext.") else "Add-ons"))


class VIEW3D_PT_banyan_other_copy(bpy.types.Panel):
    """Shown by a second enabled copy of the add-on instead of everything else."""
    bl_idname = "VIEW3D_PT_banyan_other_copy"
    bl_label = "Banyan: two copies"
    bl_space_type = 'VIEW_3D'
    bl_region_type = 'UI'
    bl_category = "Banyan"

    def draw(self, context):
        col = self.layout.column(align=True)
        col.alert = True
        for i, line in enumerate(textwrap.wrap(state.LOAD_ERROR, 36)):  # a label does not wrap
            col.label(text=line, icon='ERROR' if i == 0 else 'BLANK1')
