"""The add-on registers and unregisters cleanly twice in a row, and a
library that cannot load or does not match registers nothing broken."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bt  # noqa: E402

import addon_utils  # noqa: E402
import bpy  # noqa: E402


def has_op(idname):
    mod, name = idname.split(".")
    return hasattr(getattr(bpy.types, "MESH_OT_" + name, None), "bl_idname")


def ops_present():
    import banyan.ui.state as st
    return [i for i, _ in st.operator_entries()]


def test_cycles():
    import banyan
    from banyan.core import lib
    want = os.environ.get("BANYAN_EXPECT_LIB")
    if want:
        bt.check(os.path.realpath(lib.load().banyan_path) == os.path.realpath(want),
                 "library loaded from %s (want %s)" % (lib.load().banyan_path, want))
    bt.check(addon_utils.check("banyan")[1], "add-on loaded by --addons")
    first = ops_present()
    bt.check("mesh.banyan_tube" not in first and has_op("mesh.banyan_tube"),
             "the self-test tube is registered but in no menu: %s" % first)
    bt.check("mesh.banyan_roots" in first, "roots listed")
    for i in first:
        bt.check(has_op(i), "%s registered" % i)
    for cycle in range(2):
        addon_utils.disable("banyan", default_set=True)
        bt.check(not hasattr(bpy.types, "VIEW3D_PT_banyan"), "panel gone after disable %d" % cycle)
        for i in first:
            bt.check(not has_op(i), "%s gone after disable %d" % (i, cycle))
        addon_utils.enable("banyan", default_set=True)
        bt.check(hasattr(bpy.types, "VIEW3D_PT_banyan"), "panel back after enable %d" % cycle)
        bt.check(hasattr(bpy.types, "VIEW3D_MT_banyan_add"), "menu back after enable %d" % cycle)
        bt.check(ops_present() == first, "same operators after enable %d" % cycle)
        for i in first:
            bt.check(has_op(i), "%s back after enable %d" % (i, cycle))
    # The operators work after the cycles.
    n = len(bpy.data.objects)
    bt.check(bpy.ops.mesh.banyan_tube() == {'FINISHED'}, "tube runs after re-register")
    bt.check(len(bpy.data.objects) == n + 1, "tube made one object")


def reload_with(env_lib=None, abi=None):
    """Re-registers with another library path or a faked ABI number."""
    import banyan
    from banyan.core import lib, structs
    addon_utils.disable("banyan", default_set=True)
    old_env, old_abi = os.environ.get("BANYAN_LIB"), structs.ABI_VERSION
    lib._lib = None
    if env_lib is not None:
        os.environ["BANYAN_LIB"] = env_lib
    if abi is not None:
        structs.ABI_VERSION = abi
    try:
        banyan.register()
        import banyan.ui.state as st
        return st.LOAD_ERROR, ops_present(), hasattr(bpy.types, "VIEW3D_PT_banyan_error")
    finally:
        banyan.unregister()
        if old_env is not None:
            os.environ["BANYAN_LIB"] = old_env
        else:
            os.environ.pop("BANYAN_LIB", None)
        structs.ABI_VERSION = old_abi
        lib._lib = None


def test_bad_library():
    err, ops, panel = reload_with(env_lib="/nonexistent/libbanyan.so")
    bt.check("not found" in err and "/nonexistent/libbanyan.so" in err, "missing library named: %r" % err)
    bt.check(ops == [] and not has_op("mesh.banyan_tube"), "no operators without a library")
    bt.check(panel, "an error panel explains it")
    err, ops, panel = reload_with(abi=999)
    bt.check("ABI version" in err and "999" in err, "ABI mismatch message: %r" % err)
    bt.check(ops == [] and not has_op("mesh.banyan_tube"), "no operators with a mismatched library")
    # A struct that changed size is caught too.
    from banyan.core import structs
    saved = structs.SIZED["box"]
    structs.SIZED["box"] = structs.Error
    try:
        err, ops, panel = reload_with()
        bt.check("banyan_box" in err and "does not match" in err, "sizeof mismatch message: %r" % err)
        bt.check(ops == [], "no operators with a size mismatch")
    finally:
        structs.SIZED["box"] = saved
    addon_utils.enable("banyan", default_set=True)
    bt.check(has_op("mesh.banyan_tube"), "the real library registers again")


bt.run(test_cycles)
bt.run(test_bad_library)
bt.done()
