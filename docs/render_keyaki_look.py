"""The keyaki of presets/keyaki_mature.json, keyaki_young.json and
avenue_boulevard.json as a person sees them, for docs/keyaki.md's
before/after pictures:

    bash tools/render_docs.sh keyaki -- --tag after

writes docs/img/keyaki/look_<tag>_<view>.png:
  under   keyaki_mature from under its crown: eye 1.6 m high, 2 m from the
          trunk, an 18 mm lens pitched 40 degrees up (the trunk's split
          into limbs, the limbs, the twigs and the leaves against the sky);
  tree    keyaki_mature from 20 m at eye height, the whole tree in frame;
  avenue  the avenue preset (--avenue, default avenue_street) at eye
          height looking along it: from the street between its rows, or,
          for one row (avenue_street), from 7 m to its side. Another preset
          than avenue_street names the file look_<tag>_avenue_<preset
          without "avenue_">.png (e.g. _avenue_boulevard.png). The default
          is the street because the 100-tree boulevard is too heavy here
          once the trees carry ~30,000 leaves each: 6.6 M faces (leaves
          only, no twigs) took 2 min 11 s and 7.1 GB in Blender 3.4 on
          this 2-core machine, against 25 s and 1.5 GB for 1.2 M faces
          of 0.5 m spray cards;
  young   keyaki_young from 10 m at eye height (it must not read as a
          lollipop);
  silhouette  the tree view in black against a white sky, no ground: what
          the crown hides (wood and leaf texels passing the alpha cutoff);
  above   the avenue view's preset from above: 25 m over its crowns,
          pitched 55 degrees down onto its middle, a 24 mm lens (canopy
          or bark from above).
--values merges params into the keyaki views, --avenue-values into the
avenue view (its keys as the avenue takes them, e.g. "tree.leaf_density"),
--views picks some views, --size, --samples, --out, --colors (palette
size; 0 keeps RGB; the PNG is cut to a palette as docs/render_ivy_look.py
does). The trees stand at the origin (the avenue starts there and runs
along +x), their feet on the ground plane at z = 0."""
import argparse
import json
import math
import os
import sys
import time

import bpy
import numpy as np
from mathutils import Vector

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import render_scene as RS  # noqa: E402
from render_ivy_look import palette_png  # noqa: E402

# name: (generator, preset or None for --avenue, eye (m), how the camera looks, lens in mm or None).
# Look: ("at", target) aims at a point; ("pitch", yaw deg, pitch deg) turns from +x; ("fit", None) aims at
# the plant's bounds centre and picks the lens that frames them.
_Y = math.radians(-52)  # the horizontal direction the whole-tree views come from (RS.VIEWS["keyaki"]'s)


def under(side, turn, pitch):
    """The under view's eye and look: standing 2 m from the trunk at `side` degrees round it (from +x), 1.6 m
    high, facing the trunk turned by `turn` degrees, pitched up by `pitch`."""
    a = math.radians(side)
    return (2.0 * math.cos(a), 2.0 * math.sin(a), 1.6), ("pitch", side + 180 - turn, pitch)


VIEWS = {
    "under": ("keyaki", "keyaki_mature") + under(-142, 25, 45) + (18.0,),
    "tree": ("keyaki", "keyaki_mature", (20.0 * math.cos(_Y), 20.0 * math.sin(_Y), 1.6), ("fit", None), None),
    "avenue": ("avenue", None, (-6.0, 0.0, 1.6), ("pitch", 0.0, 9.0), 20.0),
    "young": ("keyaki", "keyaki_young", (10.0 * math.cos(_Y), 10.0 * math.sin(_Y), 1.6), ("fit", None), None),
    "silhouette": ("keyaki", "keyaki_mature", (20.0 * math.cos(_Y), 20.0 * math.sin(_Y), 1.6), ("fit", None), None),
    "above": ("avenue", None, None, ("pitch", 90.0, -55.0), 24.0),  # eye: above_eye(), from the grown avenue
}


def above_eye(plant):
    """The above view's eye: 25 m above the crowns and 17.5 m to the side
    of the middle of the plant's bounds, so that the view, pitched 55
    degrees down, centres on it."""
    lo, hi = RS.bounds(plant)
    c = (lo + hi) / 2
    return (c.x, c.y - 25.0 / math.tan(math.radians(55.0)) - 0.5 * (hi.z - lo.z) / math.tan(math.radians(55.0)),
            hi.z + 25.0)


def silhouette(plant, ground):
    """The scene as a silhouette: the plant's materials black and without
    gloss (their alpha kept), no sun, no ground, a uniform white sky."""
    sc = bpy.context.scene
    ground.hide_render = True
    for o in sc.objects:
        if o.type == 'LIGHT':
            o.data.energy = 0.0
    bg = sc.world.node_tree.nodes["Background"]
    for ln in list(bg.inputs["Color"].links):
        sc.world.node_tree.links.remove(ln)
    bg.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    bg.inputs["Strength"].default_value = 1.0  # white, rendered with the Standard view transform
    for m in {s.material for o in plant if o.type == 'MESH' for s in o.material_slots if s.material}:
        for n in m.node_tree.nodes if m.node_tree else ():
            if n.bl_idname != "ShaderNodeBsdfPrincipled":
                continue
            for name, v in (("Base Color", (0.0, 0.0, 0.0, 1.0)), ("Specular", 0.0), ("Specular IOR Level", 0.0),
                            ("Subsurface Weight", 0.0), ("Subsurface", 0.0), ("Transmission Weight", 0.0),
                            ("Emission Strength", 0.0)):
                i = n.inputs.get(name)
                if i is not None:
                    for ln in list(i.links):
                        m.node_tree.links.remove(ln)
                    i.default_value = v
        for n in list(m.node_tree.nodes) if m.node_tree else ():
            if n.bl_idname in ("ShaderNodeBsdfTranslucent", "ShaderNodeBsdfTransparent") and n.outputs[0].links:
                # a translucency mix lets light through a leaf: make that branch black too
                if n.bl_idname == "ShaderNodeBsdfTranslucent":
                    n.inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
                    for ln in list(n.inputs["Color"].links):
                        m.node_tree.links.remove(ln)


