"""banyan: procedural strangler-fig roots, keyaki trees and avenues, ivy
and segment twigs around the objects of a scene, grown by libbanyan (C)
through ctypes. The add-on only binds, collects hosts, builds meshes and
draws panels; see docs/addon.md."""

# Blender 3.4 and up (the legacy add-on zip); tested in 3.4, 4.2, 4.5, 5.0,
# 5.1 and 5.2. The extension (4.2+) stops before 5.3: blender_version_max in
# blender_manifest.toml.
bl_info = {
    "name": "Banyan",
    "author": "banyan contributors",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "View3D > Add > Mesh > Banyan, and the sidebar tab Banyan",
    "description": "Grow strangler roots, keyaki trees and avenues, ivy and twigs around scene objects",
    "category": "Add Mesh",
}

# Blender's glTF importer calls the hooks of this class on every enabled add-on's module.
from .engine.gltf_import import glTF2ImportUserExtension  # noqa: E402,F401

_registered = []
OTHER_COPY = "other copy"  # in _registered: this copy refused to register (another one is enabled)


def other_copy():
    """(package, folder) of another copy of the add-on that is enabled in
    this Blender (the legacy `banyan` and the 4.2+ extension
    `bl_ext.<repo>.banyan`), found by its sidebar panel; None when none is."""
    import os
    import sys
    import bpy
    for idname in ("VIEW3D_PT_banyan", "VIEW3D_PT_banyan_error"):
        cls = getattr(bpy.types, idname, None)
        package = getattr(cls, "__module__", "").rpartition(".")[0]
        if cls is not None and package and package != __name__:
            mod = sys.modules.get(package)
            return package, os.path.dirname(getattr(mod, "__file__", None) or "?")
    return None


def register():
    import bpy
    from .core import scripting
    from .ui import state, sidebar as ui
    other = other_copy()
    if other is not None:
        state.ERRORS, state.OPERATORS = [], []
        # Two copies would load two libraries and register the same classes,
        # each unregistering the other's: this one registers only a panel
        # that says what to remove.
        state.LOAD_ERROR = ui.other_copy_message(other[0], other[1], __name__)
        print("banyan: not enabled: %s" % state.LOAD_ERROR)
        _registered.append(OTHER_COPY)
        bpy.utils.register_class(ui.VIEW3D_PT_banyan_other_copy)
        _registered.append(ui.VIEW3D_PT_banyan_other_copy)
        return
    scripting.register(__name__)  # `import banyan` in scripts, also under the 4.2+ extension's package name
    from .core import lib
    from .core.errors import BanyanError
    from .ops import FACTORIES, tube

    state.LOAD_ERROR = ""
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

    from .engine.materials import BanyanPreferences
    bpy.utils.register_class(BanyanPreferences)
    _registered.append(BanyanPreferences)
    from .ops.base import BANYAN_OT_preset_save
    classes = [tube.MESH_OT_banyan_tube, BANYAN_OT_preset_save]
    for module, factory in FACTORIES:
        try:
            classes.append(getattr(module, factory)())
        except BanyanError as e:
            state.ERRORS.append(e.message)
            print("banyan: %s" % e.message)
    for cls in classes:
        bpy.utils.register_class(cls)
        _registered.append(cls)
        # The tube is a self-test (scripts and tests call it): not in the menus.
        if cls not in (tube.MESH_OT_banyan_tube, BANYAN_OT_preset_save):
            state.OPERATORS.append((cls.bl_idname, cls.bl_label))
    for cls in (ui.VIEW3D_MT_banyan_add, ui.VIEW3D_PT_banyan):
        bpy.utils.register_class(cls)
        _registered.append(cls)
    from .ui import panels
    panels.register()
    _registered.append("panels")
    from .engine import plant
    from .ui import plant_ui
    plant.register()
    _registered.append("plant")
    from .ui import production_ui
    for cls in plant_ui.CLASSES + production_ui.CLASSES:
        bpy.utils.register_class(cls)
        _registered.append(cls)
    bpy.types.VIEW3D_MT_mesh_add.append(ui.menu_func)
    _registered.append("menu")


def unregister():
    """Undoes what this copy's register() did, and only that."""
    import bpy
    from .ui import sidebar as ui
    refused = OTHER_COPY in _registered
    while _registered:
        cls = _registered.pop()
        if cls == "menu":
            bpy.types.VIEW3D_MT_mesh_add.remove(ui.menu_func)
        elif cls == "panels":
            from .ui import panels
            panels.unregister()
        elif cls == "plant":
            from .engine import plant
            plant.unregister()
        elif cls == OTHER_COPY:
            pass
        elif getattr(cls, "is_registered", True):
            bpy.utils.unregister_class(cls)
    if refused:
        return  # the `banyan` alias for scripts is the other copy's
    from .core import scripting
    scripting.unregister()
