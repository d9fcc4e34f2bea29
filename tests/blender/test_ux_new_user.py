"""What a new user meets first: one copy of the add-on at a time (a
second copy registers only a panel naming the first); plants the same
size in any scene unit scale; keywords given with a preset win over it;
fields that do nothing in the current mode greyed out (and checked to do
nothing in the library); roots and ivy reaching their hosts' foot, where
the ground is; one preset menu with readable names; the self-test tube in
no menu; sidebar buttons whose labels fit the default sidebar width."""
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bt  # noqa: E402
import gens  # noqa: E402

import addon_utils  # noqa: E402
import bpy  # noqa: E402
import banyan  # noqa: E402
from banyan.ui import panels  # noqa: E402
from banyan.engine import props as PP  # noqa: E402
from banyan.ui import state  # noqa: E402
from banyan.core import params as P  # noqa: E402
from banyan.core import structs as S  # noqa: E402
from banyan.ops import base  # noqa: E402

print("Blender %s" % bpy.app.version_string)


run = bt.run_op


def world_z(objs):
    return [(o.matrix_world @ v.co) for o in objs if o.type == 'MESH' for v in o.data.vertices]


def bounds(objs):
    pts = world_z(objs)
    return [min(p[k] for p in pts) for k in range(3)], [max(p[k] for p in pts) for k in range(3)]


# ------------------------------------------------------------ one copy
def test_second_copy():
    """A second copy of the package under another name (as the legacy zip
    `banyan` beside the extension `bl_ext.user_default.banyan`) refuses to
    register and says why; unregistering either leaves the other whole."""
    pkg = os.path.dirname(os.path.realpath(banyan.__file__))
    with tempfile.TemporaryDirectory() as d:
        os.symlink(pkg, os.path.join(d, "banyan_copy"))
        sys.path.insert(0, d)
        try:
            import banyan_copy
            ops_before = [i for i, _ in state.operator_entries()]
            banyan_copy.register()
            from banyan_copy.ui import state as st2
            from banyan_copy.core import lib as lib2
            bt.check(lib2._lib is None, "the second copy loads no library")
            bt.check(st2.operator_entries() == [], "the second copy registers no operator: %s"
                     % st2.operator_entries())
            bt.check(hasattr(bpy.types, "VIEW3D_PT_banyan_other_copy"), "the second copy shows its panel")
            msg = st2.LOAD_ERROR
            bt.check("'banyan'" in msg and "'banyan_copy'" in msg and "Preferences" in msg,
                     "its message names both copies and where to remove one: %r" % msg)
            panel = bpy.types.VIEW3D_PT_banyan
            bt.check(panel.__module__ == "banyan.ui.sidebar", "the sidebar panel is still the first copy's")
            banyan_copy.unregister()
            bt.check(not hasattr(bpy.types, "VIEW3D_PT_banyan_other_copy"), "its panel goes with it")
            bt.check(hasattr(bpy.types, "VIEW3D_PT_banyan") and [i for i, _ in state.operator_entries()] ==
                     ops_before, "the first copy is whole")
            bt.reset_scene()
            res, objs = run(bpy.ops.mesh.banyan_roots, growth_points=8, main_roots=2)
            bt.check(res == {'FINISHED'} and objs, "the first copy's roots still run")
            # The other way round: the first one disabled, the copy enabled, then the first again.
            addon_utils.disable("banyan", default_set=True)
            banyan_copy.register()
            bt.check(st2.LOAD_ERROR == "" and bpy.types.VIEW3D_PT_banyan.__module__ == "banyan_copy.ui.sidebar",
                     "alone, the copy registers: %r" % st2.LOAD_ERROR)
            try:
                addon_utils.enable("banyan", default_set=True)
                bt.check("'banyan_copy'" in state.LOAD_ERROR and not state.operator_entries(),
                         "then `banyan` refuses: %r" % state.LOAD_ERROR)
                addon_utils.disable("banyan", default_set=True)  # no RuntimeError, the copy untouched
                bt.check(bpy.types.VIEW3D_PT_banyan.__module__ == "banyan_copy.ui.sidebar" and
                         hasattr(bpy.types, "MESH_OT_banyan_roots"), "disabling `banyan` leaves the copy whole")
            finally:
                banyan_copy.unregister()
                addon_utils.enable("banyan", default_set=True)
            bt.check(state.LOAD_ERROR == "" and [i for i, _ in state.operator_entries()] == ops_before,
                     "`banyan` registers again once alone")
        finally:
            sys.path.remove(d)
            for name in [n for n in sys.modules if n == "banyan_copy" or n.startswith("banyan_copy.")]:
                del sys.modules[name]


