"""Edit later: a plant built by an operator or by banyan.api keeps its
generator, params, seed, hosts and options on the object, through save and
reload and duplication; Regenerate rebuilds it in place (same object and
name, user modifiers, materials and transform kept) and a failing one
leaves the object as it was."""
import json
import os
import shutil
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bt  # noqa: E402
import gens  # noqa: E402

import bpy  # noqa: E402
from banyan.engine import plant as PL  # noqa: E402
from banyan.engine import props as PP  # noqa: E402
from banyan.core.params import Params  # noqa: E402


def new_objects(before):
    return [o for o in bpy.data.objects if o.name not in before]


def build(gen, **kw):
    before = {o.name for o in bpy.data.objects}
    res = gens.op(gen)(**dict(gens.KWARGS[gen], **kw))
    bt.check(res == {'FINISHED'}, "%s: operator finished (%s)" % (gen, res))
    return new_objects(before)


def coords(obj):
    from array import array
    a = array("f", [0.0]) * (3 * len(obj.data.vertices))
    obj.data.vertices.foreach_get("co", a)
    return a


def close(a, b, eps=1e-4):
    return len(a) == len(b) and all(abs(x - y) <= eps for x, y in zip(a, b))


def regenerate():
    """bpy.ops.banyan.regenerate() -> (result, error message)."""
    try:
        return bpy.ops.banyan.regenerate(), ""
    except RuntimeError as e:  # an ERROR report from an operator called by Python
        return {'ERROR'}, str(e)


def object_state(obj):
    return (obj.name, obj.data.name, len(obj.data.vertices), tuple(coords(obj)[:30]),
            tuple(tuple(r) for r in obj.matrix_world), [m.name for m in obj.modifiers],
            [s.material.name if s.material else None for s in obj.material_slots], obj.banyan_plant.params,
            obj.banyan_plant.lossy, bt.scene_state())


def user_edits(obj):
    """What an artist does to a plant: a modifier, a material, a move."""
    obj.modifiers.new("User Decimate", 'DECIMATE')
    mat = bpy.data.materials.new("User Bark")
    obj.material_slots[0].material = mat
    return mat


def save_reload(name):
    """Saves the scene to a temporary .blend and opens it again; the file
    and its folder are removed once open (Blender holds the data)."""
    d = tempfile.mkdtemp(prefix="banyan_plant_")
    path = os.path.join(d, "plant.blend")
    try:
        bpy.ops.wm.save_as_mainfile(filepath=path)
        bpy.ops.wm.open_mainfile(filepath=path)
    finally:
        shutil.rmtree(d, ignore_errors=True)
    obj = bpy.data.objects[name]
    bpy.context.view_layer.objects.active = obj
    return obj


