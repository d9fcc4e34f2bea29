"""A .glb mesh host 500 km from the origin (made here by the CLI: a small
keyaki at x = 500,000 m, whose glTF node carries that translation):
  - core.hostset.read_glb returns the library's transform with the far
    offset in it (row 0 = [1, 0, 0, 500000]), positions near zero;
  - hosts.objects_from_preset puts the object at 500 km: its location is
    the library's, and its world bounds (location + vertex, in Python
    doubles) are the bounds of the library's own host set of the preset,
    to a millimetre; the same with a preset translation and rotation.
"""
import json
import os
import subprocess
import sys
from array import array

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bt  # noqa: E402

import bpy  # noqa: E402

from banyan.engine import hosts as H  # noqa: E402
from banyan.core.hostset import HostSet, read_glb  # noqa: E402

BUILD = os.environ.get("BANYAN_BUILD_DIR") or os.path.join(bt.SOURCE_DIR, "build")
CLI = os.path.join(BUILD, "banyan")
FAR_X = 500000.0


def far_glb():
    path = os.path.join(bt.OUT_DIR, "far_host_500km.glb")
    r = subprocess.run([CLI, "keyaki", "--set", "position=%d,0,0" % FAR_X, "--set", "levels=3", "--set",
                        "leaf_levels=0", "--textures", "off", "--stats", "-o", path], capture_output=True, text=True)
    bt.check(r.returncode == 0 and '"origin": [500000, 0, 0]' in r.stdout,
             "CLI wrote a keyaki 500 km out: rc %d %s %s" % (r.returncode, r.stdout[-200:], r.stderr[-300:]))
    return path


def world_bounds(ob):
    """(lo, hi) of location + rotation/scale * vertex, in Python doubles
    (Blender's own matrix_world product is float32: 3 cm at 500 km)."""
    n = len(ob.data.vertices)
    co = array("f", bytes(12 * n))
    ob.data.vertices.foreach_get("co", co)
    m = [list(r) for r in ob.matrix_world]
    pts = [[m[r][0] * co[i] + m[r][1] * co[i + 1] + m[r][2] * co[i + 2] + m[r][3] for r in range(3)]
           for i in range(0, len(co), 3)]
    return [min(p[k] for p in pts) for k in range(3)], [max(p[k] for p in pts) for k in range(3)]


def test_read_glb(path):
    mi = read_glb(path)
    t = mi.transform
    bt.check(t[:4] == (1.0, 0.0, 0.0, FAR_X) and t[4:] == (0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0),
             "read_glb: the library's transform with the far offset, row 0 = %s" % (t[:4],))
    bt.check(max(abs(x) for x in mi.positions) < 100, "read_glb: positions relative to the offset (max |p| %.1f)"
             % max(abs(x) for x in mi.positions))
    moved = read_glb(path, transform=(1, 0, 0, 10, 0, 1, 0, 20, 0, 0, 1, 30))
    bt.check(moved.transform[3] == FAR_X + 10 and moved.transform[7] == 20 and moved.transform[11] == 30,
             "read_glb with a translation: the offset added to it: %s" % (moved.transform[3::4],))


def test_objects(path):
    for what, entry in (("plain", {}), ("moved and turned", {"translation": [-1000, 250, 5],
                                                             "rotation_euler_deg": [0, 0, 90]})):
        bt.reset_scene()
        bpy.data.objects.remove(bpy.data.objects["Cube"])
        doc = {"generator": "roots", "schema": 1, "hosts": [dict(entry, mesh=path, name="far")]}
        preset = os.path.join(bt.OUT_DIR, "roots_far_host.json")
        with open(preset, "w", encoding="utf-8") as f:
            json.dump(doc, f)
        objs, _ = H.objects_from_preset("roots", preset)
        ob = objs[0]
        lo, hi = world_bounds(ob)
        with HostSet.from_preset(json.dumps(doc), preset) as hs:
            info = hs.info(0)
        err = max(max(abs(lo[k] - info["lo"][k]), abs(hi[k] - info["hi"][k])) for k in range(3))
        print("%s: location %s, world x %.3f .. %.3f, library %.3f .. %.3f" % (
            what, tuple(ob.location), lo[0], hi[0], info["lo"][0], info["hi"][0]), flush=True)
        bt.check(err < 1e-3, "%s: object world bounds %s..%s vs the library's %s..%s (off by %.3g m)"
                 % (what, lo, hi, info["lo"], info["hi"], err))
        # Turned a quarter about z, the offset (along x) lands on y.
        want = (-1000.0, 250.0 + FAR_X, 5.0) if entry else (FAR_X, 0.0, 0.0)
        bt.check(all(abs(ob.location[k] - want[k]) < 1e-6 for k in range(3)),
                 "%s: the object stands at %s (is at %s)" % (what, want, tuple(ob.location)))


if bt.generator("keyaki") and bt.generator("roots"):
    glb = far_glb()
    bt.run(lambda: test_read_glb(glb))
    bt.run(lambda: test_objects(glb))
bt.done()
