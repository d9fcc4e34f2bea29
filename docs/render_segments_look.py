"""The segment trees of presets/segments_paper.json and
presets/segments_bushy.json, for docs/segments.md's before/after pictures
of the composer's mesh (bark colour, taper, closed tips, junctions, zigzag):

    bash tools/render_docs.sh segments -- --tag after

writes docs/img/segments/<tag>_<view>.png for the views below: each
preset's whole tree, a close view of segments_paper's first twig where it
leaves segment 0's axis (about 0.3 m away), one of that twig's tip, and a
close view of segments_bushy's trunk where segments leave it. --views
picks some views; --size, --samples, --out, --colors as in
docs/render_ivy_look.py (a 256-colour palette PNG by default)."""
import argparse
import math
import os
import sys

from mathutils import Vector

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import render_scene as RS  # noqa: E402
from render_ivy_look import palette_png  # noqa: E402

# segments_paper, segment 0: S (0, 0, 2), axis (0.6, 0, 0.8), l 2.5, n 5;
# twig 1 leaves at D_1 = S + axis l / 6 towards R_z(40 deg) axis, m = 0.5 m.
_C = Vector((0.6, 0.0, 0.8))
_D1 = Vector((0.0, 0.0, 2.0)) + _C * (2.5 / 6)
_F1 = Vector((0.6 * math.cos(math.radians(40)), 0.6 * math.sin(math.radians(40)), 0.8))
_E1 = _D1 + _F1 * 0.5
# name: (preset, target or None (frame the whole tree), direction (target to camera), distance m, lens mm)
VIEWS = {
    "paper_whole": ("segments_paper", None, (1.0, -1.25, 0.12), None, 50.0),
    "paper_joint": ("segments_paper", tuple(_D1 + _F1 * 0.08), (-0.31, -0.11, 0.23), 0.3, 35.0),
    "paper_tip": ("segments_paper", tuple(_E1 - _F1 * 0.08), (-0.31, -0.11, 0.23), 0.3, 35.0),
    "bushy_whole": ("segments_bushy", None, (1.0, -1.25, 0.12), None, 50.0),
    "bushy_close": ("segments_bushy", (0.0, 0.0, 3.6), (1.0, -1.25, 0.05), 1.6, 35.0),
}


def main():
    ap = argparse.ArgumentParser(prog="render_segments_look.py")
    ap.add_argument("--tag", default="before")
    ap.add_argument("--views", default=",".join(VIEWS), help="comma-separated, of %s" % ", ".join(VIEWS))
    ap.add_argument("--size", default="640x400")
    ap.add_argument("--samples", type=int, default=16)
    ap.add_argument("--colors", type=int, default=256, help="palette size of the PNG (0: RGB)")
    ap.add_argument("--out", default=os.path.join(RS.REPO, "docs", "img", "segments"))
    a = ap.parse_args(RS.script_args())
    w, h = (int(v) for v in a.size.split("x"))
    for name in a.views.split(","):
        preset, target, direction, dist, lens = VIEWS[name]
        RS.reset()
        plant, _ = RS.grow("segments", preset=preset)
        RS.plant_materials(plant)
        RS.studio(plant)
        cam = RS.frame_camera(plant, direction, w, h, lens=lens)
        if target is not None:
            d = Vector(direction).normalized()
            cam.location = Vector(target) + d * dist
            cam.rotation_euler = (-d).to_track_quat('-Z', 'Y').to_euler()
            cam.data.clip_start = 0.005
        path = os.path.join(a.out, "%s_%s.png" % (a.tag, name))
        RS.render(path, w, h, a.samples, plant)
        if a.colors:
            palette_png(path, min(a.colors, 256))


main()
