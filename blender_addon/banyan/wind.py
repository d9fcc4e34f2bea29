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
from .core.errors import BanyanError

PIVOT = "wind_pivot"
SCALARS = ("wind_pivot_x", "wind_pivot_y", "wind_pivot_z")
FLOATS = ("wind_level", "wind_stiffness", "wind_phase", "wind_flutter")
GROUP_KEY, GROUP_VERSION = "banyan_wind", 1
MODIFIER = "Banyan Wind"
FLUTTER_RATIO = 3.7  # leaf flutter frequency / gust frequency

# name: (default, min, max, description)
INPUTS = {
    "Strength": (0.06, 0.0, 1.0, "Steady lean of a free tip, radians (scaled by 1 - stiffness)"),
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


def add_attributes(me, attributes, add_float):
    """Writes `attributes` on me: the pivot as one vector, the rest through
    add_float(name, data); returns the names written as floats."""
    piv = pivot_vectors(attributes)
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
    stiff = b.attribute("wind_stiffness")
    phase = b.attribute("wind_phase")
    flutter = b.attribute("wind_flutter")
    pivot = b.attribute(PIVOT, 'FLOAT_VECTOR')
    two_pi = 6.283185307179586
    # angle = Strength * (1 - stiffness) * (1 + Gust * sin(2 pi (f t + phase)))
    wave = b.math('SINE', b.math('MULTIPLY', b.math('MULTIPLY_ADD', g["Gust frequency"], t, phase), two_pi))
    osc = b.math('MULTIPLY_ADD', wave, g["Gust strength"], 1.0)
    angle = b.math('MULTIPLY', b.math('MULTIPLY', g["Strength"], b.math('SUBTRACT', 1.0, stiff)), osc)
    # Axis: horizontal, perpendicular to the wind d = (cos a, sin a, 0): z x d, so a tip leans toward d.
    rad = b.math('RADIANS', g["Direction"])
    axis = b.node('ShaderNodeCombineXYZ')
    b.link(b.math('MULTIPLY', b.math('SINE', rad), -1.0), axis.inputs["X"])
    b.link(b.math('COSINE', rad), axis.inputs["Y"])
    rot = b.node('ShaderNodeVectorRotate', rotation_type='AXIS_ANGLE')
    b.link(b.node('GeometryNodeInputPosition').outputs[0], rot.inputs["Vector"])
    b.link(pivot, rot.inputs["Center"])
    b.link(axis.outputs[0], rot.inputs["Axis"])
    b.link(angle, rot.inputs["Angle"])
    # Leaf flutter: along the normal, faster than the sway.
    fwave = b.math('SINE', b.math('MULTIPLY', b.math('MULTIPLY_ADD', b.math('MULTIPLY', g["Gust frequency"],
                                                                              FLUTTER_RATIO), t, phase), two_pi))
    amp = b.math('MULTIPLY', b.math('MULTIPLY', g["Flutter"], flutter), fwave)
    off = b.node('ShaderNodeVectorMath', operation='SCALE')
    b.link(b.node('GeometryNodeInputNormal').outputs[0], off.inputs[0])
    b.link(amp, off.inputs["Scale"])
    setp = b.node('GeometryNodeSetPosition')
    b.link(g[0], setp.inputs["Geometry"])
    b.link(rot.outputs[0], setp.inputs["Position"])
    b.link(off.outputs[0], setp.inputs["Offset"])
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
