#!/usr/bin/env python3
"""What a user waits for in levels of detail: the CLI's keyaki_mature
written without and with `--lod 0.5,0.15,billboard` (textures off, so
the difference is the levels and their write), in alternating runs; the
LOD's added time (median write time with levels minus median write time
without) over the median generation time, target at most 2x. Wall time
(the levels run on two threads) and, beside it, the CPU time the LOD adds.

Prints markdown table rows `| figure | value | target | met/not met |`
and one line naming the machine and its load.

    python3 tests/bench/bench_lod_wait.py --build build --runs 7
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


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", required=True, help="the build directory (holds the banyan CLI)")
    ap.add_argument("--runs", type=int, default=7, help="runs of each kind, alternating")
    a = ap.parse_args()
    cli = os.path.join(os.path.abspath(a.build), "banyan")
    preset = os.path.join(ROOT, "presets", "keyaki_mature.json")
    load0 = os.getloadavg()
    gen, w_plain, w_lod, cpu_plain, cpu_lod = [], [], [], [], []
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "k.glb")
        run(cli, preset, out, False)  # warm the page cache
        for _ in range(a.runs):
            g, w, c = run(cli, preset, out, False)
            gen.append(g), w_plain.append(w), cpu_plain.append(c)
            g, w, c = run(cli, preset, out, True)
            gen.append(g), w_lod.append(w), cpu_lod.append(c)
    load1 = os.getloadavg()
    g = statistics.median(gen)
    added = statistics.median(w_lod) - statistics.median(w_plain)
    added_cpu = 1e3 * (statistics.median(cpu_lod) - statistics.median(cpu_plain))
    ratio = added / g
    row(f"keyaki_mature `--lod {LOD}`: LOD's added time / generation (wall, {added:.0f} ms / {g:.0f} ms)",
        f"{ratio:.2f}x", "<= 2x", ratio <= 2.0)
    row(f"keyaki_mature `--lod {LOD}`: LOD's added CPU / generation ({added_cpu:.0f} ms / {g:.0f} ms)",
        f"{added_cpu / g:.2f}x", "—", None)
    model, cores = machine()
    print(f"Machine: {model}, {cores} logical cores; load average {load0[0]:.2f} before, {load1[0]:.2f} after "
          f"({a.runs} alternating runs of each, medians, textures off).")


if __name__ == "__main__":
    main()
