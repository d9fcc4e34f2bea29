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
from collections.abc import Mapping
import math

import bpy

from .engine import build_mesh as BM
from .engine import growth_anim as GA
from .engine import hosts as H
from .core import presets as PR
from .engine import props as PP
from .engine import wind as W
from .core import generators as G
from .core.errors import BanyanError
from .core.hostset import HostSet
from .core.params import Params
from .core.structs import Box


def make_params(gen, preset=None, params=None, values=None, **kw):
    """Params of gen: the add-on's defaults (props.addon_params: the
    library's, wind data off), then the preset, then values and kw."""
    if params is not None and not isinstance(params, Params):
        raise TypeError("params must be a banyan.core.params.Params, not %s" % type(params).__name__)
    if values is not None and not isinstance(values, Mapping):
        raise TypeError("values must be a mapping of parameter names to values, not %s" % type(values).__name__)
    p = params.copy() if params is not None else PP.addon_params(gen)
    if preset:
        path = PR.find(gen, preset)
        p.apply_preset(PR.read(path), path)
    for k, v in dict(values or {}, **{k.replace("__", "."): v for k, v in kw.items()}).items():
        if not isinstance(k, str):
            raise TypeError("parameter names are strings, not %r" % (k,))
        p.set(k, v)
    return p


def _boxes(hosts, scale=1.0):
    if hosts is None:
        return []
    if isinstance(hosts, (str, bytes, Box, bpy.types.bpy_struct)) or not hasattr(hosts, "__iter__"):
        raise TypeError("hosts must be a list of mesh objects or Box, not %s" % type(hosts).__name__)
    out = []
    for i, h in enumerate(hosts):
        if isinstance(h, Box):
            out.append(h)
        elif isinstance(h, bpy.types.Object):
            out.append(H.box_from_object(h, scale))
        else:
            raise TypeError("hosts[%d] must be a mesh object or a Box, not %s" % (i, type(h).__name__))
    return out


def _collection(collection):
    if collection is None:
        return bpy.context.scene.collection
    if not isinstance(collection, bpy.types.Collection):
        raise TypeError("collection must be a bpy.types.Collection, not %s" % type(collection).__name__)
    return collection


def _check_name(name):
    if not isinstance(name, str):
        raise TypeError("name must be a string, not %s" % type(name).__name__)


def _frame(what, value, default):
    """A frame number: finite, or the scene's when None."""
    if value is None:
        return default
    try:
        f = float(value)
    except (TypeError, ValueError):
        raise BanyanError(12, "%s = %r must be a number" % (what, value), "BANYAN_E_TYPE")
    if not math.isfinite(f):
        raise BanyanError(2, "%s = %r must be finite" % (what, value), "BANYAN_E_RANGE")
    return f


def _guard(build):
    """Runs build(created); on failure removes what it made and re-raises."""
    created = BM.Created()
    try:
        return build(created)
    except BaseException:
        created.rollback()
        raise


def _single(name, d, collection, uv, created, origin=None):
    return [BM.object_from_mesh_data(name, d, _collection(collection), created, uv=uv, origin=origin)]


# ----------------------------------------------------------- jobs, progress
from .core.errors import Cancelled  # noqa: E402

CANCELLED = 15  # BANYAN_E_CANCELLED


def is_cancelled(e):
    return isinstance(e, BanyanError) and e.status == CANCELLED


def _check_progress(progress):
    if progress is not None and not callable(progress):
        raise TypeError("progress must be callable as progress(done) -> cancel, not %s" % type(progress).__name__)


def _takes_progress(fn):
    import inspect
    try:
        return "progress" in inspect.signature(fn).parameters
    except (TypeError, ValueError):
        return False


def call_with_progress(fn, *args, progress=None):
    """fn(*args, progress=progress) when the binding takes one (the
    library reports ~100 steps and cancels on a True return); else fn
    runs whole, framed by progress(0.0) and progress(1.0), each of which
    may still cancel (the result is then dropped)."""
    if progress is None:
        return fn(*args)
    if _takes_progress(fn):
        return fn(*args, progress=progress)
    if progress(0.0):
        raise Cancelled()
    d = fn(*args)
    if progress(1.0):
        raise Cancelled()
    return d


