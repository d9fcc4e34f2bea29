"""banyan against the peers a Blender user would pick instead,
in one Blender process, on one machine, ratios from the same run:

  1. ivy      banyan's ivy_wall preset vs IvyGen (add_curve_ivygen) on the
              same 3 m x 3 m wall: IvyGen's defaults, then maxIvyLength
              matched to banyan's total stem length and to its triangles
  2. tree     banyan's keyaki_mature vs Sapling (add_curve_sapling): its
              default tree (bevel on), with and without leaves, and levels 4 with leaves
  3. roots    banyan's roots against Blender's bare foreach_set of the same
              arrays (tests/bench/blender_handoff.py's bare())
  4. memory   build/tests/bench_tube: the tube sweeper against a store loop
  5. hosts    build/tests/bench_hosts, bench_roots_hosts, bench_ivy, and
              ivy_suzanne.py: ivy on Suzanne against IvyGen
  6. textures build/tests/bench_textures: the library's textures at 1024
  7. roots C  build/tests/bench_roots: the fused surface and the tubes
  8. instancing  build/tests/bench_instancing, run by hand: copied from instancing.md
     batch / flamenco  tests/bench/bench_batch.py --write, flamenco_overhead.py: batch.md,
              flamenco.md, copied in the same way
  9. ivy large   build/tests/bench_ivy --large: per-bud tables of the 12 m and 24 m walls
 10. avenue      build/banyan avenue (1,000 trees) under /usr/bin/time -v: generate,
                 write, peak RSS
 11. waits       tests/bench/bench_*.py (WAITS): what a CLI user waits for
Sections 9 and 10 say "not built" and are skipped when their program or
flag is missing. The speed targets come first, as verdict lines; end to
end there includes Blender's first evaluation of the new objects on both
sides, and the hand-off is judged against a floor given the same edges
(blender_handoff.bare_edges); the old columns stay beside the new ones.

Every time is the median of RUNS runs with min and max; banyan and the
peer alternate within each run so both see the same machine load. Writes
docs/benchmarks.md (rewritten each time). Not run by CI.

Run: tests/bench/peers/run.sh [build_dir] [runs]   (sets BANYAN_LIB and
BLENDER_USER_SCRIPTS, builds bench_tube, then runs
  blender -b --factory-startup --python tests/bench/peers/peers.py -- runs)
"""
import contextlib
import ctypes
import datetime
import io
import json
import math
import os
import platform
import re
import statistics
import subprocess
import sys
import time
import types

import addon_utils
import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
SRC = os.path.normpath(os.path.join(HERE, "..", "..", ".."))
ARGS = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
RUNS = max(5, int(ARGS[0])) if ARGS else 5
BUILD = os.environ.get("BANYAN_BUILD_DIR") or os.path.dirname(os.environ.get("BANYAN_LIB", SRC + "/build/x"))
OUT = os.environ.get("BANYAN_BENCH_OUT", os.path.join(SRC, "docs", "benchmarks.md"))

for mod in ("banyan", "add_curve_ivygen", "add_curve_sapling"):
    if not addon_utils.enable(mod, default_set=True):
        sys.exit("peers.py: cannot enable the add-on %s" % mod)

sys.path.insert(0, os.path.dirname(HERE))
import blender_handoff as HO  # noqa: E402  bare() and clear_generated()
from machine_info import machine  # noqa: E402
from banyan import api as B  # noqa: E402
from banyan.engine import hosts as H  # noqa: E402
from banyan.core import generators as G  # noqa: E402
from banyan.core import lib as LIB  # noqa: E402
from banyan.core import structs as S  # noqa: E402

WALL_CURSOR = (0.0, 0.0, 0.05)  # the ivy_wall preset's start: bottom centre of the wall face
LEAF_CARD_TRIS = {"ivy": 12, "keyaki": 2}  # csrc/ivy/mesh.c LEAF_OUTLINE; keyaki's quads
SAPLING_LEAF_VERTS = 6  # 'hex' leaves (utils.py leafVertSize)
CHEAP_REPEAT = 3  # banyan's millisecond cases (roots, keyaki) take 3x the runs: their medians are noisier


# ------------------------------------------------------------------ helpers
class Series:
    """Times of one measured thing; med/min/max in seconds."""

    def __init__(self):
        self.t = []

    def time(self, fn, *a, **kw):
        t0 = time.perf_counter()
        r = fn(*a, **kw)
        self.t.append(time.perf_counter() - t0)
        return r

    @property
    def med(self):
        return statistics.median(self.t)

    def fmt(self, scale=1.0, unit="s", digits=3):
        return "%.*f %s [%.*f .. %.*f]" % (digits, self.med * scale, unit, digits, min(self.t) * scale,
                                           digits, max(self.t) * scale)


def quiet(fn, *a, **kw):
    """Runs fn with the peers' progress prints swallowed."""
    with contextlib.redirect_stdout(io.StringIO()):
        return fn(*a, **kw)


def keep_names():
    return {o.name for o in bpy.data.objects}


def select_only(obj):
    for o in bpy.context.view_layer.objects:
        o.select_set(False)
    obj.select_set(True)
    bpy.context.view_layer.objects.active = obj


def convert_to_mesh(obj):
    """What a user does to get a mesh from the peers' curves."""
    select_only(obj)
    r = bpy.ops.object.convert(target='MESH')
    assert r == {'FINISHED'}, r


def mesh_counts(objs):
    """(vertices, triangles) of mesh objects."""
    v = t = 0
    for o in objs:
        me = o.data
        me.calc_loop_triangles()
        v += len(me.vertices)
        t += len(me.loop_triangles)
    return v, t


def curve_length(cu):
    return sum(s.calc_length() for s in cu.splines)


KEYAKI_SKEL_TWIG = 1 << 17  # keyaki_internal.h: crown twig and segment line points of the skeleton


def skeleton_length(d, skip_tag=0):
    """Total branch / stem length: the sum of the skeleton's edge lengths
    (edges with an end whose skel_tag has a skip_tag bit left out)."""
    p, e, tag = d.skel_points, d.skel_edges, d.skel_tag
    return sum(math.dist(p[3 * e[k]:3 * e[k] + 3], p[3 * e[k + 1]:3 * e[k + 1] + 3]) for k in range(0, len(e), 2)
               if not skip_tag or not ((tag[e[k]] | tag[e[k + 1]]) & skip_tag))


def part_tris(d, material):
    return sum(p["index_count"] for p in d.parts if p["material"] == material) // 3


def new_objects(keep):
    return [o for o in bpy.data.objects if o.name not in keep]


def wall():
    """The default cube as the CLI's default wall: 3 x 0.2 x 3 m, face at y = 0."""
    cube = bpy.data.objects["Cube"]
    cube.location = (0.0, 0.1, 1.5)
    cube.scale = (1.5, 0.1, 1.5)
    bpy.context.view_layer.update()
    return cube


# -------------------------------------------------------------------- peers
class PeerRun:
    """One peer configuration: operator time, conversion time, figures.
    e2e = operator + convert (the old column); e2e_ev adds first_eval, the
    same first evaluation banyan's e2e_ev adds (the operators' closing
    view-layer updates have already evaluated the new objects, so it is
    small here)."""

    def __init__(self, label, note):
        self.label, self.note = label, note
        self.op, self.conv, self.e2e = Series(), Series(), Series()
        self.first_ev, self.e2e_ev = Series(), Series()
        self.stem = self.leaves = self.verts = self.tris = 0

    def evaluate(self, keep):
        """Times the first evaluation of what the run made; closes e2e and e2e_ev."""
        self.first_ev.time(HO.first_evaluation, new_objects(keep))
        self.e2e.t.append(self.op.t[-1] + self.conv.t[-1])
        self.e2e_ev.t.append(self.e2e.t[-1] + self.first_ev.t[-1])