# --------------------------------------------------------------- units
def centimetres():
    us = bpy.context.scene.unit_settings
    us.system = 'METRIC'
    us.scale_length = 0.01
    us.length_unit = 'CENTIMETERS'


def test_units():
    if not (bt.generator("keyaki") and bt.generator("roots")):
        return
    bt.reset_scene()
    res, objs = run(bpy.ops.mesh.banyan_keyaki_tree, levels=8)
    lo, hi = bounds(objs)
    h_m = hi[2] - lo[2]
    bt.reset_scene()
    centimetres()
    bpy.context.scene.cursor.location = (300.0, 0.0, 0.0)  # 3 m away
    res2, objs2 = run(bpy.ops.mesh.banyan_keyaki_tree, levels=8)
    lo2, hi2 = bounds(objs2)
    h_cm = (hi2[2] - lo2[2]) * 0.01
    bt.check(res == res2 == {'FINISHED'} and h_m > 3 and abs(h_cm - h_m) < 1e-4 * h_m,
             "keyaki: %.3f m tall in a metre scene, %.3f m in a centimetre scene" % (h_m, h_cm))
    bt.check(objs2 and abs(objs2[0].matrix_world.translation.x - 300.0) < 1e-3,
             "keyaki: its foot at the cursor, in centimetres")

    # Roots on a 2 m cube: the same mesh in metres, whatever the units.
    def roots(scale, **kw):
        bt.reset_scene()
        if scale != 1.0:
            centimetres()
            cube = bpy.data.objects["Cube"]
            cube.scale = (100.0, 100.0, 100.0)
            bpy.context.view_layer.update()
        res, objs = run(bpy.ops.mesh.banyan_roots, surface='tubes', growth_points=20, **kw)
        if not objs:
            return res, 0, None
        lo, hi = bounds(objs)
        return res, sum(len(o.data.vertices) for o in objs), [c * scale for c in lo + hi]
    r1, n1, b1 = roots(1.0)
    r2, n2, b2 = roots(0.01)
    bt.check(r1 == r2 == {'FINISHED'} and n1 == n2 and b1 and b2 and max(abs(a - b) for a, b in zip(b1, b2)) < 1e-4,
             "roots: the same %d vertices and bounds in metres in a centimetre scene (%d, %s / %s)"
             % (n1, n2, b1, b2))
    # The defaults (metres) become this scene's units, keeping their metres: Scale 0.05 m is 5 cm.
    props = bpy.context.window_manager.operator_properties_last("mesh.banyan_roots")
    props.banyan_unit_scale, props.unit, props.descent = 0.0, 0.05, 1.0
    fake = type("Op", (), {})()
    fake.properties = props
    fake.length_props = bpy.types.MESH_OT_banyan_roots.length_props
    s = base.BanyanOperatorMixin.to_scene_units(fake, bpy.context, {"descent": 1.0})
    bt.check(s == 0.01 and abs(props.unit - 5.0) < 1e-5 and props.descent == 1.0 and "unit" in fake.length_props,
             "roots: Scale 0.05 m becomes 5 cm (%g), a given value stays (%g)" % (props.unit, props.descent))
    props.banyan_unit_scale = 1.0  # remembered from a metre scene
    props.unit = 0.05
    base.BanyanOperatorMixin.to_scene_units(fake, bpy.context, {})
    bt.check(abs(props.unit - 5.0) < 1e-5, "a value remembered from a metre scene keeps its metres (%g)" % props.unit)
    props.unit, props.descent, props.banyan_unit_scale = 0.05, 1.0, 0.0
    # A length given by a script is in the scene's units, as in Blender's own operators.
    r3, n3, b3 = roots(0.01, unit=5.0)
    bt.check(r3 == {'FINISHED'} and n3 == n2 and b3 == b2, "roots: unit=5.0 in a centimetre scene is 5 cm (%d, %d)"
             % (n3, n2))


