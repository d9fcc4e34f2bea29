"""Host sets (banyan/hosts.h) from Python buffers; no bpy here.

    from array import array
    from banyan.core.hostset import HostSet, MeshInput
    m = MeshInput(array('f', [...]), array('I', [...]), transform=rows_4x4, name="Rock")
    with HostSet(boxes=[], meshes=[m]) as hs:
        hit = hs.closest((0, 0, 5))          # dict or None
        d = generators.roots(params, hs)     # a generator on the real surface

The set is built once (the library copies the arrays into its own BVH)
and freed by close() / the with block; whatever grows on it (an ivy
handle) must be freed first. Host numbering is the library's: the boxes
first, then the meshes in order; library messages about hosts[i] name the
object each came from.
"""
import ctypes as C
import math
import re
from array import array

from . import lib as L
from . import structs as S
from .errors import BanyanError

BAD_HOST = 4  # BANYAN_E_BAD_HOST


def _buffer(values, typecodes, what, name):
    """values as an array of 4-byte items of one of typecodes (a copy only
    when it is not one already)."""
    if isinstance(values, array) and values.typecode in typecodes and values.itemsize == 4:
        return values
    if isinstance(values, (str, bytes)) or not hasattr(values, "__len__"):
        raise TypeError("host '%s': %s must be an array or a sequence of numbers, not %s"
                        % (name, what, type(values).__name__))
    return array(typecodes[0], values)


def transform_rows(matrix):
    """The row-major 3x4 of a 4x4 (rows of 4) or 3x4 matrix, or 12 numbers."""
    if matrix is None:
        return (1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0)
    rows = list(matrix)
    if len(rows) == 12:
        return tuple(float(x) for x in rows)
    if len(rows) in (3, 4) and all(len(r) == 4 for r in rows[:3]):
        return tuple(float(rows[r][c]) for r in range(3) for c in range(4))
    raise TypeError("a host transform is a 4x4 or 3x4 matrix (rows) or 12 numbers")


class MeshInput:
    """One triangle mesh host before the set is built: positions (3 floats a
    vertex, object space; array('f') is used as is), indices (3 a
    triangle; array('I') or array('i') of 4-byte items as is), transform
    (object -> world, see transform_rows), closed (structs.HOST_*: -1
    auto, 0 open, 1 closed) and the name messages use."""

    def __init__(self, positions, indices, transform=None, closed=S.HOST_CLOSED_AUTO, name="mesh"):
        self.name = str(name)
        self.positions = _buffer(positions, "f", "positions", self.name)
        self.indices = _buffer(indices, "Ii", "indices", self.name)
        if len(self.positions) % 3 or len(self.indices) % 3:
            raise BanyanError(BAD_HOST, "host '%s': %d position floats and %d indices; both must be multiples "
                              "of 3" % (self.name, len(self.positions), len(self.indices)), "BANYAN_E_BAD_HOST")
        self.transform = transform_rows(transform)
        self.closed = int(closed)

    @property
    def vertex_count(self):
        return len(self.positions) // 3

    @property
    def triangle_count(self):
        return len(self.indices) // 3

    def struct(self):
        """The banyan_host_mesh pointing into this object's buffers (valid
        while it lives)."""
        m = S.HostMesh()
        m.positions = C.cast(self.positions.buffer_info()[0], C.POINTER(C.c_float)) if len(self.positions) else None
        m.indices = C.cast(self.indices.buffer_info()[0], C.POINTER(C.c_uint32)) if len(self.indices) else None
        m.vertex_count = min(self.vertex_count, 0xFFFFFFFF)
        m.triangle_count = min(self.triangle_count, 0xFFFFFFFF)
        m.transform[:] = self.transform
        m.closed = self.closed
        m.reserved = 0
        return m


def name_hosts(message, names, n_boxes=0):
    """A library message with hosts[i] (or meshes[j], j counted among the
    meshes) spelt as the object it came from: "hosts[2] has a vertex ..."
    -> "host 'Suzanne' has a vertex ..."."""
    def sub(m):
        i = int(m.group(2)) + (n_boxes if m.group(1) == "meshes" else 0)
        if i >= len(names) or not names[i]:
            return m.group(0)
        return "host '%s'%s" % (names[i], ": box " if m.group(4) and m.group(1) == "hosts" and i < n_boxes
                                else (": " if m.group(4) else ""))
    # "hosts[2] (mesh 0): ..." -> "host 'Rock': ..." (the object says which mesh).
    return re.sub(r"\b(hosts|meshes)\[(\d+)\]( \(mesh \d+\))?(\.)?", sub, message)


