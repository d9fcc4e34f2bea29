"""Where a run grows and where its objects stand: hosts as the generator
takes them (boxes, host sets; host_arg), origins and bounds, a preset's
points carried onto other hosts, the ground at the hosts' foot, and an
avenue's path from a curve."""
import contextlib
import json
import math

import bpy
from mathutils import Matrix, Vector
from mathutils.geometry import interpolate_bezier

from ..core import presets as PR
from ..core.errors import BanyanError
from ..core.hostset import HostSet
from ..core.params import preset_hosts
from ..core.structs import Box
from . import hosts as H
from .jobs import scene_unit_scale


ORIGINS = ('BASE', 'WORLD')


def object_base(obj):
    """Bottom centre of an object's world bounds (bound_box: modifiers
    included) under its world matrix."""
    mw = obj.matrix_world
    pts = [mw @ Vector(c) for c in obj.bound_box]
    lo = [min(p[k] for p in pts) for k in range(3)]
    hi = [max(p[k] for p in pts) for k in range(3)]
    return (0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), lo[2])


def world_bounds(objs):
    """(lo, hi) of the union of the objects' world bounds."""
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


def origin_point(origin, base):
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


def _preset_boxes(gen, preset):
    path = PR.find(gen, preset)
    return preset_hosts(PR.read(path), path)


def _preset_has_meshes(gen, preset):
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


def hosts_list(hosts):
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
    with contextlib.ExitStack() as stack:
        arg, named, _base = host_arg(gen, hosts, host_shape, preset, stack)
        return named(lambda: grow(arg))


def hosted_options(call, hosts, host_shape, preset, uv):
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


def ground_wanted(ground_at_hosts, gen, hosts, preset, params, values, kw):
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


def translation(v):
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
