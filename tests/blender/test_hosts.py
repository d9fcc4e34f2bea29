"""Host shape: hosts are the objects' real surfaces (docs/addon.md, "Hosts from objects").

On a UV sphere, Suzanne, a 32-vertex cylinder and an open plane, checked
in Blender's world space with mathutils (BVHTree of each host's evaluated
mesh), independently of the library's own queries:
  - ivy: the median distance of the buds (skeleton points) to the real
    surface is within the sucker reach; no skeleton point is inside a
    closed host;
  - the library's inside test agrees with the winding number near
    Suzanne's and the cylinder's surfaces;
  - roots on the cylinder: no vertex inside; of the vertices more than
    1 m above the ground, >= 90 % lie within 3 r of the surface;
  - Host shape = Bounding box gives the very mesh the box path gave;
  - the host set is the evaluated mesh (modifiers) in world space;
  - bad hosts (no triangles, a NaN vertex, a singular matrix) are refused
    naming the object, and the scene is left as it was;
  - a 1M-triangle host: the time to read it and build the set is printed.
"""
import math
import os
import statistics
import sys
import time
from array import array

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bt  # noqa: E402

import bpy  # noqa: E402
from mathutils import Vector  # noqa: E402
from mathutils.bvhtree import BVHTree  # noqa: E402

import banyan.api as B  # noqa: E402
from banyan.engine import hosts as H  # noqa: E402
from banyan.core import BanyanError  # noqa: E402
from banyan.core import generators as G  # noqa: E402
from banyan.core import structs as S  # noqa: E402
from banyan.core.hostset import HostSet, MeshInput  # noqa: E402
from banyan.core.params import Params  # noqa: E402

IVY_STEPS = 150
CYL_R, CYL_H = 0.5, 4.0


# ------------------------------------------------------------------ scene
def empty_scene():
    """The factory scene without its cube (camera and light stay)."""
    bt.reset_scene()
    bpy.data.objects.remove(bpy.data.objects["Cube"])


def add_host(kind):
    """One host, selected and active; returns (object, closed, ivy start
    cursor: a point just off its side, low down)."""
    empty_scene()
    if kind == "sphere":
        bpy.ops.mesh.primitive_uv_sphere_add(radius=1.0, location=(0.0, 0.0, 1.2))
        cursor, closed = (0.0, -1.2, 0.6), True
    elif kind == "suzanne":
        bpy.ops.mesh.primitive_monkey_add(size=2.0, location=(0.0, 0.0, 1.2))
        cursor, closed = (0.0, -1.2, 0.6), True
    elif kind == "cylinder":
        bpy.ops.mesh.primitive_cylinder_add(vertices=32, radius=CYL_R, depth=CYL_H, location=(0.0, 0.0, CYL_H / 2))
        cursor, closed = (0.0, -0.7, 0.1), True
    elif kind == "plane":  # an open quad standing up: a wall with no thickness
        bpy.ops.mesh.primitive_plane_add(size=3.0, location=(0.0, 0.0, 1.6), rotation=(math.pi / 2, 0.0, 0.0))
        cursor, closed = (0.3, -0.2, 0.15), False
    else:
        raise KeyError(kind)
    obj = bpy.context.active_object
    obj.name = "Host_" + kind
    bpy.context.view_layer.update()
    bpy.context.scene.cursor.location = cursor
    # The cursor as the operator reads it (single precision): the library
    # run compared with the operator's must start from the same point
    # (Blender 4.x triangulates Suzanne so that 1e-8 m changes the plant).
    return obj, closed, tuple(bpy.context.scene.cursor.location)