class Job:
    """One generator run in three steps, so that an operator can put the
    middle one on a worker thread: made here (main thread: the scene is
    read, a host set built), compute(progress) (any thread: the library
    only, no bpy), build() (main thread: the objects, rolled back on
    failure). close() frees what the job holds (host sets); run() does
    it all. `info` holds what compute learnt (ivy: "grew")."""

    def __init__(self, compute, build, cleanup=None, whole=True, unit_scale=None):
        import contextlib
        self._compute, self._make = compute, build
        # Metres per Blender unit of the scene the objects go to (read here, on the main thread).
        self.unit_scale = scene_unit_scale() if unit_scale is None else unit_scale
        # whole: build makes one object of the whole mesh, so its edge list
        # (triangle_edges, C) is computed in compute, off the main thread.
        self.whole = whole
        self.stack = contextlib.ExitStack()
        if cleanup is not None:
            self.stack.push(cleanup)
        self.data = None
        self.info = {}
        self.finishers = []  # fn(objs, created) after build, in its rollback (wind, growth setups)
        self.plant = None  # (generator, host objects, options): what build records on the plant (_recorded)

    def adopt(self, stack_or_cm):
        """Ties a context manager (or ExitStack) to the job's lifetime."""
        self.stack.enter_context(stack_or_cm)
        return self

    def compute(self, progress=None):
        _check_progress(progress)
        d = self._compute(progress)
        if self.whole and d is not None and getattr(d, "indices", None) is not None \
                and not getattr(d, "instances", None):
            from .core.mesh import triangle_edges
            d.topology = triangle_edges(d.indices, len(d.positions) // 3)
        self.data = d
        return self

    def _build(self, d, created):
        """The objects of d (build's), in the scene's units (from_metres)."""
        objs = self._make(d, created)
        from_metres(objs, self.unit_scale)
        return objs

    def build(self):
        if self.data is None:
            raise BanyanError(1, "the job has not computed yet", "BANYAN_E_INVALID_ARG")
        return _guard(lambda c: self._finish(self._build(self.data, c), c))

    def _finish(self, objs, created):
        for fn in self.finishers:
            fn(objs, created)
        if self.plant is not None:
            # Kept on the plant as an operator keeps it: Regenerate, Make LODs and the Plant panel work on it.
            from .engine import plant as PL
            gen, hosts, options = self.plant
            PL.record(objs, gen, self.params, hosts, options)
        return objs

    def close(self):
        self.stack.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def run(self, progress=None):
        with self:
            self.compute(progress)
            return self.build()


def scene_unit_scale():
    """Metres per Blender unit of the current scene (hosts.unit_scale)."""
    return H.unit_scale(bpy.context.scene)


def from_metres(objs, scale):
    """The library's objects (world metres) in Blender units of `scale`
    metres: scaled about the world origin, so their meshes, wind and
    growth data stay the library's, in metres of object space."""
    if scale == 1.0:
        return
    from mathutils import Matrix
    m = Matrix.Scale(1.0 / scale, 4)
    # Objects an instancer among objs shows (an instanced avenue's
    # variants) are scaled through it.
    shown = {c.name for o in objs if o.instance_type == 'COLLECTION' and o.instance_collection
             for c in o.instance_collection.all_objects}
    for o in objs:
        if o.parent is None and o.name not in shown:
            o.matrix_basis = m @ o.matrix_basis  # matrix_world may not be evaluated yet


def _recorded(job, gen, options, hosts=()):
    """job, set to record what it builds (plant.record: the generator, its
    params, the host objects among `hosts`, options as plant.build_job
    reads them) so that the plant can be regenerated and edited."""
    if isinstance(hosts, HostSet):
        hosts = getattr(hosts, "objects", ())  # a set made by hosts.surface_host_set
    objs = [h for h in hosts or () if isinstance(h, bpy.types.Object)]
    job.plant = (gen, objs, dict(options))
    return job


def _job(prepare):
    """Calls prepare(stack) -> Job with an ExitStack that the job adopts;
    on failure the stack is closed (host sets freed)."""
    import contextlib
    stack = contextlib.ExitStack()
    try:
        job = prepare(stack)
    except BaseException:
        stack.close()
        raise
    return job.adopt(stack)


# ------------------------------------------------------- wind and growth
def _setups(job, gen, wind=None, animate=False, frame_start=None, frame_end=None):
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
        f0 = _frame("frame_start", frame_start, sc.frame_start)
        f1 = _frame("frame_end", frame_end, sc.frame_end)
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


def add_wind(objs, **values):
    """Adds the "Banyan Wind" modifier (or sets its inputs) on each mesh
    object of objs (an object or a list): strength, gust_strength,
    gust_frequency, direction (degrees), flutter. Returns the modifiers.
    A Banyan plant built without wind data (the add-on's default) is first
    regrown with it, as Regenerate does, once per plant (an avenue: all
    its trees). BanyanError, naming the object, for one that has no wind
    attributes and is not a plant."""
    from .engine import plant as PL
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
            PL.regenerate(o, p)
    return _guard(lambda c: [W.add_wind_modifier(o, c, **values) for o in objs])


def add_growth(objs, frame_start=None, frame_end=None):
    """Adds the "Banyan Growth" modifier (by `birth`) on each mesh object of
    objs, growing it over frame_start..frame_end (the scene's when None)."""
    objs = [objs] if isinstance(objs, bpy.types.bpy_struct) else list(objs)
    sc = bpy.context.scene
    f0 = _frame("frame_start", frame_start, sc.frame_start)
    f1 = _frame("frame_end", frame_end, sc.frame_end)
    return _guard(lambda c: [GA.add_birth_modifier(o, c, f0, f1) for o in objs])


# ------------------------------------------------------------- placement
ORIGINS = ('BASE', 'WORLD')


def object_base(obj):
    """Bottom centre of an object's world bounds (bound_box: modifiers
    included) under its world matrix."""
    from mathutils import Vector
    mw = obj.matrix_world
    pts = [mw @ Vector(c) for c in obj.bound_box]
    lo = [min(p[k] for p in pts) for k in range(3)]
    hi = [max(p[k] for p in pts) for k in range(3)]
    return (0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), lo[2])


