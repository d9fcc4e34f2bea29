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
  - core.errors.Cancelled (a BanyanError) when a library progress
    callback returned True;
  - whatever a caller's progress callback raises, unchanged.
"""
from collections.abc import Mapping
import math

import bpy

from . import build_mesh as BM
from . import hosts as H
from . import presets as PR
from .core import generators as G
from .core.errors import BanyanError
from .core.hostset import HostSet
from .core.params import Params
from .core.structs import Box


def make_params(gen, preset=None, params=None, values=None, **kw):
    """Params of gen: defaults, then the preset, then values and kw."""
    if params is not None and not isinstance(params, Params):
        raise TypeError("params must be a banyan.core.params.Params, not %s" % type(params).__name__)
    if values is not None and not isinstance(values, Mapping):
        raise TypeError("values must be a mapping of parameter names to values, not %s" % type(values).__name__)
    p = params.copy() if params is not None else Params(gen)
    if preset:
        path = PR.find(gen, preset)
        p.apply_preset(PR.read(path), path)
    for k, v in dict(values or {}, **{k.replace("__", "."): v for k, v in kw.items()}).items():
        if not isinstance(k, str):
            raise TypeError("parameter names are strings, not %r" % (k,))
        p.set(k, v)
    return p


def _boxes(hosts):
    if hosts is None:
        return []
    if isinstance(hosts, (str, bytes, Box, bpy.types.bpy_struct)) or not hasattr(hosts, "__iter__"):
        raise TypeError("hosts must be a list of mesh objects or Box, not %s" % type(hosts).__name__)
    out = []
    for i, h in enumerate(hosts):
        if isinstance(h, Box):
            out.append(h)
        elif isinstance(h, bpy.types.Object):
            out.append(H.box_from_object(h))
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


def _single(name, d, collection, uv, created):
    return [BM.object_from_mesh_data(name, d, _collection(collection), created, uv=uv)]


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


def grow_on_hosts(gen, hosts, host_shape, preset, grow):
    """grow(hosts_arg) on `hosts` as `host_shape` says, and its result.
    hosts: a list of objects and core.structs.Box, or a ready
    core.hostset.HostSet (used as is; the caller frees it).
    'BOX': every object as its oriented bounding box (hosts.py); the
    preset's boxes when no hosts are given. 'SURFACE': objects as their
    evaluated meshes in a host set built here once and freed after, boxes
    staying boxes (numbered first); with no objects among the hosts this is
    the box path, to the byte."""
    if isinstance(hosts, HostSet):
        return grow(hosts)
    shape = H.check_shape(host_shape)
    hosts = _check_hosts(hosts)
    if not hosts and preset and shape == H.SURFACE and _preset_has_meshes(gen, preset):
        # The preset's own boxes and .glb meshes, as the CLI builds them.
        path = PR.find(gen, preset)
        with HostSet.from_preset(PR.read(path), path) as hs:
            return grow(hs)
    if shape == H.BOX or all(isinstance(h, Box) for h in hosts):
        boxes = _boxes(hosts)
        if not boxes and preset:
            boxes = _preset_boxes(gen, preset)
        return H.generate_named(lambda: grow(boxes), boxes)
    with H.surface_host_set(hosts) as hs:
        return grow(hs)


def _check_progress(progress):
    if progress is not None and not callable(progress):
        raise TypeError("progress must be callable as progress(done) -> bool, not %s" % type(progress).__name__)


def strangler_roots(hosts=(), *, preset=None, params=None, germination=None, collection=None,
                    name="Banyan Roots", uv=True, host_shape=H.SURFACE, progress=None, values=None, **kw):
    """Roots around `hosts` (objects, core.structs.Box, or a HostSet).
    host_shape: 'SURFACE' (the objects' evaluated meshes) or 'BOX' (their
    oriented bounding boxes). germination: a world point, or None for the
    generator's own choice (above the first host). Hosts from the preset
    are used when none are given. progress: progress(done) -> bool while
    the library grows (done 0..1; True cancels: core.errors.Cancelled)."""
    _collection(collection)
    _check_name(name)
    _check_progress(progress)
    p = make_params("roots", preset, params, values, **kw)
    if germination is not None:
        set_roots_germination(p, germination)
    d = grow_on_hosts("roots", hosts, host_shape, preset, lambda h: G.roots(p, h, progress=progress))
    return _guard(lambda c: _single(name, d, collection, uv, c))


def set_roots_germination(p, point):
    """Sets an explicit germination point G (world metres) in roots params
    and switches off germination_auto (top centre of hosts[0], lifted by r)."""
    p.set("germination", point)
    p.set("germination_auto", False)


# ----------------------------------------------------------------- keyaki
def keyaki_tree(*, preset=None, params=None, position=None, collection=None, name="Keyaki", uv=True,
                values=None, **kw):
    _collection(collection)
    _check_name(name)
    p = make_params("keyaki", preset, params, values, **kw)
    if position is not None:
        p.set("position", position)
    d = G.keyaki(p)
    return _guard(lambda c: _single(name, d, collection, uv, c))


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


def keyaki_avenue(*, path=None, preset=None, params=None, merged=False, collection=None,
                  name="Keyaki Avenue", uv=True, threads=0, progress=None, generate_progress=None, values=None,
                  **kw):
    """An avenue along `path`: a curve object, a list of points, or None
    (the params' start-end line). merged=False: one object per tree in a
    new collection; True: one object. progress(done, total) is called as
    objects are built; generate_progress(done) -> bool while the library
    grows the trees (done 0..1; True cancels: core.errors.Cancelled)."""
    _collection(collection)
    _check_name(name)
    if progress is not None and not callable(progress):
        raise TypeError("progress must be callable as progress(done, total), not %s" % type(progress).__name__)
    _check_progress(generate_progress)
    p = make_params("avenue", preset, params, values, **kw)
    curve = path if isinstance(path, bpy.types.bpy_struct) else None
    if curve is not None:
        path = curve_points(curve)
    elif path is not None and (isinstance(path, (str, bytes)) or not hasattr(path, "__iter__")):
        raise TypeError("path must be a curve object or a list of (x, y, z), not %s" % type(path).__name__)
    try:
        d = G.avenue(p, path, threads, progress=generate_progress)
    except BanyanError as e:
        if curve is not None and e.message.startswith("path"):
            raise BanyanError(e.status, "curve '%s': %s" % (curve.name, e.message), e.name) from None
        raise

    def build(created):
        parent = _collection(collection)
        if merged:
            return _single(name, d, parent, uv, created)
        coll = created.add(bpy.data.collections.new(name))
        parent.children.link(coll)
        return BM.objects_per_group(name, d, coll, created, uv=uv, progress=progress)
    return _guard(build)


# -------------------------------------------------------------------- ivy
def ivy(hosts=(), *, preset=None, params=None, start=None, steps=None, collection=None, name="Ivy", uv=True,
        animate=False, frame_start=None, frame_end=None, host_shape=H.SURFACE, progress=None, stats=None,
        values=None, **kw):
    """Ivy over hosts (objects, core.structs.Box, or a HostSet; host_shape
    as strangler_roots) from `start` (placed by the library on the nearest
    host side a stem can grow from, above the ground). animate=True adds a
    Geometry Nodes modifier revealing the plant by birth_step over
    [frame_start, frame_end] (default: the scene's). progress as
    strangler_roots. stats: a dict to fill with the plant's measures
    (core.generators.ivy_stats_dict); stats["warning"] is not empty when
    the plant could not grow (the objects are made all the same)."""
    _collection(collection)
    _check_name(name)
    _check_progress(progress)
    if stats is not None and not isinstance(stats, dict):
        raise TypeError("stats must be a dict to fill, not %s" % type(stats).__name__)
    sc = bpy.context.scene
    f0, f1 = _frame("frame_start", frame_start, sc.frame_start), _frame("frame_end", frame_end, sc.frame_end)
    p = make_params("ivy", preset, params, values, **kw)
    if start is not None:
        p.set("start", start)
    if steps is not None:
        p.set("steps", steps)
    d = grow_on_hosts("ivy", hosts, host_shape, preset, lambda h: G.ivy(p, h, progress=progress))
    if stats is not None:
        stats.update(d.stats or {})

    def build(created):
        objs = _single(name, d, collection, uv, created)
        if animate:
            from .growth_anim import add_growth_modifier
            add_growth_modifier(objs[0], created, max(1, int(p.get("steps"))), f0, f1)
        return objs
    return _guard(build)


# --------------------------------------------------------------- segments
def _has_key(text, key):
    import json
    try:
        doc = json.loads(text)
    except ValueError:
        return True  # let the library report the syntax error with its line
    return isinstance(doc, dict) and key in doc


def segment_twigs(*, preset=None, params=None, collection=None, name="Segment Twigs", uv=True, values=None,
                  **kw):
    """A segment tree: the segment list of a segments preset (its "segments"
    and "trunk"), or the random demo tree of params when the preset has
    none or no preset is given."""
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
    d, _stats = G.segments(p, inputs, count, trunk)
    return _guard(lambda c: _single(name, d, collection, uv, c))
