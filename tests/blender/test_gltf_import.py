"""Blender's own glTF importer (bpy.ops.import_scene.gltf) on the files the
CLI writes: every preset in presets/ (made smaller with --set, textures
off but for one file with small ones), a keyaki with --lod
0.5,0.15,billboard and an avenue with variants (EXT_mesh_gpu_instancing)
and a LOD. glTF-Blender-IO before 5.2 fills a mesh's custom attributes in
the order of a Python set, which depends on the hash seed, so each import
runs in child Blenders started with different PYTHONHASHSEEDs (20 in the
full tier, BANYAN_TEST_TIER=full; 2 otherwise; BANYAN_GLTF_SEEDS overrides),
one child per seed importing every file. With the add-on's importer hook
(blender_addon/banyan/engine/gltf_import.py) each import must: raise nothing;
make an object for every node of the scene and none for the coarser
MSFT_lod levels; leave the wind and growth data under the add-on's names
(wind_pivot, a vector, wind_level, ..., birth; no `_NAME` left); put
every pivot inside its mesh's bounds in Blender's frame. The children's
hash('banyan') must differ (the seeds took effect). The first child also
runs the add-on's Add Wind on the imported keyaki (the crown sways, the
foot stays) and imports a copy of it whose asset.generator is not
banyan's (the hook leaves it alone: its levels stay, no wind_pivot). One
more child, without the add-on, imports a few files: no exception, and
(where the importer keeps custom attributes, 4.2 on) the scalars
_WIND_PIVOT_X, ... as written."""
import json
import os
import shutil
import struct
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bt  # noqa: E402

sys.path.insert(0, os.path.join(bt.SOURCE_DIR, "tests", "pycommon"))
from presets_small import shrink  # noqa: E402

import bpy  # noqa: E402

BUILD = os.environ.get("BANYAN_BUILD_DIR") or os.path.join(bt.SOURCE_DIR, "build")
CLI = os.path.join(BUILD, "banyan")
PRESETS = os.path.join(bt.SOURCE_DIR, "presets")
WIND = ("wind_level", "wind_stiffness", "wind_phase", "wind_flutter")
TIER = os.environ.get("BANYAN_TEST_TIER", "quick")
SEEDS = int(os.environ.get("BANYAN_GLTF_SEEDS") or (20 if TIER == "full" else 2))

