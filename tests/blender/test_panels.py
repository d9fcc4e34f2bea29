"""The operators' redo panels: every table property shows the library's
label (words, no paper symbols) and sits in a group; units are mapped;
draw() runs for every operator through a layout that checks each call
against this Blender's own UILayout functions (both the 4.1+ layout
panels and the older boxes); broken presets are listed with the
library's error; greyed operators say why; with "Update while dragging"
off a change in the redo panel does not regrow the plant until Update."""
import math
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bt  # noqa: E402
import gens  # noqa: E402

import bpy  # noqa: E402
from banyan.ui import live  # noqa: E402
from banyan.ui import panels  # noqa: E402
from banyan.core import presets as PR  # noqa: E402
from banyan.engine import props as PP  # noqa: E402
from banyan.core import params as P  # noqa: E402
from banyan.core import structs as S  # noqa: E402

print("Blender %s" % bpy.app.version_string)


def op_class(gen):
    idname = gens.OPS[gen]
    mod, name = idname.split(".")
    return bpy.types.Operator.bl_rna_get_subclass_py("%s_OT_%s" % (mod.upper(), name))


def available():
    return [g for g in gens.OPS if bt.generator(g)]


# ------------------------------------------------------------ labels, units
WORD = re.compile(r"[A-Za-z][a-z]+|a|A")


def is_words(label):
    """"Branch angle", "Forward pull (min)": every word letters, at least
    two of them (or "a"); "T0", "W geo", "H1 buds" are not."""
    words = re.findall(r"[^\s()/,-]+", label)
    return bool(words) and label[0].isupper() and all(WORD.fullmatch(w) for w in words)


def test_labels_groups_units():
    bt.check(is_words("Branch angle") and not is_words("T0") and not is_words("W geo")
             and not is_words("H1 buds"), "the label rule itself")
    for gen in available():
        cls = op_class(gen)
        rna = gens.op(gen).get_rna_type().properties
        specs = P.specs(gen)
        shown = [n for _, names in panels.sections(gen) for n in names]
        bt.check(sorted(shown) == sorted(cls.table_props) and len(shown) == len(set(shown)),
                 "%s: the sections hold every table property once" % gen)
        titles = [t for t, _ in panels.sections(gen)]
        bt.check(2 <= len(titles) <= 10 and len(set(titles)) == len(titles),
                 "%s: a handful of distinct groups: %s" % (gen, titles))
        labels = []
        for s in specs:
            prop = rna[PP.prop_name(s.name)]
            labels.append(prop.name)
            bt.check(prop.name == s.label and is_words(prop.name),
                     "%s.%s: label '%s' is words an artist knows" % (gen, s.name, prop.name))
            bt.check(bool(s.group), "%s.%s has a group" % (gen, s.name))
            bt.check(s.description[:20].lower() in prop.description.lower(),
                     "%s.%s: the tooltip is the table's description" % (gen, s.name))
            if s.type in (S.PT_DOUBLE, S.PT_VEC3):
                bt.check(s.unit in PP.UNITS, "%s.%s: unit '%s' is mapped in props.UNITS" % (gen, s.name, s.unit))
            if s.type == S.PT_DOUBLE and s.unit == "deg":
                bt.check(prop.subtype == 'ANGLE', "%s.%s: an angle (degrees in the panel)" % (gen, s.name))
                bt.check(math.isclose(prop.soft_max, math.radians(s.max), rel_tol=1e-6),
                         "%s.%s: angle range in radians" % (gen, s.name))
            if s.unit == "m":
                bt.check(prop.unit == 'LENGTH', "%s.%s: a length (scene units)" % (gen, s.name))
            if s.type in (S.PT_DOUBLE, S.PT_INT, S.PT_VEC3):
                bt.check("%g" % s.max in prop.description, "%s.%s: the tooltip gives the range" % (gen, s.name))
        bt.check(len(labels) == len(set(labels)), "%s: labels unique" % gen)
        bt.check(any(rna[k].unit == 'ACCELERATION' for k in cls.table_props) or gen != "ivy",
                 "ivy: gravity is an acceleration")


