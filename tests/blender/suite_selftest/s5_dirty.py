"""suite_selftest.sh: leaves everything it can behind (scene, add-on state
and registration, environment, sys.path, sys.argv, working folder); the
next file must not see any of it."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import bt  # noqa: E402

import addon_utils  # noqa: E402
import bpy  # noqa: E402
from banyan.engine import materials  # noqa: E402
from banyan.ops import base  # noqa: E402

bt.check(bpy.ops.mesh.banyan_tube() == {'FINISHED'}, "tube")
bpy.data.objects.new("Leftover", None)
bpy.context.scene.collection.objects.link(bpy.data.objects["Leftover"])
materials.FALLBACK_SIZE = 7
base.LAST_PARAMS["leftover"] = 1
os.environ["BANYAN_SELFTEST_LEFTOVER"] = "1"
sys.path.insert(0, "/nonexistent/leftover")
sys.argv.append("leftover")
os.chdir("/")
addon_utils.disable("banyan", default_set=True)
bt.done()
