"""What a user waits for when banyan hands a plant to Blender,
against Blender's own floor for the same arrays. Per case, in one Blender
process (medians of RUNS, after one warm-up run that makes the shared
materials, as in a .blend that already has a plant):
  lib      Job.compute: the library call and copy-out (and, for one-object
           builds, the edge list, which compute makes off the main thread)
  build    Job.build: objects, meshes, materials
  eval     the first depsgraph evaluation of the new objects
           (evaluated_depsgraph_get + evaluated_get(dg).data)
  e2e      all three, as a script calling banyan.api waits
  floor    the same arrays by Blender's fastest stock path of its version
           (blender_handoff.stock_set), given the same edges (positions,
           edges, loop vertices and edges, loop starts, UVs, colours, every
           float attribute as the library names it), one object linked,
           its first evaluation: what any add-on pays for this mesh
  floor_min  the same with positions and topology only
Ratios: hand-off (build + eval) / floor and e2e / (lib + floor).
Cases: keyaki_l6 (a small tree, levels 6), keyaki_young, keyaki_mature,
ivy_wall (the CLI's 3 x 3 m wall, as a box), roots (defaults around the
default cube, as a box), avenue20 (20 trees, levels 8, one object each;
its floor is the whole avenue as one object), and <keyaki preset>+wind
(the Banyan Wind modifier on, evaluated on the first frame), +data (the
wind data without the modifier; the add-on's default has none) or -wind (no wind data); ivy_wall+data likewise. Before/after comparisons run two add-ons in alternating
processes (the same command with BLENDER_USER_SCRIPTS pointing at each).

  BANYAN_LIB=build/libbanyan.so BLENDER_USER_SCRIPTS=<dir with addons/banyan> \
    RUNS=5 CASES=keyaki_l6,keyaki_young,ivy_wall PROF=1 \
    blender -b --factory-startup --addons banyan --python tests/bench/handoff_small.py
PROF=1 prints a cProfile of the last build + evaluation.
"""
import bpy, time, sys, os, statistics, cProfile, pstats, io
from array import array
import banyan.api as B
from banyan.core.mesh import triangle_edges

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from blender_handoff import stock_set  # noqa: E402
RUNS = int(os.environ.get("RUNS", "5"))
CASES = os.environ.get("CASES", "keyaki_young,keyaki_mature,ivy_wall,roots").split(",")
PROF = os.environ.get("PROF")
TAG = os.environ.get("TAG", "")

def wall():
    cube = bpy.data.objects["Cube"]
    cube.location = (0.0, 0.1, 1.5); cube.scale = (1.5, 0.1, 1.5)
    bpy.context.view_layer.update(); return cube

def make_job(case):
    if case == "keyaki_l6":
        return B.keyaki_tree_job(levels=6)
    if case == "avenue20":
        return B.keyaki_avenue_job(values={"placement": "count", "count": 20, "tree.levels": 8})
    if case == "ivy_wall+data":
        return B.ivy_job(hosts=[bpy.data.objects["Cube"]], preset="ivy_wall", host_shape='BOX',
                         values={"wind": True})
    if case.endswith("+data"):
        return B.keyaki_tree_job(preset=case[:-5], values={"wind": True})
    if case.endswith("+wind"):
        return B.keyaki_tree_job(preset=case[:-5], wind=True)
    if case.endswith("-wind"):
        return B.keyaki_tree_job(preset=case[:-5], wind=False)
    if case.startswith("keyaki"):
        return B.keyaki_tree_job(preset=case)
    if case == "ivy_wall":
        return B.ivy_job(hosts=[bpy.data.objects["Cube"]], preset="ivy_wall", host_shape='BOX')
    return B.strangler_roots_job(hosts=[bpy.data.objects["Cube"]], host_shape='BOX')

def evaluate(objs):
    dg = bpy.context.evaluated_depsgraph_get()
    for o in objs:
        o.evaluated_get(dg).data

