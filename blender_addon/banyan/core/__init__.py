"""The ctypes binding of libbanyan. Plain Python: no bpy import here.

    from banyan.core import lib, params, mesh
    p = params.Params("roots"); p.set("sides", 8)
"""
from .errors import BanyanError, Cancelled, LoadError, PresetNotFound  # noqa: F401
from . import lib, structs, params, mesh  # noqa: F401
