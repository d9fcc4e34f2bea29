"""Wind in Blender: the library's wind attributes as mesh attributes and a
ready Geometry Nodes setup that sways the plant with them.

The mesh gets `wind_pivot` (FLOAT_VECTOR per point: the library's
wind_pivot_x/y/z interleaved by array slicing) and the float attributes
wind_level, wind_stiffness, wind_phase, wind_flutter (banyan.h). The
pivot is a point in the object's frame like the positions, so whatever
moves the vertices moves it too (transform_mesh).

The modifier "Banyan Wind" runs one node group per .blend, "Banyan
Wind": each vertex turns about its own pivot, about the horizontal axis
perpendicular to the wind, by
    angle = Strength * (1 - stiffness) * (1 + Gust * sin(2 pi (f t + phase)))
(t: the scene's time in seconds), and a leaf vertex moves along its
normal by Flutter * wind_flutter * sin(2 pi (3.7 f t + phase)). One
rotation per vertex, as Pivot Painter's first level: a branch turns
about its base, which itself stays where the parent was at rest, so a
strong wind opens small gaps at forks (about angle x the parent's length).
"""
from array import array

import bpy

from . import nodes as N
from ..core.errors import BanyanError

PIVOT = "wind_pivot"
SCALARS = ("wind_pivot_x", "wind_pivot_y", "wind_pivot_z")
FLOATS = ("wind_level", "wind_stiffness", "wind_phase", "wind_flutter")
GROUP_KEY, GROUP_VERSION = "banyan_wind", 2
MODIFIER = "Banyan Wind"
FLUTTER_RATIO = 3.7  # leaf flutter frequency / gust frequency
SWAY, SWAY_RATIO = 0.25, 2.3  # secondary sway: its share of Strength, its frequency / gust frequency
PLANT_PHASE = (0.0713, 0.1371)  # phi_plant = fract(0.0713 x - 0.1371 y) of the object's location

# name: (default, min, max, description)
INPUTS = {
    "Strength": (0.06, 0.0, 1.0, "Steady lean of free wood (stiffness 0): metres downwind per metre of height"),
    "Gust strength": (0.6, 0.0, 4.0, "Sway about the steady lean, as a share of Strength"),
    "Gust frequency": (0.35, 0.0, 10.0, "Sways per second (Hz)"),
    "Direction": (0.0, -360.0, 360.0, "Where the wind blows to, degrees counter-clockwise from +X"),
    "Flutter": (0.01, 0.0, 0.2, "Leaf flutter along the leaf's normal, metres"),
}


def pivot_vectors(attributes):
    """The interleaved 'f' array (3n) of the three pivot scalars in
    `attributes` ({name: array('f')}), or None when they are absent."""
    if not all(k in attributes for k in SCALARS):
        return None
    x, y, z = (attributes[k] for k in SCALARS)
    out = array("f", bytes(12 * len(x)))
    out[0::3] = x
    out[1::3] = y
    out[2::3] = z
    return out


def add_attributes(me, attributes, add_float, pivots=None):
    """Writes `attributes` on me: the pivot as one vector (`pivots`, the
    interleaved 'f' array, when the caller made it already), the rest
    through add_float(name, data); returns the names written as floats."""
    piv = pivots if pivots is not None else pivot_vectors(attributes)
    if piv is not None:
        me.attributes.new(PIVOT, 'FLOAT_VECTOR', 'POINT').data.foreach_set("vector", piv)
    done = []
    for name, data in attributes.items():
        if piv is not None and name in SCALARS:
            continue
        add_float(name, data)
        done.append(name)
    return done


def has_wind(me):
    return me is not None and PIVOT in me.attributes and all(k in me.attributes for k in FLOATS)


