"""suite_selftest.sh: crashes Blender (a read of address 0)."""
import ctypes
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import bt  # noqa: E402

bt.check(True, "passes")
print("s7_crash: crashing now", flush=True)
ctypes.string_at(0)
bt.done()
