"""The add-on's hand-off against Blender's own, in one Blender process.

Default: for the roots default, the wall ivy and the 100-tree boulevard:
  library   the generate call through the binding, copy-out included
  operator  the add-on's whole operator (bpy.ops...), library included
  bare      Blender's floor: foreach_set of the mesh's arrays into an empty
            mesh (vertices, loops, polygons, update(calc_edges=True):
            Blender derives the edges, which the add-on gets from the
            library instead) and linking one object; "bare" hands off
            positions and indices only, "bare+" also every array the
            operator hands off (the per-corner UVs, the vertex colours,
            the float attributes), and "bare+ev" also the view-layer
            update bpy.ops runs after every operator, which evaluates the
            new object once; "edges+ev" is bare_edges(): Blender given the
            same edges as the add-on, every array, smooth shading, material
            slots and the first evaluation, the floor the hand-off is
            judged against)
and the ratios (operator - library) / bare, / bare+ and / edges+ev. The
boulevard runs twice: one object per tree (100 objects, each with
Blender's per-object cost) and merged into one object, the case that
compares like with like. Every floor sets each array through Blender's
fastest stock path of the running version (stock_set: the generic
attributes from 4.0, the element properties in 3.4), so the ratios
compare the add-on with the best a script can do in that Blender.

--write: the hand-off rows of docs/benchmarks.md instead (handoff_rows):
for ivy_wall, keyaki_mature and the roots default, banyan.api's call plus
the first evaluation of its objects (e2e+ev) against the library's share
of that call (LibraryTimer) and the same-edges floor, the target
(e2e+ev - library) / edges <= 1.3.
They go to tests/bench/peers/handoff.md, one block per Blender series
(the other series' blocks kept), and that file's text replaces its copy
in docs/benchmarks.md (peers.py copies it in the same way when it
rewrites the page).

bare(), bare_edges(), first_evaluation() and clear_generated() are
imported by tests/bench/peers/peers.py,
stock_mesh() by tests/blender/test_mesh_topology.py.

Run (the runner's environment; a bpy wheel's Python with
tests/blender/bpy_blender.py stands in for `blender`):
  BANYAN_LIB=build/libbanyan.so BLENDER_USER_SCRIPTS=<dir with addons/banyan> \
    blender -b --factory-startup --addons banyan --python tests/bench/blender_handoff.py [-- runs [--write]]
"""
import os
import statistics
import sys
import time
from array import array

import bpy

from banyan.engine import hosts as H
from banyan.core import generators as G
from banyan.core.params import Params

# The default 450 steps pass the default max_vertices (4 M) on this wall.
IVY_STEPS = 300
ARGS = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
SRC = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
RUNS = int(next((a for a in ARGS if a.isdigit()), 3))
WRITE = "--write" in ARGS


def clear_generated(keep):
    for o in list(bpy.data.objects):
        if o.name not in keep:
            bpy.data.objects.remove(o)
    for m in list(bpy.data.meshes):
        if m.users == 0:
            bpy.data.meshes.remove(m)
    for m in list(bpy.data.materials):
        # The add-on's shared "Banyan ..." materials stay, as they do
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


def _int32(a):
    """A 4-byte int array seen as 'i' (no copy): the generic int attributes
    take a buffer whole only when its item type is theirs."""
    return memoryview(a).cast("B").cast("i")


def stock_set(me, what, data):
    """Blender's fastest stock way to set one array of a mesh whose elements
    were added: from 4.0 the generic attribute (position, .edge_verts,
    .corner_vert, .corner_edge, the UV map's FLOAT2 corner attribute),
    one buffer copy; else (3.4) the element property, the fast one there.
    what: "co", "edges", "vertex_index", "edge_index" or a UV map's name."""
    attr, prop, coll, conv = {
        "co": ("position", "vector", me.vertices, None),
        "edges": (".edge_verts", "value", me.edges, _int32),
        "vertex_index": (".corner_vert", "value", me.loops, _int32),
        "edge_index": (".corner_edge", "value", me.loops, _int32),
    }.get(what, (what, "vector", None, None))
    a = me.attributes.get(attr) if bpy.app.version >= (4, 0, 0) else None
    if a is not None:
        a.data.foreach_set(prop, conv(data) if conv else data)
    elif coll is None:
        me.uv_layers[what].data.foreach_set("uv", data)
    else:
        coll.foreach_set("vertices" if what == "edges" else what, data)