def camera(eye, look, lens, plant, w, h, margin=1.08):
    sc = bpy.context.scene
    cam = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    sc.collection.objects.link(cam)
    sc.camera = cam
    cam.data.sensor_fit = 'AUTO'
    eye = Vector(eye)
    kind, arg = look[0], look[1:]
    if kind == "pitch":
        yaw, pitch = (math.radians(v) for v in arg)
        d = Vector((math.cos(yaw) * math.cos(pitch), math.sin(yaw) * math.cos(pitch), math.sin(pitch)))
    else:
        lo, hi = RS.bounds(plant)
        d = ((lo + hi) / 2 - eye).normalized()
    cam.location = eye
    cam.rotation_euler = d.to_track_quat('-Z', 'Y').to_euler()
    if lens is None:
        # The shortest lens that shows every vertex of the plant (its bounds' corners would leave it small: the
        # near corners of a crown's box stand far closer than the crown), with a margin.
        rot = cam.rotation_euler.to_matrix()
        axes = np.array([rot.col[0], rot.col[1], d])
        need = 0.0
        for o in plant:
            if o.type != 'MESH':
                continue
            co = np.empty(3 * len(o.data.vertices), np.float32)
            o.data.vertices.foreach_get("co", co)
            mw = np.array(o.matrix_world)
            q = co.reshape(-1, 3) @ mw[:3, :3].T + mw[:3, 3] - np.array(eye)
            q = q @ axes.T  # right, up, forward
            q = q[q[:, 2] > 0.1]
            sx, sy = np.abs(q[:, 0]) / q[:, 2], np.abs(q[:, 1]) / q[:, 2]
            # the sensor's width covers the longer image side
            need = max(need, float(sx.max()) * margin * (1 if w >= h else h / w),
                       float(sy.max()) * margin * (w / h if w >= h else 1))
        lens = cam.data.sensor_width / (2 * need)
    cam.data.lens = lens
    cam.data.clip_start = 0.05
    cam.data.clip_end = 5000
    return cam


def main():
    ap = argparse.ArgumentParser(prog="render_keyaki_look.py")
    ap.add_argument("--tag", default="before")
    ap.add_argument("--avenue", default="avenue_street", help="the avenue view's preset")
    ap.add_argument("--values", default="{}", help="keyaki params as JSON, e.g. {\"leaf_density\": 28}")
    ap.add_argument("--avenue-values", default="{}", help="avenue params as JSON")
    ap.add_argument("--views", default=",".join(VIEWS), help="comma-separated, of %s" % ", ".join(VIEWS))
    ap.add_argument("--under", default=None, help="the under view's side,turn,pitch in degrees (default -142,25,45)")
    ap.add_argument("--size", default="640x400")
    ap.add_argument("--samples", type=int, default=8)
    ap.add_argument("--colors", type=int, default=256, help="palette size of the PNG (0: RGB)")
    ap.add_argument("--out", default=os.path.join(RS.REPO, "docs", "img", "keyaki"))
    a = ap.parse_args(RS.script_args())
    w, h = (int(v) for v in a.size.split("x"))
    if a.under:
        VIEWS["under"] = VIEWS["under"][:2] + under(*(float(v) for v in a.under.split(","))) + VIEWS["under"][4:]
    for name in a.views.split(","):
        gen, preset, eye, look, lens = VIEWS[name]
        values = json.loads(a.avenue_values if gen == "avenue" else a.values)
        if name == "avenue" and RS.import_banyan().make_params("avenue", preset=a.avenue, values=values).get("rows") < 2:
            # One row (avenue_street) stands on the view's line: stand 7 m to its side, turned 20 degrees to it.
            eye, look = (eye[0], eye[1] - 7.0, eye[2]), (look[0], look[1] + 20.0, look[2])
        t0 = time.perf_counter()
        RS.reset()
        plant, _ = RS.grow(gen, preset=preset or a.avenue, values=values)
        t1 = time.perf_counter()
        RS.plant_materials(plant)
        ground = RS.studio(plant)
        if name == "silhouette":
            silhouette(plant, ground)
        if name == "above":
            eye = above_eye(plant)
        camera(eye, look, lens, plant, w, h)
        if gen == "avenue" and a.avenue != "avenue_street":
            name += "_" + a.avenue.replace("avenue_", "")
        path = os.path.join(a.out, "look_%s_%s.png" % (a.tag, name))
        RS.render(path, w, h, a.samples, plant, view_transform='Standard' if name == "silhouette" else 'Filmic')
        if a.colors:
            palette_png(path, min(a.colors, 256))
        tris = sum(len(o.data.polygons) for o in plant if o.type == 'MESH')
        print("render_keyaki_look: %s: %s, %d faces, grown in %.1f s, rendered in %.1f s"
              % (path, preset or a.avenue, tris, t1 - t0, time.perf_counter() - t1), flush=True)


if __name__ == "__main__":  # docs/render_production.py imports camera
    main()
