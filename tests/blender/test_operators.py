"""Each operator on the default cube: objects made, meshes valid, vertex
counts equal the library's, attributes present; bad values give an error
report and an unchanged scene; undo restores the scene."""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bt  # noqa: E402
import gens  # noqa: E402

import bpy  # noqa: E402
from banyan.engine import props as PP  # noqa: E402
from banyan.engine import wind as W  # noqa: E402


def new_objects(before):
    return [o for o in bpy.data.objects if o.name not in before]


def check_mesh_objects(what, objs, lib_mesh):
    bt.check(all(o.type == 'MESH' for o in objs), "%s: all mesh objects" % what)
    total = sum(len(o.data.vertices) for o in objs)
    bt.check(total == lib_mesh.vertex_count, "%s: %d vertices, library %d" % (what, total, lib_mesh.vertex_count))
    tris = sum(len(o.data.polygons) for o in objs)
    bt.check(tris == lib_mesh.triangle_count, "%s: %d triangles, library %d" % (what, tris, lib_mesh.triangle_count))
    for o in objs:
        me = o.data
        bt.check(me.validate(verbose=False) is False, "%s: %s validates without fixes" % (what, o.name))
        for name in lib_mesh.attributes:
            if name in W.SCALARS:
                # The library's pivot scalars become one vector attribute (wind.py).
                bt.check(name not in me.attributes, "%s: %s has no attribute %s" % (what, o.name, name))
                name = W.PIVOT
            bt.check(name in me.attributes, "%s: %s has attribute %s" % (what, o.name, name))
        bt.check(len(me.uv_layers) == 1, "%s: %s has a UV map" % (what, o.name))
        bt.check(len(me.materials) == len(lib_mesh.materials), "%s: %s material slots" % (what, o.name))
    # Attribute values are the library's (first object, first vertices).
    if objs and lib_mesh.attributes:
        name, data = next(iter(lib_mesh.attributes.items()))
        o = objs[0]
        n = min(50, len(o.data.vertices))
        got = [o.data.attributes[name].data[i].value for i in range(n)]
        bt.check(got == list(data[:n]) or len(objs) > 1, "%s: attribute %s values" % (what, name))


def test_tube():
    bt.reset_scene()
    before = {o.name for o in bpy.data.objects}
    bt.check(bpy.ops.mesh.banyan_tube() == {'FINISHED'}, "tube operator finished")
    objs = new_objects(before)
    bt.check(len(objs) == 1, "tube: one object")
    bt.check(objs and objs[0].data.validate(verbose=False) is False, "tube mesh validates")


def test_generator(gen):
    bt.reset_scene()
    gens.prepare(gen)
    cube = bpy.data.objects["Cube"]
    bt.check(cube.select_get() and bpy.context.view_layer.objects.active == cube, "default cube selected")
    before = {o.name for o in bpy.data.objects}
    kw = gens.KWARGS[gen]
    res = gens.op(gen)(**kw)
    bt.check(res == {'FINISHED'}, "%s: operator finished (%s)" % (gen, res))
    objs = new_objects(before)
    lib = gens.library_mesh(gen, [cube], kw)
    if gen == "avenue":
        ntrees = len(lib.groups())
        bt.check(len(objs) == ntrees and ntrees > 1, "avenue: one object per tree (%d, %d)" % (len(objs), ntrees))
        colls = [c for c in bpy.data.collections if c.name.startswith("Keyaki Avenue")]
        bt.check(len(colls) == 1 and len(colls[0].objects) == ntrees, "avenue: a new collection holds the trees")
    else:
        bt.check(len(objs) == 1, "%s: one object (%d)" % (gen, len(objs)))
    check_mesh_objects(gen, objs, lib)
    bt.check(all(o.select_get() for o in objs), "%s: new objects selected" % gen)

    if gen == "avenue":  # merged variant
        bt.reset_scene()
        before = {o.name for o in bpy.data.objects}
        bt.check(gens.op(gen)(merged=True, line_length=30.0) == {'FINISHED'}, "avenue merged finished")
        objs = new_objects(before)
        bt.check(len(objs) == 1, "avenue merged: one object")
        check_mesh_objects("avenue merged", objs, lib)
    if gen == "ivy":
        test_ivy_animation(lib)
    if gen == "roots":
        mats = objs[0].data.materials
        from banyan.core.params import Params
        col = Params("roots").get("color")
        bt.check(len(mats) == 1 and all(abs(a - b) < 1e-6 for a, b in zip(mats[0].diffuse_color, col)),
                 "roots: material base colour is the root colour")


