"""The add-on's hand-off: a flat material (no library texture) made
by an earlier run with the same look is reused, never one an artist
edited since (a new one is made beside it, the edited one untouched);
vertices and wind pivots moved to the object's origin before the pivots
are written stay where the library put them in the world (one object,
one object per group, far from the origin); an avenue's trees join the
scene in their collection."""
import os
import sys
from array import array

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bt  # noqa: E402
import prod_util as U  # noqa: E402

import bpy  # noqa: E402
from mathutils import Vector  # noqa: E402
from banyan import api  # noqa: E402
from banyan.engine import build_mesh as BM  # noqa: E402
from banyan.engine import wind as W  # noqa: E402


def flat_materials():
    return [m for m in bpy.data.materials if m.get(BM.LOOK)]


def build(d, name="Plant", **kw):
    return BM.object_from_mesh_data(name, d, bpy.context.scene.collection, BM.Created(), **kw)


def bsdf(mat):
    return next(n for n in mat.node_tree.nodes if n.bl_idname == "ShaderNodeBsdfPrincipled")


def test_material_reuse():
    bt.reset_scene()
    a = build(U.synthetic_plant(), "A")
    b = build(U.synthetic_plant(), "B")
    ma, mb = a.data.materials[0], b.data.materials[0]
    bt.check(ma == mb and len(flat_materials()) == 1,
             "same look: one material, reused (%s, %s)" % (ma.name, mb.name))
    # A different look is another material (the key holds colour, roughness, sides).
    d = U.synthetic_plant()
    d.materials[0] = dict(d.materials[0], base_color=(0.1, 0.5, 0.1, 1.0))
    c = build(d, "C")
    bt.check(c.data.materials[0] != ma and len(flat_materials()) == 2, "another colour: another material")
    d = U.synthetic_plant()
    d.materials[0] = dict(d.materials[0], roughness=0.3)
    bt.check(build(d, "D").data.materials[0] not in (ma, c.data.materials[0]), "another roughness: another material")
    # An artist's edit: the material is theirs from then on.
    bsdf(ma).inputs["Roughness"].default_value = 0.123
    e = build(U.synthetic_plant(), "E")
    me = e.data.materials[0]
    bt.check(me != ma, "edited material not reused (%s)" % me.name)
    bt.check(abs(bsdf(ma).inputs["Roughness"].default_value - 0.123) < 1e-6,
             "edited material left as the artist set it")
    bt.check(abs(bsdf(me).inputs["Roughness"].default_value - 0.8) < 1e-6, "the new one has the library's look")
    bt.check(build(U.synthetic_plant(), "F").data.materials[0] == me, "then the new one is reused")
    # A node added counts as an edit too.
    me.node_tree.nodes.new("ShaderNodeRGB")
    bt.check(build(U.synthetic_plant(), "G").data.materials[0] not in (ma, me), "a node added: not reused")
    # A renamed, untouched material is still the same look.
    n = len(flat_materials())
    f = build(U.synthetic_plant(), "H").data.materials[0]
    f.name = "my wood"
    bt.check(build(U.synthetic_plant(), "I").data.materials[0] == f and len(flat_materials()) == n,
             "renamed but untouched: reused")
    # A failed build removes only what it made: the reused material stays.
    created = BM.Created()
    BM.object_from_mesh_data("J", U.synthetic_plant(), bpy.context.scene.collection, created)
    created.rollback()
    bt.check(f.name in bpy.data.materials, "rollback keeps a reused material")


def pivots_world(obj):
    a = obj.data.attributes[W.PIVOT]
    vec = array("f", bytes(12 * len(a.data)))
    a.data.foreach_get("vector", vec)
    mw = obj.matrix_basis  # no parent; matrix_world waits for an evaluation
    return [mw @ Vector(vec[3 * i:3 * i + 3]) for i in range(len(a.data))]


def coords_world(obj):
    mw = obj.matrix_basis  # no parent; matrix_world waits for an evaluation
    return [mw @ v.co for v in obj.data.vertices]


def plant_with_pivots(offset=(0.0, 0.0, 0.0), groups=1):
    """synthetic_plant with distinct pivots (each vertex's pivot 0.3 m below
    it), `groups` copies side by side (4 m apart in x), moved by offset."""
    base = U.synthetic_plant()
    d = U.synthetic_plant()
    nv = base.vertex_count
    pos, idx = array("f"), array("I")
    attrs = {k: array("f") for k in base.attributes}
    parts = []
    for g in range(groups):
        for i in range(nv):
            p = (base.positions[3 * i] + 4.0 * g + offset[0], base.positions[3 * i + 1] + offset[1],
                 base.positions[3 * i + 2] + offset[2])
            pos.extend(p)
            attrs["wind_pivot_x"].append(p[0])
            attrs["wind_pivot_y"].append(p[1])
            attrs["wind_pivot_z"].append(p[2] - 0.3)
        for k in base.attributes:
            if not k.startswith("wind_pivot"):
                attrs[k].extend(base.attributes[k])
        idx.extend(i + g * nv for i in base.indices)
        parts.append(dict(base.parts[0], vertex_offset=g * nv, index_offset=g * len(base.indices), group=g))
    d.positions, d.indices, d.attributes, d.parts = pos, idx, attrs, parts
    d.vertex_count, d.index_count = len(pos) // 3, len(idx)
    return d


