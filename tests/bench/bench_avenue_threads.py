#!/usr/bin/env python3
"""What a user waits for in an avenue: the CLI's generation of
avenue_boulevard (16 mature trees) and the default avenue on one thread
and on two, in alternating runs (`--stats` time_ms.generate, textures
off, the .glb written to a temporary folder); the speed-up is the median
one-thread time over the median two-thread time, target at least 1.8x
for the boulevard. Only meaningful on an idle machine: the load average
before and after is printed with the machine.

Prints markdown table rows `| figure | value | target | met/not met |`
and one line naming the machine and its load.

    python3 tests/bench/bench_avenue_threads.py --build build --runs 5
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
from machine_info import machine  # noqa: E402

TARGET = 1.8
CASES = (("avenue_boulevard", os.path.join(ROOT, "presets", "avenue_boulevard.json"), TARGET),
         ("default avenue", None, None))


def generate_ms(cli, preset, threads, out):
    cmd = [cli, "avenue", "--threads", str(threads), "--textures", "off", "--stats", "-o", out]
    if preset:
        cmd[2:2] = ["--preset", preset]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode:
        raise SystemExit("bench_avenue_threads: %s exited %d: %s" % (" ".join(cmd), p.returncode,
                                                                    (p.stderr or p.stdout).strip()[-300:]))
    for line in reversed(p.stdout.splitlines()):
        line = line.strip()
        if line.startswith("{") and '"time_ms"' in line:
            return json.loads(line)["time_ms"]["generate"]
    raise SystemExit("bench_avenue_threads: no --stats line from: " + " ".join(cmd))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", required=True, help="the build directory (holds the banyan CLI)")
    ap.add_argument("--runs", type=int, default=5, help="runs of each thread count, alternating")
    a = ap.parse_args()
    cli = os.path.join(os.path.abspath(a.build), "banyan")
    load0 = os.getloadavg()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "a.glb")
        for name, preset, target in CASES:
            generate_ms(cli, preset, 2, out)  # warm the page cache
            t = {1: [], 2: []}
            for r in range(a.runs):
                for threads in ((1, 2) if r % 2 == 0 else (2, 1)):
                    t[threads].append(generate_ms(cli, preset, threads, out))
            one, two = statistics.median(t[1]), statistics.median(t[2])
            rows.append((name, one, two, target))
    load1 = os.getloadavg()
    print("| figure | value | target | verdict |")
    print("|---|---|---|---|")
    for name, one, two, target in rows:
        ratio = one / two
        verdict = "—" if target is None else "met" if ratio >= target else "not met"
        print(f"| {name}: generation on 1 thread / on 2 threads ({one:.0f} / {two:.0f} ms) | {ratio:.2f}x | "
              f"{'>= %.1fx' % target if target else '—'} | {verdict} |")
    model, cores = machine()
    print(f"\nMachine: {model}, {cores} logical cores; load average {load0[0]:.2f} before, {load1[0]:.2f} after "
          f"({a.runs} alternating runs of each, medians, textures off).")


if __name__ == "__main__":
    main()
