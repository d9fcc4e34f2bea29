"""Presets with .glb mesh hosts applied in Blender (banyan.engine.hosts.objects_from_preset):
  - each host object holds the library's reading of the file (banyan_glb_read_host)
    under the transform the library composes from the entry: its world bounds are
    the bounds of the library's own preset host set (banyan_preset_host_set), for the
    shipped presets and for a preset with rotation_euler_deg, a non-uniform scale
    and a translation;
  - a plant grown on those objects (host shape Surface) is the plant grown on the
    preset's own host set (the CLI's), up to Blender's float matrices;
  - a preset naming a missing or non-glTF file is refused naming it, and the scene
    is left as it was.
"""
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bt  # noqa: E402

import bpy  # noqa: E402
from mathutils import Vector  # noqa: E402

import banyan.api as B  # noqa: E402
from banyan.engine import hosts as H  # noqa: E402
from banyan.core import BanyanError  # noqa: E402
from banyan.core.hostset import HostSet, read_glb  # noqa: E402

PRESETS = (("roots", "roots_column"), ("roots", "roots_rock"), ("ivy", "ivy_statue"))
HOSTS_DIR = os.path.join(bt.SOURCE_DIR, "presets", "hosts")


def empty():
    bt.reset_scene()
    bpy.data.objects.remove(bpy.data.objects["Cube"])


def world_bounds(ob):
    mw = ob.matrix_world
    pts = [mw @ v.co for v in ob.data.vertices]  # a test: a few thousand vertices
    lo = Vector([min(p[k] for p in pts) for k in range(3)])
    hi = Vector([max(p[k] for p in pts) for k in range(3)])
    return lo, hi


def check_bounds(what, ob, hs, index):
    info = hs.info(index)
    lo, hi = world_bounds(ob)
    err = max(max(abs(lo[k] - info["lo"][k]), abs(hi[k] - info["hi"][k])) for k in range(3))
    bt.check(err < 1e-4, "%s: object '%s' world bounds %s..%s vs the library's %s..%s (off by %.2g m)"
             % (what, ob.name, tuple(lo), tuple(hi), info["lo"], info["hi"], err))


def test_shipped():
    for gen, name in PRESETS:
        empty()
        objs, boxes = H.objects_from_preset(gen, name)
        bt.check(len(objs) == 1 and not boxes, "%s: one mesh host object, no boxes" % name)
        ob = objs[0]
        path = os.path.join(bt.SOURCE_DIR, "presets", name + ".json")
        with open(path, "rb") as f:
            text = f.read()
        mi = read_glb(os.path.join(HOSTS_DIR, json.loads(text)["hosts"][0]["mesh"][len("hosts/"):]))
        bt.check(len(ob.data.vertices) == mi.vertex_count and len(ob.data.polygons) == mi.triangle_count,
                 "%s: the object has the file's %d vertices and %d triangles (has %d, %d)"
                 % (name, mi.vertex_count, mi.triangle_count, len(ob.data.vertices), len(ob.data.polygons)))
        bt.check(ob[H.CLOSED_PROP] == 1, "%s: the preset's closed = \"closed\" is kept" % name)
        with HostSet.from_preset(text, path) as hs:
            check_bounds(name, ob, hs, 0)
        # The plant on the objects and the plant on the preset's own host set.
        grow = B.strangler_roots if gen == "roots" else B.ivy
        a = grow(hosts=objs, preset=name, name="OnObjects")[0]
        b = grow(preset=name, name="OnPresetSet")[0]
        na, nb = len(a.data.vertices), len(b.data.vertices)
        # The fused roots surface is a level set: the objects' float32 copy
        # of the host moves a few voxels' signs (docs/roots.md "Fused surface").
        fused = gen == "roots" and json.loads(text)["params"].get("surface", "fused") == "fused"
        same = abs(na - nb) <= 1e-3 * nb if fused else na == nb
        bt.check(same and na > 0, "%s: %d vertices on the objects, %d on the preset's host set" % (name, na, nb))
        if fused and na and nb:
            # A level set's vertex order follows its voxels: one sign that
            # flips reorders the rest, so compare where the plants lie.
            def box(o):
                from array import array
                co = array("f", bytes(12 * len(o.data.vertices)))
                o.data.vertices.foreach_get("co", co)
                return [min(co[k::3]) for k in range(3)] + [max(co[k::3]) for k in range(3)]
            d = max(abs(x - y) for x, y in zip(box(a), box(b)))
            bt.check(d < 0.01, "%s: the two plants' bounds agree to %.2g m" % (name, d))
        elif na == nb and na:
            from array import array
            pa, pb = array("f", bytes(12 * na)), array("f", bytes(12 * nb))
            a.data.vertices.foreach_get("co", pa)
            b.data.vertices.foreach_get("co", pb)
            d = max(abs(x - y) for x, y in zip(pa, pb))
            bt.check(d < 1e-3, "%s: the two plants agree to %.2g m" % (name, d))