def world_bounds(objs):
    """(lo, hi) of the union of the objects' world bounds."""
    from mathutils import Vector
    pts = [o.matrix_world @ Vector(c) for o in objs for c in o.bound_box]
    return (tuple(min(p[k] for p in pts) for k in range(3)), tuple(max(p[k] for p in pts) for k in range(3)))


def _bounds_base(lo, hi):
    return (0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), lo[2])


def _box_base(box):
    c = H.box_corners(box)
    return _bounds_base([min(p[k] for p in c) for k in range(3)], [max(p[k] for p in c) for k in range(3)])


def host_base(hosts, fallback=None, index=0, scale=1.0):
    """Bottom centre of the first host's world bounds (metres): an object
    (of a scene of `scale` metres per Blender unit), a structs.Box or host
    `index` of a HostSet; `fallback` when there is none."""
    h = hosts[0] if isinstance(hosts, (list, tuple)) and hosts else hosts
    if isinstance(h, bpy.types.Object):
        return tuple(c * scale for c in object_base(h))
    if isinstance(h, Box):
        return _box_base(h)
    if isinstance(h, HostSet) and h.handle and h.count > index:
        i = h.info(index)
        return _bounds_base(i["lo"], i["hi"])
    return tuple(fallback) if fallback is not None else None


def _origin(origin, base):
    """The point the object's origin goes to: 'BASE' -> base, None or
    'WORLD' -> none (the mesh keeps world coordinates), or a point."""
    if origin is None or origin == 'WORLD':
        return None
    if origin == 'BASE':
        return tuple(base) if base is not None else None
    if isinstance(origin, str) or not hasattr(origin, "__len__") or len(origin) != 3:
        raise TypeError("origin must be 'BASE', 'WORLD', None or a point (x, y, z), not %r" % (origin,))
    pt = tuple(float(c) for c in origin)
    if not all(math.isfinite(c) for c in pt):
        raise BanyanError(2, "origin = %r must be finite" % (origin,), "BANYAN_E_RANGE")
    return pt


def preset_host_bounds(gen, preset):
    """(lo, hi) of the union of a preset's hosts (boxes and .glb meshes,
    as the library builds them), or None when it has none."""
    path = PR.find(gen, preset)
    text = PR.read(path)
    if not _preset_has_hosts(text):
        return None
    with HostSet.from_preset(text, path) as hs:
        infos = [hs.info(i) for i in range(hs.count)]
    if not infos:
        return None
    return (tuple(min(i["lo"][k] for i in infos) for k in range(3)),
            tuple(max(i["hi"][k] for i in infos) for k in range(3)))