CHILD = r'''
import json, sys, time
import bpy
import numpy as np
if not hasattr(np, "bool"):
    np.bool = bool  # Blender 3.4's importer with Debian's numpy (docs/PLATFORM_NOTES)
files = json.loads(sys.argv[sys.argv.index("--") + 1])
if sys.argv[-1].startswith("addon"):  # enabled as a user does (then in the preferences the importer reads)
    bpy.ops.preferences.addon_enable(module="banyan")


def clear():
    for coll in (bpy.data.objects, bpy.data.meshes, bpy.data.materials, bpy.data.images, bpy.data.collections):
        for x in list(coll):
            coll.remove(x)


def report(path):
    out = {"objects": [], "meshes": []}
    for ob in bpy.data.objects:
        out["objects"].append(ob.name)
        if ob.type != 'MESH':
            continue
        me = ob.data
        n = len(me.vertices)
        m = {"name": ob.name, "vertices": n,
             "attributes": sorted(a.name for a in me.attributes if not a.name.startswith("."))}
        piv = me.attributes.get("wind_pivot")
        if n and piv is not None and piv.data_type == 'FLOAT_VECTOR' and piv.domain == 'POINT':
            co = np.empty(3 * n, np.float32)
            me.vertices.foreach_get("co", co)
            co = co.reshape(-1, 3)
            pv = np.empty(3 * n, np.float32)
            piv.data.foreach_get("vector", pv)
            pv = pv.reshape(-1, 3)
            lo, hi = co.min(axis=0), co.max(axis=0)
            tol = 1e-3 + 1e-3 * float(np.linalg.norm(hi - lo))
            m["pivots_outside"] = int(np.count_nonzero(((pv < lo - tol) | (pv > hi + tol)).any(axis=1)))
            m["arm"] = float(np.linalg.norm(pv - co, axis=1).mean())
        out["meshes"].append(m)
    return out


def add_wind():
    """The add-on's Add Wind on the imported mesh objects: the largest
    vertex move between two frames in the top 10 % by height and in the
    lowest 2 cm (the trunk's foot)."""
    obs = [o for o in bpy.data.objects if o.type == 'MESH']
    for o in bpy.data.objects:
        o.select_set(o in obs)
    r = bpy.ops.banyan.add_wind()
    moves = []
    for ob in obs:
        co = []
        for f in (1, 37):
            bpy.context.scene.frame_set(f)
            dg = bpy.context.evaluated_depsgraph_get()
            me = ob.evaluated_get(dg).to_mesh()
            a = np.empty(3 * len(me.vertices), np.float32)
            me.vertices.foreach_get("co", a)
            co.append(a.reshape(-1, 3))
            ob.evaluated_get(dg).to_mesh_clear()
        if co[0].shape != co[1].shape or not len(co[0]):
            return {"result": sorted(r), "error": "vertex count changed"}
        d = np.linalg.norm(co[1] - co[0], axis=1)
        z = co[0][:, 2]
        hi = np.quantile(z, 0.9)
        moves.append([float(d[z >= hi].max()), float(d[z <= z.min() + 0.02].max())])
    return {"result": sorted(r), "modifiers": [m.name for o in obs for m in o.modifiers], "moves": moves}


res = {"hash": hash("banyan"), "files": {}}
for path in files:
    t = time.time()
    try:
        clear()
        bpy.ops.import_scene.gltf(filepath=path)
        r = report(path)
        r["error"] = None
        if sys.argv[-1] == "addon-wind" and path.endswith("keyaki_lod.glb"):
            r["wind"] = add_wind()
    except Exception as e:
        lines = [ln for ln in str(e).splitlines() if "Error" in ln] or str(e).splitlines() or [""]
        r = {"error": "%s: %s" % (type(e).__name__, lines[-1].strip()[:300])}
    r["seconds"] = round(time.time() - t, 2)
    res["files"][path] = r
print("GLTFRESULT " + json.dumps(res), flush=True)
'''


def write_files(d):
    """[(path, what)] written by the CLI; a failure for each it refuses."""
    jobs = []
    for name in sorted(os.listdir(PRESETS)):
        if not name.endswith(".json"):
            continue
        with open(os.path.join(PRESETS, name)) as f:
            p = json.load(f)
        gen = p["generator"]
        sets = shrink(gen, p.get("params", {}))
        tex = ["--textures", "on", "--texture-size", "64"] if name == "keyaki_young.json" else ["--textures", "off"]
        jobs.append((name[:-5], [gen, "--preset", os.path.join(PRESETS, name)] + tex, sets))
    jobs.append(("keyaki_lod", ["keyaki", "--preset", os.path.join(PRESETS, "keyaki_young.json"), "--textures", "off",
                                "--lod", "0.5,0.15,billboard"], ["levels=7"]))
    jobs.append(("avenue_variants", ["avenue", "--preset", os.path.join(PRESETS, "avenue_street.json"),
                                     "--textures", "off", "--lod", "0.5"],
                 ["placement=count", "count=3", "tree.levels=6", "variants=2"]))
    out = []
    for what, args, sets in jobs:
        path = os.path.join(d, what + ".glb")
        cmd = [CLI] + args + sum((["--set", s] for s in sets), []) + ["-o", path]
        r = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
        if bt.check(r.returncode == 0 and os.path.isfile(path), "%s: the CLI wrote it: %s" % (what, r.stderr.strip())):
            out.append((path, what))
    return out


