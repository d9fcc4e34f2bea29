"""What the Blender tests run for each generator: the operator, quick
keyword arguments, and the same call made straight through the binding
(so vertex counts can be compared with the library's)."""
import bpy

OPS = {
    "roots": "mesh.banyan_roots",
    "keyaki": "mesh.banyan_keyaki_tree",
    "avenue": "mesh.banyan_keyaki_avenue",
    "ivy": "mesh.banyan_ivy",
    "segments": "mesh.banyan_segment_twigs",
}

# Small but real runs (the defaults of ivy take seconds).
KWARGS = {
    "roots": {},
    "keyaki": {},
    "avenue": {"merged": False, "line_length": 30.0},
    "ivy": {"steps": 60},
    "segments": {},
}

IVY_CURSOR = (0.0, -1.3, -0.8)


def op(gen):
    mod, name = OPS[gen].split(".")
    return getattr(getattr(bpy.ops, mod), name)


def prepare(gen):
    """Scene tweaks before the operator runs (cursor for ivy)."""
    if gen == "ivy":
        bpy.context.scene.cursor.location = IVY_CURSOR


def library_mesh(gen, hosts_objs, kwargs):
    """The MeshData the library makes for what the operator was asked."""
    from banyan.engine import hosts as H
    from banyan.core import generators as G
    from banyan.engine import props as PP
    p = PP.addon_params(gen)  # the operators' defaults (wind data off)
    for k, v in kwargs.items():
        if k in p.by_name:
            p.set(k, v)
    cur = tuple(bpy.context.scene.cursor.location)
    # The operators' ground at the hosts' foot.
    floor = gen in ("roots", "ivy") and kwargs.get("ground_at_hosts", True) and "ground_z" not in kwargs
    if gen in ("roots", "ivy") and kwargs.get("host_shape", "SURFACE") == "SURFACE":
        with H.surface_host_set(hosts_objs) as hs:  # what the operators grow on by default
            if floor:
                p.set("ground_z", H.hosts_floor(hs))
            if gen == "roots":
                return G.roots(p, hs)
            p.set("start", H.closest_on_set(hs, cur))
            return G.ivy(p, hs)
    boxes = H.boxes_from_objects(hosts_objs)
    if floor:
        p.set("ground_z", H.hosts_floor(boxes))
    if gen == "roots":
        return G.roots(p, boxes)
    if gen == "keyaki":
        p.set("position", cur)
        return G.keyaki(p)
    if gen == "avenue":
        L = kwargs.get("line_length", 60.0)
        return G.avenue(p, [cur, (cur[0] + L, cur[1], cur[2])])
    if gen == "ivy":
        start, _ = H.closest_point(boxes, cur)
        p.set("start", start)
        return G.ivy(p, boxes)
    if gen == "segments":
        return G.segments(p)[0]
    raise KeyError(gen)


def bad_double(gen):
    """(key, value) of a plain double parameter set above its maximum."""
    from banyan.core import structs as S
    from banyan.core.params import specs
    for s in specs(gen):
        if s.type == S.PT_DOUBLE and s.unit != "deg" and s.max < 1e6:
            return s.name, s.max * 10 + 1
    raise LookupError("no bounded double in %s" % gen)
