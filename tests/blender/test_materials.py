"""Shared textured materials (blender_addon/banyan/engine/materials.py):
operators run twice leave exactly one material per kind and season and one
image per texture, packed, of the preference's size, the leaves' with
alpha; node trees wire image -> Principled base colour (and alpha through a
clip for leaves, a Normal Map for bark; the leaves' and the fig bark's
times the vertex colours, which on the roots carry the soil line); EEVEE
clips leaves; autumn swaps the material, not the geometry; an artist's
edit to a shared material is never overwritten; Regenerate with another
season swaps the slot; the ivy leaf is glossy on its upper side, rougher,
paler and duller on its underside (Geometry Backfacing), its nodes
evaluated at both sides."""
import os
import sys
from array import array

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bt  # noqa: E402
import gens  # noqa: E402

import bpy  # noqa: E402
from banyan.engine import materials as MAT  # noqa: E402
from banyan.core import structs as S  # noqa: E402
from banyan.core import textures as T  # noqa: E402
from banyan.core.errors import BanyanError  # noqa: E402

SIZE = 256  # small for speed; the add-on's default is 1024
EXPECTED = {"roots": {"Banyan Fig Bark"}, "keyaki": {"Banyan Keyaki Leaf", "Banyan Keyaki Bark"},
            "ivy": {"Banyan Ivy Leaf", "Banyan Ivy Stem"}}


def set_size(size):
    a = bpy.context.preferences.addons.get("banyan")
    if a is not None:
        a.preferences.texture_size = str(size)
    MAT.FALLBACK_SIZE = size  # reset_scene loads factory preferences: no add-on entry then


def test_preference():
    a = bpy.context.preferences.addons.get("banyan")
    if a is None:  # `blender --addons` enables without a preferences entry; what addon_utils.enable adds
        a = bpy.context.preferences.addons.new()
        a.module = "banyan"
    if not bt.check(a is not None and a.preferences is not None, "the add-on has preferences"):
        return
    bt.check(a.preferences.texture_size == str(T.DEFAULT_SIZE) == "1024", "texture size defaults to 1024")
    a.preferences.texture_size = "512"
    bt.check(MAT.texture_size() == 512, "texture_size() follows the preference")
    a.preferences.texture_size = "1024"


def new_objects(before):
    return [o for o in bpy.data.objects if o.name not in before]


def run_op(gen, **kw):
    gens.prepare(gen)
    cube = bpy.data.objects["Cube"]
    for o in bpy.context.view_layer.objects:  # the host is the cube alone, as on the first run
        o.select_set(o == cube)
    bpy.context.view_layer.objects.active = cube
    before = {o.name for o in bpy.data.objects}
    args = dict(gens.KWARGS[gen])
    args.update(kw)
    res = gens.op(gen)(**args)
    bt.check(res == {'FINISHED'}, "%s %s: operator finished (%s)" % (gen, kw, res))
    return new_objects(before)


def shared():
    return [m for m in bpy.data.materials if MAT.is_shared(m)]


def upstream(socket, seen=None):
    """Every node feeding `socket`, following links back."""
    out = []
    for link in socket.links:
        n = link.from_node
        out.append((n, link.from_socket.name))
        for s in n.inputs:
            out += upstream(s)
    return out


def image_nodes(socket):
    return [(n, out) for n, out in upstream(socket) if n.bl_idname == "ShaderNodeTexImage"]


def pixels(img):
    buf = array("f", bytes(4 * len(img.pixels)))
    img.pixels.foreach_get(buf)
    return buf


