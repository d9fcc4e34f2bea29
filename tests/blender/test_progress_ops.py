"""Long runs: progress reaches 100 %, a cancel (the callback asking at
~30 %) leaves bpy.data as it was, the worker-thread runner and the modal
handler (driven here with fake timer and Esc events: a background
Blender has no window for a real modal run) build on success and add
nothing on a cancel, the host back in Edit Mode; execute() (scripts, the
redo panel) reports progress too; ivy that cannot grow is a warning."""
import os
import sys
import time
from types import SimpleNamespace

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bt  # noqa: E402

import bpy  # noqa: E402
from banyan import api as B  # noqa: E402
from banyan.core import generators as G  # noqa: E402
from banyan.core.params import Params  # noqa: E402
from banyan.core.structs import Box  # noqa: E402
from banyan.ops import base  # noqa: E402
from banyan.ops import ivy as ivy_op  # noqa: E402


def lifted_cube():
    bt.reset_scene()
    cube = bpy.data.objects["Cube"]
    cube.location.z = 1.0
    bpy.context.view_layer.update()
    return cube


def jobs(cube):
    """name -> a function making a fresh job of a long generator."""
    return {
        "ivy": lambda: B.ivy_job(hosts=[cube], start=(0.0, -1.0, 0.3), steps=120),
        "ivy box": lambda: B.ivy_job(hosts=[cube], host_shape='BOX', start=(0.0, -1.0, 0.3), steps=120),
        "roots": lambda: B.strangler_roots_job(hosts=[cube], growth_points=10),
        "avenue": lambda: B.keyaki_avenue_job(path=[(0, 0, 0), (40, 0, 0)], tree__levels=8),
        "keyaki": lambda: B.keyaki_tree_job(levels=10),
    }


class Recorder:
    def __init__(self, cancel_at=None):
        self.values = []
        self.cancel_at = cancel_at

    def __call__(self, done):
        self.values.append(done)
        return self.cancel_at is not None and done >= self.cancel_at


def test_progress_and_cancel():
    cube = lifted_cube()
    for name, make in jobs(cube).items():
        rec = Recorder()
        with make() as job:
            job.compute(rec)
            objs = job.build()
        v = rec.values
        print("progress %s: %d calls (the library's callback when it has one, else 0 and 1)" % (name, len(v)))
        bt.check(len(objs) >= 1, "%s: built" % name)
        bt.check(v and v[-1] == 1.0, "%s: progress reaches 100 %% (%d calls, last %s)" % (name, len(v),
                                                                                         v[-1] if v else None))
        bt.check(all(0.0 <= a <= b <= 1.0 for a, b in zip(v, v[1:])), "%s: progress is monotone in 0..1" % name)
        # Cancelled at ~30 %: an error with status 15, nothing added.
        state = bt.scene_state()
        rec = Recorder(cancel_at=0.3)
        try:
            make().run(rec)
            bt.check(False, "%s: cancel at 30 %% raised nothing" % name)
        except Exception as e:
            bt.check(B.is_cancelled(e), "%s: a cancel raises status 15 (%r)" % (name, e))
        bt.check(bt.scene_state() == state, "%s: cancelled, bpy.data is as before" % name)
        bt.check(rec.values and rec.values[-1] >= 0.3, "%s: the cancel came at %s" % (name, rec.values[-1:]))
    # The API's one-call form takes progress= too.
    state = bt.scene_state()
    try:
        B.ivy(hosts=[cube], start=(0.0, -1.0, 0.3), steps=60, progress=Recorder(cancel_at=0.3))
        bt.check(False, "api.ivy: the cancel raised nothing")
    except Exception as e:
        bt.check(B.is_cancelled(e), "api.ivy: the cancel raises status 15")
    bt.check(bt.scene_state() == state, "api.ivy: cancelled, bpy.data is as before")


def test_runner():
    cube = lifted_cube()
    make = jobs(cube)["ivy"]
    r = base.Runner(make()).start()
    bt.check(r.wait(120), "runner: the worker finished")
    bt.check(r.error is None and r.done == 1.0, "runner: no error, progress 100 %% (%s, %s)" % (r.error, r.done))
    with r.job:
        objs = r.job.build()  # on the main thread
    bt.check(len(objs) == 1 and len(objs[0].data.vertices) > 100, "runner: the plant built on the main thread")
    state = bt.scene_state()
    r = base.Runner(make())
    r.cancel()  # before it starts: the first progress call cancels
    r.start()
    bt.check(r.wait(120), "runner cancelled: the worker finished")
    bt.check(B.is_cancelled(r.error), "runner cancelled: the job raised status 15 (%r)" % r.error)
    r.job.close()
    bt.check(bt.scene_state() == state, "runner cancelled: bpy.data is as before")


class FakeIvyOp(ivy_op.IvyMixin):
    """The ivy operator's methods on a plain object (a background Blender
    cannot run a real modal operator: it has no window)."""
    generator = "ivy"
    banyan_idname = bl_idname = "mesh.banyan_ivy"
    extra_props = ("host_shape", "start_at_cursor", "animate")
    placement_props = ()

    def __init__(self):
        self.reports = []
        self.banyan_preset = base.NO_PRESET
        self.host_shape = 'SURFACE'
        self.start_at_cursor = True
        self.animate = False
        self.uv_map = True
        self._timer = None

    def report(self, kind, message):
        self.reports.append((set(kind), message))


def drive(op, ctx, events=(), limit=60.0):
    """Feeds events, then timer events until the modal handler ends."""
    for ev in events:
        op.modal(ctx, ev)
    t0 = time.time()
    res = {'RUNNING_MODAL'}
    while res == {'RUNNING_MODAL'} and time.time() - t0 < limit:
        time.sleep(0.02)
        res = op.modal(ctx, SimpleNamespace(type='TIMER', value='NOTHING'))
    return res