def test_api_units():
    """banyan.api as the operators: in a centimetre scene a keyaki is as
    many metres tall and stands at its position in metres, roots on a cube
    of the same metres are the same roots, an avenue along a curve of the
    same metres has the same trees."""
    import banyan.api as B
    if bt.generator("keyaki"):
        def tree(scale):
            bt.reset_scene()
            if scale != 1.0:
                centimetres()
            objs = B.keyaki_tree(position=(3.0, 0.0, 0.0), levels=8)
            bpy.context.view_layer.update()
            lo, hi = bounds(objs)
            return [c * scale for c in lo + hi], objs[0].matrix_world.translation.x * scale
        (b1, x1), (b2, x2) = tree(1.0), tree(0.01)
        h1, h2 = b1[5] - b1[2], b2[5] - b2[2]
        bt.check(h1 > 3 and abs(h2 - h1) < 1e-4 * h1, "api keyaki: %.3f m tall in a metre scene, %.3f m in a "
                 "centimetre scene" % (h1, h2))
        bt.check(abs(x1 - 3.0) < 1e-6 and abs(x2 - 3.0) < 1e-6, "api keyaki: its foot at x = 3 m (%g, %g)" % (x1, x2))
    if bt.generator("roots"):
        def roots(scale, shape):
            bt.reset_scene()
            cube = bpy.data.objects["Cube"]
            if scale != 1.0:
                centimetres()
                cube.scale = (100.0, 100.0, 100.0)
                bpy.context.view_layer.update()
            objs = B.strangler_roots(hosts=[cube], surface='tubes', growth_points=20, host_shape=shape)
            bpy.context.view_layer.update()
            lo, hi = bounds(objs)
            return sum(len(o.data.vertices) for o in objs), [c * scale for c in lo + hi]
        for shape in ('SURFACE', 'BOX'):
            (n1, b1), (n2, b2) = roots(1.0, shape), roots(0.01, shape)
            bt.check(n1 == n2 and max(abs(a - b) for a, b in zip(b1, b2)) < 1e-4 and b1[2] < -0.95,
                     "api roots (%s): the same %d vertices and bounds in metres in a centimetre scene (%d, %s / %s)"
                     % (shape, n1, n2, b1, b2))
    if bt.generator("avenue"):
        def avenue(scale):
            bt.reset_scene()
            if scale != 1.0:
                centimetres()
            cu = bpy.data.curves.new("Road", 'CURVE')
            sp = cu.splines.new('POLY')
            sp.points.add(1)
            sp.points[1].co = (20.0 / scale, 0.0, 0.0, 1.0)
            road = bpy.data.objects.new("Road", cu)
            bpy.context.scene.collection.objects.link(road)
            objs = B.keyaki_avenue(path=road, rows=1, spacing=10.0, tree__levels=5)
            bpy.context.view_layer.update()
            return sorted(round(o.matrix_world.translation.x * scale, 4) for o in objs)
        x1, x2 = avenue(1.0), avenue(0.01)
        bt.check(len(x1) > 1 and x1 == x2, "api avenue on a 20 m curve: trees at the same metres %s / %s" % (x1, x2))


# ------------------------------------------------------------ keywords
def test_keywords_win():
    if not bt.generator("roots"):
        return
    bt.reset_scene()
    res, objs = run(bpy.ops.mesh.banyan_roots, banyan_preset="roots_trunk", sides=4, surface='tubes',
                    growth_points=12)
    p = base.LAST_PARAMS.get("mesh.banyan_roots")
    bt.check(res == {'FINISHED'} and p is not None and p.get("sides") == 4 and p.get("surface") == "tubes",
             "sides=4 given with roots_trunk (sides 12) wins: %s" % (p and p.get("sides")))
    bt.check(p is not None and p.get("seed") == 7 and p.get("hugging"), "the preset's other values apply")
    # A preset newly chosen in the redo panel (a later run) applies whole.
    bt.reset_scene()
    res, objs = run(bpy.ops.mesh.banyan_roots, banyan_preset="roots_trunk", banyan_preset_loaded="NONE", sides=4,
                    surface='tubes', growth_points=12)
    p = base.LAST_PARAMS.get("mesh.banyan_roots")
    bt.check(res == {'FINISHED'} and p.get("sides") == 12, "a preset chosen in the redo panel applies whole")