def test_twice():
    bt.reset_scene()
    set_size(SIZE)
    objs = {}
    for gen in ("keyaki", "ivy", "roots"):
        if not bt.generator(gen):
            continue
        for _ in range(2):
            objs[gen] = run_op(gen)
        names = {m.name for o in objs[gen] for m in o.data.materials if m is not None}
        bt.check(names == EXPECTED[gen], "%s: slots hold %s, expected %s" % (gen, sorted(names), sorted(EXPECTED[gen])))
    mats = shared()
    bt.check(sorted(m.name for m in mats) == sorted(set().union(*(EXPECTED[g] for g in objs))),
             "one material per kind after two runs of each: %s" % sorted(m.name for m in bpy.data.materials))
    bt.check(not [m.name for m in bpy.data.materials if m.name.startswith("Banyan") and "." in m.name],
             "no Banyan material duplicated (.001)")
    imgs = [i for i in bpy.data.images if MAT.PROP in i.keys()]
    # One colour image per material, a normal image when the library draws one; none twice.
    bt.check(len({i.name for i in imgs}) == len(imgs) and not [i for i in imgs if "." in i.name],
             "no image duplicated: %s" % sorted(i.name for i in imgs))
    for m in mats:
        bt.check(bpy.data.images.get(m.name + " color") is not None, "%s: its colour image exists" % m.name)
    for img in imgs:
        bt.check(img.packed_file is not None, "%s: packed into the .blend" % img.name)
        bt.check(tuple(img.size) == (SIZE, SIZE), "%s: %s px, asked %d" % (img.name, tuple(img.size), SIZE))
    for name in ("Banyan Keyaki Leaf color", "Banyan Ivy Leaf color"):
        img = bpy.data.images.get(name)
        if img is None:
            continue
        a = pixels(img)[3::4]
        clear = sum(1 for v in a if v < 0.5)
        bt.check(img.channels == 4 and 0.1 * len(a) < clear < 0.95 * len(a),
                 "%s: alpha cuts the leaves out (%d of %d texels clear)" % (name, clear, len(a)))
    for name in ("Banyan Keyaki Bark normal", "Banyan Fig Bark normal"):
        img = bpy.data.images.get(name)
        if img is not None:
            bt.check(img.colorspace_settings.name == 'Non-Color', "%s: Non-Color" % name)
    for m in mats:
        check_nodes(m)
    for o in objs.get("roots", []):
        check_soil_line(o)


def check_soil_line(o):
    """The roots carry the soil line as the "Color" attribute (white above
    the band, darker towards the ground), and Banyan Fig Bark multiplies
    its image by it: a Color Attribute node feeds the base colour, as glTF
    viewers show texture x COLOR_0."""
    ca = o.data.color_attributes.get(MAT.COLOR_ATTRIBUTE)
    if bt.check(ca is not None and ca.domain == 'POINT', "%s: a per-vertex \"Color\" attribute" % o.name):
        buf = array("f", bytes(4 * 4 * len(ca.data)))
        ca.data.foreach_get("color", buf)
        white = sum(1 for v in buf[0::4] if v >= 0.999)
        bt.check(0 < white < len(ca.data) and min(buf[0::4]) < 0.8,
                 "%s: white above the soil line, darker below (%d of %d red at 1, least %.3f)"
                 % (o.name, white, len(ca.data), min(buf[0::4]) if len(buf) else -1))
    m = o.data.materials[0] if o.data.materials else None
    if not bt.check(m is not None and m.name == "Banyan Fig Bark", "%s: Banyan Fig Bark" % o.name):
        return
    bsdf = next((n for n in m.node_tree.nodes if n.bl_idname == "ShaderNodeBsdfPrincipled"), None)
    vc = [n for n, out in upstream(bsdf.inputs["Base Color"]) if n.bl_idname == "ShaderNodeVertexColor"]
    bt.check(len(vc) == 1 and vc[0].layer_name == MAT.COLOR_ATTRIBUTE,
             "%s: a Color Attribute node (\"Color\") -> Base Color" % m.name)