def _preset_has_hosts(text):
    import json
    try:
        # "hosts": [] counts as given: the library refuses an empty list.
        return json.loads(text).get("hosts") is not None
    except (ValueError, AttributeError):
        return False


def map_point(point, src, dst):
    """point in the box-normalised coordinates of bounds src=(lo, hi),
    carried onto bounds dst (a flat axis maps to the centre)."""
    out = []
    for k in range(3):
        a, b = src[0][k], src[1][k]
        u = (point[k] - a) / (b - a) if b - a > 1e-9 else 0.5
        out.append(dst[0][k] + u * (dst[1][k] - dst[0][k]))
    return tuple(out)


def preset_point_on(gen, preset, point, objs):
    """A preset's point (ivy start, roots germination), given relative to
    its own hosts, mapped onto the world bounds of `objs`; the point as
    is when the preset has no hosts."""
    src = preset_host_bounds(gen, preset)
    if src is None or not objs:
        return tuple(point)
    return map_point(point, src, world_bounds(objs))


# ------------------------------------------------------------------ roots


def _preset_boxes(gen, preset):
    from .core.params import preset_hosts
    path = PR.find(gen, preset)
    return preset_hosts(PR.read(path), path)


def _preset_has_meshes(gen, preset):
    import json
    try:
        doc = json.loads(PR.read(PR.find(gen, preset)))
        return any(isinstance(h, dict) and "mesh" in h for h in doc.get("hosts") or [])
    except (ValueError, AttributeError):
        return False  # the library reports it


def _check_hosts(hosts):
    if hosts is None:
        return []
    if isinstance(hosts, (str, bytes, Box, bpy.types.bpy_struct)) or not hasattr(hosts, "__iter__"):
        raise TypeError("hosts must be a list of objects or Box, or a HostSet, not %s" % type(hosts).__name__)
    hosts = list(hosts)
    for i, h in enumerate(hosts):
        if not isinstance(h, (Box, bpy.types.Object)):
            raise TypeError("hosts[%d] must be an object or a Box, not %s" % (i, type(h).__name__))
    return hosts


def _hosts_list(hosts):
    """A HostSet as it is, else the hosts as a checked list (read once)."""
    return hosts if isinstance(hosts, HostSet) else _check_hosts(hosts)


def host_arg(gen, hosts, host_shape, preset, stack, scale=None):
    """(arg, named, base): what the generator gets for `hosts` as
    `host_shape` says, a wrapper naming hosts in its errors, and the
    bottom centre of the first host's world bounds, all in metres (objects
    read in a scene of `scale` metres per Blender unit; None: the current
    scene's). Host sets built here are closed with `stack`.
    hosts: a list of objects and core.structs.Box, or a ready
    core.hostset.HostSet (used as is; the caller frees it).
    'BOX': every object as its oriented bounding box (hosts.py); the
    preset's boxes when no hosts are given. 'SURFACE': objects as their
    evaluated meshes in a host set built here once, boxes staying boxes
    (numbered first); with no objects among the hosts this is the box
    path, to the byte."""
    if isinstance(hosts, HostSet):
        return hosts, hosts.named, host_base(hosts)
    scale = scene_unit_scale() if scale is None else scale
    shape = H.check_shape(host_shape)
    hosts = _check_hosts(hosts)
    if not hosts and preset and shape == H.SURFACE and _preset_has_meshes(gen, preset):
        # The preset's own boxes and .glb meshes, as the CLI builds them.
        path = PR.find(gen, preset)
        hs = stack.enter_context(HostSet.from_preset(PR.read(path), path))
        return hs, hs.named, host_base(hs)
    if shape == H.BOX or all(isinstance(h, Box) for h in hosts):
        boxes = _boxes(hosts, scale)
        if not boxes and preset:
            boxes = _preset_boxes(gen, preset)
        return boxes, (lambda call: H.generate_named(call, boxes)), host_base(hosts or boxes, scale=scale)
    hs = stack.enter_context(H.surface_host_set(hosts, scale=scale))
    # The library's bounds of the first host (exact, where the box of an
    # object's bound_box would be loose when it is rotated); boxes are
    # numbered first in the set.
    first = 0 if isinstance(hosts[0], Box) else sum(isinstance(h, Box) for h in hosts)
    return hs, hs.named, host_base(hs, index=first)


