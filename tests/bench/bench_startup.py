"""Start-up of a CLI run: what the dynamic loader costs before and while
a plant grows (docs/benchmarks.md, "What users wait for").

    python3 tests/bench/bench_startup.py [--build build] [--runs 30]

- `banyan keyaki --list` (loads the library, prints the parameter tables, grows
  nothing): median CPU time (user + system, getrusage) over alternating
  runs as shipped and with the OpenVDB module preloaded (LD_PRELOAD: the
  cost when libbanyan.so linked OpenVDB), and their ratio.
- A keyaki_mature run (--textures off): its instructions under callgrind,
  those in the dynamic loader (ld-linux: relocations, symbol look-ups,
  lazy binding), and the loader's time, estimated as that share of the
  run's median CPU time. Target: under 3 ms.
Prints markdown rows `| figure | value | target | verdict |`."""
import argparse
import os
import re
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
from machine_info import machine  # noqa: E402


def cpu_ms(cmd, env=None):
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env, check=True)
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    return 1000.0 * (r1.ru_utime - r0.ru_utime + r1.ru_stime - r0.ru_stime)


def loader_share(cmd):
    """(instructions in ld-linux, all instructions) of one run, or None."""
    if not shutil.which("valgrind") or not shutil.which("callgrind_annotate"):
        return None
    with tempfile.TemporaryDirectory() as d:
        out = os.path.join(d, "cg.out")
        subprocess.run(["valgrind", "--tool=callgrind", "--callgrind-out-file=" + out] + cmd,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
        text = subprocess.run(["callgrind_annotate", "--inclusive=no", out], capture_output=True, text=True).stdout
    total = loader = 0
    for ln in text.splitlines():
        m = re.match(r"\s*([\d,]+) \(\s*[\d.]+%\)\s+(\S.*)", ln)
        if not m:
            continue
        n = int(m.group(1).replace(",", ""))
        if "PROGRAM TOTALS" in m.group(2):
            total = n
        elif "ld-linux" in m.group(2) or "/elf/" in m.group(2) or "dl-" in m.group(2).split(":")[0]:
            loader += n
    return loader, total


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default=os.path.join(REPO, "build"))
    ap.add_argument("--runs", type=int, default=30)
    a = ap.parse_args()
    cli = os.path.join(a.build, "banyan")
    module = os.path.join(a.build, "libbanyan_vdb.so")
    env_vdb = dict(os.environ, LD_PRELOAD=module)
    shipped, preloaded = [], []
    for _ in range(a.runs):
        shipped.append(cpu_ms([cli, "keyaki", "--list"]))
        preloaded.append(cpu_ms([cli, "keyaki", "--list"], env_vdb))
    s, p = statistics.median(shipped), statistics.median(preloaded)
    with tempfile.TemporaryDirectory() as d:
        keyaki = [cli, "keyaki", "--preset", os.path.join(REPO, "presets", "keyaki_mature.json"), "--textures", "off",
                  "-o", os.path.join(d, "k.glb")]
        run = statistics.median(cpu_ms(keyaki) for _ in range(max(5, a.runs // 3)))
        share = loader_share(keyaki)
    print("| figure | value | target | verdict |")
    print("|---|---|---|---|")
    print("| start-up, `banyan keyaki --list`: CPU ms (median of %d) | %.2f ms; with OpenVDB loaded at start %.2f ms (%.1fx) "
          "| - | reference |" % (a.runs, s, p, p / s if s else 0))
    if share:
        loader, total = share
        ms = run * loader / total if total else 0
        print("| keyaki_mature run: time in the dynamic loader (callgrind share x median CPU %.1f ms) | %.2f ms "
              "(%.2f M of %.0f M instructions) | < 3 ms | **%s** |"
              % (run, ms, loader / 1e6, total / 1e6, "met" if ms < 3 else "not met"))
    else:
        print("| keyaki_mature run: time in the dynamic loader | valgrind missing | < 3 ms | not measured |")
    model, cores = machine()
    print("\nMachine: %s, %d logical cores; load average at the end %.2f %.2f %.2f." % ((model, cores) + os.getloadavg()))


main()
