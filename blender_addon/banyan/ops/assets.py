"""Preferences > Add-ons > Banyan: the shipped presets in the Asset
Browser (engine/assets.py does the work)."""
import bpy

from ..engine import assets


class BANYAN_OT_presets_to_assets(bpy.types.Operator):
    """Add the shipped presets to the Asset Browser as the library "Banyan Presets", one catalog per generator:
    drag one into the 3D view to grow it there (roots and ivy around the selected objects)"""
    bl_idname = "banyan.presets_to_assets"
    bl_label = "Add Presets to the Asset Browser"
    bl_options = {'REGISTER'}

    @classmethod
    def poll(cls, context):
        if not assets.supported():
            cls.poll_message_set("The preset catalog needs Blender 4.2 or later")
            return False
        return True

    def execute(self, context):
        try:
            d, built = assets.install()
        except (OSError, RuntimeError) as e:
            self.report({'ERROR'}, "Banyan: %s" % e)
            return {'CANCELLED'}
        self.report({'INFO'}, "Banyan: the asset library \"%s\" is %s (%s)" % (
            assets.LIBRARY_NAME, "written" if built else "up to date", d))
        return {'FINISHED'}
