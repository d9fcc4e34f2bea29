"""The sidebar's "Plant" panel (View3D > Sidebar > Banyan) for an active
Banyan plant: its parameters, editable, and the buttons of ops/plant.py
and ops/production.py. The data and the rebuilding are engine/plant.py's."""
import bpy

from ..engine import plant as PL
from ..engine import props as PP
from ..engine.plant import active_plant
from ..core.params import specs
from .panels import draw_prop, idle, section

GENERATOR_LABELS = {"roots": "Strangler roots", "keyaki": "Keyaki tree", "avenue": "Keyaki avenue",
                    "ivy": "Ivy", "segments": "Segment twigs"}


def _groups(specs):
    """[(group title, [spec])] in table order; one untitled group when the
    table has no groups."""
    out = {}
    for s in specs:
        out.setdefault(getattr(s, "group", "") or "", []).append(s)
    return list(out.items())


def _label(s):
    return getattr(s, "label", "") or ""


class VIEW3D_PT_banyan_plant(bpy.types.Panel):
    bl_idname = "VIEW3D_PT_banyan_plant"
    bl_label = "Plant"
    bl_space_type = 'VIEW_3D'
    bl_region_type = 'UI'
    bl_category = "Banyan"

    @classmethod
    def poll(cls, context):
        return active_plant(context) is not None

    def draw(self, context):
        obj = active_plant(context)
        pl = obj.banyan_plant
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        col = layout.column(align=True)
        col.label(text=GENERATOR_LABELS.get(pl.generator, pl.generator), icon='OUTLINER_OB_MESH')
        col.label(text="Seed: %s" % pl.seed)
        hosts = PL.host_status(obj)
        if hosts:
            box = layout.box()
            box.label(text="Hosts")
            for name, h in hosts:
                if h is None:
                    box.label(text="%s (deleted)" % name, icon='ERROR')
                else:
                    box.label(text=h.name, icon='OBJECT_DATA')
        if pl.generator == "avenue" and PL.options(obj).get("path_from") == 'CURVE':
            ok = pl.path is not None and pl.path.users_scene
            layout.label(text="Path: %s" % (pl.path.name if ok else "(deleted)"), icon='CURVE_DATA' if ok else 'ERROR')
        row = layout.row(align=True)
        row.scale_y = 1.3
        row.operator("banyan.regenerate", icon='FILE_REFRESH')
        changed = PL.edited(obj)  # about 2.5 ms (roots, Blender 3.4)
        if changed:
            layout.label(text="%d change(s) not built yet" % len(changed), icon='INFO')
        # At most two buttons a row, short words and no icon beside them:
        # the labels fit the sidebar's default width (test_ux_new_user.py).
        row = layout.row(align=True)
        row.operator("banyan.randomize_seed", text="New Seed")
        row.operator("banyan.copy_preset", text="Copy Preset")
        row = layout.row(align=True)  # production setups (ops/production.py)
        row.operator("banyan.add_wind", text="Add Wind")
        row.operator("banyan.add_growth", text="Add Growth")
        layout.operator("banyan.make_lods", icon='MOD_DECIM')
        view = getattr(pl, pl.generator, None)
        if view is None:
            layout.label(text="This add-on has no '%s' generator" % pl.generator, icon='ERROR')
            return
        # Fields that do nothing with these values, greyed out as in the redo panel.
        off = idle(pl.generator, view)  # Regenerate takes every value as it is: no operator option
        for i, (title, rows) in enumerate(_groups(specs(pl.generator))):
            body = section(layout, context, pl.generator, i, title or "Parameters")
            if body is None:
                continue
            for s in rows:
                name = PP.prop_name(s.name)
                if hasattr(view, name):
                    lab = _label(s)
                    kw = {"text": lab} if lab else {}
                    draw_prop(body, view, name, off, **kw)