def world_triangles(obj):
    """The object's evaluated mesh in world space, on the evaluated mesh's
    own triangles (loop_triangles), which the add-on reads: Blender may split
    a non-planar quad of the evaluated mesh on the other diagonal than a
    to_mesh() copy (Suzanne's nose: up to 5 mm apart). (vertices, triangles)."""
    dg = bpy.context.evaluated_depsgraph_get()
    me = obj.evaluated_get(dg).data
    me.calc_loop_triangles()
    mw = obj.matrix_world
    return [mw @ v.co for v in me.vertices], [tuple(t.vertices) for t in me.loop_triangles]


class Surface:
    """A host's world-space triangles: a BVHTree for distances, the soup for winding()."""

    def __init__(self, obj):
        verts, tris = world_triangles(obj)
        self.tree = BVHTree.FromPolygons(verts, tris)
        self.soup = [(tuple(verts[a]), tuple(verts[b]), tuple(verts[c])) for a, b, c in tris]

    def find_nearest(self, p):
        return self.tree.find_nearest(p)


def world_bvh(obj):
    return Surface(obj)


def winding(soup, p):
    """Generalised winding number of the triangle soup at p (Jacobson et
    al. 2013: the sum of signed solid angles / 4 pi): about 1 inside, 0
    outside, and robust to Suzanne's holes (open eye sockets), separate
    shells (its eyes) and self-intersections, where ray parity and the
    nearest face's normal both go wrong."""
    px, py, pz = p
    total = 0.0
    for (ax, ay, az), (bx, by, bz), (cx, cy, cz) in soup:
        ax, ay, az, bx, by, bz = ax - px, ay - py, az - pz, bx - px, by - py, bz - pz
        cx, cy, cz = cx - px, cy - py, cz - pz
        la = math.sqrt(ax * ax + ay * ay + az * az)
        lb = math.sqrt(bx * bx + by * by + bz * bz)
        lc = math.sqrt(cx * cx + cy * cy + cz * cz)
        det = ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx)
        div = la * lb * lc + (ax * bx + ay * by + az * bz) * lc + (ax * cx + ay * cy + az * cz) * lb + \
            (bx * cx + by * cy + bz * cz) * la
        total += math.atan2(det, div)
    return total / (2.0 * math.pi)


def inside(bvh, p):
    return winding(bvh.soup, p) > 0.5


def distance(bvh, p):
    return bvh.find_nearest(Vector(p))[3]


