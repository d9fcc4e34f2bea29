"""Headless Python API: one call per generator, each returning the objects
it created. Works in `blender -b`: no 3D view, selection or cursor needed.

    import banyan.api as B
    objs = B.strangler_roots(hosts=[bpy.data.objects["Cube"]], sides=8)   # on its real surface
    objs = B.strangler_roots(hosts=[cube], host_shape='BOX')                # on its bounding box
    objs = B.keyaki_tree(position=(0, 0, 0), levels=14)
    objs = B.keyaki_avenue(path=curve_obj, merged=False, spacing=10)
    objs = B.ivy(hosts=[wall], start=(0, 0, 0.1), steps=200, animate=True)
    objs = B.ivy(hosts=[statue], host_shape='BOX')     # hosts: real surfaces unless 'BOX'
    objs = B.segment_twigs(preset="segments_demo")

Parameters are the generator's table keys (`banyan <gen> --list`); dotted
keys such as avenue's "tree.levels" are written tree__levels, or passed in
values={"tree.levels": 14}. `preset` is a preset name from presets/ or a
JSON file path; keyword values apply on top of it. `params` may be a ready
core.params.Params.

Errors. Nothing is ever left in the scene when a call raises:
  - BanyanError (banyan.core; .status, .name, .message) for every bad
    value: a parameter out of range or of the wrong type, an unknown key,
    a missing or malformed preset (PresetNotFound, also a
    FileNotFoundError), a host that cannot be one (not a mesh, no
    vertices, zero scale, non-finite; with host_shape='SURFACE' no
    triangles, a NaN or infinite vertex, a singular matrix, too many
    triangles; the message names the object), a
    bad path or curve, and any failure of the library itself;
  - TypeError for an argument of the wrong kind: hosts not a list of mesh
    objects / Box, params not a Params, values not a mapping, collection
    not a bpy Collection, name not a string, progress not callable;
  - ReferenceError (Blender's own) for an object that was deleted;
  - core.errors.Cancelled (a BanyanError, status 15) when a progress
    callback returned True;
  - whatever a caller's progress callback raises, unchanged.

Placement. origin='BASE' (the default) puts each object's origin where
the plant stands, its mesh local to it: a tree at its trunk foot, ivy and
roots at the bottom centre of the first host's world bounds (or the
start), a merged avenue at its path's start, each avenue tree at its
foot; origin=None keeps the library's coordinates: the object at the
mesh's own origin (the world's, identity matrix, unless the plant stands
farther than 4096 m out: then a whole-metre point near it, so floats keep
millimetres); a point puts the origin there.

Scene units. The library works in metres, and so do the calls' numbers:
parameters, presets, and the points position, start, germination, path
and origin. Blender objects are read in the scene's units: host objects
and a path curve go in as metres through the scene's Unit Scale (Scene >
Units; none when the unit system is None), and the objects made come out
scaled by 1 / Unit Scale about the world origin (their meshes, wind and
growth data stay in metres in object space), as the operators do: a
keyaki is as many metres tall in a centimetre scene as in a metre one.

The ground. Roots and ivy on hosts get the ground at the hosts' foot
(ground_at_hosts, the operators' "Ground at hosts' foot"): ground_z
goes to the lowest point of the hosts, so the default cube gets roots
down to its bottom. By default (None) it applies unless ground_z is
given: a keyword, in values, in a ready params (used as it is), or by a
preset without hosts of its own; a plant grown on a preset's own hosts
keeps the preset's ground. True applies it always (with a preset that
has hosts, as high above the hosts' foot as the preset's ground is above
its own hosts'), False never.

Records. What a call builds is recorded as a plant (plant.record, as the
operators record theirs: generator, params, host objects, the call's
options), so Regenerate, Make LODs and the Plant panel work on it.

Jobs. Each call is also a *_job(...) returning a Job: made on the main
thread (the scene read), compute(progress) on any thread (the library
only), build() on the main thread; the operators run compute on a worker
thread with a progress bar and Esc to cancel.
"""

from .engine import lod
from .engine.grow import (ivy_grew, ivy_job, keyaki_avenue_job, keyaki_tree_job, make_params,  # noqa: F401
                          segment_twigs_job, strangler_roots_job)
