"""Ivy on Suzanne, banyan against IvyGen (add_curve_ivygen), in
one Blender process, from the same start on the same mesh.

banyan grows on Suzanne's real surface (Host shape Surface: its evaluated
mesh in a host set, banyan.api.ivy) with the default parameters; IvyGen
grows with its defaults and its maxIvyLength chosen in this run by
peers.py's secant search so that its total stem length matches banyan's.
Both start at the surface point of Suzanne nearest START_NEAR (IvyGen
seeds at the 3D cursor as it is; banyan snaps its start to the surface).

peers.py puts this in docs/benchmarks.md (section 5); run alone it
prints it. Figures: times (median [min .. max] of RUNS runs,
the two alternating), stem length, leaves, triangles, and the median and
90th percentile distance of each one's stem points (banyan: skeleton
points; IvyGen: its curve's points) and leaf vertices to Suzanne's
surface, measured with mathutils' BVHTree of the evaluated mesh in world
space (the same measure for both).

Run: tests/bench/peers/run.sh build [runs] ivy_suzanne.py   (default 5 runs)
"""
import math
import os
import statistics
import sys
import time
from array import array

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import peers as PE  # noqa: E402  enables banyan and IvyGen; Series, match_ivygen, ivygen_once, ...

import bpy  # noqa: E402
from mathutils import Vector  # noqa: E402
from mathutils.bvhtree import BVHTree  # noqa: E402

from banyan import api as B  # noqa: E402
from banyan.engine import hosts as H  # noqa: E402
from banyan.core import generators as G  # noqa: E402
from banyan.core.hostset import HostSet  # noqa: E402

ARGS = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
RUNS = max(1, int(ARGS[0])) if ARGS else 5
START_NEAR = (0.0, -1.6, 0.7)  # in front of Suzanne's chin
SAMPLE = 20000  # distance samples per set of points (evenly strided)


def suzanne():
    bpy.ops.wm.read_homefile(use_factory_startup=True)
    bpy.data.objects.remove(bpy.data.objects["Cube"])
    bpy.ops.mesh.primitive_monkey_add(size=2.0, location=(0.0, 0.0, 1.2))
    obj = bpy.context.active_object
    bpy.context.view_layer.update()
    return obj


def world_bvh(obj):
    """BVHTree of the evaluated mesh's own triangles in world space (what
    the add-on hands the library and Blender draws)."""
    dg = bpy.context.evaluated_depsgraph_get()
    me = obj.evaluated_get(dg).data
    me.calc_loop_triangles()
    mw = obj.matrix_world
    bvh = BVHTree.FromPolygons([mw @ v.co for v in me.vertices], [tuple(t.vertices) for t in me.loop_triangles])
    return bvh, len(me.loop_triangles)