def test_roots():
    bt.reset_scene()
    cube = bpy.data.objects["Cube"]
    objs = build("roots", sides=6, surface="tubes")  # sides shape the tubes (the fused surface has voxels)
    bt.check(len(objs) == 1, "roots: one object")
    obj = objs[0]
    pl = obj.banyan_plant
    bt.check(PL.is_plant(obj) and pl.generator == "roots", "roots: recorded as a roots plant")
    doc = json.loads(pl.params)
    bt.check(doc["generator"] == "roots" and doc["params"]["sides"] == 6, "roots: params JSON has sides=6")
    bt.check(pl.seed == str(doc["params"]["seed"]), "roots: seed %r recorded" % pl.seed)
    bt.check([h.object for h in pl.hosts] == [cube], "roots: host is the cube (pointer)")
    opt = PL.options(obj)
    bt.check(opt.get("host_shape") == 'SURFACE' and opt.get("operator") == "mesh.banyan_roots",
             "roots: options recorded: %s" % opt)
    bt.check(pl.roots.sides == 6, "roots: editable view holds sides=6")
    bt.check(PL.edited(obj) == [], "roots: nothing edited right after the build")
    bt.check(PL.current_params(obj).raw() == PL.stored_params(obj).raw(), "roots: view maps back to the exact params")

    # Save and reload: everything is still there, the host found by pointer.
    name, n0 = obj.name, len(obj.data.vertices)
    c0 = coords(obj)
    obj = save_reload(name)
    pl = obj.banyan_plant
    bt.check(PL.is_plant(obj) and json.loads(pl.params) == doc, "roots: params survive save/reload")
    bt.check([h.object.name for h in pl.hosts] == ["Cube"], "roots: host pointer survives save/reload")
    bt.check(pl.roots.sides == 6, "roots: view survives save/reload")

    # Regenerate unchanged: same object, same geometry.
    mesh_name = obj.data.name
    res, msg = regenerate()
    bt.check(res == {'FINISHED'}, "roots: regenerate unchanged finished %s %s" % (res, msg))
    bt.check(obj.name == name and obj.data.name == mesh_name, "roots: same object and mesh name")
    bt.check(close(coords(obj), c0), "roots: unchanged params give the same vertices")
    bt.check(len(bpy.data.meshes) == len({o.data for o in bpy.data.objects if o.type == 'MESH'}),
             "roots: no orphan mesh left after regenerate")

    # Artist's edits, then a parameter edit in the sidebar, then Regenerate.
    mat = user_edits(obj)
    obj.rotation_euler = (0.0, 0.0, 0.5)
    bpy.context.view_layer.update()
    mw = obj.matrix_world.copy()
    bpy.data.objects["Cube"].name = "Renamed Host"
    pl.roots.sides = 12
    bt.check(PL.edited(obj) == ["sides"], "roots: the edit is seen: %s" % PL.edited(obj))
    bt.check(bpy.ops.banyan.copy_preset() == {'FINISHED'}, "roots: copy as preset finished")
    doc2 = json.loads(PL.current_params(obj).to_preset())
    bt.check(doc2["params"]["sides"] == 12 and doc2["params"]["seed"] == doc["params"]["seed"],
             "roots: the preset text has the edit")
    nmats = len(bpy.data.materials)
    res, msg = regenerate()
    bt.check(res == {'FINISHED'}, "roots: regenerate after edits finished %s %s" % (res, msg))
    bt.check(obj.name == name and bpy.data.objects.get(name) == obj, "roots: same object, same name")
    bt.check(obj.modifiers.get("User Decimate") is not None, "roots: user modifier kept")
    bt.check(obj.material_slots[0].material == mat, "roots: user material kept")
    bt.check(len(bpy.data.materials) == nmats, "roots: no material left over by the rebuild")
    bt.check(all(abs(a - b) < 1e-6 for ra, rb in zip(obj.matrix_world, mw) for a, b in zip(ra, rb)),
             "roots: transform kept")
    n1 = len(obj.data.vertices)
    bt.check(n1 > n0 * 1.5, "roots: 12 sides instead of 6 gives more vertices (%d -> %d)" % (n0, n1))
    bt.check(json.loads(obj.banyan_plant.params)["params"]["sides"] == 12, "roots: the edit is now stored")
    bt.check(obj.data.validate(verbose=False) is False, "roots: regenerated mesh validates")
    # Hosted plants grow where the host is: world vertices equal a plain build on the host.
    from banyan import api
    ref = api.strangler_roots(hosts=[bpy.data.objects["Renamed Host"]], params=PL.stored_params(obj))[0]
    w_ref = [ref.matrix_basis @ v.co for v in ref.data.vertices[:50]]  # no depsgraph update needed
    w_obj = [obj.matrix_world @ v.co for v in obj.data.vertices[:50]]
    bt.check(all((a - b).length < 1e-4 for a, b in zip(w_ref, w_obj)), "roots: regrown around the host in world space")
    bpy.data.objects.remove(ref)

    # Out of range in the sidebar: error naming the key, object untouched.
    before = object_state(obj)
    pl.roots.sides = 1000
    res, msg = regenerate()
    bt.check(res == {'ERROR'} and "sides" in msg, "roots: sides=1000 reported: %r" % msg)
    pl.roots.sides = 12
    bt.check(object_state(obj) == before, "roots: object unchanged after the failed regenerate")

    # Host deleted (as the X key does): error naming it, object untouched.
    host = bpy.data.objects["Renamed Host"]
    for o in bpy.context.selected_objects:
        o.select_set(False)
    host.select_set(True)
    bpy.ops.object.delete()
    bpy.context.view_layer.objects.active = obj
    obj.select_set(True)
    bt.check(PL.host_status(obj) == [("Renamed Host", None)], "roots: deleted host seen: %s" % PL.host_status(obj))
    before = object_state(obj)
    res, msg = regenerate()
    bt.check(res == {'ERROR'} and "Renamed Host" in msg and "deleted" in msg, "roots: deleted host reported: %r" % msg)
    bt.check(object_state(obj) == before, "roots: object unchanged when its host is gone")
    draw_panel(obj)


