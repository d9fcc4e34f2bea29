"""Host boxes from Blender objects: world-space oriented bounding boxes.

An object's local bounding box (obj.bound_box, which includes modifiers)
is mapped by its world matrix M = T * L. The columns of the 3x3 part L are
the world images of the local axes. They are orthonormalised (Gram-Schmidt,
in x, y, z order) into a proper rotation R; a negative determinant (a
mirrored object) flips the last axis, which a symmetric box does not
notice. Scale is folded into the half extents. With shear the image of the
box is a parallelepiped; the box returned is the smallest R-aligned box
around it, so the host is never smaller than what the user sees.
One degenerate axis (a plane, or one axis scaled to zero) gets a
thickness of MIN_HALF. An object that is not a mesh, has no extent on two
or more axes (no vertices, zero scale: a point or a line), or a
non-finite matrix or bound box is refused with a BanyanError naming it;
so is a box the library's banyan_box_validate refuses (e.g. 1e30 m away).

Host shape "Surface" (the default) instead hands the library each
object's real surface: its evaluated mesh (depsgraph: modifiers, shape
keys, curves' bevel and text all applied), triangulated (loop_triangles),
read with foreach_get into array buffers, under its world matrix as the
3x4 transform. The library builds its BVH once per host set (see
surface_host_set); an object with no triangles is refused by name, and
the library refuses NaN / inf vertices, singular matrices and the like,
naming the object too.
"""
import ctypes as C
import math
import re
from array import array

import bpy
from mathutils import Matrix

from ..core import lib as L
from ..core import presets as PR
from ..core import structs as S
from ..core.errors import BanyanError
from ..core.hostset import HostSet, MeshInput, preset_hosts_split, read_glb
from ..core.structs import Box, Error
from .build_mesh import fill_mesh

SURFACE, BOX = 'SURFACE', 'BOX'
HOST_SHAPES = (
    (SURFACE, "Surface", "Grow on the objects' real surfaces: their evaluated meshes (modifiers applied), "
                         "triangulated, in world space"),
    (BOX, "Bounding box", "Grow on each object's oriented bounding box (the fast path of earlier versions)"),
)
# Object types with an evaluated mesh (to_mesh): hosts of shape Surface.
SURFACE_TYPES = frozenset(('MESH', 'CURVE', 'SURFACE', 'FONT', 'META'))

MIN_HALF = 1e-3  # metres; planes and zero-scaled axes become 2 mm thick
DEGENERATE = 1e-6  # metres; a half extent below this is no extent (the library's floor)
BAD_HOST = 4  # BANYAN_E_BAD_HOST


def _sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def _dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def _cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _scale(a, s):
    return (a[0] * s, a[1] * s, a[2] * s)


def _norm(a):
    return math.sqrt(_dot(a, a))


def _unit(a):
    n = _norm(a)
    return _scale(a, 1.0 / n) if n > 1e-12 else None


def _any_perpendicular(a):
    t = (1.0, 0.0, 0.0) if abs(a[0]) < 0.9 else (0.0, 1.0, 0.0)
    return _unit(_cross(a, t))


def orthonormal_frame(cols):
    """A right-handed orthonormal frame close to the three columns."""
    x = _unit(cols[0])
    y0 = cols[1]
    if x is None:
        # Find any usable axis, then build around it.
        x = _unit(cols[1]) or _unit(cols[2]) or (1.0, 0.0, 0.0)
        y0 = cols[2]
    y = _unit(_sub(y0, _scale(x, _dot(y0, x))))
    if y is None:
        z0 = _unit(cols[2]) if _unit(cols[2]) is not None else None
        if z0 is not None:
            y = _unit(_cross(z0, x))
        if y is None:
            y = _any_perpendicular(x)
    z = _cross(x, y)  # right-handed, unit by construction
    return x, y, z


def _box_parts(matrix, local_min, local_max):
    """(centre, axes, raw half extents) of the local box under the matrix."""
    m = [[float(matrix[r][c]) for c in range(4)] for r in range(4)]
    c_local = [(local_min[k] + local_max[k]) * 0.5 for k in range(3)]
    h_local = [abs(local_max[k] - local_min[k]) * 0.5 for k in range(3)]
    cols = [(m[0][k], m[1][k], m[2][k]) for k in range(3)]
    center = tuple(m[r][3] + sum(m[r][k] * c_local[k] for k in range(3)) for r in range(3))
    axes = orthonormal_frame(cols)
    # Half extent along each frame axis of the (possibly sheared) image.
    half = [sum(abs(_dot(a, cols[k])) * h_local[k] for k in range(3)) for a in axes]
    return center, axes, half


def _make(center, axes, half):
    rot = [axes[c][r] for r in range(3) for c in range(3)]  # row-major, columns = axes
    return Box.make(center, [max(h, MIN_HALF) for h in half], rot)


