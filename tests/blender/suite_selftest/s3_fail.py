"""suite_selftest.sh: a failed check (exit 1); bt.done() ends the file."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import bt  # noqa: E402

bt.check(False, "fails on purpose")
bt.done()
print("s3_fail: AFTER DONE")  # never printed