def test_transform():
    """rotation_euler_deg, a non-uniform scale and a translation: the
    objects land where the library puts the meshes."""
    empty()
    rock = os.path.join(HOSTS_DIR, "rock.glb")
    doc = {"generator": "roots", "schema": 1, "hosts": [
        {"center": [5, 0, 1], "half": [0.5, 0.5, 1], "rotation_euler_deg": [0, 0, 30]},
        {"mesh": rock, "translation": [1.5, -2, 0.25], "rotation_euler_deg": [10, 25, 70], "scale": [1, 0.6, 1.3],
         "closed": "auto", "name": "tilted"},
        {"mesh": rock, "rotation": [0, -1, 0, 1, 0, 0, 0, 0, 1], "scale": 0.5, "name": "small"}]}
    path = os.path.join(bt.OUT_DIR, "roots_preset_hosts_transform.json")
    with open(path, "w", encoding="utf-8") as f:
        json.dump(doc, f)
    objs, boxes = H.objects_from_preset("roots", path)
    bt.check([o.name for o in objs] == ["tilted", "small"] and len(boxes) == 1,
             "two mesh objects in preset order and one box: %s, %d" % ([o.name for o in objs], len(boxes)))
    bt.check(abs(boxes[0].center[0] - 5) < 1e-12 and abs(boxes[0].half[2] - 1) < 1e-12, "the box as given")
    bt.check(objs[0][H.CLOSED_PROP] == -1, "closed \"auto\" kept as -1")
    with HostSet.from_preset(json.dumps(doc), path) as hs:
        bt.check(hs.count == 3, "library host set: 3 hosts")
        for i, ob in enumerate(objs):
            check_bounds("transform", ob, hs, 1 + i)  # boxes first, then the meshes


def test_refused():
    empty()
    bad = os.path.join(bt.OUT_DIR, "not_a_model.glb")
    with open(bad, "w") as f:
        f.write("this is not glTF")
    for what, mesh in (("missing file", os.path.join(bt.OUT_DIR, "no_such_host.glb")), ("not glTF", bad)):
        path = os.path.join(bt.OUT_DIR, "ivy_preset_hosts_bad.json")
        with open(path, "w", encoding="utf-8") as f:
            json.dump({"generator": "ivy", "schema": 1, "hosts": [
                {"mesh": os.path.join(HOSTS_DIR, "statue.glb")}, {"mesh": mesh}]}, f)
        state = bt.scene_state()
        try:
            H.objects_from_preset("ivy", path)
            bt.check(False, "%s: accepted" % what)
        except BanyanError as e:
            bt.check(os.path.basename(mesh) in e.message and "hosts[1]" in e.message,
                     "%s: refused naming hosts[1] and the file: %s" % (what, e.message))
        bt.check(bt.scene_state() == state, "%s: scene unchanged" % what)
    try:
        read_glb(bad)
        bt.check(False, "read_glb of a text file: accepted")
    except BanyanError as e:
        bt.check("not_a_model.glb" in e.message, "read_glb refuses a text file naming it: %s" % e.message)


if bt.generator("roots") and bt.generator("ivy"):
    bt.run(test_shipped)
    bt.run(test_transform)
    bt.run(test_refused)
bt.done()
