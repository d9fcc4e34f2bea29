#!/usr/bin/env python3
"""bench_texture_write: what textures add to the CLI's write, for
keyaki_mature and ivy_wall.

Each round runs, in turn (the order rotating from round to round, so
the machine's load falls on every variant alike):
  - untextured:        --textures off;
  - textured, cold:    textures on, the texture cache an empty folder
                       (drawn, encoded and stored);
  - textured, warm:    textures on, the cache filled by an earlier run.
The write time is the CLI's own `--stats` figure time_ms.write: the clock
around banyan_gltf_write_ex alone, after generation, so generation's
time and its noise stay out of it (no separate bench program needed).
Medians over the rounds; the ratio is the textured median over the
untextured one. Below the rows, the CPU time the textures add to the
whole run (the process's user + sys time, median, over the untextured
run's): generation is the same in both, so the difference is the
textures' work, less sensitive to the machine's load than the clock. Prints markdown rows `| figure | value | target | met |`
and the machine and its load (the 1-minute load average before and
after; this machine may be shared).

  python3 tests/bench/bench_texture_write.py --build build --runs 7
"""
import argparse
import json
import resource
import os
import shutil
import statistics
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from machine_info import machine  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
FIGURES = [("keyaki_mature", "keyaki", "presets/keyaki_mature.json"), ("ivy_wall", "ivy", "presets/ivy_wall.json")]
TARGET = 1.5


def write_ms(cli, command, preset, out, textures, cache):
    env = dict(os.environ)
    env["BANYAN_TEXTURE_CACHE"] = cache if cache else "off"
    args = [cli, command, "--preset", os.path.join(ROOT, preset), "-o", out, "--stats",
            "--textures", "on" if textures else "off"]
    ru0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    r = subprocess.run(args, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, check=False)
    ru1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    if r.returncode != 0:
        sys.exit("bench_texture_write: %s failed: %s" % (" ".join(args), r.stderr.strip()))
    cpu = (ru1.ru_utime - ru0.ru_utime + ru1.ru_stime - ru0.ru_stime) * 1e3
    return json.loads(r.stdout.strip().splitlines()[-1])["time_ms"]["write"], cpu


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--runs", type=int, default=7)
    a = ap.parse_args()
    cli = os.path.join(a.build, "banyan")
    load0 = os.getloadavg()[0]
    rows, notes = [], []
    tmp = tempfile.mkdtemp(prefix="bench_texture_write_")
    try:
        for name, command, preset in FIGURES:
            out = os.path.join(tmp, name + ".glb")
            warm = os.path.join(tmp, "warm_" + name)
            write_ms(cli, command, preset, out, True, warm)  # fills the warm cache
            times = {"untextured": [], "cold": [], "warm": []}
            cpus = {"untextured": [], "cold": [], "warm": []}
            for r in range(a.runs):
                order = ["untextured", "cold", "warm"]
                order = order[r % 3:] + order[:r % 3]
                for v in order:
                    cold = os.path.join(tmp, "cold_%s_%d" % (name, r))
                    cache = {"untextured": None, "cold": cold, "warm": warm}[v]
                    w, c = write_ms(cli, command, preset, out, v != "untextured", cache)
                    times[v].append(w)
                    cpus[v].append(c)
                    if v == "cold":
                        shutil.rmtree(cold, ignore_errors=True)
            med = {k: statistics.median(v) for k, v in times.items()}
            cpu = {k: statistics.median(v) for k, v in cpus.items()}
            for v in ("cold", "warm"):
                ratio = med[v] / med["untextured"]
                rows.append("| %s textured write / untextured, %s texture cache | %.2fx (%.1f / %.1f ms) | "
                            "<= %.1fx | %s |" % (name, v, ratio, med[v], med["untextured"], TARGET,
                                                 "met" if ratio <= TARGET else "not met"))
            for v in ("cold", "warm"):
                notes.append("%s, %s cache: the whole run's CPU time (user + sys, median) is %.0f ms over the "
                             "untextured run's" % (name, v, cpu[v] - cpu["untextured"]))
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    load1 = os.getloadavg()[0]
    model, cores = machine()
    print("| figure | value | target | verdict |")
    print("|---|---|---|---|")
    for r in rows:
        print(r)
    print()
    for n in notes:
        print("- " + n)
    print()
    print("Machine: %s, %d logical cores; 1-minute load average %.2f before, %.2f after "
          "(medians of %d alternating runs; write = the CLI's --stats time_ms.write)."
          % (model, cores, load0, load1, a.runs))


if __name__ == "__main__":
    main()
