"""Renders the EEVEE / Cycles pictures of docs/materials.md ("EEVEE and
Cycles"): keyaki_young seen from 10 m in the shared scene of
docs/render_scene.py, once per engine, into
docs/img/materials/eevee_<engine>_<tag>.png (engine: eevee, cycles):

    BANYAN_LIB=<lib> blender -b --factory-startup --python docs/render_eevee.py -- \\
        --tag after [--addon DIR] [--size 360x360] [--samples 32]

--addon is the blender_addon/ folder to use (default this repository's):
"before" is made with the add-on of a commit whose leaf alpha is read
through mipmaps. Each picture prints the share of the frame the leaves
cover, measured on a second render with a transparent film and the bark
and ground held out (the figure tests/blender/test_eevee_coverage.py
compares). Fixed samples and seed, no denoiser.
"""
import argparse
import os
import sys

import bpy
from mathutils import Vector

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import render_scene as RS  # noqa: E402

OUT = os.path.join(RS.REPO, "docs", "img", "materials")
DISTANCE = 10.0  # metres from the middle of the tree's bounds


def eevee_engine():
    return 'BLENDER_EEVEE_NEXT' if (4, 2, 0) <= bpy.app.version < (5, 0, 0) else 'BLENDER_EEVEE'


def set_engine(engine, samples):
    sc = bpy.context.scene
    sc.render.engine = engine
    if engine != 'CYCLES':
        sc.eevee.taa_render_samples = samples


def leaf_coverage(plant, engine, samples, path):
    """The film's mean alpha with everything but the leaves held out."""
    from banyan.engine import materials as MAT
    from banyan.core import textures as T
    sc = bpy.context.scene
    hold = bpy.data.materials.new("Holdout")
    if bpy.app.version < (5, 0, 0):
        hold.use_nodes = True
    nt = hold.node_tree
    nt.nodes.clear()
    nt.links.new(nt.nodes.new("ShaderNodeHoldout").outputs[0],
                 nt.nodes.new("ShaderNodeOutputMaterial").inputs["Surface"])
    saved = []
    for o in sc.objects:
        if o.type != 'MESH':
            continue
        for slot in o.material_slots:
            m = slot.material
            if not (o in plant and MAT.is_shared(m) and int(m[MAT.PROP].split("/")[0]) in T.LEAVES):
                saved.append((slot, m))
                slot.material = hold
    sc.render.film_transparent = True
    sc.render.image_settings.color_mode = 'RGBA'
    sc.render.use_compositing = False
    sc.render.filepath = path
    bpy.ops.render.render(write_still=True)
    img = bpy.data.images.load(path, check_existing=False)
    a = img.pixels[:][3::4]
    bpy.data.images.remove(img)
    os.remove(path)
    for slot, m in saved:
        slot.material = m
    sc.render.film_transparent = False
    sc.render.image_settings.color_mode = 'RGB'
    return sum(a) / len(a)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--tag", required=True, help="before | after (file name suffix)")
    ap.add_argument("--addon", default=None, help="blender_addon/ folder to import banyan from")
    ap.add_argument("--size", default="360x360")
    ap.add_argument("--samples", type=int, default=32)
    ap.add_argument("--out", default=OUT)
    a = ap.parse_args(RS.script_args())
    if a.addon:
        sys.path.insert(0, os.path.abspath(a.addon))
    api = RS.import_banyan()
    import banyan
    try:  # the API records plants on registered properties
        banyan.register()
    except (ValueError, RuntimeError):
        pass  # already registered (an installed add-on)
    print("banyan from %s, library %s" % (os.path.dirname(api.__file__), os.environ.get("BANYAN_LIB")))
    w, h = (int(v) for v in a.size.split("x"))
    RS.reset()
    plant, _ = RS.grow("keyaki", preset="keyaki_young")
    RS.studio(plant)
    lo, hi = RS.bounds(plant)
    sc = bpy.context.scene
    cam = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    sc.collection.objects.link(cam)
    sc.camera = cam
    cam.data.lens = 35.0
    d = Vector(RS.VIEWS["keyaki"]).normalized()
    cam.location = (lo + hi) / 2 + d * DISTANCE
    cam.rotation_euler = (-d).to_track_quat('-Z', 'Y').to_euler()
    os.makedirs(a.out, exist_ok=True)
    for engine, label in (('CYCLES', "cycles"), (eevee_engine(), "eevee")):
        RS.settings(w, h, a.samples)  # Cycles' settings, the colour management, the PNG format
        set_engine(engine, a.samples)
        path = os.path.join(a.out, "eevee_%s_%s.png" % (label, a.tag))
        sc.render.filepath = path
        bpy.ops.render.render(write_still=True)
        RS.strip_png_text(path)
        cov = leaf_coverage(plant, engine, a.samples, os.path.join(a.out, "coverage_tmp.png"))
        print("%s %s: %s (leaves cover %.4f of the frame)" % (engine, a.tag, path, cov), flush=True)


main()