def test_ivy():
    bt.reset_scene()
    gens.prepare("ivy")
    sc = bpy.context.scene
    sc.frame_start, sc.frame_end = 1, 50
    obj = build("ivy", animate=True)[0]
    pl = obj.banyan_plant
    start = json.loads(pl.params)["params"]["start"]
    bt.check(start != list(Params("ivy").get("start")), "ivy: the start used (snapped cursor) is recorded: %s" % start)
    bt.check(PL.options(obj).get("animate") is True, "ivy: animate option recorded")
    n0, c0 = len(obj.data.vertices), coords(obj)
    res, msg = regenerate()
    bt.check(res == {'FINISHED'} and close(coords(obj), c0), "ivy: unchanged regenerate gives the same vertices %s" % msg)
    mods = [m.name for m in obj.modifiers]
    bt.check(mods == ["Banyan Growth"], "ivy: one growth modifier, not a second: %s" % mods)
    pl.ivy.steps = 30
    res, msg = regenerate()
    bt.check(res == {'FINISHED'}, "ivy: regenerate with steps=30 %s" % msg)
    n1 = len(obj.data.vertices)
    bt.check(0 < n1 < n0, "ivy: fewer steps, fewer vertices (%d -> %d)" % (n0, n1))
    ng = obj.modifiers["Banyan Growth"].node_group
    to_max = [n.inputs["To Max"].default_value for n in ng.nodes if n.bl_idname == 'ShaderNodeMapRange']
    bt.check(to_max == [30.0], "ivy: growth animation ends at the new last step: %s" % to_max)
    sc.frame_set(50)
    ev = obj.evaluated_get(bpy.context.evaluated_depsgraph_get())
    bt.check(len(ev.data.vertices) == n1, "ivy: whole plant at the last frame after regenerate")

    # Duplicate: the copy is a plant too and regenerates on its own.
    for o in bpy.context.selected_objects:
        o.select_set(False)
    obj.select_set(True)
    bpy.context.view_layer.objects.active = obj
    bpy.ops.object.duplicate()
    dup = bpy.context.active_object
    bt.check(dup != obj and PL.is_plant(dup) and dup.banyan_plant.params == obj.banyan_plant.params,
             "ivy: a duplicate keeps the record")
    bt.check([h.object for h in dup.banyan_plant.hosts] == [bpy.data.objects["Cube"]], "ivy: duplicate keeps hosts")
    dup.banyan_plant.ivy.steps = 20
    res, msg = regenerate()
    bt.check(res == {'FINISHED'} and len(dup.data.vertices) < n1 and len(obj.data.vertices) == n1,
             "ivy: regenerating the duplicate leaves the original alone %s" % msg)

    # Host removed from the file: error, nothing changes.
    bpy.context.view_layer.objects.active = obj
    bpy.data.objects.remove(bpy.data.objects["Cube"])
    before = object_state(obj)
    res, msg = regenerate()
    bt.check(res == {'ERROR'} and "Cube" in msg, "ivy: removed host reported: %r" % msg)
    bt.check(object_state(obj) == before, "ivy: object unchanged when its host is gone")


