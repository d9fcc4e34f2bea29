"""suite_selftest.sh: an exception escapes the file (no summary line, exit 1)."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import bt  # noqa: E402

bt.check(True, "passes")
raise ValueError("s2_raise: raised on purpose")
