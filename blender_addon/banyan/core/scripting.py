"""`import banyan` for scripts, whatever package Blender loaded the add-on as.

The legacy add-on is the top-level package `banyan`. A 4.2+ extension is
`bl_ext.<repository>.banyan` (`bl_ext.user_default.banyan` when installed
from disk), so a script's `import banyan.api` would find nothing. While
such a copy is enabled, and no other `banyan` can be imported, the name
`banyan` stands for it: sys.modules["banyan"] is the add-on's package and
a finder at the front of sys.meta_path hands out its submodules as
`banyan.<sub>` (the same module objects, so one library, one state; a
submodule not loaded yet is loaded under its real name first).
unregister() takes all of it back.
"""
import importlib
import importlib.abc
import importlib.machinery
import importlib.util
import sys

ALIAS = "banyan"


class _Finder(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """banyan.<sub> -> <package>.<sub>, the module already loaded or loaded under its real name."""

    def __init__(self, package):
        self.banyan_alias_of = package  # found by this name, whichever copy of this module made it
        self.package = package

    def find_spec(self, fullname, path=None, target=None):
        if not fullname.startswith(ALIAS + "."):
            return None
        real = self.package + fullname[len(ALIAS):]
        try:
            importlib.util.find_spec(real)
        except (ImportError, ValueError):
            return None
        return importlib.machinery.ModuleSpec(fullname, self, is_package=False)

    def create_module(self, spec):
        return importlib.import_module(self.package + spec.name[len(ALIAS):])

    def exec_module(self, module):
        pass  # the module ran when it was loaded under its real name


def _importable_elsewhere():
    """Another `banyan` on sys.path (a legacy copy of the add-on, or a
    checkout's blender_addon/): it keeps the name."""
    if ALIAS in sys.modules:
        return True
    try:
        return importlib.machinery.PathFinder.find_spec(ALIAS) is not None
    except (ImportError, ValueError):
        return False


def register(package):
    """Makes `import banyan` resolve to `package` (the add-on's __name__)
    when that is not `banyan` itself and no other `banyan` is importable.
    Returns whether the alias was made."""
    if package == ALIAS:
        return False
    unregister()  # a stale alias (the add-on reloaded)
    if _importable_elsewhere():
        return False
    sys.modules[ALIAS] = sys.modules[package]
    sys.meta_path.insert(0, _Finder(package))
    return True


def unregister():
    """Removes the alias: sys.modules' banyan and banyan.<sub> entries that
    stand for a differently named package, and the finder."""
    sys.meta_path[:] = [f for f in sys.meta_path if getattr(f, "banyan_alias_of", None) is None]
    mod = sys.modules.get(ALIAS)
    if mod is None or getattr(mod, "__name__", ALIAS) == ALIAS:
        return
    for name in [n for n in sys.modules if n == ALIAS or n.startswith(ALIAS + ".")]:
        m = sys.modules[name]
        if getattr(m, "__name__", name) != name:
            del sys.modules[name]
