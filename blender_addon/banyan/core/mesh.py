"""Copying a banyan_mesh out of C memory into array.array buffers.

One copy per array: Blender's foreach_set reads array.array
('f' / 'i') buffers at memory speed, while raw ctypes arrays are read item
by item (see docs/addon.md). No numpy, no per-vertex Python loops.
"""
import contextlib
import ctypes as C
import threading
from array import array

from . import args as A
from . import lib as L
from . import structs as S


def _copy(ptr, count, typecode):
    """array(typecode) holding `count` items copied from ptr (or None)."""
    if not ptr or count == 0:
        return array(typecode) if ptr else None
    out = array(typecode)
    # One pass: frombytes reads the C memory as a buffer (no zero fill first).
    out.frombytes((C.c_char * (count * out.itemsize)).from_address(C.cast(ptr, C.c_void_p).value))
    return out


class MeshData:
    """A banyan_mesh in Python buffers (the C mesh is freed right after).

    positions 3n 'f', corner_uvs 2 per index 'f' (what Blender's UV layer
    takes, gathered in C), colors 4n 'f' or None, indices 'I' (uint32 as
    in C; Blender's loop indices are unsigned properties), attributes
    {name: 'f' n}, materials [dict], parts [dict], skeleton arrays
    ('f'/'i') or None. positions and skel_points are relative to origin
    (world metres, 3 floats = doubles): (0, 0, 0) near the world origin,
    a whole-metre point near the plant far from it (banyan_mesh.origin).
    Vertex normals and per-vertex uvs are copied only
    when asked for (vertex_arrays=True): Blender computes its own normals
    and takes uvs per corner.
    """

    def __init__(self):
        self.vertex_count = 0
        self.index_count = 0
        self.positions = self.normals = self.uvs = self.corner_uvs = self.colors = self.indices = None
        self.hash = None
        self.origin = (0.0, 0.0, 0.0)
        self.attributes = {}
        self.materials = []
        self.parts = []
        self.skel_points = self.skel_radius = self.skel_tag = self.skel_edges = None
        # (corner_edges, edges, face_starts) of indices (triangle_edges), when
        # computed ahead (api.Job.compute, off the main thread), else None.
        self.topology = None
        self.stats = None  # a generator's measures, when it reports them (ivy: generators.ivy_stats_dict)
        # banyan_mesh.images as {"width", "height", "channels", "png": PNG bytes} (banyan_image_png).
        self.images = []
        # banyan_mesh.instances: (variant, (x, y, z), rotation_z, scale) each, in the mesh's frame.
        self.instances = []
        self.c_mesh = None  # the C mesh itself, kept only under capture() (which frees it)

    @property
    def triangle_count(self):
        return self.index_count // 3

    @classmethod
    def take(cls, mesh_ptr, want_hash=False, vertex_arrays=False):
        """Copies *mesh_ptr out and frees it (even when copying fails).
        want_hash: also keep banyan_mesh_hash (costs a pass over every byte);
        vertex_arrays: also copy the vertex normals and uvs."""
        lib = L.load()
        try:
            m = mesh_ptr.contents
            d = cls()
            n = d.vertex_count = m.vertex_count
            d.index_count = m.index_count
            d.hash = lib.banyan_mesh_hash(mesh_ptr) if want_hash else None
            d.origin = tuple(m.origin)
            d.positions = _copy(m.positions, 3 * n, "f")
            if vertex_arrays:
                d.normals = _copy(m.normals, 3 * n, "f")
                d.uvs = _copy(m.uvs, 2 * n, "f")
            d.colors = _copy(m.colors, 4 * n, "f")
            d.indices = _copy(m.indices, m.index_count, "I")
            if m.uvs and m.index_count:
                d.corner_uvs = array("f", bytes(4)) * (2 * m.index_count)
                err = S.Error()
                st = lib.banyan_mesh_corner_uvs(mesh_ptr, d.corner_uvs.buffer_info()[0], len(d.corner_uvs),
                                                C.byref(err))
                if st:
                    L.raise_for(st, err)
            for i in range(m.attribute_count):
                a = m.attributes[i]
                d.attributes[a.name.decode()] = _copy(a.data, n, "f")
            for i in range(m.material_count):
                mat = m.materials[i]
                d.materials.append({"name": mat.name.decode(), "base_color": tuple(mat.base_color),
                                    "roughness": mat.roughness, "double_sided": bool(mat.double_sided),
                                    "texture": mat.texture, "season": mat.season,
                                    "alpha_cutoff": mat.alpha_cutoff, "translucency": mat.translucency,
                                    "image": mat.image})
            for i in range(m.image_count):
                d.images.append(_image_png(lib, m.images[i]))
            if m.instance_count:
                raw = (C.c_char * (m.instance_count * C.sizeof(S.Instance))).from_address(
                    C.cast(m.instances, C.c_void_p).value)
                f, u = array("f"), array("I")
                f.frombytes(raw)
                u.frombytes(raw)
                d.instances = [(u[k], (f[k + 1], f[k + 2], f[k + 3]), f[k + 4], f[k + 5])
                               for k in range(0, len(f), 6)]
            for i in range(m.part_count):
                p = m.parts[i]
                d.parts.append({k: getattr(p, k) for k, _ in S.Part._fields_})
            ns = m.skel_point_count
            d.skel_points = _copy(m.skel_points, 3 * ns, "f")
            d.skel_radius = _copy(m.skel_radius, ns, "f")
            d.skel_tag = _copy(m.skel_tag, ns, "i")
            d.skel_edges = _copy(m.skel_edges, 2 * m.skel_edge_count, "i")
            kept = getattr(_capture, "meshes", None)
            if kept is not None:
                d.c_mesh = mesh_ptr
                kept.append(mesh_ptr)
                mesh_ptr = None
            return d
        finally:
            if mesh_ptr is not None:
                lib.banyan_mesh_free(mesh_ptr)

    def groups(self):
        """{group: [part dicts]} in order of first appearance."""
        out = {}
        for p in self.parts:
            out.setdefault(p["group"], []).append(p)
        return out


