"""docs/getting-started.md, as written: a fresh Blender (empty user
scripts, no BANYAN_LIB) installs build/banyan.zip the way Edit >
Preferences > Add-ons > Install does, enables it, finds Add Strangler
Roots under Add > Mesh > Banyan, and with the default cube selected gets
roots around the cube; the guide's tweak (Growth Points 15) works too.

The steps run in a child Blender, so nothing of the add-on this test
runner loaded (from the repository) is involved."""
import json
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bt  # noqa: E402

import bpy  # noqa: E402

CHILD = r'''
import json, os, sys
import bpy
out = {}
# Edit > Preferences > Add-ons > Install..., pick the zip, then tick the box.
out["install"] = sorted(bpy.ops.preferences.addon_install(filepath=ZIP))
out["enable"] = sorted(bpy.ops.preferences.addon_enable(module="banyan"))
out["enabled"] = "banyan" in bpy.context.preferences.addons
import banyan
from banyan import state
from banyan.core import lib
out["package"] = os.path.realpath(os.path.dirname(banyan.__file__))
out["library"] = os.path.realpath(lib.load()._name)
out["load_error"] = state.LOAD_ERROR
# Add > Mesh holds the Banyan menu, which lists Add Strangler Roots.
out["menu"] = hasattr(bpy.types, "VIEW3D_MT_banyan_add") and any(
    getattr(f, "__module__", "").startswith("banyan") for f in bpy.types.VIEW3D_MT_mesh_add._dyn_ui_initialize())
out["entries"] = [list(e) for e in state.operator_entries()]
cube = bpy.data.objects["Cube"]
out["cube_selected"] = cube.select_get() and bpy.context.view_layer.objects.active == cube


def grow(**kw):
    before = set(bpy.data.objects)
    res = bpy.ops.mesh.banyan_roots(**kw)
    new = [o for o in bpy.data.objects if o not in before]
    vs = [o.matrix_world @ v.co for o in new if o.type == 'MESH' for v in o.data.vertices]
    inside = sum(1 for v in vs if max(abs(v.x), abs(v.y), abs(v.z)) < 1 - 1e-3)
    sides = [sum(1 for v in vs if v.x > 1), sum(1 for v in vs if v.x < -1),
             sum(1 for v in vs if v.y > 1), sum(1 for v in vs if v.y < -1)]
    on_top = sum(1 for v in vs if v.z > 1 and abs(v.x) < 1 and abs(v.y) < 1)
    near = sum(1 for v in vs if max(abs(v.x), abs(v.y)) < 1.5)
    for o in new:
        bpy.data.objects.remove(o)
    cube.select_set(True)
    bpy.context.view_layer.objects.active = cube
    return {"result": sorted(res), "objects": len(new), "vertices": len(vs), "inside": inside, "sides": sides,
            "on_top": on_top, "near": near}


out["defaults"] = grow()
out["tweak"] = grow(growth_points=15)
print("GETTING_STARTED " + json.dumps(out))
'''


def test_guide():
    build = os.environ.get("BANYAN_BUILD_DIR") or os.path.join(bt.SOURCE_DIR, "build")
    zip_path = os.path.join(build, "banyan.zip")
    if not bt.check(os.path.isfile(zip_path), "%s exists (the guide installs it)" % zip_path):
        return
    with tempfile.TemporaryDirectory() as user:
        script = os.path.join(user, "guide.py")
        with open(script, "w") as f:
            f.write("ZIP = %r\n" % zip_path + CHILD)
        env = {k: v for k, v in os.environ.items() if not k.startswith(("BANYAN_", "BLENDER_"))}
        env["BLENDER_USER_SCRIPTS"] = os.path.join(user, "scripts")  # a newcomer's empty scripts folder
        r = subprocess.run([bt.BLENDER, "-b", "--factory-startup", "--python-exit-code", "1",
                            "--python", script], capture_output=True, text=True, timeout=300, env=env)
        lines = [ln for ln in r.stdout.splitlines() if ln.startswith("GETTING_STARTED ")]
        if not bt.check(r.returncode == 0 and lines, "child Blender ran the guide (exit %d): %s"
                        % (r.returncode, (r.stdout + r.stderr)[-1500:])):
            return
        out = json.loads(lines[-1].split(" ", 1)[1])
        installed = os.path.realpath(os.path.join(user, "scripts", "addons", "banyan"))
    print("guide:", json.dumps(out))
    bt.check(out["install"] == ["FINISHED"] and out["enable"] == ["FINISHED"] and out["enabled"],
             "install and enable: %s %s" % (out["install"], out["enable"]))
    bt.check(out["package"] == installed, "the add-on came from the installed zip: %s" % out["package"])
    bt.check(out["library"].startswith(installed + os.sep), "the library is the zip's: %s" % out["library"])
    bt.check(out["load_error"] == "", "library loaded: %s" % out["load_error"])
    bt.check(out["menu"], "Add > Mesh has the Banyan menu")
    bt.check(["mesh.banyan_roots", "Add Strangler Roots"] in out["entries"], "menu entries: %s" % out["entries"])
    bt.check(out["cube_selected"], "the default cube is selected and active")
    for key in ("defaults", "tweak"):
        g = out[key]
        bt.check(g["result"] == ["FINISHED"] and g["objects"] == 1 and g["vertices"] > 1000,
                 "%s: one roots object (%s)" % (key, g))
        bt.check(g["inside"] == 0, "%s: no vertex inside the cube (%d)" % (key, g["inside"]))
        # Issue #18: roots that reach the ground go into the soil there
        # instead of crawling round the foot, and the cube stands 1 m above
        # the ground: the six main roots fan over the top and down, and one
        # face of the four may be left to none (seeds 1, 2, 5 of 1..5).
        bt.check(sum(1 for n in g["sides"] if n > 0) >= 3 and g["on_top"] > 0,
                 "%s: roots on at least three sides %s and on top (%d)" % (key, g["sides"], g["on_top"]))
    # The tweak keeps the roots close round the cube.
    t = out["tweak"]
    bt.check(t["near"] > 0.5 * t["vertices"], "tweak: most vertices within 0.5 m of the cube (%d of %d)"
             % (t["near"], t["vertices"]))


bt.run(test_guide)
bt.done()
