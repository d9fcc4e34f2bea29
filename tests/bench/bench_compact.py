#!/usr/bin/env python3
"""Compact glTF (--compact, docs/gltf.md "Compact files") against the plain
file: the size ratio (target: keyaki_mature's compact file at most 30 % of
its plain file; ivy_wall and the default roots for information) and the
CLI's write time (its --stats `time_ms.write`) of compact against plain,
from alternating runs (plain, compact, plain, ...; medians). Textures on,
default options otherwise, as a user writes them.

    python3 tests/bench/bench_compact.py --build build [--runs 5]

Prints markdown rows `| figure | value | target | met/not met |` and a line
naming the machine and its load. Plain python3.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from machine_info import machine  # noqa: E402  (tests/bench/)

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CASES = [  # name, CLI arguments, size-ratio target (None: for information)
    ("keyaki_mature", ["keyaki", "--preset", os.path.join(REPO, "presets", "keyaki_mature.json")], 0.30),
    ("ivy_wall", ["ivy", "--preset", os.path.join(REPO, "presets", "ivy_wall.json")], None),
    ("roots (default)", ["roots"], None),
]


def write(cli, args, out, compact):
    cmd = [cli] + args + ["--stats", "-o", out] + (["--compact"] if compact else [])
    r = subprocess.run(cmd, check=True, stdout=subprocess.PIPE, text=True)
    stats = json.loads(r.stdout.strip().splitlines()[-1])
    return stats["time_ms"]["write"], os.path.getsize(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--build", required=True, help="the CMake build folder (holds the banyan CLI)")
    ap.add_argument("--runs", type=int, default=5, help="alternating pairs per case (default 5)")
    a = ap.parse_args()
    cli = os.path.join(a.build, "banyan")
    if not os.access(cli, os.X_OK):
        sys.exit("bench_compact.py: no CLI at %s" % cli)
    load0 = os.getloadavg()[0]
    rows = []
    with tempfile.TemporaryDirectory(prefix="bench_compact_") as tmp:
        for name, args, target in CASES:
            plain_out, compact_out = os.path.join(tmp, "plain.glb"), os.path.join(tmp, "compact.glb")
            write(cli, args, plain_out, False)  # warm the caches (files, textures) once
            times = {False: [], True: []}
            sizes = {}
            for _ in range(a.runs):
                for compact in (False, True):
                    t, size = write(cli, args, compact_out if compact else plain_out, compact)
                    times[compact].append(t)
                    sizes[compact] = size
            ratio = sizes[True] / sizes[False]
            rows.append(("%s compact / plain file size (%.1f / %.1f MB)"
                         % (name, sizes[True] / 1e6, sizes[False] / 1e6),
                         "%.3f" % ratio,
                         "<= %.2f" % target if target is not None else "(information)",
                         ("met" if ratio <= target else "not met") if target is not None else "-"))
            tp, tc = statistics.median(times[False]), statistics.median(times[True])
            rows.append(("%s write time, compact / plain (medians %.0f / %.0f ms, %d alternating pairs)"
                         % (name, tc, tp, a.runs),
                         "%.2fx" % (tc / tp), "(information)", "-"))
    model, cores = machine()
    print("| figure | value | target | verdict |")
    print("|---|---|---|---|")
    for r in rows:
        print("| %s | %s | %s | %s |" % r)
    print()
    print("Measured on %s (%d logical cores), load average %.1f at the start and %.1f at the end "
          "(a shared machine: the ratios come from alternating runs)." % (model, cores, load0, os.getloadavg()[0]))


if __name__ == "__main__":
    main()
