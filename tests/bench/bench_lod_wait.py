#!/usr/bin/env python3
"""What a user waits for in levels of detail: the CLI's keyaki_mature
written without and with `--lod 0.5,0.15,billboard` (textures off, so
the difference is the levels and their write), in alternating runs; the
LOD's added time (median write time with levels minus median write time
without) over the median generation time, target at most 2x. Wall time
(the levels run on two threads) and, beside it, the CPU time the LOD adds.

Prints markdown table rows `| figure | value | target | met/not met |`
and one line naming the machine and its load.

    python3 tests/bench/bench_lod_wait.py --build build --runs 7 [--against OLD_BUILD]
"""
import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
from machine_info import machine  # noqa: E402

LOD = "0.5,0.15,billboard"


def cpu_children():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def run(cli, preset, out, lod):
    """One CLI run: (generate ms, write ms, CPU s of the process)."""
    cmd = [cli, "keyaki", "--preset", preset, "-o", out, "--textures", "off", "--stats"]
    if lod:
        cmd += ["--lod", LOD]
    c0 = cpu_children()
    p = subprocess.run(cmd, capture_output=True, text=True, check=True)
    cpu = cpu_children() - c0
    stats = None
    for line in (p.stdout + "\n" + p.stderr).splitlines():
        line = line.strip()
        if line.startswith("{") and '"time_ms"' in line:
            stats = json.loads(line)
    if not stats:
        raise SystemExit("no --stats line from: " + " ".join(cmd))
    return stats["time_ms"]["generate"], stats["time_ms"]["write"], cpu


def row(figure, value, target, met):
    """met None: a figure shown beside the targets, with none of its own."""
    status = "—" if met is None else "met" if met else "not met"
    print(f"| {figure} | {value} | {target} | {status} |")


def measure(cli, preset, out, sums):
    """One alternating pair (without, with --lod) into sums."""
    g, w, c = run(cli, preset, out, False)
    sums["gen"].append(g), sums["w_plain"].append(w), sums["cpu_plain"].append(c)
    g, w, c = run(cli, preset, out, True)
    sums["gen"].append(g), sums["w_lod"].append(w), sums["cpu_lod"].append(c)


def figures(sums):
    """(generation ms, LOD's added wall ms, its added CPU ms)."""
    g = statistics.median(sums["gen"])
    added = statistics.median(sums["w_lod"]) - statistics.median(sums["w_plain"])
    added_cpu = 1e3 * (statistics.median(sums["cpu_lod"]) - statistics.median(sums["cpu_plain"]))
    return g, added, added_cpu


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", required=True, help="the build directory (holds the banyan CLI)")
    ap.add_argument("--runs", type=int, default=7, help="runs of each kind, alternating")
    ap.add_argument("--against", help="another build directory (an older banyan), run in the same alternation "
                                      "and shown as its own rows")
    a = ap.parse_args()
    builds = [a.build] + ([a.against] if a.against else [])
    clis = [os.path.join(os.path.abspath(b), "banyan") for b in builds]
    preset = os.path.join(ROOT, "presets", "keyaki_mature.json")
    load0 = os.getloadavg()
    sums = [{k: [] for k in ("gen", "w_plain", "w_lod", "cpu_plain", "cpu_lod")} for _ in clis]
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "k.glb")
        for cli in clis:
            run(cli, preset, out, False)  # warm the page cache
        for _ in range(a.runs):
            for cli, sm in zip(clis, sums):
                measure(cli, preset, out, sm)
    load1 = os.getloadavg()
    print("| figure | value | target | verdict |")
    print("|---|---|---|---|")
    for b, sm in zip(builds, sums):
        g, added, added_cpu = figures(sm)
        ratio = added / g
        tag = "" if b == a.build else f" ({b})"
        row(f"keyaki_mature `--lod {LOD}`{tag}: LOD's added time / generation (wall, {added:.0f} ms / {g:.0f} ms)",
            f"{ratio:.2f}x", "<= 2x", ratio <= 2.0)
        row(f"keyaki_mature `--lod {LOD}`{tag}: LOD's added CPU time (user + system, {added_cpu:.0f} ms) / "
            f"generation (wall)", f"{added_cpu / g:.2f}x", "—", None)
    model, cores = machine()
    print(f"\nMachine: {model}, {cores} logical cores; load average {load0[0]:.2f} before, {load1[0]:.2f} after "
          f"({a.runs} alternating runs of each, medians, textures off).")


if __name__ == "__main__":
    main()
