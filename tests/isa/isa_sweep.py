#!/usr/bin/env python3
"""Same bytes on every x86-64 CPU (docs/api.md, "Determinism").

    isa_sweep.py --cli BANYAN --preload embree_isa_preload.so --probe libm_probe
                 --repo REPO --out DIR

Grows every preset (mesh hosts, levels of detail, avenue variants, hosts
given with --host, the textures and the demos included) through the CLI
once as the reference (one thread, the machine's own kernels), then again
under each kernel set this machine can stand in for, and compares every
output file's sha256 with the reference:

  threads      all cores (--threads 0)
  embree-X     Embree's kernels pinned to X (sse2, sse4.2, avx, avx2,
               avx512: those the CPU has), through embree_isa_preload.so
  libm-nofma   glibc's libm without its FMA/AVX2 builds (GLIBC_TUNABLES),
               as on a CPU without FMA
  oldest       both: Embree SSE2, libm and string functions at baseline

Only the hashes are kept (each case's files are removed once hashed).
Each stand-in is checked to take effect: Embree's verbose report must name
the pinned kernel set, and libm_probe must print another hash under the
tunable than without it (when the CPU has FMA). BANYAN_TEST_TIER=quick
runs the reference, `threads`, `oldest` and the widest Embree set only.
Prints "isa_sweep: N passed, N failed".
"""
import argparse
import concurrent.futures
import glob
import hashlib
import json
import os
import shutil
import subprocess
import sys
import time

TEXTURE_SIZE = "256"  # the painters run the same code at every size
# glibc's hwcaps tunable: -X removes X from the features its ifuncs see.
NOFMA = "glibc.cpu.hwcaps=-AVX2,-FMA,-AVX512F"
BASELINE = "glibc.cpu.hwcaps=-AVX2,-FMA,-AVX512F,-AVX,-SSE4_1,-SSE4_2,-SSSE3,-BMI1,-BMI2,-LZCNT,-POPCNT,-ERMS,-FSRM"
# Embree's kernel sets and the CPU flags each needs (/proc/cpuinfo), with
# the word its verbose report shows for the set chosen and the word it
# must not show (the next set up).
EMBREE_SETS = [
    ("sse2", [], "SSE2", "SSE4.2"),
    ("sse4.2", ["sse4_2"], "SSE4.2", "AVX"),
    ("avx", ["avx"], "AVX", "AVX2"),
    ("avx2", ["avx2", "fma", "bmi2"], "AVX2", "AVX512F"),
    ("avx512", ["avx512f", "avx512cd", "avx512dq", "avx512bw", "avx512vl"], "AVX512F", None),
]

passed = failed = 0


def check(ok, what):
    global passed, failed
    if ok:
        passed += 1
    else:
        failed += 1
        print("FAIL: " + what, flush=True)
    return ok


def cpu_flags():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("flags"):
                    return set(line.split(":", 1)[1].split())
    except OSError:
        pass
    return set()


def cases(repo):
    """(name, CLI arguments): each writes a .glb, or with textures its PNGs,
    into the case's own folder."""
    out = []
    for p in sorted(glob.glob(os.path.join(repo, "presets", "*.json"))):
        name = os.path.splitext(os.path.basename(p))[0]
        with open(p) as f:
            gen = json.load(f)["generator"]
        args = [gen, "--preset", p]
        if name == "avenue_boulevard":  # 100 unique trees, 1.7 GB: the same code on 12
            args += ["--set", "end=60,0,0"]
        out.append((name, args))
    pre = lambda n: os.path.join(repo, "presets", n + ".json")
    host = lambda n: os.path.join(repo, "presets", "hosts", n + ".glb")
    out += [
        ("lod_keyaki", ["keyaki", "--preset", pre("keyaki_mature"), "--lod", "0.5,0.15,billboard"]),
        ("lod_roots_rock", ["roots", "--preset", pre("roots_rock"), "--lod", "0.5,0.2"]),
        ("lod_ivy_statue", ["ivy", "--preset", pre("ivy_statue"), "--lod", "0.4,billboard"]),
        ("variants", ["avenue", "--preset", pre("avenue_street"), "--set", "variants=3"]),
        ("host_roots_statue", ["roots", "--host", host("statue")]),
        ("host_ivy_column", ["ivy", "--host", host("column")]),
        ("engine_uvs", ["keyaki", "--preset", pre("keyaki_young"), "--engine-uvs"]),
        ("tube", ["tube"]),
        ("segments_demo", ["segments"]),
        ("textures", ["textures", "--size", TEXTURE_SIZE, "--seed", "7"]),
    ]
    return out


