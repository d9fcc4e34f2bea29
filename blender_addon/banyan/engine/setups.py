"""The wind and growth setups a run adds to what it builds (inside its
rollback): the "Banyan Wind" modifier (wind.py) and the "Banyan Growth"
modifier (growth_anim.py)."""
import bpy

from . import growth_anim as GA
from . import props as PP
from . import wind as W
from .jobs import frame_number


def setups(job, gen, wind=None, animate=False, frame_start=None, frame_end=None):
    """Production setups on what job builds. wind: None (the params'
    wind data as they are, no modifier), True (wind data on and the
    "Banyan Wind" modifier: wind.py), False (no wind data). animate: the
    "Banyan Growth" modifier (growth_anim.py) over frame_start..frame_end
    (the scene's when None)."""
    if wind is not None:
        job.params.set(PP.wind_key(gen), bool(wind))
    return add_setups(job, wind=bool(wind), animate=animate, frame_start=frame_start, frame_end=frame_end)


def add_setups(job, wind=False, animate=False, frame_start=None, frame_end=None):
    """Adds the wind and growth modifiers to what job builds (inside its
    rollback); the plant must carry the attributes (params' wind)."""
    if animate:
        sc = bpy.context.scene
        f0 = frame_number("frame_start", frame_start, sc.frame_start)
        f1 = frame_number("frame_end", frame_end, sc.frame_end)
    if not wind and not animate:
        return job

    def finish(objs, created):
        meshes = [o for o in objs if o.type == 'MESH']
        for o in meshes:
            if animate:
                GA.add_birth_modifier(o, created, f0, f1)
            if wind:
                W.add_wind_modifier(o, created)
    job.finishers.append(finish)
    return job
