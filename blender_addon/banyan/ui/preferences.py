"""The add-on's preferences (Edit > Preferences > Add-ons > Banyan)."""
import bpy

from ..core import textures as T
from ..engine.materials import ADDON


class BanyanPreferences(bpy.types.AddonPreferences):
    bl_idname = ADDON

    texture_size: bpy.props.EnumProperty(
        name="Texture Size",
        description="Pixels per side of the leaf and bark textures the library draws for new materials "
                    "(materials already in the file are reused as they are)",
        items=[(str(s), "%d px" % s, "") for s in T.SIZES], default=str(T.DEFAULT_SIZE))

    def draw(self, context):
        self.layout.prop(self, "texture_size")
        row = self.layout.row()
        row.operator("banyan.presets_to_assets", icon='ASSET_MANAGER')
        row.operator("banyan.presets_from_assets", icon='REMOVE')
