"""banyan's scheduler-neutral batch entry: task index -> seed range -> the runner.

    python3 <addon>/banyan/batch_task.py -- --task-index I --per-task K --seeds A:B \\
        [--parent-pid P] [runner args: --preset ... --out DIR ...]
    python3 <addon>/banyan/batch_task.py -- --task-count --per-task K --seeds A:B
    blender -b --factory-startup --python <addon>/banyan/batch_task.py -- ...   (renders)

A scheduler that numbers its tasks 0, 1, 2 ... (a Slurm array, an Open Job
Description task parameter, a Dask future per index) hands each task its
index; task I runs the batch runner (batch_run.py) on seeds
A + I*K .. min(A + (I+1)*K, B) - 1, half-open like the runner's --seeds.
The runner is imported and its main() called with an argument list, in
this process: the runner arguments pass through untouched (--seeds is this
entry's). --task-count prints ceil((B-A)/K), the number of tasks.

A, B, K and I are decimal digits only (0 <= A < B <= 2^32, K >= 1,
0 <= I < the task count); anything else exits 2 naming the argument.

--parent-pid P: the process that started this one (a Dask worker). On
Linux the kernel kills this process when its parent thread dies
(prctl PR_SET_PDEATHSIG); on every system a watchdog thread exits when
the parent changes. If P is already gone at start, exit 1 at once. So a
killed worker leaves no runner writing behind it while a retry runs.

Exit status: the runner's (0 done, 1 a seed failed, 2 bad arguments), or
2 for a bad entry argument, 1 when the parent is gone.
"""
import importlib.util
import os
import re
import sys
import threading
import time

OWN = ("--task-index", "--per-task", "--seeds", "--parent-pid")
_DIGITS = re.compile(r"[0-9]+\Z")
SEED_LIMIT = 2 ** 32


class UsageError(Exception):
    pass


def _whole(text, what):
    if text is None or not _DIGITS.match(text):
        raise UsageError("%s '%s' must be a whole number in decimal digits (0-9 only)" % (what, text))
    return int(text)


def parse_args(argv):
    """argv (after '--') -> (own options dict, runner argv list)."""
    own, rest, task_count = {}, [], False
    i = 0
    while i < len(argv):
        a = argv[i]
        name, eq, val = a.partition("=")
        if name in OWN:
            if not eq:
                if i + 1 >= len(argv):
                    raise UsageError("%s needs a value" % name)
                i += 1
                val = argv[i]
            if name in own:
                raise UsageError("%s given twice" % name)
            own[name] = val
        elif a == "--task-count":
            task_count = True
        else:
            rest.append(a)
        i += 1
    return own, rest, task_count


def seed_range(seeds, per_task):
    """'A:B', 'K' -> (A, B, K, task count); UsageError naming the argument."""
    parts = (seeds or "").split(":")
    if seeds is None or len(parts) != 2 or not all(_DIGITS.match(p) for p in parts):
        raise UsageError("--seeds '%s' must look like A:B in decimal digits (half-open: seeds A .. B-1)" % seeds)
    a, b = int(parts[0]), int(parts[1])
    if not (a < b <= SEED_LIMIT):
        raise UsageError("--seeds '%s' must have 0 <= A < B <= %d (half-open: seeds A .. B-1)" % (seeds, SEED_LIMIT))
    k = _whole(per_task, "--per-task")
    if k < 1:
        raise UsageError("--per-task '%s' must be at least 1" % per_task)
    return a, b, k, (b - a + k - 1) // k


def task_seeds(a, b, k, count, index_text):
    i = _whole(index_text, "--task-index")
    if i >= count:
        raise UsageError("--task-index %d must be below the task count %d (seeds %d:%d, %d per task)"
                         % (i, count, a, b, k))
    return a + i * k, min(a + (i + 1) * k, b)


def _die_with_parent(parent):
    """Exit when `parent` is no longer this process's parent (see the module doc)."""
    if sys.platform.startswith("linux"):
        try:
            import ctypes
            import signal
            libc = ctypes.CDLL(None, use_errno=True)
            PR_SET_PDEATHSIG = 1
            libc.prctl(PR_SET_PDEATHSIG, int(signal.SIGKILL), 0, 0, 0)
        except (OSError, AttributeError):
            pass
    if os.getppid() != parent:  # died before prctl took effect
        print("batch_task: parent %d is gone; not starting" % parent, file=sys.stderr, flush=True)
        os._exit(1)

    def watch():
        while True:
            time.sleep(0.5)
            if os.getppid() != parent:
                os._exit(1)
    threading.Thread(target=watch, name="batch_task-parent", daemon=True).start()


def _runner():
    here = os.path.dirname(os.path.abspath(__file__))
    mod = sys.modules.get("_banyan_batch_run")
    if mod is None:
        spec = importlib.util.spec_from_file_location("_banyan_batch_run", os.path.join(here, "batch_run.py"))
        mod = importlib.util.module_from_spec(spec)
        sys.modules["_banyan_batch_run"] = mod
        spec.loader.exec_module(mod)
    return mod


def main(argv=None):
    if argv is None:
        argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else sys.argv[1:]
    elif "--" in argv:
        argv = argv[argv.index("--") + 1:]
    try:
        own, rest, task_count = parse_args(list(argv))
        a, b, k, count = seed_range(own.get("--seeds"), own.get("--per-task"))
        if task_count:
            if "--task-index" in own or rest:
                raise UsageError("--task-count takes --seeds and --per-task only (got %s)"
                                 % " ".join(["--task-index"] * ("--task-index" in own) + rest))
            print(count, flush=True)
            return 0
        lo, hi = task_seeds(a, b, k, count, own.get("--task-index"))
        if "--parent-pid" in own:
            _die_with_parent(_whole(own["--parent-pid"], "--parent-pid"))
    except UsageError as e:
        print("batch_task: error: %s" % e, file=sys.stderr, flush=True)
        return 2
    return _runner().main(rest + ["--seeds", "%d:%d" % (lo, hi)])


def _in_blender():
    try:
        import bpy  # noqa: F401
    except ImportError:
        return False
    return True


if __name__ == "__main__":
    code = main()
    if _in_blender():
        sys.stdout.flush()
        os._exit(code) if code else None  # blender -b --python: a non-zero status needs an explicit exit
    else:
        sys.exit(code)
