"""Instanced avenues: an avenue with `variants` > 0 becomes
one object per variant in "<name> variants" (excluded from the view
layer, one collection per variant) and one collection-instance empty per
tree; the empties stand where the unique avenue's trees stand (their
feet: the trunk's wind pivot) and there are `variants` variants. First
with a synthetic instanced mesh (placement, rotation, scale, bulk speed
of 10,000 empties), then with the library's avenue."""
import math
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bt  # noqa: E402
import prod_util as U  # noqa: E402

import bpy  # noqa: E402
from banyan import api  # noqa: E402
from banyan.engine import build_mesh as BM  # noqa: E402
from banyan.engine import instances as I  # noqa: E402
from banyan.engine import wind as W  # noqa: E402

VARIANTS = 3
PATH = [(0.0, 0.0, 0.0), (60.0, 0.0, 0.0)]


def excluded(coll):
    def find(lc):
        if lc.collection == coll:
            return lc
        for c in lc.children:
            r = find(c)
            if r is not None:
                return r
        return None
    lc = find(bpy.context.view_layer.layer_collection)
    return lc is not None and lc.exclude


def test_synthetic():
    bt.reset_scene()
    c = BM.Created()
    d = U.synthetic_plant()
    d.origin = (1000.0, 0.0, 0.0)
    n = 10000
    d.instances = [(0, (float(i % 100) * 3.0, float(i // 100) * 3.0, 0.0), 0.01 * i, 1.0 + 0.001 * (i % 7))
                   for i in range(n)]
    t = time.monotonic()
    objs = I.build_instanced("Grove", d, bpy.context.scene.collection, c)
    dt = time.monotonic() - t
    print("10,000 instance empties in %.2f s" % dt)
    bt.check(dt < 30.0, "10,000 empties in seconds, not minutes (%.2f s)" % dt)
    variants = [o for o in objs if o.type == 'MESH']
    empties = [o for o in objs if o.type == 'EMPTY']
    bt.check(len(variants) == 1 and len(empties) == n, "one variant object and %d empties" % n)
    e = empties[1234]
    v, tr, rz, s = d.instances[1234]
    bt.check(e.instance_type == 'COLLECTION' and e.instance_collection is not None
             and variants[0].name in e.instance_collection.objects, "an empty instances its variant's collection")
    bt.check(max(abs(e.location[k] - (d.origin[k] + tr[k])) for k in range(3)) < 1e-3
             and math.isclose(e.rotation_euler[2], rz, abs_tol=1e-6) and math.isclose(e.scale[0], s, rel_tol=1e-6),
             "an empty's place: origin + translation, rotation_z, scale")
    vroot = bpy.data.collections.get("Grove variants")
    bt.check(vroot is not None and excluded(vroot), "the variants collection is excluded from the view layer")
    bt.check(bpy.data.collections["Grove"].name in bpy.context.scene.collection.children,
             "the grove's collection is in the scene")
    piv = U.attribute(variants[0].data, W.PIVOT)
    world_pivot = [variants[0].location[k] + piv[k] for k in range(3)]
    bt.check(max(abs(x) for x in world_pivot) < 1e-5,
             "a variant's pivots stay at its foot in the collection's frame: %s" % world_pivot)


def feet(objs):
    """World trunk foot of each unique tree: its level-0 vertices' pivot."""
    out = []
    for o in objs:
        lev = U.attribute(o.data, "wind_level")
        piv = U.attribute(o.data, W.PIVOT)
        i = next(i for i, x in enumerate(lev) if x == 0.0)
        from mathutils import Vector
        out.append(tuple(o.matrix_world @ Vector(piv[3 * i:3 * i + 3])))
    return out


def test_avenue():
    if not bt.generator("avenue"):
        return
    bt.reset_scene()
    unique = api.keyaki_avenue(path=PATH, name="Unique", tree__levels=5, tree__wind=True)
    bpy.context.view_layer.update()
    inst = api.keyaki_avenue(path=PATH, name="Inst", tree__levels=5, tree__wind=True, variants=VARIANTS)
    empties = [o for o in inst if o.type == 'EMPTY']
    variants = [o for o in inst if o.type == 'MESH']
    bt.check(len(variants) == VARIANTS, "%d variant objects (got %d)" % (VARIANTS, len(variants)))
    bt.check(len(empties) == len(unique), "one empty per tree: %d vs %d unique trees" % (len(empties), len(unique)))
    if not empties or not all(W.has_wind(o.data) for o in unique):
        bt.check(False, "the avenue's trees carry wind data (their feet are read from the trunk's pivot)")
        return
    ft = feet(unique)
    worst = 0.0
    for e in empties:
        worst = max(worst, min(math.dist(tuple(e.location), f) for f in ft))
    bt.check(worst < 0.01, "every empty stands on a unique tree's foot (worst %.4g m)" % worst)
    vc = {e.instance_collection.name for e in empties}
    bt.check(len(vc) == VARIANTS, "the empties use the %d variants: %s" % (VARIANTS, sorted(vc)))
    bt.check(excluded(bpy.data.collections["Inst variants"]), "the variants collection is excluded")


for t in (test_synthetic, test_avenue):
    bt.run(t)
bt.done()