def evaluate(socket, back, colour):
    """The value reaching an input socket for a face seen from the front
    (back 0) or behind (back 1), the colour image reading `colour` and the
    vertex colours white: Math / Vector Math nodes and Geometry's
    Backfacing evaluated; None for any other node."""
    if not socket.is_linked:
        v = socket.default_value
        return tuple(v)[:3] if hasattr(v, "__len__") else float(v)
    link = socket.links[0]
    n, out = link.from_node, link.from_socket.name
    if n.bl_idname == "ShaderNodeNewGeometry":
        return float(back) if out == "Backfacing" else None
    if n.bl_idname == "ShaderNodeTexImage":
        return tuple(colour) if out == "Color" else None
    if n.bl_idname == "ShaderNodeVertexColor":
        return (1.0, 1.0, 1.0)
    if n.bl_idname not in ("ShaderNodeMath", "ShaderNodeVectorMath"):
        return None
    args = [evaluate(i, back, colour) for i in list(n.inputs)[:3]]
    vec = n.bl_idname == "ShaderNodeVectorMath"
    if any(a is None for a in args[:2]):
        return None
    if vec:
        v = [a if isinstance(a, tuple) else (a, a, a) for a in args]
        op = {'MULTIPLY': lambda: tuple(x * y for x, y in zip(v[0], v[1])),
              'SUBTRACT': lambda: tuple(x - y for x, y in zip(v[0], v[1])),
              'ADD': lambda: tuple(x + y for x, y in zip(v[0], v[1])),
              'MULTIPLY_ADD': lambda: tuple(x * y + z for x, y, z in zip(*v)),
              'DOT_PRODUCT': lambda: sum(x * y for x, y in zip(v[0], v[1]))}.get(n.operation)
        if op is None:
            return None
        r = op()
        return r if out == "Vector" or not isinstance(r, tuple) else None
    a = [x if not isinstance(x, tuple) else x[0] for x in args]
    return {'MULTIPLY': lambda: a[0] * a[1], 'ADD': lambda: a[0] + a[1], 'MULTIPLY_ADD': lambda: a[0] * a[1] + a[2],
            'GREATER_THAN': lambda: float(a[0] > a[1]), 'LESS_THAN': lambda: float(a[0] < a[1])}.get(
        n.operation, lambda: None)()


def check_underside(m, bsdf):
    """Banyan Ivy Leaf: glossy upper side, a rougher, paler and duller
    underside (the card's back face, Geometry Backfacing), in Math nodes
    only, so the same on every Blender version (plants.md section 2)."""
    leaf = (0.05, 0.12, 0.02)  # a linear leaf green
    col = [evaluate(bsdf.inputs["Base Color"], b, leaf) for b in (0, 1)]
    rough = [evaluate(bsdf.inputs["Roughness"], b, leaf) for b in (0, 1)]
    back = [n for n, out in upstream(bsdf.inputs["Roughness"]) + upstream(bsdf.inputs["Base Color"])
            if n.bl_idname == "ShaderNodeNewGeometry" and out == "Backfacing"]
    bt.check(len(back) >= 2, "%s: Geometry Backfacing drives roughness and colour" % m.name)
    if not bt.check(None not in col and None not in rough,
                    "%s: roughness %s and colour %s evaluate" % (m.name, rough, col)):
        return
    luma = [0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2] for c in col]
    sat = [(max(c) - min(c)) / max(c) for c in col]
    bt.check(0.25 <= rough[0] <= 0.45 and rough[1] >= 0.6,
             "%s: roughness upper side %.3f (glossy, 0.25-0.45), underside %.3f (>= 0.6)" % (m.name, rough[0], rough[1]))
    bt.check(max(abs(x - y) for x, y in zip(col[0], leaf)) < 1e-6,
             "%s: the upper side shows the texture x vertex colour as it is (%s)" % (m.name, col[0]))
    bt.check(luma[1] > 1.15 * luma[0] and sat[1] < 0.85 * sat[0],
             "%s: underside paler and duller: luminance %.4f -> %.4f, saturation %.3f -> %.3f"
             % (m.name, luma[0], luma[1], sat[0], sat[1]))