def points(flat):
    return [tuple(flat[3 * i:3 * i + 3]) for i in range(len(flat) // 3)]


def world_vertices(obj):
    n = len(obj.data.vertices)
    co = array("f", bytes(12 * n))
    obj.data.vertices.foreach_get("co", co)
    mw = obj.matrix_world
    return [tuple(mw @ Vector(p)) for p in points(co)]


def new_objects(before):
    return [o for o in bpy.data.objects if o.name not in before]


def select_only(obj):
    for o in bpy.context.view_layer.objects:
        o.select_set(False)
    obj.select_set(True)
    bpy.context.view_layer.objects.active = obj


def world_offset(obj, positions):
    """Largest distance between obj's vertices in world space and the
    library's world positions (inf when the counts differ). The object
    has its origin at the plant's base, its mesh local to it."""
    n = len(obj.data.vertices)
    if 3 * n != len(positions):
        return float("inf")
    co = array("f", bytes(12 * n))
    obj.data.vertices.foreach_get("co", co)
    mw = obj.matrix_world
    return max(((mw @ Vector(co[3 * i:3 * i + 3])) - Vector(positions[3 * i:3 * i + 3])).length for i in range(n))


def run_op(op, host=None, **kw):
    """op(**kw) with `host` alone selected (the operator selects what it made);
    the ground at z = 0, as in the library calls these runs are compared with."""
    if host is not None:
        select_only(host)
    kw.setdefault("ground_at_hosts", False)
    before = {o.name for o in bpy.data.objects}
    res = op(**kw)
    return res, new_objects(before)


# ------------------------------------------------------------------ tests
def test_binding():
    """The host-set binding on a UV sphere: struct sizes (checked at load),
    info, closest, inside, against the sphere's geometry."""
    for cls, key in ((S.HostMesh, "host_mesh"), (S.HostHit, "host_hit"), (S.HostInfo, "host_info")):
        bt.check(S.SIZED.get(key) is cls, "%s is size-checked at load" % key)
    obj, _closed, _cur = add_host("sphere")
    obj.location = (2.0, 1.0, 3.0)
    obj.scale = (2.0, 2.0, 2.0)
    bpy.context.view_layer.update()
    dg = bpy.context.evaluated_depsgraph_get()
    me = obj.evaluated_get(dg).data
    me.calc_loop_triangles()
    with H.surface_host_set([obj]) as hs:
        bt.check(hs.count == 1, "one host")
        info = hs.info(0)
        bt.check(info["kind"] == "mesh" and info["closed"], "sphere: a closed mesh host (%s)" % info)
        bt.check(info["triangle_count"] == len(me.loop_triangles), "sphere: %d triangles kept of %d" % (
            info["triangle_count"], len(me.loop_triangles)))
        # The world transform is applied: bounds about centre +- 2.
        bt.check(all(abs(info["lo"][k] - (c - 2.0)) < 0.01 and abs(info["hi"][k] - (c + 2.0)) < 0.01
                     for k, c in enumerate((2.0, 1.0, 3.0))), "sphere: world bounds %s %s" % (info["lo"], info["hi"]))
        hit = hs.closest((2.0, 1.0, 8.0))
        bt.check(hit is not None and abs(hit["distance"] - 3.0) < 0.02 and abs(hit["point"][2] - 5.0) < 0.02,
                 "closest from above: %s" % (hit,))
        hit = hs.closest((2.0, 1.0, 3.5))
        bt.check(hit is not None and -1.5 - 0.02 < hit["distance"] < -1.5 + 0.05, "inside: signed distance %s" % (
            hit and hit["distance"],))
        bt.check(hs.inside((2.0, 1.0, 3.0)) and not hs.inside((2.0, 1.0, 5.5)), "inside / outside")
        bt.check(hs.closest((2.0, 1.0, 8.0), max_distance=1.0) is None, "nothing within max_distance")
    bt.check(not hs.handle, "the set is freed at the end of the with block")


def library_ivy(obj, cursor, shape):
    """The ivy the operator grows (same start rule: the cursor itself, for
    the library to place, unless it is out of snapping reach), as MeshData.
    The plant is chaotic: a start 1e-9 m off grows another one."""
    p = Params("ivy")
    p.set("steps", IVY_STEPS)
    reach = 0.99 * p.get("start_snap_max")
    if shape == H.BOX:
        boxes = H.boxes_from_objects([obj])
        near = H.closest_point(boxes, cursor)[0]
        p.set("start", near if math.dist(near, cursor) > reach else cursor)
        return G.ivy(p, boxes)
    with H.surface_host_set([obj]) as hs:
        near = H.closest_on_set(hs, cursor)
        p.set("start", near if math.dist(near, cursor) > reach else cursor)
        return G.ivy(p, hs)


def test_ivy(kind):
    obj, closed, cursor = add_host(kind)
    reach = Params("ivy").get("sucker_length")
    t = time.perf_counter()
    res, objs = run_op(bpy.ops.mesh.banyan_ivy, obj, steps=IVY_STEPS)
    t = time.perf_counter() - t
    bt.check(res == {'FINISHED'} and len(objs) == 1, "ivy on %s: operator finished, one object" % kind)
    d = library_ivy(obj, cursor, H.SURFACE)
    if objs:
        bt.check(len(objs[0].data.vertices) == d.vertex_count, "ivy on %s: operator %d vertices, library %d" % (
            kind, len(objs[0].data.vertices), d.vertex_count))
    bvh = world_bvh(obj)
    buds = points(d.skel_points)
    bt.check(len(buds) > 50, "ivy on %s: grew (%d buds)" % (kind, len(buds)))
    dist = [distance(bvh, q) for q in buds]
    med = statistics.median(dist)
    bt.check(med <= reach, "ivy on %s: median bud distance to the surface %.4f m <= sucker reach %.3f m" % (
        kind, med, reach))
    # The box path, for the record: how far the same ivy on the bounding box is.
    box_med = statistics.median(distance(bvh, q) for q in points(library_ivy(obj, cursor, H.BOX).skel_points))
    n_in = sum(inside(bvh, q) for q in buds) if closed else 0
    if closed:  # the measure itself: the host's centre is inside, a point beside it is not
        c = obj.matrix_world.translation
        bt.check(inside(bvh, c) and not inside(bvh, c + Vector((0.0, -2.0, 0.0))),
                 "%s: the winding number tells inside from outside" % kind)
    if closed:
        bt.check(n_in == 0, "ivy on %s: %d of %d skeleton points inside the host" % (kind, n_in, len(buds)))
    print("ivy on %-8s %5d buds, median distance %.4f m (box path %.4f m), max %.3f m, %d inside; operator %.2f s"
          % (kind, len(buds), med, box_med, max(dist), n_in, t), flush=True)


def test_inside_matches_winding(kind, n=1500, near=0.06):
    """The library's inside test against the winding number on n points
    within `near` of the host's surface, where holes and overlapping
    shells (Suzanne's eye sockets and eyes) make rays and normals go wrong;
    points within 0.01 of w = 1/2 are left out as undecidable."""
    import random
    obj, _, _ = add_host(kind)
    bvh = world_bvh(obj)
    rng = random.Random(5)
    wrong, undecided = [], 0
    with H.surface_host_set([obj]) as hs:
        for _ in range(n):
            a, b, c = bvh.soup[rng.randrange(len(bvh.soup))]
            u, v = rng.random(), rng.random()
            if u + v > 1:
                u, v = 1 - u, 1 - v
            q = tuple(a[k] + u * (b[k] - a[k]) + v * (c[k] - a[k]) + rng.uniform(-near, near) for k in range(3))
            w = winding(bvh.soup, q)
            if abs(abs(w) - 0.5) < 0.01:
                undecided += 1
            elif (abs(w) > 0.5) != bool(hs.inside(q)):
                wrong.append((q, w))
    bt.check(not wrong, "%s: the inside test disagrees with the winding number at %d of %d points near the "
             "surface, e.g. %s" % (kind, len(wrong), n, wrong[:2]))
    print("inside vs winding number on %s: %d points, %d disagree, %d undecided" % (kind, n, len(wrong), undecided),
          flush=True)


def test_roots_cylinder():
    obj, _closed, _cur = add_host("cylinder")
    r = Params("roots").get("radius") * Params("roots").get("unit")
    bvh = world_bvh(obj)
    apothem = CYL_R * math.cos(math.pi / 32)
    for shape in (H.SURFACE, H.BOX):
        res, objs = run_op(bpy.ops.mesh.banyan_roots, obj, host_shape=shape)
        bt.check(res == {'FINISHED'} and len(objs) == 1, "roots on the cylinder (%s): one object" % shape)
        if not objs:
            continue
        pts = world_vertices(objs[0])

        def in_prism(q, m=1e-4):  # strictly inside the 32-gon prism (its faces are at the apothem)
            if not (m < q[2] < CYL_H - m):
                return False
            for k in range(32):
                a = 2 * math.pi * (k + 0.5) / 32  # the face normals of Blender's cylinder
                if q[0] * math.cos(a) + q[1] * math.sin(a) > apothem - m:
                    return False
            return True
        n_in = sum(in_prism(q) for q in pts)
        high = [q for q in pts if q[2] > 1.0]
        near = sum(distance(bvh, q) <= 3 * r for q in high)
        frac = near / max(1, len(high))
        print("roots on the cylinder (%s): %d vertices, %d inside, %d above 1 m, %.1f %% of them within 3 r = %.3f m"
              % (shape, len(pts), n_in, len(high), 100 * frac, 3 * r), flush=True)
        if shape == H.SURFACE:
            bt.check(len(pts) > 1000 and len(high) > 100, "roots: a real net on the cylinder (%d, %d above 1 m)" % (
                len(pts), len(high)))
            bt.check(n_in == 0, "roots on the cylinder: %d vertices inside" % n_in)
            bt.check(frac >= 0.9, "roots on the cylinder: %.1f %% of the vertices above 1 m within 3 r" % (100 * frac))
        for o in objs:
            bpy.data.objects.remove(o)


def test_box_shape_unchanged():
    """Bounding box: the operator and the API give the box path's exact mesh;
    Box hosts given to the API stay boxes (the same bytes) under Surface too."""
    bt.reset_scene()
    cube = bpy.data.objects["Cube"]
    cube.rotation_euler = (0.2, 0.1, 0.4)
    cube.scale = (0.8, 1.2, 1.5)
    cube.location = (0.0, 0.0, 1.6)
    bpy.context.view_layer.update()
    boxes = H.boxes_from_objects([cube])
    ref = G.roots(Params("roots"), boxes)
    res, objs = run_op(bpy.ops.mesh.banyan_roots, cube, host_shape='BOX')
    bt.check(res == {'FINISHED'} and len(objs) == 1, "roots (box): operator finished")
    if objs:
        d = world_offset(objs[0], ref.positions)
        bt.check(d < 1e-5, "roots (box): the operator's vertices are the box path's, in world space (%.2g m)" % d)
    # origin=None: the library's world coordinates as they are.
    api_objs = B.strangler_roots(hosts=[cube], host_shape='BOX', origin=None, ground_at_hosts=False)
    co = array("f", bytes(12 * len(api_objs[0].data.vertices)))
    api_objs[0].data.vertices.foreach_get("co", co)
    bt.check(co.tobytes() == ref.positions.tobytes(), "roots (box): the API's vertices are the box path's bytes")
    api_objs = B.strangler_roots(hosts=list(boxes), origin=None,  # Box structs under the default (Surface)
                                 ground_at_hosts=False)
    co = array("f", bytes(12 * len(api_objs[0].data.vertices)))
    api_objs[0].data.vertices.foreach_get("co", co)
    bt.check(co.tobytes() == ref.positions.tobytes(), "roots: Box hosts stay boxes under Surface")
    surf = B.strangler_roots(hosts=[cube])
    bt.check(len(surf[0].data.vertices) > 1000, "roots on the cube's surface: a net (%d vertices)"
             % len(surf[0].data.vertices))
    # Ivy, box path: the operator's mesh is the library's box mesh.
    p = Params("ivy")
    p.set("steps", 60)
    bpy.context.scene.cursor.location = (0.0, -1.5, 0.5)
    p.set("start", (0.0, -1.5, 0.5))  # the cursor, placed by the library
    ref = G.ivy(p, boxes)
    res, objs = run_op(bpy.ops.mesh.banyan_ivy, cube, host_shape='BOX', steps=60)
    if objs:
        d = world_offset(objs[0], ref.positions)
        bt.check(d < 1e-5, "ivy (box): the operator's vertices are the box path's, in world space (%.2g m)" % d)
    else:
        bt.check(False, "ivy (box): operator made nothing (%s)" % res)


def test_evaluated_world_mesh():
    """The host is the evaluated mesh (a Subdivision modifier applied, a
    Bevel curve meshed) under the world matrix."""
    bt.reset_scene()
    cube = bpy.data.objects["Cube"]
    mod = cube.modifiers.new("sub", 'SUBSURF')
    mod.levels = 2
    cube.location = (1.0, 2.0, 3.0)
    cube.rotation_euler = (0.0, 0.0, math.pi / 4)
    bpy.context.view_layer.update()
    dg = bpy.context.evaluated_depsgraph_get()
    m = H.mesh_input_from_object(cube, dg)
    bt.check(m.triangle_count == 2 * 6 * 16, "subdivided cube: %d triangles (96 quads -> 192)" % m.triangle_count)
    bt.check(all(abs(m.transform[k] - v) < 1e-9 for k, v in ((3, 1.0), (7, 2.0), (11, 3.0))),
             "world translation in the transform")
    bt.check(abs(m.transform[0] - math.cos(math.pi / 4)) < 1e-6 and abs(m.transform[4] - math.sin(math.pi / 4)) < 1e-6,
             "world rotation in the transform")
    bt.check(m.positions.typecode == "f" and m.indices.typecode == "I", "typed buffers ('f', 'I')")
    with HostSet(meshes=[m]) as hs:
        # Subdivision pulls the corners in: the old corner is outside the host.
        corner = Vector((1.0, 2.0, 3.0)) + cube.matrix_world.to_3x3() @ Vector((0.99, 0.99, 0.99))
        bt.check(not hs.inside(corner), "the smoothed cube does not reach its old corner")
        bt.check(hs.inside((1.0, 2.0, 3.0)), "its centre is inside")
    # A curve with a bevel is a surface host (to_mesh of the evaluated object).
    bpy.ops.curve.primitive_bezier_circle_add(radius=1.0, location=(5.0, 0.0, 1.0))
    curve = bpy.context.active_object
    curve.data.bevel_depth = 0.2
    bpy.context.view_layer.update()
    m = H.mesh_input_from_object(curve, bpy.context.evaluated_depsgraph_get())
    bt.check(m.triangle_count > 100, "bevelled curve: %d triangles" % m.triangle_count)
    # A camera among the selection is not a host; the operator skips it.
    bt.reset_scene()
    bpy.data.objects["Camera"].select_set(True)
    bpy.context.scene.cursor.location = (0.0, -1.3, -0.8)
    res, objs = run_op(bpy.ops.mesh.banyan_ivy, steps=20)
    bt.check(res == {'FINISHED'} and len(objs) == 1, "ivy with a camera selected too: finished")


def expect_refused(what, call, name, state):
    try:
        call()
        bt.check(False, "%s: accepted" % what)
    except (RuntimeError, BanyanError) as e:
        msg = str(e)
        bt.check(name in msg, "%s: refused naming '%s': %s" % (what, name, msg))
    bt.check(bt.scene_state() == state, "%s: scene unchanged" % what)


def test_bad_hosts():
    for gen, op, api in (("roots", bpy.ops.mesh.banyan_roots, B.strangler_roots),
                         ("ivy", bpy.ops.mesh.banyan_ivy, B.ivy)):
        # An empty mesh object.
        bt.reset_scene()
        bpy.data.objects["Cube"].select_set(False)
        ob = bpy.data.objects.new("EmptyHost", bpy.data.meshes.new("EmptyHost"))
        bpy.context.scene.collection.objects.link(ob)
        ob.select_set(True)
        bpy.context.view_layer.objects.active = ob
        bpy.context.view_layer.update()
        state = bt.scene_state()
        expect_refused("%s on an empty mesh (operator)" % gen, lambda: op(steps=5) if gen == "ivy" else op(),
                       "EmptyHost", state)
        expect_refused("%s on an empty mesh (API)" % gen, lambda: api(hosts=[ob]), "EmptyHost", state)
        # A mesh with a NaN vertex.
        bt.reset_scene()
        cube = bpy.data.objects["Cube"]
        cube.name = "NaNCube"
        cube.data.vertices[3].co = (float("nan"), 1.0, 1.0)
        bpy.context.view_layer.update()
        state = bt.scene_state()
        expect_refused("%s on a NaN vertex (operator)" % gen, lambda: op(steps=5) if gen == "ivy" else op(),
                       "NaNCube", state)
        expect_refused("%s on a NaN vertex (API)" % gen, lambda: api(hosts=[cube]), "NaNCube", state)
        # Scaled flat: a singular world matrix.
        bt.reset_scene()
        cube = bpy.data.objects["Cube"]
        cube.name = "FlatCube"
        cube.scale = (1.0, 1.0, 0.0)
        bpy.context.view_layer.update()
        state = bt.scene_state()
        expect_refused("%s on a zero-scaled object (operator)" % gen, lambda: op(steps=5) if gen == "ivy" else op(),
                       "FlatCube", state)
        # A curve without bevel has no triangles.
        bt.reset_scene()
        bpy.ops.curve.primitive_bezier_circle_add(radius=1.0)
        bpy.context.active_object.name = "BareCurve"
        state = bt.scene_state()
        expect_refused("%s on a curve with no bevel (API)" % gen, lambda: api(hosts=[bpy.data.objects["BareCurve"]]),
                       "BareCurve", state)
    bt.reset_scene()
    state = bt.scene_state()
    try:
        B.strangler_roots(hosts=[bpy.data.objects["Cube"]], host_shape="SPHERE")
        bt.check(False, "host_shape='SPHERE' accepted")
    except BanyanError as e:
        bt.check("host_shape" in e.message, "a bad host_shape is named: %s" % e.message)
    bt.check(bt.scene_state() == state, "scene unchanged after a bad host_shape")
    # MeshInput with an index out of range: the library refuses, naming the host.
    try:
        HostSet(meshes=[MeshInput(array("f", [0, 0, 0, 1, 0, 0, 0, 1, 0]), array("I", [0, 1, 7]), name="Broken")])
        bt.check(False, "an index out of range accepted")
    except BanyanError as e:
        bt.check("Broken" in e.message, "index out of range refused naming the host: %s" % e.message)


def test_large_host():
    """A 1.3M-triangle icosphere (20 * 4^8): read + build time printed (not asserted)."""
    empty_scene()
    t = time.perf_counter()
    bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=9, radius=1.0, location=(0.0, 0.0, 1.2))
    obj = bpy.context.active_object
    bpy.context.view_layer.update()
    t_make = time.perf_counter() - t
    dg = bpy.context.evaluated_depsgraph_get()
    t = time.perf_counter()
    m = H.mesh_input_from_object(obj, dg)
    t_read = time.perf_counter() - t
    t = time.perf_counter()
    with HostSet(meshes=[m]) as hs:
        t_build = time.perf_counter() - t
        bt.check(hs.info(0)["triangle_count"] == m.triangle_count, "large host: every triangle kept")
    bpy.context.scene.cursor.location = (0.0, -1.2, 0.6)
    t = time.perf_counter()
    res, objs = run_op(bpy.ops.mesh.banyan_ivy, obj, steps=60)
    t_op = time.perf_counter() - t
    bt.check(res == {'FINISHED'} and len(objs) == 1, "ivy on a 1.3M-triangle host finished")
    print("large host: %d triangles; Blender made it in %.2f s; read (foreach_get) %.3f s, host set built %.3f s; "
          "ivy operator (60 steps, read + build included) %.2f s" % (m.triangle_count, t_make, t_read, t_build, t_op),
          flush=True)


print("Blender %s" % bpy.app.version_string, flush=True)
if bt.generator("ivy") and bt.generator("roots"):
    bt.run(test_binding)
    for k in ("sphere", "suzanne", "cylinder", "plane"):
        bt.run(lambda: test_ivy(k))
    for k in ("suzanne", "cylinder"):
        bt.run(lambda: test_inside_matches_winding(k))
    bt.run(test_roots_cylinder)
    bt.run(test_box_shape_unchanged)
    bt.run(test_evaluated_world_mesh)
    bt.run(test_bad_hosts)
    bt.run(test_large_host)
bt.done()
