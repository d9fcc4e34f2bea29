"""Renders the pictures of docs/getting-started.md into docs/img/start/:

    blender -b --factory-startup --addons banyan --python docs/render_getting_started.py

(or `bash tools/render_docs.sh start`). Blender cannot screenshot its UI
headless, so these are renders of the scene the guide produces, from the
default camera: Blender's default scene, the same scene after the guide's
three clicks (the default cube selected, Add > Mesh > Banyan > Add
Strangler Roots, run here as the same operator with its defaults), and
after the guide's tweak in the operator's redo panel (Growth Points 15,
run here as the operator with that value, which is what the panel does).
They are Workbench renders, which draw what the viewport's Solid shading
draws.
"""
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import render_scene as RS  # noqa: E402

OUT = os.path.join(RS.REPO, "docs", "img", "start")
W, H = 360, 270


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


def main():
    os.makedirs(OUT, exist_ok=True)
    bpy.ops.wm.read_homefile(use_factory_startup=True)  # the scene a new Blender opens with
    solid(os.path.join(OUT, "1_default_scene.png"))
    cube = bpy.data.objects["Cube"]
    assert cube.select_get() and bpy.context.view_layer.objects.active == cube
    before = set(bpy.data.objects)
    if bpy.ops.mesh.banyan_roots() != {'FINISHED'}:  # Add > Mesh > Banyan > Add Strangler Roots
        raise SystemExit("render_getting_started: the roots operator failed")
    solid(os.path.join(OUT, "2_roots.png"))
    # The redo panel: undo, then run again with the changed value.
    for o in set(bpy.data.objects) - before:
        bpy.data.objects.remove(o)
    cube.select_set(True)
    bpy.context.view_layer.objects.active = cube
    if bpy.ops.mesh.banyan_roots(growth_points=15) != {'FINISHED'}:
        raise SystemExit("render_getting_started: the roots operator failed with growth_points = 15")
    solid(os.path.join(OUT, "3_roots_15_points.png"))


main()
