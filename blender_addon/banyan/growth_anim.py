"""The ivy's growth animation: a Geometry Nodes modifier that deletes the
vertices whose birth_step is later than the step the current frame maps
to (frame_start -> step 0, frame_end -> the last step)."""
import bpy


def _socket(node, kind, stype):
    socks = node.outputs if kind == "out" else node.inputs
    return next(s for s in socks if s.type == stype and s.enabled)


def _group_sockets(ng):
    if hasattr(ng, "interface"):  # Blender 4.0+
        ng.interface.new_socket("Geometry", in_out='INPUT', socket_type='NodeSocketGeometry')
        ng.interface.new_socket("Geometry", in_out='OUTPUT', socket_type='NodeSocketGeometry')
    else:
        ng.inputs.new('NodeSocketGeometry', "Geometry")
        ng.outputs.new('NodeSocketGeometry', "Geometry")


def add_growth_modifier(obj, created, last_step, frame_start, frame_end, attribute="birth_step"):
    ng = created.add(bpy.data.node_groups.new("Banyan Ivy Growth", 'GeometryNodeTree'))
    _group_sockets(ng)
    N = ng.nodes
    gin = N.new('NodeGroupInput')
    gout = N.new('NodeGroupOutput')
    attr = N.new('GeometryNodeInputNamedAttribute')
    attr.data_type = 'FLOAT'
    attr.inputs["Name"].default_value = attribute
    time = N.new('GeometryNodeInputSceneTime')
    mapr = N.new('ShaderNodeMapRange')
    mapr.clamp = True
    mapr.inputs["From Min"].default_value = float(frame_start)
    mapr.inputs["From Max"].default_value = float(max(frame_end, frame_start + 1))
    mapr.inputs["To Min"].default_value = 0.0
    mapr.inputs["To Max"].default_value = float(last_step)
    cmp = N.new('ShaderNodeMath')
    cmp.operation = 'GREATER_THAN'
    delete = N.new('GeometryNodeDeleteGeometry')
    delete.domain = 'POINT'
    L = ng.links
    L.new(time.outputs["Frame"], mapr.inputs["Value"])
    L.new(_socket(attr, "out", 'VALUE'), cmp.inputs[0])
    L.new(mapr.outputs["Result"], cmp.inputs[1])
    L.new(gin.outputs[0], delete.inputs["Geometry"])
    L.new(cmp.outputs[0], delete.inputs["Selection"])
    L.new(delete.outputs["Geometry"], gout.inputs[0])
    for i, n in enumerate((gin, attr, time, mapr, cmp, delete, gout)):
        n.location = (200 * i, 0)
    mod = obj.modifiers.new("Banyan Growth", 'NODES')
    mod.node_group = ng
    return mod
