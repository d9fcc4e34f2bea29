"""A glb written by Blender's own glTF exporter from each generated object
passes the Khronos validator (node tests/gltf/validate.mjs)."""
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bt  # noqa: E402

import bpy  # noqa: E402
import banyan.api as B  # noqa: E402

VALIDATE = os.path.join(bt.SOURCE_DIR, "tests", "gltf", "validate.mjs")

MAKERS = {
    "tube": lambda cube: [bpy.ops.mesh.banyan_tube() and bpy.context.active_object],
    "roots": lambda cube: B.strangler_roots(hosts=[cube]),
    "keyaki": lambda cube: B.keyaki_tree(levels=12),
    "avenue": lambda cube: B.keyaki_avenue(path=[(0, 0, 0), (16, 0, 0)], spacing=8.0, merged=True),
    "ivy": lambda cube: B.ivy(hosts=[cube], start=(0.0, -1.05, -0.9), steps=40),
    "segments": lambda cube: B.segment_twigs(),
}


def export_and_validate(name):
    bt.reset_scene()
    cube = bpy.data.objects["Cube"]
    objs = MAKERS[name](cube)
    for o in bpy.context.scene.objects:
        o.select_set(o in objs)
    path = os.path.join(bt.OUT_DIR, "blender_%s.glb" % name)
    if os.path.exists(path):
        os.remove(path)
    res = bpy.ops.export_scene.gltf(filepath=path, export_format='GLB', use_selection=True,
                                    export_attributes=True, export_apply=True)
    bt.check(res == {'FINISHED'} and os.path.getsize(path) > 1000, "%s: exported %s" % (name, path))
    r = subprocess.run(["node", VALIDATE, path], capture_output=True, text=True)
    print(r.stdout.strip())
    bt.check(r.returncode == 0, "%s: Khronos validator passes (%s)" % (name, (r.stdout + r.stderr).strip()[-300:]))


export_and_validate("tube")
for g in ("roots", "keyaki", "avenue", "ivy", "segments"):
    if bt.generator(g):
        bt.run(lambda: export_and_validate(g))
bt.done()