# ------------------------------------------------------------------- draw()
class FakeLayout:
    """Records what draw() asks for and checks every call against this
    Blender's UILayout: the function must exist with those keywords, a
    prop() must name a property of its data, a setting must be one of
    UILayout's properties."""
    FUNCS = bpy.types.UILayout.bl_rna.functions
    SETTINGS = set(bpy.types.UILayout.bl_rna.properties.keys())

    def __init__(self, log, open_all, with_panels):
        object.__setattr__(self, "_log", log)
        object.__setattr__(self, "_open_all", open_all)
        object.__setattr__(self, "_with_panels", with_panels)

    def __setattr__(self, k, v):
        bt.check(k in self.SETTINGS, "UILayout has no setting '%s'" % k)
        object.__setattr__(self, k, v)

    def __getattr__(self, name):
        if name.startswith("_"):
            raise AttributeError(name)
        if name == "panel" and not self._with_panels:
            raise AttributeError(name)  # Blender before 4.1 as far as draw() can tell
        if name not in self.FUNCS:
            bt.check(False, "UILayout has no function '%s' in Blender %s" % (name, bpy.app.version_string))
            raise AttributeError(name)
        params = set(self.FUNCS[name].parameters.keys())

        def call(*args, **kw):
            bad = set(kw) - params
            bt.check(not bad, "UILayout.%s has no parameter(s) %s" % (name, sorted(bad)))
            for k, v in kw.items():  # enum keywords (icon, ...) must name one of this Blender's items
                p = self.FUNCS[name].parameters.get(k)
                if p is not None and p.type == 'ENUM' and isinstance(v, str):
                    bt.check(v in {i.identifier for i in p.enum_items},
                             "UILayout.%s(%s=%r): not an item in Blender %s" % (name, k, v, bpy.app.version_string))
            self._log.append((name, args, kw))
            if name in ("prop", "prop_enum", "prop_menu_enum"):
                data, prop = args[0], args[1]
                ok = prop in data.bl_rna.properties
                bt.check(ok, "prop(%s, '%s'): no such property" % (type(data).__name__, prop))
                if ok and "index" in kw:
                    bt.check(0 <= kw["index"] < data.bl_rna.properties[prop].array_length,
                             "prop(%s, index=%d) in range" % (prop, kw["index"]))
            if name == "operator":
                bt.check(_op_exists(args[0]), "operator '%s' exists" % args[0])
                return _FakeOpProps()
            if name == "panel":
                kids = (FakeLayout(self._log, self._open_all, True), FakeLayout(self._log, self._open_all, True))
                return kids[0], (kids[1] if self._open_all or not kw.get("default_closed") else None)
            if name in ("row", "column", "box", "split", "column_flow", "grid_flow"):
                return FakeLayout(self._log, self._open_all, self._with_panels)
            return None
        return call


class _FakeOpProps:
    def __setattr__(self, k, v):
        object.__setattr__(self, k, v)


def _op_exists(idname):
    mod, name = idname.split(".")
    return hasattr(getattr(bpy.ops, mod), name)


class FakeOp:
    """What draw() reads from an operator: its class attributes, its
    properties (the last-used ones) and a layout."""

    def __init__(self, cls, layout):
        self.__dict__.update({k: getattr(cls, k) for k in ("generator", "extra_props", "table_props",
                                                          "banyan_idname", "bl_idname")})
        self.properties = bpy.context.window_manager.operator_properties_last(cls.bl_idname)
        self.layout = layout


def drawn_props(log):
    return [c[1][1] for c in log if c[0] == "prop"]


