"""Headless Python API: one call per generator, each returning the objects
it created. Works in `blender -b`: no 3D view, selection or cursor needed.

    import banyan.api as B
    objs = B.strangler_roots(hosts=[bpy.data.objects["Cube"]], sides=8)
    objs = B.keyaki_tree(position=(0, 0, 0), levels=14)
    objs = B.keyaki_avenue(path=curve_obj, merged=False, spacing=10)
    objs = B.ivy(hosts=[wall], start=(0, 0, 0.1), steps=200, animate=True)
    objs = B.segment_twigs(preset="segments_demo")

Parameters are the generator's table keys (`banyan <gen> --list`); dotted
keys such as avenue's "tree.levels" are written tree__levels, or passed in
values={"tree.levels": 14}. `preset` is a preset name from presets/ or a
JSON file path; keyword values apply on top of it. `params` may be a ready
core.params.Params. On any error a BanyanError is raised and nothing is
left in the scene.
"""
import bpy

from . import build_mesh as BM
from . import hosts as H
from . import presets as PR
from .core import generators as G
from .core.errors import BanyanError
from .core.params import Params
from .core.structs import Box


def make_params(gen, preset=None, params=None, values=None, **kw):
    """Params of gen: defaults, then the preset, then values and kw."""
    p = params.copy() if params is not None else Params(gen)
    if preset:
        path = PR.find(gen, preset)
        p.apply_preset(PR.read(path), path)
    for k, v in dict(values or {}, **{k.replace("__", "."): v for k, v in kw.items()}).items():
        p.set(k, v)
    return p


def _boxes(hosts):
    out = []
    for h in hosts or ():
        out.append(h if isinstance(h, Box) else H.box_from_object(h))
    return out


def _collection(collection):
    return collection if collection is not None else bpy.context.scene.collection


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


def strangler_roots(hosts=(), *, preset=None, params=None, germination=None, collection=None,
                    name="Banyan Roots", uv=True, values=None, **kw):
    """Roots around `hosts` (mesh objects or core.structs.Box). germination:
    a world point, or None for the generator's own choice (top centre of
    the first host). Hosts from the preset are used when none are given."""
    p = make_params("roots", preset, params, values, **kw)
    boxes = _boxes(hosts)
    if not boxes and preset:
        from .core.params import preset_hosts
        path = PR.find("roots", preset)
        boxes = preset_hosts(PR.read(path), path)
    if germination is not None:
        set_roots_germination(p, germination)
    d = G.roots(p, boxes)
    return _guard(lambda c: _single(name, d, collection, uv, c))


def set_roots_germination(p, point):
    """Sets an explicit germination point G (world metres) in roots params
    and switches off germination_auto (top centre of hosts[0], lifted by r)."""
    p.set("germination", tuple(point))
    p.set("germination_auto", False)


# ----------------------------------------------------------------- keyaki
def keyaki_tree(*, preset=None, params=None, position=None, collection=None, name="Keyaki", uv=True,
                values=None, **kw):
    p = make_params("keyaki", preset, params, values, **kw)
    if position is not None:
        p.set("position", tuple(position))
    d = G.keyaki(p)
    return _guard(lambda c: _single(name, d, collection, uv, c))


def curve_points(obj, depsgraph=None):
    """World points of the first spline of a curve object (evaluated, at
    its resolution), consecutive duplicates removed."""
    depsgraph = depsgraph or bpy.context.evaluated_depsgraph_get()
    ev = obj.evaluated_get(depsgraph)
    me = ev.to_mesh()
    try:
        mw = obj.matrix_world
        pts = [tuple(mw @ v.co) for v in me.vertices]
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
    out = []
    for q in pts:
        if not out or sum((a - b) ** 2 for a, b in zip(q, out[-1])) > 1e-18:
            out.append(q)
    return out


def keyaki_avenue(*, path=None, preset=None, params=None, merged=False, collection=None,
                  name="Keyaki Avenue", uv=True, threads=0, progress=None, values=None, **kw):
    """An avenue along `path`: a curve object, a list of points, or None
    (the params' start-end line). merged=False: one object per tree in a
    new collection; True: one object. progress(done, total) is called as
    objects are built."""
    p = make_params("avenue", preset, params, values, **kw)
    pts = curve_points(path) if isinstance(path, bpy.types.Object) else (list(path) if path else None)
    if pts is not None and len(pts) < 2:
        raise BanyanError(1, "the avenue path needs at least 2 distinct points, got %d" % len(pts))
    d = G.avenue(p, pts, threads)

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
        animate=False, frame_start=None, frame_end=None, values=None, **kw):
    """Ivy over hosts from `start` (snapped by the library to the nearest
    host). animate=True adds a Geometry Nodes modifier revealing the plant
    by birth_step over [frame_start, frame_end] (default: the scene's)."""
    p = make_params("ivy", preset, params, values, **kw)
    if start is not None:
        p.set("start", tuple(start))
    if steps is not None:
        p.set("steps", int(steps))
    boxes = _boxes(hosts)
    if not boxes and preset:
        from .core.params import preset_hosts
        path = PR.find("ivy", preset)
        boxes = preset_hosts(PR.read(path), path)
    d = G.ivy(p, boxes)

    def build(created):
        objs = _single(name, d, collection, uv, created)
        if animate:
            from .growth_anim import add_growth_modifier
            sc = bpy.context.scene
            add_growth_modifier(objs[0], created, max(1, int(p.get("steps"))),
                                sc.frame_start if frame_start is None else frame_start,
                                sc.frame_end if frame_end is None else frame_end)
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