# ---------------------------------------------------------- idle fields
class Recorder:
    """A layout that records (active, what) for prop() and operator()
    calls, and the rows they are in."""

    def __init__(self, log, active=True, row=None):
        object.__setattr__(self, "_log", log)
        object.__setattr__(self, "_active", active)
        object.__setattr__(self, "_row", row)

    def __setattr__(self, k, v):
        if k == "active":
            object.__setattr__(self, "_active", self._active and v)
        object.__setattr__(self, k, v)

    def _child(self, kind):
        return Recorder(self._log, self._active, [] if kind == "row" else None)

    def row(self, *a, **kw):
        r = self._child("row")
        return r

    def column(self, *a, **kw):
        return self._child("column")

    box = split = grid_flow = column_flow = column

    def panel(self, *a, **kw):
        return self._child("column"), self._child("column")

    def prop(self, data, name, **kw):
        self._log.append(("prop", name, self._active, self._row, kw))

    def operator(self, idname, **kw):
        self._log.append(("operator", idname, self._active, self._row, kw))
        if self._row is not None:
            self._row.append((idname, kw))
        return type("OpProps", (), {})()

    def __getattr__(self, name):
        if name.startswith("_"):
            raise AttributeError(name)
        return lambda *a, **kw: (self._child("column"), self._child("column")) if name == "panel" else None


def other_value(spec, v):
    if spec.type == S.PT_BOOL:
        return not v
    if spec.type == S.PT_INT:
        return v + 2 if v + 2 <= spec.max else v - 2
    if spec.type == S.PT_DOUBLE:
        return v * 1.5 + 0.1 if v * 1.5 + 0.1 <= spec.max else (v + spec.min) / 2
    if spec.type == S.PT_VEC3:
        return tuple(c + 0.3 for c in v)
    if spec.type == S.PT_ENUM:
        return next(c for c in spec.choices if c != v)
    return v


# Values that make each of panels.IDLE's tests true, tried in order.
CANDIDATES = {
    "roots": [{"surface": "fused"}, {"surface": "tubes"}, {"surface": "tubes", "first_branches": False},
              {"surface": "tubes", "second_branches": False}, {"surface": "tubes", "hugging": False},
              {"surface": "tubes", "ground": False}, {"surface": "tubes", "soil_entry": False},
              {"surface": "tubes", "germination_auto": True}],
    "ivy": [{"ground": "none"}],
}


def library_run(gen, values):
    from banyan.core import generators as G
    from banyan.core.structs import Box
    box = Box.make((0.0, 0.0, 1.0), (1.0, 1.0, 1.0), [1, 0, 0, 0, 1, 0, 0, 0, 1])
    p = PP.addon_params(gen)
    base_values = {"roots": {"growth_points": 15, "main_roots": 3},
                   "ivy": {"steps": 40, "start": (0.0, -1.0, 0.6)}}[gen]
    for k, v in dict(base_values, **values).items():
        p.set(k, v)
    d = G.roots(p, [box]) if gen == "roots" else G.ivy(p, [box])
    return d.vertex_count, bytes(memoryview(d.positions).cast("B"))