def test_keyaki():
    bt.reset_scene()
    bpy.context.scene.cursor.location = (3.0, -2.0, 0.0)
    obj = build("keyaki", levels=8)[0]
    pl = obj.banyan_plant
    bt.check(json.loads(pl.params)["params"]["position"] == [3.0, -2.0, 0.0], "keyaki: position recorded")
    bt.check(len(pl.hosts) == 0, "keyaki: no hosts")
    mat = user_edits(obj).name
    name, n0, c0 = obj.name, len(obj.data.vertices), coords(obj)
    obj.location = (10.0, 0.0, 0.0)  # the artist moves the tree: it stays moved
    obj.scale = (2.0, 2.0, 2.0)
    bpy.context.scene.cursor.location = (-50.0, 0.0, 0.0)  # not used by a regenerate
    obj = save_reload(name)
    res, msg = regenerate()
    bt.check(res == {'FINISHED'}, "keyaki: regenerate finished %s" % msg)
    bt.check(close(coords(obj), c0), "keyaki: unchanged params: same local vertices after a move")
    bt.check(tuple(obj.location) == (10.0, 0.0, 0.0) and tuple(obj.scale) == (2.0, 2.0, 2.0), "keyaki: transform kept")
    obj.banyan_plant.keyaki.levels = 10
    res, msg = regenerate()
    n1 = len(obj.data.vertices)
    bt.check(res == {'FINISHED'} and n1 > n0, "keyaki: more levels, more vertices (%d -> %d) %s" % (n0, n1, msg))
    bt.check(obj.material_slots[0].material.name == mat and obj.modifiers.get("User Decimate"),
             "keyaki: material and modifier kept")
    old_seed = obj.banyan_plant.seed
    c1 = coords(obj)
    bt.check(bpy.ops.banyan.randomize_seed() == {'FINISHED'}, "keyaki: randomize seed finished")
    bt.check(obj.banyan_plant.seed != old_seed and not close(coords(obj), c1), "keyaki: new seed, new tree")
    bt.check(bpy.data.objects.get(name) == obj, "keyaki: still the same object")
    draw_panel(obj)


def test_segments():
    bt.reset_scene()
    bpy.context.scene.cursor.location = (1.0, 2.0, 0.0)
    obj = build("segments")[0]
    c0, n0 = coords(obj), len(obj.data.vertices)
    bt.check(tuple(obj.location) == (1.0, 2.0, 0.0), "segments: object at the cursor")
    res, msg = regenerate()
    bt.check(res == {'FINISHED'} and close(coords(obj), c0), "segments: unchanged regenerate, same vertices %s" % msg)
    bt.check(tuple(obj.location) == (1.0, 2.0, 0.0), "segments: still at the cursor")
    obj.banyan_plant.segments.seed = 7
    res, msg = regenerate()
    bt.check(res == {'FINISHED'} and not close(coords(obj), c0), "segments: a new seed, a new tree %s" % msg)
    draw_panel(obj)