def test_ivy_animation(lib):
    bt.reset_scene()
    gens.prepare("ivy")
    sc = bpy.context.scene
    sc.frame_start, sc.frame_end = 1, 50
    before = {o.name for o in bpy.data.objects}
    bt.check(gens.op("ivy")(steps=60, animate=True) == {'FINISHED'}, "ivy animated finished")
    objs = new_objects(before)
    o = objs[0]
    bt.check(any(m.type == 'NODES' for m in o.modifiers), "ivy: geometry nodes modifier")
    counts = []
    for f in (1, 25, 50):
        sc.frame_set(f)
        dg = bpy.context.evaluated_depsgraph_get()
        ev = o.evaluated_get(dg)
        counts.append(len(ev.data.vertices))
    bt.check(counts[0] < counts[1] < counts[2], "ivy grows over the frames: %s" % counts)
    bt.check(counts[2] == lib.vertex_count, "ivy complete at the last frame (%d, %d)" % (counts[2], lib.vertex_count))
    bt.check(counts[0] > 0, "ivy: something at the first frame")
    # years > 0 grows years x shoot_growth / internode steps: the growth
    # modifier's last step follows it, not `steps`.
    bt.reset_scene()
    gens.prepare("ivy")
    before = {o.name for o in bpy.data.objects}
    kw = {PP.prop_name("steps"): 5, PP.prop_name("years"): 1.2, PP.prop_name("shoot_growth"): 1.5,
          PP.prop_name("internode"): 0.03, "animate": True}
    bt.check(gens.op("ivy")(**kw) == {'FINISHED'}, "ivy by years finished")
    objs = new_objects(before)
    last = [n.inputs["To Max"].default_value for m in objs[0].modifiers if m.type == 'NODES' and m.node_group
            for n in m.node_group.nodes if n.bl_idname == 'ShaderNodeMapRange']
    bt.check(last == [60.0], "ivy by years: the growth modifier ends at step %s, want 60" % last)


def test_bad_values(gen):
    bt.reset_scene()
    gens.prepare(gen)
    key, value = gens.bad_double(gen)
    for v in (value, float("nan")):
        state = bt.scene_state()
        kw = dict(gens.KWARGS[gen])
        kw[PP.prop_name(key)] = v
        try:
            res = gens.op(gen)(**kw)
            msg = ""
        except RuntimeError as e:
            res, msg = {'ERROR'}, str(e)
        bt.check(res == {'ERROR'} and key in msg, "%s: %s=%r reported as an error: %r" % (gen, key, v, msg))
        bt.check(bt.scene_state() == state, "%s: scene unchanged after %s=%r" % (gen, key, v))
    # A cross-field or host error after the params are fine (hosts for roots / ivy).
    if gen in ("roots", "ivy"):
        cube = bpy.data.objects["Cube"]
        cube.scale = (1.0, 1.0, 0.0)  # a flat host box is thickened, not refused
        bt.check(gens.op(gen)(host_shape='BOX', **gens.KWARGS[gen]) == {'FINISHED'}, "%s: flat host works" % gen)


def test_undo(gen):
    bt.reset_scene()
    gens.prepare(gen)
    # Background Blender has no undo stack until pushed; operators do not push
    # by themselves there, so push what the UI pushes: before and after.
    bpy.ops.ed.undo_push(message="init")
    bpy.ops.ed.undo_push(message="before")
    state = bt.scene_state()
    bt.check(gens.op(gen)(**gens.KWARGS[gen]) == {'FINISHED'}, "%s: ran for undo" % gen)
    bpy.ops.ed.undo_push(message=gens.OPS[gen])
    bt.check(bt.scene_state() != state, "%s: scene changed" % gen)
    bpy.ops.ed.undo()
    bt.check(bt.scene_state() == state, "%s: undo restores the scene" % gen)


bt.run(test_tube)
for g in gens.OPS:
    if bt.generator(g):
        bt.run(lambda: test_generator(g))
        bt.run(lambda: test_bad_values(g))
        bt.run(lambda: test_undo(g))
bt.done()
