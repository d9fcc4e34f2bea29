"""suite_selftest.sh: an ordinary passing file."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import bt  # noqa: E402

bt.check(True, "passes")
bt.done()
