"""Renders the before / after pictures of docs/hosts.md into
docs/img/hosts/, in the shared scene of docs/render_scene.py:

    blender -b --factory-startup --python docs/render_hosts.py -- [--only NAME ...] \
        [--size 480x360] [--samples 16] [--out docs/img/hosts]

(or `bash tools/render_docs.sh hosts`). Each host is a Blender primitive
grown on through banyan.api with host_shape 'BOX' (its oriented bounding
box) and 'SURFACE' (its real
triangles). The two pictures of a pair share one camera, framed on the
host's bounds with a fixed margin, so only the host shape differs.
Cycles on the CPU, fixed seed and samples, no denoiser; every picture is
checked not to be blank (render_scene.render).
"""
import argparse
import os
import sys
import time

import bpy
from mathutils import Vector

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import render_scene as RS  # noqa: E402

OUT = os.path.join(RS.REPO, "docs", "img", "hosts")


def uv_sphere():
    """A UV sphere of radius 1 m resting on the ground."""
    bpy.ops.mesh.primitive_uv_sphere_add(segments=48, ring_count=24, radius=1.0, location=(0, 0, 1.0))
    return bpy.context.active_object


def column():
    """A 32-sided cylinder, r 0.4 m, 3.5 m tall, standing on the ground."""
    bpy.ops.mesh.primitive_cylinder_add(vertices=32, radius=0.4, depth=3.5, location=(0, 0, 1.75))
    return bpy.context.active_object


def suzanne():
    """Blender's Suzanne, 1.9 m wide, facing -y (the ivy view), chin on the ground."""
    bpy.ops.mesh.primitive_monkey_add(size=2.0, location=(0, 0, 0))
    ob = bpy.context.active_object
    ob.scale = (0.95, 0.95, 0.95)
    bpy.context.view_layer.update()
    lo, _ = RS.bounds([ob])
    ob.location.z = -lo.z
    bpy.context.view_layer.update()
    return ob


# name: (generator, host maker, host_shape, preset for the params, values,
#        framing: a margin (m) round the host's bounds, or a (lo, hi) box,
#        view direction)
IVY = {"seed": 1, "steps": 450, "t0": 20, "start": (0.0, -1.05, 0.05)}  # start just off the sphere's bounding box
COLUMN_MID = ((-0.7, -0.7, 1.2), (0.7, 0.7, 3.8))  # the upper shaft, close: where the box's corners stand off
COLUMN_VIEW = (1.0, -1.25, 0.45)
SHOTS = {
    "ivy_sphere_box": ("ivy", uv_sphere, 'BOX', "ivy_statue", IVY, 0.7, RS.VIEWS["ivy"]),
    "ivy_sphere_surface": ("ivy", uv_sphere, 'SURFACE', "ivy_statue", IVY, 0.7, RS.VIEWS["ivy"]),
    "roots_column_box": ("roots", column, 'BOX', "roots_column", {}, COLUMN_MID, COLUMN_VIEW),
    "roots_column_surface": ("roots", column, 'SURFACE', "roots_column", {}, COLUMN_MID, COLUMN_VIEW),
    # Fewer steps than the sphere: the face must still show through.
    "ivy_suzanne_surface": ("ivy", suzanne, 'SURFACE', "ivy_statue", dict(IVY, steps=240, start=(0.6, -0.5, 0.05)),
                            0.3, RS.VIEWS["ivy"]),
    # The full 450 steps, with the blades fitted to the relief (leaf_relief, the default) and without.
    "ivy_suzanne_relief": ("ivy", suzanne, 'SURFACE', "ivy_statue", dict(IVY, start=(0.6, -0.5, 0.05)),
                           0.3, RS.VIEWS["ivy"]),
    "ivy_suzanne_relief_off": ("ivy", suzanne, 'SURFACE', "ivy_statue",
                               dict(IVY, start=(0.6, -0.5, 0.05), leaf_relief=0.0), 0.3, RS.VIEWS["ivy"]),
    # The full 450 steps with stems that never wrap over the curves (wrap_angle 0).
    "ivy_suzanne_wrap_off": ("ivy", suzanne, 'SURFACE', "ivy_statue",
                             dict(IVY, start=(0.6, -0.5, 0.05), wrap_angle=0.0), 0.3, RS.VIEWS["ivy"]),
}


def args():
    ap = argparse.ArgumentParser(prog="render_hosts.py")
    ap.add_argument("--only", nargs="*", default=None, help="pictures: " + ", ".join(SHOTS))
    ap.add_argument("--size", default="480x360")
    ap.add_argument("--samples", type=int, default=16)
    ap.add_argument("--out", default=OUT)
    a = ap.parse_args(RS.script_args())
    a.width, a.height = (int(v) for v in a.size.split("x"))
    unknown = set(a.only or ()) - set(SHOTS)
    if unknown:
        raise SystemExit("render_hosts: no such pictures: %s" % ", ".join(sorted(unknown)))
    return a


def render_one(name, a):
    gen, make, shape, preset, values, framing, view = SHOTS[name]
    RS.reset()
    host = make()
    bpy.ops.object.select_all(action='DESELECT')
    if isinstance(framing, tuple):
        box = (Vector(framing[0]), Vector(framing[1]))
    else:
        lo, hi = RS.bounds([host])
        box = (lo - Vector((framing, framing, 0)), hi + Vector((framing, framing, framing)))
    plant, hosts = RS.grow(gen, preset=preset, values=values, hosts=[host], host_shape=shape)
    hosts = RS.host_objects(hosts)
    RS.plant_materials(plant)
    RS.studio(plant + hosts)
    RS.frame_camera(plant + hosts, view, a.width, a.height, box=box)
    return RS.render(os.path.join(a.out, name + ".png"), a.width, a.height, a.samples, plant)


def main():
    a = args()
    failed = []
    t_all = time.time()
    for name in SHOTS:
        if a.only is not None and name not in a.only:
            continue
        t0 = time.time()
        try:
            var, cov = render_one(name, a)
            print("render_hosts: %-22s %5.1f s  variance %.4f  plant %5.1f%% of pixels"
                  % (name, time.time() - t0, var, 100 * cov), flush=True)
        except Exception as e:  # noqa: BLE001 - every failure is reported, then the script fails
            failed.append(name)
            print("render_hosts: FAILED %s: %s" % (name, e), flush=True)
    print("render_hosts: done in %.1f s" % (time.time() - t_all), flush=True)
    if failed:
        sys.exit(1)


if __name__ == "__main__":
    main()
