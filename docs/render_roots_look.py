"""The default root net (the CLI's trunk: a 0.8 m x 0.8 m x 8 m box) seen
from 1 m, 3 m and 10 m, for docs/roots.md's before/after pictures:

    bash tools/render_docs.sh roots -- --tag after --values '{"surface": 1}'

writes docs/img/roots/look_<tag>_1m.png, _3m.png, _10m.png (--preset
grows a preset instead, --suzanne grows on Blender's Suzanne (2 m, chin
on the ground) as a mesh host through the add-on, --size, --samples)."""
import argparse
import json
import os
import sys

import bpy

from mathutils import Vector

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import render_scene as RS  # noqa: E402

# (name, target, distance in m): the foot at the host's corner that faces
# the camera, the lower trunk, the whole tree. Targets are fractions of the
# hosts' bounds, so every preset is seen alike (on the default trunk, a
# 0.8 m x 0.8 m x 8 m box: (0.25, -0.25, 0.25), (0, 0, 0.9), (0, 0, 3.6)).
VIEWS = [("1m", 1.0), ("3m", 3.0), ("10m", 10.0)]


def target(name, lo, hi):
    c = [(lo[k] + hi[k]) / 2 for k in range(3)]
    h = [(hi[k] - lo[k]) / 2 for k in range(3)]
    if name == "1m":
        return (c[0] + 0.625 * h[0], c[1] - 0.625 * h[1], lo[2] + 0.25)
    if name == "3m":
        return (c[0], c[1], lo[2] + 0.9)
    return (c[0], c[1], lo[2] + 0.45 * (hi[2] - lo[2]))


def bounds(objs):
    pts = [o.matrix_world @ Vector(c) for o in objs for c in o.bound_box]
    return [min(p[k] for p in pts) for k in range(3)], [max(p[k] for p in pts) for k in range(3)]


def main():
    ap = argparse.ArgumentParser(prog="render_roots_look.py")
    ap.add_argument("--tag", default="before")
    ap.add_argument("--preset", default=None)
    ap.add_argument("--values", default="{}", help="params as JSON, e.g. {\"surface\": 1}")
    ap.add_argument("--suzanne", action="store_true", help="grow on Suzanne (a mesh host) instead")
    ap.add_argument("--size", default="640x400")
    ap.add_argument("--samples", type=int, default=8)
    ap.add_argument("--out", default=os.path.join(RS.REPO, "docs", "img", "roots"))
    a = ap.parse_args(RS.script_args())
    w, h = (int(v) for v in a.size.split("x"))
    for name, dist in VIEWS:
        RS.reset()
        host = None
        if a.suzanne:
            bpy.ops.mesh.primitive_monkey_add(size=2.0, location=(0, 0, 1.0))
            host = [bpy.context.active_object]
        plant, hosts = RS.grow("roots", preset=a.preset, values=json.loads(a.values), hosts=host)
        hosts = RS.host_objects(hosts)
        RS.plant_materials(plant)
        RS.studio(plant + hosts)
        cam = RS.frame_camera(plant + hosts, RS.VIEWS["roots"], w, h)
        d = Vector(RS.VIEWS["roots"]).normalized()
        t = Vector(target(name, *bounds(hosts)))
        cam.location = t + d * dist
        cam.rotation_euler = (-d).to_track_quat('-Z', 'Y').to_euler()
        cam.data.lens = 28.0
        cam.data.clip_start = 0.01
        tag = a.tag if not (a.preset or a.suzanne) else "%s_%s" % (a.preset or "suzanne", a.tag)
        RS.render(os.path.join(a.out, "look_%s_%s.png" % (tag, name)), w, h, a.samples, plant)


main()
