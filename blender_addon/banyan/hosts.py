"""Host boxes from Blender objects: world-space oriented bounding boxes.

An object's local bounding box (obj.bound_box, which includes modifiers)
is mapped by its world matrix M = T * L. The columns of the 3x3 part L are
the world images of the local axes. They are orthonormalised (Gram-Schmidt,
in x, y, z order) into a proper rotation R; a negative determinant (a
mirrored object) flips the last axis, which a symmetric box does not
notice. Scale is folded into the half extents. With shear the image of the
box is a parallelepiped; the box returned is the smallest R-aligned box
around it, so the host is never smaller than what the user sees.
Degenerate axes (zero scale, flat planes) get a thickness of MIN_HALF.
"""
import math

from .core.structs import Box

MIN_HALF = 1e-3  # metres; planes and zero-scaled axes become 2 mm thick


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


def box_from_matrix(matrix, local_min, local_max):
    """An oriented Box for the local box [local_min, local_max] under the
    4x4 world matrix (any sequence of rows, e.g. mathutils.Matrix)."""
    m = [[float(matrix[r][c]) for c in range(4)] for r in range(4)]
    c_local = [(local_min[k] + local_max[k]) * 0.5 for k in range(3)]
    h_local = [abs(local_max[k] - local_min[k]) * 0.5 for k in range(3)]
    cols = [(m[0][k], m[1][k], m[2][k]) for k in range(3)]
    center = tuple(m[r][3] + sum(m[r][k] * c_local[k] for k in range(3)) for r in range(3))
    axes = orthonormal_frame(cols)
    # Half extent along each frame axis of the (possibly sheared) image.
    half = []
    for a in axes:
        h = sum(abs(_dot(a, cols[k])) * h_local[k] for k in range(3))
        half.append(max(h, MIN_HALF))
    rot = [axes[c][r] for r in range(3) for c in range(3)]  # row-major, columns = axes
    return Box.make(center, half, rot)


def box_from_object(obj):
    """The world-space oriented bounding box of a Blender object."""
    bb = [tuple(v) for v in obj.bound_box]
    lo = [min(p[k] for p in bb) for k in range(3)]
    hi = [max(p[k] for p in bb) for k in range(3)]
    return box_from_matrix(obj.matrix_world, lo, hi)


def boxes_from_objects(objects):
    return [box_from_object(o) for o in objects if o.type == 'MESH']


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


def signed_distance(box, p):
    """Signed distance from p to the box (negative inside)."""
    d = _sub(p, tuple(box.center))
    q = []
    for k in range(3):
        axis = (box.rotation[k], box.rotation[3 + k], box.rotation[6 + k])
        q.append(abs(_dot(d, axis)) - box.half[k])
    outside = _norm(tuple(max(x, 0.0) for x in q))
    inside = min(max(q[0], q[1], q[2]), 0.0)
    return outside + inside


def closest_point(boxes, p):
    """The point on the surface of the nearest box to p, and that box."""
    best = None
    for b in boxes:
        d = _sub(p, tuple(b.center))
        loc = []
        axes = [(b.rotation[k], b.rotation[3 + k], b.rotation[6 + k]) for k in range(3)]
        for k in range(3):
            loc.append(max(-b.half[k], min(b.half[k], _dot(d, axes[k]))))
        if all(abs(loc[k]) < b.half[k] for k in range(3)):
            # Inside: push to the nearest face.
            k = min(range(3), key=lambda i: b.half[i] - abs(loc[i]))
            loc[k] = b.half[k] if loc[k] >= 0 else -b.half[k]
        q = tuple(b.center[r] + sum(loc[k] * axes[k][r] for k in range(3)) for r in range(3))
        dist = _norm(_sub(q, p))
        if best is None or dist < best[0]:
            best = (dist, q, b)
    return (best[1], best[2]) if best else (None, None)