def test_draw():
    wm = bpy.context.window_manager
    bt.check(hasattr(wm, "banyan_sections"), "section state registered on the window manager")
    real_panels = "panel" in FakeLayout.FUNCS
    print("layout.panel in this Blender: %s" % real_panels)
    for gen in available():
        cls = op_class(gen)
        first = set(panels.sections(gen)[0][1])
        rest = set(cls.table_props) - first
        # Each path this Blender can take, and the older one everywhere.
        for with_panels in ([True, False] if real_panels else [False]):
            for open_all in (False, True):
                state = wm.banyan_sections
                vec = getattr(state, gen)
                for i in range(len(vec)):
                    vec[i] = open_all or i == 0
                log = []
                op = FakeOp(cls, FakeLayout(log, open_all, with_panels))
                try:
                    cls.draw(op, bpy.context)
                except Exception as e:
                    bt.check(False, "%s: draw() raised %s: %s" % (gen, type(e).__name__, e))
                    continue
                shown = set(drawn_props(log))
                what = "%s (%s, %s)" % (gen, "layout.panel" if with_panels else "boxes",
                                        "all open" if open_all else "first open")
                bt.check(first <= shown, "%s: the first section is open" % what)
                bt.check((rest <= shown) if open_all else not (rest & shown),
                         "%s: the other sections are %s" % (what, "shown" if open_all else "closed"))
                bt.check("banyan_preset" in shown and live.LIVE in shown, "%s: preset and live rows" % what)
                bt.check(set(cls.extra_props) <= shown, "%s: the operator's options" % what)
                names = [c[0] for c in log]
                bt.check(("panel" in names) == with_panels, "%s: sections drawn the right way" % what)
    # The panel warns before a run would fail: avenue along the active curve without one.
    if "avenue" in available():
        bt.reset_scene()  # the cube is active
        wm = bpy.context.window_manager  # a new one after reading the home file
        cls = op_class("avenue")
        props = wm.operator_properties_last(cls.bl_idname)
        props.path_from = 'CURVE'
        log = []
        cls.draw(FakeOp(cls, FakeLayout(log, False, real_panels)), bpy.context)
        texts = [c[2].get("text", "") for c in log if c[0] == "label"]
        bt.check(any("not a curve" in s for s in texts), "avenue: the panel says the active object is not a curve")
        props.path_from = 'CURSOR'
    # The sidebar panel draws too.
    log = []
    fake = type("P", (), {})()
    fake.layout = FakeLayout(log, True, real_panels)
    try:
        bpy.types.Panel.bl_rna_get_subclass_py("VIEW3D_PT_banyan").draw(fake, bpy.context)
        bt.check(any(c[0] == "operator" for c in log), "sidebar: operator buttons drawn")
    except Exception as e:
        bt.check(False, "sidebar draw() raised %s: %s" % (type(e).__name__, e))


# --------------------------------------------------------------- presets
BROKEN = '{"generator": "ivy", "schema": 1,\n "params": {"steps": 10,\n   "t0": }}\n'


def test_broken_preset():
    if "ivy" not in available():
        return
    d = PR.user_dir(create=True)
    path = os.path.join(d, "ivy_zz_panels_broken.json")
    with open(path, "w") as f:
        f.write(BROKEN)
    try:
        broken = {k: e for k, _, e in PR.broken_presets("ivy")}
        err = broken.get("ivy_zz_panels_broken", "")
        bt.check(err.startswith("ivy_zz_panels_broken.json:3:") and "JSON" in err,
                 "broken preset listed with the library's line and message: %r" % err)
        bt.check("ivy_zz_panels_broken" not in [k for k, _, _ in PR.list_presets("ivy")],
                 "not offered as a good preset")
        from banyan.ops.base import preset_items
        items = {i[0]: i for i in preset_items("ivy")}
        it = items.get("ivy_zz_panels_broken")
        bt.check(it is not None and "(broken: " in it[1] and err in it[1] and it[3] == 'ERROR',
                 "preset menu shows it as broken with its error: %r" % (it,))
        # Choosing it reports the library's error, nothing is built.
        bt.reset_scene()
        n = len(bpy.data.objects)
        try:
            res = gens.op("ivy")(banyan_preset="ivy_zz_panels_broken", steps=20)
            msg = ""
        except RuntimeError as e:
            res, msg = {'CANCELLED'}, str(e)
        bt.check(res == {'CANCELLED'} and "ivy_zz_panels_broken.json:3:" in msg and len(bpy.data.objects) == n,
                 "choosing the broken preset reports its error: %r" % msg)
        # The sidebar lists it.
        log = []
        fake = type("P", (), {})()
        fake.layout = FakeLayout(log, True, False)
        bpy.types.Panel.bl_rna_get_subclass_py("VIEW3D_PT_banyan").draw(fake, bpy.context)
        texts = [c[2].get("text", "") for c in log if c[0] == "label"]
        bt.check("Broken presets" in texts and "ivy_zz_panels_broken" in texts and err in " ".join(texts),
                 "sidebar box lists the broken preset and its error")
    finally:
        os.remove(path)
    bt.check("ivy_zz_panels_broken" not in [k for k, _, _ in PR.broken_presets("ivy")], "gone when removed")


# ------------------------------------------------------------------ poll
def test_poll_message():
    bt.reset_scene()
    for o in bpy.context.selected_objects:
        o.select_set(False)
    for gen in ("roots", "ivy"):
        if gen not in available():
            continue
        bt.check(not gens.op(gen).poll(), "%s: poll fails with nothing selected" % gen)
        try:
            gens.op(gen)()
            msg = ""
        except RuntimeError as e:
            msg = str(e)
        bt.check("Select the objects to grow on" in msg, "%s: poll says why: %r" % (gen, msg))
    if "keyaki" in available():
        bt.check(gens.op("keyaki").poll(), "keyaki tree needs no selection")


