"""Shared, textured materials of the library's leaves and bark.

A banyan_material that names a texture (keyaki/ivy leaf atlas, keyaki/fig
bark, ivy stem) becomes ONE material per kind and season, named for
artists ("Banyan Keyaki Leaf", "Banyan Keyaki Leaf (autumn)", "Banyan Fig
Bark", ...) and shared by every object and every run. Its images are drawn
by the library (banyan_texture_generate, PNG by banyan_image_png) and
packed into the .blend, so the file renders anywhere.

Reuse rule: a material (or image) that already has the name is used as it
is and never touched again, so an artist's edits to "Banyan Keyaki Leaf"
survive every run and every Regenerate; to get the library's version
back, delete or rename it. The texture size (add-on preference, default
1024) applies to materials made from then on.

Node setup, the same on Blender 3.4 to 5.0 (only inputs whose names did
not change in 4.0 are used: Base Color, Roughness, Alpha, Normal):
  image (sRGB) [x vertex colour: per-leaf tints, the fig bark's soil
  line] -> Principled Base Color (the texture carries the colour;
  base_color is the viewport colour), as glTF viewers show texture x
  COLOR_0;
  leaves: image alpha > alpha_cutoff (a Math node, so the edge is a hard
  clip in Cycles, EEVEE Legacy and EEVEE Next alike) -> Principled Alpha,
  the alpha read by a second image node with Closest interpolation (no
  mipmaps in EEVEE: see _alpha_clip);
  translucency: a Translucent BSDF of the same colour mixed in (weight
  translucency x alpha, so cut-out texels stay transparent), the glow
  of a back-lit leaf (Principled's subsurface/transmission inputs were
  renamed in 4.0 and behave differently across versions);
  normal image (Non-Color) -> Normal Map (tangent, "UVMap") -> Normal;
  the ivy leaf's underside (UNDERSIDE): Geometry Backfacing (the card's
  back, the side towards the wall) mixes the roughness from the
  material's (the glossy upper side) to a rougher one and the colour to
  a paler, duller one, with Math / Vector Math nodes only (the same on
  every version; one glTF material cannot differ by side).
EEVEE: 3.4-4.1 blend_method CLIP + shadow_method CLIP; 4.2+ (EEVEE Next)
surface_render_method DITHERED, which with a 0/1 alpha is a clip.
"""
import bpy

from ..core import structs as S
from ..core import textures as T

PROP = "banyan_texture"  # "kind/season" on materials and images this module made
UV_MAP = "UVMap"         # build_mesh.fill_mesh's layer
COLOR_ATTRIBUTE = "Color"
# Leaf kinds whose underside differs from the upper side: (roughness,
# lift, grey). Boston ivy: glossy upper side, paler and duller below
# (shared/reference/plants.md): the underside's colour is
# (1 + lift) x mix(colour, its luminance, grey).
UNDERSIDE = {S.TEX_IVY_LEAF: (0.7, 0.35, 0.4)}
_LUMA = (0.2126, 0.7152, 0.0722)


def material_name(kind, season):
    name = "Banyan " + T.KIND_NAMES[kind]
    if kind in T.LEAVES and season == S.SEASON_AUTUMN:
        name += " (autumn)"
    return name


def is_shared(mat):
    """True for a material this module made, still under its name (one
    the artist renamed is theirs)."""
    if mat is None or PROP not in mat.keys():
        return False
    try:
        kind, season = (int(x) for x in str(mat[PROP]).split("/"))
        return mat.name == material_name(kind, season)
    except (ValueError, KeyError):
        return False


# The size when the add-on has no preferences entry (imported as a module
# by a script, or after factory preferences were loaded).
FALLBACK_SIZE = T.DEFAULT_SIZE
ADDON = __package__.rpartition(".")[0]  # the add-on's package: "banyan" or "bl_ext.<repository>.banyan"


def texture_size():
    """The add-on preference's texture size (ui/preferences.py), else FALLBACK_SIZE."""
    a = bpy.context.preferences.addons.get(ADDON)
    try:
        return int(a.preferences.texture_size)
    except (AttributeError, ValueError, TypeError):
        return FALLBACK_SIZE