def stock_mesh(d, name="bare"):
    """Blender's own way from arrays to a mesh: positions, loops and
    triangles by foreach_set (stock_set), then update(calc_edges=True)
    derives the edges. tests/blender/test_mesh_topology.py compares the
    add-on's edges with these."""
    me = bpy.data.meshes.new(name)
    nv, ni = d.vertex_count, d.index_count
    me.vertices.add(nv)
    stock_set(me, "co", d.positions)
    me.loops.add(ni)
    stock_set(me, "vertex_index", d.indices)
    me.polygons.add(ni // 3)
    me.polygons.foreach_set("loop_start", array("I", range(0, ni, 3)))
    if not bpy.types.MeshPolygon.bl_rna.properties["loop_total"].is_readonly:  # read-only from 4.0
        me.polygons.foreach_set("loop_total", array("I", [3]) * (ni // 3))
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
    kind = getattr(d.indices, "typecode", None) or getattr(d.indices, "format", None)  # an array, or a borrowed view
    ind = d.indices if kind == "I" else array("I", d.indices)
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
    version and size (4.1+: Mesh.shade_smooth(); 4.0: no sharp_face
    attribute; older: the operator's one C loop on big meshes, foreach_set
    of the bit flags on small ones)."""
    if bpy.app.version >= (4, 1, 0):
        me.shade_smooth()
    elif bpy.app.version >= (4, 0, 0):
        if me.attributes.get("sharp_face") is not None:
            me.attributes.remove(me.attributes["sharp_face"])
    elif nt >= SMOOTH_OP_MIN:
        with bpy.context.temp_override(selected_editable_objects=[ob], active_object=ob, object=ob):
            bpy.ops.object.shade_smooth()
    else:
        me.polygons.foreach_set("use_smooth", array("b", [1]) * nt)


def bare_edges(d, topo=None, evaluate=True, cpu=None):
    """Blender's floor given the same edges as the add-on: foreach_set
    (stock_set, the fastest stock path of this Blender) of the same vertices, edges, loops (vertex and edge index) and triangles,
    the material slots and indices, smooth shading, the UV, colour and
    every attribute array the library returns (the wind pivot as one
    vector, as the add-on writes it; the floor stays fixed when the add-on
    changes what it hands off),
    one linked object, and with evaluate its first evaluation
    (first_evaluation). topo: triangle_topology(d), computed outside the
    clock when not given. The seconds taken; with cpu (a list) the
    process's CPU seconds are appended to it too."""
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
    c, t = time.process_time(), time.perf_counter()
    me = bpy.data.meshes.new("bare_edges")
    for m in mats:
        me.materials.append(m)
    me.vertices.add(nv)
    stock_set(me, "co", d.positions)
    me.edges.add(len(edges) // 2)
    stock_set(me, "edges", edges)
    me.loops.add(ni)
    stock_set(me, "vertex_index", d.indices)
    stock_set(me, "edge_index", corner_edges)
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
        stock_set(me, me.uv_layers.new(name="UVMap", do_init=False).name, d.corner_uvs)
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
    if cpu is not None:
        cpu.append(time.process_time() - c)
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
        stock_set(me, me.uv_layers.new(name="UVMap").name, d.corner_uvs)
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
        lambda **kw: bpy.ops.mesh.banyan_roots(host_shape='BOX', ground_at_hosts=False, **kw)  # the library's ground


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
    print("banyan Blender hand-off benchmark, median of %d runs, Blender %s" % (RUNS, bpy.app.version_string))
    print("op: the operator through bpy.ops, whose closing view-layer update is the new objects' first evaluation")
    print("%-20s %9s %9s %9s %8s %8s %8s %8s %8s %11s %12s %13s %12s %9s" % (
        "case", "vertices", "tris", "library", "bare", "bare+", "bare+ev", "edges+ev", "op", "(op-l)/bare",
        "(op-l)/bare+", "(op-l)/bare+ev", "(op-l)/edges", "op no-uv"))
    for label, gen, setup in CASES:
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


class LibraryTimer:
    """Within the block, the wall and CPU seconds of every generate call
    through ctypes (core.generators' call_generate, without its copy-out
    into Python arrays, which the hand-off does and is timed with): the
    library's share of an end-to-end call, timed inside that call, so that
    both see the same state of the process's memory (a separate library
    run can catch its allocator in another state: page faults of fresh
    pages cost it tens of ms, or not)."""

    def __enter__(self):
        self.wall = self.cpu = 0.0
        self.saved = G.call_generate

        def timed(func):
            def call(*args):
                c, t = time.process_time(), time.perf_counter()
                try:
                    return func(*args)
                finally:
                    self.wall += time.perf_counter() - t
                    self.cpu += time.process_time() - c
            return call
        G.call_generate = lambda func, *args: self.saved(timed(func), *args)
        return self

    def __exit__(self, *exc):
        G.call_generate = self.saved


HANDOFF_MD = "handoff.md"  # in tests/bench/peers/, beside batch.md
HANDOFF_TITLE = "## The hand-off against Blender's floor, per Blender version"
HANDOFF_TARGET = 1.3


def _handoff_cases():
    """(generator, setup) of each hand-off row; setup(), in a fresh factory
    scene (the cube as ivy_wall's wall, as peers.py has it), gives (label,
    job, api): job() a new banyan.api Job and api() the public call with
    the same arguments, so that the floor's mesh (the job's data) and the
    end to end are the same plant."""
    from banyan import api as B

    def ivy():
        cube = bpy.data.objects["Cube"]
        cube.location = (0.0, 0.1, 1.5)
        cube.scale = (1.5, 0.1, 1.5)
        bpy.context.view_layer.update()
        kw = dict(hosts=[cube], preset="ivy_wall", host_shape='BOX')
        return "ivy_wall (%d steps)" % B.make_params("ivy", preset="ivy_wall").get("steps"), \
            lambda: B.ivy_job(**kw), lambda: B.ivy(**kw)

    def keyaki():
        kw = dict(preset="keyaki_mature")
        return "keyaki_mature", lambda: B.keyaki_tree_job(**kw), lambda: B.keyaki_tree(**kw)

    def roots():
        kw = dict(hosts=[bpy.data.objects["Cube"]], host_shape='BOX')
        return "roots default (default cube)", lambda: B.strangler_roots_job(**kw), lambda: B.strangler_roots(**kw)

    return (("ivy", ivy), ("keyaki", keyaki), ("roots", roots))


def _job_data(job_call):
    """The MeshData of a new job's compute (the plant the api call makes)."""
    with job_call() as job:
        return job.compute().data


def _ms(xs):
    return "%.1f ms [%.1f .. %.1f]" % (1000 * statistics.median(xs), 1000 * min(xs), 1000 * max(xs))


def handoff_rows(runs):
    """The markdown rows of the hand-off table for this Blender: per case,
    `runs` rounds of the same-edges floor (bare_edges) and banyan.api's
    call with its first evaluation, its generate calls timed within it
    (LibraryTimer), interleaved; medians."""
    rows, notes = [], []
    for gen, setup in _handoff_cases():
        bpy.ops.wm.read_homefile(use_factory_startup=True)
        keep = {o.name for o in bpy.data.objects}
        label, job_call, api_call = setup()
        d = _job_data(job_call)
        topo = triangle_topology(d)
        libs, floors, e2e, ev = [], [], [], []
        cpu_lib, cpu_floor, cpu_tot = [], [], []
        for r in range(runs):
            floors.append(bare_edges(d, topo, cpu=cpu_floor))
            c, t = time.process_time(), time.perf_counter()
            with LibraryTimer() as lib_t:
                api_call()
            e2e.append(time.perf_counter() - t)
            libs.append(lib_t.wall)
            cpu_lib.append(lib_t.cpu)
            new = [o for o in bpy.data.objects if o.name not in keep]
            t = time.perf_counter()
            first_evaluation(new)
            ev.append(time.perf_counter() - t)
            cpu_tot.append(time.process_time() - c)
            if r == 0:
                notes += ["%s: %s" % (label, x) for x in floor_differences(d, topo, new)]
            clear_generated(keep)
        e2e_ev = [a + b for a, b in zip(e2e, ev)]
        lib, floor, tot = (statistics.median(x) for x in (libs, floors, e2e_ev))
        ratio = (tot - lib) / floor
        c_lib, c_floor, c_tot = (statistics.median(x) for x in (cpu_lib, cpu_floor, cpu_tot))
        c_ratio = (c_tot - c_lib) / c_floor
        rows.append("| %s | %d | %d | %s | %s | %s | %s | %s | %.2f | %.2f | %.2f | %s |" % (
            label, d.vertex_count, d.triangle_count, _ms(libs), _ms(e2e), _ms(ev), _ms(e2e_ev), _ms(floors),
            tot / (lib + floor), ratio, c_ratio,
            "**met**" if max(ratio, c_ratio) <= HANDOFF_TARGET else "**not met**"))
        print(rows[-1], flush=True)
    return rows, notes


def handoff_block(runs):
    """This Blender's block of handoff.md, between its markers."""
    import datetime
    import platform
    from machine_info import machine
    series = "%d.%d" % bpy.app.version[:2]
    load0, t0 = os.getloadavg(), time.perf_counter()
    started = datetime.datetime.now(datetime.timezone.utc)
    rows, notes = handoff_rows(runs)
    load1 = os.getloadavg()
    model, cores = machine()
    stock = ("the generic attributes position, .edge_verts, .corner_vert, .corner_edge and the UV map's FLOAT2 "
             "corner attribute" if bpy.app.version >= (4, 0, 0) else
             "vertices.co, edges.vertices, loops.vertex_index / edge_index and the UV layer's data.uv")
    out = ["<!-- blender %s -->" % series,
           "### Blender %s" % bpy.app.version_string, "",
           "Python %s; banyan %s. Machine: %s, %d logical cores; load average %.2f at the start, %.2f at the end; "
           "measured %s UTC, %.0f s. Median of %d runs [min .. max]; the floor sets the arrays through %s." % (
               platform.python_version(), _banyan_commit(), model, cores, load0[0], load1[0],
               started.strftime("%Y-%m-%d %H:%M"), time.perf_counter() - t0, runs, stock), "",
           "| run | vertices | triangles | library | end to end | first evaluation | e2e+ev | edges (floor) | "
           "e2e+ev / (library + edges) | hand-off (e2e+ev - lib) / edges | the same in CPU time | "
           "hand-off <= %.1f |" % HANDOFF_TARGET,
           "|---|---|---|---|---|---|---|---|---|---|---|---|"] + rows + [""]
    out.append("The floor's mesh against the add-on's (`floor_differences`): %s." % (
        "; ".join(notes) if notes else "the same for every run above"))
    out.append("<!-- end blender %s -->" % series)
    return series, out


def _banyan_commit():
    import subprocess
    try:
        head = subprocess.run(["git", "-C", SRC, "rev-parse", "--short", "HEAD"], capture_output=True, text=True,
                              check=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", SRC, "diff", "--quiet", "HEAD"]).returncode != 0
        return head + (" with uncommitted changes" if dirty else "")
    except (OSError, subprocess.CalledProcessError):
        return "?"


def write_handoff(runs):
    """Measures this Blender's block, puts it into tests/bench/peers/handoff.md
    (blocks ordered by Blender series, the others kept) and that file's
    text into docs/benchmarks.md in place of its copy there (before the
    sections measured by hand when it has none)."""
    series, block = handoff_block(runs)
    path = os.path.join(SRC, "tests", "bench", "peers", HANDOFF_MD)
    blocks = {}
    if os.path.exists(path):
        cur = None
        for line in open(path).read().splitlines():
            if line.startswith("<!-- blender "):
                cur = line[len("<!-- blender "):-len(" -->")]
                blocks[cur] = []
            if cur is not None:
                blocks[cur].append(line)
            if line.startswith("<!-- end blender "):
                cur = None
    blocks[series] = block
    head = [HANDOFF_TITLE, "",
            "<!-- kept in tests/bench/peers/%s, written by tests/bench/blender_handoff.py --write (one block per "
            "Blender version); peers.py copies it in -->" % HANDOFF_MD, "",
            "`blender -b --factory-startup --addons banyan --python tests/bench/blender_handoff.py -- RUNS --write`, "
            "in Debian's Blender and in each bpy wheel (tests/blender/bpy_blender.py as `blender`). *library*, *end "
            "to end* (`banyan.api`), *first evaluation*, *e2e+ev* and *edges* (the same-edges floor, "
            "`blender_handoff.bare_edges`) as in Terms, *library* timed inside the end-to-end call "
            "(`blender_handoff.LibraryTimer`: both see the same state of the process's memory); each Blender's floor sets the arrays through that version's "
            "fastest stock path, as the add-on does (`build_mesh._Writer`), so the hand-off ratio compares "
            "like with like. Target: hand-off (e2e+ev - library) / edges <= %.1f; *the same in CPU time* takes the "
            "medians of the Blender process's CPU time (`time.process_time`, every thread) instead of wall-clock "
            "time, less sensitive to the other processes of a shared machine; the target is met when both are." %
            HANDOFF_TARGET, ""]
    key = lambda v: tuple(int(x) for x in v.split("."))  # noqa: E731
    text = "\n".join(head + [ln for v in sorted(blocks, key=key) for ln in blocks[v] + [""]]).rstrip() + "\n"
    with open(path, "w") as f:
        f.write(text)
    print("blender_handoff.py: wrote %s" % path)
    docs = os.path.join(SRC, "docs", "benchmarks.md")
    lines = open(docs).read().split("\n")
    new = text.rstrip().split("\n") + [""]
    if HANDOFF_TITLE in lines:
        i = lines.index(HANDOFF_TITLE)
        j = next((k for k in range(i + 1, len(lines)) if lines[k].startswith("## ")), len(lines))
        lines[i:j] = new
    else:
        i = next((k for k, ln in enumerate(lines) if ln.startswith("## 8.")), len(lines))
        lines[i:i] = new
    with open(docs, "w") as f:
        f.write("\n".join(lines))
    print("blender_handoff.py: wrote %s" % docs)


if __name__ == "__main__":  # tests/bench/peers/peers.py imports bare()
    if WRITE:
        sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))  # machine_info
        write_handoff(max(RUNS, 1))
    else:
        main()
