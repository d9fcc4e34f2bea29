"""Blender's own USD importer (bpy.ops.wm.usd_import) on the layers the
CLI writes (docs/usd.md): a keyaki, written as .usda and as .glb by the
same CLI, and an avenue of 3 variants placed as instances. Each import must
give the stage's frame unchanged (Z up, metres: the keyaki's bounds equal
the .glb's within 1 mm after glTF's Y-up turn), the wind and growth
primvars as point attributes (wind_pivot a vector, within 1 mm of the
.glb's pivots, wind_level ... birth), the uvs, and the avenue's
PointInstancer as as many instances as it places. Blenders built without
USD (Debian's 3.4) have no importer: the test then checks only that the
operator is missing and says so."""
import json
import os
import struct
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bt  # noqa: E402

import bpy  # noqa: E402

BUILD = os.environ.get("BANYAN_BUILD_DIR") or os.path.join(bt.SOURCE_DIR, "build")
CLI = os.path.join(BUILD, "banyan")
PRESETS = os.path.join(bt.SOURCE_DIR, "presets")
OUT = os.path.join(bt.OUT_DIR, "usd_import_%d_%d" % bpy.app.version[:2])
SCALARS = ("wind_level", "wind_stiffness", "wind_phase", "wind_flutter", "birth")


def cli(*args):
    r = subprocess.run([CLI] + list(args) + ["--texture-size", "64"], capture_output=True, text=True)
    bt.check(r.returncode == 0, "banyan %s: %s" % (" ".join(args), r.stderr[-300:]))
    return r.returncode == 0


def glb_mesh(path):
    """The .glb's first mesh: positions and wind pivots (Y up), in order."""
    b = open(path, "rb").read()
    n = struct.unpack_from("<I", b, 12)[0]
    j = json.loads(b[20:20 + n])
    base = 20 + n + 8

    def read(acc):
        a = j["accessors"][acc]
        v = j["bufferViews"][a["bufferView"]]
        k = 3 if a["type"] == "VEC3" else 1
        off = base + v.get("byteOffset", 0) + a.get("byteOffset", 0)
        return struct.unpack_from("<%df" % (k * a["count"]), b, off)

    pos, piv = [], []
    for p in j["meshes"][0]["primitives"]:
        at = p["attributes"]
        pos.append(read(at["POSITION"]))
        xs, ys, zs = (read(at["_WIND_PIVOT_" + c]) for c in "XYZ")
        piv.append([v for t in zip(xs, ys, zs) for v in t])
    return pos, piv


def clear():
    for coll in (bpy.data.objects, bpy.data.meshes, bpy.data.materials, bpy.data.images, bpy.data.collections,
                 bpy.data.pointclouds):
        for x in list(coll):
            coll.remove(x)


def keyaki():
    layer, glb = os.path.join(OUT, "keyaki.usda"), os.path.join(OUT, "keyaki.glb")
    preset = os.path.join(PRESETS, "keyaki_young.json")
    if not (cli("keyaki", "--preset", preset, "-o", layer) and cli("keyaki", "--preset", preset, "-o", glb)):
        return
    clear()
    bt.check(bpy.ops.wm.usd_import(filepath=layer) == {"FINISHED"}, "import " + layer)
    meshes = [o for o in bpy.data.objects if o.type == "MESH"]
    bt.check([o.name for o in meshes] == ["keyaki_bark", "keyaki_leaf"], "keyaki meshes: %s" % [o.name for o in meshes])
    pos, piv = glb_mesh(glb)
    for o, p, w in zip(meshes, pos, piv):
        me = o.data
        n = len(me.vertices)
        bt.check(3 * n == len(p), "%s: %d vertices, the .glb's part %d" % (o.name, n, len(p) // 3))
        if 3 * n != len(p):
            continue
        co = [0.0] * (3 * n)
        me.attributes["position"].data.foreach_get("vector", co)
        m = o.matrix_world
        world = [m @ __import__("mathutils").Vector(co[3 * i:3 * i + 3]) for i in range(0, n, max(1, n // 500))]
        err = max(max(abs(v.x - p[3 * i]), abs(v.y + p[3 * i + 2]), abs(v.z - p[3 * i + 1]))
                  for v, i in zip(world, range(0, n, max(1, n // 500))))
        bt.check(err < 1e-3, "%s: positions %.2g m off the .glb's (Z up, metres)" % (o.name, err))
        a = me.attributes.get("wind_pivot")
        bt.check(a is not None and a.data_type == "FLOAT_VECTOR" and a.domain == "POINT",
                 "%s: wind_pivot a point vector: %s" % (o.name, a and (a.data_type, a.domain)))
        if a is not None and a.data_type == "FLOAT_VECTOR":
            q = [0.0] * (3 * n)
            a.data.foreach_get("vector", q)
            err = max(max(abs(q[3 * i] - w[3 * i]), abs(q[3 * i + 1] + w[3 * i + 2]), abs(q[3 * i + 2] - w[3 * i + 1]))
                      for i in range(n))
            bt.check(err < 1e-3, "%s: wind pivots %.2g m off the .glb's" % (o.name, err))
        for s in SCALARS:
            b = me.attributes.get(s)
            bt.check(b is not None and b.data_type == "FLOAT" and b.domain == "POINT", "%s: %s a point float" % (o.name, s))
        bt.check(me.uv_layers.get("st") is not None, "%s: the uvs as uv map st" % o.name)
    bt.check(abs(bpy.context.scene.unit_settings.scale_length - 1.0) < 1e-9, "scene unit scale 1")


def avenue():
    layer = os.path.join(OUT, "avenue.usda")
    if not cli("avenue", "--preset", os.path.join(PRESETS, "avenue_street.json"), "--set", "variants=3",
               "--set", "tree.levels=6", "-o", layer):
        return
    want = None
    with open(layer) as f:
        for line in f:
            if "int[] protoIndices" in line:
                want = line.count(",") + 1
                break
    clear()
    bt.check(bpy.ops.wm.usd_import(filepath=layer) == {"FINISHED"}, "import " + layer)
    clouds = [o for o in bpy.data.objects if o.type == "POINTCLOUD"]
    bt.check(len(clouds) == 1 and len(clouds[0].data.points) == want,
             "the PointInstancer as one point cloud of %s points: %s" % (want, [len(c.data.points) for c in clouds]))
    dg = bpy.context.evaluated_depsgraph_get()
    trees = {tuple(round(x, 3) for x in i.matrix_world.translation) for i in dg.object_instances if i.is_instance}
    bt.check(len(trees) == want, "%d instance places in the scene, want %s" % (len(trees), want))


os.makedirs(OUT, exist_ok=True)
if "usd_import" not in dir(bpy.ops.wm):
    print("this Blender %s has no USD importer (built without USD)" % bpy.app.version_string)
    bt.check(bpy.app.version < (4, 0, 0), "a Blender from 4.0 on without the USD importer")
else:
    keyaki()
    avenue()
bt.done()
