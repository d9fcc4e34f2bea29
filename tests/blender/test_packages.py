"""The two packages are self-contained: build/banyan.zip (the legacy
add-on, every Blender) and build/banyan_extension.zip (Blender 4.2+).
Each is unpacked into an empty folder where `ldd` must resolve every
library of lib/ to that folder or to the C, C++ and math runtimes; then
a child Blender with empty user folders and no BANYAN_* variables installs
it the way Preferences does (Install... / Install from Disk), enables it
and grows roots around the default cube, and its /proc/self/maps must hold
no library from the build or source tree, and the OpenVDB module
(libbanyan_vdb.so) only once the fused roots were meshed. BANYAN_ZIP_DIR names the folder
holding the zips (default BANYAN_BUILD_DIR); tests/blender/packages.sh runs
this with the build folder moved away. Under either package a script's
`import banyan` must give the add-on's own modules (scripting.py)."""
import json
import os
import subprocess
import sys
import tempfile
import zipfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bt  # noqa: E402

import bpy  # noqa: E402

# Runtimes every Linux that runs Blender has (glibc, libstdc++, libgcc_s).
SYSTEM = ("linux-vdso.so", "libc.so", "libm.so", "libdl.so", "libpthread.so", "librt.so", "libstdc++.so",
          "libgcc_s.so", "ld-linux")

CHILD = r'''
import json, sys
import bpy
out = {"version": list(bpy.app.version)}
if KIND == "extension":
    out["install"] = sorted(bpy.ops.extensions.package_install_files(filepath=ZIP, repo="user_default",
                                                                      enable_on_install=True))
    name = "bl_ext.user_default.banyan"
else:
    out["install"] = sorted(bpy.ops.preferences.addon_install(filepath=ZIP))
    bpy.ops.preferences.addon_enable(module="banyan")
    name = "banyan"
out["enabled"] = name in bpy.context.preferences.addons
pkg = sys.modules[name]
out["package"] = pkg.__file__
out["load_error"] = sys.modules[name + ".ui.state"].LOAD_ERROR
out["library"] = sys.modules[name + ".core.lib"].load().banyan_path
def maps():
    return sorted({ln.split()[-1] for ln in open("/proc/self/maps") if ".so" in ln.rsplit("/", 1)[-1]})
out["maps_start"] = maps()
n = len(bpy.data.objects)
out["roots"] = sorted(bpy.ops.mesh.banyan_roots())  # a fused surface: loads the OpenVDB module
out["objects"] = len(bpy.data.objects) - n
out["maps"] = maps()
# A script's `import banyan`, whatever the package is called: the same modules, a recorded plant.
import banyan
import banyan.api
import banyan.engine.lod  # not loaded yet by the add-on itself
out["alias"] = [banyan is pkg, banyan.api is sys.modules[name + ".api"], banyan.engine.lod is sys.modules[name + ".engine.lod"]]
tree = banyan.api.keyaki_tree(levels=6)[0]
out["api_plant"] = tree.banyan_plant.generator
out["api_lods"] = len(banyan.api.make_lods(tree, ratios=(0.5,), billboard=False))
bpy.ops.preferences.addon_disable(module=name)
out["after_disable"] = [n for n in sys.modules if n == "banyan" or n.startswith("banyan.")
                        if sys.modules[n].__name__ != n]
print("PACKAGE " + json.dumps(out))
'''


def zip_dir():
    return os.environ.get("BANYAN_ZIP_DIR") or os.environ.get("BANYAN_BUILD_DIR") or os.path.join(bt.SOURCE_DIR,
                                                                                                   "build")


def check_ldd(kind, zip_path):
    """Every library in the zip's lib/ resolves inside the unpacked folder
    or to a system runtime; nothing is 'not found'."""
    with tempfile.TemporaryDirectory() as d:
        zipfile.ZipFile(zip_path).extractall(d)
        lib = os.path.join(d, "banyan", "lib") if kind == "legacy" else os.path.join(d, "lib")
        sos = sorted(f for f in os.listdir(lib) if ".so" in f)
        bt.check("libbanyan.so" in sos and len(sos) >= 2, "%s: lib/ holds libbanyan.so and its libraries: %s"
                 % (kind, sos))
        with open(os.path.join(lib, "bundled.txt")) as f:
            bundled = f.read().split()
        bt.check(sorted(bundled + ["libbanyan.so", "libbanyan_vdb.so"]) == sos,
                 "%s: lib/ holds libbanyan.so, its OpenVDB module and what bundled.txt lists" % kind)
        env = {k: v for k, v in os.environ.items() if k != "LD_LIBRARY_PATH"}
        for so in sos:
            r = subprocess.run(["ldd", os.path.join(lib, so)], capture_output=True, text=True, env=env)
            outside = []
            for ln in r.stdout.splitlines():
                parts = ln.split()
                if not parts or parts[0].startswith(SYSTEM):
                    continue
                if "not found" in ln:
                    outside.append(parts[0] + " not found")
                elif "=>" in parts and not os.path.realpath(parts[2]).startswith(os.path.realpath(lib) + os.sep):
                    outside.append("%s => %s" % (parts[0], parts[2]))
            bt.check(r.returncode == 0 and not outside, "%s: ldd %s resolves only inside the package: %s"
                     % (kind, so, outside or r.stderr.strip()))
        return bundled


