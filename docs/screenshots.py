"""Screenshots of the add-on's UI from a real Blender window, into
docs/img/ui/: Blender runs with a window on a virtual X display (Xvfb,
Mesa's llvmpipe draws it), not headless:

    bash tools/render_docs.sh ui

which runs, in effect,
    xvfb-run -s "-screen 0 1600x1000x24" blender --factory-startup \
        --addons banyan --python docs/screenshots.py

Each shot is a step run from a timer once the window is up (operators
need the window's context): select the host, run an operator as the
menu does (INVOKE_DEFAULT), open its redo panel (F9, screen.redo_last),
save the window (screen.screenshot) and crop the part the docs show.
Cropping uses Blender's image API (no PIL here)."""
import os
import sys

import bpy

REPO = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
OUT = os.path.join(REPO, "docs", "img", "ui")
TMP = os.path.join(OUT, "_window.png")


def ctx():
    win = bpy.context.window_manager.windows[0]
    area = next(a for a in win.screen.areas if a.type == 'VIEW_3D')
    region = next(r for r in area.regions if r.type == 'WINDOW')
    return win, area, region


def override(**kw):
    win, area, region = ctx()
    d = dict(window=win, area=area, region=region, screen=win.screen)
    d.update(kw)
    return bpy.context.temp_override(**d)


def crop(src, dst, x0, y0, w, h):
    """Saves the window screenshot's rectangle (x0, y0 from the top left, in
    pixels) as dst."""
    img = bpy.data.images.load(src)
    W, H = img.size
    x0, y0 = max(0, min(x0, W - 1)), max(0, min(y0, H - 1))
    w, h = min(w, W - x0), min(h, H - y0)
    px = [0.0] * (W * H * 4)
    img.pixels.foreach_get(px)
    out = []
    for row in range(h):  # Blender's rows go bottom-up
        yb = H - 1 - (y0 + h - 1 - row)
        start = (yb * W + x0) * 4
        out.extend(px[start:start + w * 4])
    new = bpy.data.images.new(os.path.basename(dst), w, h)
    new.pixels.foreach_set(out)
    new.filepath_raw = dst
    new.file_format = 'PNG'
    new.save()
    bpy.data.images.remove(new)
    bpy.data.images.remove(img)
    print("screenshot:", dst, "%dx%d" % (w, h), flush=True)


def shoot(name, rect):
    """Saves the window and crops rect from it; rect may be a function of
    the window's screenshot file giving the rectangle."""
    with override():
        bpy.ops.screen.screenshot(filepath=TMP)
    crop(TMP, os.path.join(OUT, name), *(rect(TMP) if callable(rect) else rect))


def popup_rect(src, x, y, margin=6):
    """The rectangle (x0, y0 from the top, w, h) of the popup under window
    pixel (x, y), plus margin: Blender moves a tall popup up to keep it in
    the window, so its place depends on its height. Found in the pixels:
    the popup's background is a flat dark grey (the theme's, under
    --factory-startup), darker than the viewport behind it, and its left
    padding column holds nothing else from top to bottom."""
    img = bpy.data.images.load(src)
    W, H = img.size
    px = [0.0] * (W * H * 4)
    img.pixels.foreach_get(px)
    bpy.data.images.remove(img)

    def grey(u, v):  # v from the top
        return px[((H - 1 - v) * W + u) * 4]
    bg = 0.094  # the popup's background, 24/255
    flat = lambda u, v: abs(grey(u, v) - bg) < 0.01  # noqa: E731
    left = next(u for u in range(max(0, x - 100), min(W - 4, x + 100)) if all(flat(u + k, y) for k in range(4)))
    col = left + 2
    top, bottom = y, y
    while top > 0 and flat(col, top - 1):
        top -= 1
    while bottom < H - 1 and flat(col, bottom + 1):
        bottom += 1
    right = col  # along a row of the top padding, above the title
    while right < W - 1 and flat(right + 1, top + 5):
        right += 1
    x0, y0 = max(0, left - margin), max(0, top - margin)
    return x0, y0, min(W, right + 1 + margin) - x0, min(H, bottom + 1 + margin) - y0