def box_from_matrix(matrix, local_min, local_max):
    """An oriented Box for the local box [local_min, local_max] under the
    4x4 world matrix (any sequence of rows, e.g. mathutils.Matrix)."""
    return _make(*_box_parts(matrix, local_min, local_max))


def _finite(values):
    return all(math.isfinite(x) for x in values)


def box_from_object(obj, scale=1.0):
    """The world-space oriented bounding box of a mesh object, in metres
    for a scene of `scale` metres per Blender unit; raises BanyanError
    (BANYAN_E_BAD_HOST) naming the object when it cannot be a host (see
    the module docstring)."""
    if not hasattr(obj, "bound_box") or not hasattr(obj, "matrix_world"):
        raise TypeError("a host must be a mesh object or a banyan Box, not %s" % type(obj).__name__)
    name = obj.name
    if obj.type != 'MESH':
        raise BanyanError(BAD_HOST, "host '%s' is a %s object, not a mesh" % (name, obj.type.lower()),
                          "BANYAN_E_BAD_HOST")
    if not len(obj.data.vertices) and not obj.modifiers:  # the bound box of a new object may be stale
        raise BanyanError(BAD_HOST, "host '%s' has no surface to grow on: it has no vertices" % name,
                          "BANYAN_E_BAD_HOST")
    mw = to_metres(obj.matrix_world, scale)
    if not _finite(x for row in mw for x in row):
        raise BanyanError(BAD_HOST, "host '%s' has a non-finite location, rotation or scale" % name,
                          "BANYAN_E_BAD_HOST")
    bb = [tuple(v) for v in obj.bound_box]
    # Corner 0 is the minimum, 6 the maximum; inverted when no vertex is finite.
    if not _finite(x for p in bb for x in p) or any(bb[0][k] > bb[6][k] for k in range(3)):
        raise BanyanError(BAD_HOST, "host '%s' has no finite vertex coordinates" % name, "BANYAN_E_BAD_HOST")
    lo = [min(p[k] for p in bb) for k in range(3)]
    hi = [max(p[k] for p in bb) for k in range(3)]
    center, axes, half = _box_parts(mw, lo, hi)
    if not _finite(center + tuple(half)):
        raise BanyanError(BAD_HOST, "host '%s' is too large or too far away (its box overflows)" % name,
                          "BANYAN_E_BAD_HOST")
    if sum(h < DEGENERATE for h in half) >= 2:
        if obj.data is not None and not len(obj.data.vertices):
            why = "it has no vertices"
        elif any(abs(s) < DEGENERATE for s in obj.scale):
            why = "it is scaled to zero (scale %s)" % ", ".join("%g" % s for s in obj.scale)
        else:
            why = "it is a point or a line (half extents %s m)" % ", ".join("%.3g" % h for h in half)
        raise BanyanError(BAD_HOST, "host '%s' has no surface to grow on: %s" % (name, why), "BANYAN_E_BAD_HOST")
    box = _make(center, axes, half)
    check_box(box, name)
    box.host_name = name  # for messages about this box (generate_named)
    return box


def check_box(box, name):
    """The library's own check of one box, its message naming the object."""
    err = Error()
    st = L.load().banyan_box_validate(C.byref(box), 0, C.byref(err))
    if st:
        raise BanyanError(st, name_hosts(err.text(), [name]), L.status_name(st))


def name_hosts(message, names):
    """A library message with "hosts[i]" spelt as the object it came from
    ("hosts[0].half[2] = 0 ..." -> "host 'Cube': box half[2] = 0 ...")."""
    def sub(m):
        i = int(m.group(1))
        if i >= len(names) or not names[i]:
            return m.group(0)
        return "host '%s'%s" % (names[i], ": box " if m.group(2) else "")
    return re.sub(r"hosts\[(\d+)\](\.)?", sub, message)


def generate_named(call, boxes):
    """call(); a BanyanError about hosts[i] names the object of boxes[i]
    (boxes made by box_from_object carry its name)."""
    try:
        return call()
    except BanyanError as e:
        names = [getattr(b, "host_name", None) for b in boxes]
        msg = name_hosts(e.message, names)
        if msg == e.message:
            raise
        raise BanyanError(e.status, msg, e.name) from None


def boxes_from_objects(objects, scale=1.0):
    """Boxes of the mesh objects among `objects` (others are skipped), in
    metres for a scene of `scale` metres per Blender unit."""
    return [box_from_object(o, scale) for o in objects if o.type == 'MESH']


