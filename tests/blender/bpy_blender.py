"""`blender -b` for the bpy module: runs, in a Python that has the `bpy`
wheel from PyPI (tools/blender_versions.sh), the subset of Blender's
command line that the tests and the docs' scripts use:

    python bpy_blender.py -b [--factory-startup] [--addons banyan[,..]]
                          [--python-exit-code N] --python SCRIPT [-- ARGS...]

The bpy module has no `blender` binary and no command line of its own:
it starts with the factory scene (the default cube, camera and light) and
no add-on. This reads the factory settings again when asked (so the
user's preferences do not leak in), enables the listed add-ons from
BLENDER_USER_SCRIPTS/addons (as `--addons` does), sets sys.argv to the
command line as Blender would (scripts read their own options after
`--`), and runs SCRIPT as __main__; an exception exits with the
--python-exit-code status. tests/blender/run_bpy.sh writes a `blender`
wrapper around it per Blender, which is also what BANYAN_BLENDER names
for the tests that start a child Blender."""
import os
import runpy
import sys
import traceback


def main(argv):
    script = None
    addons = []
    exit_code = 0
    factory = False
    i = 0
    while i < len(argv):
        a = argv[i]
        if a == "--":
            break
        if a in ("-b", "--background"):
            pass
        elif a == "--factory-startup":
            factory = True
        elif a == "--addons":
            i += 1
            addons += [m for m in argv[i].split(",") if m]
        elif a == "--python-exit-code":
            i += 1
            exit_code = int(argv[i])
        elif a in ("--python", "-P"):
            i += 1
            script = argv[i]
        else:
            sys.stderr.write("bpy_blender.py: unsupported option %s\n" % a)
            return 2
        i += 1
    import bpy
    import addon_utils
    if factory:
        bpy.ops.wm.read_factory_settings(use_empty=False)
    for m in addons:
        if addon_utils.enable(m, default_set=True, handle_error=None) is None:
            sys.stderr.write("bpy_blender.py: add-on %s could not be enabled\n" % m)
    print("Blender %s (bpy module, %s)" % (bpy.app.version_string, sys.executable), flush=True)
    if script is None:
        return 0
    # Blender's sys.argv: the binary, then the whole command line.
    sys.argv = [os.environ.get("BANYAN_BLENDER", sys.argv[0])] + argv
    try:
        runpy.run_path(script, run_name="__main__")
    except SystemExit as e:
        raise
    except BaseException:
        traceback.print_exc()
        sys.stdout.flush()
        sys.stderr.flush()
        return exit_code
    return 0


def _purge_session_temp():
    """Removes Blender's session temp folder (bpy.app.tempdir, named
    "blender_" and six random characters), which Blender purges on a
    normal exit and os._exit skips."""
    bpy = sys.modules.get("bpy")
    d = getattr(getattr(bpy, "app", None), "tempdir", "") if bpy else ""
    if d and os.path.basename(os.path.normpath(d)).startswith("blender_"):
        import shutil
        shutil.rmtree(d, ignore_errors=True)


if __name__ == "__main__":
    try:
        rc = main(sys.argv[1:])
    finally:
        _purge_session_temp()
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(rc)