def ivygen_once(run, host, max_length, cursor=WALL_CURSOR, inspect=None):
    """IvyGen's operator on host from the cursor, then its curve to a mesh.
    inspect(curve, leaf): called on IvyGen's objects before the conversion."""
    keep = keep_names()
    props = bpy.context.window_manager.ivy_gen_props
    props.maxIvyLength = max_length
    bpy.context.scene.cursor.location = cursor
    select_only(host)
    run.op.time(quiet, bpy.ops.curve.ivy_gen, updateIvy=True)
    curve = bpy.data.objects["IVY_Curve"]
    leaf = bpy.data.objects.get("IvyLeaf")
    run.stem = curve_length(curve.data)
    if inspect:
        inspect(curve, leaf)
    run.conv.time(convert_to_mesh, curve)
    run.evaluate(keep)
    run.leaves = len(leaf.data.polygons) if leaf else 0
    run.verts, run.tris = mesh_counts(new_objects(keep))
    HO.clear_generated(keep)


def sapling_once(run, kw):
    keep = keep_names()
    run.op.time(quiet, bpy.ops.curve.tree_add, **kw)
    made = new_objects(keep)
    tree = next(o for o in made if o.type == 'CURVE')
    run.stem = curve_length(tree.data)
    run.conv.time(convert_to_mesh, tree)
    run.evaluate(keep)
    leaf = next((o for o in made if o.name.startswith("leaves")), None)
    run.leaves = len(leaf.data.vertices) // SAPLING_LEAF_VERTS if leaf else 0
    run.verts, run.tris = mesh_counts(new_objects(keep))
    HO.clear_generated(keep)


def match_ivygen(target, key, host, probes=7, tol=0.03, cursor=WALL_CURSOR):
    """IvyGen's maxIvyLength whose `key` figure (stem or tris) is closest to
    target. The figure grows monotonically with maxIvyLength (the same
    seeded growth, stopped later); secant steps in log-log."""
    seen = []

    def probe(x):
        r = PeerRun("probe", "")
        ivygen_once(r, host, x, cursor)
        seen.append((x, getattr(r, key)))

    probe(3.0)
    probe(5.0)
    while len(seen) < probes:
        seen.sort(key=lambda s: abs(math.log(s[1] / target)))
        (xa, va), (xb, vb) = seen[0], seen[1]
        if abs(va / target - 1) < tol or va == vb or xa == xb:
            break
        k = math.log(va / vb) / math.log(xa / xb)
        probe(min(12.0, max(0.5, xa * (target / va) ** (1.0 / k))))
    x, v = min(seen, key=lambda s: abs(math.log(s[1] / target)))
    return round(x, 3), v


# ------------------------------------------------------------------- banyan
class BanyanRun:
    """banyan's library call, growth (ivy), end to end via banyan.api, and
    Blender's bare hand-off of the same arrays. e2e is the api call alone
    (the old column); e2e_ev adds the first evaluation of its objects
    (blender_handoff.first_evaluation), timed right after it in the same
    run. bare_edges: the same-edges floor, first evaluation included."""

    def __init__(self, label):
        self.label = label
        self.lib, self.grow, self.e2e, self.bare, self.bare_full = Series(), Series(), Series(), Series(), Series()
        self.copy = Series()  # the binding's call with its copy-out into Python arrays
        self.first_ev, self.e2e_ev, self.bare_edges = Series(), Series(), Series()
        self.d = None
        self.topo = None  # the edges handed to the bare_edges floor (computed once, off its clock)
        self.floor_diff = None  # blender_handoff.floor_differences after the first run
        self.stem = self.leaves = 0

    def once(self, lib_call, api_call, grow_call=None):
        keep = keep_names()
        if grow_call:
            self.grow.time(grow_call)
        self.lib.time(native, lib_call)
        self.d = self.copy.time(lib_call)
        if self.topo is None:
            self.topo = HO.triangle_topology(self.d)
        self.bare.t.append(HO.bare(self.d))
        self.bare_full.t.append(HO.bare(self.d, full=True))
        self.bare_edges.t.append(HO.bare_edges(self.d, self.topo))
        self.e2e.time(api_call)
        self.first_ev.time(HO.first_evaluation, new_objects(keep))
        self.e2e_ev.t.append(self.e2e.t[-1] + self.first_ev.t[-1])
        if self.floor_diff is None:  # once: does the floor hand Blender what the add-on does?
            self.floor_diff = HO.floor_differences(self.d, self.topo, new_objects(keep))
            for line in self.floor_diff:
                print("peers.py: WARNING %s: the same-edges floor differs from the add-on's mesh: %s" % (
                    self.label, line), flush=True)
        HO.clear_generated(keep)

    @property
    def verts(self):
        return self.d.vertex_count

    @property
    def tris(self):
        return self.d.triangle_count

    def handoff(self, full=True):
        return (self.e2e.med - self.lib.med) / (self.bare_full if full else self.bare).med

    def handoff_edges(self):
        """The hand-off: (end to end with first evaluation - library)
        over the same-edges floor with its first evaluation."""
        return (self.e2e_ev.med - self.lib.med) / self.bare_edges.med

    def e2e_over_floor(self):
        """End to end with first evaluation over library + the same-edges floor."""
        return self.e2e_ev.med / (self.lib.med + self.bare_edges.med)


def _generate_and_free(func, *args):
    out = ctypes.POINTER(S.Mesh)()
    err = S.Error()
    st = func(*args, ctypes.byref(out), ctypes.byref(err))
    if st:
        LIB.raise_for(st, err)
    LIB.load().banyan_mesh_free(out)
    return types.SimpleNamespace()  # stands for the MeshData (generators.ivy sets .stats on it)


def native(call):
    """The library alone: `call`'s generate function through ctypes, then
    banyan_mesh_free, with no copy-out into Python arrays (the add-on's
    hand-off does that, and is timed with it)."""
    saved = G.call_generate
    G.call_generate = _generate_and_free
    try:
        call()
    finally:
        G.call_generate = saved


def ivy_grow(p, boxes):
    plant = G.IvyPlant(p, boxes)
    plant.step(p.get("steps"))
    plant.close()


# ----------------------------------------------------------------- sections
def section_ivy():
    bpy.ops.wm.read_homefile(use_factory_startup=True)
    host = wall()
    boxes = H.boxes_from_objects([host])
    p = B.make_params("ivy", preset="ivy_wall")
    ban = BanyanRun("banyan ivy_wall (%d steps)" % p.get("steps"))
    ban.once(lambda: G.ivy(p, boxes), lambda: B.ivy(hosts=[host], preset="ivy_wall", host_shape='BOX'), lambda: ivy_grow(p, boxes))
    ban.stem = skeleton_length(ban.d)
    ban.leaves = part_tris(ban.d, 1) // LEAF_CARD_TRIS["ivy"]
    x_stem, _ = match_ivygen(ban.stem, "stem", host)
    x_tris, _ = match_ivygen(ban.tris, "tris", host)
    peers = [(PeerRun("IvyGen defaults", "maxIvyLength 1.0"), 1.0),
             (PeerRun("IvyGen, stem length matched", "maxIvyLength %.3g" % x_stem), x_stem),
             (PeerRun("IvyGen, triangles matched", "maxIvyLength %.3g" % x_tris), x_tris)]
    for r in range(RUNS):
        if r:
            ban.once(lambda: G.ivy(p, boxes), lambda: B.ivy(hosts=[host], preset="ivy_wall", host_shape='BOX'),
                     lambda: ivy_grow(p, boxes))
        for run, x in peers:
            ivygen_once(run, host, x)
        print("ivy run %d/%d done" % (r + 1, RUNS), flush=True)
    return ban, [r for r, _ in peers]


