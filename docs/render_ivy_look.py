"""The ivy of presets/ivy_wall.json (a 3 m x 3 m wall, its front face at
y = 0 looking along -y, the ivy from its bottom centre) and
presets/ivy_pillar.json, for docs/ivy.md's before/after pictures:

    bash tools/render_docs.sh ivy -- --tag after --values '{"t0": 20}'

writes docs/img/ivy/look_<tag>_front.png (the whole wall front-on from
10 m: density, fan, stripes), _close.png (0.7 m from the wall at 1.2 m
height, 30 degrees off its normal: leaves standing off the wall and their
tilt), _stems.png (the front view with leaves = 0: the stem architecture)
_foot.png (the lower half of the wall from 3 m, 15 degrees off its
normal, leaves = 0: the trunks at the foot), _base.png (the same view in
leaf: do the trunks show between the leaves) and _pillar.png (ivy_pillar from 5 m: the cap, the wall top and the stems
hanging past them). The front view also prints how its clumps read from
10 m: the coefficient of variation of the picture's mean luminance over
the wall face's 0.5 m and 1 m cells (each cell the pixel rectangle its
corners project to). --preset grows that preset instead of ivy_wall for the
wall views (the pillar view keeps ivy_pillar), --values merges params into
every view, --views picks some views, --size, --samples, --out.

Leaves at 640 x 400 make a noisy, detailed picture whose RGB PNG runs to
400-500 KB; the written PNG is therefore cut to a 256-colour palette
(median cut, no dithering: the same picture gives the same bytes), about
half the size and indistinguishable by eye. --colors 0 keeps RGB."""
import argparse
import json
import math
import os
import struct
import sys
import zlib

import bpy
import numpy as np
from bpy_extras.object_utils import world_to_camera_view
from mathutils import Vector

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import render_scene as RS  # noqa: E402

_A = math.radians(30)  # the close-up's angle off the wall's normal
# name: (preset or None for the wall preset, extra params, target, direction (target to camera),
#        distance in m, lens in mm).
VIEWS = {
    "front": (None, {}, (0.0, 0.0, 1.45), (0.0, -1.0, 0.12), 10.0, 60.0),
    "close": (None, {}, (0.0, -0.03, 1.2), (math.sin(_A), -math.cos(_A), 0.08), 0.7, 35.0),
    "stems": (None, {"leaves": 0}, (0.0, 0.0, 1.45), (0.0, -1.0, 0.12), 10.0, 60.0),
    "foot": (None, {"leaves": 0}, (0.0, 0.0, 0.75), (math.sin(_A / 2), -math.cos(_A / 2), 0.25), 3.0, 35.0),
    "base": (None, {}, (0.0, 0.0, 0.75), (math.sin(_A / 2), -math.cos(_A / 2), 0.25), 3.0, 35.0),
    "pillar": ("ivy_pillar", {}, (0.6, -0.3, 1.2), (0.55, -1.0, 0.32), 5.0, 32.0),
}


def _chunk(tag, data):
    return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data) & 0xffffffff)


def _median_cut(px, n):
    """Palette indices and palette (at most n colours) for px (N x 3
    uint8): the box with the largest channel range x pixel count is split
    at its median until there are n boxes; a box's colour is its mean."""
    def box(ids):
        c = px[ids]
        span = c.max(0).astype(int) - c.min(0)
        return (int(span.max()) * len(ids) if len(ids) > 1 else -1, int(span.argmax()), ids)
    boxes = [box(np.arange(len(px)))]
    while len(boxes) < n:
        i = max(range(len(boxes)), key=lambda k: boxes[k][0])
        key, ch, ids = boxes[i]
        if key <= 0:
            break
        order = ids[np.argsort(px[ids, ch], kind="stable")]
        boxes[i:i + 1] = [box(order[:len(order) // 2]), box(order[len(order) // 2:])]
    idx = np.empty(len(px), np.uint8)
    pal = np.zeros((len(boxes), 3), np.uint8)
    for i, (_, _, ids) in enumerate(boxes):
        idx[ids] = i
        pal[i] = np.rint(px[ids].mean(0))
    return idx, pal


def palette_png(path, colors=256):
    """Rewrites the 8-bit RGB PNG at path as a palette PNG."""
    img = bpy.data.images.load(path, check_existing=False)
    try:
        w, h = img.size
        px = np.empty(w * h * 4, np.float32)
        img.pixels.foreach_get(px)  # byte images: the stored values / 255, rows bottom up
    finally:
        bpy.data.images.remove(img)
    rgb = np.rint(px.reshape(h, w, 4)[::-1, :, :3] * 255).astype(np.uint8)
    idx, pal = _median_cut(rgb.reshape(-1, 3), colors)
    rows = np.hstack([np.zeros((h, 1), np.uint8), idx.reshape(h, w)])  # filter type 0 per row
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + _chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 3, 0, 0, 0))
                + _chunk(b"PLTE", pal.tobytes()) + _chunk(b"IDAT", zlib.compress(rows.tobytes(), 9))
                + _chunk(b"IEND", b""))


