"""A complete headless example: a keyaki avenue along a curving street,
grown through banyan.api and rendered with Cycles on the CPU.

    blender -b --factory-startup --python docs/examples/render_avenue.py -- \
        [--out out/avenue.png] [--size 480x270] [--samples 16]

The avenue follows a Bezier curve object (its first spline, evaluated):
two rows of trees 14 m apart, one tree every 9 m, each its own seed.
The scene around it (ground, sun, sky, camera, render settings, blank
check) is docs/render_scene.py's.
"""
import argparse
import os
import sys

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, ".."))
import render_scene as RS  # noqa: E402


def args():
    ap = argparse.ArgumentParser(prog="render_avenue.py")
    ap.add_argument("--out", default=os.path.join(RS.REPO, "out", "avenue.png"))
    ap.add_argument("--size", default="480x270")
    ap.add_argument("--samples", type=int, default=16)
    a = ap.parse_args(RS.script_args())
    a.width, a.height = (int(v) for v in a.size.split("x"))
    return a


def street_curve():
    """A street 80 m long that bends gently to the left."""
    cu = bpy.data.curves.new("Street", 'CURVE')
    cu.dimensions = '3D'
    sp = cu.splines.new('BEZIER')
    sp.bezier_points.add(2)
    for p, co in zip(sp.bezier_points, [(0, 0, 0), (40, 4, 0), (78, 18, 0)]):
        p.co = co
        p.handle_left_type = p.handle_right_type = 'AUTO'
    ob = bpy.data.objects.new("Street", cu)
    bpy.context.scene.collection.objects.link(ob)
    return ob


def main():
    a = args()
    api = RS.import_banyan()  # banyan.api: the add-on's headless API
    RS.reset()
    street = street_curve()

    # One object per tree, in a new collection "Avenue". Keys are the
    # avenue's parameter table (`banyan avenue --list`); tree keys are
    # written tree__<name> (or values={"tree.levels": 19}).
    trees = api.keyaki_avenue(path=street, preset="avenue_street", name="Avenue", merged=False, threads=2,
                              rows=2, row_offset=14.0, spacing=9.0, placement="spacing",
                              tree__levels=19, seed=2025)
    street.hide_render = True

    RS.studio(trees)
    # Low, from beyond the start, looking down the street.
    RS.frame_camera(trees, (-1.0, -0.3, 0.2), a.width, a.height, box=RS.near_part(*RS.bounds(trees), ratio=1.0))
    RS.render(a.out, a.width, a.height, a.samples, trees)
    verts = sum(len(o.data.vertices) for o in trees)
    print("render_avenue: %d trees, %d vertices; wrote %s" % (len(trees), verts, a.out))


main()
