"""The check tally of the plain-python tests: check() counts and prints
what failed, finish(name) prints "name: N passed, N failed" and exits 1
when a check failed."""
import sys

_tally = {"passed": 0, "failed": 0}


def check(ok, what):
    """Counts one check; prints what failed. Returns ok."""
    _tally["passed" if ok else "failed"] += 1
    if not ok:
        print("FAIL: " + what, flush=True)
    return ok


def finish(name):
    """Prints the tally and exits 1 if a check failed."""
    print("%s: %d passed, %d failed" % (name, _tally["passed"], _tally["failed"]))
    sys.exit(1 if _tally["failed"] else 0)
