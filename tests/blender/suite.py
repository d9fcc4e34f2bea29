"""Runs many tests/blender/test_*.py files in ONE Blender (tests/blender/run.sh):

    blender -b --factory-startup --addons banyan --python-exit-code 1 \\
        --python suite.py -- STATUS_FILE OUT_DIR test_a.py test_b.py ...

A Blender start costs seconds (more for the bpy wheels), so run.sh hands
every file that does not need a Blender of its own (SEPARATE below) to one
driver. For each file in turn it:
  - from the second file on, disables the add-on, drops every module of
    the add-on and of the tests' helpers (gens, prod_util, docs/, tests/bench/)
    from sys.modules, reads the factory start-up file and enables the
    add-on again: the file starts as it would in a Blender of its own (fresh
    module state, factory scene, the add-on's preferences at their
    defaults), only without paying for the start;
  - sends stdout and stderr (Python's and the C side's) to OUT_DIR/<name>.log,
    headed by the Blender version, as run.sh did for a process of its own;
  - runs the file as __main__ with sys.argv as its own Blender would show it;
    bt.done() records `name: N passed, N failed` and ends the file (bt.Done)
    instead of ending the process;
  - restores sys.argv, sys.path, os.environ and the working folder.
STATUS_FILE gets `start NAME MS` before a file and `end NAME RC MS` after it
(RC: the exit code its own Blender would have given, MS: epoch / elapsed
milliseconds), written straight to the file so that a crash leaves every
finished line behind: run.sh reports the file that was running as failed
and starts a new driver for the rest.

`python3 suite.py --separate` prints the names of SEPARATE, one a line
(run.sh reads it)."""
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))

# The files that run in a Blender of their own, and why. Every other
# test_*.py runs in the shared driver (BANYAN_BLENDER_SEPARATE=1 makes
# run.sh start one Blender per file for every file).
SEPARATE = {
    "test_register": "disables, enables and re-registers the add-on, with a library path and ABI it fakes; "
                     "its first check is the state `--addons` left at start-up",
    "test_getting_started": "tests a fresh start-up: a child Blender with empty user folders installs the zip",
    "test_packages": "child Blenders with empty user folders install both packages (packages.sh runs it alone)",
    "test_render": "child Blenders run the docs' example scripts, each a whole Blender start",
}


def _flush():
    sys.stdout.flush()
    sys.stderr.flush()
    try:
        import ctypes
        ctypes.CDLL(None).fflush(None)  # Blender's own printf buffers
    except Exception:  # noqa: BLE001 - nothing else to do
        pass


class _Status:
    def __init__(self, path):
        self.fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_APPEND, 0o644)

    def write(self, line):
        os.write(self.fd, (line + "\n").encode())


def _own(name, source_dir):
    """True for a module a test file or the add-on brought in: the add-on
    (from the repository or an unpacked zip) and anything else from the
    repository's tests/, docs/ and blender_addon/ (gens, prod_util,
    tests/bench/blender_handoff, docs/render_scene, ...) but this driver and
    bt."""
    if name == "banyan" or name.startswith("banyan."):
        return True
    if name in ("__main__", "bt", "suite"):
        return False
    f = getattr(sys.modules.get(name), "__file__", None)
    if not f:
        return False
    f = os.path.realpath(f)
    return any(f.startswith(os.path.join(source_dir, d) + os.sep) for d in ("tests", "docs", "blender_addon"))


def _fresh(state):
    """The add-on unregistered and forgotten, the factory scene, the add-on
    enabled again as at start-up."""
    import addon_utils
    import bpy

    def fail(ex):
        raise ex
    addon_utils.disable("banyan", default_set=True)  # also drops its preferences entry (texture size)
    for m in [m for m in list(sys.modules) if _own(m, state["source"])]:
        del sys.modules[m]
    bpy.ops.wm.read_homefile(use_factory_startup=True)
    mod = addon_utils.enable("banyan", default_set=state["entry"], persistent=True, handle_error=fail)
    if mod is None or not hasattr(bpy.types, "VIEW3D_PT_banyan") and not hasattr(bpy.types,
                                                                               "VIEW3D_PT_banyan_error"):
        raise RuntimeError("the add-on did not register again")


