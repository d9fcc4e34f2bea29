"""The default root net (the CLI's trunk: a 0.8 m x 0.8 m x 8 m box) seen
from 1 m, 3 m and 10 m, for docs/roots.md's before/after pictures of
issue #18:

    bash tools/render_docs.sh roots -- --tag after --values '{"surface": 1}'

writes docs/img/roots/look_<tag>_1m.png, _3m.png, _10m.png (--preset
grows a preset instead, --size, --samples)."""
import argparse
import json
import os
import sys

from mathutils import Vector

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import render_scene as RS  # noqa: E402

# (name, target, distance in m): the foot, the lower trunk, the whole tree.
VIEWS = [("1m", (0.25, -0.25, 0.25), 1.0), ("3m", (0.0, 0.0, 0.9), 3.0), ("10m", (0.0, 0.0, 3.6), 10.0)]


def main():
    ap = argparse.ArgumentParser(prog="render_roots_look.py")
    ap.add_argument("--tag", default="before")
    ap.add_argument("--preset", default=None)
    ap.add_argument("--values", default="{}", help="params as JSON, e.g. {\"surface\": 1}")
    ap.add_argument("--size", default="640x400")
    ap.add_argument("--samples", type=int, default=8)
    ap.add_argument("--out", default=os.path.join(RS.REPO, "docs", "img", "roots"))
    a = ap.parse_args(RS.script_args())
    w, h = (int(v) for v in a.size.split("x"))
    for name, target, dist in VIEWS:
        RS.reset()
        plant, hosts = RS.grow("roots", preset=a.preset, values=json.loads(a.values))
        hosts = RS.host_objects(hosts)
        RS.plant_materials(plant)
        RS.studio(plant + hosts)
        cam = RS.frame_camera(plant + hosts, RS.VIEWS["roots"], w, h)
        d = Vector(RS.VIEWS["roots"]).normalized()
        cam.location = Vector(target) + d * dist
        cam.rotation_euler = (-d).to_track_quat('-Z', 'Y').to_euler()
        cam.data.lens = 28.0
        cam.data.clip_start = 0.01
        tag = a.tag if not a.preset else "%s_%s" % (a.preset, a.tag)
        RS.render(os.path.join(a.out, "look_%s_%s.png" % (tag, name)), w, h, a.samples, plant)


main()