def floor(d, edges_pre, full=True):
    corner_edges, edges, starts = edges_pre
    t = time.perf_counter()
    me = bpy.data.meshes.new("floor")
    nv, ni = len(d.positions)//3, len(d.indices)
    me.vertices.add(nv); stock_set(me, "co", d.positions)
    me.edges.add(len(edges)//2); stock_set(me, "edges", edges)
    me.loops.add(ni); stock_set(me, "vertex_index", d.indices); stock_set(me, "edge_index", corner_edges)
    me.polygons.add(ni//3); me.polygons.foreach_set("loop_start", starts)
    if not bpy.types.MeshPolygon.bl_rna.properties["loop_total"].is_readonly:
        me.polygons.foreach_set("loop_total", array("I", [3]) * (ni//3))
    me.update()
    if full:
        if d.corner_uvs is not None:
            stock_set(me, me.uv_layers.new(name="UVMap", do_init=False).name, d.corner_uvs)
        if d.colors is not None:
            me.color_attributes.new("Color", 'FLOAT_COLOR', 'POINT').data.foreach_set("color", d.colors)
        for name, a in d.attributes.items():
            me.attributes.new(name, 'FLOAT', 'POINT').data.foreach_set("value", a)
    ob = bpy.data.objects.new("floor", me)
    bpy.context.scene.collection.objects.link(ob)
    evaluate([ob])
    dt = time.perf_counter() - t
    bpy.data.objects.remove(ob); bpy.data.meshes.remove(me)
    return dt

def cleanup(objs):
    for o in objs:
        me = o.data if o.type == 'MESH' else None
        bpy.data.objects.remove(o)
        if me is not None and me.users == 0:
            bpy.data.meshes.remove(me)
    for c in list(bpy.data.collections):
        if c.name.startswith("Keyaki Avenue"):
            bpy.data.collections.remove(c)
    evaluate([])

res = {}
for case in CASES:
    bpy.ops.wm.read_homefile(use_factory_startup=True)
    if case.startswith("ivy_wall"):
        wall()
    evaluate([])
    # warm: first run makes shared materials / textures
    j = make_job(case); objs = j.run(); evaluate(objs); cleanup(objs)
    lib, build, ev, e2e, fl, flmin = [], [], [], [], [], []
    for r in range(RUNS):
        # e2e: as a user calls it
        j = make_job(case)
        t0 = time.perf_counter()
        with j:
            j.compute()
            t1 = time.perf_counter()
            if PROF and r == RUNS - 1:
                pr = cProfile.Profile(); pr.enable()
            objs = j.build()
            t2 = time.perf_counter()
            evaluate(objs)
            t3 = time.perf_counter()
            if PROF and r == RUNS - 1:
                pr.disable()
        lib.append(t1 - t0); build.append(t2 - t1); ev.append(t3 - t2); e2e.append(t3 - t0)
        d = j.data
        cleanup(objs)
        pre = triangle_edges(d.indices, len(d.positions)//3)
        fl.append(floor(d, pre, True))
        flmin.append(floor(d, pre, False))
    m = statistics.median
    lib_, b_, ev_, e_, f_, fm_ = (m(x) for x in (lib, build, ev, e2e, fl, flmin))
    print("RESULT %s %-14s lib %8.2f build %8.2f eval %8.2f e2e %8.2f | floor %8.2f floor_min %8.2f | handoff/floor %.2f  e2e/(lib+floor) %.2f (ms)" % (
        TAG, case, lib_*1e3, b_*1e3, ev_*1e3, e_*1e3, f_*1e3, fm_*1e3, (b_+ev_)/f_, e_/(lib_+f_)), flush=True)
    if PROF:
        s = io.StringIO(); pstats.Stats(pr, stream=s).sort_stats("cumulative").print_stats(25); print(s.getvalue())
        s = io.StringIO(); pstats.Stats(pr, stream=s).sort_stats("tottime").print_stats(15); print(s.getvalue())