def region_rect(area, rtype):
    """(x, y from the top, w, h) of a region of an area, in window pixels."""
    win = bpy.context.window_manager.windows[0]
    r = next(r for r in area.regions if r.type == rtype)
    return r.x, win.height - (r.y + r.height), r.width, r.height


STEPS = []


def step(delay):
    def deco(fn):
        STEPS.append((delay, fn))
        return fn
    return deco


def click(x, y):
    """A left click at window pixel (x, y from the top left): Blender's
    event simulation (--enable-event-simulate), which the sidebar's tabs
    need (their active tab cannot be set from Python)."""
    win = bpy.context.window_manager.windows[0]
    yy = win.height - y
    win.event_simulate(type='MOUSEMOVE', value='NOTHING', x=x, y=yy)
    win.event_simulate(type='LEFTMOUSE', value='PRESS', x=x, y=yy)
    win.event_simulate(type='LEFTMOUSE', value='RELEASE', x=x, y=yy)


def move(x, y):
    win = bpy.context.window_manager.windows[0]
    win.event_simulate(type='MOUSEMOVE', value='NOTHING', x=x, y=win.height - y)


def select_cube():
    cube = bpy.data.objects["Cube"]
    for o in bpy.context.view_layer.objects:
        o.select_set(o == cube)
    bpy.context.view_layer.objects.active = cube


@step(2.0)
def setup():
    os.makedirs(OUT, exist_ok=True)
    # The cube resting on the ground, the cursor at the origin: on its bottom face.
    bpy.data.objects["Cube"].location.z = 1.0
    bpy.context.scene.cursor.location = (0.0, 0.0, 0.0)
    select_cube()
    move(*POPUP_AT)


# F9 opens the redo panel with its top left near the mouse.
POPUP_AT = (760, 300)


def redo_panel(op, name, view=None):
    def run():
        select_cube()
        with override():
            # undo=True as the UI calls it: registered, so F9 (redo_last) can show it.
            getattr(bpy.ops.mesh, op)('INVOKE_DEFAULT', True)

    def f9():
        move(*POPUP_AT)
        with override():
            bpy.ops.screen.redo_last('INVOKE_DEFAULT')

    def shot():
        x, y = POPUP_AT
        shoot(name, lambda src: popup_rect(src, x, y + 20))
        move(40, 40)  # away: the popup closes

    def viewport():
        for o in bpy.context.selected_objects:  # no selection outline over the plant
            o.select_set(False)
        win, area, region = ctx()
        x, y, w, h = region_rect(area, 'WINDOW')
        shoot(view, (x + w // 2 - 330, y + h // 2 - 230, 660, 420))
    STEPS.extend([(1.0, run), (2.0, f9), (2.0, shot), (1.0, lambda: None)])
    if view:
        STEPS.append((1.0, viewport))


redo_panel("banyan_ivy", "redo_ivy.png", view="ivy_on_grounded_cube.png")
redo_panel("banyan_roots", "redo_roots.png")


@step(1.0)
def sidebar():
    win, area, region = ctx()
    area.spaces.active.show_region_ui = True


@step(1.5)
def sidebar_tab():
    win, area, region = ctx()
    x, y, w, h = region_rect(area, 'UI')
    # The tabs stand at the region's right edge, in order Item, Tool, View, Banyan
    # (about 55 px each at 1x UI scale); the Banyan tab is the 4th.
    click(x + w - 12, y + 30 + 3 * 55)


@step(2.0)
def sidebar_shot():
    win, area, region = ctx()
    shoot("sidebar_plant.png", region_rect(area, 'UI'))


@step(0.5)
def finish():
    if os.path.exists(TMP):
        os.remove(TMP)
    bpy.ops.wm.quit_blender()


def run_steps(i=0):
    def tick():
        delay, fn = STEPS[i]
        try:
            fn()
        except Exception:
            import traceback
            traceback.print_exc()
            os._exit(1)
        if i + 1 < len(STEPS):
            run_steps(i + 1)
        return None
    bpy.app.timers.register(tick, first_interval=STEPS[i][0])


if bpy.app.background:
    sys.exit("docs/screenshots.py needs a window: run it under xvfb-run (tools/render_docs.sh ui)")
run_steps()
