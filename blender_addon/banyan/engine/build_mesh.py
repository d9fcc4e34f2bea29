"""MeshData -> Blender meshes, materials and objects, via foreach_set
through the fastest stock path of each Blender (the generic attributes
from 4.0, the element collections in 3.4: _Writer).

Every datablock made here is recorded in a Created list so a failure
half way removes everything again (the operator then leaves the scene as
it was). No per-vertex Python loops: arrays are sliced, per-corner UVs come
gathered by the library (banyan_mesh_corner_uvs), and splitting a mesh
into one object per group runs in C too (banyan_group_localize), and so
does the edge list Blender would otherwise derive (banyan_triangle_edges).
"""
import hashlib
import struct
from array import array

import bpy
from mathutils import Matrix

from ..core import structs as S
from ..core.mesh import localize_group, triangle_edges
from . import wind as W
from .materials import image_material, shared_material

COLOR_ATTRIBUTE = "Color"


class Created:
    """The datablocks an operation made, for rollback on failure."""

    def __init__(self):
        self.items = []

    def add(self, idblock):
        self.items.append(idblock)
        return idblock

    def objects(self):
        return [i for i in self.items if isinstance(i, bpy.types.Object)]

    def rollback(self):
        for idb in reversed(self.items):
            try:
                coll = _collection_of(idb)
                if coll is not None:
                    coll.remove(idb)
            except (ReferenceError, RuntimeError):
                pass
        self.items.clear()


def _collection_of(idb):
    for t, coll in ((bpy.types.Object, bpy.data.objects), (bpy.types.Mesh, bpy.data.meshes),
                    (bpy.types.Material, bpy.data.materials), (bpy.types.Collection, bpy.data.collections),
                    (bpy.types.NodeTree, bpy.data.node_groups), (bpy.types.Curve, bpy.data.curves),
                    (bpy.types.Image, bpy.data.images)):
        if isinstance(idb, t):
            return coll
    return None


LOOK = "banyan_look"    # on a flat material: the key of the look it was made for
STATE = "banyan_state"  # ...and the fingerprint of the material as made (an artist's edit changes it)
LOOK_VERSION = 1        # bump when make_material's node setup changes


def _look_key(spec, vertex_colors):
    """The look a flat material is made from (what make_material reads), as text."""
    col = tuple(round(float(c), 6) for c in spec["base_color"])
    tint = bool(vertex_colors and min(col[:3]) >= 0.99)
    return "%d|%s|%s|%.6f|%d|%d" % (LOOK_VERSION, spec["name"], ",".join("%.6f" % c for c in col),
                                   float(spec["roughness"]), bool(spec["double_sided"]), tint)


def _fingerprint(mat):
    """A hash of what an artist may change on a flat material: its viewport
    colour, roughness, culling and every node, input value and link of its
    node tree. Equal to the stored one: untouched since make_material."""
    h = hashlib.sha1()
    h.update(repr((tuple(round(c, 6) for c in mat.diffuse_color), round(mat.roughness, 6),
                   mat.use_backface_culling)).encode())
    nt = mat.node_tree
    if nt is not None:
        for n in sorted(nt.nodes, key=lambda n: n.name):
            h.update(("%s|%s|%s|" % (n.name, n.bl_idname, getattr(n, "layer_name", ""))).encode())
            for i in n.inputs:
                v = getattr(i, "default_value", None)
                if v is not None:
                    try:
                        v = tuple(round(x, 6) for x in v)
                    except TypeError:
                        v = round(v, 6) if isinstance(v, float) else v
                h.update(repr((i.identifier, v, i.is_linked)).encode())
        for ln in nt.links:
            h.update(("%s.%s>%s.%s|" % (ln.from_node.name, ln.from_socket.identifier, ln.to_node.name,
                                        ln.to_socket.identifier)).encode())
    return h.hexdigest()


def _reusable(mat, key):
    return (mat is not None and mat.library is None and mat.get(LOOK) == key
            and mat.get(STATE) == _fingerprint(mat))


def find_flat_material(spec, name, vertex_colors=False):
    """The flat material make_material made earlier for this look (same
    key), untouched since (its fingerprint unchanged), or None. The name a
    new one would get is tried first (one look-up), then every material."""
    key = _look_key(spec, vertex_colors)
    mat = bpy.data.materials.get(name)
    if _reusable(mat, key):
        return mat
    for m in bpy.data.materials:
        if m.get(LOOK) == key and _reusable(m, key):
            return m
    return None


