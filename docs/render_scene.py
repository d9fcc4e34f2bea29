"""The scene every documentation render shares (headless Blender, Cycles
on the CPU): grey hosts (boxes, or a preset's .glb meshes as objects), a
ground plane, a sun and a Nishita sky, a camera framed on the plant's
bounds, and a check that the picture shows the plant. Used by
docs/render_gallery.py, docs/render_params.py, docs/render_hosts.py and
the scripts in docs/examples/.

    import render_scene as RS
    RS.reset()
    plant, hosts = RS.grow("roots", preset="roots_trunk")  # Boxes and objects
    hosts = RS.host_objects(hosts)
    RS.plant_materials(plant)
    RS.studio(plant + hosts)
    RS.frame_camera(plant + hosts, RS.VIEWS["roots"], 320, 240)
    RS.render("out.png", 320, 240, samples=16, plant=plant)

The add-on is imported from blender_addon/ when it is not installed; the
library is found as the add-on finds it (BANYAN_LIB, banyan/lib/, or the
repository's build/). Renders are deterministic: fixed Cycles seed and
samples, no denoiser, no animated seed.
"""
import math
import os
import struct
import sys
import tempfile
from array import array

import bpy
from mathutils import Matrix, Vector

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.normpath(os.path.join(HERE, ".."))

# Camera direction (from the target towards the camera) per generator.
VIEWS = {
    "roots": (1.0, -1.25, 0.7),
    "keyaki": (1.0, -1.3, 0.32),
    "avenue": (-1.0, -0.42, 0.28),  # from beyond the start, down the avenue
    "ivy": (0.45, -1.0, 0.3),        # the walls' front faces look along -y
    "segments": (1.0, -1.25, 0.12),  # low: the thin twigs against the sky
}

PLANT_INDEX = 1  # object pass index of the plant, for the coverage mask


def import_banyan():
    """The add-on's API, installed or from this repository."""
    try:
        import banyan.api  # noqa: F401
    except ImportError:
        sys.path.insert(0, os.path.join(REPO, "blender_addon"))
    import banyan.api as api
    return api


def script_args():
    """The arguments after Blender's `--` (a second `--`, as in
    `tools/render_docs.sh roots -- --tag after`, is dropped)."""
    args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    return args[1:] if args[:1] == ["--"] else args


def reset():
    """An empty scene, nothing left from the last picture."""
    bpy.ops.wm.read_homefile(use_empty=True)
    for coll in (bpy.data.meshes, bpy.data.materials, bpy.data.images, bpy.data.worlds, bpy.data.lights,
                 bpy.data.cameras):
        for block in list(coll):
            if block.users == 0:
                coll.remove(block)


def preset_path(gen, preset):
    from banyan.core import presets
    return presets.find(gen, preset)


def preset_hosts(gen, preset):
    """The hosts of a preset (may be none): its boxes (banyan Box), then,
    for its .glb mesh hosts, new Blender objects made by
    banyan.engine.hosts.objects_from_preset (placed as the library places them)."""
    import json
    from banyan.engine import hosts as H
    from banyan.core import presets
    from banyan.core.params import preset_hosts as hosts_of
    path = presets.find(gen, preset)
    text = presets.read(path)
    if any(isinstance(h, dict) and "mesh" in h for h in json.loads(text).get("hosts") or []):
        objs, boxes = H.objects_from_preset(gen, preset)
        return list(boxes) + objs
    return hosts_of(text, path)


def grow(gen, preset=None, values=None, hosts=None, host_shape='SURFACE'):
    """Builds one plant through banyan.api: (objects, hosts), hosts being
    banyan Boxes and Blender objects (host_objects draws both). Hosts
    come from the preset unless given; roots without any get the CLI's
    default trunk. Objects are grown on as host_shape says ('SURFACE':
    their real surface; boxes stay boxes either way)."""
    api = import_banyan()
    from banyan.core.structs import Box
    values = dict(values or {})
    if hosts is None:
        hosts = preset_hosts(gen, preset) if preset else []
    hosts = list(hosts)
    if gen == "roots":
        if not hosts:
            hosts = [Box.make((0, 0, 4), (0.4, 0.4, 4))]
        objs = api.strangler_roots(hosts=hosts, preset=preset, name="Roots", values=values, host_shape=host_shape)
    elif gen == "keyaki":
        objs = api.keyaki_tree(preset=preset, name="Keyaki", values=values)
    elif gen == "avenue":
        objs = api.keyaki_avenue(preset=preset, merged=True, name="Avenue", values=values)
    elif gen == "ivy":
        objs = api.ivy(hosts=hosts, preset=preset, name="Ivy", values=values, host_shape=host_shape)
    elif gen == "segments":
        objs = api.segment_twigs(preset=preset, name="Segments", values=values)
    else:
        raise ValueError("unknown generator %s" % gen)
    return objs, hosts


