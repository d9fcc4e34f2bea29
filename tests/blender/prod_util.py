"""Helpers of the production tests (wind, growth, LOD, instancing):
evaluated coordinates at a frame, synthetic plants with the attributes
the library writes, attribute reads without per-vertex Python."""
from array import array

import bpy


def evaluated_coords(obj, frame):
    """Flat 'f' array of obj's evaluated vertex positions (object space) at frame."""
    bpy.context.scene.frame_set(frame)
    dg = bpy.context.evaluated_depsgraph_get()
    ev = obj.evaluated_get(dg)
    me = ev.to_mesh()
    try:
        out = array("f", bytes(12 * len(me.vertices)))
        me.vertices.foreach_get("co", out)
        return out
    finally:
        ev.to_mesh_clear()


def evaluated_count(obj, frame):
    return len(evaluated_coords(obj, frame)) // 3


def rest_coords(obj):
    out = array("f", bytes(12 * len(obj.data.vertices)))
    obj.data.vertices.foreach_get("co", out)
    return out


def attribute(me, name):
    a = me.attributes[name]
    n = len(a.data)
    if a.data_type == 'FLOAT_VECTOR':
        out = array("f", bytes(12 * n))
        a.data.foreach_get("vector", out)
    else:
        out = array("f", bytes(4 * n))
        a.data.foreach_get("value", out)
    return out


def displacement_by_height(rest, moved, share=0.1):
    """(mean displacement of the top share of vertices by height, of the
    bottom share, max displacement of the bottom share)."""
    n = len(rest) // 3
    order = sorted(range(n), key=lambda i: rest[3 * i + 2])
    k = max(1, int(n * share))

    def d(i):
        return sum((moved[3 * i + c] - rest[3 * i + c]) ** 2 for c in range(3)) ** 0.5
    bottom = [d(i) for i in order[:k]]
    top = [d(i) for i in order[-k:]]
    return sum(top) / k, sum(bottom) / k, max(bottom)


def synthetic_plant(n=40, height=8.0):
    """A MeshData like a generator's: a vertical strip (the trunk, pivot at
    its foot, stiffness 1 at the foot falling to 0 at the top, birth
    rising ring by ring) with the library's attribute names."""
    from banyan.core.mesh import MeshData
    d = MeshData()
    pos, idx = array("f"), array("I")
    for k in range(n):
        z = height * k / (n - 1)
        pos.extend([-0.1, 0.0, z, 0.1, 0.0, z])
    for k in range(n - 1):
        a = 2 * k
        idx.extend([a, a + 1, a + 3, a, a + 3, a + 2])
    nv = 2 * n
    d.vertex_count, d.index_count, d.positions, d.indices = nv, len(idx), pos, idx
    up = array("f", [(v // 2) / (n - 1) for v in range(nv)])
    zero = array("f", [0.0]) * nv
    d.attributes = {"wind_pivot_x": zero, "wind_pivot_y": zero, "wind_pivot_z": zero, "wind_level": zero,
                    "wind_stiffness": array("f", [1.0 - u for u in up]), "wind_phase": array("f", [0.25]) * nv,
                    "wind_flutter": zero, "birth": up}
    d.materials = [{"name": "wood", "base_color": (0.4, 0.3, 0.2, 1.0), "roughness": 0.8, "double_sided": False,
                    "texture": 0, "season": 0, "alpha_cutoff": 0.0, "translucency": 0.0, "image": 0}]
    d.parts = [{"vertex_offset": 0, "vertex_count": nv, "index_offset": 0, "index_count": len(idx), "material": 0,
                "group": 0}]
    return d
