"""Tiny test helper for tests run inside headless Blender.

    import bt
    bt.check(cond, "what")      # records pass / fail, prints failures
    if bt.generator("roots"): ... # True when the library loads (it has every
                                  # generator); a library that does not is a failure
    bt.done()                   # prints "name: N passed, N failed", exits 1 on failure
                                  # (under suite.py: records the exit code and ends
                                  # the file, raising Done, so the next file runs)
"""
import os
import sys
import traceback

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

NAME = os.path.splitext(os.path.basename(sys.argv[-1]))[0] if sys.argv else "test"
_passed = 0
_failed = 0
# Set by tests/blender/suite.py, which runs many files in one Blender: done()
# then leaves the exit code the file's own Blender would have given in
# RESULT and raises Done instead of ending the process.
DRIVER = False
RESULT = None
SOURCE_DIR = os.environ.get("BANYAN_SOURCE_DIR", os.path.normpath(os.path.join(os.path.dirname(__file__), "..", "..")))
OUT_DIR = os.environ.get("BANYAN_TEST_OUT", "/tmp")
# The command that starts a child Blender: `blender` itself, or for the bpy
# module (which has no binary) the wrapper tests/blender/run_bpy.sh writes.
BLENDER = os.environ.get("BANYAN_BLENDER") or __import__("bpy").app.binary_path


def check(cond, what):
    global _passed, _failed
    if cond:
        _passed += 1
    else:
        _failed += 1
        print("FAIL: %s" % what, flush=True)
    return bool(cond)


def run(fn):
    """Runs a test function; an exception counts as a failure."""
    try:
        fn()
    except Exception:
        traceback.print_exc()
        check(False, "%s raised" % fn.__name__)


def generator(gen):
    from banyan.core import lib, params, structs
    if not check(gen in structs.GENERATORS, "'%s' is a generator" % gen):
        return False
    try:
        lib.load()  # a library that does not load is a failure, never a skip
        params.specs(gen)
    except Exception as e:
        check(False, "library did not load or has no table for '%s': %s" % (gen, e))
        return False
    return True


class Done(BaseException):
    """done() under suite.py: this file is over (a BaseException, so that
    no `except Exception` in a test swallows it)."""


def done():
    global RESULT
    print("%s: %d passed, %d failed" % (NAME, _passed, _failed), flush=True)
    sys.stdout.flush()
    rc = 1 if _failed or not _passed else 0
    if DRIVER:
        RESULT = rc
        raise Done()
    os._exit(rc)


def reset_scene():
    """Factory scene: the default cube (selected, active), camera, light."""
    import bpy
    bpy.ops.wm.read_homefile(use_factory_startup=True)


def scene_state():
    """Names of every object, mesh, material, collection and node group."""
    import bpy
    return (sorted(o.name for o in bpy.data.objects), sorted(m.name for m in bpy.data.meshes),
            sorted(m.name for m in bpy.data.materials), sorted(c.name for c in bpy.data.collections),
            sorted(n.name for n in bpy.data.node_groups))


def run_op(op, **kw):
    """(op(**kw)'s result, the objects it added)."""
    import bpy
    before = {o.name for o in bpy.data.objects}
    res = op(**kw)
    return res, [o for o in bpy.data.objects if o.name not in before]