def test_avenue():
    bt.reset_scene()
    objs = build("avenue", tree__levels=6)
    names = sorted(o.name for o in objs)
    groups = {o.banyan_plant.group for o in objs}
    bt.check(len(objs) > 1 and len(groups) == 1 and "" not in groups, "avenue: %d trees, one group" % len(objs))
    bt.check(sorted(o.banyan_plant.index for o in objs) == list(range(len(objs))), "avenue: trees numbered")
    # The cursor line: as path points, or as the params' start-end line.
    line = PL.options(objs[0]).get("path_points") or [json.loads(objs[0].banyan_plant.params)["params"][k]
                                                     for k in ("start", "end")]
    bt.check(abs(line[1][0] - line[0][0] - 30.0) < 1e-6, "avenue: the 30 m cursor line recorded: %s" % line)
    counts = {o.name: len(o.data.vertices) for o in objs}
    coll = objs[0].users_collection[0]
    bpy.context.view_layer.objects.active = objs[-1]
    res, msg = regenerate()
    bt.check(res == {'FINISHED'}, "avenue: regenerate finished %s" % msg)
    bt.check(sorted(o.name for o in coll.objects) == names, "avenue: the same trees after regenerate")
    bt.check({o.name: len(o.data.vertices) for o in coll.objects} == counts, "avenue: same vertex counts")
    act = bpy.context.view_layer.objects.active
    n = len(objs)
    act.banyan_plant.avenue.spacing = 4.0
    res, msg = regenerate()
    n1 = len(coll.objects)
    bt.check(res == {'FINISHED'} and n1 > n, "avenue: spacing 8 -> 4 m, %d -> %d trees %s" % (n, n1, msg))
    bt.check(set(names) <= {o.name for o in coll.objects}, "avenue: the old trees are still the same objects")
    bt.check(all(PL.is_plant(o) for o in coll.objects) and len({o.banyan_plant.group for o in coll.objects}) == 1,
             "avenue: every tree recorded, one group")
    # The trees stand where a fresh build with the same values puts them.
    from banyan import api
    fresh = api.keyaki_avenue(path=PL.options(act).get("path_points"), params=PL.stored_params(act))
    bpy.context.view_layer.update()
    spots = sorted(tuple(round(c, 4) for c in o.matrix_world.translation) for o in coll.objects)
    want = sorted(tuple(round(c, 4) for c in o.matrix_world.translation) for o in fresh)
    bt.check(spots == want, "avenue: regenerated trees at the fresh build's places: %s %s" % (spots[:3], want[:3]))
    bt.check(sorted(len(o.data.vertices) for o in coll.objects) == sorted(len(o.data.vertices) for o in fresh),
             "avenue: regenerated trees have the fresh build's vertex counts")
    fresh_coll = fresh[0].users_collection[0]
    for o in fresh:
        me = o.data
        bpy.data.objects.remove(o)
        bpy.data.meshes.remove(me)
    bpy.data.collections.remove(fresh_coll)
    act.banyan_plant.avenue.rows = 1
    res, msg = regenerate()
    bt.check(res == {'FINISHED'} and len(coll.objects) == (n1 + 1) // 2, "avenue: one row, %d trees (%d) %s"
             % ((n1 + 1) // 2, len(coll.objects), msg))
    bt.check(bpy.data.objects.get(act.name) == act, "avenue: the active tree survives")
    bt.check(len(bpy.data.meshes) == len({o.data for o in bpy.data.objects if o.type == 'MESH'}),
             "avenue: no orphan mesh left")


def test_avenue_curve():
    bt.reset_scene()
    cu = bpy.data.curves.new("Road", 'CURVE')
    sp = cu.splines.new('POLY')
    sp.points.add(2)
    for p, co in zip(sp.points, ((0, 0, 0, 1), (20, 0, 0, 1), (30, 10, 0, 1))):
        p.co = co
    road = bpy.data.objects.new("Road", cu)
    bpy.context.scene.collection.objects.link(road)
    for o in bpy.context.selected_objects:
        o.select_set(False)
    road.select_set(True)
    bpy.context.view_layer.objects.active = road
    objs = build("avenue", path_from='CURVE', rows=1, tree__levels=5)
    bt.check(objs and all(o.banyan_plant.path == road for o in objs), "avenue on a curve: the curve kept as a pointer")
    n = len(objs)
    road.name = "Renamed Road"
    sp.points[2].co = (60, 10, 0, 1)  # a longer road: more trees
    bpy.context.view_layer.objects.active = objs[0]
    res, msg = regenerate()
    coll = objs[0].users_collection[0]
    bt.check(res == {'FINISHED'} and len(coll.objects) > n, "avenue follows the edited curve: %d -> %d trees %s"
             % (n, len(coll.objects), msg))
    bpy.data.objects.remove(road)
    before = object_state(objs[0])
    res, msg = regenerate()
    bt.check(res == {'ERROR'} and "curve" in msg, "avenue: deleted curve reported: %r" % msg)
    bt.check(object_state(objs[0]) == before, "avenue: unchanged when its curve is gone")


def test_undo():
    """Undo after Regenerate gives back the plant as it was (mesh and record)."""
    bt.reset_scene()
    obj = build("keyaki", levels=6)[0]
    name, n0 = obj.name, len(obj.data.vertices)
    # Background Blender pushes no undo steps by itself: push what the UI would.
    bpy.ops.ed.undo_push(message="built")
    obj.banyan_plant.keyaki.levels = 8
    bpy.ops.ed.undo_push(message="edited")
    res, msg = regenerate()
    bpy.ops.ed.undo_push(message="regenerated")
    n1 = len(bpy.data.objects[name].data.vertices)
    bt.check(res == {'FINISHED'} and n1 > n0, "undo: regenerated %d -> %d %s" % (n0, n1, msg))
    bpy.ops.ed.undo()
    obj = bpy.data.objects[name]
    bt.check(len(obj.data.vertices) == n0, "undo: the mesh as before Regenerate (%d)" % len(obj.data.vertices))
    bt.check(json.loads(obj.banyan_plant.params)["params"]["levels"] == 6 and obj.banyan_plant.keyaki.levels == 8,
             "undo: stored levels 6 again, the edit (8) still in the panel")


def test_record_options():
    """record() keeps what JSON can hold (vectors as lists) and drops the rest."""
    from mathutils import Euler, Vector
    bt.reset_scene()
    cube = bpy.data.objects["Cube"]
    PL.record(cube, "keyaki", Params("keyaki"), [], {"location": Vector((1, 2, 3)), "rotation": Euler((0, 0, 1)),
                                                     "align": 'WORLD', "thing": object()})
    opt = PL.options(cube)
    bt.check(opt == {"location": [1.0, 2.0, 3.0], "rotation": [0.0, 0.0, 1.0], "align": 'WORLD'},
             "record: options as JSON: %s" % opt)
    bt.check(PL.is_plant(cube) and not PL.is_plant(bpy.data.objects["Camera"]), "record: the cube is now a plant")


def test_api_plants():
    """Plants made by banyan.api are recorded as the operators' are: the
    Plant panel shows them, Regenerate rebuilds them (the same mesh for
    unchanged params, another for an edit), make_lods works on them."""
    import banyan.api as B
    from banyan.engine import hosts as H
    bt.reset_scene()
    cube = bpy.data.objects["Cube"]

    def on_host_set():
        with H.surface_host_set([cube]) as hs:
            return B.strangler_roots(hosts=hs, seed=3)
    calls = {
        "roots": lambda: B.strangler_roots(hosts=[cube]),
        "ivy": lambda: B.ivy(hosts=[cube], start=(0.0, -1.05, -0.9), steps=40),
        "keyaki": lambda: B.keyaki_tree(position=(5.0, 0.0, 0.0), levels=6),
        "keyaki world": lambda: B.keyaki_tree(position=(0.0, 5.0, 0.0), levels=6, origin=None),
        "avenue": lambda: B.keyaki_avenue(path=[(0, 10, 0), (20, 10, 0)], spacing=10.0, tree__levels=6),
        "segments": lambda: B.segment_twigs(),
        "roots preset hosts": lambda: B.strangler_roots(preset="roots_boulder"),
        "roots host set": on_host_set,
    }
    edit = {"roots": ("seed", 7), "ivy": ("steps", 30), "keyaki": ("levels", 7), "avenue": ("tree__levels", 7),
            "segments": ("seed", 7)}
    for what, call in calls.items():
        gen = what.split()[0]
        if not bt.generator(gen):
            continue
        objs = call()
        obj = objs[0]
        pl = obj.banyan_plant
        bt.check(all(PL.is_plant(o) and o.banyan_plant.generator == gen for o in objs),
                 "api %s: every object recorded as a %s plant" % (what, gen))
        if gen in PL.HOSTED and what != "roots preset hosts":
            bt.check([h.name for h in pl.hosts] == ["Cube"], "api %s: the cube recorded as its host" % what)
        bt.check(PL.stored_params(obj).to_preset() == pl.params and PL.edited(obj) == [],
                 "api %s: the params kept, no edit pending" % what)
        draw_panel(obj)
        bpy.context.view_layer.objects.active = obj
        bpy.context.view_layer.update()  # matrix_world of the objects just made
        name, c0, mw = obj.name, coords(obj), [tuple(r) for r in obj.matrix_world]
        res, msg = regenerate()
        obj = bpy.data.objects[name]
        bt.check(res == {'FINISHED'} and close(coords(obj), c0) and [tuple(r) for r in obj.matrix_world] == mw,
                 "api %s: Regenerate with unchanged params, the same mesh and place %s" % (what, msg))
        key, value = edit[gen]
        setattr(getattr(obj.banyan_plant, gen), PP.prop_name(key.replace("__", ".")), value)
        res, msg = regenerate()
        obj = bpy.data.objects[name]
        bt.check(res == {'FINISHED'} and not close(coords(obj), c0),
                 "api %s: Regenerate after %s = %r: another mesh %s" % (what, key, value, msg))
    if bt.generator("keyaki"):
        tree = B.keyaki_tree(levels=6, name="LOD tree")[0]
        lods = B.make_lods(tree, ratios=(0.5,), billboard=False)
        bt.check([o.name for o in lods] == ["LOD tree_LOD0", "LOD tree_LOD1"], "api keyaki: make_lods: %s"
                 % [o.name for o in lods])
        bpy.context.view_layer.objects.active = tree
        bt.check(bpy.ops.banyan.make_lods.poll(), "api keyaki: Make LODs available on it")


def world_bounds(objs):
    bpy.context.view_layer.update()
    pts = [o.matrix_world @ v.co for o in objs if o.type == 'MESH' for v in o.data.vertices]
    return [min(p[k] for p in pts) for k in range(3)] + [max(p[k] for p in pts) for k in range(3)]


def test_units():
    """In a centimetre scene (Unit Scale 0.01) Regenerate gives the plant
    the sizes of its first build, for plants of the operators and of
    banyan.api, on hosts and along a curve; the Plant panel holds the
    lengths in the scene's units (roots' Scale 0.05 m as 5 cm)."""
    import banyan.api as B

    def centimetres():
        us = bpy.context.scene.unit_settings
        us.system, us.scale_length, us.length_unit = 'METRIC', 0.01, 'CENTIMETERS'

    def road():
        cu = bpy.data.curves.new("Road", 'CURVE')
        sp = cu.splines.new('POLY')
        sp.points.add(1)
        sp.points[1].co = (2000.0, 0.0, 0.0, 1.0)  # 20 m
        ob = bpy.data.objects.new("Road", cu)
        bpy.context.scene.collection.objects.link(ob)
        for o in bpy.context.selected_objects:
            o.select_set(False)
        ob.select_set(True)
        bpy.context.view_layer.objects.active = ob
        return ob

    def cube():
        c = bpy.data.objects["Cube"]
        c.scale = (100.0, 100.0, 100.0)  # 2 m
        bpy.context.view_layer.update()
        return c
    cases = {
        "roots": ("roots", lambda: (cube(), build("roots", surface='tubes', growth_points=20))[1]),
        "keyaki": ("keyaki", lambda: build("keyaki", levels=6)),
        "avenue on a curve": ("avenue", lambda: (road(), build("avenue", path_from='CURVE', rows=1,
                                                                 tree__levels=5))[1]),
        "api roots": ("roots", lambda: B.strangler_roots(hosts=[cube()], surface='tubes', growth_points=20)),
        "api keyaki": ("keyaki", lambda: B.keyaki_tree(position=(3.0, 0.0, 0.0), levels=6)),
        "api avenue on a curve": ("avenue", lambda: B.keyaki_avenue(path=road(), rows=1, tree__levels=5)),
    }
    for what, (gen, make) in cases.items():
        if not bt.generator(gen):
            continue
        bt.reset_scene()
        centimetres()
        objs = make()
        b0 = world_bounds(objs)
        height = (b0[5] - b0[2]) * 0.01
        bt.check(height > 1.0, "%s: %.2f m tall in a centimetre scene" % (what, height))
        bpy.context.view_layer.objects.active = objs[0]
        coll = objs[0].users_collection[0]
        res, msg = regenerate()
        b1 = world_bounds(list(coll.objects) if gen == "avenue" else [bpy.context.view_layer.objects.active])
        bt.check(res == {'FINISHED'} and max(abs(a - b) for a, b in zip(b0, b1)) < 1e-3,
                 "%s: Regenerate in a centimetre scene, the same bounds (cm) %s / %s %s"
                 % (what, [round(c, 2) for c in b0], [round(c, 2) for c in b1], msg))
    if bt.generator("roots"):
        bt.reset_scene()
        centimetres()
        cube()
        obj = build("roots", growth_points=8)[0]
        view = obj.banyan_plant.roots
        bt.check(abs(view.unit - 5.0) < 1e-5 and PL.current_params(obj).get("unit") == 0.05 and not PL.edited(obj),
                 "Plant panel: Scale 0.05 m held as 5 cm (%g), read back as %g m, no edit pending"
                 % (view.unit, PL.current_params(obj).get("unit")))
        view.unit = 6.0
        bt.check(PL.current_params(obj).get("unit") == 0.06 and PL.edited(obj) == ["unit"],
                 "Plant panel: 6 cm typed is 0.06 m (%g)" % PL.current_params(obj).get("unit"))


class _Layout:
    """Records what the panel draws (no window in background Blender)."""

    def __init__(self, log):
        self.log = log
        self.use_property_split = self.use_property_decorate = False
        self.scale_y = 1.0

    def _child(self, *a, **k):
        return _Layout(self.log)

    row = column = box = _child

    def panel(self, idname, default_closed=False):
        return _Layout(self.log), _Layout(self.log)

    def label(self, text="", icon='NONE'):
        self.log.append(("label", text, icon))

    def prop(self, data, name, text=None):
        if not hasattr(data, name):
            raise AttributeError(name)
        self.log.append(("prop", name, text))

    def operator(self, idname, text="", icon='NONE'):
        self.log.append(("op", idname))


def draw_panel(obj):
    from banyan.ui.plant import VIEW3D_PT_banyan_plant as P
    log = []

    class Ctx:
        active_object = obj
        mode = 'OBJECT'
    panel = type("Fake", (), {"layout": _Layout(log)})()
    bt.check(P.poll(Ctx), "panel shown for a plant")
    P.draw(panel, Ctx)
    gen = obj.banyan_plant.generator
    props = [e[1] for e in log if e[0] == "prop"]
    bt.check(len(props) == len(PP.annotations(gen)), "%s: the panel draws every parameter (%d)" % (gen, len(props)))
    bt.check(("op", "banyan.regenerate") in log, "%s: the panel has Regenerate" % gen)
    hosts = [e for e in log if e[0] == "label" and e[2] == 'ERROR']
    bt.check(bool(hosts) == any(h is None for _n, h in PL.host_status(obj)), "%s: deleted host flagged" % gen)

    class NotPlant:
        active_object = bpy.data.objects.get("Camera")
        mode = 'OBJECT'
    bt.check(not P.poll(NotPlant), "panel hidden for a non-plant")
    bt.check(not NotPlant.active_object.is_property_set("banyan_plant"), "the panel adds no record to a non-plant")


def main():
    print("Blender %s" % bpy.app.version_string)
    for gen, fn in (("roots", test_roots), ("ivy", test_ivy), ("keyaki", test_keyaki), ("avenue", test_avenue),
                    ("segments", test_segments), ("avenue", test_avenue_curve), ("keyaki", test_record_options),
                    ("keyaki", test_api_plants), ("roots", test_units),
                    ("keyaki", test_undo)):
        if bt.generator(gen):
            bt.run(fn)
    bt.done()


main()