def grow_on_hosts(gen, hosts, host_shape, preset, grow):
    """grow(hosts_arg) on `hosts` (see host_arg), host sets freed after."""
    import contextlib
    with contextlib.ExitStack() as stack:
        arg, named, _base = host_arg(gen, hosts, host_shape, preset, stack)
        return named(lambda: grow(arg))


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


def strangler_roots_job(hosts=(), *, preset=None, params=None, germination=None, collection=None,
                        name="Banyan Roots", uv=True, host_shape=H.SURFACE, origin='BASE', values=None, wind=None,
                        animate=False, frame_start=None, frame_end=None, ground_at_hosts=None, **kw):
    """strangler_roots as a Job (see Job). wind, animate, frame_start,
    frame_end: the wind and growth setups (_setups); ground_at_hosts: see
    the module docstring (The ground)."""
    _collection(collection)
    _check_name(name)
    p = make_params("roots", preset, params, values, **kw)
    if germination is not None:
        set_roots_germination(p, germination)
    hosts = _hosts_list(hosts)
    ground = _ground_wanted(ground_at_hosts, "roots", hosts, preset, params, values, kw)
    scale = scene_unit_scale()

    def prepare(stack):
        arg, named, base = host_arg("roots", hosts, host_shape, preset, stack, scale)
        if ground:
            set_ground_at_hosts("roots", p, arg, preset)
        o = _origin(origin, base if base is not None else p.get("germination"))
        return Job(lambda prog: named(lambda: call_with_progress(G.roots, p, arg, progress=prog)),
                   lambda d, c: _single(name, d, collection, uv, c, o), unit_scale=scale)
    job = _job(prepare)
    job.params = p
    _recorded(job, "roots", _hosted_options("strangler_roots", hosts, host_shape, preset, uv), hosts)
    return _setups(job, "roots", wind, animate, frame_start, frame_end)


def _hosted_options(call, hosts, host_shape, preset, uv):
    """The options a roots or ivy plant records: the call, uv_map, the host
    shape, and the preset whose own hosts it grew on when none were given."""
    opts = {"api": call, "uv_map": bool(uv), "host_shape": host_shape}
    if preset and not isinstance(hosts, HostSet) and not list(hosts or ()):
        opts["preset_hosts"] = preset
    return opts


def set_ground_at_hosts(gen, params, hosts, preset=None):
    """Puts params' ground_z at the lowest point of `hosts` (boxes or a
    HostSet, metres: what the generator grows on), so that the plant
    reaches their foot and spreads on the ground there; with a preset that
    has hosts, as high above (or below) that point as the preset's ground
    is above its own hosts' lowest point (a boulder sunk into the ground
    stays so). Nothing for no hosts. The operators' Ground at hosts' foot."""
    z = H.hosts_floor(hosts)
    if z is None:
        return
    bounds = preset_host_bounds(gen, preset) if preset else None
    if bounds is not None:
        shift = z - bounds[0][2]
        if abs(shift) <= 1e-6:
            return  # the preset's own hosts where it has them (to float32): its ground as it is
        z = params.get("ground_z") + shift
    params.set("ground_z", z)


def _ground_wanted(ground_at_hosts, gen, hosts, preset, params, values, kw):
    """Whether a call puts the ground at its hosts' foot (set_ground_at_hosts):
    ground_at_hosts True or False as given; None: unless ground_z is given
    (a keyword, in values, in a ready params, a preset without hosts that
    sets it) or the plant grows on the preset's own hosts."""
    if ground_at_hosts is not None:
        if not isinstance(ground_at_hosts, bool):
            raise TypeError("ground_at_hosts must be True, False or None, not %r" % (ground_at_hosts,))
        return ground_at_hosts
    if params is not None or "ground_z" in kw or "ground_z" in dict(values or {}):
        return False
    if not isinstance(hosts, HostSet) and not hosts:
        return False  # the preset's own hosts and ground (or none: nothing to stand on)
    if preset:
        import json
        try:
            doc = json.loads(PR.read(PR.find(gen, preset)))
            if "ground_z" in (doc.get("params") or {}) and not doc.get("hosts"):
                return False
        except (ValueError, AttributeError, TypeError):
            pass  # make_params has read it: the library's own reading
    return True


def set_roots_germination(p, point):
    """Sets an explicit germination point G (world metres) in roots params
    and switches off germination_auto (top centre of hosts[0], lifted by r)."""
    p.set("germination", point)
    p.set("germination_auto", False)