def distances(bvh, pts):
    step = max(1, len(pts) // SAMPLE)
    return sorted(bvh.find_nearest(Vector(p))[3] for p in pts[::step])


def summary(d):
    if not d:
        return "-"
    return "%.4f / %.4f" % (statistics.median(d), d[min(len(d) - 1, int(0.9 * len(d)))])


def triples(flat, mw=None):
    pts = [tuple(flat[i:i + 3]) for i in range(0, len(flat) - 2, 3)]
    return [tuple(mw @ Vector(p)) for p in pts] if mw is not None else pts


def banyan_points(d):
    """(stem points: the skeleton, leaf vertices) of a MeshData."""
    part = d.attributes.get("part")
    pos = d.positions
    leaves = [tuple(pos[3 * i:3 * i + 3]) for i in range(d.vertex_count) if part is not None and part[i] > 0.5]
    return triples(d.skel_points), leaves


def ivygen_points(curve, leaf):
    """(stem points: the curve's poly points, leaf vertices), world."""
    mw = curve.matrix_world
    stem = [tuple(mw @ Vector(p.co[:3])) for s in curve.data.splines for p in s.points]
    lv = []
    if leaf is not None:
        co = array("f", bytes(12 * len(leaf.data.vertices)))
        leaf.data.vertices.foreach_get("co", co)
        lv = triples(co, leaf.matrix_world)
    return stem, lv


def section(runs=RUNS):
    """The section's markdown lines (and progress on stdout)."""
    t_all = time.perf_counter()
    out = []
    host = suzanne()
    bvh, host_tris = world_bvh(host)
    start = tuple(bvh.find_nearest(Vector(START_NEAR))[0])
    print("ivy_suzanne.py: %d runs, Blender %s, library %s; Suzanne %d triangles, start %s" % (
        runs, bpy.app.version_string, os.environ.get("BANYAN_LIB"), host_tris,
        tuple(round(c, 4) for c in start)), flush=True)
    p = B.make_params("ivy")
    p.set("start", start)
    dg = bpy.context.evaluated_depsgraph_get()

    build, grow, e2e = PE.Series(), PE.Series(), PE.Series()
    d = None

    def banyan_once():
        nonlocal d
        keep = PE.keep_names()
        m = build.time(H.mesh_input_from_object, host, dg)
        t0 = time.perf_counter()
        hs = HostSet(meshes=[m])
        build.t[-1] += time.perf_counter() - t0
        try:
            d = grow.time(G.ivy, p, hs)
        finally:
            hs.close()
        e2e.time(B.ivy, hosts=[host], params=p)
        PE.HO.clear_generated(keep)

    banyan_once()
    stem_len = PE.skeleton_length(d)
    b_stem, b_leaf = banyan_points(d)
    x, got = PE.match_ivygen(stem_len, "stem", host, cursor=start)
    print("banyan stem %.1f m; IvyGen maxIvyLength %.3g gives %.1f m" % (stem_len, x, got), flush=True)

    ig = PE.PeerRun("IvyGen, stem length matched", "maxIvyLength %.3g" % x)
    seen = {}

    def keep_points(curve, leaf):
        seen["stem"], seen["leaf"] = ivygen_points(curve, leaf)

    for r in range(runs):
        if r:
            banyan_once()
        PE.ivygen_once(ig, host, x, start, keep_points if r == 0 else None)
        print("run %d/%d done" % (r + 1, runs), flush=True)

    bd_stem, bd_leaf = distances(bvh, b_stem), distances(bvh, b_leaf)
    gd_stem, gd_leaf = distances(bvh, seen["stem"]), distances(bvh, seen["leaf"])
    leaves = PE.part_tris(d, 1) // PE.LEAF_CARD_TRIS["ivy"]
    w = out.append
    w("Suzanne (bpy.ops.mesh.primitive_monkey_add, size 2, %d triangles); start %s on its surface; median "
      "[min .. max] of %d runs; distances to Suzanne's surface (mathutils BVHTree, world space): median / "
      "90th percentile, metres." % (host_tris, tuple(round(c, 3) for c in start), runs))
    w("")
    w("| run | setting | stem m | leaves | triangles | host set | growth / operator | end to end | "
      "stem points: distance | leaf vertices: distance |")
    w("|---|---|---|---|---|---|---|---|---|---|")
    w("| banyan ivy | defaults (%d steps), Surface | %.1f | %d | %d | %s | %s | %s | %s | %s |" % (
        p.get("steps"), stem_len, leaves, d.triangle_count, build.fmt(1e3, "ms", 1), grow.fmt(), e2e.fmt(),
        summary(bd_stem), summary(bd_leaf)))
    w("| IvyGen | %s | %.1f | %d | %d | - | %s | %s | %s | %s |" % (
        ig.note, ig.stem, ig.leaves, ig.tris, ig.op.fmt(), ig.e2e.fmt(), summary(gd_stem), summary(gd_leaf)))
    w("")
    w("banyan sucker reach %.3f m, clearance %.4f m; %d / %d stem points, %d / %d leaf vertices sampled. "
      "Ratio of end-to-end times IvyGen / banyan: %.1fx; %.0f s in all." % (
          p.get("sucker_length"), p.get("clearance"), len(bd_stem), len(b_stem), len(bd_leaf), len(b_leaf),
          ig.e2e.med / e2e.med, time.perf_counter() - t_all))
    return out, ig.e2e.med / e2e.med


if __name__ == "__main__":
    lines, _ = section()
    print("\n".join(lines))
