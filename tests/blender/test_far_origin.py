"""Far from the origin (docs/addon.md): roots grown around a cube at
x = 999,999 m keep millimetres. The library's mesh carries a whole-metre
origin; the object's location takes it (Blender keeps locations in
float32, exact for whole metres), so the world vertices (location + local
vertex, added here in Python doubles: Blender's own matrix_world product
is float32) are the roots around a cube at 0 moved, to 1 mm, vertex by
vertex. An avenue split into trees far away keeps each tree's foot."""
import os
import sys
from array import array

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bt  # noqa: E402

import bpy  # noqa: E402
from banyan import api as B  # noqa: E402

FAR = (999999.0, -500000.0, 5000.0)
SMALL = {"main_roots": 4, "growth_points": 16}


def world(obj):
    """The object's world vertices, in doubles (no rotation or scale here)."""
    n = len(obj.data.vertices)
    co = array("f", bytes(12 * n))
    obj.data.vertices.foreach_get("co", co)
    loc = tuple(obj.location)
    return [loc[i % 3] + co[i] for i in range(len(co))]


def cube_at(at):
    bt.reset_scene()
    cube = bpy.data.objects["Cube"]
    cube.location = at
    bpy.context.view_layer.update()
    return cube


def grow(at, **kw):
    cube = cube_at(at)
    objs = B.strangler_roots([cube], values=dict(SMALL, ground_z=at[2] - 1.0), **kw)  # the ground under the cube
    bt.check(len(objs) == 1, "roots at %s: one object" % (at,))
    return objs[0]


def test_roots_far():
    # The cube centred on FAR: the host set's frame is then FAR itself, the
    # same local numbers as the cube at 0 (the fused surface's voxel lattice
    # is the frame's: a frame shifted by a fraction of a voxel meshes the
    # roots a little differently, near 0 as far away; docs/api.md).
    near = grow((0.0, 0.0, 0.0))
    wn = world(near)
    bt.check(tuple(near.location) == (0.0, 0.0, -1.0), "near: the object at its base (%s)" % (tuple(near.location),))
    far_at = FAR
    base = (FAR[0], FAR[1], FAR[2] - 1.0)
    for origin in ('BASE', None):
        far = grow(far_at, origin=origin)
        loc = tuple(far.location)
        # BASE: the bottom centre of the cube's bounds; None: the mesh's own origin (whole metres near it).
        if origin == 'BASE':
            bt.check(loc == base, "far, BASE: location %s is the cube's base %s" % (loc, base))
        else:
            bt.check(all(float(c).is_integer() and abs(c - f) < 10 for c, f in zip(loc, FAR)),
                     "far, origin None: location %s is the mesh's whole-metre origin" % (loc,))
        wf = world(far)
        bt.check(len(wf) == len(wn) and len(wn) > 0, "far (%s): %d vertices, near %d" % (origin, len(wf) // 3,
                                                                                          len(wn) // 3))
        if len(wf) == len(wn):
            worst = max(abs(wf[i] - (wn[i] + FAR[i % 3])) for i in range(len(wn)))
            print("roots far (origin %s): world vertices within %.3g m of the near ones moved" % (origin, worst))
            bt.check(worst <= 1e-3, "far (%s): world vertices differ from the near ones moved by %.3g m"
                     % (origin, worst))


def test_avenue_far():
    """Trees of an avenue far away: each object stands at its foot and its
    world vertices are the near avenue's moved."""
    kw = {"tree.levels": 10, "placement": "count", "count": 2}

    def avenue(at):
        bt.reset_scene()
        start = at
        end = (at[0] - 12.0, at[1], at[2])
        objs = B.keyaki_avenue(values=dict(kw, start=start, end=end), name="Far Avenue")
        return [(o.name, tuple(o.location), world(o)) for o in sorted(objs, key=lambda o: o.name)]
    near, far = avenue((0.0, 0.0, 0.0)), avenue(FAR)
    bt.check(len(near) == len(far) == 4, "avenue: four trees near and far (%d, %d)" % (len(near), len(far)))
    for (_, la, wa), (name, lb, wb) in zip(near, far):
        moved = [lb[k] - la[k] - FAR[k] for k in range(3)]
        bt.check(max(abs(m) for m in moved) < 0.07, "avenue %s: the far tree stands at the near one's foot moved "
                 "(to float32's 6 cm) %s" % (name, moved))
        if len(wa) != len(wb):
            bt.check(False, "avenue %s: %d / %d vertices" % (name, len(wa), len(wb)))
            continue
        worst = max(abs(wb[i] - (wa[i] + FAR[i % 3])) for i in range(len(wa)))
        print("avenue %s far: world vertices within %.3g m" % (name, worst))
        bt.check(worst <= 1e-3, "avenue %s far: world vertices off by %.3g m" % (name, worst))


if bt.generator("roots"):
    bt.run(test_roots_far)
if bt.generator("avenue"):
    bt.run(test_avenue_far)
bt.done()
