"""Issue 7 "Speed": in one Blender process, for the roots default, the
wall ivy and the 100-tree boulevard:
  library   the generate call through the binding, copy-out included
  operator  the add-on's whole operator (bpy.ops...), library included
  bare      Blender's floor: foreach_set of the mesh's arrays into an empty
            mesh (vertices, loops, polygons, update(calc_edges=True):
            Blender derives the edges, which the add-on gets from the
            library instead; indices as MeshData holds them, 'I') and
            linking one object; "bare" hands off positions and indices
            only, "bare+" also every array the operator hands off (the
            per-corner UVs, the vertex colours, the float attributes), and
            "bare+ev" also the view-layer update bpy.ops runs after every
            operator, which evaluates the new object once; "edges+ev" is
            bare_edges(): Blender given the same edges as the add-on, every
            array, smooth shading, material slots and the first evaluation,
            the floor issue 23 compares the hand-off with)
and the ratios (operator - library) / bare and / bare+: the add-on's
hand-off against Blender's own for the same arrays (target <= 1.5).
The boulevard runs twice: one object per tree (100 objects, each with
Blender's per-object cost) and merged into one object, the case that
compares like with like.

bare(), bare_edges(), first_evaluation() and clear_generated() are
imported by tests/bench/peers/peers.py,
stock_mesh() by tests/blender/test_mesh_topology.py.

Run (the runner's environment):
  BANYAN_LIB=build/libbanyan.so BLENDER_USER_SCRIPTS=<dir with addons/banyan> \
    blender -b --factory-startup --addons banyan --python tests/bench/blender_handoff.py [-- runs]
"""
import statistics
import sys
import time
from array import array

import bpy

from banyan import hosts as H
from banyan.core import generators as G
from banyan.core.params import Params

# The default 450 steps pass the default max_vertices (4 M) on this wall.
IVY_STEPS = 300
RUNS = int(sys.argv[sys.argv.index("--") + 1]) if "--" in sys.argv else 3


def clear_generated(keep):
    for o in list(bpy.data.objects):
        if o.name not in keep:
            bpy.data.objects.remove(o)
    for m in list(bpy.data.meshes):
        if m.users == 0:
            bpy.data.meshes.remove(m)
    for m in list(bpy.data.materials):
        # The add-on's shared "Banyan ..." materials (issue 17) stay, as they do
        # in a user's .blend: only the first plant of a kind draws their
        # textures, and peers.py reports that cost on its own.
        if m.users == 0 and not m.name.startswith("Banyan "):
            bpy.data.materials.remove(m)
    for c in list(bpy.data.curves):  # peers.py: what IvyGen and Sapling leave
        if c.users == 0:
            bpy.data.curves.remove(c)
    for c in list(bpy.data.collections):
        if c.name.startswith("Keyaki Avenue"):
            bpy.data.collections.remove(c)
    # Evaluate the cleared scene now, so the view-layer update bpy.ops runs
    # before the next operator does not bill this housekeeping to it.
    bpy.context.view_layer.update()