def check_install(kind, zip_path, bundled):
    with tempfile.TemporaryDirectory() as user:
        script = os.path.join(user, "pkg.py")
        with open(script, "w") as f:
            f.write("ZIP = %r\nKIND = %r\n" % (zip_path, kind) + CHILD)
        env = {k: v for k, v in os.environ.items()
               if not k.startswith(("BANYAN_", "BLENDER_")) and k != "LD_LIBRARY_PATH"}
        env["BLENDER_USER_SCRIPTS"] = os.path.join(user, "scripts")
        env["BLENDER_USER_EXTENSIONS"] = os.path.join(user, "extensions")
        env["BLENDER_USER_CONFIG"] = os.path.join(user, "config")
        r = subprocess.run([bt.BLENDER, "-b", "--factory-startup", "--python-exit-code", "1", "--python", script],
                           capture_output=True, text=True, timeout=300, env=env, cwd=user)
        lines = [ln for ln in r.stdout.splitlines() if ln.startswith("PACKAGE ")]
        if not bt.check(r.returncode == 0 and lines, "%s: child Blender installed the package (exit %d): %s"
                        % (kind, r.returncode, (r.stdout + r.stderr)[-1500:])):
            return
        out = json.loads(lines[-1].split(" ", 1)[1])
        root = os.path.realpath(os.path.join(user, "extensions", "user_default", "banyan") if kind == "extension"
                                else os.path.join(user, "scripts", "addons", "banyan"))
        print("%s:" % kind, json.dumps({k: v for k, v in out.items() if not k.startswith("maps")}))
        bt.check(out["install"] == ["FINISHED"] and out["enabled"], "%s: installed and enabled: %s"
                 % (kind, out["install"]))
        bt.check(os.path.realpath(out["package"]).startswith(root + os.sep), "%s: package from the install: %s"
                 % (kind, out["package"]))
        bt.check(out["load_error"] == "", "%s: library loaded: %s" % (kind, out["load_error"]))
        bt.check(os.path.realpath(out["library"]) == os.path.join(root, "lib", "libbanyan.so"),
                 "%s: the package's own library: %s" % (kind, out["library"]))
        maps = [os.path.realpath(m) for m in out["maps"]]
        module = os.path.join(root, "lib", "libbanyan_vdb.so")
        bt.check(module not in [os.path.realpath(m) for m in out["maps_start"]] and module in maps,
                 "%s: the OpenVDB module loaded from the package when fused roots were meshed, not at start" % kind)
        for name in bundled:
            mine = os.path.join(root, "lib", name)
            # A soname Blender loaded first (4.5+ ships libtbb.so.12) is used as it is: one runtime per process.
            # (realpath: Debian's /usr/lib/.../libembree3.so.3.13.5 for the soname libembree3.so.3).
            theirs = [m for m in maps if m != mine and (os.path.basename(m) + ".").startswith(name + ".")]
            bt.check(mine in maps or theirs, "%s: %s loaded from the package (or Blender's own)" % (kind, name))
        for tree in (os.environ.get("BANYAN_BUILD_DIR"), bt.SOURCE_DIR):
            if tree:
                tree = os.path.realpath(tree) + os.sep
                bad = [m for m in maps if m.startswith(tree)]
                bt.check(not bad, "%s: nothing loaded from %s: %s" % (kind, tree, bad))
        bt.check(out["roots"] == ["FINISHED"] and out["objects"] == 1, "%s: roots around the cube: %s, %d object(s)"
                 % (kind, out["roots"], out["objects"]))
        bt.check(out["alias"] == [True, True, True], "%s: a script's import banyan, banyan.api, banyan.engine.lod are the "
                 "add-on's own modules: %s" % (kind, out["alias"]))
        bt.check(out["api_plant"] == "keyaki" and out["api_lods"] == 2, "%s: banyan.api.keyaki_tree from a script: a "
                 "recorded plant (%r), make_lods on it: %d object(s)" % (kind, out["api_plant"], out["api_lods"]))
        bt.check(out["after_disable"] == [], "%s: disabled, no alias of banyan is left: %s"
                 % (kind, out["after_disable"]))


def test_package(kind, name):
    zip_path = os.path.join(zip_dir(), name)
    if not bt.check(os.path.isfile(zip_path), "%s exists (build the banyan_addon_zip and banyan_extension_zip "
                    "targets)" % zip_path):
        return
    bundled = check_ldd(kind, zip_path)
    check_install(kind, zip_path, bundled)


print("Blender %s" % bpy.app.version_string)
bt.run(lambda: test_package("legacy", "banyan.zip"))
if bpy.app.version >= (4, 2, 0):
    bt.run(lambda: test_package("extension", "banyan_extension.zip"))
else:
    print("SKIP: Blender %s has no extensions (4.2+); the legacy zip is tested" % bpy.app.version_string)
bt.done()