class HostSet:
    """A banyan_hosts handle: boxes (structs.Box) then meshes (MeshInput).
    Raises BanyanError naming the host on a bad one (BANYAN_E_BAD_HOST /
    BANYAN_E_LIMIT / BANYAN_E_NO_HOSTS)."""

    def __init__(self, boxes=(), meshes=()):
        boxes = list(boxes)
        meshes = list(meshes)
        self.handle = C.c_void_p()
        self.n_boxes, self.n_meshes = len(boxes), len(meshes)
        self.names = [getattr(b, "host_name", None) for b in boxes] + [m.name for m in meshes]
        if not boxes and not meshes:
            raise BanyanError(3, "no hosts: give one or more boxes or meshes", "BANYAN_E_NO_HOSTS")
        lib = L.load()
        barr = (S.Box * max(1, len(boxes)))(*boxes)
        marr = (S.HostMesh * max(1, len(meshes)))(*[m.struct() for m in meshes])
        err = S.Error()
        st = lib.banyan_hosts_create(barr if boxes else None, len(boxes), marr if meshes else None, len(meshes),
                                     C.byref(self.handle), C.byref(err))
        if st:
            self.handle = C.c_void_p()
            msg = err.text() if err.code else L.status_name(st)
            raise BanyanError(st, self.name_message(msg), L.status_name(st))
        if not self.handle:
            raise BanyanError(14, "banyan_hosts_create returned OK but no host set", "BANYAN_E_INTERNAL")

    # ------------------------------------------------------------ queries
    def _live(self):
        if not self.handle:
            raise BanyanError(1, "the host set was closed", "BANYAN_E_INVALID_ARG")
        return self.handle

    @property
    def count(self):
        return L.load().banyan_hosts_count(self._live())

    @property
    def has_meshes(self):
        return self.n_meshes > 0

    def info(self, index):
        """{kind: 'box'|'mesh', closed, triangle_count, dropped_triangles,
        boundary_edges, shells, lo, hi, name} of host `index`."""
        out = S.HostInfo()
        err = S.Error()
        L.raise_for(L.load().banyan_hosts_info(self._live(), int(index), C.byref(out), C.byref(err)), err)
        d = {k: getattr(out, k) for k, _ in S.HostInfo._fields_}
        d["kind"] = "mesh" if out.kind == 1 else "box"
        d["closed"] = bool(out.closed)
        d["lo"], d["hi"] = tuple(out.lo), tuple(out.hi)
        d["name"] = self.names[index] if index < len(self.names) else None
        return d

    @staticmethod
    def _hit(h):
        if h.host < 0:
            return None
        return {"host": h.host, "primitive": h.primitive, "distance": h.distance, "point": tuple(h.point),
                "normal": tuple(h.normal)}

    def closest(self, p, max_distance=math.inf):
        """The nearest surface point to p: dict(host, primitive, distance
        (signed: < 0 inside a closed host), point, normal), or None when
        none is within max_distance."""
        hit = S.HostHit()
        err = S.Error()
        q = (C.c_double * 3)(*[float(x) for x in p])
        L.raise_for(L.load().banyan_hosts_closest(self._live(), q, float(max_distance), C.byref(hit), C.byref(err)),
                    err)
        return self._hit(hit)

    def raycast(self, origin, direction, max_t=math.inf):
        hit = S.HostHit()
        err = S.Error()
        o = (C.c_double * 3)(*[float(x) for x in origin])
        d = (C.c_double * 3)(*[float(x) for x in direction])
        L.raise_for(L.load().banyan_hosts_raycast(self._live(), o, d, float(max_t), C.byref(hit), C.byref(err)), err)
        return self._hit(hit)

    def inside(self, p):
        """True when p is inside a closed host."""
        q = (C.c_double * 3)(*[float(x) for x in p])
        return bool(L.load().banyan_hosts_inside(self._live(), q))

    def name_message(self, message):
        return name_hosts(message, self.names, self.n_boxes)

    def named(self, call):
        """call(); a BanyanError about hosts[i] names the object of host i."""
        try:
            return call()
        except BanyanError as e:
            msg = self.name_message(e.message)
            if msg == e.message:
                raise
            raise BanyanError(e.status, msg, e.name) from None

    # ----------------------------------------------------------- lifetime
    def close(self):
        if self.handle:
            L.load().banyan_hosts_free(self.handle)
            self.handle = C.c_void_p()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __del__(self):
        try:
            self.close()
        except Exception:
            pass
