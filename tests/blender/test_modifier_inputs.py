"""Geometry Nodes modifier inputs through banyan.engine.nodes (set_inputs,
get_input, copy_inputs), which the wind and growth modifiers and Make LODs
use: Blender 5.2 keeps the values in mod.properties.inputs, older ones as
ID properties of the modifier. Checked on the evaluated mesh, so a value
that is stored but never reaches the modifier fails: a one-vertex mesh
moved by a small group (Set Position, Offset = Offset input + (Shift, 0, 0)),
its inputs set, read back, copied to a second object's modifier, and the
copy of Shift read from a point attribute. Then Make LODs on roots with
wind: each level's wind modifier has the plant's Strength and Direction."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bt  # noqa: E402
import gens  # noqa: E402

import bpy  # noqa: E402
from banyan.engine import nodes as N  # noqa: E402


def group():
    ng = bpy.data.node_groups.new("Banyan test inputs", 'GeometryNodeTree')
    N.new_socket(ng, "Geometry", 'INPUT', 'NodeSocketGeometry')
    N.new_socket(ng, "Shift", 'INPUT', 'NodeSocketFloat', 0.0)
    N.new_socket(ng, "Offset", 'INPUT', 'NodeSocketVector')
    N.new_socket(ng, "Geometry", 'OUTPUT', 'NodeSocketGeometry')
    b = N.Builder(ng)
    gin, gout = b.node('NodeGroupInput'), b.node('NodeGroupOutput')
    xyz = b.node('ShaderNodeCombineXYZ')
    b.link(gin.outputs["Shift"], xyz.inputs[0])
    add = b.node('ShaderNodeVectorMath', operation='ADD')
    b.link(xyz.outputs[0], add.inputs[0])
    b.link(gin.outputs["Offset"], add.inputs[1])
    setpos = b.node('GeometryNodeSetPosition')
    b.link(gin.outputs["Geometry"], setpos.inputs["Geometry"])
    b.link(add.outputs[0], setpos.inputs["Offset"])
    b.link(setpos.outputs["Geometry"], gout.inputs[0])
    return ng


def point_object(name, ng):
    me = bpy.data.meshes.new(name)
    me.from_pydata([(1.0, 2.0, 3.0)], [], [])
    attr = me.attributes.new("shift_attr", 'FLOAT', 'POINT')
    attr.data[0].value = 0.5
    obj = bpy.data.objects.new(name, me)
    bpy.context.scene.collection.objects.link(obj)
    mod = obj.modifiers.new("Inputs", 'NODES')
    mod.node_group = ng
    return obj, mod


def moved(obj):
    """The evaluated vertex minus the original one."""
    dg = bpy.context.evaluated_depsgraph_get()
    dg.update()
    ev = obj.evaluated_get(dg)
    me = ev.to_mesh()
    try:
        co = tuple(me.vertices[0].co) if len(me.vertices) == 1 else None
    finally:
        ev.to_mesh_clear()
    return None if co is None else tuple(round(c - o, 5) for c, o in zip(co, (1.0, 2.0, 3.0)))


def use_attribute(mod, name, attribute):
    """Switches an input to read a named attribute, as the modifier's
    toggle does."""
    ident = N.group_inputs(mod.node_group)[name]
    inputs = N._input_values(mod)
    if inputs is not None:  # Blender 5.2+
        s = getattr(inputs, ident)
        s.type = 'ATTRIBUTE'
        s.attribute_name = attribute
    else:
        key = ident + "_use_attribute"
        mod[key] = type(mod[key])(1)  # an int in 3.x, a bool from 4.x
        mod[ident + "_attribute_name"] = attribute
    mod.id_data.update_tag()


def test_inputs():
    bt.reset_scene()
    ng = group()
    a, ma = point_object("A", ng)
    bt.check(moved(a) == (0.0, 0.0, 0.0), "defaults: the vertex stays (%r)" % (moved(a),))
    N.set_inputs(ma, {"Shift": 0.25, "Offset": (0.0, 0.0, 1.0), "Unused": None})
    bt.check(moved(a) == (0.25, 0.0, 1.0), "set_inputs reaches the modifier (%r)" % (moved(a),))
    bt.check(abs(N.get_input(ma, "Shift") - 0.25) < 1e-6, "get_input reads Shift back")
    bt.check(tuple(N.get_input(ma, "Offset")) == (0.0, 0.0, 1.0), "get_input reads Offset back")
    try:
        N.set_inputs(ma, {"Nope": 1.0})
        bt.check(False, "an unknown input is refused")
    except KeyError as e:
        bt.check("Nope" in str(e), "the refusal names the input: %s" % e)

    b, mb = point_object("B", ng)
    N.copy_inputs(ma, mb)
    bt.check(moved(b) == (0.25, 0.0, 1.0), "copy_inputs: the copy moves the same (%r)" % (moved(b),))
    use_attribute(ma, "Shift", "shift_attr")
    bt.check(moved(a) == (0.5, 0.0, 1.0), "Shift read from the attribute (%r)" % (moved(a),))
    c, mc = point_object("C", ng)
    N.copy_inputs(ma, mc)
    bt.check(moved(c) == (0.5, 0.0, 1.0), "copy_inputs copies the attribute toggle (%r)" % (moved(c),))
    N.set_inputs(ma, {"Shift": -1.0})
    bt.check(abs(N.get_input(mc, "Shift") - 0.25) < 1e-6, "the copy is its own (Shift %.3f)" % N.get_input(mc, "Shift"))


def test_lods_keep_wind():
    """Make LODs copies the plant's wind modifier with its input values."""
    if not bt.generator("roots"):
        return
    from banyan import api
    from banyan.engine import props as P
    from banyan.engine import wind as W
    bt.reset_scene()
    gens.prepare("roots")
    before = {o.name for o in bpy.data.objects}
    res = gens.op("roots")(**dict(gens.KWARGS["roots"], growth_points=10, **{P.prop_name(P.wind_key("roots")): True}))
    objs = [o for o in bpy.data.objects if o.name not in before and o.type == 'MESH']
    if not bt.check(res == {'FINISHED'} and len(objs) == 1, "roots with wind built"):
        return
    api.add_wind(objs[0], strength=0.3, direction=30.0)
    levels = api.make_lods(objs[0], ratios=(0.5,), billboard=False)
    bt.check(len(levels) == 2, "two levels (%d)" % len(levels))
    for o in levels[1:]:
        mod = o.modifiers.get(W.MODIFIER)
        if bt.check(mod is not None, "%s has the wind modifier" % o.name):
            got = (N.get_input(mod, "Strength"), N.get_input(mod, "Direction"))
            bt.check(abs(got[0] - 0.3) < 1e-6 and abs(got[1] - 30.0) < 1e-4,
                     "%s: Strength, Direction copied (%.3f, %.3f)" % ((o.name,) + got))


bt.run(test_inputs)
bt.run(test_lods_keep_wind)
bt.done()
