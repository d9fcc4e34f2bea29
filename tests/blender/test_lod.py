"""Levels of detail: banyan.api.make_lods / Make LODs on a
keyaki (and roots) grown by an operator: a collection "<name> LODs" with
<name>_LOD0 (the plant's own mesh) .. LOD2 at about 50 % and 15 % of its
triangles (within 10 %), bounding boxes within 5 %, and for the tree a
last billboard level whose material packs an image. Bad ratios are
refused with nothing left behind."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bt  # noqa: E402
import gens  # noqa: E402

import bpy  # noqa: E402
from banyan import api  # noqa: E402
from banyan.core.errors import BanyanError  # noqa: E402


def tris(o):
    return sum(len(p.vertices) - 2 for p in o.data.polygons)


def bounds(o):
    from mathutils import Vector
    pts = [o.matrix_world @ Vector(c) for c in o.bound_box]
    return [min(p[k] for p in pts) for k in range(3)], [max(p[k] for p in pts) for k in range(3)]


def check_lods(obj, gen, billboard):
    name = obj.name
    before = bt.scene_state()
    for bad in ((0.0,), (1.5,), ("x",), (0.15, 0.5), (1.0,)):
        try:
            api.make_lods(obj, ratios=bad)
            bt.check(False, "%s: ratios %r refused" % (gen, bad))
        except BanyanError as e:
            bt.check("ratios" in e.message, "%s: the refusal names ratios: %s" % (gen, e.message))
    bt.check(bt.scene_state() == before, "%s: a refused call leaves nothing" % gen)
    try:
        objs = api.make_lods(obj, ratios=(0.5, 0.15), billboard=billboard)
    except BanyanError as e:
        bt.check(False, "%s: make_lods built (%s)" % (gen, e.message))
        bt.check(bt.scene_state() == before, "%s: a failed make_lods leaves nothing" % gen)
        return
    coll = bpy.data.collections.get("%s LODs" % name)
    bt.check(coll is not None and [o.name for o in objs] == ["%s_LOD%d" % (name, k) for k in range(len(objs))]
             and all(o.name in coll.objects for o in objs), "%s: %s_LOD0.. in '%s LODs'" % (gen, name, name))
    bt.check(len(objs) == 3 + bool(billboard), "%s: %d levels" % (gen, len(objs)))
    bt.check(objs[0].data == obj.data, "%s: LOD0 is the plant's own mesh" % gen)
    t0 = tris(obj)
    lo0, hi0 = bounds(obj)
    size = max(hi0[k] - lo0[k] for k in range(3))
    for o, r in zip(objs[1:3], (0.5, 0.15)):
        got = tris(o) / t0
        print("%s: %s keeps %.3f of %d triangles" % (gen, o.name, got, t0))
        bt.check(abs(got - r) <= 0.1 * r, "%s: %s keeps %.3f of %d triangles (asked %.2f, 10 %%)"
                 % (gen, o.name, got, t0, r))
        lo, hi = bounds(o)
        err = max(max(abs(lo[k] - lo0[k]), abs(hi[k] - hi0[k])) for k in range(3))
        bt.check(err <= 0.05 * size, "%s: %s bounds within 5 %% (%.3g m of %.3g m)" % (gen, o.name, err, size))
    if billboard:
        bb = objs[-1]
        imgs = [n.image for s in bb.material_slots if s.material and s.material.node_tree
                for n in s.material.node_tree.nodes if n.bl_idname == 'ShaderNodeTexImage' and n.image]
        bt.check(imgs and imgs[0].packed_file is not None and imgs[0].size[0] > 0,
                 "%s: the billboard's material packs an image" % gen)
        bt.check(tris(bb) < 0.05 * t0, "%s: the billboard is a few cards (%d triangles)" % (gen, tris(bb)))
        # The top card (a single-sided material) is transparent from below in
        # a render too: its alpha passes through the Geometry node's Backfacing.
        mats = [s.material for s in bb.material_slots if s.material and s.material.node_tree]
        single = [m for m in mats if m.use_backface_culling]
        bt.check(len(single) == 1 and len(mats) == 2, "%s: vertical cards and one single-sided top card (%s)"
                 % (gen, [(m.name, m.use_backface_culling) for m in mats]))
        for m in single:
            bt.check(any(lk.from_socket.name == "Backfacing" for lk in m.node_tree.links),
                     "%s: %s hides its back face in a render" % (gen, m.name))


def build(gen, **kw):
    gens.prepare(gen)
    before = {o.name for o in bpy.data.objects}
    res = gens.op(gen)(**dict(gens.KWARGS[gen], **kw))
    bt.check(res == {'FINISHED'}, "%s: built" % gen)
    return [o for o in bpy.data.objects if o.name not in before]


def test_keyaki():
    if not bt.generator("keyaki"):
        return
    bt.reset_scene()
    obj = build("keyaki", levels=6)[0]
    obj.location = (4.0, 1.0, 0.0)  # the levels stand where the plant stands now
    check_lods(obj, "keyaki", True)


def test_roots():
    if not bt.generator("roots"):
        return
    bt.reset_scene()
    obj = build("roots", growth_points=10)[0]
    check_lods(obj, "roots", False)


def test_not_a_plant():
    bt.reset_scene()
    try:
        api.make_lods(bpy.data.objects["Cube"])
        bt.check(False, "a plain cube is refused")
    except BanyanError as e:
        bt.check("Cube" in e.message, "the refusal names the object: %s" % e.message)


for t in (test_not_a_plant, test_keyaki, test_roots):
    bt.run(t)
bt.done()
