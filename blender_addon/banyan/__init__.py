"""banyan: procedural strangler-fig roots, keyaki trees and avenues, ivy
and segment twigs around the objects of a scene, grown by libbanyan (C)
through ctypes. core/ binds the library (no bpy), engine/ does the
Blender-side work, ops/ holds the operators, ui/ the menus and panels;
api.py is the scripting API. See docs/addon.md."""

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

_parts = []  # what register() registered, undone in reverse


def register():
    # Imported here, not above: `banyan.core` works in plain Python, without bpy.
    from . import engine, ops, ui
    from .ui import guard
    _parts.append(guard)
    if not guard.start(__name__):  # another copy enabled, or no library: only a panel says so
        return
    for part in (engine, ops, ui):
        part.register()
        _parts.append(part)


def unregister():
    """Undoes what this copy's register() did, and only that."""
    while _parts:
        _parts.pop().unregister()
