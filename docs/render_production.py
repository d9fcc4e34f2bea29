"""Production pictures: keyaki_mature's levels of detail side by side, and
keyaki_young's growth animation at three frames, through the add-on
(api.make_lods, the "Banyan Growth" modifier):

    bash tools/render_docs.sh production

writes docs/img/production/:
  lod_<distance>m.png   LOD0 (the tree), 0.5, 0.15 and the billboard
                        (vertical cards and a top card), each from <distance> m at eye height
                        (the same camera for all four; the first distance
                        frames the tree, the others keep its lens), one
                        image per distance, the levels left to right;
  growth.png            keyaki_young at 30 %, 60 % and 100 % of its growth
                        (frames of the growth modifier), from 10 m.
--distances, --size (of one panel), --samples, --out."""
import argparse
import math
import os
import sys
import time

import bpy
from mathutils import Vector

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import render_scene as RS  # noqa: E402
from render_ivy_look import palette_png  # noqa: E402
from render_keyaki_look import camera  # noqa: E402

_Y = math.radians(-52)  # the whole-tree views' direction, as render_keyaki_look's


def panels(paths, out):
    """Pastes equal-sized PNGs left to right into one."""
    imgs = [bpy.data.images.load(p) for p in paths]
    w, h = imgs[0].size
    big = bpy.data.images.new("panels", w * len(imgs), h, alpha=False)
    px = [0.0] * (w * len(imgs) * h * 4)
    for k, im in enumerate(imgs):
        src = list(im.pixels)
        for y in range(h):
            row = (y * w * len(imgs) + k * w) * 4
            px[row:row + w * 4] = src[y * w * 4:(y + 1) * w * 4]
    big.pixels = px
    big.filepath_raw = out
    big.file_format = 'PNG'
    big.save()
    for im in imgs:
        bpy.data.images.remove(im)
    bpy.data.images.remove(big)
    for p in paths:
        os.remove(p)


def solo(objs, keep):
    for o in objs:
        o.hide_render = o is not keep


def render_lods(a, w, h):
    api = RS.import_banyan()
    RS.reset()
    # Through the operator: make_lods grows a recorded plant again from its parameters.
    bpy.ops.mesh.banyan_keyaki_tree(banyan_preset="keyaki_mature")
    plant = [o for o in bpy.context.scene.objects if o.type == 'MESH']
    RS.plant_materials(plant)
    t0 = time.perf_counter()
    levels = api.make_lods(plant[0], ratios=(0.5, 0.15), billboard=True, billboard_size=512)
    print("render_production: LODs made in %.1f s: %s" % (
        time.perf_counter() - t0, ", ".join("%s %d faces" % (o.name, len(o.data.polygons)) for o in levels)))
    for o in levels[1:]:  # the levels stand where the tree stands
        o.location = plant[0].location
    RS.studio(levels)
    lens = None
    for d in (float(v) for v in a.distances.split(",")):
        eye = (d * math.cos(_Y), d * math.sin(_Y), 1.6)
        # The first distance frames the tree; the others keep its lens, so the tree shrinks as it would.
        lens = camera(eye, ("fit", None), lens, [levels[0]], w, h).data.lens
        paths = []
        for k, o in enumerate(levels):
            solo(list(plant) + list(levels), o)
            p = os.path.join(a.out, "_lod%d.png" % k)
            RS.render(p, w, h, a.samples, [o])
            paths.append(p)
        out = os.path.join(a.out, "lod_%dm.png" % d)
        panels(paths, out)
        palette_png(out, 256)
        print("render_production: %s" % out, flush=True)


def render_growth(a, w, h):
    api = RS.import_banyan()
    RS.reset()
    objs = api.keyaki_tree(preset="keyaki_young", name="Keyaki", animate=True, frame_start=1, frame_end=100)
    RS.plant_materials(objs)
    RS.studio(objs)
    eye = (10.0 * math.cos(_Y), 10.0 * math.sin(_Y), 1.6)
    sc = bpy.context.scene
    sc.frame_set(100)  # framed on the grown tree (bound boxes are the evaluated mesh's)
    camera(eye, ("fit", None), None, objs, w, h)
    paths = []
    for k, frame in enumerate((30, 60, 100)):
        sc.frame_set(frame)
        p = os.path.join(a.out, "_growth%d.png" % k)
        RS.render(p, w, h, a.samples, objs, min_coverage=0.0005)
        paths.append(p)
    out = os.path.join(a.out, "growth.png")
    panels(paths, out)
    palette_png(out, 256)
    print("render_production: %s" % out, flush=True)


def main():
    ap = argparse.ArgumentParser(prog="render_production.py")
    ap.add_argument("--distances", default="20,60")
    ap.add_argument("--size", default="300x360")
    ap.add_argument("--samples", type=int, default=8)
    ap.add_argument("--views", default="lod,growth")
    ap.add_argument("--out", default=os.path.join(RS.REPO, "docs", "img", "production"))
    a = ap.parse_args(RS.script_args())
    os.makedirs(a.out, exist_ok=True)
    w, h = (int(v) for v in a.size.split("x"))
    if "lod" in a.views:
        render_lods(a, w, h)
    if "growth" in a.views:
        render_growth(a, w, h)


main()
