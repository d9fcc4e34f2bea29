"""What the user sees: the Add menu and the sidebar (sidebar.py), the
redo panel's drawing, sections and live updates (panels.py, live.py), the
Plant panel (plant.py), the preferences (preferences.py), and what
register() found (state.py, guard.py)."""
import bpy

from . import panels, sidebar
from .plant import VIEW3D_PT_banyan_plant
from .preferences import BanyanPreferences

CLASSES = (BanyanPreferences, sidebar.VIEW3D_MT_banyan_add, sidebar.VIEW3D_PT_banyan, VIEW3D_PT_banyan_plant)


def register():
    for cls in CLASSES:
        bpy.utils.register_class(cls)
    panels.register()
    bpy.types.VIEW3D_MT_mesh_add.append(sidebar.menu_func)


def unregister():
    bpy.types.VIEW3D_MT_mesh_add.remove(sidebar.menu_func)
    panels.unregister()
    for cls in reversed(CLASSES):
        if cls.is_registered:
            bpy.utils.unregister_class(cls)
