"""build/banyan_extension.zip installs as a Blender 4.2+ extension the way
Edit > Preferences > Get Extensions > Install from Disk does (in a child
Blender with empty user folders and no BANYAN_LIB), loads the zip's own
library (with the libraries bundled beside it) and grows roots around the
default cube. Blender before 4.2 has no extensions: the test says so."""
import json
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bt  # noqa: E402

import bpy  # noqa: E402

CHILD = r'''
import json, sys
import bpy
out = {}
out["install"] = sorted(bpy.ops.extensions.package_install_files(filepath=ZIP, repo="user_default",
                                                                  enable_on_install=True))
name = "bl_ext.user_default.banyan"
out["enabled"] = name in bpy.context.preferences.addons
pkg = sys.modules[name]
out["version"] = list(bpy.app.version)
out["package"] = pkg.__file__
out["library"] = sys.modules[name + ".core.lib"].load().banyan_path
out["load_error"] = sys.modules[name + ".state"].LOAD_ERROR
out["maps"] = [ln.split()[-1] for ln in open("/proc/self/maps") if ln.rstrip().endswith((".so", ".so.0", ".so.1", ".so.2d", ".so.3", ".so.12"))]
n = len(bpy.data.objects)
out["roots"] = sorted(bpy.ops.mesh.banyan_roots())
out["objects"] = len(bpy.data.objects) - n
print("EXTENSION " + json.dumps(out))
'''


def test_extension():
    build = os.environ.get("BANYAN_BUILD_DIR") or os.path.join(bt.SOURCE_DIR, "build")
    zip_path = os.path.join(build, "banyan_extension.zip")
    if not bt.check(os.path.isfile(zip_path), "%s exists (build the banyan_extension_zip target)" % zip_path):
        return
    with tempfile.TemporaryDirectory() as user:
        script = os.path.join(user, "ext.py")
        with open(script, "w") as f:
            f.write("ZIP = %r\n" % zip_path + CHILD)
        env = {k: v for k, v in os.environ.items() if not k.startswith(("BANYAN_", "BLENDER_"))}
        env["BLENDER_USER_SCRIPTS"] = os.path.join(user, "scripts")
        env["BLENDER_USER_EXTENSIONS"] = os.path.join(user, "extensions")
        env["BLENDER_USER_CONFIG"] = os.path.join(user, "config")
        r = subprocess.run([bt.BLENDER, "-b", "--factory-startup", "--python-exit-code", "1", "--python", script],
                           capture_output=True, text=True, timeout=300, env=env)
        lines = [ln for ln in r.stdout.splitlines() if ln.startswith("EXTENSION ")]
        if not bt.check(r.returncode == 0 and lines, "child Blender installed the extension (exit %d): %s"
                        % (r.returncode, (r.stdout + r.stderr)[-1500:])):
            return
        out = json.loads(lines[-1].split(" ", 1)[1])
        root = os.path.realpath(os.path.join(user, "extensions", "user_default", "banyan"))
        print("extension:", json.dumps({k: v for k, v in out.items() if k != "maps"}))
        bt.check(out["install"] == ["FINISHED"] and out["enabled"], "installed and enabled: %s" % out["install"])
        bt.check(os.path.realpath(out["package"]).startswith(root + os.sep), "package from the extension: %s"
                 % out["package"])
        bt.check(os.path.realpath(out["library"]) == os.path.join(root, "lib", "libbanyan.so"),
                 "the extension's library: %s" % out["library"])
        bt.check(out["load_error"] == "", "library loaded: %s" % out["load_error"])
        with open(os.path.join(root, "lib", "bundled.txt")) if os.path.isfile(os.path.join(root, "lib", "bundled.txt")) \
                else open(os.devnull) as f:
            bundled = f.read().split()
        for name in bundled:
            bt.check(os.path.join(root, "lib", name) in [os.path.realpath(m) for m in out["maps"]],
                     "bundled %s is the one loaded" % name)
        bt.check(out["roots"] == ["FINISHED"] and out["objects"] == 1, "roots around the cube: %s, %d object(s)"
                 % (out["roots"], out["objects"]))


if bpy.app.version < (4, 2, 0):
    print("SKIP: Blender %s has no extensions (4.2+)" % bpy.app.version_string)
    bt.check(True, "nothing to test before 4.2")
else:
    bt.run(test_extension)
bt.done()
