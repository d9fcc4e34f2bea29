"""Placement: each plant's object has its origin where it stands (a tree
at its trunk foot, ivy and roots at the bottom centre of the active
host's world bounds, a merged avenue at its path's start, each avenue
tree at its foot), its mesh local to it and its world vertices the
library's; the tree and the twigs take Blender's Align / Location /
Rotation; an operator run in Edit Mode leaves it first, and puts it back
when it fails."""
import math
import os
import sys
from array import array

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bt  # noqa: E402

import bpy  # noqa: E402
from mathutils import Euler, Matrix, Vector  # noqa: E402
from banyan import api as B  # noqa: E402
from banyan.core import generators as G  # noqa: E402
from banyan.core.params import Params  # noqa: E402


def local_co(obj):
    n = len(obj.data.vertices)
    co = array("f", bytes(12 * n))
    obj.data.vertices.foreach_get("co", co)
    return co


def world_offset(obj, positions, stride=1):
    """Largest distance between obj's world vertices and the library's world positions."""
    co = local_co(obj)
    if len(co) != len(positions):
        return math.inf
    mw = obj.matrix_world
    return max(((mw @ Vector(co[i:i + 3])) - Vector(positions[i:i + 3])).length
               for i in range(0, len(co), 3 * stride))


run = bt.run_op


def close(a, b, tol=1e-5):
    return (Vector(a) - Vector(b)).length < tol


