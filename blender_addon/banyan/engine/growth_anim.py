"""Growth animations: Geometry Nodes modifiers that delete the vertices
not yet born at the current frame.

Every plant's mesh carries `birth` (0..1, banyan.h): add_birth_modifier
shows the vertices with birth <= t, t running from 0 at Start frame to 1
at End frame (one node group per .blend, "Banyan Growth", the frames
being the modifier's inputs). The ivy keeps its own modifier on its
`birth_step` (frame_start -> step 0, frame_end -> the last step; its node
group per object, "Banyan Ivy Growth")."""
import bpy

from . import nodes as N
from ..core.errors import BanyanError

BIRTH = "birth"
MODIFIER = "Banyan Growth"
GROUP_KEY, GROUP_VERSION = "banyan_growth", 1

# Kept for callers of the first version.
_socket = N.socket


def _group_sockets(ng):
    N.new_socket(ng, "Geometry", 'INPUT', 'NodeSocketGeometry')
    N.new_socket(ng, "Geometry", 'OUTPUT', 'NodeSocketGeometry')


def add_growth_modifier(obj, created, last_step, frame_start, frame_end, attribute="birth_step"):
    ng = created.add(bpy.data.node_groups.new("Banyan Ivy Growth", 'GeometryNodeTree'))
    _group_sockets(ng)
    nodes = ng.nodes
    gin = nodes.new('NodeGroupInput')
    gout = nodes.new('NodeGroupOutput')
    attr = nodes.new('GeometryNodeInputNamedAttribute')
    attr.data_type = 'FLOAT'
    attr.inputs["Name"].default_value = attribute
    time = nodes.new('GeometryNodeInputSceneTime')
    mapr = nodes.new('ShaderNodeMapRange')
    mapr.clamp = True
    mapr.inputs["From Min"].default_value = float(frame_start)
    mapr.inputs["From Max"].default_value = float(max(frame_end, frame_start + 1))
    mapr.inputs["To Min"].default_value = 0.0
    mapr.inputs["To Max"].default_value = float(last_step)
    cmp = nodes.new('ShaderNodeMath')
    cmp.operation = 'GREATER_THAN'
    delete = nodes.new('GeometryNodeDeleteGeometry')
    delete.domain = 'POINT'
    L = ng.links
    L.new(time.outputs["Frame"], mapr.inputs["Value"])
    L.new(N.socket(attr, "out", 'VALUE'), cmp.inputs[0])
    L.new(mapr.outputs["Result"], cmp.inputs[1])
    L.new(gin.outputs[0], delete.inputs["Geometry"])
    L.new(cmp.outputs[0], delete.inputs["Selection"])
    L.new(delete.outputs["Geometry"], gout.inputs[0])
    for i, n in enumerate((gin, attr, time, mapr, cmp, delete, gout)):
        n.location = (200 * i, 0)
    mod = obj.modifiers.new(MODIFIER, 'NODES')
    mod.node_group = ng
    return mod


def _build_birth_group(ng):
    N.new_socket(ng, "Geometry", 'INPUT', 'NodeSocketGeometry')
    N.new_socket(ng, "Start frame", 'INPUT', 'NodeSocketFloat', 1.0, description="The first wood shows")
    N.new_socket(ng, "End frame", 'INPUT', 'NodeSocketFloat', 250.0, description="The whole plant shows")
    N.new_socket(ng, "Geometry", 'OUTPUT', 'NodeSocketGeometry')
    b = N.Builder(ng)
    gin = b.node('NodeGroupInput')
    gout = b.node('NodeGroupOutput')
    frame = b.node('GeometryNodeInputSceneTime').outputs["Frame"]
    # t = clamp((frame - start) / max(end - start, 1), 0, 1); delete birth > t.
    span = b.math('MAXIMUM', b.math('SUBTRACT', gin.outputs["End frame"], gin.outputs["Start frame"]), 1.0)
    t = b.math('DIVIDE', b.math('SUBTRACT', frame, gin.outputs["Start frame"]), span)
    clamp = b.node('ShaderNodeClamp')
    b.link(t, clamp.inputs["Value"])
    later = b.math('GREATER_THAN', b.attribute(BIRTH), clamp.outputs[0])
    delete = b.node('GeometryNodeDeleteGeometry', domain='POINT')
    b.link(gin.outputs[0], delete.inputs["Geometry"])
    b.link(later, delete.inputs["Selection"])
    b.link(delete.outputs["Geometry"], gout.inputs[0])


def birth_group(created=None):
    return N.shared_group(GROUP_KEY, GROUP_VERSION, "Banyan Growth", _build_birth_group, created)


def add_birth_modifier(obj, created, frame_start, frame_end):
    """obj grows over frame_start..frame_end by its `birth` attribute
    (BanyanError when its mesh has none). The modifier goes first, so a
    wind setup sways the grown part only."""
    if BIRTH not in obj.data.attributes:
        raise BanyanError(1, "'%s' has no '%s' attribute to grow by" % (obj.name, BIRTH), "BANYAN_E_INVALID_ARG")
    ng = birth_group(created)
    mod = next((m for m in obj.modifiers if m.type == 'NODES' and m.node_group == ng), None)
    if mod is None:
        mod = obj.modifiers.new(MODIFIER, 'NODES')
        mod.node_group = ng
        if len(obj.modifiers) > 1 and hasattr(obj.modifiers, "move"):  # Blender 4.0+; else it stays last
            obj.modifiers.move(len(obj.modifiers) - 1, 0)
    N.set_inputs(mod, {"Start frame": float(frame_start), "End frame": float(max(frame_end, frame_start + 1))})
    return mod