def start_modal(op, ctx, steps=200):
    """What invoke does after its window check."""
    op._mode = base.leave_edit_mode(ctx)
    params = B.make_params("ivy", steps=steps)
    op._params = params
    op._runner = base.Runner(op.prepare(ctx, params)).start()


def test_modal():
    ctx = bpy.context
    # Success: built on the main thread when the worker is done.
    cube = lifted_cube()
    ctx.scene.cursor.location = (0.0, -1.2, 0.4)
    op = FakeIvyOp()
    start_modal(op, ctx)
    before = {o.name for o in bpy.data.objects}
    res = drive(op, ctx)
    new = [o for o in bpy.data.objects if o.name not in before]
    bt.check(res == {'FINISHED'} and len(new) == 1, "modal: finished with one object (%s)" % res)
    bt.check(any('INFO' in k for k, _ in op.reports), "modal: an info report (%s)" % op.reports)
    bt.check(new and ctx.view_layer.objects.active == new[0], "modal: the plant is active")
    # Esc: nothing added, the host back in Edit Mode.
    cube = lifted_cube()
    ctx.scene.cursor.location = (0.0, -1.2, 0.4)
    bpy.ops.object.mode_set(mode='EDIT')
    state = bt.scene_state()
    op = FakeIvyOp()
    start_modal(op, ctx, steps=450)
    bt.check(cube.mode == 'OBJECT', "modal: Edit Mode left while it grows")
    res = drive(op, ctx, [SimpleNamespace(type='ESC', value='PRESS')])
    bt.check(res == {'CANCELLED'}, "modal Esc: cancelled (%s)" % res)
    bt.check(bt.scene_state() == state, "modal Esc: bpy.data is as before")
    bt.check(cube.mode == 'EDIT', "modal Esc: the host is back in Edit Mode (%s)" % cube.mode)
    bt.check(any("cancelled" in m for _, m in op.reports), "modal Esc: reported (%s)" % op.reports)
    bpy.ops.object.mode_set(mode='OBJECT')
    # Right-click cancels too; view events pass through.
    op = FakeIvyOp()
    start_modal(op, ctx, steps=450)
    bt.check(op.modal(ctx, SimpleNamespace(type='MIDDLEMOUSE', value='PRESS')) == {'PASS_THROUGH'},
             "modal: view navigation passes through")
    bt.check(op.modal(ctx, SimpleNamespace(type='A', value='PRESS')) == {'RUNNING_MODAL'},
             "modal: other keys are held while it grows")
    res = drive(op, ctx, [SimpleNamespace(type='RIGHTMOUSE', value='PRESS')])
    bt.check(res == {'CANCELLED'}, "modal right-click: cancelled (%s)" % res)


def test_execute_progress():
    """execute() (scripts, the redo panel) reports progress up to 100 %."""
    seen = []
    orig = base._sync_progress

    def recording(wm):
        inner = orig(wm)

        def progress(done):
            seen.append(done)
            return inner(done)
        return progress
    base._sync_progress = recording
    try:
        lifted_cube()
        bpy.context.scene.cursor.location = (0.0, -1.2, 0.4)
        res = bpy.ops.mesh.banyan_ivy(steps=80)
        bt.check(res == {'FINISHED'}, "execute: finished")
        bt.check(seen and seen[-1] == 1.0, "execute: progress reaches 100 %% (%d calls)" % len(seen))
        # The redo panel calls execute again: still fine.
        seen.clear()
        res = bpy.ops.mesh.banyan_roots(growth_points=8)
        bt.check(res == {'FINISHED'} and seen and seen[-1] == 1.0, "execute roots: progress reaches 100 %")
    finally:
        base._sync_progress = orig


def test_ivy_cannot_grow():
    """The lifted cube, the cursor at the origin (under its
    bottom face). It grows (the library places the start on a side), or,
    with a library that cannot, a warning and not a success report."""
    ctx = bpy.context
    lifted_cube()
    ctx.scene.cursor.location = (0.0, 0.0, 0.0)
    op = FakeIvyOp()
    params = B.make_params("ivy")
    job = op.prepare(ctx, params)
    job.compute()
    grew = job.info.get("grew")
    nv = len(job.data.positions) // 3
    res = op._finish(ctx, params, job)
    kinds = [k for k, _ in op.reports]
    bt.check(res == {'FINISHED'}, "lifted cube: finished")
    bt.check(grew == (nv > 1000), "lifted cube: 'grew' says what the mesh shows (%s, %d vertices)" % (grew, nv))
    bt.check(any('WARNING' in k for k in kinds) == (not grew), "lifted cube: a warning exactly when it did not "
             "grow (%s)" % op.reports)
    if not grew:
        bt.check(any("could not grow" in m and "3D cursor" in m for _, m in op.reports),
                 "lifted cube: the warning says what to do (%s)" % op.reports)
    bt.check(grew, "lifted cube: the ivy grows from a side (%d vertices)" % nv)
    # The verdict is the library's (banyan_ivy_stats' cannot_grow), read from the mesh's stats.
    bt.check(B.ivy_grew(SimpleNamespace(stats={"cannot_grow": 2})) is False
             and B.ivy_grew(SimpleNamespace(stats={"cannot_grow": 0})) is True,
             "ivy_grew: the library's cannot_grow decides")
    d = G.ivy(Params("ivy"), [Box.make((0, 0, 1), (1, 1, 1))])
    bt.check("cannot_grow" in (d.stats or {}), "the ivy mesh carries the library's verdict (%s)" % sorted(d.stats or {}))


for t in (test_progress_and_cancel, test_runner, test_modal, test_execute_progress, test_ivy_cannot_grow):
    bt.run(t)
bt.done()