def test_tree_at_cursor():
    bt.reset_scene()
    sc = bpy.context.scene
    sc.cursor.location = (3.0, -2.0, 0.5)
    res, objs = run(bpy.ops.mesh.banyan_keyaki_tree, levels=10)
    bt.check(res == {'FINISHED'} and len(objs) == 1, "tree: finished, one object (%s)" % res)
    if not objs:
        return
    o = objs[0]
    bt.check(close(o.location, (3.0, -2.0, 0.5)), "tree: the object's origin is the cursor (%s)" % (tuple(o.location),))
    co = local_co(o)
    lo_z = min(co[2::3])
    bt.check(abs(lo_z) < 0.05, "tree: the mesh is local to its foot (lowest local z %.3g)" % lo_z)
    p = Params("keyaki")
    p.set("levels", 10)
    p.set("position", (3.0, -2.0, 0.5))
    ref = G.keyaki(p)
    d = world_offset(o, ref.positions, 7)
    bt.check(d < 1e-4, "tree: world vertices are the library's tree at the cursor (%.2g m)" % d)
    # The trunk foot: the vertices near the ground ring the local origin.
    foot = [(co[i], co[i + 1]) for i in range(0, len(co), 3) if co[i + 2] < lo_z + 0.02]
    cx = sum(x for x, _ in foot) / len(foot)
    cy = sum(y for _, y in foot) / len(foot)
    bt.check(math.hypot(cx, cy) < 0.2, "tree: the trunk foot is at the local origin (%.3g, %.3g)" % (cx, cy))

    # Rotation: the tree turns about its foot, which stays at Location.
    res, objs = run(bpy.ops.mesh.banyan_keyaki_tree, levels=10, location=(1.0, 1.0, 0.0),
                    rotation=(0.0, 0.0, math.pi / 2))
    bt.check(res == {'FINISHED'} and len(objs) == 1, "tree rotated: finished")
    if objs:
        o = objs[0]
        bt.check(close(o.location, (1.0, 1.0, 0.0)), "tree rotated: at Location (%s)" % (tuple(o.location),))
        bt.check(abs(o.rotation_euler.z - math.pi / 2) < 1e-5, "tree rotated: Rotation on the object")
        p.set("position", (0.0, 0.0, 0.0))
        ref = G.keyaki(p)
        rot = Matrix.Translation((1.0, 1.0, 0.0)) @ Euler((0, 0, math.pi / 2)).to_matrix().to_4x4()
        co = local_co(o)
        d = max(((o.matrix_world @ Vector(co[i:i + 3])) - rot @ Vector(ref.positions[i:i + 3])).length
                for i in range(0, len(co), 21))
        bt.check(d < 1e-4, "tree rotated: turned about its foot (%.2g m)" % d)
        top = max(range(0, len(co), 3), key=lambda i: co[i + 2])
        bt.check(close(o.matrix_world @ Vector((0, 0, 0)), (1.0, 1.0, 0.0)),
                 "tree rotated: the foot stays put (top vertex %d)" % (top // 3))

    # Align 3D Cursor: the cursor's rotation.
    sc.cursor.rotation_euler = (0.0, 0.3, 1.0)
    res, objs = run(bpy.ops.mesh.banyan_keyaki_tree, levels=8, align='CURSOR')
    if bt.check(res == {'FINISHED'} and len(objs) == 1, "tree aligned to the cursor: finished"):
        want = sc.cursor.matrix.to_3x3()
        got = objs[0].matrix_world.to_3x3()
        bt.check(all(abs(got[r][c] - want[r][c]) < 1e-5 for r in range(3) for c in range(3)),
                 "tree aligned to the cursor: the cursor's rotation")
        bt.check(close(objs[0].location, sc.cursor.location), "tree aligned to the cursor: at the cursor")

    # At 3D cursor off: the foot at `position`, the origin there.
    res, objs = run(bpy.ops.mesh.banyan_keyaki_tree, levels=8, at_cursor=False, position=(-4.0, 2.0, 1.0))
    if bt.check(res == {'FINISHED'} and len(objs) == 1, "tree at position: finished"):
        bt.check(close(objs[0].location, (-4.0, 2.0, 1.0)), "tree at position: origin at `position`")


def cube_lifted():
    bt.reset_scene()
    cube = bpy.data.objects["Cube"]
    cube.location = (2.0, 1.0, 1.0)
    cube.rotation_euler = (0.0, 0.0, 0.4)
    bpy.context.view_layer.update()
    return cube


def test_hosts_origin():
    """Ivy and roots: origin at the bottom centre of the host's world bounds."""
    for gen, op, kw in (("ivy", bpy.ops.mesh.banyan_ivy, {"steps": 40}),
                        ("roots", bpy.ops.mesh.banyan_roots, {"growth_points": 6})):
        for shape in ('SURFACE', 'BOX'):
            cube = cube_lifted()
            bpy.context.scene.cursor.location = (2.0, 0.0, 0.3)
            res, objs = run(op, host_shape=shape, **kw)
            if not bt.check(res == {'FINISHED'} and len(objs) == 1, "%s %s: finished (%s)" % (gen, shape, res)):
                continue
            o = objs[0]
            lo, hi = B.world_bounds([cube])
            want = (0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), lo[2])
            bt.check(close(o.location, want, 1e-4), "%s %s: origin at the host's base %s (is %s)"
                     % (gen, shape, tuple(round(x, 4) for x in want), tuple(round(x, 4) for x in o.location)))
            # The same plant in world coordinates through the API.
            call = B.ivy if gen == "ivy" else B.strangler_roots
            extra = {"start": bpy.context.scene.cursor.location[:]} if gen == "ivy" else {}
            ref = call(hosts=[cube], host_shape=shape, origin=None, name="ref", **dict(kw, **extra))[0]
            bt.check(tuple(ref.location) == (0.0, 0.0, 0.0), "%s %s: origin=None keeps world coordinates" % (gen, shape))
            d = world_offset(o, local_co(ref), 5)
            bt.check(d < 1e-4, "%s %s: world vertices are the world-coordinate plant's (%.2g m)" % (gen, shape, d))


def test_avenue_origins():
    bt.reset_scene()
    bpy.context.scene.cursor.location = (5.0, 5.0, 0.0)
    res, objs = run(bpy.ops.mesh.banyan_keyaki_avenue, merged=True, line_length=30.0, tree__levels=8)
    if bt.check(res == {'FINISHED'} and len(objs) == 1, "avenue merged: finished"):
        bt.check(close(objs[0].location, (5.0, 5.0, 0.0)), "avenue merged: origin at the path start (the cursor)")
    res, objs = run(bpy.ops.mesh.banyan_keyaki_avenue, merged=False, line_length=30.0, tree__levels=8)
    if bt.check(res == {'FINISHED'} and len(objs) > 1, "avenue per tree: finished, %d trees" % len(objs)):
        lows = [min(local_co(o)[2::3]) for o in objs]
        bt.check(all(abs(z) < 0.05 for z in lows), "avenue per tree: each mesh local to its foot (%s)"
                 % [round(z, 3) for z in lows])
        xs = sorted(o.location.x for o in objs)
        bt.check(xs[0] >= 5.0 - 1.0 and xs[-1] <= 35.0 + 1.0, "avenue per tree: origins along the line (%.1f..%.1f)"
                 % (xs[0], xs[-1]))


def test_twigs_placement():
    bt.reset_scene()
    bpy.context.scene.cursor.location = (1.0, 2.0, 3.0)
    res, objs = run(bpy.ops.mesh.banyan_segment_twigs, rotation=(0.0, 0.0, 1.0))
    if bt.check(res == {'FINISHED'} and len(objs) == 1, "twigs: finished"):
        bt.check(close(objs[0].location, (1.0, 2.0, 3.0)), "twigs: at the cursor")
        bt.check(abs(objs[0].rotation_euler.z - 1.0) < 1e-6, "twigs: Rotation")


def test_tube_placement():
    bt.reset_scene()
    bpy.context.scene.cursor.location = (2.0, -1.0, 0.5)
    res, objs = run(bpy.ops.mesh.banyan_tube)
    if bt.check(res == {'FINISHED'} and len(objs) == 1, "tube: finished"):
        bt.check(close(objs[0].location, (2.0, -1.0, 0.5)), "tube: its origin at the cursor")
        bt.check(abs(min(local_co(objs[0])[2::3])) < 1e-3, "tube: its mesh local to its foot")


def test_edit_mode():
    """Run in Edit Mode: the host leaves it before the build, the new plant
    is active in Object Mode; a failure puts the host back in Edit Mode."""
    for gen, op, kw in (("ivy", bpy.ops.mesh.banyan_ivy, {"steps": 30}),
                        ("roots", bpy.ops.mesh.banyan_roots, {"growth_points": 5}),
                        ("keyaki", bpy.ops.mesh.banyan_keyaki_tree, {"levels": 6})):
        bt.reset_scene()
        cube = bpy.data.objects["Cube"]
        bpy.context.scene.cursor.location = (0.0, -1.2, 0.0)
        bpy.ops.object.mode_set(mode='EDIT')
        bt.check(cube.mode == 'EDIT', "%s: the cube is in Edit Mode" % gen)
        res, objs = run(op, **kw)
        bt.check(res == {'FINISHED'} and len(objs) == 1, "%s in Edit Mode: finished (%s)" % (gen, res))
        bt.check(cube.mode == 'OBJECT', "%s in Edit Mode: the cube left it (%s)" % (gen, cube.mode))
        act = bpy.context.view_layer.objects.active
        bt.check(objs and act == objs[0] and act.mode == 'OBJECT', "%s in Edit Mode: the plant is active, in "
                 "Object Mode" % gen)
        bt.check(bpy.context.mode == 'OBJECT', "%s in Edit Mode: the context is in Object Mode" % gen)
        if gen == "keyaki":
            bt.check(len(cube.data.vertices) == 8, "keyaki in Edit Mode: not joined into the cube")
        # A failure puts the mode back and adds nothing.
        bt.reset_scene()
        cube = bpy.data.objects["Cube"]
        bpy.ops.object.mode_set(mode='EDIT')
        state = bt.scene_state()
        # A 3D cursor at NaN: refused once Edit Mode is left (the cursor is read in prepare).
        bpy.context.scene.cursor.location = (float("nan"), 0.0, 0.0)
        bad = dict(kw, germinate_at='CURSOR') if gen == "roots" else kw
        try:
            res = op(**bad)
        except RuntimeError as e:  # bpy.ops raises on an error report
            res = {'CANCELLED'} if "3D cursor" in str(e) else str(e)
        bt.check(res == {'CANCELLED'}, "%s bad value in Edit Mode: cancelled (%s)" % (gen, res))
        bt.check(cube.mode == 'EDIT', "%s bad value in Edit Mode: the cube is back in Edit Mode (%s)"
                 % (gen, cube.mode))
        bt.check(bt.scene_state() == state, "%s bad value in Edit Mode: nothing added" % gen)


for t in (test_tree_at_cursor, test_hosts_origin, test_avenue_origins, test_twigs_placement, test_tube_placement,
          test_edit_mode):
    bt.run(t)
bt.done()