def unit_scale(scene):
    """Metres per Blender unit of a scene: its unit scale (Scene > Units >
    Unit Scale), 1 when its unit system is None (Blender then applies no
    scale either). The library works in metres; the add-on converts at its
    boundary: host objects in (to_metres), plants out (scaled by 1/scale)."""
    us = getattr(scene, "unit_settings", None)
    if us is None or us.system == 'NONE':
        return 1.0
    s = float("%.7g" % us.scale_length)  # a float32 setting: 0.01, not 0.0099999998
    return s if math.isfinite(s) and s > 0 else 1.0


def to_metres(matrix, scale):
    """A world matrix of a scene of `scale` metres per unit, in metres."""
    if scale == 1.0:
        return matrix
    return Matrix.Scale(scale, 4) @ matrix


def hosts_floor(hosts):
    """The lowest point (z) of a host set's hosts or of a list of boxes:
    where the ground goes when it is at the hosts' foot; None for none."""
    if isinstance(hosts, HostSet):
        zs = [hosts.info(i)["lo"][2] for i in range(hosts.count)]
    else:
        zs = [min(p[2] for p in box_corners(b)) for b in hosts if isinstance(b, Box)]
    return min(zs) if zs else None


def box_top_center(box):
    """Centre of the box face whose outward normal points most upward."""
    best, best_k, best_s = -2.0, 0, 1.0
    for k in range(3):
        axis_z = box.rotation[3 * 2 + k]  # z component of axis k
        for s in (1.0, -1.0):
            if s * axis_z > best:
                best, best_k, best_s = s * axis_z, k, s
    return tuple(box.center[r] + best_s * box.half[best_k] * box.rotation[3 * r + best_k] for r in range(3))


def box_corners(box):
    out = []
    for sx in (-1, 1):
        for sy in (-1, 1):
            for sz in (-1, 1):
                s = (sx, sy, sz)
                out.append(tuple(box.center[r] + sum(s[k] * box.half[k] * box.rotation[3 * r + k] for k in range(3))
                                 for r in range(3)))
    return out


def closest_point(boxes, p):
    """The point on the surface of the nearest box to p, and that box: the
    library's answer (banyan_hosts_closest on a host set of the boxes)."""
    boxes = list(boxes)
    if not boxes:
        return None, None
    with HostSet(boxes=boxes) as hs:
        hit = hs.closest(p)
    return (hit["point"], boxes[hit["host"]]) if hit else (None, None)


# ------------------------------------------------------------- surfaces
def check_shape(host_shape):
    """'SURFACE' or 'BOX' (case-insensitive), else BanyanError / TypeError."""
    if not isinstance(host_shape, str):
        raise TypeError("host_shape must be 'SURFACE' or 'BOX', not %s" % type(host_shape).__name__)
    shape = host_shape.upper()
    if shape not in (SURFACE, BOX):
        raise BanyanError(2, "host_shape = %r must be 'SURFACE' or 'BOX'" % host_shape, "BANYAN_E_RANGE")
    return shape


def _read_mesh(me, name):
    """(positions 'f', triangle vertices 'I') of a Mesh: two foreach_get
    calls into buffers of the property's own item type (whole-buffer copies)."""
    me.calc_loop_triangles()
    nv, nt = len(me.vertices), len(me.loop_triangles)
    if nt == 0:
        raise BanyanError(BAD_HOST, "host '%s' has no surface to grow on: its evaluated mesh has %s" % (
            name, "no vertices" if nv == 0 else "%d vertices but no faces" % nv), "BANYAN_E_BAD_HOST")
    if nt > S.HOSTS_MAX_TRIANGLES:
        raise BanyanError(11, "host '%s' has %d triangles; a host set takes at most %d" % (
            name, nt, S.HOSTS_MAX_TRIANGLES), "BANYAN_E_LIMIT")
    pos = array("f", bytes(12 * nv))
    me.vertices.foreach_get("co", pos)
    # Loop-triangle vertices are unsigned properties: an 'I' buffer is copied
    # whole (1M triangles: 0.05 s here, 0.36 s item by item into 'i').
    tri = array("I", bytes(12 * nt))
    me.loop_triangles.foreach_get("vertices", tri)
    return pos, tri