def transform_vectors(vec, matrix):
    """vec (flat 'f' array of points) under matrix, in C: a temporary mesh's
    vertices moved by Mesh.transform (no per-point Python)."""
    n = len(vec) // 3
    tmp = bpy.data.meshes.new("banyan_tmp_pivots")
    try:
        tmp.vertices.add(n)
        tmp.vertices.foreach_set("co", vec)
        tmp.transform(matrix)
        out = array("f", bytes(4 * len(vec)))
        tmp.vertices.foreach_get("co", out)
        return out
    finally:
        bpy.data.meshes.remove(tmp)


def transform_mesh(me, matrix):
    """me.transform(matrix), its wind pivots moved with its vertices."""
    me.transform(matrix)
    a = me.attributes.get(PIVOT)
    if a is not None and a.data_type == 'FLOAT_VECTOR' and len(a.data):
        vec = array("f", bytes(12 * len(a.data)))
        a.data.foreach_get("vector", vec)
        a.data.foreach_set("vector", transform_vectors(vec, matrix))


def _plant_phase(b):
    """phi_plant: one phase per object, from where it stands (the viewer's
    per-instance phase: fract(0.0713 x - 0.1371 y) of its location); 0
    where the Self Object node is missing."""
    try:
        me = b.node('GeometryNodeSelfObject')
    except RuntimeError:
        return 0.0
    info = b.node('GeometryNodeObjectInfo')
    b.link(me.outputs[0], info.inputs["Object"])
    loc = b.node('ShaderNodeSeparateXYZ')
    b.link(info.outputs["Location"], loc.inputs[0])
    return b.math('FRACT', b.math('MULTIPLY_ADD', loc.outputs["Y"], -PLANT_PHASE[1],
                                  b.math('MULTIPLY', loc.outputs["X"], PLANT_PHASE[0])))