# ----------------------------------------------------------------- keyaki
def keyaki_tree(*, progress=None, **kw):
    """One tree. position: where its trunk foot stands (world); origin
    'BASE' (default) puts the object's origin there, the mesh local to
    it (rotating the object turns the tree about its foot); None keeps
    world coordinates."""
    return keyaki_tree_job(**kw).run(progress)


def keyaki_tree_job(*, preset=None, params=None, position=None, collection=None, name="Keyaki", uv=True,
                    origin='BASE', values=None, wind=None, animate=False, frame_start=None, frame_end=None, **kw):
    _collection(collection)
    _check_name(name)
    p = make_params("keyaki", preset, params, values, **kw)
    if position is not None:
        p.set("position", position)
    foot = p.get("position")
    o = _origin(origin, foot)
    local = p
    if o is not None:
        # Grown at the world origin and placed: the library's tree moves
        # with its position (checked to float precision), so the mesh is
        # local to the foot without losing digits far from the origin.
        local = p.copy()
        local.set("position", (0.0, 0.0, 0.0))

    def build(d, c):
        objs = _single(name, d, collection, uv, c)
        if o is not None:
            if o != foot:  # an explicit origin: the mesh moves so that the foot stays at `position`
                W.transform_mesh(objs[0].data, _translation(tuple(foot[k] - o[k] for k in range(3))))
            objs[0].location = o
        return objs
    job = Job(lambda prog: call_with_progress(G.keyaki, local, progress=prog), build)
    job.params = p
    _recorded(job, "keyaki", {"api": "keyaki_tree", "uv_map": bool(uv),
                              "origin": origin if origin is not None else 'WORLD'})
    if wind is not None:
        local.set("wind", bool(wind))
    return _setups(job, "keyaki", wind, animate, frame_start, frame_end)


def _translation(v):
    from mathutils import Matrix
    return Matrix.Translation(v)


def curve_points(obj, depsgraph=None):
    """World points along the first spline of a curve object: a Bezier
    spline at its resolution, a Poly spline through its points, a NURBS
    spline from the evaluated curve (which then must have no bevel or
    extrusion). Consecutive duplicates are removed; BanyanError, naming
    the curve, when fewer than 2 distinct points remain."""
    if not isinstance(obj, bpy.types.Object) or obj.type != 'CURVE':
        raise BanyanError(1, "the avenue path object '%s' is not a curve" % getattr(obj, "name", obj),
                          "BANYAN_E_INVALID_ARG")
    splines = obj.data.splines
    if not len(splines):
        raise BanyanError(1, "curve '%s' has no points; an avenue path needs at least 2" % obj.name,
                          "BANYAN_E_INVALID_ARG")
    sp = splines[0]
    if sp.type == 'BEZIER':
        from mathutils.geometry import interpolate_bezier
        bp = list(sp.bezier_points)
        segs = list(zip(bp, bp[1:])) + ([(bp[-1], bp[0])] if sp.use_cyclic_u and len(bp) > 2 else [])
        local = [bp[0].co.copy()] if bp else []
        for a, b in segs:
            local += interpolate_bezier(a.co, a.handle_right, b.handle_left, b.co, max(1, sp.resolution_u) + 1)[1:]
    elif sp.type == 'POLY':
        local = [p.co.xyz for p in sp.points]
        if sp.use_cyclic_u and len(local) > 2:
            local.append(local[0])
    else:
        local = _evaluated_polyline(obj, depsgraph)
    mw = obj.matrix_world
    out = []
    for v in local:
        q = tuple(mw @ v)
        # "not <=" keeps NaN points: the library names them.
        if not out or not sum((a - b) ** 2 for a, b in zip(q, out[-1])) <= 1e-18:
            out.append(q)
    if len(out) < 2:
        raise BanyanError(1, "curve '%s' has %d distinct point(s); an avenue path needs at least 2" % (
            obj.name, len(out)), "BANYAN_E_INVALID_ARG")
    return out