def run_case(cli, case, folder, env, threads):
    """({file: sha256} of what the case wrote, or None; the CLI's output)."""
    name, args = case
    os.makedirs(folder, exist_ok=True)
    if args[0] == "textures":
        cmd = [cli] + args + ["-o", folder]
    else:
        cmd = [cli] + args + ["--texture-size", TEXTURE_SIZE, "--threads", threads, "-o",
                              os.path.join(folder, "out.glb")]
    r = subprocess.run(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if r.returncode != 0:
        return None, r.stdout[-2000:]
    sums = {}
    for f in sorted(os.listdir(folder)):
        with open(os.path.join(folder, f), "rb") as fh:
            sums[f] = hashlib.sha256(fh.read()).hexdigest()
    shutil.rmtree(folder)  # the hashes are what is compared: a full sweep would keep some 20 GB
    return sums, r.stdout


def sweep(cli, all_cases, out, tag, env, threads):
    """{case: {file: sha256}} for one configuration; a failed run is left out.
    Cases run side by side, one per core."""
    res = {}
    with concurrent.futures.ThreadPoolExecutor(max_workers=os.cpu_count() or 1) as pool:
        runs = [(case, pool.submit(run_case, cli, case, os.path.join(out, tag, case[0]), env, threads))
                for case in all_cases]
        for case, fut in runs:
            sums, log = fut.result()
            if check(sums is not None, "%s: %s failed under %s: %s" % (case[0], " ".join(case[1]), tag, log)):
                res[case[0]] = sums
    return res


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cli", required=True)
    ap.add_argument("--preload", required=True)
    ap.add_argument("--probe", required=True)
    ap.add_argument("--repo", required=True)
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    quick = os.environ.get("BANYAN_TEST_TIER") == "quick"
    os.makedirs(a.out, exist_ok=True)
    flags = cpu_flags()
    base = dict(os.environ)
    for k in ("LD_PRELOAD", "GLIBC_TUNABLES", "BANYAN_TEST_EMBREE_CONFIG"):
        base.pop(k, None)

    def env(embree=None, tunables=None):
        e = dict(base)
        if embree:
            e["LD_PRELOAD"] = a.preload
            e["BANYAN_TEST_EMBREE_CONFIG"] = "isa=" + embree
        if tunables:
            e["GLIBC_TUNABLES"] = tunables
        return e

    # The stand-ins take effect.
    supported = [s for s in EMBREE_SETS if all(f in flags for f in s[1])]
    check(bool(supported), "no Embree kernel set matches this CPU's flags")
    rock = os.path.join(a.repo, "presets", "roots_rock.json")
    for isa, _, shows, not_shows in supported:
        e = env(isa)
        e["BANYAN_TEST_EMBREE_CONFIG"] += ",verbose=1"
        r = subprocess.run([a.cli, "roots", "--preset", rock, "--textures", "off", "-o",
                            os.path.join(a.out, "verbose.glb")], env=e, stdout=subprocess.PIPE,
                           stderr=subprocess.STDOUT, text=True)
        isa_lines = [ln.split(":", 1)[1].split() for ln in r.stdout.splitlines() if ln.strip().startswith("ISA")]
        chosen = isa_lines[-1] if isa_lines else []  # the first line is the CPU's, the last the device's
        check(r.returncode == 0 and shows in chosen and (not_shows is None or not_shows not in chosen),
              "Embree pinned to %s reports kernels %s (exit %d)%s" % (
                  isa, " ".join(chosen) or "(none)", r.returncode, "" if r.returncode == 0 else ": " + r.stdout[-500:]))
    has_fma = "fma" in flags and "avx2" in flags
    if has_fma:
        p0 = subprocess.run([a.probe], env=env(), stdout=subprocess.PIPE, text=True).stdout.strip()
        p1 = subprocess.run([a.probe], env=env(tunables=NOFMA), stdout=subprocess.PIPE, text=True).stdout.strip()
        check(p0 and p1 and p0 != p1, "GLIBC_TUNABLES=%s switches libm's kernels (probe %s vs %s)" % (NOFMA, p0, p1))
    else:
        print("isa_sweep: the CPU has no FMA/AVX2: libm already runs its baseline kernels", flush=True)

    configs = [("threads", env(), "0")]
    widest = supported[-1][0] if supported else None
    for isa, _, _, _ in supported:
        if not quick or isa == widest:
            configs.append(("embree-" + isa, env(isa), "1"))
    if has_fma and not quick:
        configs.append(("libm-nofma", env(tunables=NOFMA), "1"))
    configs.append(("oldest", env("sse2", BASELINE), "1"))

    all_cases = cases(a.repo)
    t0 = time.time()
    ref = sweep(a.cli, all_cases, a.out, "reference", env(), "1")
    print("isa_sweep: reference: %d cases, %d files, %.1f s" % (
        len(ref), sum(len(v) for v in ref.values()), time.time() - t0), flush=True)
    for tag, e, threads in configs:
        t = time.time()
        got = sweep(a.cli, all_cases, a.out, tag, e, threads)
        same = 0
        for case, sums in ref.items():
            for f, h in sums.items():
                g = got.get(case, {}).get(f)
                if check(g == h, "%s/%s under %s: sha256 %s, reference %s" % (case, f, tag, g, h)):
                    same += 1
        print("isa_sweep: %-14s %3d of %3d files identical, %.1f s" % (
            tag, same, sum(len(v) for v in ref.values()), time.time() - t), flush=True)
    print("isa_sweep: %s tier, Embree kernel sets %s, libm %s" % (
        "quick" if quick else "full", " ".join(s[0] for s in supported), "FMA and baseline" if has_fma else "baseline"))
    print("isa_sweep: %d passed, %d failed" % (passed, failed))
    return 1 if failed or not passed else 0


if __name__ == "__main__":
    sys.exit(main())