def _build_group(ng):
    N.new_socket(ng, "Geometry", 'INPUT', 'NodeSocketGeometry')
    for name, (dflt, lo, hi, desc) in INPUTS.items():
        N.new_socket(ng, name, 'INPUT', 'NodeSocketFloat', dflt, lo, hi, desc)
    N.new_socket(ng, "Geometry", 'OUTPUT', 'NodeSocketGeometry')
    b = N.Builder(ng)
    gin = b.node('NodeGroupInput')
    gout = b.node('NodeGroupOutput')
    g = gin.outputs
    t = b.node('GeometryNodeInputSceneTime').outputs["Seconds"]
    free = b.math('SUBTRACT', 1.0, b.attribute("wind_stiffness"))
    phase = b.attribute("wind_phase")
    flutter = b.attribute("wind_flutter")
    pivot = b.attribute(PIVOT, 'FLOAT_VECTOR')
    pos = b.node('GeometryNodeInputPosition').outputs[0]
    two_pi = 6.283185307179586
    ft = b.math('MULTIPLY', g["Gust frequency"], t)
    rad = b.math('RADIANS', g["Direction"])
    cos_d, sin_d = b.math('COSINE', rad), b.math('SINE', rad)
    # 1. Main bend: along d = (cos a, sin a, 0) by
    #    Strength * (1 - s)^2 * h * (1 + Gust * sin(2 pi (f t + phi_plant))), h above the lowest point.
    box = b.node('GeometryNodeBoundBox')
    b.link(g[0], box.inputs[0])
    low = b.node('ShaderNodeSeparateXYZ')
    b.link(box.outputs["Min"], low.inputs[0])
    here = b.node('ShaderNodeSeparateXYZ')
    b.link(pos, here.inputs[0])
    h = b.math('SUBTRACT', here.outputs["Z"], low.outputs["Z"])
    gust = b.math('MULTIPLY_ADD', b.math('SINE', b.math('MULTIPLY', b.math('ADD', ft, _plant_phase(b)), two_pi)),
                  g["Gust strength"], 1.0)
    bend = b.math('MULTIPLY', b.math('MULTIPLY', b.math('MULTIPLY', g["Strength"], b.math('MULTIPLY', free, free)),
                                     h), gust)
    push = b.node('ShaderNodeCombineXYZ')
    b.link(b.math('MULTIPLY', cos_d, bend), push.inputs["X"])
    b.link(b.math('MULTIPLY', sin_d, bend), push.inputs["Y"])
    # 2. Secondary sway: about the vertex's pivot, about the horizontal axis z x d (a tip leans toward d), by
    #    SWAY * Strength * (1 - s) * sin(2 pi (SWAY_RATIO f t + phase)).
    axis = b.node('ShaderNodeCombineXYZ')
    b.link(b.math('MULTIPLY', sin_d, -1.0), axis.inputs["X"])
    b.link(cos_d, axis.inputs["Y"])
    sway = b.math('SINE', b.math('MULTIPLY', b.math('MULTIPLY_ADD', ft, SWAY_RATIO, phase), two_pi))
    angle = b.math('MULTIPLY', b.math('MULTIPLY', b.math('MULTIPLY', g["Strength"], SWAY), free), sway)
    rot = b.node('ShaderNodeVectorRotate', rotation_type='AXIS_ANGLE')
    b.link(pos, rot.inputs["Vector"])
    b.link(pivot, rot.inputs["Center"])
    b.link(axis.outputs[0], rot.inputs["Axis"])
    b.link(angle, rot.inputs["Angle"])
    # 3. Leaf flutter: along the normal, faster than the sway.
    fwave = b.math('SINE', b.math('MULTIPLY', b.math('MULTIPLY_ADD', ft, FLUTTER_RATIO, phase), two_pi))
    amp = b.math('MULTIPLY', b.math('MULTIPLY', g["Flutter"], flutter), fwave)
    off = b.node('ShaderNodeVectorMath', operation='SCALE')
    b.link(b.node('GeometryNodeInputNormal').outputs[0], off.inputs[0])
    b.link(amp, off.inputs["Scale"])
    total = b.node('ShaderNodeVectorMath', operation='ADD')
    b.link(push.outputs[0], total.inputs[0])
    b.link(off.outputs[0], total.inputs[1])
    setp = b.node('GeometryNodeSetPosition')
    b.link(g[0], setp.inputs["Geometry"])
    b.link(rot.outputs[0], setp.inputs["Position"])
    b.link(total.outputs[0], setp.inputs["Offset"])
    b.link(setp.outputs[0], gout.inputs[0])


def wind_group(created=None):
    """The .blend's "Banyan Wind" node group (made on first use)."""
    return N.shared_group(GROUP_KEY, GROUP_VERSION, "Banyan Wind", _build_group, created)


def add_wind_modifier(obj, created=None, **values):
    """Adds (or updates) obj's "Banyan Wind" modifier. values: the group's
    inputs by name with spaces as underscores (strength=0.1,
    gust_strength=.., gust_frequency=.., direction=deg, flutter=..).
    BanyanError when obj's mesh has no wind attributes (params' wind 0)."""
    if not isinstance(obj, bpy.types.Object) or obj.type != 'MESH':
        raise TypeError("wind needs a mesh object, not %r" % (obj,))
    if not has_wind(obj.data):
        raise BanyanError(1, "'%s' has no wind attributes (%s, %s); grow it with the parameter wind on"
                          % (obj.name, PIVOT, ", ".join(FLOATS)), "BANYAN_E_INVALID_ARG")
    by_name = {k.lower().replace(" ", "_"): k for k in INPUTS}
    bad = [k for k in values if k not in by_name]
    if bad:
        raise TypeError("unknown wind input(s) %s; known: %s" % (", ".join(bad), ", ".join(sorted(by_name))))
    ng = wind_group(created)
    mod = next((m for m in obj.modifiers if m.type == 'NODES' and m.node_group == ng), None)
    if mod is None:
        mod = obj.modifiers.new(MODIFIER, 'NODES')
        mod.node_group = ng
    N.set_inputs(mod, {by_name[k]: float(v) for k, v in values.items() if v is not None})
    return mod
