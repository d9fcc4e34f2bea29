"""Growth animation by `birth`: the Banyan Growth modifier
shows few vertices at frame_start, every vertex at frame_end (the
evaluated count equal to the mesh's), and counts never fall in between;
for a synthetic plant (the node group alone), then roots, keyaki and an
avenue grown by the library (animate=True, and the operators' Growth
animation). The ivy keeps its birth_step modifier (test_operators,
test_plant)."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bt  # noqa: E402
import gens  # noqa: E402
import prod_util as U  # noqa: E402

import bpy  # noqa: E402
from banyan import api  # noqa: E402
from banyan.engine import build_mesh as BM  # noqa: E402
from banyan.engine import growth_anim as GA  # noqa: E402

F0, F1 = 5, 45


def check_grows(obj, what, f0=F0, f1=F1):
    total = len(obj.data.vertices)
    frames = [f0 - 3, f0] + [f0 + (f1 - f0) * k // 8 for k in range(1, 8)] + [f1, f1 + 5]
    counts = [U.evaluated_count(obj, f) for f in frames]
    bt.check(counts[1] < 0.2 * total, "%s: few vertices at frame_start (%d of %d)" % (what, counts[1], total))
    bt.check(counts[-2] == total and counts[-1] == total, "%s: every vertex at frame_end: %s of %d"
             % (what, counts[-2:], total))
    bt.check(all(a <= b for a, b in zip(counts, counts[1:])), "%s: counts never fall: %s" % (what, counts))
    bt.check(len(set(counts)) >= 4, "%s: it grows in steps, not at once: %s" % (what, counts))
    return counts


def test_synthetic():
    bt.reset_scene()
    c = BM.Created()
    obj = BM.object_from_mesh_data("Synthetic", U.synthetic_plant(), bpy.context.scene.collection, c)
    api.add_growth(obj, frame_start=F0, frame_end=F1)
    bt.check([m.name for m in obj.modifiers] == [GA.MODIFIER], "add_growth adds Banyan Growth")
    check_grows(obj, "synthetic")
    other = BM.object_from_mesh_data("Synthetic2", U.synthetic_plant(), bpy.context.scene.collection, c)
    api.add_growth(other, frame_start=1, frame_end=10)
    groups = [g for g in bpy.data.node_groups if g.get(GA.GROUP_KEY)]
    bt.check(len(groups) == 1, "one growth node group per .blend (frames are modifier inputs)")
    check_grows(other, "synthetic, its own frames", 1, 10)
    check_grows(obj, "synthetic, still its frames")


def test_generators():
    for gen, make in (
            ("roots", lambda: api.strangler_roots(hosts=[bpy.data.objects["Cube"]], growth_points=10, animate=True,
                                                  frame_start=F0, frame_end=F1)),
            ("keyaki", lambda: api.keyaki_tree(levels=6, animate=True, frame_start=F0, frame_end=F1)),
            ("avenue", lambda: api.keyaki_avenue(path=[(0, 0, 0), (25, 0, 0)], animate=True, frame_start=F0,
                                                 frame_end=F1)[:2])):
        if not bt.generator(gen):
            continue
        bt.reset_scene()
        try:
            objs = make()
        except Exception as e:  # noqa: BLE001 - reported as a failure with its reason
            bt.check(False, "%s: animate=True built (%s)" % (gen, e))
            continue
        for o in objs:
            bt.check(GA.MODIFIER in [m.name for m in o.modifiers], "%s: the growth modifier" % gen)
            check_grows(o, "%s '%s'" % (gen, o.name))


def test_operator():
    if not bt.generator("keyaki"):
        return
    bt.reset_scene()
    bpy.context.scene.frame_start, bpy.context.scene.frame_end = F0, F1
    before = {o.name for o in bpy.data.objects}
    try:
        res = gens.op("keyaki")(animate=True, levels=5)
    except RuntimeError as e:
        res = {str(e)}
    objs = [o for o in bpy.data.objects if o.name not in before]
    bt.check(res == {'FINISHED'} and objs and GA.MODIFIER in [m.name for m in objs[0].modifiers],
             "keyaki operator: Growth animation adds the modifier (%s)" % res)
    if res == {'FINISHED'} and objs:
        check_grows(objs[0], "keyaki operator")


for t in (test_synthetic, test_generators, test_operator):
    bt.run(t)
bt.done()
