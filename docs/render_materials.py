"""Renders the before / after pictures of docs/materials.md ("In
Blender") into docs/img/materials/render_<shot>_<tag>.png: the camera
1 m from a leaf and from a bark surface, in the shared scene of
docs/render_scene.py:

    BANYAN_LIB=<lib> blender -b --factory-startup --python docs/render_materials.py -- \
        --tag after [--addon DIR] [--only NAME ...] [--size 480x360] [--samples 32] [--texture-size 1024]

--addon is the blender_addon/ folder to use (default this repository's):
"before" is made with the add-on and library of commit e9b3e72 (flat
colours), "after" with this one (shared textured materials),
same plants, same cameras. Each shot picks its surface point from the
plant's own vertices (the one furthest out towards the view direction in
a height band), so both versions frame the same spot. Cycles on the CPU,
fixed seed and samples, no denoiser; render_scene.render checks the
picture is not blank.
"""
import argparse
import os
import sys
from array import array

import bpy
from mathutils import Vector

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import render_scene as RS  # noqa: E402

OUT = os.path.join(RS.REPO, "docs", "img", "materials")


def wall():
    """A wall 6 m wide, 0.3 m thick, 3 m tall, its face towards -y."""
    bpy.ops.mesh.primitive_cube_add(size=1.0, location=(0, 0, 1.5))
    ob = bpy.context.active_object
    ob.scale = (6.0, 0.3, 3.0)
    bpy.context.view_layer.update()
    return ob


def verts(objs, slot_words):
    """World positions of the vertices of polygons whose material name
    holds one of slot_words (any material when None)."""
    out = []
    for o in objs:
        me = o.data
        names = [(m.name.lower() if m else "") for m in me.materials]
        want = {i for i, n in enumerate(names) if slot_words is None or any(w in n for w in slot_words)}
        if not want:
            continue
        mi = array("i", bytes(4 * len(me.polygons)))
        me.polygons.foreach_get("material_index", mi)
        co = array("f", bytes(12 * len(me.vertices)))
        me.vertices.foreach_get("co", co)
        keep = set()
        for p, m in zip(me.polygons, mi):
            if m in want:
                keep.update(p.vertices)
        mw = o.matrix_world
        out += [mw @ Vector(co[3 * i:3 * i + 3]) for i in keep]
    return out


def pick(points, direction, zmin, zmax, centre, radius=1.0):
    """The point furthest out along `direction` (horizontal part) among
    those with zmin <= z <= zmax within `radius` of the vertical plane
    through `centre` along it (the middle of the plant, not its edge)."""
    d = Vector((direction[0], direction[1], 0)).normalized()
    side = Vector((-d.y, d.x, 0))
    band = [p for p in points if zmin <= p.z <= zmax] or points
    mid = [p for p in band if abs((p - centre).dot(side)) <= radius] or band
    return max(mid, key=lambda p: (p - centre).dot(d))


def aim(target, direction, distance=1.0, lens=35.0):
    sc = bpy.context.scene
    cam = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    sc.collection.objects.link(cam)
    sc.camera = cam
    cam.data.lens = lens
    cam.data.clip_start = 0.01
    d = Vector(direction).normalized()
    cam.location = target + d * distance
    cam.rotation_euler = (-d).to_track_quat('-Z', 'Y').to_euler()


# name: (generator, values, hosts maker, slot words of the surface,
#        z band, view direction, season label or None)
IVY = {"seed": 1, "steps": 500, "start": (0.0, -0.16, 0.05)}
SHOTS = {
    "ivy_leaf": ("ivy", IVY, wall, ("leaf",), (0.8, 1.4), (0.25, -1.0, 0.15)),
    "keyaki_leaf": ("keyaki", {"seed": 1}, None, ("leaf",), (8.0, 11.0), (1.0, -1.3, 0.1)),
    "keyaki_leaf_autumn": ("keyaki", {"seed": 1, "season": "autumn"}, None, ("leaf",), (8.0, 11.0),
                           (1.0, -1.3, 0.1)),
    "keyaki_bark": ("keyaki", {"seed": 1}, None, ("bark", "trunk", "wood"), (0.8, 1.6), (1.0, -1.3, 0.1)),
    "fig_bark": ("roots", {"seed": 1}, None, None, (0.8, 1.8), (1.0, -1.25, 0.2)),
}


def shoot(name, out_dir, width, height, samples, tag):
    gen, values, hosts_fn, words, (z0, z1), direction = SHOTS[name]
    RS.reset()
    hosts = [hosts_fn()] if hosts_fn else None
    plant, hosts = RS.grow(gen, values=values, hosts=hosts)
    host_objs = RS.host_objects(hosts)
    RS.plant_materials(plant)
    RS.studio(plant + list(host_objs))
    pts = verts(plant, words) or verts(plant, None)
    lo, hi = RS.bounds(plant)
    target = pick(pts, direction, z0, z1, (lo + hi) / 2)
    aim(target, direction)
    path = os.path.join(out_dir, "render_%s_%s.png" % (name, tag))
    var, cov = RS.render(path, width, height, samples, plant)
    print("%s: %s (variance %.4f, plant %.0f%% of the pixels, target %s)" % (
        name, path, var, 100 * cov, tuple(round(v, 2) for v in target)), flush=True)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--tag", required=True, help="before | after (file name suffix)")
    ap.add_argument("--addon", default=None, help="blender_addon/ folder to import banyan from")
    ap.add_argument("--only", nargs="*", default=None)
    ap.add_argument("--size", default="480x360")
    ap.add_argument("--samples", type=int, default=32)
    ap.add_argument("--texture-size", type=int, default=1024)
    ap.add_argument("--out", default=OUT)
    a = ap.parse_args(RS.script_args())
    if a.addon:
        sys.path.insert(0, os.path.abspath(a.addon))
    api = RS.import_banyan()
    try:  # this add-on's texture size (an add-on preference when registered)
        from banyan.engine import materials
        materials.FALLBACK_SIZE = a.texture_size
    except ImportError:
        pass  # the "before" add-on (flat colours)
    print("banyan from %s, library %s" % (os.path.dirname(api.__file__), os.environ.get("BANYAN_LIB")))
    w, h = (int(v) for v in a.size.split("x"))
    for name in a.only or SHOTS:
        if "season" in SHOTS[name][1] and a.tag == "before":
            continue  # the "before" add-on has no seasons
        shoot(name, a.out, w, h, a.samples, a.tag)


main()