def make_material(spec, created, prefix="banyan", vertex_colors=False, images=None):
    """A Principled material from a banyan_material dict. A white material
    on a mesh with vertex colours (the segments generator's) takes its
    base colour from them, as glTF viewers show base colour x COLOR_0.
    A material naming a library texture is the shared one of its kind and
    season instead (materials.py: made once, reused by every run). One
    naming an image of the mesh (a billboard's picture) gets it packed.
    A flat material is reused from an earlier run with the same look
    (key in LOOK) unless it was edited since (STATE, a fingerprint, no
    longer matches): an artist's material is never changed, and a new
    one is made beside it."""
    if 0 < spec.get("image", 0) <= len(images or ()):  # image k is images[k - 1]; 0: none
        return image_material(spec, images[spec["image"] - 1], created, prefix)
    if spec.get("texture", S.TEX_NONE) != S.TEX_NONE:
        return shared_material(spec, created, vertex_colors)
    name = "%s_%s" % (prefix, spec["name"])
    mat = find_flat_material(spec, name, vertex_colors)
    if mat is not None:
        return mat
    mat = created.add(bpy.data.materials.new(name))
    col = tuple(spec["base_color"])
    mat.diffuse_color = col
    mat.roughness = spec["roughness"]
    mat.use_backface_culling = not spec["double_sided"]
    if bpy.app.version < (5, 0, 0):  # 5.0: a new material always has its node tree (use_nodes is deprecated)
        mat.use_nodes = True
    bsdf = mat.node_tree.nodes.get("Principled BSDF")
    if bsdf is not None:
        bsdf.inputs["Base Color"].default_value = col
        bsdf.inputs["Roughness"].default_value = spec["roughness"]
        if vertex_colors and min(col[:3]) >= 0.99:
            vc = mat.node_tree.nodes.new("ShaderNodeVertexColor")
            vc.layer_name = COLOR_ATTRIBUTE
            mat.node_tree.links.new(vc.outputs["Color"], bsdf.inputs["Base Color"])
    mat[LOOK] = _look_key(spec, vertex_colors)
    mat[STATE] = _fingerprint(mat)
    return mat


def _unsigned(a):
    """a as array('I'): foreach_set copies a buffer whole only when its
    type matches the property's, and loop, edge and polygon indices are
    unsigned (an 'i' buffer goes item by item, 7x slower). MeshData's
    indices are 'I' already; other int arrays are copied once."""
    if isinstance(a, array) and a.typecode == "I":
        return a
    out = array("I")
    if isinstance(a, array) and a.itemsize == out.itemsize:
        out.frombytes(a)
    else:
        out.extend(a)
    return out


# From this many polygons on _smooth uses the operator: its fixed cost (a
# view-layer update before and after, about 1 ms in a small scene; the
# relations update it runs is one the first evaluation then skips) against
# 50 to 500 ns a polygon item by item (Blender 3.4.1: 0.6 vs
# 0.15 ms at 2,000 polygons, 1.0 vs 0.6 at 10,000, 1.3 vs 51 at 100,000).
SMOOTH_OP_MIN = 10000


DEFER = 'DEFER'  # fill_mesh(smooth=DEFER): the caller smooths many meshes at once (smooth_objects)


def _smooth_op(objs):
    """object.shade_smooth on objs (linked to a scene or not) in one call;
    False when it cannot run. Only in object mode: in a paint mode the
    operator would smooth the active object instead."""
    if bpy.context.mode != 'OBJECT':
        return False
    with bpy.context.temp_override(selected_editable_objects=objs, active_object=objs[0], object=objs[0]):
        return bpy.ops.object.shade_smooth.poll() and bpy.ops.object.shade_smooth() == {'FINISHED'}


def _smooth(me, nt):
    """Makes every polygon smooth. use_smooth is a bit flag, so foreach_set
    goes item by item (about 40 ns a polygon: 35 ms for the wall ivy), and
    Blender 3.4 has no Mesh.shade_smooth(); its operator sets the flags in
    one C loop (3 ms), here on a temporary object."""
    if nt >= SMOOTH_OP_MIN:
        ob = bpy.data.objects.new("banyan_smooth", me)
        try:
            if _smooth_op([ob]):
                return
        finally:
            bpy.data.objects.remove(ob)
    me.polygons.foreach_set("use_smooth", array("b", [1]) * nt)