def material(name, rgba, rough=0.8):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    b = m.node_tree.nodes["Principled BSDF"]
    b.inputs["Base Color"].default_value = rgba
    b.inputs["Roughness"].default_value = rough
    m.diffuse_color = rgba
    return m


def host_objects(hosts, rgba=(0.45, 0.45, 0.45, 1.0)):
    """The hosts drawn in grey: a box object per banyan Box; Blender
    objects (mesh hosts) as they are, given the grey material and smooth
    shading below 40 degrees (the surface the plant grew on is unchanged)."""
    grey = material("Host", rgba)
    out = []
    faces = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    for i, box in enumerate(hosts):
        if isinstance(box, bpy.types.Object):
            me = box.data
            me.materials.clear()
            me.materials.append(grey)
            me.polygons.foreach_set("use_smooth", array("b", [1]) * len(me.polygons))
            me.use_auto_smooth = True
            me.auto_smooth_angle = math.radians(40)
            out.append(box)
            continue
        me = bpy.data.meshes.new("Host%d" % i)
        h = box.half
        me.from_pydata([(sx * h[0], sy * h[1], sz * h[2]) for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)],
                       [], faces)
        me.materials.append(grey)
        ob = bpy.data.objects.new("Host%d" % i, me)
        r = box.rotation
        rot = Matrix(((r[0], r[1], r[2]), (r[3], r[4], r[5]), (r[6], r[7], r[8]))).to_4x4()
        ob.matrix_world = Matrix.Translation(Vector(box.center)) @ rot
        bpy.context.scene.collection.objects.link(ob)
        out.append(ob)
    return out


def bounds(objs):
    """World-space (lo, hi) corners of the objects' bounding boxes."""
    pts = [o.matrix_world @ Vector(c) for o in objs for c in o.bound_box]
    lo = Vector([min(p[k] for p in pts) for k in range(3)])
    hi = Vector([max(p[k] for p in pts) for k in range(3)])
    return lo, hi


def studio(objs, ground_rgba=(0.11, 0.09, 0.06, 1.0), sun_energy=3.0, sky_strength=0.6):
    """Ground plane at z = 0 (the generators' ground) reaching well beyond
    the objects, a sun, and a sky: a gradient from a pale horizon to a
    blue zenith (simple, and less noisy to sample than a physical sky)."""
    sc = bpy.context.scene
    lo, hi = bounds(objs)
    size = max(hi.x - lo.x, hi.y - lo.y, hi.z - lo.z, 10.0) * 200  # its far edge is the horizon
    bpy.ops.mesh.primitive_plane_add(size=size, location=((lo.x + hi.x) / 2, (lo.y + hi.y) / 2, 0))
    ground = bpy.context.active_object
    ground.name = "Ground"
    ground.data.materials.append(material("Ground", ground_rgba, 1.0))
    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", 'SUN'))
    sun.data.energy = sun_energy
    sun.data.angle = math.radians(3)
    sun.rotation_euler = (math.radians(45), 0, math.radians(-40))  # shadows fall to the right of the views
    sc.collection.objects.link(sun)
    world = bpy.data.worlds.new("Sky")
    world.use_nodes = True
    nt = world.node_tree
    coord = nt.nodes.new("ShaderNodeTexCoord")
    xyz = nt.nodes.new("ShaderNodeSeparateXYZ")
    ramp = nt.nodes.new("ShaderNodeValToRGB")
    ramp.color_ramp.elements[0].color = (0.75, 0.82, 0.9, 1.0)   # horizon
    ramp.color_ramp.elements[1].color = (0.18, 0.35, 0.75, 1.0)  # zenith
    ramp.color_ramp.elements[1].position = 0.6
    bg = nt.nodes["Background"]
    nt.links.new(coord.outputs["Generated"], xyz.inputs["Vector"])
    nt.links.new(xyz.outputs["Z"], ramp.inputs["Fac"])
    nt.links.new(ramp.outputs["Color"], bg.inputs["Color"])
    bg.inputs["Strength"].default_value = sky_strength
    sc.world = world
    return ground