def check_nodes(m):
    kind = int(m[MAT.PROP].split("/")[0])
    leaf = kind in T.LEAVES
    nodes = m.node_tree.nodes
    bsdf = next((n for n in nodes if n.bl_idname == "ShaderNodeBsdfPrincipled"), None)
    out = next((n for n in nodes if n.bl_idname == "ShaderNodeOutputMaterial"), None)
    if not bt.check(bsdf is not None and out is not None, "%s: Principled BSDF and output" % m.name):
        return
    bt.check(out.inputs["Surface"].is_linked and any(n == bsdf for n, _ in upstream(out.inputs["Surface"])),
             "%s: the Principled BSDF reaches the output" % m.name)
    base = image_nodes(bsdf.inputs["Base Color"])
    bt.check(any(n.image is not None and n.image.name == m.name + " color" and o == "Color" for n, o in base),
             "%s: colour image -> Base Color" % m.name)
    if leaf:
        al = image_nodes(bsdf.inputs["Alpha"])
        bt.check(any(o == "Alpha" and n.image.name == m.name + " color" for n, o in al),
                 "%s: image alpha -> Principled Alpha" % m.name)
        clip = [n for n, _ in upstream(bsdf.inputs["Alpha"]) if n.bl_idname == "ShaderNodeMath"]
        bt.check(any(n.operation == 'GREATER_THAN' and 0 < n.inputs[1].default_value < 1 for n in clip),
                 "%s: alpha clipped at the cutoff" % m.name)
        if hasattr(m, "surface_render_method"):
            bt.check(m.surface_render_method == 'DITHERED', "%s: EEVEE Next dithered (clip)" % m.name)
        else:
            bt.check(m.blend_method == 'CLIP' and 0 < m.alpha_threshold < 1, "%s: EEVEE clip" % m.name)
        bt.check(not m.use_backface_culling, "%s: double sided" % m.name)
        bt.check(any(n.bl_idname == "ShaderNodeBsdfTranslucent" for n, _ in upstream(out.inputs["Surface"])),
                 "%s: translucent BSDF mixed in (back-lit glow)" % m.name)
        if kind == S.TEX_IVY_LEAF:
            check_underside(m, bsdf)
    else:
        nm = [n for n, _ in upstream(bsdf.inputs["Normal"]) if n.bl_idname == "ShaderNodeNormalMap"]
        bt.check(len(nm) == 1 and nm[0].space == 'TANGENT', "%s: Normal Map -> Normal" % m.name)
        if nm:
            im = image_nodes(nm[0].inputs["Color"])
            bt.check(any(n.image.colorspace_settings.name == 'Non-Color' for n, _ in im),
                     "%s: a Non-Color image feeds the normal map" % m.name)


def season_items(gen):
    op = gens.OPS[gen].split(".")
    rna = getattr(getattr(bpy.ops, op[0]), op[1]).get_rna_type()
    p = rna.properties.get("season")
    return [i.identifier for i in p.enum_items] if p is not None else []


def coords(objs):
    out = []
    for o in objs:
        buf = array("f", bytes(12 * len(o.data.vertices)))
        o.data.vertices.foreach_get("co", buf)
        out.append(buf.tobytes())
    return out


def test_season():
    for gen, leaf in (("keyaki", "Banyan Keyaki Leaf"), ("ivy", "Banyan Ivy Leaf")):
        if not bt.generator(gen):
            continue
        items = season_items(gen)
        if not bt.check(len(items) == 2, "%s: a Season choice of two (%s)" % (gen, items)):
            continue
        bt.reset_scene()
        set_size(SIZE)
        summer = run_op(gen, season=items[0])
        autumn = run_op(gen, season=items[1])
        bt.check(coords(summer) == coords(autumn), "%s: autumn has the same vertex positions" % gen)
        ms = {m.name for o in summer for m in o.data.materials}
        ma = {m.name for o in autumn for m in o.data.materials}
        bt.check(leaf in ms and leaf not in ma and leaf + " (autumn)" in ma,
                 "%s: autumn swaps the leaf material (%s -> %s)" % (gen, sorted(ms), sorted(ma)))
        bt.check(len(ms & ma) == 1, "%s: the bark/stem material is shared by both seasons" % gen)
        # Regenerate with the other season: the library's slot follows, an artist's slot stays.
        from banyan import api
        from banyan.engine import plant
        obj = summer[0]
        me = obj.data
        own = bpy.data.materials.new("Artist Bark")
        slot = next(i for i, m in enumerate(me.materials) if m.name != leaf)
        me.materials[slot] = own
        p = plant.current_params(obj)
        p.set("season", 1)
        new = api.regenerate(obj, p)
        got = [m.name for m in new[0].data.materials]
        bt.check(leaf + " (autumn)" in got and "Artist Bark" in got,
                 "%s: regenerate in autumn: %s" % (gen, got))
        bt.check(coords(new) == coords(summer[:1]) or gen == "ivy", "%s: regenerate kept the geometry" % gen)