def smooth_objects(objs):
    """Every polygon of the objects' meshes smooth (made with
    smooth=DEFER): one operator call for all of them on Blender 3.x
    (an avenue's trees: one pair of view-layer updates, not one per tree);
    nothing to do from 4.0 on (fill_mesh smoothed them, _shade)."""
    if not objs or bpy.app.version >= (4, 0, 0):
        return
    if sum(len(o.data.polygons) for o in objs) >= SMOOTH_OP_MIN and _smooth_op(objs):
        return
    for o in objs:
        o.data.polygons.foreach_set("use_smooth", array("b", [1]) * len(o.data.polygons))


def _int32(a):
    """a (4-byte ints, 'I' or 'i') seen as signed 'i', without a copy: the
    generic attributes .edge_verts, .corner_vert and .corner_edge are
    int32, and foreach_set copies a buffer whole only when its item type
    matches (an 'I' buffer goes item by item, 80x slower)."""
    return memoryview(a).cast("B").cast("i")


class _Writer:
    """Sets a mesh's vertices, edges and corners through the fastest stock
    path of the running Blender, told apart by what the mesh holds: the
    generic attributes position, .edge_verts, .corner_vert and .corner_edge
    (Blender 4.0 on; each one buffer copy), else the element collections'
    own properties (vertices.co, edges.vertices, loops.vertex_index and
    edge_index: Blender 3.4, where they are the fast ones; from 4.0 they go
    through the attributes item by item, 40 to 100 ms for the wall ivy)."""

    def __init__(self, me):
        self.me = me

    def _attr(self, name):
        return self.me.attributes.get(name)

    def positions(self, data, get=False):
        a = self._attr("position")
        if a is not None and a.domain == 'POINT' and a.data_type == 'FLOAT_VECTOR':
            (a.data.foreach_get if get else a.data.foreach_set)("vector", data)
        else:
            (self.me.vertices.foreach_get if get else self.me.vertices.foreach_set)("co", data)

    def _ints(self, attr, coll, prop, data):
        """The int32 generic attribute attr (4.0 on), else coll's prop."""
        a = self._attr(attr)
        if a is not None:
            a.data.foreach_set("value", _int32(data))
        else:
            coll.foreach_set(prop, data)

    def edges(self, data):
        self._ints(".edge_verts", self.me.edges, "vertices", data)

    def corner_verts(self, data):
        self._ints(".corner_vert", self.me.loops, "vertex_index", data)

    def corner_edges(self, data):
        self._ints(".corner_edge", self.me.loops, "edge_index", data)

    def uvs(self, data, name="UVMap"):
        """The per-corner UVs as a new UV map (made current): from 4.0 through
        its FLOAT2 corner attribute (the layer's data.uv goes item by item)."""
        layer = self.me.uv_layers.new(name=name, do_init=False)  # no default uvs: all are set next
        a = self._attr(layer.name)
        if a is not None and a.domain == 'CORNER' and a.data_type == 'FLOAT2' and bpy.app.version >= (4, 0, 0):
            a.data.foreach_set("vector", data)
        else:
            layer.data.foreach_set("uv", data)
        return layer


def _shade(me, nt, smooth):
    """Every polygon smooth (or flat) by the cheapest stock way: from 4.0
    the sharp_face attribute (absent: smooth; all true: flat, one buffer
    copy from a '?' buffer, the attribute's own item type, where a 'b'
    one goes item by item and Mesh.shade_flat() takes 100 ms for 300,000
    polygons in 4.5); 3.4 the use_smooth flags (_smooth)."""
    if bpy.app.version >= (4, 0, 0):
        sharp = me.attributes.get("sharp_face")
        if smooth and sharp is not None:
            me.attributes.remove(sharp)
        elif not smooth:
            sharp = sharp or me.attributes.new("sharp_face", 'BOOLEAN', 'FACE')
            sharp.data.foreach_set("value", memoryview(bytearray(b"\x01") * nt).cast("?"))
    elif smooth and smooth != DEFER:
        _smooth(me, nt)