def _local(coll, name):
    """The local (not linked) datablock called name, or None (one look-up
    by name; the scan only when that one is linked from a library)."""
    idb = coll.get(name)
    if idb is None or idb.library is None:
        return idb
    for idb in coll:
        if idb.name == name and idb.library is None:
            return idb
    return None


def _image(name, png, alpha, non_color, key, created):
    """A packed image from PNG bytes (reused by name when present)."""
    img = _local(bpy.data.images, name)
    if img is not None:
        return img
    data, w, h, _c = png
    img = created.add(bpy.data.images.new(name, w, h, alpha=alpha))
    # Packed from memory: no temporary file; source FILE decodes the PNG.
    img.pack(data=data, data_len=len(data))
    img.source = 'FILE'
    if non_color:
        img.colorspace_settings.name = 'Non-Color'
    img[PROP] = key
    return img


def _eevee_clip(mat, cutoff):
    if hasattr(mat, "surface_render_method"):  # EEVEE Next (4.2+)
        mat.surface_render_method = 'DITHERED'
        if hasattr(mat, "use_transparent_shadow"):
            mat.use_transparent_shadow = True
    else:                                      # EEVEE Legacy (3.4-4.1)
        mat.blend_method = 'CLIP'
        mat.alpha_threshold = cutoff
        mat.shadow_method = 'CLIP'


def _alpha_clip(nodes, links, img, uv, cutoff, at):
    """The image's alpha > cutoff (0 or 1), read by an image node of its
    own with Closest interpolation. EEVEE samples a Linear image node
    through mipmaps: a leaf smaller than a pixel reads its cell's mean
    alpha (a keyaki leaf covers 15-25 % of its cell), below the cutoff,
    and the whole leaf is clipped away. Closest has no mipmaps in EEVEE
    (Legacy and Next): each anti-aliasing sample reads one texel, so the
    samples' mean is the leaf's coverage of the pixel, as in Cycles, which
    never uses mipmaps. The colour keeps its own Linear, mipmapped node."""
    tex = nodes.new("ShaderNodeTexImage")
    tex.image = img
    tex.interpolation = 'Closest'
    tex.label = "Alpha (Closest: no mipmaps)"
    tex.location = at
    links.new(uv, tex.inputs["Vector"])
    clip = nodes.new("ShaderNodeMath")
    clip.operation = 'GREATER_THAN'
    clip.label = "Alpha clip"
    clip.location = (at[0] + 350, at[1])
    links.new(tex.outputs["Alpha"], clip.inputs[0])
    clip.inputs[1].default_value = cutoff
    return clip.outputs[0]


def _multiply(nodes, links, colour, other, x):
    """colour x other, as a Vector Math node (the same node and sockets
    on 3.4 to 5.0, unlike the Mix nodes)."""
    m = nodes.new("ShaderNodeVectorMath")
    m.operation = 'MULTIPLY'
    m.location = (x, 300)
    links.new(colour, m.inputs[0])
    links.new(other, m.inputs[1])
    return m.outputs[0]


def _underside(nodes, links, colour, roughness, under):
    """Colour and roughness that change on the back face: (colour,
    roughness) output sockets. Backfacing is 1 on a face seen from behind
    (by its winding, not its shading normal)."""
    u_rough, lift, grey = under
    geo = nodes.new("ShaderNodeNewGeometry")
    geo.location = (-300, 800)
    back = geo.outputs["Backfacing"]
    rough = nodes.new("ShaderNodeMath")
    rough.operation = 'MULTIPLY_ADD'
    rough.label = "Underside roughness"
    rough.location = (0, 800)
    links.new(back, rough.inputs[0])
    rough.inputs[1].default_value = u_rough - roughness
    rough.inputs[2].default_value = roughness
    luma = nodes.new("ShaderNodeVectorMath")
    luma.operation = 'DOT_PRODUCT'
    luma.location = (-100, 650)
    links.new(colour, luma.inputs[0])
    luma.inputs[1].default_value = _LUMA
    grey_part = nodes.new("ShaderNodeMath")
    grey_part.operation = 'MULTIPLY'
    grey_part.location = (100, 650)
    links.new(luma.outputs["Value"], grey_part.inputs[0])
    grey_part.inputs[1].default_value = (1.0 + lift) * grey
    pale = nodes.new("ShaderNodeVectorMath")
    pale.operation = 'MULTIPLY_ADD'
    pale.label = "Underside colour (paler, duller)"
    pale.location = (300, 650)
    links.new(colour, pale.inputs[0])
    pale.inputs[1].default_value = ((1.0 + lift) * (1.0 - grey),) * 3
    links.new(grey_part.outputs[0], pale.inputs[2])
    diff = nodes.new("ShaderNodeVectorMath")
    diff.operation = 'SUBTRACT'
    diff.location = (500, 650)
    links.new(pale.outputs[0], diff.inputs[0])
    links.new(colour, diff.inputs[1])
    side = nodes.new("ShaderNodeVectorMath")
    side.operation = 'MULTIPLY_ADD'
    side.label = "Upper or underside colour"
    side.location = (700, 650)
    links.new(diff.outputs[0], side.inputs[0])
    links.new(back, side.inputs[1])
    links.new(colour, side.inputs[2])
    return side.outputs[0], rough.outputs[0]


