"""Progress and cancel through the binding (core.generators roots / ivy /
keyaki / avenue, progress=), and ivy's "cannot grow" flag (docs/api.md,
docs/ivy.md):
  - progress(done) sees a fraction that never decreases and ends at 1.0,
    and the mesh is the one grown without a callback;
  - returning True raises core.errors.Cancelled (a BanyanError, status 15)
    and nothing is made; an exception raised in the callback cancels and
    comes back out unchanged; a callback run from a worker thread works;
  - Blender's default cube lifted onto the ground, ivy started at the
    origin (its bottom face) grows a plant, also through banyan.api; a
    start boxed in grows nothing and says so in stats["warning"]."""
import os
import sys
import threading

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bt  # noqa: E402

import bpy  # noqa: E402

from banyan.core import BanyanError, Cancelled, structs as S  # noqa: E402
from banyan.core import generators as G  # noqa: E402
from banyan.core.params import Params  # noqa: E402


class Recorder:
    def __init__(self, cancel_at=2.0):
        self.seen = []
        self.cancel_at = cancel_at

    def __call__(self, done):
        self.seen.append(done)
        return done >= self.cancel_at

    def monotone(self):
        return all(b >= a for a, b in zip(self.seen, self.seen[1:]))


def same(a, b):
    return (a.vertex_count == b.vertex_count and a.positions == b.positions and a.indices == b.indices)


def make(gen, progress=None):
    if gen == "roots":
        return G.roots(Params("roots"), [S.Box.make((0, 0, 4), (0.4, 0.4, 4))], progress=progress)
    if gen == "ivy":
        p = Params("ivy")
        p.set("steps", 150)
        return G.ivy(p, [S.Box.make((0, 0.1, 1.5), (1.5, 0.1, 1.5))], progress=progress)
    if gen == "keyaki":
        p = Params("keyaki")
        p.set("levels", 12)
        return G.keyaki(p, progress=progress)
    p = Params("avenue")
    p.set("count", 6)
    p.set("placement", "count")
    p.set("threads", 2)
    return G.avenue(p, None, progress=progress)


class Boom(Exception):
    pass


def test_generator(gen):
    plain = make(gen)
    r = Recorder()
    d = make(gen, r)
    bt.check(len(r.seen) >= 2 and r.monotone() and r.seen[-1] == 1.0 and r.seen.count(1.0) == 1,
             "%s: progress monotone, one final 1.0 (%d calls, last %s)" % (gen, len(r.seen), r.seen[-1:]))
    bt.check(len(r.seen) <= 150, "%s: %d progress calls" % (gen, len(r.seen)))
    bt.check(same(plain, d), "%s: same mesh with a progress callback" % gen)

    r = Recorder(0.3)
    try:
        make(gen, r)
        bt.check(False, "%s: returning True did not cancel" % gen)
    except Cancelled as e:
        bt.check(isinstance(e, BanyanError) and e.status == 15 and e.name == "BANYAN_E_CANCELLED",
                 "%s: Cancelled(15): %s %s" % (gen, e.status, e.name))
        bt.check(r.seen[-1] >= 0.3 and r.seen[-1] < 1.0, "%s: stopped at %s" % (gen, r.seen[-1]))

    calls = []

    def boom(done):
        calls.append(done)
        if done > 0.2:
            raise Boom("at %g" % done)
        return False
    try:
        make(gen, boom)
        bt.check(False, "%s: the callback's exception was swallowed" % gen)
    except Boom:
        bt.check(calls[-1] > 0.2 and calls[-1] < 1.0, "%s: the callback's exception cancelled at %s" % (gen, calls[-1]))
    except Exception as e:
        bt.check(False, "%s: %s instead of the callback's exception" % (gen, type(e).__name__))

    try:
        make(gen, progress=0.5)
        bt.check(False, "%s: a number accepted as progress" % gen)
    except TypeError:
        bt.check(True, "")


def test_thread():
    out = {}

    def work():
        try:
            make("ivy", Recorder(0.5))
        except Cancelled as e:
            out["e"] = e
    t = threading.Thread(target=work)
    t.start()
    t.join()
    bt.check(isinstance(out.get("e"), Cancelled), "ivy cancelled from a worker thread: %r" % out)


def test_ivy_start():
    bpy.ops.wm.read_homefile(use_empty=True)
    bpy.ops.mesh.primitive_cube_add(size=2.0, location=(0, 0, 1))
    cube = bpy.context.active_object
    from banyan import api
    stats = {}
    objs = api.ivy(hosts=[cube], start=(0, 0, 0), steps=120, stats=stats)
    nv = len(objs[0].data.vertices)
    bt.check(nv > 5000 and stats.get("cannot_grow") == 0 and stats.get("warning") == "",
             "ivy from the grounded cube's bottom face grows: %d vertices, %s" % (nv, stats.get("warning")))
    stats = {}
    objs = api.ivy(hosts=[cube], start=(0, 0, 0), steps=120, stats=stats, host_shape='BOX')
    bt.check(stats.get("buds", 0) > 100 and not stats.get("cannot_grow"), "the same on its box: %s buds" % stats.get("buds"))
    # A closed 2 cm cavity: no internode fits.
    cave = [S.Box.make(c, h) for c, h in [((0, 0, 0.985), (0.05, 0.05, 0.005)), ((0, 0, 1.015), (0.05, 0.05, 0.005)),
                                          ((-0.015, 0, 1), (0.005, 0.05, 0.05)), ((0.015, 0, 1), (0.005, 0.05, 0.05)),
                                          ((0, -0.015, 1), (0.05, 0.005, 0.05)), ((0, 0.015, 1), (0.05, 0.005, 0.05))]]
    p = Params("ivy")
    p.set("start", (0, 0, 1))
    p.set("steps", 30)
    d = G.ivy(p, cave)
    bt.check(d.stats["cannot_grow"] == S.IVY_BLOCKED and "could not grow" in d.stats["warning"],
             "boxed-in start flagged: %s %s" % (d.stats["cannot_grow"], d.stats["warning"]))


for g in ("roots", "ivy", "keyaki", "avenue"):
    if bt.generator(g):
        bt.run(lambda: test_generator(g))
if bt.generator("ivy"):
    bt.run(test_thread)
    bt.run(test_ivy_start)
bt.done()
