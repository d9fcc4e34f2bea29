"""Renders the pictures of docs/getting-started.md into docs/img/start/:

    blender -b --factory-startup --addons banyan --python docs/render_getting_started.py

(or `bash tools/render_docs.sh start`). Blender cannot screenshot its UI
headless, so these are renders of the scene the guide produces, from the
default camera: Blender's default scene, the same scene after the guide's
three clicks (the default cube selected, Add > Mesh > Banyan > Add
Strangler Roots, run here as the same operator with its defaults), and
after the guide's tweak in the operator's redo panel (Main roots 12,
run here as the operator with that value, which is what the panel does).
They are Workbench renders, which draw what the viewport's Solid shading
draws.

The figures the guide quotes about those roots (vertices, how high and
how low they reach, how far out from the cube) are measured here too and
written into docs/getting-started.md between its `<!-- figures ... -->`
and `<!-- end figures -->` lines. `--figures` measures and writes them
without rendering; tests/blender/test_getting_started.py measures them
with measure() in a fresh Blender and checks the guide still says them.
"""
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import render_scene as RS  # noqa: E402

OUT = os.path.join(RS.REPO, "docs", "img", "start")
GUIDE = os.path.join(RS.REPO, "docs", "getting-started.md")
W, H = 360, 270
TWEAK = {"main_roots": 12}  # the guide's change in the redo panel: Main roots 12
BEGIN = "<!-- figures: written by docs/render_getting_started.py, do not edit -->"
END = "<!-- end figures -->"


def solid(path):
    """A Workbench render: the viewport's Solid shading, from the scene camera."""
    sc = bpy.context.scene
    sc.render.engine = 'BLENDER_WORKBENCH'
    sh = sc.display.shading
    sh.light = 'STUDIO'
    sh.color_type = 'MATERIAL'
    sh.show_shadows = False
    sh.show_cavity = True
    sc.display.render_aa = '8'
    sc.world.color = (0.05, 0.05, 0.05)  # the viewport's grey
    sc.render.resolution_x, sc.render.resolution_y, sc.render.resolution_percentage = W, H, 100
    sc.render.image_settings.file_format = 'PNG'
    sc.render.image_settings.color_mode = 'RGB'
    sc.render.image_settings.compression = 100
    sc.render.dither_intensity = 0
    for key in dir(sc.render):
        if key.startswith("use_stamp"):
            setattr(sc.render, key, False)
    sc.render.filepath = path
    bpy.ops.render.render(write_still=True)
    RS.strip_png_text(path)
    print("render_getting_started: wrote %s" % path, flush=True)


def grow(**kw):
    """Add > Mesh > Banyan > Add Strangler Roots with the default cube
    selected and active, as the menu runs it: the new objects."""
    cube = bpy.data.objects["Cube"]
    cube.select_set(True)
    bpy.context.view_layer.objects.active = cube
    before = set(bpy.data.objects)
    if bpy.ops.mesh.banyan_roots(**kw) != {'FINISHED'}:
        raise SystemExit("render_getting_started: the roots operator failed with %r" % (kw,))
    return [o for o in bpy.data.objects if o not in before]


def measure(objs):
    """What the guide says about roots around the default cube (2 m, centred
    on the origin): objects, vertices, the highest and lowest root point,
    how far any root stands out from the cube's faces above its foot (0.3 m
    over the ground at z = -1) and how far the foot's roots run out over the
    ground, how many of its four side faces have roots on them."""
    vs = [o.matrix_world @ v.co for o in objs if o.type == 'MESH' for v in o.data.vertices]
    out = max(max(abs(v.x), abs(v.y)) for v in vs if v.z > -0.7) - 1.0
    reach = max(max(abs(v.x), abs(v.y)) for v in vs) - 1.0
    faces = [any(v.x > 1 for v in vs), any(v.x < -1 for v in vs), any(v.y > 1 for v in vs), any(v.y < -1 for v in vs)]
    return {"objects": len(objs), "vertices": len(vs), "top": round(max(v.z for v in vs), 2),
            "bottom": round(min(v.z for v in vs), 2), "out": round(out, 2), "reach": round(reach, 2),
            "faces": sum(faces)}


def figures_text(defaults, tweak):
    """The guide's figures block, from measure() of the defaults and the tweak."""
    d, t = defaults, tweak
    return "\n".join([
        BEGIN,
        "With the defaults the operator makes %d object of %s vertices: roots from"
        % (d["objects"], format(d["vertices"], ",")),
        "z = %.2f m down to z = %.2f m (the cube reaches from z = -1 to 1 m), on %d of"
        % (d["top"], d["bottom"], d["faces"]),
        "its 4 side faces and never more than %.2f m out from them above the foot;" % d["out"],
        "at the foot, buttresses and surface roots run %.2f m out over the ground." % d["reach"],
        "With Main roots 12: %s vertices, on %d faces, at most %.2f m out above the foot."
        % (format(t["vertices"], ","), t["faces"], t["out"]),
        END])


def write_figures(text):
    with open(GUIDE, encoding="utf-8") as f:
        doc = f.read()
    a, b = doc.find(BEGIN), doc.find(END)
    if a < 0 or b < a:
        raise SystemExit("render_getting_started: no figures block in %s" % GUIDE)
    with open(GUIDE, "w", encoding="utf-8") as f:
        f.write(doc[:a] + text + doc[b + len(END):])
    print("render_getting_started: wrote the figures into %s" % GUIDE, flush=True)


def clear(objs):
    for o in objs:
        bpy.data.objects.remove(o)


def main(render=True):
    os.makedirs(OUT, exist_ok=True)
    bpy.ops.wm.read_homefile(use_factory_startup=True)  # the scene a new Blender opens with
    cube = bpy.data.objects["Cube"]
    assert cube.select_get() and bpy.context.view_layer.objects.active == cube
    if render:
        solid(os.path.join(OUT, "1_default_scene.png"))
    objs = grow()  # Add > Mesh > Banyan > Add Strangler Roots
    defaults = measure(objs)
    if render:
        solid(os.path.join(OUT, "2_roots.png"))
    clear(objs)  # the redo panel: undo, then run again with the changed value
    objs = grow(**TWEAK)
    tweak = measure(objs)
    if render:
        solid(os.path.join(OUT, "3_roots_12_main_roots.png"))
    write_figures(figures_text(defaults, tweak))


if __name__ == "__main__":
    main(render="--figures" not in sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else True)