def plant_materials(objs, rgba=(0.2, 0.14, 0.09, 1.0)):
    """A plain bark material for plant objects that came without one (the
    add-on's own materials already show vertex colours where they carry
    the colour)."""
    bark = None
    for o in objs:
        if o.type == 'MESH' and not o.data.materials:
            bark = bark or material("Bark", rgba)
            o.data.materials.append(bark)


def near_part(lo, hi, ratio=2.0):
    """The bounds cut along x to `ratio` times their y extent, keeping the
    low-x end: for an avenue seen from its start, the near trees fill the
    frame and the rest recede behind them."""
    cut = lo.x + ratio * max(hi.y - lo.y, 1.0)
    return lo, Vector((min(hi.x, cut), hi.y, hi.z))


def frame_camera(objs, direction, width, height, lens=50.0, margin=1.06, box=None):
    """A camera along `direction` from the centre of the objects' bounds
    (or of box = (lo, hi)), just far enough that all 8 corners fit the
    frame."""
    sc = bpy.context.scene
    cam = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    sc.collection.objects.link(cam)
    sc.camera = cam
    cam.data.lens = lens
    cam.data.sensor_fit = 'AUTO'
    lo, hi = box or bounds(objs)
    centre = (lo + hi) / 2
    d = Vector(direction).normalized()
    cam.rotation_euler = (-d).to_track_quat('-Z', 'Y').to_euler()
    rot = cam.rotation_euler.to_matrix()
    right, up = rot.col[0], rot.col[1]
    # Half-angle tangents: the sensor's width covers the longer image side.
    t = cam.data.sensor_width / (2 * lens)
    tx, ty = (t, t * height / width) if width >= height else (t * width / height, t)
    need = 0.0
    for x in (lo.x, hi.x):
        for y in (lo.y, hi.y):
            for z in (lo.z, hi.z):
                q = Vector((x, y, z)) - centre
                along = q.dot(d)  # towards the camera
                need = max(need, along + abs(q.dot(right)) * margin / tx, along + abs(q.dot(up)) * margin / ty)
    cam.location = centre + d * need
    cam.data.clip_start = max(0.01, need * 1e-3)
    cam.data.clip_end = need * 400
    return cam


def settings(width, height, samples):
    """Cycles on the CPU, fixed seed and samples, no denoising."""
    sc = bpy.context.scene
    sc.render.engine = 'CYCLES'
    sc.cycles.device = 'CPU'
    sc.cycles.samples = samples
    sc.cycles.use_adaptive_sampling = False
    sc.cycles.use_denoising = False
    sc.cycles.seed = 0
    sc.cycles.use_animated_seed = False
    # Few bounces and clamped indirect light: less noise per sample, so
    # small, quick and compact thumbnails.
    sc.cycles.max_bounces = 4
    sc.cycles.diffuse_bounces = 2
    sc.cycles.glossy_bounces = 1
    sc.cycles.transparent_max_bounces = 4
    sc.cycles.sample_clamp_indirect = 2.0
    sc.cycles.filter_width = 1.8
    sc.render.resolution_x = width
    sc.render.resolution_y = height
    sc.render.resolution_percentage = 100
    # Filmic, Blender 3.x's default: 4.0+ default to AgX, which renders the
    # same scene darker and flatter (the plant then hardly stands out).
    sc.view_settings.view_transform = 'Filmic'
    sc.view_settings.exposure = -0.5
    sc.render.image_settings.file_format = 'PNG'
    sc.render.image_settings.color_mode = 'RGB'
    sc.render.image_settings.compression = 100
    sc.render.dither_intensity = 0  # dither noise only makes the PNGs bigger
    for key in dir(sc.render):
        if key.startswith("use_stamp"):
            setattr(sc.render, key, False)


def strip_png_text(path):
    """Drops the text chunks (render date, time, ...) Blender writes into
    a PNG, so the same picture gives the same bytes."""
    with open(path, "rb") as f:
        data = f.read()
    out, pos = [data[:8]], 8
    while pos < len(data):
        n = struct.unpack(">I", data[pos:pos + 4])[0]
        if data[pos + 4:pos + 8] not in (b"tEXt", b"zTXt", b"iTXt"):
            out.append(data[pos:pos + 12 + n])
        pos += 12 + n
    with open(path, "wb") as f:
        f.write(b"".join(out))


