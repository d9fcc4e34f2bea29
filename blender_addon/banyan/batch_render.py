"""Renders of the batch runner (batch_run.py), inside Blender only.

A fixed camera frames the plant's bounding sphere from the front-right,
a little above (50 mm lens, the same direction for every seed), so the
same mesh gives the same picture; Workbench (studio light, one flat
colour) or EEVEE (a sun and a grey world). The render metadata that
would differ between runs (date, time, render time, host...) is turned
off, so the PNG depends only on the mesh, the engine and the size.
"""
import math

import bpy
from mathutils import Vector

from .engine.build_mesh import fill_mesh

_NAME = "banyan_batch"
VIEW = Vector((1.0, -1.6, 0.9)).normalized()  # from the plant's centre towards the camera
LENS_MM, SENSOR_MM = 50.0, 36.0
PLANT_RGB = (0.08, 0.14, 0.05)  # dark on a light grey: thin young trees stay visible at 64 px


def _engine_id(engine):
    items = {e.identifier for e in bpy.types.RenderSettings.bl_rna.properties["engine"].enum_items}
    if engine == "WORKBENCH":
        return "BLENDER_WORKBENCH"
    # EEVEE's id: BLENDER_EEVEE (3.4 - 4.1, 5.0+), BLENDER_EEVEE_NEXT (4.2 - 4.5).
    for e in ("BLENDER_EEVEE_NEXT", "BLENDER_EEVEE"):
        if e in items:
            return e
    raise RuntimeError("this Blender has no EEVEE (engines: %s)" % ", ".join(sorted(items)))


def _clear(scene):
    for obj in list(scene.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    for me in list(bpy.data.meshes):
        if me.users == 0:
            bpy.data.meshes.remove(me)
    for coll in (bpy.data.cameras, bpy.data.lights, bpy.data.materials):
        for block in list(coll):
            if block.users == 0:
                coll.remove(block)


def _bounds(d):
    p = d.positions
    o = d.origin
    lo = [min(p[i::3]) + o[i] for i in range(3)]
    hi = [max(p[i::3]) + o[i] for i in range(3)]
    return Vector(lo), Vector(hi)


def _setup(scene, engine, size):
    r = scene.render
    r.engine = _engine_id(engine)
    r.resolution_x = r.resolution_y = size
    r.resolution_percentage = 100
    r.film_transparent = False
    r.image_settings.file_format = 'PNG'
    r.image_settings.color_mode = 'RGB'
    r.image_settings.color_depth = '8'
    for attr in dir(r):
        if attr.startswith("use_stamp"):
            try:
                setattr(r, attr, False)
            except (AttributeError, TypeError):
                pass
    scene.view_settings.view_transform = 'Standard'
    scene.view_settings.look = 'None'
    if engine == "WORKBENCH":
        sh = scene.display.shading
        sh.light = 'STUDIO'
        sh.color_type = 'SINGLE'
        sh.single_color = PLANT_RGB
        sh.show_shadows = False
        sh.show_cavity = False
    world = scene.world or bpy.data.worlds.new(_NAME)
    scene.world = world
    world.use_nodes = False
    world.color = (0.6, 0.65, 0.7)  # Workbench's render background too
    if engine != "WORKBENCH":
        if hasattr(scene, "eevee") and hasattr(scene.eevee, "taa_render_samples"):
            scene.eevee.taa_render_samples = 4


def render(d, path, size=64, engine="WORKBENCH"):
    """Renders MeshData d (world = d.origin + positions) into the PNG at
    path (written as is: the caller renames it into place)."""
    scene = bpy.context.scene
    _clear(scene)
    _setup(scene, engine, size)
    me = bpy.data.meshes.new(_NAME)
    fill_mesh(me, d.positions, d.indices, smooth=True)
    obj = bpy.data.objects.new(_NAME, me)
    obj.location = d.origin
    scene.collection.objects.link(obj)
    if engine != "WORKBENCH":
        mat = bpy.data.materials.new(_NAME)
        mat.diffuse_color = PLANT_RGB + (1.0,)
        mat.use_nodes = True
        bsdf = mat.node_tree.nodes.get("Principled BSDF")
        if bsdf is not None:
            bsdf.inputs["Base Color"].default_value = PLANT_RGB + (1.0,)
        me.materials.append(mat)
        sun = bpy.data.objects.new(_NAME + "_sun", bpy.data.lights.new(_NAME + "_sun", 'SUN'))
        sun.data.energy = 3.0
        sun.rotation_euler = (math.radians(40), 0.0, math.radians(30))
        scene.collection.objects.link(sun)
    lo, hi = _bounds(d)
    centre = (lo + hi) * 0.5
    radius = max((hi - lo).length * 0.5, 1e-3)
    half_fov = math.atan(SENSOR_MM * 0.5 / LENS_MM)
    dist = radius / math.sin(half_fov) * 1.02
    cam_data = bpy.data.cameras.new(_NAME)
    cam_data.lens = LENS_MM
    cam_data.sensor_width = SENSOR_MM
    cam_data.sensor_fit = 'HORIZONTAL'
    cam_data.clip_start = max(dist - radius * 1.5, dist * 1e-3)
    cam_data.clip_end = dist + radius * 1.5
    cam = bpy.data.objects.new(_NAME + "_camera", cam_data)
    cam.location = centre + VIEW * dist
    cam.rotation_euler = (centre - cam.location).to_track_quat('-Z', 'Y').to_euler()
    scene.collection.objects.link(cam)
    scene.camera = cam
    bpy.ops.render.render(write_still=False)
    bpy.data.images["Render Result"].save_render(path, scene=scene)
