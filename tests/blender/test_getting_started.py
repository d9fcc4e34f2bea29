"""docs/getting-started.md, as written: a fresh Blender (empty user
scripts, no BANYAN_LIB) installs build/banyan.zip the way Edit >
Preferences > Add-ons > Install does, enables it, finds Add Strangler
Roots under Add > Mesh > Banyan, and with the default cube selected gets
roots around the cube down to its foot; the guide's tweak (Main roots 12)
works too, and the figures the guide quotes are what
docs/render_getting_started.py measures now.

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
from banyan.ui import state
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


sys.path.insert(0, DOCS)
import render_getting_started as RG
figures = {}


def grow(**kw):
    before = set(bpy.data.objects)
    res = bpy.ops.mesh.banyan_roots(**kw)
    new = [o for o in bpy.data.objects if o not in before]
    figures[len(figures)] = RG.measure(new) if new else None
    vs = [o.matrix_world @ v.co for o in new if o.type == 'MESH' for v in o.data.vertices]
    inside = sum(1 for v in vs if max(abs(v.x), abs(v.y), abs(v.z)) < 1 - 1e-3)
    sides = [sum(1 for v in vs if v.x > 1), sum(1 for v in vs if v.x < -1),
             sum(1 for v in vs if v.y > 1), sum(1 for v in vs if v.y < -1)]
    on_top = sum(1 for v in vs if v.z > 1 and abs(v.x) < 1 and abs(v.y) < 1)
    # above the foot (0.3 m over the ground at z = -1): the buttresses and
    # surface roots at the foot run out over the ground on purpose
    lifted = [v for v in vs if v.z > -0.7]
    near = sum(1 for v in lifted if max(abs(v.x), abs(v.y)) < 1.5)
    bottom = min((v.z for v in vs), default=0.0)
    for o in new:
        bpy.data.objects.remove(o)
    cube.select_set(True)
    bpy.context.view_layer.objects.active = cube
    return {"result": sorted(res), "objects": len(new), "vertices": len(vs), "inside": inside, "sides": sides,
            "on_top": on_top, "near": near, "lifted": len(lifted), "bottom": bottom}


out["defaults"] = grow()
out["tweak"] = grow(**RG.TWEAK)
out["figures"] = RG.figures_text(figures[0], figures[1]) if figures[0] and figures[1] else None
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
            f.write("ZIP = %r\nDOCS = %r\n" % (zip_path, os.path.join(bt.SOURCE_DIR, "docs")) + CHILD)
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
        # The six main roots fan over the top and down; one face of the
        # four may be left to none.
        bt.check(sum(1 for n in g["sides"] if n > 0) >= 3 and g["on_top"] > 0,
                 "%s: roots on at least three sides %s and on top (%d)" % (key, g["sides"], g["on_top"]))
        # The ground is at the cube's foot (z = -1): the roots reach it and enter the soil beside it.
        bt.check(g["bottom"] < -0.95, "%s: roots down to the cube's foot (lowest z %.3f)" % (key, g["bottom"]))
        bt.check(g["near"] > 0.9 * g["lifted"], "%s: roots close round the cube, not crawling away: %d of %d "
                 "vertices above the foot within 0.5 m of it" % (key, g["near"], g["lifted"]))
    bt.check(out["tweak"]["vertices"] > out["defaults"]["vertices"], "tweak: more main roots, more vertices (%d -> %d)"
             % (out["defaults"]["vertices"], out["tweak"]["vertices"]))
    with open(os.path.join(bt.SOURCE_DIR, "docs", "getting-started.md"), encoding="utf-8") as f:
        guide = f.read()
    bt.check(out["figures"] and out["figures"] in guide, "docs/getting-started.md quotes what "
             "docs/render_getting_started.py measures now (bash tools/render_docs.sh start writes it):\n%s"
             % out["figures"])


bt.run(test_guide)
bt.done()
