"""Renders the pictures of parameter effects on the generator pages
(docs/roots.md, docs/ivy.md) into docs/img/params/, in the shared scene
of docs/render_scene.py:

    blender -b --factory-startup --python docs/render_params.py -- [--only GROUP ...]

(or `bash tools/render_docs.sh params`). Each group renders one preset
with one parameter changed; the pictures of a group share one camera, so
only the parameter differs between them. The keyaki model progression
uses the gallery's thumbnails of the keyaki_model_* presets.
"""
import argparse
import os
import sys
import time

from mathutils import Vector

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import render_scene as RS  # noqa: E402

OUT = os.path.join(RS.REPO, "docs", "img", "params")

# The top of the trunk preset's 10 m host, where the roots leave G.
TRUNK_TOP = ((-0.3, -0.3, 9.6), (0.3, 0.3, 10.15))

# group: (generator, preset, parameter, values, framing). Framing "union"
# frames every picture of the group on the union of their bounds, "own"
# each on its own bounds; a (lo, hi) pair frames that box (a close-up).
GROUPS = {
    "roots_radius": ("roots", "roots_trunk", "radius", [0.5, 0.8, 1.4], TRUNK_TOP),
    # Closer still, and flat-shaded so the facets show.
    "roots_sides": ("roots", "roots_trunk", "sides", [4, 8, 16], ((-0.2, -0.2, 9.9), (0.2, 0.2, 10.12))),
    "roots_first_branches": ("roots", "roots_boulder", "first_branches", [True, False], "union"),
    "roots_hugging": ("roots", "roots_trunk", "hugging", [True, False], "own"),
    "ivy_t0": ("ivy", "ivy_wall", "t0", [10, 15, 20, 25], "union"),
}


def args():
    ap = argparse.ArgumentParser(prog="render_params.py")
    ap.add_argument("--only", nargs="*", default=None, help="group names: " + ", ".join(GROUPS))
    ap.add_argument("--size", default="200x150")
    ap.add_argument("--samples", type=int, default=16)
    a = ap.parse_args(RS.script_args())
    a.width, a.height = (int(v) for v in a.size.split("x"))
    return a


def file_name(group, value):
    v = {True: "on", False: "off"}.get(value, value) if isinstance(value, bool) else value
    return "%s_%s.png" % (group, v)


FLAT = {"roots_sides"}


def scene(gen, preset, key, value, flat=False):
    RS.reset()
    plant, boxes = RS.grow(gen, preset=preset, values={key: value})
    for o in plant if flat else ():
        o.data.polygons.foreach_set("use_smooth", [False] * len(o.data.polygons))
    hosts = RS.host_objects(boxes)
    RS.plant_materials(plant)
    return plant, hosts


def union_box(gen, preset, key, values):
    lo, hi = None, None
    for v in values:
        plant, hosts = scene(gen, preset, key, v)
        a, b = RS.bounds(plant + hosts)
        lo = a if lo is None else Vector(map(min, lo, a))
        hi = b if hi is None else Vector(map(max, hi, b))
    return lo, hi


def render_group(group, a):
    gen, preset, key, values, framing = GROUPS[group]
    if framing == "union":
        box = union_box(gen, preset, key, values)
    else:
        box = None if framing == "own" else tuple(Vector(c) for c in framing)
    for v in values:
        t0 = time.time()
        plant, hosts = scene(gen, preset, key, v, group in FLAT)
        RS.studio(plant + hosts)
        RS.frame_camera(plant + hosts, RS.VIEWS[gen], a.width, a.height, box=box)
        path = os.path.join(OUT, file_name(group, v))
        var, cov = RS.render(path, a.width, a.height, a.samples, plant)
        print("render_params: %-34s %5.1f s  variance %.4f  plant %5.1f%% of pixels"
              % (os.path.basename(path), time.time() - t0, var, 100 * cov), flush=True)


def main():
    a = args()
    groups = a.only if a.only else list(GROUPS)
    unknown = set(groups) - set(GROUPS)
    if unknown:
        raise SystemExit("render_params: no such groups: %s" % ", ".join(sorted(unknown)))
    failed = []
    for g in groups:
        try:
            render_group(g, a)
        except Exception as e:  # noqa: BLE001 - reported, then the script fails
            failed.append(g)
            print("render_params: FAILED %s: %s" % (g, e), flush=True)
    if failed:
        sys.exit(1)


if __name__ == "__main__":
    main()