def stock_mesh(d, name="bare"):
    """Blender's own way from arrays to a mesh: positions, loops and
    triangles by foreach_set, then update(calc_edges=True) derives the
    edges. tests/blender/test_mesh_topology.py compares the add-on's
    edges with these."""
    me = bpy.data.meshes.new(name)
    nv, ni = d.vertex_count, d.index_count
    me.vertices.add(nv)
    me.vertices.foreach_set("co", d.positions)
    me.loops.add(ni)
    me.loops.foreach_set("vertex_index", d.indices)
    me.polygons.add(ni // 3)
    me.polygons.foreach_set("loop_start", array("i", range(0, ni, 3)))
    me.polygons.foreach_set("loop_total", array("i", [3]) * (ni // 3))
    me.update(calc_edges=True)
    return me


def first_evaluation(objs):
    """Blender's first evaluation of new objects, as a user pays it before
    seeing them: the depsgraph update that bpy.ops runs after every
    operator (the peers' convert step pays it inside bpy.ops), then each
    object's evaluated mesh fetched (its modifier stack, e.g. a wind or
    growth modifier, evaluated by then). Drawing is not included: no
    viewport in -b, for either side. Returns the vertices seen."""
    dg = bpy.context.evaluated_depsgraph_get()
    n = 0
    for o in objs:
        if o.type == 'MESH':
            n += len(o.evaluated_get(dg).data.vertices)
    return n


def triangle_topology(d):
    """Edges of d as the add-on hands them to Blender (banyan_triangle_edges):
    (corner_edges, edges, loop_starts). Computed outside bare_edges' clock:
    the floor is given the edges."""
    from banyan.core.mesh import triangle_edges
    ind = d.indices if d.indices.typecode == "I" else array("I", d.indices)
    return triangle_edges(ind, d.vertex_count)


def _material_slots(d):
    """Per-triangle material index of d's parts (None when all are 0)."""
    if all(p["material"] == 0 for p in d.parts):
        return None
    out = array("i")
    for p in d.parts:
        out += array("i", [p["material"]]) * (p["index_count"] // 3)
    return out


PIVOT_SCALARS = ("wind_pivot_x", "wind_pivot_y", "wind_pivot_z")
SMOOTH_OP_MIN = 10000  # as build_mesh.py: below, foreach_set of use_smooth is cheaper than the operator (~1 ms fixed cost)


def _smooth_floor(me, ob, nt):
    """Every polygon smooth, by Blender's cheapest stock way for this
    version and size (4.1+: Mesh.shade_smooth(); older: the operator's one
    C loop on big meshes, foreach_set of the bit flags on small ones)."""
    if bpy.app.version >= (4, 1, 0):
        me.shade_smooth()
    elif nt >= SMOOTH_OP_MIN:
        with bpy.context.temp_override(selected_editable_objects=[ob], active_object=ob, object=ob):
            bpy.ops.object.shade_smooth()
    else:
        me.polygons.foreach_set("use_smooth", array("b", [1]) * nt)


def bare_edges(d, topo=None, evaluate=True):
    """Blender's floor given the same edges as the add-on: foreach_set of
    the same vertices, edges, loops (vertex and edge index) and triangles,
    the material slots and indices, smooth shading, the UV, colour and
    every attribute array the library returns (the wind pivot as one
    vector, as the add-on writes it; the floor stays fixed when the add-on
    changes what it hands off),
    one linked object, and with evaluate its first evaluation
    (first_evaluation). topo: triangle_topology(d), computed outside the
    clock when not given. The seconds taken."""
    topo = topo or triangle_topology(d)
    corner_edges, edges, starts = topo
    mat_index = _material_slots(d)
    attrs = list((d.attributes or {}).items())
    pivot = None
    if all(k in (d.attributes or {}) for k in PIVOT_SCALARS):  # one vector, as the add-on writes it
        pivot = array("f", bytes(12 * d.vertex_count))
        for k, name in enumerate(PIVOT_SCALARS):
            pivot[k::3] = d.attributes[name]
    mats = [bpy.data.materials.new("bare_edges slot") for _ in d.materials]
    nv, ni = d.vertex_count, d.index_count
    nt = ni // 3
    t = time.perf_counter()
    me = bpy.data.meshes.new("bare_edges")
    for m in mats:
        me.materials.append(m)
    me.vertices.add(nv)
    me.vertices.foreach_set("co", d.positions)
    me.edges.add(len(edges) // 2)
    me.edges.foreach_set("vertices", edges)
    me.loops.add(ni)
    me.loops.foreach_set("vertex_index", d.indices)
    me.loops.foreach_set("edge_index", corner_edges)
    me.polygons.add(nt)
    me.polygons.foreach_set("loop_start", starts)
    if not bpy.types.MeshPolygon.bl_rna.properties["loop_total"].is_readonly:  # read-only from 4.0
        me.polygons.foreach_set("loop_total", array("I", [3]) * nt)
    if mat_index is not None:
        me.attributes.new("material_index", 'INT', 'FACE').data.foreach_set("value", mat_index)
    ob = bpy.data.objects.new("bare_edges", me)
    _smooth_floor(me, ob, nt)
    me.update()
    if d.corner_uvs is not None and nt:
        me.uv_layers.new(name="UVMap", do_init=False).data.foreach_set("uv", d.corner_uvs)
    if d.colors is not None:
        me.color_attributes.new("Color", 'FLOAT_COLOR', 'POINT').data.foreach_set("color", d.colors)
    for name, a in attrs:
        if pivot is not None and name in PIVOT_SCALARS:
            continue
        me.attributes.new(name if name not in me.attributes else "banyan_" + name, 'FLOAT',
                          'POINT').data.foreach_set("value", a)
    if pivot is not None:
        me.attributes.new("wind_pivot", 'FLOAT_VECTOR', 'POINT').data.foreach_set("vector", pivot)
    bpy.context.scene.collection.objects.link(ob)
    if evaluate:
        first_evaluation([ob])
    dt = time.perf_counter() - t
    bpy.data.objects.remove(ob)
    bpy.data.meshes.remove(me)
    for m in mats:
        bpy.data.materials.remove(m)
    bpy.context.view_layer.update()  # the removal's update, billed to no one
    return dt


def floor_differences(d, topo, objs):
    """What the add-on's objects hold that bare_edges' mesh of d would not,
    or the other way round: element counts and attribute names (a floor
    that hands off fewer or more arrays than the add-on is no floor).
    [] when they match; only for one-object results."""
    meshes = [o.data for o in objs if o.type == 'MESH']
    if len(meshes) != 1:
        return ["%d mesh objects, not one" % len(meshes)]
    me, out = meshes[0], []
    for what, have, want in (("vertices", len(me.vertices), d.vertex_count),
                             ("edges", len(me.edges), len(topo[1]) // 2),
                             ("polygons", len(me.polygons), d.index_count // 3),
                             ("material slots", len(me.materials), len(d.materials))):
        if have != want:
            out.append("%s: add-on %d, floor %d" % (what, have, want))
    attrs = d.attributes or {}
    floor = {n for n in attrs if n not in PIVOT_SCALARS or not all(k in attrs for k in PIVOT_SCALARS)}
    if all(k in attrs for k in PIVOT_SCALARS):
        floor.add("wind_pivot")
    if d.corner_uvs is not None:
        floor.add("UVMap")
    if d.colors is not None:
        floor.add("Color")
    if _material_slots(d) is not None:
        floor.add("material_index")
    addon = {a.name for a in me.attributes if not a.name.startswith(".") and a.name not in (
        "position", "sharp_face")} | {u.name for u in me.uv_layers}
    addon = {n[len("banyan_"):] if n.startswith("banyan_") and n[len("banyan_"):] in floor else n for n in addon}
    if addon - floor:
        out.append("only the add-on writes %s" % ", ".join(sorted(addon - floor)))
    if floor - addon:
        out.append("only the floor writes %s" % ", ".join(sorted(floor - addon)))
    return out


def bare(d, full=False, evaluate=False):
    """Blender's own hand-off of d: positions and indices, and with full
    also the UV, colour and attribute arrays the operator sets; with
    evaluate also the view-layer update that bpy.ops runs after every
    operator (the new object's first evaluation: normals, bounds)."""
    t = time.perf_counter()
    me = stock_mesh(d)
    if full and d.corner_uvs is not None:
        me.uv_layers.new(name="UVMap").data.foreach_set("uv", d.corner_uvs)
    if full and d.colors is not None:
        me.color_attributes.new("Color", 'FLOAT_COLOR', 'POINT').data.foreach_set("color", d.colors)
    for name, a in (d.attributes.items() if full else ()):
        me.attributes.new(name, 'FLOAT', 'POINT').data.foreach_set("value", a)
    ob = bpy.data.objects.new("bare", me)
    bpy.context.scene.collection.objects.link(ob)
    if evaluate:
        bpy.context.view_layer.update()
    dt = time.perf_counter() - t
    bpy.data.objects.remove(ob)
    bpy.data.meshes.remove(me)
    bpy.context.view_layer.update()  # the removal's update, billed to no one
    return dt


def setup_roots():
    cube = bpy.data.objects["Cube"]
    return [cube], lambda: G.roots(Params("roots"), H.boxes_from_objects([cube])), \
        lambda **kw: bpy.ops.mesh.banyan_roots(host_shape='BOX', **kw)


def setup_ivy():
    cube = bpy.data.objects["Cube"]
    cube.location = (0.0, 0.1, 1.5)
    cube.scale = (1.5, 0.1, 1.5)  # the CLI's default wall: 3 x 0.2 x 3 m
    bpy.context.view_layer.update()
    p = Params("ivy")
    p.set("steps", IVY_STEPS)
    return [cube], lambda: G.ivy(p, H.boxes_from_objects([cube])), \
        lambda **kw: bpy.ops.mesh.banyan_ivy(host_shape='BOX', start_at_cursor=False, steps=IVY_STEPS, **kw)


def setup_boulevard(merged=False):
    p = Params("avenue")
    p.set("placement", "count")
    p.set("count", 50)
    p.set("rows", 2)
    return [], lambda: G.avenue(p), \
        lambda **kw: bpy.ops.mesh.banyan_keyaki_avenue(path_from='PARAMS', placement='count', count=50, rows=2,
                                                       merged=merged, **kw)


CASES = [("roots default", "roots", setup_roots), ("wall ivy", "ivy", setup_ivy),
         ("boulevard, per tree", "avenue", setup_boulevard),
         ("boulevard, merged", "avenue", lambda: setup_boulevard(merged=True))]


def main():
    avail = G.available()
    print("banyan Blender hand-off benchmark, median of %d runs, Blender %s" % (RUNS, bpy.app.version_string))
    print("op: the operator through bpy.ops, whose closing view-layer update is the new objects' first evaluation")
    print("%-20s %9s %9s %9s %8s %8s %8s %8s %8s %11s %12s %13s %12s %9s" % (
        "case", "vertices", "tris", "library", "bare", "bare+", "bare+ev", "edges+ev", "op", "(op-l)/bare",
        "(op-l)/bare+", "(op-l)/bare+ev", "(op-l)/edges", "op no-uv"))
    for label, gen, setup in CASES:
        if not avail[gen]:
            print("%-20s not built into this library" % label)
            continue
        bpy.ops.wm.read_homefile(use_factory_startup=True)
        keep = {o.name for o in bpy.data.objects}
        hosts, lib_call, op_call = setup()
        libs, bares, bplus, bev, bedges, ops, nouv = [], [], [], [], [], [], []
        d = None
        for _ in range(RUNS):
            t = time.perf_counter()
            d = lib_call()
            libs.append(time.perf_counter() - t)
            bares.append(bare(d))
            bplus.append(bare(d, full=True))
            bev.append(bare(d, full=True, evaluate=True))
            bedges.append(bare_edges(d))
            for uv, out in ((True, ops), (False, nouv)):
                for h in hosts:
                    h.select_set(True)
                    bpy.context.view_layer.objects.active = h
                t = time.perf_counter()
                res = op_call(uv_map=uv)
                out.append(time.perf_counter() - t)
                assert res == {'FINISHED'}, res
                clear_generated(keep)
        lib_t, bare_t, bp_t, ev_t, ed_t, op_t, nouv_t = (statistics.median(x) for x in (
            libs, bares, bplus, bev, bedges, ops, nouv))
        print("%-20s %9d %9d %8.3fs %7.3fs %7.3fs %7.3fs %7.3fs %7.3fs %11.2f %12.2f %13.2f %12.2f %8.3fs" % (
            label, d.vertex_count, d.triangle_count, lib_t, bare_t, bp_t, ev_t, ed_t, op_t,
            (op_t - lib_t) / bare_t, (op_t - lib_t) / bp_t, (op_t - lib_t) / ev_t, (op_t - lib_t) / ed_t, nouv_t))
        sys.stdout.flush()


if __name__ == "__main__":  # tests/bench/peers/peers.py imports bare()
    main()
