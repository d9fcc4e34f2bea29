"""Renders strangler-fig roots (a roots preset, or the defaults) to a PNG
with Cycles on the CPU, headless.

    blender -b --factory-startup --python docs/examples/render_roots.py -- \
        [--preset roots_trunk] [--out out/roots.png] [--size 480] [--samples 16]

The scene: the preset's host boxes (grey; without hosts, the CLI's default
0.8 x 0.8 x 8 m trunk), the roots with their own colour, a ground plane,
a sun and a sky, and a camera framing the roots. The add-on is imported
from blender_addon/ beside this script when it is not installed; the
library is found as the add-on finds it (BANYAN_LIB, banyan/lib/, or the
repo's build/).
"""
import argparse
import math
import os
import sys

import bpy
from mathutils import Matrix, Vector

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.normpath(os.path.join(HERE, "..", ".."))


def import_banyan():
    try:
        import banyan.api  # noqa: F401  (installed add-on)
    except ImportError:
        sys.path.insert(0, os.path.join(REPO, "blender_addon"))
    import banyan.api as api
    from banyan import presets
    from banyan.core.params import preset_hosts
    from banyan.core.structs import Box
    return api, presets, preset_hosts, Box


def args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    ap = argparse.ArgumentParser(prog="render_roots.py")
    ap.add_argument("--preset", default=None, help="a roots preset name or JSON path")
    ap.add_argument("--out", default=os.path.join(REPO, "out", "roots.png"))
    ap.add_argument("--size", type=int, default=480)
    ap.add_argument("--samples", type=int, default=16)
    return ap.parse_args(argv)


def host_object(box, i, mat):
    me = bpy.data.meshes.new("Host%d" % i)
    h = box.half
    corners = [(sx * h[0], sy * h[1], sz * h[2]) for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]
    faces = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    me.from_pydata(corners, [], faces)
    me.materials.append(mat)
    ob = bpy.data.objects.new("Host%d" % i, me)
    r = box.rotation
    rot = Matrix(((r[0], r[1], r[2]), (r[3], r[4], r[5]), (r[6], r[7], r[8]))).to_4x4()
    ob.matrix_world = Matrix.Translation(Vector(box.center)) @ rot
    bpy.context.scene.collection.objects.link(ob)
    return ob


def material(name, rgba, rough=0.8):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    b = m.node_tree.nodes["Principled BSDF"]
    b.inputs["Base Color"].default_value = rgba
    b.inputs["Roughness"].default_value = rough
    return m


def frame_camera(cam, objs, size):
    pts = [o.matrix_world @ Vector(c) for o in objs for c in o.bound_box]
    lo = Vector([min(p[k] for p in pts) for k in range(3)])
    hi = Vector([max(p[k] for p in pts) for k in range(3)])
    centre = (lo + hi) / 2
    radius = max((hi - lo).length / 2, 0.5)
    direction = Vector((1.0, -1.25, 0.7)).normalized()
    cam.data.lens = 50
    fov = 2 * math.atan(cam.data.sensor_width / (2 * cam.data.lens))
    dist = radius / math.sin(fov / 2) * 0.8
    cam.location = centre + direction * dist
    cam.rotation_euler = (centre - cam.location).to_track_quat('-Z', 'Y').to_euler()
    cam.data.clip_end = dist * 4


def main():
    a = args()
    api, presets, preset_hosts, Box = import_banyan()
    bpy.ops.wm.read_homefile(use_empty=True)
    sc = bpy.context.scene
    boxes = []
    if a.preset:
        path = presets.find("roots", a.preset)
        boxes = preset_hosts(presets.read(path), path)
    if not boxes:
        boxes = [Box.make((0, 0, 4), (0.4, 0.4, 4))]
    grey = material("Host", (0.45, 0.45, 0.45, 1.0))
    hosts = [host_object(b, i, grey) for i, b in enumerate(boxes)]
    roots = api.strangler_roots(hosts=boxes, preset=a.preset, name="Roots")

    bpy.ops.mesh.primitive_plane_add(size=200, location=(0, 0, 0))
    bpy.context.active_object.data.materials.append(material("Ground", (0.12, 0.1, 0.08, 1.0), 1.0))
    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", 'SUN'))
    sun.data.energy = 2.5
    sun.data.angle = math.radians(3)
    sun.rotation_euler = (math.radians(50), 0, math.radians(35))
    sc.collection.objects.link(sun)
    world = bpy.data.worlds.new("Sky")
    world.use_nodes = True
    sky = world.node_tree.nodes.new("ShaderNodeTexSky")
    sky.sky_type = 'NISHITA' if hasattr(sky, "sky_type") else sky.sky_type
    sky.sun_elevation = math.radians(40)
    world.node_tree.links.new(sky.outputs["Color"], world.node_tree.nodes["Background"].inputs["Color"])
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.08
    sc.world = world
    cam = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    sc.collection.objects.link(cam)
    sc.camera = cam
    frame_camera(cam, roots + hosts, a.size)

    sc.render.engine = 'CYCLES'
    sc.cycles.device = 'CPU'
    sc.cycles.samples = a.samples
    sc.cycles.use_denoising = False
    sc.render.resolution_x = a.size
    sc.render.resolution_y = a.size
    sc.render.resolution_percentage = 100
    sc.view_settings.exposure = -0.5
    sc.render.image_settings.file_format = 'PNG'
    os.makedirs(os.path.dirname(os.path.abspath(a.out)), exist_ok=True)
    sc.render.filepath = os.path.abspath(a.out)
    bpy.ops.render.render(write_still=True)
    print("render_roots: wrote %s (%d vertices of roots)" % (a.out, sum(len(o.data.vertices) for o in roots)))


main()