def test_user_edit():
    """A shared material the artist edited is reused as it is."""
    if not bt.generator("roots"):
        return
    bt.reset_scene()
    set_size(SIZE)
    run_op("roots")
    m = bpy.data.materials["Banyan Fig Bark"]
    bsdf = next(n for n in m.node_tree.nodes if n.bl_idname == "ShaderNodeBsdfPrincipled")
    bsdf.inputs["Roughness"].default_value = 0.123
    n_nodes = len(m.node_tree.nodes)
    objs = run_op("roots")
    bt.check(objs and objs[0].data.materials[0] == m, "roots: the second run uses the edited material")
    bt.check(abs(bsdf.inputs["Roughness"].default_value - 0.123) < 1e-6 and len(m.node_tree.nodes) == n_nodes,
             "roots: the artist's edit survives another run")
    bt.check(len([x for x in bpy.data.materials if x.name.startswith("Banyan Fig Bark")]) == 1,
             "roots: still one Fig Bark material")
    # A renamed library material is the artist's: the next run makes a fresh one.
    m.name = "My Fig Bark"
    run_op("roots")
    bt.check("Banyan Fig Bark" in bpy.data.materials and "My Fig Bark" in bpy.data.materials,
             "roots: after a rename the library's material comes back beside the artist's")


def test_bad_size():
    for size in (0, 100, 16384):
        try:
            T.generate_png(S.TEX_FIG_BARK, 0, size)
            bt.check(False, "texture size %d refused" % size)
        except BanyanError as e:
            bt.check("size" in e.message, "texture size %d refused naming the size: %s" % (size, e.message))


def test_render_clip():
    """A plane showing the whole leaf atlas, rendered by Cycles with a
    transparent film: the leaves are opaque, between them it is clear."""
    if not bt.generator("keyaki"):
        return
    bt.reset_scene()
    set_size(SIZE)
    run_op("keyaki")
    mat = bpy.data.materials["Banyan Keyaki Leaf"]
    for o in list(bpy.data.objects):
        if o.type == 'MESH':
            bpy.data.objects.remove(o)
    bpy.ops.mesh.primitive_plane_add(size=2.0)  # uvs 0..1 over the plane: the whole atlas
    plane = bpy.context.active_object
    plane.data.uv_layers[0].name = MAT.UV_MAP
    plane.data.materials.append(mat)
    cam = bpy.data.objects["Camera"]
    cam.location, cam.rotation_euler = (0, 0, 3), (0, 0, 0)
    cam.data.type = 'ORTHO'
    cam.data.ortho_scale = 2.0
    sc = bpy.context.scene
    sc.render.engine = 'CYCLES'
    sc.cycles.samples = 4
    sc.cycles.use_denoising = False
    sc.cycles.device = 'CPU'
    sc.render.film_transparent = True
    sc.render.resolution_x = sc.render.resolution_y = 64
    sc.render.resolution_percentage = 100
    sc.render.image_settings.file_format = 'PNG'
    sc.render.image_settings.color_mode = 'RGBA'
    path = os.path.join(bt.OUT_DIR, "materials_clip.png")
    sc.render.filepath = path
    bpy.ops.render.render(write_still=True)
    img = bpy.data.images.load(path, check_existing=False)
    a = pixels(img)[3::4]
    clear = sum(1 for v in a if v < 0.05)
    solid = sum(1 for v in a if v > 0.95)  # the keyaki atlas: one leaf a cell, 15-25% of it
    bt.check(clear > 0.5 * len(a) and solid > 0.01 * len(a),
             "Cycles render of the leaf atlas: %d clear, %d opaque of %d pixels" % (clear, solid, len(a)))


def test_save_reload():
    """The packed images travel in the .blend: saved, reopened, decoded."""
    if not bt.generator("roots"):
        return
    bt.reset_scene()
    set_size(SIZE)
    run_op("roots")
    path = os.path.join(bt.OUT_DIR, "materials_packed.blend")
    bpy.ops.wm.save_as_mainfile(filepath=path, copy=True)
    bpy.ops.wm.open_mainfile(filepath=path)
    img = bpy.data.images.get("Banyan Fig Bark color")
    bt.check(img is not None and img.packed_file is not None, "reopened: the bark image is still packed")
    if img is not None:
        px = pixels(img)
        bt.check(tuple(img.size) == (SIZE, SIZE) and max(px[0::4]) > 0.05,
                 "reopened: the packed image decodes (%s px)" % (tuple(img.size),))
    bt.reset_scene()


bt.run(test_preference)
bt.run(test_twice)
bt.run(test_season)
bt.run(test_user_edit)
bt.run(test_bad_size)
bt.run(test_render_clip)
bt.run(test_save_reload)
bt.done()