def section_tree():
    bpy.ops.wm.read_homefile(use_factory_startup=True)
    p = B.make_params("keyaki", preset="keyaki_mature")
    ban = BanyanRun("banyan keyaki_mature")
    configs = [(PeerRun("Sapling default tree", "operator defaults (levels 3, no leaves) + bevel"),
                dict(bevel=True)),
               (PeerRun("Sapling default tree, leaves", "defaults + bevel, leaves (25, hex)"),
                dict(bevel=True, showLeaves=True)),
               (PeerRun("Sapling levels 4, leaves", "defaults + bevel, levels 4, leaves (25, hex)"),
                dict(bevel=True, levels=4, showLeaves=True))]
    for r in range(RUNS):
        for _ in range(CHEAP_REPEAT):
            ban.once(lambda: G.keyaki(p), lambda: B.keyaki_tree(preset="keyaki_mature"))
        for run, kw in configs:
            sapling_once(run, kw)
    ban.stem = skeleton_length(ban.d, KEYAKI_SKEL_TWIG)  # the branches, as before twigs joined the skeleton
    ban.leaves = part_tris(ban.d, 1) // LEAF_CARD_TRIS["keyaki"]
    leaf_verts = sum(p["vertex_count"] for p in ban.d.parts if p["material"] == 1)
    if leaf_verts != 4 * ban.leaves:  # the count above assumes one quad a leaf (~30,000 of them)
        print("peers.py: WARNING keyaki leaves are not one quad each (%d leaf vertices for %d leaves); "
              "the leaves column is wrong: update LEAF_CARD_TRIS" % (leaf_verts, ban.leaves), flush=True)
    return ban, [r for r, _ in configs]


def section_roots():
    out = []
    for label, preset in (("banyan roots default (default cube)", None), ("banyan roots_trunk preset", "roots_trunk")):
        bpy.ops.wm.read_homefile(use_factory_startup=True)
        cube = bpy.data.objects["Cube"]
        if preset:
            from banyan.core import presets as PR
            from banyan.core.params import preset_hosts
            path = PR.find("roots", preset)
            boxes = preset_hosts(PR.read(path), path)
            p = B.make_params("roots", preset=preset)
            api = lambda: B.strangler_roots(preset=preset)  # noqa: E731  the preset's hosts
        else:
            boxes = H.boxes_from_objects([cube])
            p = B.make_params("roots")
            # The ground at z = 0 as in the library call (the add-on would put it at the cube's foot).
            api = lambda: B.strangler_roots(hosts=[cube], host_shape='BOX', ground_at_hosts=False)  # noqa: E731
        ban = BanyanRun(label)
        for _ in range(RUNS * CHEAP_REPEAT):
            ban.once(lambda: G.roots(p, boxes), api)
        out.append(ban)
    return out


def section_memory():
    exe = os.path.join(BUILD, "tests", "bench_tube")
    res = subprocess.run([exe, str(RUNS)], capture_output=True, text=True, check=True)
    line = next(l for l in res.stdout.splitlines() if l.startswith("JSON "))
    return json.loads(line[5:]), res.stdout


def first_plant(runs):
    """The first keyaki_mature in a .blend (its two shared materials made:
    textures drawn, PNG encoded, packed and decoded by Blender) against the
    next ones (materials reused), end to end through banyan.api."""
    first, later = [], []
    for _ in range(runs):
        keep = keep_names()
        for m in list(bpy.data.materials):
            if m.name.startswith("Banyan ") and m.users == 0:
                bpy.data.materials.remove(m)
        for im in list(bpy.data.images):
            if im.name.startswith("Banyan ") and im.users == 0:
                bpy.data.images.remove(im)
        for bucket in (first, later):
            t = time.perf_counter()
            B.keyaki_tree(preset="keyaki_mature")
            bucket.append(time.perf_counter() - t)
            HO.clear_generated(keep)
    return statistics.median(first), statistics.median(later)