def test_idle_fields():
    for gen, rules in panels.IDLE.items():
        if not bt.generator(gen):
            continue
        specs = {s.name: s for s in P.specs(gen)}
        for i, (test, keys) in enumerate(rules):
            cond = next((c for c in CANDIDATES[gen] if test(lambda k, c=c: c.get(k, P.Params(gen).get(k)))), None)
            if not bt.check(cond is not None, "%s: rule %d has values to test it with" % (gen, i)):
                continue
            ref = library_run(gen, cond)
            for k in keys:
                w = other_value(specs[k], PP.addon_params(gen).get(k))
                if k == "sides":
                    w = 4
                bt.check(library_run(gen, dict(cond, **{k: w})) == ref,
                         "%s: with %s, %s = %r changes nothing (greyed out)" % (gen, cond, k, w))
    # A control: the same comparison sees a change that matters.
    if bt.generator("roots"):
        bt.check(library_run("roots", {"surface": "tubes", "sides": 4}) != library_run("roots", {"surface": "tubes"}),
                 "roots: the comparison sees Sides with tubes")
    # The redo panel greys them: Surface Fused greys Sides, Tubes does not.
    if not bt.generator("roots"):
        return
    cls = bpy.types.Operator.bl_rna_get_subclass_py("MESH_OT_banyan_roots")
    props = bpy.context.window_manager.operator_properties_last("mesh.banyan_roots")
    for surface, greyed in (("fused", True), ("tubes", False)):
        props.surface = surface
        log = []
        op = type("FakeOp", (), {})()
        for k in ("generator", "extra_props", "table_props", "banyan_idname", "bl_idname"):
            setattr(op, k, getattr(cls, k))
        op.properties, op.layout = props, Recorder(log)
        cls.draw(op, bpy.context)
        rows = {c[1]: c[2] for c in log if c[0] == "prop"}
        bt.check("sides" in rows and rows["sides"] is not greyed and rows.get("fuse_radius") is greyed,
                 "redo panel, Surface %s: Sides %s, Fusing %s" % (surface, "greyed" if greyed else "active",
                                                                   "active" if greyed else "greyed"))
        bt.check(rows.get("ground_z") is False, "redo panel: Ground height greyed while Ground at hosts' foot is on")
    props.surface = "fused"
    # The Plant panel too.
    bt.reset_scene()
    res, objs = run(bpy.ops.mesh.banyan_roots, growth_points=10, main_roots=2)
    if not bt.check(res == {'FINISHED'} and objs, "a roots plant to show"):
        return
    log = []
    fake = type("P", (), {})()
    fake.layout = Recorder(log)
    bpy.types.VIEW3D_PT_banyan_plant.draw(fake, bpy.context)
    rows = {c[1]: c[2] for c in log if c[0] == "prop"}
    bt.check(rows.get("sides") is False and rows.get("fuse_radius") is True,
             "Plant panel of a fused plant: Sides greyed, Fusing active")


# ------------------------------------------------------------ the ground
def test_ground_at_foot():
    if bt.generator("roots"):
        bt.reset_scene()  # the default cube, z from -1 to 1
        res, objs = run(bpy.ops.mesh.banyan_roots)
        pts = world_z(objs)
        low = min(p.z for p in pts) if pts else 0.0
        out = sum(1 for p in pts if p.z < -0.8 and max(abs(p.x), abs(p.y)) > 1.05)
        bt.check(res == {'FINISHED'} and low < -0.95, "roots reach the cube's foot (lowest z %.3f)" % low)
        bt.check(out > 0, "roots spread on the ground at the cube's foot (%d vertices)" % out)
        p = base.LAST_PARAMS["mesh.banyan_roots"]
        bt.check(abs(p.get("ground_z") + 1.0) < 1e-6, "roots: ground_z %g" % p.get("ground_z"))
        bt.reset_scene()
        res, objs = run(bpy.ops.mesh.banyan_roots, ground_at_hosts=False)
        low = min(p.z for p in world_z(objs))
        bt.check(res == {'FINISHED'} and low > -0.5, "without it the ground stays at Ground height 0 (%.3f)" % low)
        bt.reset_scene()
        res, objs = run(bpy.ops.mesh.banyan_roots, ground_z=-0.5)
        p = base.LAST_PARAMS["mesh.banyan_roots"]
        bt.check(res == {'FINISHED'} and p.get("ground_z") == -0.5, "a ground_z keyword wins over the hosts' foot "
                 "(%g)" % p.get("ground_z"))
    if bt.generator("ivy"):
        bt.reset_scene()
        gens.prepare("ivy")
        res, objs = run(bpy.ops.mesh.banyan_ivy, steps=40)
        p = base.LAST_PARAMS["mesh.banyan_ivy"]
        bt.check(res == {'FINISHED'} and abs(p.get("ground_z") + 1.0) < 1e-6, "ivy: the ground at the cube's foot "
                 "(%g)" % p.get("ground_z"))


