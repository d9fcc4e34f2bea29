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
import json
import math
import os
import re
from array import array

from . import lib as L
from . import structs as S
from .errors import BanyanError
from .params import preset_hosts

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


def read_glb(path, transform=None, closed=S.HOST_CLOSED_AUTO, name=None):
    """A .glb file read by the library (banyan_glb_read_host: every triangle
    of its default scene under its node transforms, Z up, coincident
    vertices merged) as a MeshInput: object-space positions and triangles
    copied out of the library's allocation with two memmoves, and the
    object -> world matrix the library returns with them: `transform` (see
    transform_rows) with, for a mesh far from the origin, the whole-metre
    point its positions are relative to folded into the translation (so
    they keep float precision). BanyanError with the path when the file is
    not a readable glTF binary with triangles."""
    lib = L.load()
    rows = transform_rows(transform)
    out = C.POINTER(S.HostMesh)()
    err = S.Error()
    st = lib.banyan_glb_read_host(os.fsencode(path), (C.c_double * 12)(*rows), int(closed), C.byref(out),
                                  C.byref(err))
    L.raise_for(st, err)
    try:
        m = out.contents
        pos = array("f", bytes(12 * m.vertex_count))
        tri = array("I", bytes(12 * m.triangle_count))
        C.memmove(pos.buffer_info()[0], m.positions, 12 * m.vertex_count)
        C.memmove(tri.buffer_info()[0], m.indices, 12 * m.triangle_count)
        rows = tuple(m.transform)  # the far offset included
    finally:
        lib.banyan_host_mesh_free(out)
    return MeshInput(pos, tri, transform=rows, closed=closed, name=name or os.path.basename(path))


def preset_hosts_split(text, source="<preset>", base_dir=None):
    """(boxes, meshes) of a preset's "hosts" that may name .glb meshes.
    The whole preset is first checked by the library
    (banyan_preset_host_set, which reads every file), so a bad entry or
    file is refused with its message before anything is made. boxes: the
    box entries as structs.Box, read by the library; meshes: one dict per
    mesh entry, in order: {"index" (in the preset's hosts), "name",
    "path" (joined to base_dir), "transform" (12 rows), "closed"}."""
    data = text.encode() if isinstance(text, str) else bytes(text)
    source = str(source)
    base = os.path.dirname(os.path.abspath(source)) if base_dir is None and os.path.isfile(source) else base_dir
    # Checked (and built, then dropped) by the library: one rule, one message.
    HostSet.from_preset(data, source, base).close()
    doc = json.loads(data.decode("utf-8"))
    entries = list(doc.get("hosts") or [])
    boxes = []
    box_entries = [e for e in entries if "mesh" not in e]
    if box_entries:
        boxes = preset_hosts(json.dumps(dict(doc, hosts=box_entries)), source)
    return boxes, preset_meshes(data, source, base)


def preset_meshes(text, source="<preset>", base_dir=None):
    """The preset's mesh host entries as the library composes them
    (banyan_preset_meshes, no file read): one dict each, in order:
    {"index" (in the preset's hosts), "name", "path" (joined to base_dir),
    "transform" (12 rows), "closed"}."""
    data = text.encode() if isinstance(text, str) else bytes(text)
    lib = L.load()
    out = (S.PresetMesh * S.MAX_HOSTS)()
    count = C.c_uint32(0)
    err = S.Error()
    base = os.fsencode(base_dir) if base_dir is not None else None
    st = lib.banyan_preset_meshes(data, len(data), L.source_name(source), base, out, S.MAX_HOSTS, C.byref(count),
                                  C.byref(err))
    if st:
        L.raise_for(st, err)
    return [{"index": int(m.index), "name": m.name.decode("utf-8", "replace"),
             "path": os.fsdecode(m.path), "transform": tuple(m.transform),
             "closed": int(m.closed)} for m in out[:count.value]]


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


class HostSet(L.Handle):
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

    @classmethod
    def from_preset(cls, text, source="<preset>", base_dir=None, extra=()):
        """The host set of a preset (banyan_preset_host_set): its boxes and
        .glb meshes (paths relative to base_dir, by default the preset's
        folder), then the MeshInputs in `extra`. BanyanError naming
        hosts[i] on a bad entry or file; BANYAN_E_NO_HOSTS when it has
        none."""
        data = text.encode() if isinstance(text, str) else bytes(text)
        source = str(source)
        if base_dir is None and os.path.isfile(source):
            base_dir = os.path.dirname(os.path.abspath(source))
        extra = list(extra)
        self = cls.__new__(cls)
        self.handle = C.c_void_p()
        try:
            doc = json.loads(data.decode("utf-8"))
            entries = [h for h in doc.get("hosts") or [] if isinstance(h, dict)]
        except (ValueError, AttributeError):
            entries = []  # the library reports the syntax error with its line
        boxes = [h for h in entries if "mesh" not in h]
        self.n_boxes = len(boxes)
        self.n_meshes = len(entries) - len(boxes) + len(extra)
        self.names = ([h.get("name") for h in boxes] + [h.get("name") or h.get("mesh") for h in entries
                                                        if "mesh" in h] + [m.name for m in extra])
        marr = (S.HostMesh * max(1, len(extra)))(*[m.struct() for m in extra])
        err = S.Error()
        st = L.load().banyan_preset_host_set(data, len(data), L.source_name(source),
                                             os.fsencode(base_dir) if base_dir else None,
                                             marr if extra else None, len(extra), C.byref(self.handle), C.byref(err))
        if st:
            self.handle = C.c_void_p()
            raise BanyanError(st, err.text() if err.code else L.status_name(st), L.status_name(st))
        return self

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