def mesh_input_from_object(obj, depsgraph, scale=1.0):
    """The MeshInput of an object's evaluated surface in world space (in
    metres for a scene of `scale` metres per Blender unit); BanyanError
    naming it when it has none."""
    if not hasattr(obj, "evaluated_get") or not hasattr(obj, "matrix_world"):
        raise TypeError("a host must be an object or a banyan Box, not %s" % type(obj).__name__)
    name = obj.name
    if obj.type not in SURFACE_TYPES:
        raise BanyanError(BAD_HOST, "host '%s' is a %s object, which has no surface (use a mesh, curve, surface, "
                          "text or metaball)" % (name, obj.type.lower()), "BANYAN_E_BAD_HOST")
    mw = obj.matrix_world
    if not _finite(x for row in mw for x in row):
        raise BanyanError(BAD_HOST, "host '%s' has a non-finite location, rotation or scale" % name,
                          "BANYAN_E_BAD_HOST")
    ev = obj.evaluated_get(depsgraph)
    if obj.type == 'MESH' and obj.mode != 'EDIT' and isinstance(ev.data, _mesh_type()):
        # The evaluated mesh itself: no copy (to_mesh would copy a 1M-triangle sculpt).
        pos, tri = _read_mesh(ev.data, name)
    else:
        me = ev.to_mesh()
        try:
            if me is None:
                raise BanyanError(BAD_HOST, "host '%s' has no surface to grow on: it evaluates to no mesh" % name,
                                  "BANYAN_E_BAD_HOST")
            pos, tri = _read_mesh(me, name)
        finally:
            ev.to_mesh_clear()
    return MeshInput(pos, tri, transform=to_metres(ev.matrix_world, scale), closed=closed_mode(obj), name=name)


CLOSED_PROP = "banyan_host_closed"  # object property: -1 auto, 0 open, 1 closed (e.g. from a preset)


def closed_mode(obj):
    """The object's banyan_host_closed property when it holds a valid mode
    (objects made by objects_from_preset carry the preset's), else auto."""
    try:
        v = int(obj.get(CLOSED_PROP, S.HOST_CLOSED_AUTO))
    except (TypeError, ValueError, AttributeError):
        return S.HOST_CLOSED_AUTO
    return v if v in (S.HOST_CLOSED_AUTO, S.HOST_OPEN, S.HOST_CLOSED) else S.HOST_CLOSED_AUTO


def mesh_from_input(name, mi):
    """A new Mesh datablock of a MeshInput's object-space triangles, flat
    shaded (a glTF mesh without normals is drawn flat): build_mesh.fill_mesh,
    from its typed buffers through the fastest stock path of the running
    Blender, the edges from the library."""
    return fill_mesh(bpy.data.meshes.new(name), mi.positions, mi.indices, smooth=False)


def objects_from_preset(gen, preset, collection=None, material=None):
    """Blender objects for the mesh hosts of a preset (its "hosts" entries
    with "mesh": "file.glb"): each file read through the library
    (banyan_glb_read_host, exactly as the CLI reads it), its object-space
    triangles in a new mesh object whose matrix_world is the entry's
    translation / rotation / scale composed as the library composes them,
    so a plant grown on these objects with host shape Surface lines up
    with the CLI's. The preset's "closed" is kept in the object's
    banyan_host_closed property. Returns (objects, boxes): the new objects
    in preset order and the preset's box hosts (structs.Box). The whole
    preset is checked by the library first: a bad entry or file raises
    BanyanError and nothing is added to the scene."""
    path = PR.find(gen, preset)
    boxes, entries = preset_hosts_split(PR.read(path), path)
    inputs = [read_glb(e["path"], e["transform"], e["closed"], e["name"]) for e in entries]
    coll = collection or bpy.context.scene.collection
    out = []
    try:
        for e, mi in zip(entries, inputs):
            me = mesh_from_input(e["name"], mi)
            if material is not None:
                me.materials.append(material)
            ob = bpy.data.objects.new(e["name"], me)
            t = mi.transform
            ob.matrix_world = Matrix((t[0:4], t[4:8], t[8:12], (0.0, 0.0, 0.0, 1.0)))
            ob[CLOSED_PROP] = e["closed"]
            coll.objects.link(ob)
            out.append(ob)
    except BaseException:
        for ob in out:
            me = ob.data
            bpy.data.objects.remove(ob)
            bpy.data.meshes.remove(me)
        raise
    return out, boxes


def _mesh_type():
    return bpy.types.Mesh


def surface_host_set(hosts, depsgraph=None, scale=1.0):
    """A HostSet of `hosts` (objects and structs.Box): objects as their real
    surfaces (in metres for a scene of `scale` metres per Blender unit),
    boxes as boxes (host numbering: the boxes first, then the objects in
    order). The caller closes it (with-block)."""
    depsgraph = depsgraph or bpy.context.evaluated_depsgraph_get()
    boxes, meshes = [], []
    for h in hosts:
        if isinstance(h, Box):
            boxes.append(h)
        else:
            meshes.append(mesh_input_from_object(h, depsgraph, scale))
    hs = HostSet(boxes, meshes)
    hs.objects = [h for h in hosts if not isinstance(h, Box)]  # what a plant grown on it records (plant.py)
    return hs


def closest_on_set(hs, p):
    """The surface point of the host set nearest p (None when it has none)."""
    hit = hs.closest(p)
    return hit["point"] if hit else None