def fill_mesh(me, positions, indices, *, corner_uvs=None, colors=None, attributes=None, material_index=None,
              smooth=True, shift=None, pivot_shift=None, topology=None):
    """Fills an empty mesh from flat buffers (indices are local vertex numbers),
    through the fastest stock path of the running Blender (_Writer).
    The edges come from the library (banyan_triangle_edges) with each
    loop's edge, so update() has nothing to derive. shift: a translation
    of the vertices and wind pivots (Mesh.transform, in double);
    pivot_shift: one of the pivots alone (vertices already moved in C).
    Both are applied before the pivots are written, so they are written
    once; the pivots are moved as the mesh's own vertices before the real
    ones are set (no temporary mesh: making and removing one costs about
    9 ms a tree). topology: triangle_edges(indices) computed ahead
    (MeshData.topology)."""
    nv = len(positions) // 3
    ni = len(indices)
    nt = ni // 3
    indices = _unsigned(indices)
    if topology is None or len(topology[0]) != ni:
        topology = triangle_edges(indices, nv)
    corner_edges, edges, loop_start = topology
    moved = shift is not None and any(shift)
    piv_shift = tuple((shift[k] if moved else 0.0) + (pivot_shift[k] if pivot_shift is not None else 0.0)
                      for k in range(3))
    me.vertices.add(nv)
    put = _Writer(me)
    pivots = W.pivot_vectors(attributes or {})
    if pivots is not None and any(piv_shift) and len(pivots) == len(positions):
        put.positions(pivots)
        me.transform(Matrix.Translation(piv_shift))
        put.positions(pivots, get=True)
    put.positions(positions)
    if moved:
        me.transform(Matrix.Translation(shift))
    me.edges.add(len(edges) // 2)
    put.edges(edges)
    me.loops.add(ni)
    put.corner_verts(indices)
    put.corner_edges(corner_edges)
    me.polygons.add(nt)
    me.polygons.foreach_set("loop_start", loop_start)
    if not bpy.types.MeshPolygon.bl_rna.properties["loop_total"].is_readonly:  # read-only from Blender 4.0
        me.polygons.foreach_set("loop_total", array("I", [3]) * nt)
    if material_index is not None:
        # The generic attribute (Blender 3.4+) takes the buffer whole; the
        # polygons' material_index goes item by item (50x slower).
        attr = me.attributes.get("material_index") or me.attributes.new("material_index", 'INT', 'FACE')
        attr.data.foreach_set("value", material_index)
    _shade(me, nt, smooth)
    me.update()
    if corner_uvs is not None and nt:
        put.uvs(corner_uvs)
    if colors is not None:
        ca = me.color_attributes.new(COLOR_ATTRIBUTE, 'FLOAT_COLOR', 'POINT')
        ca.data.foreach_set("color", colors)
    def add_float(name, data):
        attr_name = name if name not in me.attributes else "banyan_" + name
        me.attributes.new(attr_name, 'FLOAT', 'POINT').data.foreach_set("value", data)
    # The wind pivot's three scalars become one vector (wind.py).
    W.add_attributes(me, attributes or {}, add_float, pivots=pivots)
    return me


def material_indices(parts, tri_offset=0, part_material=None):
    """Per-triangle material slots from parts (None when all are slot 0)."""
    part_material = part_material or (lambda p: p["material"])
    if all(part_material(p) == 0 for p in parts):
        return None
    out = array("i")
    for p in parts:
        out += array("i", [part_material(p)]) * (p["index_count"] // 3)
    return out


def as_location(p):
    """p as an object's location holds it: Blender keeps locations in
    float32 (6 cm steps at 1e6 m; whole metres are exact)."""
    return struct.unpack("3f", struct.pack("3f", *p))


def placement(at, mesh_origin):
    """(location, shift): obj's location for `at` (world, snapped to
    float32) and the move of vertices relative to mesh_origin (world,
    double) that keeps them where they are (see place)."""
    loc = as_location(at)
    return loc, tuple(mesh_origin[k] - loc[k] for k in range(3))


def place(me, obj, at, mesh_origin):
    """Puts obj at `at` (world, snapped to float32) with me, whose vertices
    are relative to mesh_origin (world, double), moved so that they stay
    where they are: by mesh_origin - location, a short move in double when
    `at` is near the plant (docs/addon.md, "Far from the origin")."""
    loc = as_location(at)
    shift = tuple(mesh_origin[k] - loc[k] for k in range(3))
    if any(shift):
        W.transform_mesh(me, Matrix.Translation(shift))
    if any(loc):
        obj.location = loc


def object_from_mesh_data(name, d, collection, created, *, materials=None, uv=True, smooth=True, origin=None):
    """One object holding all of MeshData d (world = d.origin + position).
    origin: a world point that becomes the object's location, the mesh
    moved to be local to it (Mesh.transform, in C), or None (the object at
    d.origin: the world's origin, unless the plant is far from it)."""
    me = created.add(bpy.data.meshes.new(name))
    mats = materials if materials is not None else [
        make_material(m, created, name, d.colors is not None, getattr(d, "images", None)) for m in d.materials]
    for m in mats:
        me.materials.append(m)
    mesh_origin = getattr(d, "origin", (0.0, 0.0, 0.0))
    loc, shift = placement(mesh_origin if origin is None else origin, mesh_origin)
    # Blender 3.x smooths on the new object itself (smooth_objects, before it
    # joins the scene), not on a temporary one made and removed again.
    fill_mesh(me, d.positions, d.indices, corner_uvs=d.corner_uvs if uv else None, colors=d.colors,
              attributes=d.attributes, material_index=material_indices(d.parts), smooth=DEFER if smooth else False,
              shift=shift, topology=getattr(d, "topology", None))
    obj = created.add(bpy.data.objects.new(name, me))
    if smooth:
        smooth_objects([obj])
    if any(loc):
        obj.location = loc
    collection.objects.link(obj)
    return obj


def group_ranges(parts):
    """(v0, v1, i0, i1) of a list of contiguous parts, or None if not contiguous."""
    parts = sorted(parts, key=lambda p: p["vertex_offset"])
    v0, i0 = parts[0]["vertex_offset"], parts[0]["index_offset"]
    v, i = v0, i0
    for p in parts:
        if p["vertex_offset"] != v or p["index_offset"] != i:
            return None
        v += p["vertex_count"]
        i += p["index_count"]
    return v0, v, i0, i


def objects_per_group(prefix, d, collection, created, *, uv=True, smooth=True, progress=None, frame_local=False,
                      collections=None):
    """One object per part group (e.g. one per tree), origins at each
    group's base (bottom centre of its bounds). Returns the objects.
    frame_local: located in the mesh's frame (d.origin left out: an
    instanced avenue's variants, drawn where its instances put them).
    collections: {group: collection} to link each object to instead."""
    mats = [make_material(m, created, prefix, d.colors is not None, getattr(d, "images", None)) for m in d.materials]
    groups = d.groups()
    objs = []
    for n, (g, parts) in enumerate(groups.items()):
        r = group_ranges(parts)
        if r is None:
            raise ValueError("parts of group %d are not contiguous" % g)
        v0, v1, i0, i1 = r
        pos, idx, base = localize_group(d.positions[3 * v0:3 * v1], d.indices[i0:i1], v0)
        uvs = d.corner_uvs[2 * i0:2 * i1] if (uv and d.corner_uvs is not None) else None
        cols = d.colors[4 * v0:4 * v1] if d.colors is not None else None
        attrs = {k: a[v0:v1] for k, a in d.attributes.items()}
        me = created.add(bpy.data.meshes.new("%s_%03d" % (prefix, g)))
        for m in mats:
            me.materials.append(m)
        local_parts = [dict(p, index_offset=p["index_offset"] - i0) for p in parts]
        mo = getattr(d, "origin", (0.0, 0.0, 0.0))
        foot = tuple(mo[k] + base[k] for k in range(3))  # base is in the mesh's frame
        if any(mo) and not frame_local:
            loc, shift = placement(foot, foot)
        else:
            loc, shift = base, None
        # The pivots follow the vertices to the group's base (moved by C).
        fill_mesh(me, pos, idx, corner_uvs=uvs, colors=cols, attributes=attrs,
                  material_index=material_indices(local_parts), smooth=DEFER if smooth else False, shift=shift,
                  pivot_shift=tuple(-c for c in base))
        obj = created.add(bpy.data.objects.new(me.name, me))
        obj.location = loc
        (collections[g] if collections is not None else collection).objects.link(obj)
        objs.append(obj)
        if progress:
            progress(n + 1, len(groups))
    if smooth:
        smooth_objects(objs)
    return objs