def _mask_nodes(sc, plant, mask_dir):
    """Compositor: the image to Composite, the plant's object-index mask
    to a PNG in mask_dir (so coverage is measured, not guessed)."""
    for o in sc.objects:
        o.pass_index = PLANT_INDEX if o in plant else 0
    sc.view_layers[0].use_pass_object_index = True
    if bpy.app.version >= (5, 0, 0):
        # Blender 5.0: the scene's compositor is a node group with a Group
        # Output (no Composite node); File Output takes a directory, a file
        # name and items, and writes multilayer EXR unless told otherwise.
        nt = bpy.data.node_groups.new("banyan_mask", 'CompositorNodeTree')
        sc.compositing_node_group = nt
        nt.interface.new_socket("Image", in_out='OUTPUT', socket_type='NodeSocketColor')
        rl = nt.nodes.new("CompositorNodeRLayers")
        comp = nt.nodes.new("NodeGroupOutput")
        nt.links.new(rl.outputs["Image"], comp.inputs[0])
        idm = nt.nodes.new("CompositorNodeIDMask")
        idm.inputs["Index"].default_value = PLANT_INDEX
        out = nt.nodes.new("CompositorNodeOutputFile")
        out.directory = mask_dir
        out.file_name = "mask"
        out.format.media_type = 'IMAGE'
        out.format.file_format = 'PNG'
        out.format.color_mode = 'BW'
        if not len(out.file_output_items):
            out.file_output_items.new('FLOAT', "")
        nt.links.new(rl.outputs["Object Index"], idm.inputs["ID value"])
    else:
        sc.use_nodes = True
        nt = sc.node_tree
        nt.nodes.clear()
        rl = nt.nodes.new("CompositorNodeRLayers")
        comp = nt.nodes.new("CompositorNodeComposite")
        nt.links.new(rl.outputs["Image"], comp.inputs["Image"])
        idm = nt.nodes.new("CompositorNodeIDMask")
        idm.index = PLANT_INDEX
        out = nt.nodes.new("CompositorNodeOutputFile")
        out.base_path = mask_dir
        out.format.file_format = 'PNG'
        out.format.color_mode = 'BW'
        out.file_slots[0].path = "mask"
        nt.links.new(rl.outputs["IndexOB"], idm.inputs["ID value"])
    nt.links.new(idm.outputs["Alpha"], out.inputs[0])
    sc.render.use_compositing = True


def _luminance(path):
    img = bpy.data.images.load(path, check_existing=False)
    try:
        px = img.pixels[:]
    finally:
        bpy.data.images.remove(img)
    return [0.2126 * px[i] + 0.7152 * px[i + 1] + 0.0722 * px[i + 2] for i in range(0, len(px), 4)]


class BlankRender(RuntimeError):
    pass


def render(path, width, height, samples, plant, min_variance=2e-4, min_coverage=0.003, view_transform='Filmic'):
    """Renders to path (PNG) and checks the picture: the luminance variance
    over the whole image and the share of pixels where the plant is the
    first thing the camera sees. Raises BlankRender below the thresholds.
    view_transform 'Standard' keeps pixel values linear in what a pixel
    covers (a silhouette). Returns (variance, coverage)."""
    sc = bpy.context.scene
    settings(width, height, samples)
    if view_transform != 'Filmic':
        sc.view_settings.view_transform = view_transform
        sc.view_settings.exposure = 0.0
    with tempfile.TemporaryDirectory() as mask_dir:
        _mask_nodes(sc, plant, mask_dir)
        os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
        sc.render.filepath = os.path.abspath(path)
        bpy.ops.render.render(write_still=True)
        strip_png_text(path)
        masks = [f for f in os.listdir(mask_dir) if f.startswith("mask")]
        if not masks:
            raise BlankRender("%s: the compositor wrote no plant mask" % path)
        mask = _luminance(os.path.join(mask_dir, masks[0]))
    lum = _luminance(path)
    mean = sum(lum) / len(lum)
    variance = sum((x - mean) ** 2 for x in lum) / len(lum)
    coverage = sum(1 for m in mask if m > 0.5) / len(mask)
    if variance < min_variance or coverage < min_coverage:
        raise BlankRender("%s looks blank: luminance variance %.6f (need %.6f), plant covers %.2f%% of the "
                          "pixels (need %.2f%%)" % (path, variance, min_variance, 100 * coverage,
                                                    100 * min_coverage))
    return variance, coverage
