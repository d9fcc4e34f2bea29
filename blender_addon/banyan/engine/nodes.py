"""Small helpers for the add-on's Geometry Nodes groups (wind, growth):
group sockets across Blender's interface API change (4.0), typed output
sockets of nodes whose outputs change with their data type, and shared
groups made once per .blend."""
import bpy


def socket(node, kind, stype):
    """node's first enabled input ("in") or output ("out") of type stype."""
    socks = node.outputs if kind == "out" else node.inputs
    return next(s for s in socks if s.type == stype and s.enabled)


def new_socket(ng, name, in_out, stype, default=None, lo=None, hi=None, description=""):
    """A group input or output; its identifier keys the modifier's value."""
    if hasattr(ng, "interface"):  # Blender 4.0+
        s = ng.interface.new_socket(name, in_out=in_out, socket_type=stype)
    else:
        s = (ng.inputs if in_out == 'INPUT' else ng.outputs).new(stype, name)
    if default is not None:
        s.default_value = default
    if lo is not None:
        s.min_value = lo
    if hi is not None:
        s.max_value = hi
    if description and hasattr(s, "description"):
        s.description = description
    return s


def group_inputs(ng):
    """{name: identifier} of a group's inputs."""
    if hasattr(ng, "interface"):
        return {i.name: i.identifier for i in ng.interface.items_tree
                if getattr(i, "item_type", "SOCKET") == 'SOCKET' and i.in_out == 'INPUT'}
    return {s.name: s.identifier for s in ng.inputs}


def shared_group(key, version, name, build, created):
    """The node group tagged key == version in this .blend, else a new one
    made by build(ng) (recorded in created for rollback)."""
    for ng in bpy.data.node_groups:
        if ng.get(key) == version and ng.bl_idname == 'GeometryNodeTree':
            return ng
    ng = bpy.data.node_groups.new(name, 'GeometryNodeTree')
    if created is not None:
        created.add(ng)
    ng[key] = version
    build(ng)
    return ng


def _input_values(mod):
    """Where a Geometry Nodes modifier keeps its input values: Blender 5.2+
    has mod.properties.inputs, one struct per input identifier whose
    `.value` is the value (the modifier itself takes no ID properties
    there); earlier versions keep them as ID properties of the
    modifier keyed by identifier, and get None here."""
    props = getattr(mod, "properties", None)
    return getattr(props, "inputs", None)


def set_inputs(mod, values):
    """Sets a Geometry Nodes modifier's inputs by socket name."""
    ids = group_inputs(mod.node_group)
    inputs = _input_values(mod)
    for k, v in values.items():
        if v is None:
            continue
        if k not in ids:
            raise KeyError("the node group '%s' has no input '%s'" % (mod.node_group.name, k))
        if inputs is not None:
            getattr(inputs, ids[k]).value = v
        elif hasattr(mod.get(ids[k]), "to_list"):
            mod[ids[k]][:] = v  # in place: an array made from Python floats is doubles, which 3.4 ignores
        else:
            mod[ids[k]] = v
    mod.id_data.update_tag()  # an ID property write alone does not re-evaluate the modifier


def copy_inputs(src, dst):
    """Copies a Geometry Nodes modifier's input values, attribute toggles
    included, to dst, which has the same node group."""
    si, di = _input_values(src), _input_values(dst)
    if si is None:
        for k in src.keys():
            try:
                dst[k] = src[k]
            except (TypeError, KeyError):
                pass
        return
    for name in si.bl_rna.properties.keys():
        s, d = getattr(si, name, None), getattr(di, name, None)
        if name in ("rna_type", "name") or s is None or d is None:
            continue
        for p in s.bl_rna.properties:
            if p.identifier not in ("rna_type", "name") and not p.is_readonly:
                try:
                    setattr(d, p.identifier, getattr(s, p.identifier))
                except (TypeError, AttributeError, ValueError):
                    pass


def get_input(mod, name):
    """A Geometry Nodes modifier's input value by socket name."""
    ident = group_inputs(mod.node_group)[name]
    inputs = _input_values(mod)
    return getattr(inputs, ident).value if inputs is not None else mod[ident]


class Builder:
    """Adds nodes to a tree in a row, linking by socket objects."""

    def __init__(self, ng):
        self.ng = ng
        self.n = 0

    def node(self, kind, **props):
        nd = self.ng.nodes.new(kind)
        for k, v in props.items():
            setattr(nd, k, v)
        nd.location = (180 * (self.n // 6), -160 * (self.n % 6))
        self.n += 1
        return nd

    def link(self, a, b):
        self.ng.links.new(a, b)

    def math(self, op, a, b=None, c=None):
        """A Math node: a, b, c are sockets or numbers; returns its output."""
        nd = self.node('ShaderNodeMath', operation=op)
        for i, x in enumerate((a, b, c)):
            if x is None:
                continue
            if isinstance(x, (int, float)):
                nd.inputs[i].default_value = float(x)
            else:
                self.link(x, nd.inputs[i])
        return nd.outputs[0]

    def attribute(self, name, data_type='FLOAT'):
        nd = self.node('GeometryNodeInputNamedAttribute', data_type=data_type)
        nd.inputs["Name"].default_value = name
        return socket(nd, "out", 'VALUE' if data_type == 'FLOAT' else 'VECTOR')
