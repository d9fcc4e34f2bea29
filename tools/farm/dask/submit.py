#!/usr/bin/env python3
"""banyan's batch runner on a Dask cluster: one task per task index, then the merge.

    python3 tools/farm/dask/submit.py (--scheduler tcp://HOST:8786 | --local N) \\
        --addon DIR --seeds A:B --per-task K [--retries 3] [--python python3] \\
        -- --preset P --out DIR [runner args...]

Each task (a future from client.submit, with retries=) runs on a worker
`PYTHON DIR/batch_task.py -- --task-index I --per-task K --seeds A:B
--parent-pid <worker pid> <runner args>` as a child process (an argument
list, no shell, same session). The entry exits when the worker that
started it dies (prctl PR_SET_PDEATHSIG on Linux, a parent watchdog
elsewhere: batch_task.py), so a killed worker leaves no runner writing
while the scheduler runs its task again elsewhere. A worker killed
mid-task is a worker failure, not a task exception: the scheduler reruns
the task up to `distributed.scheduler.allowed-failures` times (set to
--retries for --local; a running scheduler uses its own setting);
retries= covers a runner that exits 1 (a seed failed). Exit 2 (bad
arguments) is not retried. When every task is done, the merge
(`batch_run.py -- --merge-manifest OUT --seeds A:B --verify`) runs here.

--local N starts a LocalCluster of N worker processes (one thread each)
bound to 127.0.0.1, for one machine. The add-on folder, the preset and
--out must be valid paths on every worker (shared storage).

Exit status: 0 done and verified, 2 bad arguments, 1 otherwise.
"""
import argparse
import os
import subprocess
import sys


def run_task(python, addon, index, per_task, seeds, runner_args):
    """On a worker: the entry for one task index, as a child of this worker
    process. Returns (exit status, output tail); raises on a retryable failure."""
    argv = [python, os.path.join(addon, "batch_task.py"), "--", "--task-index", str(index),
            "--per-task", str(per_task), "--seeds", seeds, "--parent-pid", str(os.getpid())] + list(runner_args)
    r = subprocess.run(argv, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                       start_new_session=False)
    tail = r.stdout[-2000:]
    if r.returncode not in (0, 2):
        raise RuntimeError("task %d: runner exit %d\n%s" % (index, r.returncode, tail))
    return r.returncode, tail


def task_count(python, addon, seeds, per_task):
    r = subprocess.run([python, os.path.join(addon, "batch_task.py"), "--", "--task-count", "--seeds", seeds,
                        "--per-task", str(per_task)], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        raise SystemExit(r.stderr.strip() or "batch_task.py --task-count: exit %d" % r.returncode)
    return int(r.stdout.strip())


def _out_of(runner_args):
    for i, a in enumerate(runner_args):
        if a == "--out" and i + 1 < len(runner_args):
            return runner_args[i + 1]
        if a.startswith("--out="):
            return a[len("--out="):]
    return None


def run(client, python, addon, seeds, per_task, runner_args, retries, log=print):
    """Submits the tasks to `client`, waits, merges. Returns the exit status."""
    from dask.distributed import as_completed
    out = _out_of(runner_args)
    if out is None:
        log("submit: error: the runner arguments need --out DIR")
        return 2
    n = task_count(python, addon, seeds, per_task)
    futures = [client.submit(run_task, python, addon, i, per_task, seeds, runner_args,
                             key="banyan-task-%d-%s" % (i, seeds), retries=retries, pure=False)
               for i in range(n)]
    status = 0
    for fut in as_completed(futures):
        try:
            code, tail = fut.result()
        except Exception as e:  # retries and allowed worker failures used up
            log("submit: %s failed: %s" % (fut.key, e))
            status = 1
            continue
        if code:
            log("submit: %s refused (exit %d):\n%s" % (fut.key, code, tail))
            status = max(status, 2)
    if status:
        return status
    r = subprocess.run([python, os.path.join(addon, "batch_run.py"), "--", "--merge-manifest", out, "--seeds", seeds,
                        "--verify"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    log(r.stdout.rstrip())
    return 0 if r.returncode == 0 else 1


def main(argv=None):
    argv = sys.argv[1:] if argv is None else list(argv)
    runner_args = []
    if "--" in argv:
        runner_args = argv[argv.index("--") + 1:]
        argv = argv[:argv.index("--")]
    p = argparse.ArgumentParser(prog="submit.py", description="banyan's batch runner on Dask (docs/batch.md)")
    where = p.add_mutually_exclusive_group(required=True)
    where.add_argument("--scheduler", help="a running Dask scheduler's address")
    where.add_argument("--local", type=int, metavar="N", help="a LocalCluster of N worker processes on 127.0.0.1")
    p.add_argument("--addon", required=True, help="the banyan add-on folder (batch_task.py) as the workers see it")
    p.add_argument("--python", default=sys.executable, help="Python 3 on the workers (default: this one)")
    p.add_argument("--seeds", required=True, help="A:B, half-open")
    p.add_argument("--per-task", required=True, help="K, seeds per task")
    p.add_argument("--retries", type=int, default=3, help="retries per task (default 3)")
    args = p.parse_args(argv)
    if args.retries < 0:
        p.error("--retries %d must be 0 or more" % args.retries)
    if args.local is not None and args.local < 1:
        p.error("--local %d must be at least 1" % args.local)
    # Bad seeds or K: refused by the entry before anything starts.
    r = subprocess.run([args.python, os.path.join(args.addon, "batch_task.py"), "--", "--task-count", "--seeds",
                        args.seeds, "--per-task", args.per_task], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                       text=True)
    if r.returncode != 0:
        print(r.stderr.strip() or "submit: batch_task.py exit %d" % r.returncode, file=sys.stderr)
        return 2
    import dask
    from dask.distributed import Client, LocalCluster
    if args.local is not None:
        dask.config.set({"distributed.scheduler.allowed-failures": args.retries})
        with LocalCluster(n_workers=args.local, threads_per_worker=1, processes=True, host="127.0.0.1",
                          dashboard_address=None) as cluster, Client(cluster) as client:
            print("submit: LocalCluster %s, workers %s" % (cluster.scheduler_address,
                                                           sorted(client.run(os.getpid).values())), flush=True)
            return run(client, args.python, args.addon, args.seeds, args.per_task, runner_args, args.retries,
                       log=lambda m: print(m, flush=True))
    with Client(args.scheduler) as client:
        return run(client, args.python, args.addon, args.seeds, args.per_task, runner_args, args.retries,
                   log=lambda m: print(m, flush=True))


if __name__ == "__main__":
    sys.exit(main())