def shared_material(spec, created, vertex_colors=False):
    """The shared material of a textured banyan_material dict (made once)."""
    kind, season = spec["texture"], spec["season"] if spec["texture"] in T.LEAVES else S.SEASON_SUMMER
    name = material_name(kind, season)
    mat = _local(bpy.data.materials, name)
    if mat is not None:
        return mat
    key = "%d/%d" % (kind, season)
    leaf = kind in T.LEAVES
    cutoff = float(spec.get("alpha_cutoff", 0.0))
    size = texture_size()
    base_png, normal_png = T.generate_png(kind, season, size)
    img = _image("%s color" % name, base_png, True, False, key, created)
    nimg = _image("%s normal" % name, normal_png, False, True, key, created) if normal_png else None

    mat = created.add(bpy.data.materials.new(name))
    mat[PROP] = key
    col = tuple(spec["base_color"])
    mat.diffuse_color = col  # the viewport's solid colour
    mat.roughness = spec["roughness"]
    mat.use_backface_culling = not spec["double_sided"]
    if bpy.app.version < (5, 0, 0):  # 5.0: a new material always has its node tree (use_nodes is deprecated)
        mat.use_nodes = True
    nt = mat.node_tree
    nodes, links = nt.nodes, nt.links
    bsdf = nodes.get("Principled BSDF") or nodes.new("ShaderNodeBsdfPrincipled")
    out = nodes.get("Material Output") or nodes.new("ShaderNodeOutputMaterial")
    bsdf.location, out.location = (300, 300), (900, 300)
    bsdf.inputs["Roughness"].default_value = spec["roughness"]

    uv = nodes.new("ShaderNodeUVMap")
    uv.uv_map = UV_MAP
    uv.location = (-900, 300)
    tex = nodes.new("ShaderNodeTexImage")
    tex.image = img
    tex.label = "Base Color"
    tex.location = (-650, 400)
    links.new(uv.outputs["UV"], tex.inputs["Vector"])
    colour = tex.outputs["Color"]
    # The texture carries the colour (base_color is the flat colour of
    # untextured viewers: here the viewport's), as in the glTF writer;
    # the vertex colours (COLOR_0) multiply it: leaves are tinted leaf by
    # leaf, the fig's roots darken towards the soil (the soil line).
    if vertex_colors and (leaf or kind == S.TEX_FIG_BARK):
        vc = nodes.new("ShaderNodeVertexColor")
        vc.layer_name = COLOR_ATTRIBUTE
        vc.location = (-300, 550)
        colour = _multiply(nodes, links, colour, vc.outputs["Color"], -100)
    surface = colour
    if kind in UNDERSIDE:
        surface, rough = _underside(nodes, links, colour, float(spec["roughness"]), UNDERSIDE[kind])
        links.new(rough, bsdf.inputs["Roughness"])
    links.new(surface, bsdf.inputs["Base Color"])

    shader = bsdf.outputs["BSDF"]
    alpha = None
    if leaf and cutoff > 0.0:
        alpha = _alpha_clip(nodes, links, img, uv.outputs["UV"], cutoff, (-650, 100))
        links.new(alpha, bsdf.inputs["Alpha"])
        _eevee_clip(mat, cutoff)
    translucency = float(spec.get("translucency", 0.0))
    if translucency > 0.0:
        tr = nodes.new("ShaderNodeBsdfTranslucent")
        tr.location = (300, -200)
        links.new(colour, tr.inputs["Color"])
        mix = nodes.new("ShaderNodeMixShader")
        mix.label = "Translucency"
        mix.location = (650, 300)
        if alpha is not None:
            w = nodes.new("ShaderNodeMath")
            w.operation = 'MULTIPLY'
            w.location = (300, 550)
            links.new(alpha, w.inputs[0])
            w.inputs[1].default_value = translucency
            links.new(w.outputs[0], mix.inputs["Fac"])
        else:
            mix.inputs["Fac"].default_value = translucency
        links.new(shader, mix.inputs[1])
        links.new(tr.outputs["BSDF"], mix.inputs[2])
        shader = mix.outputs["Shader"]
    if nimg is not None:
        ntex = nodes.new("ShaderNodeTexImage")
        ntex.image = nimg
        ntex.label = "Normal"
        ntex.location = (-650, -100)
        links.new(uv.outputs["UV"], ntex.inputs["Vector"])
        nm = nodes.new("ShaderNodeNormalMap")
        nm.space = 'TANGENT'
        nm.uv_map = UV_MAP
        nm.location = (-300, -150)
        links.new(ntex.outputs["Color"], nm.inputs["Color"])
        links.new(nm.outputs["Normal"], bsdf.inputs["Normal"])
    links.new(shader, out.inputs["Surface"])
    return mat


