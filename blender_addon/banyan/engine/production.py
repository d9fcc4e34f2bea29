"""Wind and growth on plants already built (Add Wind, Add Growth)."""
import bpy

from ..core.errors import BanyanError
from . import growth_anim as GA
from . import plant as PL
from . import props as PP
from . import wind as W
from .jobs import frame_number, guard
from .regenerate import regenerate


def add_wind(objs, **values):
    """Adds the "Banyan Wind" modifier (or sets its inputs) on each mesh
    object of objs (an object or a list): strength, gust_strength,
    gust_frequency, direction (degrees), flutter. Returns the modifiers.
    A Banyan plant built without wind data (the add-on's default) is first
    regrown with it, as Regenerate does, once per plant (an avenue: all
    its trees). BanyanError, naming the object, for one that has no wind
    attributes and is not a plant."""
    objs = [objs] if isinstance(objs, bpy.types.bpy_struct) else list(objs)
    for o in objs:
        if not isinstance(o, bpy.types.Object) or o.type != 'MESH' \
                or not (W.has_wind(o.data) or PL.is_plant(o)):
            raise BanyanError(1, "'%s' has no wind attributes; grow it with the parameter wind on"
                              % getattr(o, "name", o), "BANYAN_E_INVALID_ARG")
    for o in objs:
        if not W.has_wind(o.data):  # not regrown with an earlier tree of its avenue
            p = PL.stored_params(o)
            p.set(PP.wind_key(o.banyan_plant.generator), True)
            regenerate(o, p)
    return guard(lambda c: [W.add_wind_modifier(o, c, **values) for o in objs])


def add_growth(objs, frame_start=None, frame_end=None):
    """Adds the "Banyan Growth" modifier (by `birth`) on each mesh object of
    objs, growing it over frame_start..frame_end (the scene's when None)."""
    objs = [objs] if isinstance(objs, bpy.types.bpy_struct) else list(objs)
    sc = bpy.context.scene
    f0 = frame_number("frame_start", frame_start, sc.frame_start)
    f1 = frame_number("frame_end", frame_end, sc.frame_end)
    return guard(lambda c: [GA.add_birth_modifier(o, c, f0, f1) for o in objs])
