"""Rotated, scaled, mirrored and sheared hosts: the roots never enter the
host's true shape. Checked in Blender's world space, independently of the
add-on's box code: every root vertex is mapped back into the host's local
space by the inverse world matrix, where the host is its bounding box."""
import math
import os
import sys
from array import array

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bt  # noqa: E402

import bpy  # noqa: E402
from mathutils import Matrix, Vector  # noqa: E402


def world_vertices(obj):
    n = len(obj.data.vertices)
    co = array("f", bytes(4 * 3 * n))
    obj.data.vertices.foreach_get("co", co)
    mw = obj.matrix_world
    return [mw @ Vector(co[3 * i:3 * i + 3]) for i in range(n)]


def inside_count(host, pts, margin):
    """Vertices strictly inside the host's local box shrunk by `margin`
    (in metres, converted to local units per axis)."""
    inv = host.matrix_world.inverted()
    bb = [Vector(c) for c in host.bound_box]
    lo = Vector([min(c[k] for c in bb) for k in range(3)])
    hi = Vector([max(c[k] for c in bb) for k in range(3)])
    # Local length of one world metre along each local axis (upper bound).
    L = host.matrix_world.to_3x3()
    scale = [L.col[k].length for k in range(3)]
    m = [margin / s for s in scale]
    worst = 0.0
    count = 0
    for p in pts:
        q = inv @ p
        if all(lo[k] + m[k] < q[k] < hi[k] - m[k] for k in range(3)):
            count += 1
            depth = min(min(q[k] - lo[k], hi[k] - q[k]) * scale[k] for k in range(3))
            worst = max(worst, depth)
    return count, worst


def run_case(label, setup):
    bt.reset_scene()
    cube = bpy.data.objects["Cube"]
    setup(cube)
    bpy.context.view_layer.update()
    before = {o.name for o in bpy.data.objects}
    res = bpy.ops.mesh.banyan_roots()
    bt.check(res == {'FINISHED'}, "%s: roots finished" % label)
    objs = [o for o in bpy.data.objects if o.name not in before]
    bt.check(len(objs) == 1, "%s: one roots object" % label)
    if not objs:
        return
    pts = world_vertices(objs[0])
    bt.check(len(pts) > 1000, "%s: a real root net (%d vertices)" % (label, len(pts)))
    n, worst = inside_count(cube, pts, 1e-4)
    bt.check(n == 0, "%s: %d root vertices inside the host (deepest %.5f m)" % (label, n, worst))
    # The roots wrap the host: many vertices lie near its surface.
    n_near, _ = inside_count(cube, pts, -0.5)
    bt.check(n_near > len(pts) // 10, "%s: roots hug the host (%d of %d within 0.5 m)" % (label, n_near, len(pts)))


def rotated_scaled(c):
    c.location = (0.4, -0.3, 1.6)
    c.rotation_euler = (math.radians(25), math.radians(-15), math.radians(40))
    c.scale = (1.6, 0.7, 1.3)


def mirrored(c):
    c.location = (0.0, 0.0, 1.2)
    c.rotation_euler = (0.0, 0.0, math.radians(30))
    c.scale = (-1.2, 0.8, 1.2)


def sheared(c):
    # A rotated child of a non-uniformly scaled parent is sheared.
    parent = bpy.data.objects.new("ShearParent", None)
    bpy.context.scene.collection.objects.link(parent)
    parent.scale = (2.0, 1.0, 1.0)
    c.parent = parent
    c.location = (0.0, 0.0, 1.3)
    c.rotation_euler = (0.0, 0.0, math.radians(35))


def test_cases():
    run_case("rotated+scaled", rotated_scaled)
    run_case("mirrored", mirrored)
    run_case("sheared", sheared)


def test_germination_cursor():
    bt.reset_scene()
    cube = bpy.data.objects["Cube"]
    bpy.context.scene.cursor.location = (0.2, 0.1, 1.4)
    res = bpy.ops.mesh.banyan_roots(germinate_at='CURSOR')
    bt.check(res == {'FINISHED'}, "germination at the cursor works")
    from banyan.ops.base import LAST_PARAMS
    p = LAST_PARAMS["mesh.banyan_roots"]
    bt.check(not p.get("germination_auto") and all(abs(a - b) < 1e-6 for a, b in
                                                   zip(p.get("germination"), (0.2, 0.1, 1.4))),
             "cursor became the germination point")
    # Cursor inside the host: the library refuses, the scene stays as it was.
    # (The run above selected its roots; the cube is the host again.)
    for o in bpy.context.selected_objects:
        o.select_set(False)
    cube.select_set(True)
    bpy.context.view_layer.objects.active = cube
    bpy.context.scene.cursor.location = (0.0, 0.0, 0.0)
    state = bt.scene_state()
    try:
        bpy.ops.mesh.banyan_roots(germinate_at='CURSOR')
        bt.check(False, "germination inside the host accepted")
    except RuntimeError as e:
        bt.check("Banyan" in str(e), "germination inside the host reported: %s" % e)
    bt.check(bt.scene_state() == state, "scene unchanged after a refused germination point")


if bt.generator("roots"):
    bt.run(test_cases)
    bt.run(test_germination_cursor)
else:
    bt.check(True, "roots not built (expected)")
bt.done()