def _evaluated_polyline(obj, depsgraph=None):
    """Local points of a curve's evaluated wire mesh, in edge order."""
    cu = obj.data
    if cu.bevel_depth or cu.extrude or cu.bevel_object is not None or len(cu.splines) > 1:
        raise BanyanError(13, "curve '%s': a NURBS path must be a single spline without bevel or extrusion "
                          "(or convert it to Bezier or Poly)" % obj.name, "BANYAN_E_UNSUPPORTED")
    depsgraph = depsgraph or bpy.context.evaluated_depsgraph_get()
    ev = obj.evaluated_get(depsgraph)
    me = ev.to_mesh()
    if me is None:
        return []
    try:
        pts = [v.co.copy() for v in me.vertices]
        if me.edges:
            # Follow the edge chain from an end so the order is the curve's.
            adj = {}
            for e in me.edges:
                a, b = e.vertices
                adj.setdefault(a, []).append(b)
                adj.setdefault(b, []).append(a)
            start = min((v for v, n in adj.items() if len(n) == 1), default=0)
            order, prev, cur = [start], None, start
            while True:
                nxt = [n for n in adj.get(cur, []) if n != prev and n not in order[-2:]]
                if not nxt or nxt[0] == order[0]:
                    break
                prev, cur = cur, nxt[0]
                order.append(cur)
            pts = [pts[i] for i in order]
    finally:
        ev.to_mesh_clear()
    return pts


def _avenue_progress(progress):
    """(generation progress, object-building progress): progress(done) ->
    cancel for the whole run, or the earlier progress(done, total) called
    as objects are built."""
    if progress is None:
        return None, None
    import inspect
    try:
        inspect.signature(progress).bind(0.5)
        return progress, None
    except TypeError:
        return None, progress
    except ValueError:  # no signature (a builtin): the one-argument form
        return progress, None


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
    _check_progress(generate_progress)
    gen_progress, build_progress = _avenue_progress(progress)
    return keyaki_avenue_job(build_progress=build_progress, **kw).run(generate_progress or gen_progress)


def keyaki_avenue_job(*, path=None, preset=None, params=None, merged=False, collection=None,
                      name="Keyaki Avenue", uv=True, threads=0, origin='BASE', build_progress=None, values=None,
                      wind=None, animate=False, frame_start=None, frame_end=None, **kw):
    _collection(collection)
    _check_name(name)
    if build_progress is not None and not callable(build_progress):
        raise TypeError("progress must be callable as progress(done, total), not %s" % type(build_progress).__name__)
    p = make_params("avenue", preset, params, values, **kw)
    curve = path if isinstance(path, bpy.types.bpy_struct) else None
    scale = scene_unit_scale()
    if curve is not None:
        path = [tuple(c * scale for c in q) for q in curve_points(curve)]  # in metres, as the library's
    elif path is not None and (isinstance(path, (str, bytes)) or not hasattr(path, "__iter__")):
        raise TypeError("path must be a curve object or a list of (x, y, z), not %s" % type(path).__name__)
    path = list(path) if path is not None else None
    start = tuple(path[0]) if path else p.get("start")

    def compute(prog):
        try:
            return call_with_progress(G.avenue, p, path, threads, progress=prog)
        except BanyanError as e:
            if curve is not None and e.message.startswith("path"):
                raise BanyanError(e.status, "curve '%s': %s" % (curve.name, e.message), e.name) from None
            raise

    def build(d, created):
        parent = _collection(collection)
        if getattr(d, "instances", None):
            from .engine.instances import build_instanced
            return build_instanced(name, d, parent, created, uv=uv, progress=build_progress)
        if merged:
            return _single(name, d, parent, uv, created, _origin(origin, start))
        coll = created.add(bpy.data.collections.new(name))
        objs = BM.objects_per_group(name, d, coll, created, uv=uv, progress=build_progress)
        # Joins the scene once its trees are in: Blender syncs the view
        # layers once, not once per tree.
        parent.children.link(coll)
        return objs
    job = Job(compute, build, whole=merged, unit_scale=scale)
    job.params = p
    opts = {"api": "keyaki_avenue", "uv_map": bool(uv), "merged": bool(merged)}
    if curve is not None:
        opts.update(path_from='CURVE', path=curve)
    elif path is not None:
        opts.update(path_from='POINTS', path=path)
    else:
        opts["path_from"] = 'PARAMS'
    _recorded(job, "avenue", opts)
    return _setups(job, "avenue", wind, animate, frame_start, frame_end)


# -------------------------------------------------------------------- ivy
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


