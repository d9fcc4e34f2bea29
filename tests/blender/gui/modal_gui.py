"""The modal run in a real Blender window (under Xvfb: run_gui.sh): Add
Ivy invoked from the 3D view runs on a worker thread (RUNNING_MODAL),
builds its plant when done; a second, long run gets Esc (simulated,
--enable-event-simulate) and leaves bpy.data exactly as before, with a
"cancelled" report. Prints "modal_gui: N passed, M failed" and quits."""
import time

import bpy
from banyan import api
from banyan.ops import base

S = {"phase": 0, "t": 0.0, "passed": 0, "failed": 0}


def check(cond, what):
    S["passed" if cond else "failed"] += 1
    if not cond:
        print("FAIL: %s" % what, flush=True)


def state():
    return (sorted(o.name for o in bpy.data.objects), sorted(m.name for m in bpy.data.meshes),
            sorted(m.name for m in bpy.data.materials), sorted(c.name for c in bpy.data.collections))


def view3d():
    win = bpy.context.window_manager.windows[0]
    for area in win.screen.areas:
        if area.type == 'VIEW_3D':
            for region in area.regions:
                if region.type == 'WINDOW':
                    return win, area, region
    return win, None, None


def finish():
    print("modal_gui: %d passed, %d failed" % (S["passed"], S["failed"]), flush=True)
    bpy.ops.wm.quit_blender()


def step():
    try:
        return _step()
    except Exception:
        import traceback
        traceback.print_exc()
        check(False, "raised")
        finish()
        return None


def _step():
    win, area, region = view3d()
    if S["phase"] == 0:
        check(area is not None, "a 3D view")
        bpy.data.objects["Cube"].location.z = 1.0
        bpy.context.scene.cursor.location = (0.0, -1.2, 0.6)
        S["before"] = state()
        with bpy.context.temp_override(window=win, area=area, region=region):
            r = bpy.ops.mesh.banyan_ivy('INVOKE_DEFAULT', steps=300)
        check(r == {'RUNNING_MODAL'}, "invoke runs modal (%s)" % r)
        S["phase"], S["t"] = 1, time.time()
        return 0.1
    if S["phase"] == 1:
        new = [n for n in state()[0] if n not in S["before"][0]]
        if not new and time.time() - S["t"] < 120:
            return 0.1
        check(len(new) == 1, "the plant is built when the worker is done (%s)" % new)
        check(bpy.context.view_layer.objects.active is not None and
              bpy.context.view_layer.objects.active.name in new, "the plant is active")
        S["phase"] = 2
        return 0.2
    if S["phase"] == 2:
        S["before"] = state()
        with bpy.context.temp_override(window=win, area=area, region=region):
            r = bpy.ops.mesh.banyan_ivy('INVOKE_DEFAULT', steps=5000, max_buds=10 ** 7)
        check(r == {'RUNNING_MODAL'}, "second invoke runs modal (%s)" % r)
        check(len(base.RUNNING) == 1, "one run in progress")
        S["runner"] = base.RUNNING[0] if base.RUNNING else None
        S["phase"], S["t"] = 3, time.time()
        return 0.5
    if S["phase"] == 3:
        r = S["runner"]
        check(r is not None and not r.finished, "still growing when Esc comes")
        print("modal_gui: %.0f %% done at Esc" % (100 * (r.done if r else 0)), flush=True)
        win.event_simulate(type='ESC', value='PRESS')
        win.event_simulate(type='ESC', value='RELEASE')
        S["phase"], S["esc"], S["esc_mono"] = 4, time.time(), time.monotonic()
        return 0.1
    if S["phase"] == 4:
        if base.RUNNING and time.time() - S["esc"] < 60:
            return 0.1
        r = S["runner"]
        check(not base.RUNNING, "Esc: the modal run ended")
        check(r is not None and r.cancelled and api.is_cancelled(r.error),
              "Esc: the worker stopped on the cancel (%r)" % (r.error if r else None))
        # Three delays: Blender handing Esc to the modal handler (the event loop, slow
        # when llvmpipe redraws a big plant), the worker stopping once cancelled (the
        # library's progress calls), the handler's next timer tick noticing.
        print("modal_gui: cancelled %.2f s after Esc, at %.0f %% (Esc reached the handler after %.2f s, the "
              "worker stopped %.3f s after the cancel)" % (
                  time.time() - S["esc"], 100 * r.done, (r.cancelled_at or 0) - S["esc_mono"],
                  (r.ended_at or 0) - (r.cancelled_at or 0)), flush=True)
        check(r.ended_at is not None and r.cancelled_at is not None and r.ended_at - r.cancelled_at < 1.0,
              "the worker stopped within 1 s of the cancel")
        check(state() == S["before"], "Esc: bpy.data is as before")
        finish()
        return None


bpy.app.timers.register(step, first_interval=2.0)
