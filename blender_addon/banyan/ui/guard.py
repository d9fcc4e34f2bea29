"""What register() settles before anything else: another enabled copy of
the add-on (then this one registers only a panel naming it) and the
library (when it does not load, only a panel saying why). unregister()
undoes what start() did."""
import os
import sys

import bpy

from ..core import lib, scripting
from ..core.errors import BanyanError
from . import state
from .sidebar import VIEW3D_PT_banyan_error, VIEW3D_PT_banyan_other_copy, other_copy_message

_panels = []
_alias = []  # the package `import banyan` stands for, when this copy set it


def other_copy(package):
    """(package, folder) of another copy of the add-on that is enabled in
    this Blender (the legacy `banyan` and the 4.2+ extension
    `bl_ext.<repo>.banyan`), found by its sidebar panel; None when none is."""
    for idname in ("VIEW3D_PT_banyan", "VIEW3D_PT_banyan_error"):
        cls = getattr(bpy.types, idname, None)
        other = getattr(cls, "__module__", "").partition(".ui.")[0]
        if cls is not None and other and other != package:
            mod = sys.modules.get(other)
            return other, os.path.dirname(getattr(mod, "__file__", None) or "?")
    return None


def start(package):
    """True when the add-on is to register everything; else it has
    registered the one panel that says why."""
    other = other_copy(package)
    state.ERRORS, state.OPERATORS, state.LOAD_ERROR = [], [], ""
    if other is not None:
        # Two copies would load two libraries and register the same classes,
        # each unregistering the other's.
        state.LOAD_ERROR = other_copy_message(other[0], other[1], package)
        print("banyan: not enabled: %s" % state.LOAD_ERROR)
        return _panel(VIEW3D_PT_banyan_other_copy)
    scripting.register(package)  # `import banyan` in scripts, also under the 4.2+ extension's package name
    _alias.append(package)
    try:
        lib.load()
        state.VERSION = lib.version()
    except BanyanError as e:
        # No operator that could call a broken library.
        state.LOAD_ERROR = e.message
        print("banyan: not loaded: %s" % e.message)
        return _panel(VIEW3D_PT_banyan_error)
    return True


def _panel(cls):
    bpy.utils.register_class(cls)
    _panels.append(cls)
    return False


def unregister():
    while _panels:
        cls = _panels.pop()
        if cls.is_registered:
            bpy.utils.unregister_class(cls)
    if _alias:  # a copy that refused leaves the alias to the other one
        _alias.clear()
        scripting.unregister()