_capture = threading.local()


@contextlib.contextmanager
def capture():
    """Within the block, MeshData.take keeps the C mesh alive as d.c_mesh
    (for calls that take a banyan_mesh, e.g. banyan_mesh_lod) instead of
    freeing it; all are freed when the block ends (this thread only)."""
    outer = getattr(_capture, "meshes", None)
    _capture.meshes = []
    try:
        yield
    finally:
        kept, _capture.meshes = _capture.meshes, outer
        lib = L.load()
        for ptr in kept:
            lib.banyan_mesh_free(ptr)


def _image_png(lib, img):
    """A banyan_image as PNG bytes (the library's encoder), with its size."""
    data = C.POINTER(C.c_uint8)()
    size = C.c_size_t(0)
    err = S.Error()
    st = lib.banyan_image_png(C.byref(img), C.byref(data), C.byref(size), C.byref(err))
    if st:
        L.raise_for(st, err)
    try:
        png = C.string_at(data, size.value)
    finally:
        lib.banyan_png_free(data)
    return {"width": img.width, "height": img.height, "channels": img.channels, "png": png}


def localize_group(positions, indices, first_vertex):
    """banyan_group_localize on copies: (positions, indices) of one group
    made 0-based with the origin at the bottom centre of its bounds, and
    that origin. The inputs are slices the caller owns."""
    lib = L.load()
    origin = (C.c_double * 3)()
    err = S.Error()
    st = lib.banyan_group_localize(positions.buffer_info()[0], len(positions) // 3, indices.buffer_info()[0],
                                   len(indices), first_vertex, origin, C.byref(err))
    if st:
        L.raise_for(st, err)
    return positions, indices, tuple(origin)