def test_api_ground():
    """banyan.api puts the ground at its hosts' foot as the operators do,
    unless told not to (ground_at_hosts=False) or given a ground_z."""
    import banyan.api as B
    from banyan.engine import plant as PL
    if bt.generator("roots"):
        bt.reset_scene()  # the default cube, z from -1 to 1
        cube = bpy.data.objects["Cube"]
        objs = B.strangler_roots(hosts=[cube])
        bpy.context.view_layer.update()
        pts = world_z(objs)
        low = min(p.z for p in pts)
        out = sum(1 for p in pts if p.z < -0.8 and max(abs(p.x), abs(p.y)) > 1.05)
        bt.check(low < -0.95 and out > 0, "api roots reach the cube's foot (lowest z %.3f) and spread there (%d)"
                 % (low, out))
        bt.check(abs(PL.stored_params(objs[0]).get("ground_z") + 1.0) < 1e-6, "api roots: ground_z %g recorded"
                 % PL.stored_params(objs[0]).get("ground_z"))
        bt.reset_scene()
        cube = bpy.data.objects["Cube"]
        objs = B.strangler_roots(hosts=[cube], ground_at_hosts=False)
        bpy.context.view_layer.update()
        low = min(p.z for p in world_z(objs))
        bt.check(low > -0.5 and PL.stored_params(objs[0]).get("ground_z") == 0.0,
                 "api roots, ground_at_hosts=False: the ground stays at 0 (lowest z %.3f)" % low)
        for kw in ({"ground_z": -0.5}, {"values": {"ground_z": -0.5}}):
            bt.reset_scene()
            objs = B.strangler_roots(hosts=[bpy.data.objects["Cube"]], growth_points=8, **kw)
            bt.check(PL.stored_params(objs[0]).get("ground_z") == -0.5, "api roots: %s is kept" % kw)
        bt.reset_scene()
        objs = B.strangler_roots(hosts=[bpy.data.objects["Cube"]], growth_points=8, ground_z=-0.5,
                                 ground_at_hosts=True)
        bt.check(abs(PL.stored_params(objs[0]).get("ground_z") + 1.0) < 1e-6, "api roots: ground_at_hosts=True wins")
        # A preset with hosts: its ground as high above the given hosts' foot as above its own hosts'.
        bt.reset_scene()
        lo = B.preset_host_bounds("roots", "roots_trunk")[0][2]
        objs = B.strangler_roots(hosts=[bpy.data.objects["Cube"]], preset="roots_trunk", growth_points=8,
                                 ground_z=lo + 0.25, ground_at_hosts=True)
        bt.check(abs(PL.stored_params(objs[0]).get("ground_z") + 0.75) < 1e-6, "api roots, roots_trunk on the cube: "
                 "the ground 0.25 m above its foot (%g)" % PL.stored_params(objs[0]).get("ground_z"))
        objs = B.strangler_roots(preset="roots_trunk", growth_points=8)
        bt.check(PL.stored_params(objs[0]).get("ground_z") == B.make_params("roots", "roots_trunk").get("ground_z"),
                 "api roots on roots_trunk's own hosts: its own ground")
        bt.reset_scene()
        centimetres()
        cube = bpy.data.objects["Cube"]
        cube.scale = (100.0, 100.0, 100.0)
        bpy.context.view_layer.update()
        objs = B.strangler_roots(hosts=[cube], growth_points=8, host_shape='BOX')
        bt.check(abs(PL.stored_params(objs[0]).get("ground_z") + 1.0) < 1e-6, "api roots in a centimetre scene: "
                 "ground_z %g m" % PL.stored_params(objs[0]).get("ground_z"))
        try:
            B.strangler_roots(hosts=[cube], ground_at_hosts="yes")
            bt.check(False, "ground_at_hosts='yes' accepted")
        except TypeError as e:
            bt.check("ground_at_hosts" in str(e), "ground_at_hosts must be a bool: %s" % e)
    if bt.generator("ivy"):
        bt.reset_scene()
        objs = B.ivy(hosts=[bpy.data.objects["Cube"]], start=(0.0, -1.05, -0.9), steps=40)
        bt.check(abs(PL.stored_params(objs[0]).get("ground_z") + 1.0) < 1e-6, "api ivy: the ground at the cube's "
                 "foot (%g)" % PL.stored_params(objs[0]).get("ground_z"))


