"""Preferences > Add-ons > Banyan: the shipped presets in the Asset
Browser, added and taken out again (engine/assets.py does the work)."""
import bpy

from ..engine import assets


def _supported(cls):
    """The operators' shared poll: the catalog needs Blender 4.2 or later."""
    if not assets.supported():
        cls.poll_message_set("The preset catalog needs Blender 4.2 or later")
        return False
    return True


class BANYAN_OT_presets_to_assets(bpy.types.Operator):
    """Add the shipped presets to the Asset Browser as the library "Banyan Presets", one catalog per generator:
    drag one into the 3D view to grow it there (roots and ivy around the selected objects)"""
    bl_idname = "banyan.presets_to_assets"
    bl_label = "Add Presets to the Asset Browser"
    bl_options = {'REGISTER'}

    @classmethod
    def poll(cls, context):
        return _supported(cls)

    def execute(self, context):
        try:
            d, built = assets.install()
        except (OSError, RuntimeError) as e:
            self.report({'ERROR'}, "Banyan: %s" % e)
            return {'CANCELLED'}
        self.report({'INFO'}, "Banyan: the asset library \"%s\" is %s (%s)" % (
            assets.LIBRARY_NAME, "written" if built else "up to date", d))
        return {'FINISHED'}


class BANYAN_OT_presets_from_assets(bpy.types.Operator):
    """Take the library "Banyan Presets" out of the Asset Browser (the preferences' asset libraries); its folder
    stays, so adding it again is quick. Do this before removing the add-on"""
    bl_idname = "banyan.presets_from_assets"
    bl_label = "Remove Presets from the Asset Browser"
    bl_options = {'REGISTER'}

    @classmethod
    def poll(cls, context):
        if not _supported(cls):
            return False
        if not assets.installed():
            cls.poll_message_set("The presets are not in the Asset Browser")
            return False
        return True

    def execute(self, context):
        n = assets.uninstall()
        self.report({'INFO'}, "Banyan: the asset library \"%s\" is out of the Asset Browser (%d entr%s)" % (
            assets.LIBRARY_NAME, n, "y" if n == 1 else "ies"))
        return {'FINISHED'}