def close(a, b, tol):
    return len(a) == len(b) and all((x - y).length <= tol for x, y in zip(a, b))


def expected(d, origin=(0.0, 0.0, 0.0)):
    o = Vector(origin)
    pts = [Vector(d.positions[3 * i:3 * i + 3]) + o for i in range(d.vertex_count)]
    piv = [Vector((d.attributes["wind_pivot_x"][i], d.attributes["wind_pivot_y"][i],
                   d.attributes["wind_pivot_z"][i])) + o for i in range(d.vertex_count)]
    return pts, piv


def test_pivots_placed():
    bt.reset_scene()
    d = plant_with_pivots((5.0, -3.0, 1.0))
    pts, piv = expected(d)
    for origin in ((2.0, 1.0, 0.5), None, (5.0, -3.0, 1.0)):
        obj = build(d, "P", origin=origin)
        bt.check(close(coords_world(obj), pts, 1e-5), "origin %s: vertices stay in the world" % (origin,))
        bt.check(close(pivots_world(obj), piv, 1e-5), "origin %s: pivots stay in the world" % (origin,))
        if origin is not None:
            bt.check((obj.location - Vector(origin)).length < 1e-6, "origin %s: object there" % (origin,))
    # Far from the origin: the mesh's own origin holds the kilometres.
    far = plant_with_pivots()
    far.origin = (1.0e6 + 0.37, -2.0e6, 12.0)
    pts, piv = expected(far, far.origin)
    obj = build(far, "Far", origin=(1.0e6, -2.0e6, 12.0))
    bt.check(close(coords_world(obj), pts, 0.1), "far: vertices in place (float32 world matrix)")
    lo = Vector(obj.location)
    # Local to the object, exactly: vertex - pivot = the library's 0.3 m.
    loc_v = [v.co for v in obj.data.vertices]
    a = obj.data.attributes[W.PIVOT]
    bt.check(all(abs((loc_v[i] - Vector(a.data[i].vector)).z - 0.3) < 1e-5 and
                 abs((loc_v[i] - Vector(a.data[i].vector)).x) < 1e-5 for i in range(len(loc_v))),
             "far: pivots 0.3 m below their vertices in the object's frame (lo %s)" % (tuple(lo),))


def test_pivots_per_group():
    bt.reset_scene()
    d = plant_with_pivots((10.0, 2.0, 0.0), groups=3)
    pts, piv = expected(d)
    coll = bpy.data.collections.new("groups")
    bpy.context.scene.collection.children.link(coll)
    objs = BM.objects_per_group("G", d, coll, BM.Created())
    bt.check(len(objs) == 3, "three groups, three objects")
    nv = d.vertex_count // 3
    for g, o in enumerate(objs):
        bt.check(close(coords_world(o), pts[g * nv:(g + 1) * nv], 1e-5), "group %d: vertices in place" % g)
        bt.check(close(pivots_world(o), piv[g * nv:(g + 1) * nv], 1e-5), "group %d: pivots in place" % g)
        bt.check(abs(o.location.z) < 1e-6 and abs(o.location.x - (10.0 + 4.0 * g)) < 1e-5,
                 "group %d: origin at its foot %s" % (g, tuple(o.location)))
    mats = {o.data.materials[0] for o in objs}
    bt.check(len(mats) == 1, "one material for every group")


def test_avenue():
    if not bt.generator("avenue"):
        return
    bt.reset_scene()
    objs = api.keyaki_avenue(path=[(0, 0, 0), (30, 0, 0)], tree__levels=5)
    bt.check(len(objs) >= 2, "avenue: %d trees" % len(objs))
    colls = {c for o in objs for c in o.users_collection}
    bt.check(len(colls) == 1 and next(iter(colls)).name.startswith("Keyaki Avenue"), "avenue: one collection")
    coll = next(iter(colls))
    bt.check(coll.name in bpy.context.scene.collection.children, "avenue: its collection is in the scene")
    bpy.context.view_layer.update()
    bt.check(all(o.name in bpy.context.view_layer.objects for o in objs), "avenue: every tree in the view layer")
    mats = {m for o in objs for m in o.data.materials}
    bt.check(len(mats) == len(objs[0].data.materials), "avenue: the trees share their materials (%d)" % len(mats))


def test_topology_ahead():
    if not bt.generator("keyaki"):
        return
    bt.reset_scene()
    job = api.keyaki_tree_job(levels=5)
    with job:
        job.compute()
        topo = job.data.topology
        bt.check(topo is not None and len(topo[0]) == job.data.index_count, "compute: the edge list made ahead")
        obj = job.build()[0]
    me = obj.data
    bt.check(len(me.edges) == len(topo[1]) // 2, "the mesh has the edges made ahead (%d)" % len(me.edges))
    bt.check(me.validate(verbose=False) is False, "and validates without fixes")
    # A wrong edge list (another mesh's) is not used: the edges come from the indices.
    d = U.synthetic_plant()
    d.topology = topo
    o2 = build(d, "Other")
    bt.check(o2.data.validate(verbose=False) is False, "a stale edge list is ignored")


for t in (test_material_reuse, test_pivots_placed, test_pivots_per_group, test_avenue, test_topology_ahead):
    bt.run(t)
bt.done()