def expected(path):
    """From the file's JSON: node names the scene reaches, node names
    MSFT_lod reaches, asset.generator, the accessor types of the custom
    attributes, and whether every primitive carries the wind."""
    with open(path, "rb") as f:
        head = f.read(20)
        j = json.loads(f.read(struct.unpack("<I", head[12:16])[0]))
    nodes = j.get("nodes", [])

    def reach(roots):
        seen, stack = [], list(roots)
        while stack:
            i = stack.pop()
            seen.append(i)
            stack += nodes[i].get("children", [])
        return seen
    scene = reach(j["scenes"][j.get("scene", 0)]["nodes"])
    lods = reach([i for n in nodes for i in (n.get("extensions") or {}).get("MSFT_lod", {}).get("ids", [])])
    types = {j["accessors"][a]["type"] for m in j["meshes"] for p in m["primitives"]
             for k, a in p["attributes"].items() if k.startswith("_")}
    wind = all("_WIND_PIVOT_X" in p["attributes"] for m in j["meshes"] for p in m["primitives"])
    return {"scene": [nodes[i].get("name") for i in scene], "lods": [nodes[i].get("name") for i in lods],
            "generator": j["asset"].get("generator"), "types": sorted(types), "wind": wind}


def run_child(paths, seed, addon, wind=False):
    with tempfile.NamedTemporaryFile("w", suffix=".py", delete=False) as f:
        f.write(CHILD)
        script = f.name
    env = dict(os.environ)
    env["PYTHONHASHSEED"] = str(seed)
    cmd = [bt.BLENDER, "-b", "--factory-startup", "--python-exit-code", "1", "--python", script, "--",
           json.dumps(paths), ("addon-wind" if wind else "addon") if addon else "none"]
    try:
        r = subprocess.run(cmd, capture_output=True, text=True, timeout=900, env=env)
    finally:
        os.unlink(script)
    lines = [ln for ln in r.stdout.splitlines() if ln.startswith("GLTFRESULT ")]
    if not bt.check(r.returncode == 0 and lines, "seed %d: the child Blender ran (exit %d): %s"
                    % (seed, r.returncode, (r.stdout + r.stderr)[-2000:])):
        return None
    return json.loads(lines[-1][len("GLTFRESULT "):])


def check_with_addon(seed, res, files, exp):
    for path, what in files:
        r = res["files"].get(path, {"error": "not imported"})
        e = exp[path]
        if not bt.check(r["error"] is None, "seed %d, %s: imports: %s" % (seed, what, r["error"])):
            continue
        base = {o.split(".")[0] for o in r["objects"]}
        missing = [n for n in e["scene"] if n not in base]
        bt.check(not missing, "seed %d, %s: an object for every node of the scene; missing %s (have %s)"
                 % (seed, what, missing, r["objects"][:8]))
        extra = [n for n in e["lods"] if n in base]
        bt.check(not extra, "seed %d, %s: no coarser MSFT_lod level in the scene: %s" % (seed, what, extra))
        bt.check(len(r["meshes"]) > 0, "seed %d, %s: mesh objects" % (seed, what))
        for m in r["meshes"]:
            left = [a for a in m["attributes"] if a.startswith("_")]
            bt.check(not left, "seed %d, %s/%s: every custom attribute under the add-on's name; left %s"
                     % (seed, what, m["name"], left))
            if e["wind"]:
                has = "wind_pivot" in m["attributes"] and all(w in m["attributes"] for w in WIND)
                bt.check(has and "birth" in m["attributes"], "seed %d, %s/%s: wind_pivot, %s and birth: %s"
                         % (seed, what, m["name"], ", ".join(WIND), m["attributes"]))
                bt.check(has and m.get("pivots_outside") == 0,
                         "seed %d, %s/%s: every pivot inside the mesh's bounds in Blender's frame: %s outside of %d"
                         % (seed, what, m["name"], m.get("pivots_outside"), m["vertices"]))


