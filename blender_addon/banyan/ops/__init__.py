"""Every operator. The generators' operators are written as classes here;
the rows of the library's parameter tables become their properties when
they are registered (base.complete), as only the loaded library knows
them."""
import bpy

from ..core.errors import BanyanError
from ..ui import state
from .assets import BANYAN_OT_presets_from_assets, BANYAN_OT_presets_to_assets
from .base import BANYAN_OT_preset_save, complete
from .ivy import MESH_OT_banyan_ivy
from .keyaki import MESH_OT_banyan_keyaki_avenue, MESH_OT_banyan_keyaki_tree
from .plant import BANYAN_OT_copy_preset, BANYAN_OT_randomize_seed, BANYAN_OT_regenerate
from .production import BANYAN_OT_add_growth, BANYAN_OT_add_wind, BANYAN_OT_make_lods
from .roots import MESH_OT_banyan_roots
from .segments import MESH_OT_banyan_segment_twigs
from .tube import MESH_OT_banyan_tube

# The generators' operators, in the Add menu's order.
GENERATORS = (MESH_OT_banyan_roots, MESH_OT_banyan_keyaki_tree, MESH_OT_banyan_keyaki_avenue, MESH_OT_banyan_ivy,
              MESH_OT_banyan_segment_twigs)
# The tube is a self-test (scripts and tests call it): in no menu, as the preset save dialog.
OTHERS = (MESH_OT_banyan_tube, BANYAN_OT_preset_save, BANYAN_OT_regenerate, BANYAN_OT_randomize_seed,
          BANYAN_OT_copy_preset, BANYAN_OT_add_wind, BANYAN_OT_add_growth, BANYAN_OT_make_lods,
          BANYAN_OT_presets_to_assets, BANYAN_OT_presets_from_assets)


def register():
    """Registers every operator; a generator's whose properties cannot be
    made is left out, its message in state.ERRORS (the sidebar shows it)."""
    state.ERRORS, state.OPERATORS = [], []
    for cls in GENERATORS:
        try:
            complete(cls)
        except BanyanError as e:
            state.ERRORS.append(e.message)
            print("banyan: %s" % e.message)
            continue
        bpy.utils.register_class(cls)
        state.OPERATORS.append((cls.bl_idname, cls.bl_label))
    for cls in OTHERS:
        bpy.utils.register_class(cls)


def unregister():
    for cls in reversed(GENERATORS + OTHERS):
        if cls.is_registered:
            bpy.utils.unregister_class(cls)