def triangle_edges(indices, vertex_count):
    """banyan_triangle_edges: Blender's topology of a triangle list, so
    Blender need not derive it (update(calc_edges=True) is a hash table
    of its own, ten times slower). Returns array('I')s (corner_edges,
    edges, face_starts): each corner's edge (MeshLoop.edge_index), the
    edges' vertex pairs (MeshEdge.vertices) and each triangle's first
    corner (MeshPolygon.loop_start). indices: an 'i' or 'I' array."""
    lib = L.load()
    if not isinstance(indices, array) or indices.itemsize != 4:
        raise TypeError("indices must be an array of 4-byte ints ('i' or 'I')")
    n = len(indices)
    corner_edges = array("I", [0]) * n
    edges = array("I", [0]) * (2 * n)  # n edges at most; trimmed below
    starts = array("I", [0]) * (n // 3)
    count = C.c_uint64()
    err = S.Error()
    st = lib.banyan_triangle_edges(indices.buffer_info()[0] if n else None, n, vertex_count,
                                   corner_edges.buffer_info()[0], edges.buffer_info()[0], n, C.byref(count),
                                   starts.buffer_info()[0], C.byref(err))
    if st:
        L.raise_for(st, err)
    del edges[2 * count.value:]
    return corner_edges, edges, starts


def call_generate(func, *args):
    """Calls a banyan_*_generate-style function whose last two arguments
    are (banyan_mesh **out, banyan_error *err); returns MeshData."""
    out = C.POINTER(S.Mesh)()
    err = S.Error()
    st = func(*args, C.byref(out), C.byref(err))
    if st:
        if out:  # the contract says *out stays NULL; free defensively
            L.load().banyan_mesh_free(out)
        L.raise_for(st, err)
    if not out:
        raise L.BanyanError(14, "the library returned OK but no mesh", "BANYAN_E_INTERNAL")
    return MeshData.take(out)


def tube(points, radii, sides=12, caps=True):
    """banyan_tube_generate: the smallest thing the library makes."""
    pts, n = A.points("points", points)
    rad, nr = A.numbers_of("radii", radii)
    if nr != n:
        raise L.BanyanError(1, "%d radii for %d points" % (nr, n), "BANYAN_E_INVALID_ARG")
    return call_generate(L.load().banyan_tube_generate, pts, rad, n, A.int32("sides", sides), int(bool(caps)))


def lods(d, ratios, billboard=False, size=None, threads=0):
    """banyan_mesh_lods of MeshData d taken under capture(): the levels of
    the falling ratios (each made from the one before), then with
    billboard the crossed cards (size: the picture's pixels), as a list of
    MeshData. The library checks ratios and names the bad one."""
    if d.c_mesh is None:
        raise L.BanyanError(1, "the mesh was not kept (take it under core.mesh.capture())", "BANYAN_E_INVALID_ARG")
    lib = L.load()
    n = len(ratios)
    arr = (C.c_double * max(n, 1))(*[float(r) for r in ratios])
    bb = None
    if billboard:
        bb = S.LodParams()
        lib.banyan_lod_params_init(C.byref(bb))
        bb.billboard = 1
        if size is not None:
            bb.billboard_size = int(size)
    count = n + (1 if billboard else 0)
    out = (C.POINTER(S.Mesh) * max(count, 1))()
    err = S.Error()
    st = lib.banyan_mesh_lods(d.c_mesh, arr, n, C.byref(bb) if bb is not None else None, int(threads), None, out,
                              C.byref(err))
    if st:
        L.raise_for(st, err)
    return [MeshData.take(out[k]) for k in range(count)]


def lod(d, ratio=0.5, billboard=False, planes=None, size=None, seed=None):
    """banyan_mesh_lod of MeshData d taken under capture() (d.c_mesh):
    a coarser MeshData, about ratio of the triangles, or the crossed
    billboard cards (planes, size: the picture's pixels) with billboard."""
    if d.c_mesh is None:
        raise L.BanyanError(1, "the mesh was not kept (take it under core.mesh.capture())", "BANYAN_E_INVALID_ARG")
    lib = L.load()
    p = S.LodParams()
    lib.banyan_lod_params_init(C.byref(p))
    p.ratio = float(ratio)
    p.billboard = int(bool(billboard))
    if planes is not None:
        p.billboard_planes = int(planes)
    if size is not None:
        p.billboard_size = int(size)
    if seed is not None:
        p.seed = int(seed)
    return call_generate(lib.banyan_mesh_lod, d.c_mesh, C.byref(p))