def main():
    if not bt.check(os.path.isfile(CLI), "the CLI %s exists" % CLI):
        return
    d = os.path.join(bt.OUT_DIR, "gltf_import")
    shutil.rmtree(d, ignore_errors=True)
    os.makedirs(d)
    files = write_files(d)
    exp = {p: expected(p) for p, _ in files}
    for p, what in files:
        e = exp[p]
        bt.check(e["generator"] == "banyan", "%s: asset.generator is 'banyan': %r" % (what, e["generator"]))
        bt.check(e["types"] in ([], ["SCALAR"]), "%s: every custom attribute is SCALAR: %s" % (what, e["types"]))
    bt.check(sum(bool(exp[p]["lods"]) for p, _ in files) >= 2, "two files carry MSFT_lod levels")
    bt.check(sum(exp[p]["wind"] for p, _ in files) >= len(files) - 2,
             "the files carry wind: %d of %d" % (sum(exp[p]["wind"] for p, _ in files), len(files)))
    # A file from another generator: the hook leaves it as the importer makes it.
    other = os.path.join(d, "not_banyan.glb")
    with open(os.path.join(d, "keyaki_lod.glb"), "rb") as f:
        data = f.read()
    with open(other, "wb") as f:
        f.write(data.replace(b'"generator":"banyan"', b'"generator":"nobody"', 1))
    bt.check(expected(other)["generator"] == "nobody", "not_banyan.glb: generator 'nobody'")
    paths = [p for p, _ in files]
    hashes = []
    for seed in range(SEEDS):
        res = run_child(paths + ([other] if seed == 0 else []), seed, True, wind=seed == 0)
        if res is None:
            continue
        hashes.append(res["hash"])
        check_with_addon(seed, res, files, exp)
        if seed == 0:
            r = res["files"].get(other, {"error": "not imported"})
            lods = expected(os.path.join(d, "keyaki_lod.glb"))["lods"]
            if bt.check(r["error"] is None, "not_banyan.glb imports: %s" % r["error"]):
                base = {o.split(".")[0] for o in r["objects"]}
                bt.check(all(n in base for n in lods), "not_banyan.glb: the hook leaves its levels: %s" % r["objects"])
                kept = [m for m in r["meshes"] if "wind_pivot" in m["attributes"]]
                bt.check(not kept, "not_banyan.glb: the hook makes no wind_pivot: %s" % [m["name"] for m in kept])
            w = next((r.get("wind") for p, r in res["files"].items() if p.endswith("keyaki_lod.glb")), None) or {}
            ok = w.get("result") == ["FINISHED"] and "Banyan Wind" in w.get("modifiers", []) and w.get("moves")
            bt.check(ok and all(top > 0.01 and bottom < 0.001 for top, bottom in w["moves"]),
                     "Add Wind on the imported keyaki: the crown sways (> 1 cm), the foot stays (< 1 mm): %s" % w)
            slow = sorted(((r.get("seconds", 0), os.path.basename(p)) for p, r in res["files"].items()), reverse=True)
            print("gltf_import: %d files, import %.1f s in all (slowest %s); Add Wind moves (top, foot) %s m"
                  % (len(paths), sum(s for s, _ in slow), slow[:3], w.get("moves")), flush=True)
    bt.check(len(set(hashes)) == SEEDS, "%d seeds gave %d different hash('banyan')" % (SEEDS, len(set(hashes))))

    # Without the add-on: the stock importer alone.
    few = [p for p, w in files if w in ("keyaki_lod", "ivy_wall", "roots_trunk", "avenue_variants")]
    res = run_child(few, 1, False)
    if res is not None:
        keeps = bpy.app.version >= (4, 2, 0)  # 3.4's importer keeps no custom attribute
        for p in few:
            r = res["files"][p]
            if not bt.check(r["error"] is None, "no add-on, %s: imports: %s" % (os.path.basename(p), r["error"])):
                continue
            if keeps:
                bt.check(all("_WIND_PIVOT_X" in m["attributes"] and "_WIND_LEVEL" in m["attributes"]
                             for m in r["meshes"]),
                         "no add-on, %s: the scalars _WIND_PIVOT_X, _WIND_LEVEL, ... kept"
                         % os.path.basename(p))


bt.run(main)
bt.done()