def face_cell_cv(path, cam, face, cell):
    """Coefficient of variation of the mean luminance (of the stored
    values) over the cells of side `cell` of the wall face
    face = (x0, x1, z0, z1) at y = 0, each cell the pixel rectangle its
    corners project to."""
    img = bpy.data.images.load(path, check_existing=False)
    try:
        w, h = img.size
        px = np.empty(w * h * 4, np.float32)
        img.pixels.foreach_get(px)
    finally:
        bpy.data.images.remove(img)
    px = px.reshape(h, w, 4)  # rows bottom up, as camera-view y
    lum = px[..., :3] @ np.array([0.2126, 0.7152, 0.0722], np.float32)
    sc = bpy.context.scene
    x0, x1, z0, z1 = face
    means = []
    for i in range(int(round((x1 - x0) / cell))):
        for k in range(int(round((z1 - z0) / cell))):
            a = world_to_camera_view(sc, cam, Vector((x0 + i * cell, 0.0, z0 + k * cell)))
            b = world_to_camera_view(sc, cam, Vector((x0 + (i + 1) * cell, 0.0, z0 + (k + 1) * cell)))
            c0, c1 = sorted((int(a.x * w), int(b.x * w)))
            r0, r1 = sorted((int(a.y * h), int(b.y * h)))
            if c1 > c0 and r1 > r0:
                means.append(float(lum[r0:r1, c0:c1].mean()))
    m = np.array(means)
    return float(m.std() / m.mean()) if len(m) and m.mean() > 0 else 0.0


def main():
    ap = argparse.ArgumentParser(prog="render_ivy_look.py")
    ap.add_argument("--tag", default="before")
    ap.add_argument("--preset", default=None, help="the wall views' preset (default ivy_wall)")
    ap.add_argument("--values", default="{}", help="params as JSON, e.g. {\"t0\": 20}")
    ap.add_argument("--views", default=",".join(VIEWS), help="comma-separated, of %s" % ", ".join(VIEWS))
    ap.add_argument("--size", default="640x400")
    ap.add_argument("--samples", type=int, default=8)
    ap.add_argument("--colors", type=int, default=256, help="palette size of the PNG (0: RGB)")
    ap.add_argument("--out", default=os.path.join(RS.REPO, "docs", "img", "ivy"))
    a = ap.parse_args(RS.script_args())
    w, h = (int(v) for v in a.size.split("x"))
    values = json.loads(a.values)
    for name in a.views.split(","):
        preset, extra, target, direction, dist, lens = VIEWS[name]
        RS.reset()
        plant, hosts = RS.grow("ivy", preset=preset or a.preset or "ivy_wall", values=dict(values, **extra))
        hosts = RS.host_objects(hosts)
        RS.plant_materials(plant)
        RS.studio(plant + hosts)
        cam = RS.frame_camera(plant + hosts, direction, w, h)
        d = Vector(direction).normalized()
        cam.location = Vector(target) + d * dist
        cam.rotation_euler = (-d).to_track_quat('-Z', 'Y').to_euler()
        cam.data.lens = lens
        cam.data.clip_start = 0.01
        tag = a.tag if not a.preset else "%s_%s" % (a.preset, a.tag)
        path = os.path.join(a.out, "look_%s_%s.png" % (tag, name))
        RS.render(path, w, h, a.samples, plant)
        if name == "front" and not (a.preset and a.preset != "ivy_wall"):
            face = (-1.5, 1.5, 0.0, 3.0)  # ivy_wall's front face
            print("front: luminance CV over the face's 0.5 m cells %.3f, 1 m cells %.3f"
                  % (face_cell_cv(path, cam, face, 0.5), face_cell_cv(path, cam, face, 1.0)))
        if a.colors:
            palette_png(path, min(a.colors, 256))


if __name__ == "__main__":  # docs/render_keyaki_look.py imports palette_png
    main()