from .engine.jobs import (CANCELLED, Cancelled, Job, check_progress, from_metres, is_cancelled,  # noqa: F401
                          scene_unit_scale)
from .engine.grow import avenue_progress
from .engine.placement import (ORIGINS, curve_points, host_arg, map_point, object_base, preset_host_bounds,  # noqa: F401
                               preset_point_on, set_ground_at_hosts, set_roots_germination, world_bounds)
from .engine.production import add_growth, add_wind  # noqa: F401
from .engine.regenerate import regenerate  # noqa: F401
from .engine.setups import add_setups  # noqa: F401


def strangler_roots(hosts=(), *, progress=None, **kw):
    """Roots around `hosts` (objects, core.structs.Box, or a HostSet).
    host_shape: 'SURFACE' (the objects' evaluated meshes) or 'BOX' (their
    oriented bounding boxes). germination: a world point, or None for the
    generator's own choice (above the first host). Hosts from the preset
    are used when none are given. origin: 'BASE' (default: the object's
    origin at the bottom centre of the first host's world bounds), None
    (world coordinates) or a point. progress(done) -> True cancels
    (raises Cancelled, nothing made)."""
    return strangler_roots_job(hosts, **kw).run(progress)


def keyaki_tree(*, progress=None, **kw):
    """One tree. position: where its trunk foot stands (world); origin
    'BASE' (default) puts the object's origin there, the mesh local to
    it (rotating the object turns the tree about its foot); None keeps
    world coordinates."""
    return keyaki_tree_job(**kw).run(progress)


def keyaki_avenue(*, progress=None, generate_progress=None, **kw):
    """An avenue along `path`: a curve object, a list of points, or None
    (the params' start-end line). merged=False: one object per tree in a
    new collection (origins at each tree's foot); True: one object, its
    origin at the path's start (origin=None: world coordinates).
    progress: progress(done) -> True cancels (the library's run), or
    progress(done, total), called as the objects are built.
    generate_progress(done) -> True cancels: the library's run, whatever
    progress is."""
    if progress is not None and not callable(progress):
        raise TypeError("progress must be callable as progress(done) or progress(done, total), not %s"
                        % type(progress).__name__)
    check_progress(generate_progress)
    gen_progress, build_progress = avenue_progress(progress)
    return keyaki_avenue_job(build_progress=build_progress, **kw).run(generate_progress or gen_progress)


def ivy(hosts=(), *, progress=None, stats=None, **kw):
    """Ivy over hosts (objects, core.structs.Box, or a HostSet; host_shape
    as strangler_roots) from `start` (placed by the library on the
    nearest host side where a stem can grow). animate=True adds a
    Geometry Nodes modifier revealing the plant by birth_step over
    [frame_start, frame_end] (default: the scene's). origin as
    strangler_roots ('BASE': the first host's base, or the start).
    ivy_job(...) gives the run as a Job whose info["grew"] says whether
    the plant grew (see ivy_grew). stats: a dict to fill with the plant's
    measures (core.generators.ivy_stats_dict, when the binding gives
    them); stats["warning"] is not empty when the plant could not grow
    (the objects are made all the same)."""
    if stats is not None and not isinstance(stats, dict):
        raise TypeError("stats must be a dict to fill, not %s" % type(stats).__name__)
    job = ivy_job(hosts, **kw)
    objs = job.run(progress)
    if stats is not None:
        stats.update(getattr(job.data, "stats", None) or {})
    return objs


def segment_twigs(*, progress=None, **kw):
    """A segment tree: the segment list of a segments preset (its "segments"
    and "trunk"), or the random demo tree of params when the preset has
    none or no preset is given. Its root stands at the object's origin."""
    return segment_twigs_job(**kw).run(progress)


def make_lods(obj, ratios=(0.5, 0.15), billboard=True, billboard_size=256, collection=None):
    """obj's levels of detail in a collection "<name> LODs" (lod.py):
    <name>_LOD0 (obj's mesh), one level per ratio (share of the
    triangles; falling, each level made from the one before:
    banyan_mesh_lods), then crossed billboard cards when billboard. Returns the
    objects; raises BanyanError with nothing left behind."""
    return lod.make_lods(obj, ratios, billboard=billboard, billboard_size=billboard_size, collection=collection)
