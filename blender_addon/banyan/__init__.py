"""banyan: procedural strangler-fig roots, keyaki trees and avenues, ivy
and segment twigs around the objects of a scene, grown by libbanyan (C)
through ctypes. The add-on only binds, collects hosts, builds meshes and
draws panels; see docs/addon.md."""

bl_info = {
    "name": "Banyan",
    "author": "banyan contributors",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "View3D > Add > Mesh > Banyan, and the sidebar tab Banyan",
    "description": "Grow strangler roots, keyaki trees and avenues, ivy and twigs around scene objects",
    "category": "Add Mesh",
}

_registered = []


def register():
    import bpy
    from . import state, ui
    from .core import lib
    from .core import generators as G
    from .core.errors import BanyanError
    from .operators import FACTORIES, tube

    state.LOAD_ERROR = ""
    state.MISSING = set()
    state.ERRORS = []
    state.OPERATORS = []
    try:
        lib.load()
        state.VERSION = lib.version()
    except BanyanError as e:
        # Register only a panel that says what is wrong: no operator that could call a broken library.
        state.LOAD_ERROR = e.message
        print("banyan: not loaded: %s" % e.message)
        bpy.utils.register_class(ui.VIEW3D_PT_banyan_error)
        _registered.append(ui.VIEW3D_PT_banyan_error)
        return

    from .materials import BanyanPreferences
    bpy.utils.register_class(BanyanPreferences)
    _registered.append(BanyanPreferences)
    avail = G.available()
    from .operators.base import BANYAN_OT_preset_save
    classes = [tube.MESH_OT_banyan_tube, BANYAN_OT_preset_save]
    for gens, module, factory in FACTORIES:
        if not all(avail[g] for g in gens):
            state.MISSING.update(g for g in gens if not avail[g])
            continue
        try:
            classes.append(getattr(module, factory)())
        except BanyanError as e:
            state.ERRORS.append(e.message)
            print("banyan: %s" % e.message)
    for cls in classes:
        bpy.utils.register_class(cls)
        _registered.append(cls)
        if cls not in (tube.MESH_OT_banyan_tube, BANYAN_OT_preset_save):
            state.OPERATORS.append((cls.bl_idname, cls.bl_label))
    state.OPERATORS.append((tube.MESH_OT_banyan_tube.bl_idname, tube.MESH_OT_banyan_tube.bl_label))
    for cls in (ui.VIEW3D_MT_banyan_add, ui.VIEW3D_PT_banyan):
        bpy.utils.register_class(cls)
        _registered.append(cls)
    from . import panels
    panels.register()
    _registered.append("panels")
    from . import plant, plant_ui
    plant.register([g for g, ok in avail.items() if ok])
    _registered.append("plant")
    from . import production_ui
    for cls in plant_ui.CLASSES + production_ui.CLASSES:
        bpy.utils.register_class(cls)
        _registered.append(cls)
    bpy.types.VIEW3D_MT_mesh_add.append(ui.menu_func)
    _registered.append("menu")


def unregister():
    import bpy
    from . import ui
    while _registered:
        cls = _registered.pop()
        if cls == "menu":
            bpy.types.VIEW3D_MT_mesh_add.remove(ui.menu_func)
        elif cls == "panels":
            from . import panels
            panels.unregister()
        elif cls == "plant":
            from . import plant
            plant.unregister()
        else:
            bpy.utils.unregister_class(cls)
