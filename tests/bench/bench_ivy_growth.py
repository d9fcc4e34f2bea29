#!/usr/bin/env python3
"""Ivy growth speed: presets/ivy_wall.json grown through libbanyan.so
(banyan_ivy_create + banyan_ivy_step(steps) + banyan_ivy_free, the
"growth" column of docs/benchmarks.md section 1), in metres of stem per
second, against IvyGen's operator rate (stem-matched; IvyGen needs
Blender, so its metres per second come in as --ivygen-m-per-s, by default
the figure of docs/benchmarks.md section 1). The stem length is the
plant's sum of internode lengths (banyan_ivy_stats.stem_length); section
1 measures the mesh's skeleton, a little shorter, so its rate is a little
lower than this one's.

With --base DIR (a build of another commit) the two builds run
alternately, one worker process at a time (two libbanyan.so cannot share
a process), and the speed-up is the median of the pairs' ratios.

Usage: python3 tests/bench/bench_ivy_growth.py --build build [--runs 15]
           [--base ../base/build] [--ivygen-m-per-s 538] [--preset FILE]
Prints markdown rows | figure | value | target | met/not met |."""
import argparse
import ctypes
import json
import os
import re
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.dirname(os.path.dirname(HERE))
TARGET_X = 25.0  # ivy growth >= 25x IvyGen's operator per metre of stem
IVYGEN_DEFAULT = 538.0  # m/s, IvyGen stem-matched operator (docs/benchmarks.md section 1)
GROWTHS_PER_WORKER = 3  # growths per worker process; the first is a warm-up


class Error(ctypes.Structure):
    _fields_ = [("code", ctypes.c_int32), ("message", ctypes.c_char * 256)]


class Box(ctypes.Structure):
    _fields_ = [("center", ctypes.c_double * 3), ("half", ctypes.c_double * 3), ("rotation", ctypes.c_double * 9)]


class Stats(ctypes.Structure):  # banyan_ivy_stats (csrc/include/banyan/ivy.h)
    _fields_ = [("steps", ctypes.c_int32), ("buds", ctypes.c_int32), ("by_state", ctypes.c_int32 * 5),
                ("attached", ctypes.c_int32), ("branch_points", ctypes.c_int32), ("crossings", ctypes.c_int32),
                ("cannot_grow", ctypes.c_int32), ("attached_fraction", ctypes.c_double),
                ("covered_area", ctypes.c_double), ("density", ctypes.c_double), ("stem_length", ctypes.c_double),
                ("step_seconds", ctypes.c_double)]


GEN_IVY = None  # BANYAN_GEN_IVY, read from csrc/include/banyan.h


def gen_ivy_value():
    m = re.search(r"BANYAN_GEN_IVY\s*=\s*(\d+)", open(os.path.join(SOURCE, "csrc", "include", "banyan.h")).read())
    if not m:
        raise SystemExit("bench_ivy_growth: BANYAN_GEN_IVY not found in csrc/include/banyan.h")
    return int(m.group(1))


def worker(lib_path, preset, n):
    """n growths of the preset in this process: [(wall s, CPU s)], stem m."""
    lib = ctypes.CDLL(lib_path)
    lib.banyan_sizeof_ivy_params.restype = ctypes.c_size_t
    lib.banyan_sizeof_ivy_stats.restype = ctypes.c_size_t
    if lib.banyan_sizeof_ivy_stats() != ctypes.sizeof(Stats):
        raise SystemExit("bench_ivy_growth: banyan_ivy_stats is %d bytes, this script knows %d"
                         % (lib.banyan_sizeof_ivy_stats(), ctypes.sizeof(Stats)))
    params = ctypes.create_string_buffer(lib.banyan_sizeof_ivy_params())
    err = Error()
    text = open(preset, "rb").read()

    def check(status, what):
        if status:
            raise SystemExit("bench_ivy_growth: %s: %s" % (what, err.message.decode()))

    lib.banyan_ivy_params_init(params)
    check(lib.banyan_preset_apply(GEN_IVY, params, text, ctypes.c_size_t(len(text)), preset.encode(),
                                  ctypes.byref(err)), "preset")
    boxes = (Box * 64)()
    nb = ctypes.c_uint32(0)
    check(lib.banyan_preset_hosts(text, ctypes.c_size_t(len(text)), preset.encode(), boxes, 64, ctypes.byref(nb),
                                  ctypes.byref(err)), "preset hosts")
    hosts = ctypes.c_void_p()
    check(lib.banyan_hosts_create(boxes, nb, None, 0, ctypes.byref(hosts), ctypes.byref(err)), "host set")
    lib.banyan_ivy_steps.restype = ctypes.c_int32
    steps = lib.banyan_ivy_steps(params)
    times, stem = [], 0.0
    for _ in range(n):
        iv = ctypes.c_void_p()
        w0, c0 = time.perf_counter(), time.process_time()
        check(lib.banyan_ivy_create(params, hosts, ctypes.byref(iv), ctypes.byref(err)), "create")
        check(lib.banyan_ivy_step(iv, steps, ctypes.byref(err)), "step")
        w1, c1 = time.perf_counter(), time.process_time()
        st = Stats()
        check(lib.banyan_ivy_get_stats(iv, ctypes.byref(st), ctypes.byref(err)), "stats")
        w2 = time.perf_counter()
        lib.banyan_ivy_free(iv)
        w3 = time.perf_counter()
        times.append((w1 - w0 + (w3 - w2), c1 - c0))
        stem = st.stem_length
    lib.banyan_hosts_free(hosts)
    return times, stem, steps


