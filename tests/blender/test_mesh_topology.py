"""build_mesh.fill_mesh hands Blender the edges (banyan_triangle_edges)
instead of update(calc_edges=True): for every generator's mesh,
mesh.validate finds nothing to fix, the edges are the ones Blender derives
itself (same count, same vertex pairs), every loop's edge joins its vertex
and the next loop's, and positions, loops and uvs are what the library
made. Polygons come out smooth by either path of _smooth (foreach_set, or
the operator on big meshes), and the operator path touches no other
object: not in edit mode, not in a paint mode on another object."""
import os
import sys
from array import array

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "bench"))
import bt  # noqa: E402
from blender_handoff import stock_mesh  # noqa: E402  Blender's own edges (calc_edges)
import gens  # noqa: E402

import bpy  # noqa: E402
from banyan import build_mesh as BM  # noqa: E402


def get(coll, prop, n, typecode="i"):
    a = array(typecode, [0]) * n
    coll.foreach_get(prop, a)
    return a


def edge_pairs(me):
    ev = get(me.edges, "vertices", 2 * len(me.edges))
    return [(min(a, b), max(a, b)) for a, b in zip(ev[0::2], ev[1::2])]


def smooth_count(me):
    return sum(get(me.polygons, "use_smooth", len(me.polygons), "b"))


def test_topology(gen):
    bt.reset_scene()
    gens.prepare(gen)
    cube = bpy.data.objects["Cube"]
    d = gens.library_mesh(gen, [cube], gens.KWARGS[gen])
    me = bpy.data.meshes.new("ours")
    BM.fill_mesh(me, d.positions, d.indices, corner_uvs=d.corner_uvs)
    ref = stock_mesh(d, "reference")
    ni, nt = d.index_count, d.index_count // 3
    bt.check(ni > 0 and len(me.loops) == ni and len(me.polygons) == nt, "%s: %d loops, %d polygons" % (
        gen, len(me.loops), len(me.polygons)))
    ours, theirs = edge_pairs(me), edge_pairs(ref)
    bt.check(len(ours) == len(theirs), "%s: %d edges, calc_edges makes %d" % (gen, len(ours), len(theirs)))
    bt.check(len(set(ours)) == len(ours), "%s: no edge twice" % gen)
    bt.check(set(ours) == set(theirs), "%s: the edges are calc_edges' (%d differ)" % (
        gen, len(set(ours) ^ set(theirs))))
    vi = get(me.loops, "vertex_index", ni)
    ei = get(me.loops, "edge_index", ni)
    bad = sum(ours[ei[k]] != (min(vi[k], vi[k + 1 - 3 * (k % 3 == 2)]), max(vi[k], vi[k + 1 - 3 * (k % 3 == 2)]))
              for k in range(ni))
    bt.check(bad == 0, "%s: %d loops whose edge does not join them to the next loop" % (gen, bad))
    bt.check(list(vi) == list(d.indices), "%s: loop vertices are the library's indices" % gen)
    bt.check(get(me.polygons, "loop_start", nt) == array("i", range(0, ni, 3)), "%s: loop starts" % gen)
    bt.check(get(me.vertices, "co", 3 * d.vertex_count, "f") == d.positions, "%s: positions" % gen)
    bt.check(get(me.uv_layers["UVMap"].data, "uv", 2 * ni, "f") == d.corner_uvs, "%s: uvs" % gen)
    bt.check(smooth_count(me) == nt, "%s: all polygons smooth" % gen)
    # validate() returns True when it had something to fix: nothing here
    bt.check(me.validate(verbose=True) is False, "%s: mesh.validate() fixed something" % gen)
    bt.check(len(me.edges) == len(theirs), "%s: validate() kept every edge" % gen)
    bpy.data.meshes.remove(me)
    bpy.data.meshes.remove(ref)


def quad_mesh():
    """A big enough strip of triangles for the operator path."""
    n = 400
    pos = array("f")
    for i in range(n):
        pos.extend((i, 0.0, 0.0, i, 1.0, 0.0))
    idx = array("I")
    for i in range(n - 1):
        a = 2 * i
        idx.extend((a, a + 2, a + 1, a + 1, a + 2, a + 3))
    return pos, idx


def test_smooth_paths():
    bt.reset_scene()
    pos, idx = quad_mesh()
    nt = len(idx) // 3
    old = BM.SMOOTH_OP_MIN
    try:
        for label, limit in (("foreach_set", 10 ** 9), ("operator", 1)):
            BM.SMOOTH_OP_MIN = limit
            before = {o.name for o in bpy.data.objects}
            me = BM.fill_mesh(bpy.data.meshes.new(label), pos, idx)
            bt.check(smooth_count(me) == nt, "%s: all %d polygons smooth (%d)" % (label, nt, smooth_count(me)))
            bt.check({o.name for o in bpy.data.objects} == before, "%s: no object left behind" % label)
            bt.check(me.validate() is False, "%s: mesh valid" % label)
            flat = BM.fill_mesh(bpy.data.meshes.new(label + " flat"), pos, idx, smooth=False)
            bt.check(smooth_count(flat) == 0, "%s: smooth=False leaves polygons flat" % label)
        # The operator must not reach the user's active object in another mode.
        cube = bpy.data.objects["Cube"]
        bpy.context.view_layer.objects.active = cube
        for mode in ("EDIT", "SCULPT", "VERTEX_PAINT"):
            bpy.ops.object.mode_set(mode=mode)
            me = BM.fill_mesh(bpy.data.meshes.new("in " + mode), pos, idx)
            bpy.ops.object.mode_set(mode='OBJECT')
            bt.check(smooth_count(me) == nt, "%s mode: all polygons smooth" % mode)
            bt.check(smooth_count(cube.data) == 0, "%s mode: the active cube stays flat" % mode)
    finally:
        BM.SMOOTH_OP_MIN = old


def test_binding_errors():
    from banyan.core import BanyanError
    from banyan.core.mesh import triangle_edges
    try:
        triangle_edges(array("I", [0, 1, 5]), 3)
        bt.check(False, "an index past the vertices accepted")
    except BanyanError as e:
        bt.check(e.status == 2 and "indices[2] = 5" in e.message, "out of range: %s" % e.message)
    try:
        triangle_edges(array("d", [0, 1, 2]), 3)
        bt.check(False, "a double array accepted")
    except TypeError:
        bt.check(True, "")
    ce, ed, st = triangle_edges(array("I"), 0)
    bt.check(len(ce) == len(ed) == len(st) == 0, "no triangles, no edges")


for g in gens.OPS:
    if bt.generator(g):
        bt.run(lambda: test_topology(g))
bt.run(test_smooth_paths)
bt.run(test_binding_errors)
bt.done()