def section_textures():
    """bench_textures' output (the library's textures at 1024, one
    thread), and what the first plant of a kind pays in Blender."""
    exe = os.path.join(BUILD, "tests", "bench_textures")
    res = subprocess.run([exe, "1024", str(RUNS)], capture_output=True, text=True, check=True)
    return res.stdout, first_plant(max(3, RUNS // 2))


def section_roots_c():
    """bench_roots' output (fused surface and tubes, one thread)."""
    exe = os.path.join(BUILD, "tests", "bench_roots")
    out = subprocess.run([exe], capture_output=True, text=True, check=True).stdout
    print(out, flush=True)
    return out


def roots_c_figures(out):
    """(fused ms, fused peak MB, tubes n = 16 reused ms, tubes defaults reused ms) from bench_roots."""
    def find(pattern):
        m = re.search(pattern, out)
        return float(m.group(1)) if m else float("nan")
    return (find(r"fused surface.*\n(?:.*\n)*?\s+median per net:\s+([0-9.]+) ms"),
            find(r"memory peak of a call:\s+([0-9.]+) MB"),
            find(r"median per net, reused:\s+([0-9.]+) ms"),
            find(r"median per net:\s+[0-9.]+ ms fresh, ([0-9.]+) ms reused"))


def section_hosts():
    """The C host benchmarks' output, and ivy on Suzanne against
    IvyGen (ivy_suzanne.py)."""
    outs = {}
    for name, args in (("bench_hosts", ["3"]), ("bench_roots_hosts", []), ("bench_ivy", ["3"])):
        exe = os.path.join(BUILD, "tests", name)
        outs[name] = subprocess.run([exe] + args, capture_output=True, text=True, check=True).stdout
        print(outs[name], flush=True)
    sys.path.insert(0, HERE)
    import ivy_suzanne
    lines, ratio = ivy_suzanne.section(RUNS)
    return outs, lines, ratio


def hosts_figures(outs):
    """(1M build s, roots mesh/box, ivy mesh/box CPU) parsed from the benchmarks' lines."""
    def find(text, pattern):
        m = re.search(pattern, text)
        return float(m.group(1)) if m else float("nan")
    return (find(outs["bench_hosts"], r"1000000 triangles.*median ([0-9.]+) s"),
            find(outs["bench_roots_hosts"], r"mesh / box: +([0-9.]+)x per call"),
            find(outs["bench_ivy"], r"mesh / box: [0-9.]+x wall, ([0-9.]+)x CPU"))


# ------------------------------------------- C figures from other programs
IVY_LARGE_ROW = re.compile(r"^\s*(\d+)\s+(\d+)\s+([0-9.]+)\s+([0-9.]+)\s+([0-9.]+)\s+([0-9.]+)\s+([0-9.]+)\s*$")
# The 1,000-tree avenue at tree.levels=8: ~9.4k triangles a tree, 12 M in
# all (the default tree has ~180k: 1,000 of them would be 27 GB). BANYAN_BENCH_AVENUE_SET adds --set
# KEY=VALUE pairs (space-separated) when a workload must be changed by hand.
AVENUE_1000 = ["avenue", "--set", "placement=count", "--set", "count=500", "--set", "max_vertices=100000000",
               "--set", "tree.levels=8", "--threads", "2", "--stats"]
for _kv in os.environ.get("BANYAN_BENCH_AVENUE_SET", "").split():
    AVENUE_1000 += ["--set", _kv]


def section_ivy_large(wall="ivy_wall_large"):
    """`build/tests/bench_ivy --large 0 WALL`,
    the per-bud table of the 12 m x 12 m wall (presets/ivy_wall_large),
    or of the 24 m one that reaches 600,000 buds (tests/bench/ivy_wall_24m).
    Returns {"text", "rows"} or
    {"skip": reason} when the program or its --large mode is not built,
    or it fails. rows: (buds, step, wall s, CPU s, us/bud cumulative,
    us/bud marginal, CPU us/bud marginal), parsed from the table."""
    exe = os.path.join(BUILD, "tests", "bench_ivy")
    if not os.path.exists(exe):
        return {"skip": "not built: %s does not exist" % exe}
    with open(exe, "rb") as f:
        if b"--large" not in f.read():
            return {"skip": "not built: this build's `bench_ivy` has no `--large` mode"}
    try:
        res = subprocess.run([exe, "--large", "0", wall], capture_output=True, text=True, timeout=3600)
    except subprocess.TimeoutExpired:
        return {"skip": "failed: `bench_ivy --large` ran past an hour"}
    if res.returncode:
        return {"skip": "failed: `bench_ivy --large` exited with %d (%s)" % (
            res.returncode, (res.stderr.strip().splitlines() or ["no message"])[-1])}
    rows = [tuple(float(x) for x in m.groups()) for m in map(IVY_LARGE_ROW.match, res.stdout.splitlines()) if m]
    print(res.stdout, flush=True)
    return {"text": res.stdout, "rows": rows}


def _time_v(stderr, label):
    m = re.search(r"^\s*%s:\s*(\S+)\s*$" % re.escape(label), stderr, re.M)
    return m.group(1) if m else None


def _clock(text):
    """/usr/bin/time's "h:mm:ss" or "m:ss.ss" as seconds."""
    out = 0.0
    for part in text.split(":"):
        out = out * 60 + float(part)
    return out


def section_avenue_write(runs=3):
    """The 1,000-tree avenue
    (`banyan avenue --set placement=count --set count=500 --set
    max_vertices=100000000 --set tree.levels=8 --threads 2 --stats -o X.glb`) under
    `/usr/bin/time -v`, `runs` times. Returns {"runs": [...]} or
    {"skip": reason}. Each run: generate and write s (the CLI's --stats
    time_ms), wall, user and system s, peak RSS and file bytes."""
    exe = os.path.join(BUILD, "banyan")
    if not os.path.exists(exe):
        return {"skip": "not built: %s does not exist" % exe}
    if not os.path.exists("/usr/bin/time"):
        return {"skip": "not measured: /usr/bin/time is missing (Debian package `time`)"}
    import tempfile
    out = []
    for _ in range(runs):
        # Each run starts with nothing left to write back (the last run's
        # 1.4 GB and its deletion), as a user's one write does.
        os.sync()
        time.sleep(2)
        with tempfile.TemporaryDirectory(prefix="banyan_bench_") as tmp:
            glb = os.path.join(tmp, "avenue_1000.glb")
            try:
                res = subprocess.run(["/usr/bin/time", "-v", exe] + AVENUE_1000 + ["-o", glb], capture_output=True,
                                     text=True, timeout=1800)
            except subprocess.TimeoutExpired:
                return {"skip": "failed: the 1,000-tree avenue ran past 30 min"}
            if res.returncode or not os.path.exists(glb):
                said = [l.strip() for l in (res.stdout + res.stderr).splitlines()
                        if l.startswith("banyan") and not l.startswith("\t")]
                return {"skip": "failed: the CLI exited with %d: %s" % (res.returncode, (said or ["no message"])[0])}
            stats = None
            for line in reversed(res.stdout.splitlines()):
                if line.startswith("{"):
                    with contextlib.suppress(ValueError):
                        stats = json.loads(line)
                        break
            tm = (stats or {}).get("time_ms") or {}
            rss = _time_v(res.stderr, "Maximum resident set size (kbytes)")
            wall = _time_v(res.stderr, "Elapsed (wall clock) time (h:mm:ss or m:ss)")
            r = {"generate": tm.get("generate", float("nan")) / 1e3, "write": tm.get("write", float("nan")) / 1e3,
                 "wall": _clock(wall) if wall else float("nan"),
                 "user": float(_time_v(res.stderr, "User time (seconds)") or "nan"),
                 "sys": float(_time_v(res.stderr, "System time (seconds)") or "nan"),
                 "rss": 1024.0 * float(rss) if rss else float("nan"), "bytes": os.path.getsize(glb),
                 "triangles": (stats or {}).get("triangles"), "trees": (stats or {}).get("trees")}
            out.append(r)
            print("avenue 1,000 trees: %s" % r, flush=True)
    return {"runs": out}


def avenue_medians(av):
    return {k: statistics.median(r[k] for r in av["runs"]) for k in ("generate", "write", "wall", "user", "sys",
                                                                      "rss", "bytes")}


def ivy_large_flatness(rows):
    """(max / min of the CPU us per bud between checkpoints, max / min of
    the cumulative us per bud, buds of the last row) of the large wall's
    table, or None when it has fewer than two rows."""
    if len(rows) < 2:
        return None
    marg = [r[6] for r in rows]
    cum = [r[4] for r in rows]
    return max(marg) / min(marg), max(cum) / min(cum), int(rows[-1][0])


# ------------------------------------------------------------------- report
# What a user waits for: each script under tests/bench/ times one wait with
# alternating runs of the CLI and prints markdown rows
# `| figure | value | target | verdict |`, copied in as they are.
WAITS = (("Levels of detail", "bench_lod_wait.py"), ("Textured writes", "bench_texture_write.py"),
         ("Start-up", "bench_startup.py"), ("Compact glTF", "bench_compact.py"),
         ("Avenue on two threads", "bench_avenue_threads.py"))


def section_waits():
    out = []
    for title, script in WAITS:
        path = os.path.join(SRC, "tests", "bench", script)
        if not os.path.isfile(path):
            continue
        res = subprocess.run(["python3", path, "--build", BUILD, "--runs", str(max(RUNS, 5))], capture_output=True,
                             text=True)
        text = res.stdout.strip() if res.returncode == 0 else "failed (exit %d): %s" % (
            res.returncode, (res.stderr or res.stdout).strip()[-400:])
        out.append((title, script, text))
        print("waits: %s done" % script, flush=True)
    return out


def waits_lines(waits, ban_i, peers_i, run_model):
    L = ["## What users wait for", "",
         "Measured in this run (%s) by the scripts named, each with alternating runs of the CLI; the load they "
         "name is the machine's as they ran." % run_model, ""]
    ig = peers_i[1]
    rg = (ban_i.stem / ban_i.grow.med) / (ig.stem / ig.op.med)
    L += ["### Ivy growth (section 1)", "", "| figure | value | target | verdict |", "|---|---|---|---|",
          "| ivy_wall growth per metre of stem against IvyGen's operator, stem-matched | %.1fx (%.0f m/s against "
          "%.0f m/s) | >= 25x | **%s** |" % (rg, ban_i.stem / ban_i.grow.med, ig.stem / ig.op.med,
                                             "met" if rg >= 25 else "not met"), ""]
    for title, script, text in waits:
        L += ["### %s (`tests/bench/%s`)" % (title, script), "", text, ""]
    return L


def git_rev():
    """HEAD, with "+changes" when tracked files other than OUT differ from it."""
    def git(*a):
        return subprocess.run(["git", "-C", SRC] + list(a), capture_output=True, text=True, check=True).stdout
    try:
        out = os.path.relpath(OUT, SRC)
        changed = [l for l in git("status", "--porcelain", "--untracked-files=no").splitlines() if l[3:] != out]
        return git("rev-parse", "--short", "HEAD").strip() + (" +changes" if changed else "")
    except (OSError, subprocess.CalledProcessError):
        return "?"


def mtris(n, s):
    return n / s / 1e6


def e2e_ratio(ban, peer, first_eval=True):
    """banyan / peer triangles per second end to end, with or
    without the first evaluation on both sides."""
    if first_eval:
        return (ban.tris / ban.e2e_ev.med) / (peer.tris / peer.e2e_ev.med)
    return (ban.tris / ban.e2e.med) / (peer.tris / peer.e2e.med)


def stem_rate_mesh(ban, peer):
    """banyan / peer metres of stem per second: banyan's library + mesh
    (the binding's generate call with its copy-out) against the peer's
    whole operator."""
    return (ban.stem / ban.copy.med) / (peer.stem / peer.op.med)


def at_floor(ban, peer):
    """The end-to-end tris/s ratio if banyan's end to end took exactly the bare floor."""
    return (ban.tris / ban.bare.med) / (peer.tris / peer.e2e.med)


def verdict(ok):
    return "**met**" if ok else "**missed**"


def verdict23(ok):
    return "**met**" if ok else "**not met**"


def memory_total():
    with contextlib.suppress(OSError, ValueError, IndexError):
        with open("/proc/meminfo") as f:
            for line in f:
                if line.startswith("MemTotal:"):
                    return int(line.split()[1]) / 1024 / 1024
    return float("nan")


def kept_section(name, run_model):
    """A section measured by hand (tests/bench/peers/<name>), copied in. It
    must say its own machine (a "Machine:" line); a missing one is said."""
    path = os.path.join(HERE, name)
    if not os.path.exists(path):
        return []
    with open(path) as f:
        text = f.read().rstrip()
    lines = text.splitlines()
    if "Machine:" not in text:
        lines.insert(1, "")
        lines.insert(2, "*Machine not stated in `tests/bench/peers/%s`: not measured in this run (%s); its "
                        "figures compare with each other only.*" % (name, run_model))
    return lines + [""]


def targets23(ban_i, peers_i, ban_t, peers_t, mem, ivy_large, avenue):
    """The speed targets, one verdict line each."""
    L = []
    w = L.append
    ig_stem, ig_tris = peers_i[1], peers_i[2]
    w("## Targets (issue 23)")
    w("")
    w("Measured in this run (section numbers below); *e2e+ev*: end to end with Blender's first evaluation of "
      "the new objects on both sides; *edges*: the same-edges floor (see Terms). The old figures (without the "
      "first evaluation, against *bare+*) stay in their sections.")
    w("")
    w("| target | figure | verdict |")
    w("|---|---|---|")
    r_new, r_old = e2e_ratio(ban_i, ig_stem), e2e_ratio(ban_i, ig_stem, False)
    w("| ivy e2e+ev >= 5x IvyGen tris/s at matched stem length (section 1) | %.1fx (without the first evaluation "
      "%.1fx; against the triangle-matched IvyGen %.1fx) | %s |" % (
          r_new, r_old, e2e_ratio(ban_i, ig_tris), verdict23(r_new >= 5)))
    for r in peers_t:
        if not r.leaves:
            continue
        re_new, re_old = e2e_ratio(ban_t, r), e2e_ratio(ban_t, r, False)
        w("| keyaki e2e+ev >= 10x Sapling tris/s with leaves (%s; section 2) | %.1fx (without the first "
          "evaluation %.1fx) | %s |" % (r.label, re_new, re_old, verdict23(re_new >= 10)))
    rm, rg = stem_rate_mesh(ban_i, ig_stem), (ban_i.stem / ban_i.grow.med) / (ig_stem.stem / ig_stem.op.med)
    w("| ivy library (growth + mesh + copy-out) >= 40x IvyGen's operator per metre of stem, stem-matched "
      "(section 1) | %.0fx (growth alone %.0fx) | %s |" % (rm, rg, verdict23(rm >= 40)))
    h = ban_t.handoff_edges()
    w("| keyaki e2e+ev within 1.3x the same-edges floor: (e2e+ev - library) / edges (section 3) | %.2f "
      "(e2e+ev / (library + edges) %.2f; old hand-off against bare+ %.2f) | %s |" % (
          h, ban_t.e2e_over_floor(), ban_t.handoff(), verdict23(h <= 1.3)))
    for key, what in (("12m", "the 12 m x 12 m wall (covered before 600k buds)"),
                      ("24m", "the 24 m x 24 m wall")):
        big = ivy_large.get(key, {"skip": "not run"})
        flat = ivy_large_flatness(big.get("rows", []))
        head = "| ivy on %s: cost per bud flat within 1.5x from 50k to 600k buds (section 9) |" % what
        if "skip" in big:
            w("%s %s | not measured |" % (head, big["skip"]))
        elif flat is None:
            w("%s table not parsed (output copied in section 9) | not judged |" % head)
        else:
            ok = flat[0] <= 1.5 and flat[2] >= 600000
            w("%s CPU us per bud between checkpoints: max / min %.2f (cumulative %.2f), up to %d buds | %s |" % (
                head, flat[0], flat[1], flat[2], verdict23(ok) if key == "24m" else
                "reference (%s)" % ("flat to where the wall is covered" if flat[0] <= 1.5 else "not flat")))
    if "skip" in avenue:
        w("| 1,000-tree avenue: peak RSS <= 1.3x the file, write <= generate (section 10) | %s | not measured |"
          % avenue["skip"])
    else:
        m = avenue_medians(avenue)
        w("| 1,000-tree avenue: CLI peak RSS <= 1.3x the .glb (section 10) | %.0f MB for %.0f MB: %.2fx | %s |" % (
            m["rss"] / 1e6, m["bytes"] / 1e6, m["rss"] / m["bytes"], verdict23(m["rss"] <= 1.3 * m["bytes"])))
        w("| 1,000-tree avenue: write time <= generate time (section 10) | write %.2f s, generate %.2f s | %s |" % (
            m["write"], m["generate"], verdict23(m["write"] <= m["generate"])))
    for c in mem["cases"]:
        if c["how"] != "api":
            continue
        f = c["triangles"] / c["seconds"][0] / c["bound_tris_per_s"]
        w("| one-shot generate call writes >= 25%% of the store-loop bound (tube sweeper, %s, api; section 4) | "
          "%.1f%% | %s |" % (c["workload"], 100 * f, verdict23(f >= 0.25)))
    w("")
    return L


def ivy_large_lines(ivy_large, run_model):
    L = ["## 9. Ivy at scale: the 12 m x 12 m and 24 m x 24 m walls (issue 23)", ""]
    L += ["`build/tests/bench_ivy --large 0 WALL` (tests/bench/bench_ivy.c), each wall run once in this run (%s): "
          "growth alone, one step a call, timed at the bud-count checkpoints. Target: cost per bud flat within "
          "1.5x from 50k to 600k buds (judged on CPU microseconds per bud between checkpoints, which other jobs on "
          "the machine disturb less than wall time). The issue's wall, `presets/ivy_wall_large.json` (12 m x 12 m, "
          "1,800 steps), is covered on both faces at about 250,000 buds, at the density of the 3 m wall (the "
          "issue's 621,000 buds came from an earlier, denser ivy); `tests/bench/ivy_wall_24m.json`, the same "
          "settings on a 24 m x 24 m wall for 3,600 steps, carries the table to 600,000 buds before that wall is covered (a 20 m wall nears cover there and its last buds cost more, as the 12 m one does)." % run_model, ""]
    for key, wall in (("12m", "ivy_wall_large"), ("24m", "ivy_wall_24m")):
        big = ivy_large.get(key, {"skip": "not run"})
        if "skip" in big:
            L += ["`%s`: %s." % (wall, big["skip"]), ""]
        else:
            L += ["```", big["text"].strip(), "```", ""]
    return L


def avenue_lines(avenue, run_model):
    L = ["## 10. The 1,000-tree avenue: generate, write, peak memory (issue 23)", ""]
    cmd = "banyan " + " ".join(AVENUE_1000) + " -o X.glb"
    if "skip" in avenue:
        L += ["`%s`: %s; this section is skipped." % (cmd, avenue["skip"]), ""]
        return L
    L += ["`/usr/bin/time -v build/%s` (%s), %d runs in this run; generate and write from the CLI's `--stats` "
          "(`time_ms`), peak RSS from `time -v` (Maximum resident set size). Targets: peak RSS at most 1.3x the "
          "file, write at most generate." % (cmd, run_model, len(avenue["runs"])), "",
          "| run | trees | triangles | generate s | write s | wall s | user s | system s | peak RSS MB | .glb MB | "
          "RSS / file |", "|---|---|---|---|---|---|---|---|---|---|---|"]
    for k, r in enumerate(avenue["runs"]):
        L.append("| %d | %s | %s | %.2f | %.2f | %.2f | %.2f | %.2f | %.0f | %.0f | %.2f |" % (
            k + 1, r["trees"], r["triangles"], r["generate"], r["write"], r["wall"], r["user"], r["sys"],
            r["rss"] / 1e6, r["bytes"] / 1e6, r["rss"] / r["bytes"]))
    m = avenue_medians(avenue)
    L.append("| median | | | %.2f | %.2f | %.2f | %.2f | %.2f | %.0f | %.0f | %.2f |" % (
        m["generate"], m["write"], m["wall"], m["user"], m["sys"], m["rss"] / 1e6, m["bytes"] / 1e6,
        m["rss"] / m["bytes"]))
    L.append("")
    return L


def report(ivy, tree, roots, mem, mem_text, hosts, load0, load1, elapsed, textures=("", (0.0, 0.0)), roots_c="",
           ivy_large=None, avenue=None, started=None, waits=None):
    ban_i, peers_i = ivy
    ban_t, peers_t = tree
    model, cores = machine()
    ivy_large = ivy_large or {"skip": "not run"}
    avenue = avenue or {"skip": "not run"}
    started = started or datetime.datetime.now(datetime.timezone.utc)
    run_model = "%s, %d logical cores, %s" % (model, cores, started.strftime("%Y-%m-%d"))
    L = []
    w = L.append
    w("# Benchmarks against the peers (issue 9)")
    w("")
    w("Written by `tests/bench/peers/peers.py` (rewritten on each run). banyan against the add-ons that ship "
      "with Blender: IvyGen (`add_curve_ivygen`) and Sapling Tree Gen (`add_curve_sapling`), in one Blender "
      "process; ratios are taken within this run (absolute times on this shared machine are noise). Every "
      "time is the median of %d runs, [min .. max] (%d for banyan's roots and keyaki, which take milliseconds); "
      "banyan and the peer alternate within each run." % (RUNS, RUNS * CHEAP_REPEAT))
    w("")
    w("## Run")
    w("")
    w("- Command: `tests/bench/peers/run.sh build %d`, which builds `libbanyan.so` and `bench_tube`, links "
      "the add-on into a temporary `BLENDER_USER_SCRIPTS` (as `tests/blender/run.sh` does), sets "
      "`BANYAN_LIB=build/libbanyan.so` and runs `blender -b --factory-startup --python "
      "tests/bench/peers/peers.py -- %d`." % (RUNS, RUNS))
    w("- Blender %s, Python %s; banyan %s." % (bpy.app.version_string, platform.python_version(), git_rev()))
    w("- Machine: %s (`/proc/cpuinfo` model name), %d logical cores, %.1f GB of memory, %s. Load average (1/5/15 min) %.2f %.2f %.2f at the start, "
      "%.2f %.2f %.2f at the end (the machine is shared); %.0f s in all." %
      (model, cores, memory_total(), platform.platform(), *load0, *load1, elapsed))
    w("- Date: %s, started %s UTC." % (started.strftime("%Y-%m-%d"), started.strftime("%H:%M")))
    w("- Every section below was measured in this run on this machine, except those copied in from runs by hand "
      "(section 8 and the profiles), which name their own machine and date.")
    w("")
    w("Terms. *library*: libbanyan's generate call, made through the add-on's ctypes binding and followed by "
      "`banyan_mesh_free`: what a script calling the library pays. *copy-out*: the binding's copy of the "
      "mesh into Python arrays (`MeshData.take`), the first step of the add-on's hand-off; it is timed in "
      "the hand-off, and shown on its own in section 3. *growth*: ivy's simulation alone (`banyan_ivy_create` + `banyan_ivy_step`). *end to end*: "
      "`banyan.api.<generator>(...)`, which ends with a mesh object in the scene. For the peers, *operator* "
      "is `bpy.ops.curve.ivy_gen` / `bpy.ops.curve.tree_add` (curves, and their leaf mesh), and *end to end* "
      "adds `bpy.ops.object.convert(target='MESH')` of the curve, since their output is a curve; vertices "
      "and triangles are counted after conversion (Blender's `loop_triangles`, leaves included). "
      "*bare*: Blender's floor for the same mesh, `foreach_set` of positions and indices into an empty mesh "
      "plus one object (`tests/bench/blender_handoff.py`); *bare+* also sets the UV, colour and attribute "
      "arrays the add-on sets. *Hand-off* = (end to end - library) / bare+.")
    w("")
    w("banyan runs with the add-on's defaults, as an artist gets them: since issue 23 they grow without the "
      "wind data (the parameter `wind` off in Blender only; Wind setup and Add Wind turn it on, docs/addon.md "
      "\"Wind data: off unless asked\"), so the library call, the copy-out and the layers Blender gets are "
      "those of a plant without the five wind layers. Neither IvyGen nor Sapling makes wind data. Runs before "
      "that change timed the plants with it.")
    w("")
    w("Issue 23 adds, beside those columns: *first evaluation*: Blender's first depsgraph evaluation of the new "
      "objects, as a user pays it before seeing them: `bpy.context.evaluated_depsgraph_get()` (the view-layer "
      "update that `bpy.ops` runs after every operator) and each new object's `evaluated_get(dg).data` fetched "
      "(its modifier stack, if any, evaluated by then). The peers pay it inside their operators (`bpy.ops` "
      "updates the view layer after IvyGen's, Sapling's and the convert operator), banyan's `api` call does not; "
      "both sides get the same call after their end to end, timed in the same run. *e2e+ev* = end to end + "
      "first evaluation. *edges*: Blender's floor given the same edges as the add-on "
      "(`blender_handoff.bare_edges`): `foreach_set` of the same vertices, edges (from `banyan_triangle_edges`, "
      "computed off the clock), loops with their edge indices, triangles, material slots and indices, smooth "
      "shading (Blender's cheapest stock way for its version and size), the UVs, colours and every attribute "
      "array the library returns (the wind pivot as one vector), one linked object and the same first "
      "evaluation. *Hand-off (issue 23)* = (e2e+ev - library) / edges. *library + mesh*: for ivy, the binding's "
      "`generate` call with its copy-out (growth, mesh and copy into Python arrays), what the stem-rate target "
      "of issue 23 counts.")
    w("")

    L.extend(targets23(ban_i, peers_i, ban_t, peers_t, mem, ivy_large, avenue))
    # ---- ivy
    w("## 1. Ivy: banyan vs IvyGen on a 3 m x 3 m wall")
    w("")
    w("The default cube scaled to 3 x 0.2 x 3 m; IvyGen starts at the 3D cursor %s, banyan at the preset's "
      "start (the same point). IvyGen's default settings, then its `maxIvyLength` (the length of the longest "
      "branch; growth stops there) chosen in this run by a secant search so that its total stem length, "
      "then its triangle count, matches banyan's `ivy_wall` preset. Stem length: the sum of the curve "
      "splines' lengths (IvyGen), of the skeleton's internode edges (banyan). Leaves: IvyGen's leaf quads; "
      "banyan's 12-triangle leaf blades on 6-triangle petioles (one per bud)." % (WALL_CURSOR,))
    w("")
    w("| run | setting | stem m | leaves | vertices | triangles | operator / library | growth | "
      "library + mesh | end to end | e2e+ev | m stem/s | M tris/s e2e | M tris/s e2e+ev |")
    w("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    w("| %s | preset | %.0f | %d | %d | %d | %s | %s | %s | %s | %s | %.0f (growth), %.0f (library + mesh) | "
      "%.2f | %.2f |" % (
          ban_i.label, ban_i.stem, ban_i.leaves, ban_i.verts, ban_i.tris, ban_i.lib.fmt(), ban_i.grow.fmt(),
          ban_i.copy.fmt(), ban_i.e2e.fmt(), ban_i.e2e_ev.fmt(), ban_i.stem / ban_i.grow.med,
          ban_i.stem / ban_i.copy.med, mtris(ban_i.tris, ban_i.e2e.med), mtris(ban_i.tris, ban_i.e2e_ev.med)))
    for r in peers_i:
        w("| %s | %s | %.0f | %d | %d | %d | %s | - | - | %s | %s | %.0f (operator) | %.2f | %.2f |" % (
            r.label, r.note, r.stem, r.leaves, r.verts, r.tris, r.op.fmt(), r.e2e.fmt(), r.e2e_ev.fmt(),
            r.stem / r.op.med, mtris(r.tris, r.e2e.med), mtris(r.tris, r.e2e_ev.med)))
    w("")
    stem_rate = ban_i.stem / ban_i.grow.med
    w("| ratio banyan / IvyGen | stem length/s, growth vs operator | stem length/s, library + mesh vs operator | "
      "tris/s, library vs operator | tris/s end to end | tris/s e2e+ev |")
    w("|---|---|---|---|---|---|")
    for r in peers_i:
        w("| vs %s | %.0fx | %.0fx | %.1fx | %.1fx | %.1fx |" % (
            r.label, stem_rate / (r.stem / r.op.med), stem_rate_mesh(ban_i, r),
            (ban_i.tris / ban_i.lib.med) / (r.tris / r.op.med), e2e_ratio(ban_i, r, False), e2e_ratio(ban_i, r)))
    w("")

    # ---- tree
    w("## 2. Tree: banyan keyaki_mature vs Sapling")
    w("")
    w("Sapling's operator defaults have `bevel` off (the curves have no surface, so no triangles); every "
      "Sapling run turns it on. The tree targets ask for leaves on both sides, so the leafless default tree "
      "is reported for reference and judged only with its leaves on. Leaves: both sides emit one layer of leaf faces, drawn from both sides "
      "(banyan's `keyaki_leaf` material is double-sided; Blender draws Sapling's faces two-sided), so "
      "leaf triangles are counted once on both sides. Branch length: the curve splines' lengths "
      "(Sapling), the skeleton's edges (banyan).")
    w("")
    w("| run | setting | branch m | leaves | vertices | triangles | operator / library | end to end | e2e+ev | "
      "M tris/s library/op | M tris/s e2e | M tris/s e2e+ev |")
    w("|---|---|---|---|---|---|---|---|---|---|---|---|")
    w("| %s | preset | %.0f | %d | %d | %d | %s | %s | %s | %.2f | %.2f | %.2f |" % (
        ban_t.label, ban_t.stem, ban_t.leaves, ban_t.verts, ban_t.tris, ban_t.lib.fmt(digits=4),
        ban_t.e2e.fmt(digits=4), ban_t.e2e_ev.fmt(digits=4), mtris(ban_t.tris, ban_t.lib.med),
        mtris(ban_t.tris, ban_t.e2e.med), mtris(ban_t.tris, ban_t.e2e_ev.med)))
    for r in peers_t:
        w("| %s | %s | %.0f | %d | %d | %d | %s | %s | %s | %.2f | %.2f | %.2f |" % (
            r.label, r.note, r.stem, r.leaves, r.verts, r.tris, r.op.fmt(digits=4), r.e2e.fmt(digits=4),
            r.e2e_ev.fmt(digits=4), mtris(r.tris, r.op.med), mtris(r.tris, r.e2e.med), mtris(r.tris, r.e2e_ev.med)))
    w("")
    w("| ratio banyan / Sapling | tris/s, library vs operator | tris/s end to end | tris/s e2e+ev |")
    w("|---|---|---|---|")
    for r in peers_t:
        w("| vs %s | %.0fx | %.1fx | %.1fx |" % (r.label, (ban_t.tris / ban_t.lib.med) / (r.tris / r.op.med),
                                                 e2e_ratio(ban_t, r, False), e2e_ratio(ban_t, r)))
    w("")

    # ---- roots and hand-off
    w("## 3. Roots, and every generator's hand-off against Blender's floor")
    w("")
    w("| run | vertices | triangles | library | copy-out | bare | bare+ | end to end | library / bare | "
      "end to end / bare+ | hand-off (e2e - lib) / bare+ |")
    w("|---|---|---|---|---|---|---|---|---|---|---|")
    for b in roots + [ban_i, ban_t]:
        w("| %s | %d | %d | %s | %.2f ms | %s | %s | %s | %.2f | %.2f | %.2f |" % (
            b.label, b.verts, b.tris, b.lib.fmt(1e3, "ms", 2), 1e3 * (b.copy.med - b.lib.med),
            b.bare.fmt(1e3, "ms", 2),
            b.bare_full.fmt(1e3, "ms", 2), b.e2e.fmt(1e3, "ms", 2), b.lib.med / b.bare.med,
            b.e2e.med / b.bare_full.med, b.handoff()))
    w("")
    w("Against the same-edges floor, first evaluation on both sides (issue 23). The old columns above let "
      "Blender derive the edges in the floor (*bare*, *bare+*) and leave the first evaluation out of both.")
    w("")
    w("| run | library | end to end | first evaluation | e2e+ev | edges (floor) | e2e+ev / (library + edges) | "
      "hand-off (e2e+ev - lib) / edges |")
    w("|---|---|---|---|---|---|---|---|")
    for b in roots + [ban_i, ban_t]:
        w("| %s | %s | %s | %s | %s | %s | %.2f | %.2f |" % (
            b.label, b.lib.fmt(1e3, "ms", 2), b.e2e.fmt(1e3, "ms", 2), b.first_ev.fmt(1e3, "ms", 2),
            b.e2e_ev.fmt(1e3, "ms", 2), b.bare_edges.fmt(1e3, "ms", 2), b.e2e_over_floor(), b.handoff_edges()))
    w("")
    diffs = ["%s: %s" % (b.label, "; ".join(b.floor_diff)) for b in roots + [ban_i, ban_t] if b.floor_diff]
    w("The floor's mesh against the add-on's (`blender_handoff.floor_differences`: element counts, material "
      "slots, attribute and UV layer names): %s." % ("the same for every run above" if not diffs else
                                                     "**differs**: " + " | ".join(diffs)))
    w("")

    # ---- memory
    w("## 4. The tube sweeper against memory write bandwidth")
    w("")
    sbw, fbw = mem["store_bytes_per_s"], mem["fresh_store_bytes_per_s"]
    w("`build/tests/bench_tube %d` (tests/bench/bench_tube.c), one thread, %d sides, no caps. Store loop "
      "over 256 MiB: %.2f GB/s [%.2f .. %.2f] into memory touched beforehand (the issue's bound), %.2f GB/s "
      "[%.2f .. %.2f] into fresh memory (a new buffer each pass: the kernel's page faults and zeroing "
      "included). The bound in triangles/s is that bandwidth over the bytes the workload writes per "
      "triangle (12 of indices plus its share of 32-byte vertices)." % (
          mem["runs"], mem["sides"], sbw[0] / 1e9, sbw[1] / 1e9, sbw[2] / 1e9, fbw[0] / 1e9, fbw[1] / 1e9,
          fbw[2] / 1e9))
    w("")
    w("| workload | how | triangles | bytes/tri | bound M tris/s | time | M tris/s | fraction of the bound | "
      "of the fresh-memory bound |")
    w("|---|---|---|---|---|---|---|---|---|")
    for c in mem["cases"]:
        s = c["seconds"]
        rate = c["triangles"] / s[0]
        w("| %s (%d x %d points) | %s | %d | %.1f | %.1f | %.1f ms [%.1f .. %.1f] | %.1f | %.0f%% | %s |" % (
            c["workload"], c["tubes"], c["points"], c["how"], c["triangles"], c["bytes_per_triangle"],
            c["bound_tris_per_s"] / 1e6, s[0] * 1e3, s[1] * 1e3, s[2] * 1e3, rate / 1e6,
            100 * rate / c["bound_tris_per_s"],
            "-" if c["how"] == "reused" else "%.0f%%" % (100 * rate / c["bound_fresh_tris_per_s"])))
    w("")
    w("*reused*: into a builder whose arrays are already allocated and touched, as the store loop's buffer "
      "is; *fresh*: new output memory each run (page faults included), as a one-shot generate call; *api*: "
      "`banyan_tube_generate` (validation and skeleton too).")
    w("")

    # ---- hosts
    outs, suz_lines, suz_ratio = hosts
    build_1m, roots_ratio, ivy_ratio = hosts_figures(outs)
    w("## 5. Hosts of any shape (issue 15)")
    w("")
    w("### Ivy on Suzanne: banyan (host shape Surface) vs IvyGen")
    w("")
    L.extend(suz_lines)
    w("")
    w("### Host sets, roots and ivy on meshes (C benchmarks, one thread)")
    w("")
    w("| target | figure | verdict |")
    w("|---|---|---|")
    w("| host set build, 1M triangles < 0.5 s on one core | %.3f s (median of 3) | %s |" % (
        build_1m, verdict(build_1m < 0.5)))
    w("| default roots on a 50k-triangle host within 5x of its bounding box | %.2fx | %s |" % (
        roots_ratio, verdict(roots_ratio <= 5)))
    w("| ivy_wall with the wall as a 12-triangle mesh within 1.5x of the box | %.2fx CPU | %s |" % (
        ivy_ratio, verdict(ivy_ratio <= 1.5)))
    w("| ivy on Suzanne: end to end against IvyGen at equal stem length | %.1fx faster | reference |" % suz_ratio)
    w("")
    for name in ("bench_hosts", "bench_roots_hosts", "bench_ivy"):
        w("`build/tests/%s`:" % name)
        w("")
        w("```")
        w(outs[name].strip())
        w("```")
        w("")

    # ---- targets
    w("## Targets (issue 9)")
    w("")
    ig_stem = peers_i[1]
    ig_tris = peers_i[2]
    r_stem = stem_rate / (ig_stem.stem / ig_stem.op.med)
    r_e2e = (ban_i.tris / ban_i.e2e.med) / (ig_tris.tris / ig_tris.e2e.med)
    w("| target | figure | verdict |")
    w("|---|---|---|")
    w("| ivy library >= 100x IvyGen stem length/s | %.0fx (growth vs operator, stem-matched IvyGen) | %s |" % (
        r_stem, verdict(r_stem >= 100)))
    w("| ivy end to end >= 5x IvyGen tris/s at equal triangles | %.1fx (vs the triangle-matched IvyGen); "
      "at the bare floor %.1fx | %s |" % (r_e2e, at_floor(ban_i, ig_tris), verdict(r_e2e >= 5)))
    for r in peers_t:
        rl = (ban_t.tris / ban_t.lib.med) / (r.tris / r.op.med)
        re = (ban_t.tris / ban_t.e2e.med) / (r.tris / r.e2e.med)
        # The tree targets are "with leaves on both sides": a leafless Sapling
        # tree is shown for reference, not judged.
        judge = verdict if r.leaves else (lambda ok: "reference (Sapling without leaves)")
        w("| tree library >= 100x Sapling tris/s (%s) | %.0fx | %s |" % (r.label, rl, judge(rl >= 100)))
        w("| tree end to end >= 10x Sapling tris/s (%s) | %.1fx; at the bare floor %.1fx | %s |" % (
            r.label, re, at_floor(ban_t, r), judge(re >= 10)))
    for b in roots + [ban_i, ban_t]:
        w("| hand-off <= 1.5x bare+ (%s) | %.2f | %s |" % (b.label, b.handoff(), verdict(b.handoff() <= 1.5)))
    for c in mem["cases"]:
        f = c["triangles"] / c["seconds"][0] / c["bound_tris_per_s"]
        ff = "" if c["how"] == "reused" else "; %.0f%% of the fresh-memory bound" % (
            100 * c["triangles"] / c["seconds"][0] / c["bound_fresh_tris_per_s"])
        w("| tube sweeper >= 25%% of the memory-write bound (%s, %s) | %.1f%%%s | %s |" % (
            c["workload"], c["how"], 100 * f, ff, verdict(f >= 0.25)))
    w("")
    w("*At the bare floor*: the end-to-end ratio if banyan's end to end took exactly Blender's stock floor for "
      "its mesh (*bare*: positions and indices by `foreach_set`, Blender computing the edges). The add-on "
      "hands Blender its edges (`banyan_triangle_edges`), so its end to end can come in under that floor.")
    w("")
    # ---- textures
    w("## 6. Textures (issue 17)")
    w("")
    w("`build/tests/bench_textures 1024 %d` (tests/bench/bench_textures.c): every texture the library draws "
      "(keyaki and Boston ivy leaf atlases in both seasons, keyaki, fig and ivy-stem bark; base colour and "
      "normal map each) at 1024 x 1024 on one thread, then their PNG encoding once. Target: the set under "
      "150 ms on one core. The add-on draws a material's textures once per .blend (shared materials), so only "
      "the first plant of a kind pays them; the glTF writer pays them once per file." % RUNS)
    w("")
    w("```")
    w(textures[0].strip())
    w("```")
    w("")
    first, later = textures[1]
    w("In Blender, end to end (`banyan.api.keyaki_tree(preset=\"keyaki_mature\")`, textures at 1024, median "
      "of %d): the first tree of a .blend %.2f s, the next ones %.2f s; the difference, %.2f s, is its two "
      "shared materials (leaf atlas and bark: drawn, PNG-encoded, packed and decoded by Blender). Sections "
      "1-3 time plants after the first (the shared materials stay between runs, as in a user's file)."
      % (max(3, RUNS // 2), first, later, first - later))
    w("")
    # ---- roots, C
    fused_ms, fused_mb, tube16, tube8 = roots_c_figures(roots_c)
    w("## 7. Roots: fused surface and tubes (issue 18)")
    w("")
    w("`build/tests/bench_roots` (tests/bench/bench_roots.c): the default net on the default trunk, one thread; "
      "the fused surface (OpenVDB, the default) and the plain tubes. Absolute times follow this shared VM's "
      "phases (docs/roots.md \"Speed\" compares builds in alternating runs).")
    w("")
    w("| target | figure | verdict |")
    w("|---|---|---|")
    w("| fused surface, default net < 250 ms on one core | %.1f ms (median of 10 seeds) | %s |" % (
        fused_ms, verdict(fused_ms < 250)))
    w("| fused surface memory peak | %.1f MB (peak resident set growth of one call) | reference |" % fused_mb)
    w("| tube mode, default net < 2 ms (n = 16, the history's figure) | %.3f ms reused | %s |" % (
        tube16, verdict(tube16 < 2)))
    w("| tube mode, default params (n = 8) | %.3f ms reused | reference |" % tube8)
    w("")
    w("```")
    w(roots_c.strip())
    w("```")
    w("")
    # Sections measured by hand (too long for this run), kept beside it and copied in.
    L.extend(kept_section("handoff.md", run_model))  # blender_handoff.py --write, one block per Blender
    L.extend(kept_section("instancing.md", run_model))
    L.extend(ivy_large_lines(ivy_large, run_model))
    L.extend(avenue_lines(avenue, run_model))
    L.extend(waits_lines(waits or [], ban_i, peers_i, run_model))
    L.extend(kept_section("batch.md", run_model))
    L.extend(kept_section("flamenco.md", run_model))
    L.extend(kept_section("profile.md", run_model))
    w("<!-- bench_tube output:")
    w(mem_text.strip().replace("--", "- -"))
    w("-->")
    return "\n".join(L) + "\n"


def main():
    t0 = time.perf_counter()
    started = datetime.datetime.now(datetime.timezone.utc)
    load0 = os.getloadavg()
    print("peers.py: %d runs per figure, Blender %s, library %s" % (RUNS, bpy.app.version_string,
                                                                   os.environ.get("BANYAN_LIB")), flush=True)
    mem = section_memory()
    print(mem[1], flush=True)
    roots = section_roots()
    print("roots done", flush=True)
    tree = section_tree()
    print("tree done", flush=True)
    ivy = section_ivy()
    print("ivy done", flush=True)
    hosts = section_hosts()
    textures = section_textures()
    print(textures[0], textures[1], flush=True)
    roots_c = section_roots_c()
    ivy_large = {"12m": section_ivy_large("ivy_wall_large"), "24m": section_ivy_large("ivy_wall_24m")}
    for key, big in ivy_large.items():
        print("ivy large %s: %s" % (key, big.get("skip", "%d rows" % len(big.get("rows", [])))), flush=True)
    avenue = section_avenue_write()
    print("avenue: %s" % avenue.get("skip", "done"), flush=True)
    waits = section_waits()
    text = report(ivy, tree, roots, mem[0], mem[1], hosts, load0, os.getloadavg(), time.perf_counter() - t0,
                  textures, roots_c, ivy_large, avenue, started, waits)
    with open(OUT, "w") as f:
        f.write(text)
    print(text)
    print("peers.py: wrote %s" % OUT, flush=True)


if __name__ == "__main__":  # ivy_suzanne.py imports the helpers above
    main()