# --------------------------------------------------------- live update
def redo(idname, **changes):
    """What Blender does for a change in the redo panel: set the values on
    the last operator, undo it and run it again (ED_undo_operator_repeat)."""
    last = bpy.context.window_manager.operators[-1]
    bt.check(last.bl_idname == op_class_from(idname).bl_rna.identifier, "the last operator is %s" % idname)
    for k, v in changes.items():
        setattr(last.properties, k, v)
    # From the 3D view's region, as the panel's redo runs (the bpy module
    # crashes in ED_undo_operator_repeat without an area).
    win = bpy.context.window_manager.windows[0]
    area = next(a for a in win.screen.areas if a.type == 'VIEW_3D')
    region = next(r for r in area.regions if r.type == 'WINDOW')
    with bpy.context.temp_override(window=win, area=area, region=region):
        return bpy.ops.ed.undo_redo()


def op_class_from(idname):
    mod, name = idname.split(".")
    return bpy.types.Operator.bl_rna_get_subclass_py("%s_OT_%s" % (mod.upper(), name))


def test_live_update():
    for gen in ("roots", "keyaki"):
        if gen not in available():
            continue
        idname = gens.OPS[gen]
        cls = op_class(gen)
        bt.check(gens.op(gen).get_rna_type().properties[live.LIVE].default is True, "%s: live update on by default" % gen)
        bt.reset_scene()
        bpy.ops.ed.undo_push(message="start")  # background Blender starts without an undo stack
        runs = lambda: live.RUNS.get(idname, 0)  # noqa: E731
        r0 = runs()
        key = "main_roots" if gen == "roots" else "levels"
        res = gens.op(gen)('EXEC_DEFAULT', True, live_update=False, **{key: 3})
        made = [o.name for o in bpy.context.selected_objects]
        bt.check(res == {'FINISHED'} and runs() == r0 + 1 and made, "%s: the first run grows" % gen)
        verts = sum(len(bpy.data.objects[n].data.vertices) for n in made)
        # Live off: a change keeps the plant as it was, without running the generator.
        res = redo(idname, **{key: 4})
        bt.check(runs() == r0 + 1, "%s: live off, a change does not run the generator" % gen)
        bt.check(all(n in bpy.data.objects for n in made) and
                 sum(len(bpy.data.objects[n].data.vertices) for n in made) == verts,
                 "%s: live off, the plant stays as built (%s)" % (gen, res))
        last = bpy.context.window_manager.operators[-1]
        bt.check(getattr(last.properties, key) == 4, "%s: the panel keeps the new value" % gen)
        # Update regrows once with the values shown, then is off again.
        res = redo(idname, **{live.UPDATE: True})
        bt.check(res == {'FINISHED'} and runs() == r0 + 2, "%s: Update regrows (%s)" % (gen, res))
        bt.check(not bpy.context.window_manager.operators[-1].properties.banyan_update, "%s: Update resets" % gen)
        verts2 = sum(len(o.data.vertices) for o in bpy.context.selected_objects)
        bt.check(verts2 != verts, "%s: the regrown plant has the new value (%d -> %d vertices)" % (gen, verts, verts2))
        # A redo that changes nothing (a section opened on Blender < 4.1) does not regrow either.
        res = redo(idname, **{live.LIVE: True})
        bt.check(runs() == r0 + 2, "%s: turning live on with nothing pending does not regrow" % gen)
        # Live on: every change regrows.
        res = redo(idname, **{key: 3})
        bt.check(res == {'FINISHED'} and runs() == r0 + 3, "%s: live on, a change regrows" % gen)
        verts3 = sum(len(o.data.vertices) for o in bpy.context.selected_objects)
        bt.check(verts3 == verts, "%s: back to the first plant (%d vertices)" % (gen, verts3))
    for gen in ("ivy", "avenue"):
        if gen in available():
            bt.check(gens.op(gen).get_rna_type().properties[live.LIVE].default is False,
                     "%s: live update off by default (slow)" % gen)


for fn in (test_labels_groups_units, test_draw, test_broken_preset, test_poll_message, test_live_update):
    bt.run(fn)
bt.done()
