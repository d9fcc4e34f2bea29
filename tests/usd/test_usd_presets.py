#!/usr/bin/env python3
"""USD output (docs/usd.md), tested with OpenUSD itself:

    test_usd_presets.py CLI OUT_DIR [PRESET ...]

Every preset (or the ones named) written by the CLI as .usda and as .glb,
made small as the glTF import test makes them (tests/pycommon/presets_small.py);
each layer checked by tests/usd/usd_check.py in OpenUSD's Python library
(tools/usd/usd_venv.sh): it opens without a warning, passes every OpenUSD
validator, and its first node holds the .glb's vertices and wind pivots.
Then a levels-of-detail variant set with a billboard, an instanced
avenue, and the refusals (a crate extension, a glTF-only option). Prints
`usd_presets: N passed, N failed`; exits 1 on a failure."""
import glob
import json
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(ROOT, "tests", "pycommon"))
from presets_small import shrink  # noqa: E402
from tally import check, finish  # noqa: E402

def venv_python():
    r = subprocess.run(["bash", os.path.join(ROOT, "tools", "usd", "usd_venv.sh")], stdout=subprocess.PIPE, text=True)
    if r.returncode != 0:
        print("FAIL: tools/usd/usd_venv.sh could not install usd-core (exit %d)" % r.returncode)
        sys.exit(1)
    return os.path.join(r.stdout.strip().splitlines()[-1], "bin", "python")


def cli(args):
    return subprocess.run(args, capture_output=True, text=True)


def usd_check(py, layer, glb=None):
    """The checker's counts, or None after reporting its failure."""
    r = subprocess.run([py, os.path.join(HERE, "usd_check.py"), layer] + ([glb] if glb else []),
                       capture_output=True, text=True)
    noisy = [l for l in r.stderr.splitlines() if "Warning" in l or "Error" in l or "Coding" in l]
    check(r.returncode == 0, "%s: %s" % (layer, (r.stdout + r.stderr).strip()[-600:]))
    check(not noisy, "%s: OpenUSD said: %s" % (layer, noisy[:3]))
    return json.loads(r.stdout.strip().splitlines()[-1]) if r.returncode == 0 else None


def main():
    exe, out = sys.argv[1], sys.argv[2]
    names = sys.argv[3:]
    os.makedirs(out, exist_ok=True)
    py = venv_python()
    presets = sorted(glob.glob(os.path.join(ROOT, "presets", "*.json")))
    if names:
        presets = [p for p in presets if os.path.basename(p)[:-5] in names]
    common = ["--texture-size", "64"]
    for p in presets:
        name = os.path.basename(p)[:-5]
        doc = json.load(open(p))
        gen = doc["generator"]
        sets = sum((["--set", x] for x in shrink(gen, doc.get("params", {}))), [])
        layer, glb = os.path.join(out, name + ".usda"), os.path.join(out, name + ".glb")
        r1 = cli([exe, gen, "--preset", p, "-o", layer] + sets + common)
        r2 = cli([exe, gen, "--preset", p, "-o", glb] + sets + common)
        check(r1.returncode == 0 and r2.returncode == 0, "%s: the CLI failed: %s" % (name, (r1.stderr + r2.stderr)[-400:]))
        if r1.returncode == 0 and r2.returncode == 0:
            c = usd_check(py, layer, glb)
            if c:
                print("%s: %s" % (name, json.dumps(c)))
        for f in (layer, glb):
            if os.path.exists(f):
                os.remove(f)
    if not names:
        extra(exe, out, py, common)
    finish("usd_presets")


def extra(exe, out, py, common):
    keyaki = os.path.join(ROOT, "presets", "keyaki_young.json")
    layer = os.path.join(out, "young_lod.usda")
    r = cli([exe, "keyaki", "--preset", keyaki, "--lod", "0.5,billboard", "-o", layer] + common)
    check(r.returncode == 0, "keyaki --lod: " + r.stderr[-300:])
    c = usd_check(py, layer) if r.returncode == 0 else None
    check(c is not None and c["lods"] == 3, "keyaki --lod 0.5,billboard: LOD variants %s, want 3" % (c and c["lods"]))
    billboard = glob.glob(os.path.join(out, "textures", "young_lod_0_lod2_image*.png"))
    check(len(billboard) == 1, "the billboard's picture beside the layer: %s" % billboard)
    layer = os.path.join(out, "street.usda")
    r = cli([exe, "avenue", "--preset", os.path.join(ROOT, "presets", "avenue_street.json"), "--set", "variants=3",
             "--set", "tree.levels=6", "-o", layer] + common)
    check(r.returncode == 0, "avenue variants=3: " + r.stderr[-300:])
    c = usd_check(py, layer) if r.returncode == 0 else None
    check(c is not None and c["instances"] > 3 and c["meshes"] >= 3,
          "instanced avenue: %s (want its instances on a PointInstancer over 3 variants)" % c)
    for bad, args, want in (("x.usdc", [], "usdcat"), ("x.usdz", [], "usdcat"),
                            ("x.usda", ["--engine-uvs"], "engine_uvs"), ("x.usda", ["--compact"], "compact")):
        path = os.path.join(out, bad)
        r = cli([exe, "keyaki", "--preset", keyaki, "-o", path] + args + common)
        check(r.returncode != 0 and want in r.stderr and not os.path.exists(path),
              "%s %s: exit %d, %r (want a refusal naming %s and no file)" % (bad, args, r.returncode,
                                                                            r.stderr[-200:], want))


main()