# ------------------------------------------------------- menus, labels
def test_menus():
    entries = [i for i, _ in state.operator_entries()]
    bt.check("mesh.banyan_tube" not in entries and "mesh.banyan_roots" in entries,
             "the self-test tube is not among the menu entries: %s" % entries)
    for cls_name in ("VIEW3D_MT_banyan_add", "VIEW3D_PT_banyan"):
        log = []
        fake = type("P", (), {})()
        fake.layout = Recorder(log)
        getattr(bpy.types, cls_name).draw(fake, bpy.context)
        ops = [c[1] for c in log if c[0] == "operator"]
        bt.check(ops and "mesh.banyan_tube" not in ops, "%s: no tube (%s)" % (cls_name, ops))
    bt.reset_scene()
    bt.check(bpy.ops.mesh.banyan_tube() == {'FINISHED'}, "the tube still runs for tests and scripts")
    for gen, idname in gens.OPS.items():
        if not bt.generator(gen):
            continue
        cls = getattr(bpy.types, "MESH_OT_" + idname.split(".")[1])
        bt.check('PRESET' not in cls.bl_options, "%s: no second (Blender operator) preset menu" % idname)
        items = base.preset_items(gen)
        keys = [i[0] for i in items if i[3] != 'ERROR' and i[0] != base.NO_PRESET]
        names = [i[1] for i in items if i[3] != 'ERROR' and i[0] != base.NO_PRESET]
        bt.check(keys and all("_" not in n and n[:1].isupper() for n in names) and len(set(names)) == len(names),
                 "%s: presets under readable names: %s" % (gen, names))
    bt.check(base.PR.title("roots_mature_fig", "roots") == "Mature fig", "a title: %r"
             % base.PR.title("roots_mature_fig", "roots"))


# Blender's sidebar is UI_SIDEBAR_PANEL_WIDTH = 220 px wide at UI scale 1;
# the tab strip and the panel's margins leave its buttons about 184 px; a
# button draws its icon in a 20 px square and pads its text by about 7 px a
# side. Calibrated on what a user saw: "Randomize Seed" with its icon in a
# row of two showed as "Randomi..." (some 55 px of text).
SIDEBAR = 184.0
ICON = 20.0
PAD = 14.0


def text_width(text):
    import blf
    try:
        blf.size(0, 11)
    except TypeError:
        blf.size(0, 11, 72)  # Blender before 4.0
    w = blf.dimensions(0, text)[0]
    return w if w > 0 else 6.5 * len(text)  # no font: an average character of the UI font


def test_labels_fit():
    if not bt.generator("roots"):
        return
    bt.reset_scene()
    res, objs = run(bpy.ops.mesh.banyan_roots, growth_points=10, main_roots=2)
    if not bt.check(res == {'FINISHED'}, "a plant for the Plant panel"):
        return
    for cls_name in ("VIEW3D_PT_banyan_plant", "VIEW3D_PT_banyan"):
        log = []
        fake = type("P", (), {})()
        fake.layout = Recorder(log)
        getattr(bpy.types, cls_name).draw(fake, bpy.context)
        rows = {}
        for c in log:
            if c[0] != "operator":
                continue
            row = c[3]
            n = len(row) if row is not None else 1
            idname, kw = c[1], c[4]
            mod, name = idname.split(".")
            label = kw.get("text")
            if label is None:
                label = getattr(bpy.types, "%s_OT_%s" % (mod.upper(), name)).bl_label
            room = SIDEBAR / n - PAD - (ICON if kw.get("icon") else 0.0)
            w = text_width(label)
            rows[label] = (w, room)
            bt.check(w <= room, "%s: '%s' fits its button (%.0f px of text in %.0f px)" % (cls_name, label, w, room))
        print("%s buttons (text px, room px): %s" % (cls_name, {k: (round(a), round(b)) for k, (a, b) in rows.items()}))


bt.run(test_menus)
bt.run(test_keywords_win)
bt.run(test_idle_fields)
bt.run(test_ground_at_foot)
bt.run(test_labels_fit)
bt.run(test_units)
bt.run(test_api_units)
bt.run(test_api_ground)
bt.run(test_second_copy)
bt.done()