def image_material(spec, image, created, prefix="banyan"):
    """A material of its own for a mesh's image (a billboard's picture of
    the plant): the PNG packed, its alpha clipped at alpha_cutoff (0.5
    when the spec has none). A single-sided one (a billboard's top card,
    facing up) is transparent from behind in every engine: backface
    culling alone hides it only in the viewport, not in a Cycles render."""
    name = "%s_%s" % (prefix, spec["name"])
    img = created.add(bpy.data.images.new(name, image["width"], image["height"], alpha=image["channels"] == 4))
    img.pack(data=image["png"], data_len=len(image["png"]))
    img.source = 'FILE'
    mat = created.add(bpy.data.materials.new(name))
    mat.diffuse_color = tuple(spec["base_color"])
    single = not spec.get("double_sided", 1)
    mat.use_backface_culling = single
    if bpy.app.version < (5, 0, 0):
        mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    bsdf = nodes.get("Principled BSDF") or nodes.new("ShaderNodeBsdfPrincipled")
    bsdf.inputs["Roughness"].default_value = spec["roughness"]
    uv = nodes.new("ShaderNodeUVMap")
    uv.uv_map = UV_MAP
    uv.location = (-900, 300)
    tex = nodes.new("ShaderNodeTexImage")
    tex.image = img
    tex.label = "Billboard"
    tex.location = (-650, 300)
    links.new(uv.outputs["UV"], tex.inputs["Vector"])
    links.new(tex.outputs["Color"], bsdf.inputs["Base Color"])
    cutoff = float(spec.get("alpha_cutoff", 0.0)) or 0.5
    alpha = _alpha_clip(nodes, links, img, uv.outputs["UV"], cutoff, (-650, 0))
    if single:
        geo = nodes.new("ShaderNodeNewGeometry")
        geo.location = (-650, -300)
        front = nodes.new("ShaderNodeMath")
        front.operation = 'LESS_THAN'
        front.label = "Front face only"
        front.location = (-300, -300)
        links.new(geo.outputs["Backfacing"], front.inputs[0])
        front.inputs[1].default_value = 0.5
        keep = nodes.new("ShaderNodeMath")
        keep.operation = 'MULTIPLY'
        keep.location = (-100, -150)
        links.new(alpha, keep.inputs[0])
        links.new(front.outputs[0], keep.inputs[1])
        alpha = keep.outputs[0]
    links.new(alpha, bsdf.inputs["Alpha"])
    _eevee_clip(mat, cutoff)
    return mat

