"""docs/examples/render_roots.py renders a non-blank PNG headless (Cycles
CPU), for the defaults and for a shipped preset; the scripting guide's
docs/examples/render_avenue.py runs as written (small and quick here)."""
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bt  # noqa: E402

import bpy  # noqa: E402

SCRIPT = os.path.join(bt.SOURCE_DIR, "docs", "examples", "render_roots.py")


def render(preset, name):
    out = os.path.join(bt.OUT_DIR, name)
    if os.path.exists(out):
        os.remove(out)
    cmd = [bt.BLENDER, "-b", "--factory-startup", "--python-exit-code", "1", "--python", SCRIPT, "--",
           "--out", out, "--size", "96", "--samples", "4"]
    if preset:
        cmd += ["--preset", preset]
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    bt.check(r.returncode == 0 and os.path.isfile(out), "render %s: exit %d %s" % (name, r.returncode, r.stderr[-400:]))
    if not os.path.isfile(out):
        return
    img = bpy.data.images.load(out)
    w, h = img.size
    px = list(img.pixels)
    bt.check((w, h) == (96, 96), "%s: 96x96 (%dx%d)" % (name, w, h))
    lum = [0.2126 * px[i] + 0.7152 * px[i + 1] + 0.0722 * px[i + 2] for i in range(0, len(px), 4)]
    mean = sum(lum) / len(lum)
    var = sum((x - mean) ** 2 for x in lum) / len(lum)
    bt.check(0.02 < mean < 0.98, "%s: not black or white (mean %.3f)" % (name, mean))
    bt.check(var > 1e-4, "%s: not flat (variance %.5f)" % (name, var))
    # The roots are in the middle of the frame: many centre pixels differ from
    # the background (the corners' mean). Pixel by pixel, not the mean: under
    # AgX / Filmic the roots' mean can match the backdrop's.
    def at(x, y):
        return lum[y * w + x]
    corner = sum(at(x, y) for x in range(0, 10) for y in range(0, 10)) / 100
    centre = [at(x, y) for x in range(32, 64) for y in range(24, 72)]
    covered = sum(abs(v - corner) > 0.03 for v in centre) / len(centre)
    print("%s: %.0f %% of the centre differs from the background" % (name, 100 * covered))
    bt.check(covered > 0.1, "%s: something in the middle (%.0f %% of the centre differs from the background %.3f)"
             % (name, 100 * covered, corner))


def render_avenue():
    out = os.path.join(bt.OUT_DIR, "render_avenue.png")
    if os.path.exists(out):
        os.remove(out)
    script = os.path.join(bt.SOURCE_DIR, "docs", "examples", "render_avenue.py")
    r = subprocess.run([bt.BLENDER, "-b", "--factory-startup", "--python-exit-code", "1", "--python", script,
                        "--", "--out", out, "--size", "96x54", "--samples", "2"], capture_output=True, text=True,
                       timeout=300)
    # The script's own blank check (render_scene.render) raises on a blank picture.
    bt.check(r.returncode == 0 and os.path.isfile(out) and "render_avenue: 18 trees" in r.stdout,
             "render_avenue.py: exit %d %s" % (r.returncode, (r.stdout + r.stderr)[-600:]))


if bt.generator("avenue"):
    render_avenue()
if bt.generator("roots"):
    render(None, "render_roots_default.png")
    render("roots_trunk", "render_roots_trunk.png")
else:
    bt.check(True, "roots not built (expected)")
bt.done()
