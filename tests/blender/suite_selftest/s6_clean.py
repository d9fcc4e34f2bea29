"""suite_selftest.sh: runs after s5_dirty.py and sees none of what it left."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import bt  # noqa: E402

import addon_utils  # noqa: E402
import bpy  # noqa: E402

bt.check(sorted(o.name for o in bpy.data.objects) == ["Camera", "Cube", "Light"],
         "the factory scene: %s" % sorted(o.name for o in bpy.data.objects))
bt.check(addon_utils.check("banyan")[1] and hasattr(bpy.types, "VIEW3D_PT_banyan"), "the add-on enabled again")
from banyan.engine import materials  # noqa: E402
from banyan.core import textures  # noqa: E402
from banyan.ops import base  # noqa: E402
bt.check(materials.FALLBACK_SIZE == textures.DEFAULT_SIZE, "the add-on's modules loaded afresh")
bt.check(not base.LAST_PARAMS, "no operator run yet in this add-on")
bt.check(bpy.ops.mesh.banyan_tube() == {'FINISHED'}, "its operators work")
bt.check("BANYAN_SELFTEST_LEFTOVER" not in os.environ, "the environment restored")
bt.check("/nonexistent/leftover" not in sys.path, "sys.path restored")
bt.check(sys.argv[-1] == os.path.abspath(__file__) and "--" not in sys.argv and "leftover" not in sys.argv,
         "sys.argv as this file's own Blender gives it: %s" % sys.argv)
bt.check(os.getcwd() != "/", "the working folder restored")
bt.done()
