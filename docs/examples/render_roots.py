"""Renders strangler-fig roots (a roots preset, or the defaults) to a PNG
with Cycles on the CPU, headless.

    blender -b --factory-startup --python docs/examples/render_roots.py -- \
        [--preset roots_trunk] [--out out/roots.png] [--size 480] [--samples 16]

The scene is docs/render_scene.py's: the preset's host boxes (grey;
without hosts, the CLI's default 0.8 x 0.8 x 8 m trunk), the roots with
their own colour, a ground plane, a sun and a sky, and a camera framing
the roots. The add-on is imported from blender_addon/ when it is not
installed; the library is found as the add-on finds it (BANYAN_LIB,
banyan/lib/, or the repo's build/).
"""
import argparse
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, ".."))
import render_scene as RS  # noqa: E402


def args():
    ap = argparse.ArgumentParser(prog="render_roots.py")
    ap.add_argument("--preset", default=None, help="a roots preset name or JSON path")
    ap.add_argument("--out", default=os.path.join(RS.REPO, "out", "roots.png"))
    ap.add_argument("--size", type=int, default=480)
    ap.add_argument("--samples", type=int, default=16)
    return ap.parse_args(RS.script_args())


def main():
    a = args()
    RS.reset()
    roots, boxes = RS.grow("roots", preset=a.preset)
    hosts = RS.host_objects(boxes)
    RS.studio(roots + hosts)
    RS.frame_camera(roots + hosts, RS.VIEWS["roots"], a.size, a.size)
    RS.render(a.out, a.size, a.size, a.samples, roots)
    print("render_roots: wrote %s (%d vertices of roots)" % (a.out, sum(len(o.data.vertices) for o in roots)))


main()
