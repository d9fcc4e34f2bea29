"""The headless API with no selection, no active object and the cursor
elsewhere; errors leave the scene unchanged; presets round-trip through
JSON text, a saved user preset and the operator's preset menu."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bt  # noqa: E402
import gens  # noqa: E402

import bpy  # noqa: E402
import banyan.api as B  # noqa: E402
from banyan.core import BanyanError  # noqa: E402
from banyan.core import structs as S  # noqa: E402
from banyan.core.params import Params  # noqa: E402


def bare_scene():
    bt.reset_scene()
    for o in bpy.context.selected_objects:
        o.select_set(False)
    bpy.context.view_layer.objects.active = None
    bpy.context.scene.cursor.location = (50.0, 50.0, 50.0)  # the API must not care


CALLS = {
    "roots": lambda cube: B.strangler_roots(hosts=[cube]),
    "keyaki": lambda cube: B.keyaki_tree(position=(5.0, 0.0, 0.0), levels=12),
    "avenue": lambda cube: B.keyaki_avenue(path=[(0, 10, 0), (20, 10, 0)], spacing=10.0),
    "ivy": lambda cube: B.ivy(hosts=[cube], start=(0.0, -1.05, -0.9), steps=40),
    "segments": lambda cube: B.segment_twigs(),
}


def test_api(gen):
    bare_scene()
    cube = bpy.data.objects["Cube"]
    before = {o.name for o in bpy.data.objects}
    objs = CALLS[gen](cube)
    bt.check(isinstance(objs, list) and objs, "%s: api returns objects" % gen)
    bt.check(all(o.name in bpy.context.scene.objects for o in objs), "%s: objects are in the scene" % gen)
    bt.check({o.name for o in bpy.data.objects} - before == {o.name for o in objs}, "%s: only those objects added" % gen)
    bt.check(all(len(o.data.vertices) > 0 for o in objs), "%s: non-empty meshes" % gen)
    from banyan.engine import plant as PL
    bt.check(all(PL.is_plant(o) and o.banyan_plant.generator == gen for o in objs),
             "%s: recorded as a plant, as an operator's (Regenerate, Make LODs; test_plant.py)" % gen)
    # Where the colour lives in the vertex colours (a white material), the
    # material shows them; elsewhere the material carries the colour.
    # A shared textured material (materials.py) takes it from its image.
    from banyan.engine.materials import is_shared
    for o in objs:
        for m in o.data.materials:
            bsdf = m.node_tree.nodes["Principled BSDF"]
            white = min(bsdf.inputs["Base Color"].default_value[:3]) >= 0.99
            linked = bsdf.inputs["Base Color"].is_linked
            bt.check(linked == (is_shared(m) or (white and bool(o.data.color_attributes))),
                     "%s: material %s base colour linked to vertex colours: %s" % (gen, m.name, linked))
    for o in objs:  # every material slot drawn by some polygon, none beyond the slots
        me = o.data
        used = {p.material_index for p in me.polygons}
        bt.check(used == set(range(len(me.materials))), "%s: %s uses material slots %s of %d" % (
            gen, o.name, sorted(used), len(me.materials)))
    # An error through the API: BanyanError, scene unchanged.
    state = bt.scene_state()
    key, value = gens.bad_double(gen)
    try:
        if gen in ("roots", "ivy"):
            getattr(B, {"roots": "strangler_roots", "ivy": "ivy"}[gen])(hosts=[cube], values={key: value})
        else:
            getattr(B, {"keyaki": "keyaki_tree", "avenue": "keyaki_avenue", "segments": "segment_twigs"}[gen])(
                values={key: value})
        bt.check(False, "%s: %s=%g accepted" % (gen, key, value))
    except BanyanError as e:
        bt.check(e.status == 2 and key in e.message, "%s: range error names %s: %s" % (gen, key, e.message))
    bt.check(bt.scene_state() == state, "%s: scene unchanged after an API error" % gen)
    if gen in ("roots", "ivy"):
        try:
            getattr(B, {"roots": "strangler_roots", "ivy": "ivy"}[gen])(hosts=[])
            bt.check(False, "%s: no hosts accepted" % gen)
        except BanyanError as e:
            bt.check(e.status == 3, "%s: no hosts -> BANYAN_E_NO_HOSTS (%d %s)" % (gen, e.status, e.message))
        bt.check(bt.scene_state() == state, "%s: scene unchanged after no hosts" % gen)


def changed_params(gen):
    """Params with one value of each kind changed from the default."""
    p = Params(gen)
    done = set()
    for s in p.specs:
        if s.type in done or s.name in ("max_vertices",):
            continue
        v = p.get(s.name)
        if s.type == S.PT_DOUBLE and s.max > s.min:
            nv = s.min + (s.max - s.min) * 0.37 if s.max < 1e5 else min(s.max, v + 0.123)
        elif s.type == S.PT_INT and s.max > s.min:
            nv = int(s.min) + 1 if v != int(s.min) + 1 else int(s.min)
        elif s.type == S.PT_BOOL:
            nv = not v
        elif s.type == S.PT_ENUM and len(s.choices) > 1:
            nv = s.choices[1] if v != s.choices[1] else s.choices[0]
        elif s.type == S.PT_SEED:
            nv = 123456789012
        elif s.type == S.PT_VEC3:
            nv = tuple(max(s.min, min(s.max, c + 0.25)) for c in v)
        elif s.type == S.PT_COLOR:
            nv = (0.1, 0.2, 0.3, 1.0)
        else:
            continue
        try:
            p.set(s.name, nv)
            done.add(s.type)
        except BanyanError:
            pass
    return p


def test_preset_roundtrip(gen):
    p = changed_params(gen)
    d = Params(gen).as_dict()
    bt.check(p.as_dict() != d, "%s: values changed for the round trip" % gen)
    text = p.to_preset("round trip")
    q = Params(gen)
    q.apply_preset(text, "roundtrip.json")
    bt.check(q.as_dict() == p.as_dict(), "%s: JSON preset round-trips every value" % gen)
    # A bad preset is refused and leaves the params unchanged.
    r = Params(gen)
    before = r.as_dict()
    try:
        r.apply_preset('{"generator": "%s", "schema": 1, "params": {"no_such_key": 1}}' % gen, "bad.json")
        bt.check(False, "%s: unknown key accepted" % gen)
    except BanyanError as e:
        bt.check("no_such_key" in e.message, "%s: unknown preset key named: %s" % (gen, e.message))
    bt.check(r.as_dict() == before, "%s: params unchanged after a bad preset" % gen)


def test_user_preset(gen):
    """Operator values saved as a user preset, then chosen in the operator's preset menu."""
    bt.reset_scene()
    gens.prepare(gen)
    op = gens.op(gen)
    kw = dict(gens.KWARGS[gen])
    from banyan.core.params import specs
    from banyan.engine import props as PP
    # Change one int parameter to a value different from the default.
    p0 = Params(gen)
    tweak = None
    for s in specs(gen):
        if s.type == S.PT_SEED:
            tweak = (s.name, 7 if p0.get(s.name) != 7 else 8)
            break
    kw[PP.prop_name(tweak[0])] = tweak[1]
    bt.check(op(**kw) == {'FINISHED'}, "%s: ran with %s=%s" % (gen, tweak[0], tweak[1]))
    res = bpy.ops.banyan.preset_save(operator=gens.OPS[gen], name="bt_roundtrip")
    bt.check(res == {'FINISHED'}, "%s: preset saved" % gen)
    from banyan.core import presets as PR
    keys = [k for k, _, _ in PR.list_presets(gen)]
    key = "%s_bt_roundtrip" % gen
    bt.check(key in keys, "%s: saved preset listed: %s" % (gen, keys))
    q = Params(gen)
    path = PR.find(gen, key)
    q.apply_preset(PR.read(path), path)
    bt.check(q.get(tweak[0]) == tweak[1], "%s: saved preset holds %s" % (gen, tweak[0]))
    # Choose it in the operator from defaults: the object equals the first one.
    first = [o for o in bpy.context.selected_objects]
    nv_first = sum(len(o.data.vertices) for o in first)
    bt.reset_scene()
    gens.prepare(gen)
    kw2 = dict(gens.KWARGS[gen])
    kw2["banyan_preset"] = key
    bt.check(op(**kw2) == {'FINISHED'}, "%s: ran with the saved preset" % gen)
    nv = sum(len(o.data.vertices) for o in bpy.context.selected_objects)
    bt.check(nv == nv_first, "%s: preset run gives the same mesh (%d, %d)" % (gen, nv, nv_first))
    from banyan.ops.base import LAST_PARAMS
    bt.check(LAST_PARAMS[gens.OPS[gen]].get(tweak[0]) == tweak[1], "%s: the run used the preset's %s" % (gen, tweak[0]))
    os.remove(path)


def test_shipped_presets(gen):
    """Every presets/<gen>*.json applies through the API."""
    from banyan.core import presets as PR
    for key, path, _ in PR.list_presets(gen):
        p = Params(gen)
        try:
            p.apply_preset(PR.read(path), path)
            bt.check(True, "")
        except BanyanError as e:
            bt.check(False, "%s: shipped preset %s refused: %s" % (gen, key, e.message))


for g in gens.OPS:
    if bt.generator(g):
        bt.run(lambda: test_api(g))
        bt.run(lambda: test_preset_roundtrip(g))
        bt.run(lambda: test_user_preset(g))
        bt.run(lambda: test_shipped_presets(g))
bt.done()
