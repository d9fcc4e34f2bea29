"""docs/render_scene.py's blank check passes a picture of a plant and
stops a picture without one; every preset has a one-line description,
a committed thumbnail and a row in the generated presets/README.md."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bt  # noqa: E402

sys.path.insert(0, os.path.join(bt.SOURCE_DIR, "docs"))
import render_gallery as RG  # noqa: E402
import render_scene as RS  # noqa: E402


def scene():
    RS.reset()
    roots, boxes = RS.grow("roots", preset="roots_trunk", values={"growth_points": 12})
    hosts = RS.host_objects(boxes)
    RS.plant_materials(roots)
    RS.studio(roots + hosts)
    cam = RS.frame_camera(roots + hosts, RS.VIEWS["roots"], 64, 48)
    return roots, cam


def test_check():
    roots, cam = scene()
    out = os.path.join(bt.OUT_DIR, "gallery_check.png")
    var, cov = RS.render(out, 64, 48, 2, roots)
    bt.check(var > 2e-4 and cov > 0.003, "plant in view: variance %.5f, coverage %.4f" % (var, cov))
    # The camera turned to look away from the plant: sky and ground only.
    cam.rotation_euler.z += 3.14159
    try:
        RS.render(out, 64, 48, 2, roots)
        bt.check(False, "a picture without the plant must be refused")
    except RS.BlankRender as e:
        bt.check("looks blank" in str(e), "blank picture refused: %s" % e)


def test_gallery_current():
    rows = RG.presets()
    bt.check(len(rows) >= 22, "%d presets" % len(rows))
    with open(RG.README, encoding="utf-8") as f:
        readme = f.read()
    for name, gen, desc in rows:
        bt.check(desc and "\n" not in desc, "%s: a one-line description" % name)
        bt.check(os.path.isfile(os.path.join(RG.IMG, name + ".png")), "%s: thumbnail docs/img/presets/%s.png "
                 "(run docs/render_gallery.py)" % (name, name))
        bt.check("[`%s`](%s.json) | %s |" % (name, name, gen) in readme, "%s: row in presets/README.md" % name)


if bt.generator("roots"):
    bt.run(test_check)
bt.run(test_gallery_current)
bt.done()