def _argv_for(base_argv, path):
    """sys.argv as the file's own Blender would show it: the driver's command
    line with the file in place of suite.py and nothing after `--`."""
    argv = list(base_argv)
    if "--" in argv:
        argv = argv[:argv.index("--")]
    me = os.path.abspath(__file__)
    return [path if (a.endswith(".py") and os.path.abspath(a) == me) else a for a in argv]


def _run_file(path, name, bt):
    import runpy
    bt.NAME = name
    bt._passed = bt._failed = 0
    bt.RESULT = None
    rc = None
    try:
        runpy.run_path(path, run_name="__main__")
    except bt.Done:
        pass
    except SystemExit as e:
        rc = e.code if isinstance(e.code, int) else (0 if e.code is None else 1)
    except KeyboardInterrupt:
        raise
    except BaseException:  # noqa: BLE001 - what --python-exit-code 1 does with it
        import traceback
        traceback.print_exc()
        rc = 1
    if rc is None:
        rc = bt.RESULT if bt.RESULT is not None else 0  # no bt.done(): run.sh sees no summary line
    return rc


def drive(status_path, out_dir, files):
    import bpy
    sys.path.insert(0, HERE)
    import bt
    bt.DRIVER = True
    state = {"source": os.path.realpath(os.path.join(HERE, "..", "..")),
             # `blender --addons` enables without a preferences entry, bpy_blender.py with one.
             "entry": "banyan" in bpy.context.preferences.addons}
    status = _Status(status_path)
    base_argv, base_path, base_env, base_cwd = list(sys.argv), list(sys.path), dict(os.environ), os.getcwd()
    own_out, own_err = os.dup(1), os.dup(2)
    version = "Blender %s" % bpy.app.version_string
    print("%s: %d files in one Blender" % (version, len(files)), flush=True)
    for i, path in enumerate(files):
        name = os.path.splitext(os.path.basename(path))[0]
        if i:
            try:
                _fresh(state)
            except Exception:  # noqa: BLE001 - run.sh runs the rest in a new Blender
                import traceback
                traceback.print_exc()
                _flush()
                os._exit(3)
        status.write("start %s %d" % (name, int(time.time() * 1000)))
        _flush()
        log = os.open(os.path.join(out_dir, name + ".log"), os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)
        os.dup2(log, 1)
        os.dup2(log, 2)
        os.close(log)
        print("%s (tests/blender/suite.py: file %d of %d in this Blender)" % (version, i + 1, len(files)), flush=True)
        sys.argv = _argv_for(base_argv, path)
        t, cpu = time.perf_counter(), time.process_time()
        rc = _run_file(path, name, bt)
        ms = int((time.perf_counter() - t) * 1000)
        cpu = time.process_time() - cpu
        _flush()
        os.dup2(own_out, 1)
        os.dup2(own_err, 2)
        sys.argv = list(base_argv)
        sys.path[:] = base_path
        if dict(os.environ) != base_env:
            os.environ.clear()
            os.environ.update(base_env)
        os.chdir(base_cwd)
        status.write("end %s %d %d" % (name, rc, ms))
        print("%s: exit %d, %.1f s (CPU %.1f s, every thread)" % (name, rc, ms / 1000.0, cpu), flush=True)
    _flush()
    os._exit(0)  # as bt.done() did: no slow (or crashing) teardown of every file's leftovers


def main():
    if sys.argv[1:] == ["--separate"]:
        print("\n".join(sorted(SEPARATE)))
        return
    args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(args) < 3:
        sys.stderr.write("usage: blender -b ... --python suite.py -- STATUS_FILE OUT_DIR test.py...\n")
        sys.exit(2)
    drive(args[0], args[1], [os.path.abspath(a) for a in args[2:]])


if __name__ == "__main__":
    main()