def ivy_job(hosts=(), *, preset=None, params=None, start=None, steps=None, collection=None, name="Ivy", uv=True,
            animate=False, frame_start=None, frame_end=None, host_shape=H.SURFACE, origin='BASE', values=None,
            wind=None, ground_at_hosts=None, **kw):
    _collection(collection)
    _check_name(name)
    sc = bpy.context.scene
    f0, f1 = _frame("frame_start", frame_start, sc.frame_start), _frame("frame_end", frame_end, sc.frame_end)
    p = make_params("ivy", preset, params, values, **kw)
    if start is not None:
        p.set("start", start)
    if steps is not None:
        p.set("steps", steps)
    hosts = _hosts_list(hosts)
    ground = _ground_wanted(ground_at_hosts, "ivy", hosts, preset, params, values, kw)
    scale = scene_unit_scale()

    def prepare(stack):
        arg, named, base = host_arg("ivy", hosts, host_shape, preset, stack, scale)
        if ground:
            set_ground_at_hosts("ivy", p, arg, preset)
        o = _origin(origin, base if base is not None else p.get("start"))

        def compute(prog):
            d = named(lambda: call_with_progress(G.ivy, p, arg, progress=prog))
            job.info["grew"] = ivy_grew(d, G.ivy_steps(p))
            return d

        def build(d, created):
            objs = _single(name, d, collection, uv, created, o)
            if animate:
                from .engine.growth_anim import add_growth_modifier
                add_growth_modifier(objs[0], created, max(1, G.ivy_steps(p)), f0, f1)
            return objs
        job = Job(compute, build, unit_scale=scale)
        return job
    if wind is not None:
        p.set("wind", bool(wind))
    job = _job(prepare)
    job.params = p
    _recorded(job, "ivy", _hosted_options("ivy", hosts, host_shape, preset, uv), hosts)
    return _setups(job, "ivy", wind)


IVY_MIN_INTERNODES = 5  # BANYAN_IVY_MIN_INTERNODES (banyan/ivy.h)


def ivy_grew(d, steps):
    """False when the ivy could not grow: the library's cannot_grow
    (banyan_ivy_stats) when the binding hands it over with the mesh,
    else its rule on the skeleton: fewer than min(steps, 5) internodes."""
    for holder in (d, getattr(d, "stats", None)):
        if isinstance(holder, dict):
            flag = holder.get("cannot_grow")
        else:
            flag = getattr(holder, "cannot_grow", None)
        if flag is not None:
            return not flag
    if d.skel_edges is None and getattr(d, "skel_points", None) is None:
        return True  # no skeleton at all: nothing to judge by
    internodes = len(d.skel_edges) // 2 if d.skel_edges is not None else 0  # no edges: a lone bud
    return internodes >= min(int(steps), IVY_MIN_INTERNODES)


# --------------------------------------------------------------- segments
def _has_key(text, key):
    import json
    try:
        doc = json.loads(text)
    except ValueError:
        return True  # let the library report the syntax error with its line
    return isinstance(doc, dict) and key in doc


def segment_twigs(*, progress=None, **kw):
    """A segment tree: the segment list of a segments preset (its "segments"
    and "trunk"), or the random demo tree of params when the preset has
    none or no preset is given. Its root stands at the object's origin."""
    return segment_twigs_job(**kw).run(progress)


def segment_twigs_job(*, preset=None, params=None, collection=None, name="Segment Twigs", uv=True, values=None,
                      wind=None, **kw):
    _collection(collection)
    _check_name(name)
    p = make_params("segments", preset, params, values, **kw)
    inputs = None
    count, trunk = 0, None
    if preset:
        path = PR.find("segments", preset)
        text = PR.read(path)
        if _has_key(text, "segments"):
            inputs, count, trunk = G.segments_read(text, path)
    job = Job(lambda prog: call_with_progress(lambda: G.segments(p, inputs, count, trunk)[0], progress=prog),
              lambda d, c: _single(name, d, collection, uv, c))
    job.params = p
    _recorded(job, "segments", {"api": "segment_twigs", "uv_map": bool(uv), "banyan_preset": preset})
    return _setups(job, "segments", wind)


# ------------------------------------------------------ levels of detail
def make_lods(obj, ratios=(0.5, 0.15), billboard=True, billboard_size=256, collection=None):
    """obj's levels of detail in a collection "<name> LODs" (lod.py):
    <name>_LOD0 (obj's mesh), one level per ratio (share of the
    triangles), then crossed billboard cards when billboard. Returns the
    objects; raises BanyanError with nothing left behind."""
    from .engine.lod import make_lods as _make_lods
    return _make_lods(obj, ratios, billboard=billboard, billboard_size=billboard_size, collection=collection)