def run_worker(build, preset):
    out = subprocess.run([sys.executable, __file__, "--worker", os.path.join(build, "libbanyan.so"), preset,
                          str(GROWTHS_PER_WORKER)], check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def load_average():
    try:
        return os.getloadavg()[0]
    except OSError:
        return float("nan")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default=os.path.join(SOURCE, "build"), help="build directory (libbanyan.so)")
    ap.add_argument("--runs", type=int, default=15, help="worker processes per build (each: 1 warm-up + %d timed)"
                    % (GROWTHS_PER_WORKER - 1))
    ap.add_argument("--base", help="build directory of the commit to compare with (alternating runs)")
    ap.add_argument("--ivygen-m-per-s", type=float, default=IVYGEN_DEFAULT,
                    help="IvyGen operator metres of stem per second, stem-matched (default %g)" % IVYGEN_DEFAULT)
    ap.add_argument("--preset", default=os.path.join(SOURCE, "presets", "ivy_wall.json"))
    ap.add_argument("--worker", nargs=3, help=argparse.SUPPRESS)
    a = ap.parse_args()
    global GEN_IVY
    GEN_IVY = gen_ivy_value()
    if a.worker:
        times, stem, steps = worker(a.worker[0], a.worker[1], int(a.worker[2]))
        print(json.dumps({"times": times[1:], "stem": stem, "steps": steps}))
        return 0
    builds = [("this build", a.build)] + ([("base", a.base)] if a.base else [])
    res = {name: {"wall": [], "cpu": [], "stem": None} for name, _ in builds}
    pairs_wall, pairs_cpu = [], []
    load0 = load_average()
    for r in range(max(1, a.runs)):
        order = builds if r % 2 == 0 else builds[::-1]  # alternate which goes first
        got = {}
        for name, build in order:
            w = run_worker(build, a.preset)
            res[name]["wall"] += [t[0] for t in w["times"]]
            res[name]["cpu"] += [t[1] for t in w["times"]]
            res[name]["stem"] = w["stem"]
            res[name]["steps"] = w["steps"]
            got[name] = w["times"]
        if a.base:
            pairs_wall.append(statistics.median(t[0] for t in got["base"]) /
                              statistics.median(t[0] for t in got["this build"]))
            pairs_cpu.append(statistics.median(t[1] for t in got["base"]) /
                             statistics.median(t[1] for t in got["this build"]))
    load1 = load_average()
    me = res["this build"]
    wall, cpu = statistics.median(me["wall"]), statistics.median(me["cpu"])
    rate = me["stem"] / wall
    ratio = rate / a.ivygen_m_per_s
    name = os.path.splitext(os.path.basename(a.preset))[0]
    print("bench_ivy_growth: %s, %d steps, %.0f m of stem (sum of internodes); %d growths a build, "
          "load average %.1f .. %.1f" % (name, me["steps"], me["stem"], len(me["wall"]), load0, load1))
    print()
    print("| figure | value | target | met/not met |")
    print("|---|---|---|---|")
    print("| %s growth (create + %d steps + free), median | %.4f s wall [%.4f .. %.4f], %.4f s CPU | reference "
          "| |" % (name, me["steps"], wall, min(me["wall"]), max(me["wall"]), cpu))
    print("| %s growth rate | %.0f m of stem/s | reference | |" % (name, rate))
    print("| ivy growth / IvyGen operator per metre of stem (stem-matched, IvyGen %.0f m/s) | %.1fx | >= %.0fx | %s |"
          % (a.ivygen_m_per_s, ratio, TARGET_X, "met" if ratio >= TARGET_X else "not met"))
    if a.base:
        b = res["base"]
        same = abs(b["stem"] - me["stem"]) <= 1e-9 * max(1.0, me["stem"])
        print("| growth speed-up over the base build (alternating, median of %d pairs) | %.2fx wall, %.2fx CPU "
              "(base %.4f s) | reference | |" % (len(pairs_wall), statistics.median(pairs_wall),
                                                statistics.median(pairs_cpu), statistics.median(b["wall"])))
        print("| same stem length as the base build | %s (%.6f m, base %.6f m) | same | %s |"
              % ("yes" if same else "no", me["stem"], b["stem"], "met" if same else "not met"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
