#!/usr/bin/env python3
"""Writes docs/reliability.md from real runs (issue 8): nothing in its tables
is typed by hand.

Sources:
  - the bad-input test: `test_bad_input --table` prints one JSON object per
    case (generator, entry point, class of bad input, input, wanted and
    returned status, message); run here unless --bad-input FILE is given;
  - the fuzz results, out/fuzz_results.json: one JSON line per harness and
    run, appended by tools/fuzz.sh;
  - the crashers found and fixed: files in tests/fuzz/regressions/<harness>/;
  - the add-on's hostile-input results, out/addon_hostile.json (a JSON list
    of {operator, property, value, result, message, scene_unchanged}, written
    by the headless Blender test), when present.

Usage: python3 tools/reliability_table.py [--build build] [--bad-input FILE]
       [--fuzz out/fuzz_results.json] [--addon out/addon_hostile.json]
       [--out docs/reliability.md]
Plain python3, no dependencies.
"""
import argparse
import collections
import datetime
import json
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
GENERATORS = ["roots", "keyaki", "avenue", "ivy", "segments", "textures", "presets", "common"]
HARNESSES = ["fuzz_preset", "fuzz_roots", "fuzz_keyaki", "fuzz_ivy", "fuzz_segments"]

POLICY = """\
## Policy

Every public call validates its input and fails with a status, never with
a crash: it returns the status, fills `banyan_error` (`code` equal to the
status, a message naming the field, its value and its valid range) and
leaves its out pointer NULL. The statuses are distinct per kind of fault:

| fault | status |
|---|---|
| NULL pointer, unknown generator, capacity too small | `BANYAN_E_INVALID_ARG` |
| NaN, inf, a value outside its range, rules that tie fields together | `BANYAN_E_RANGE` |
| no hosts where hosts are required | `BANYAN_E_NO_HOSTS` |
| a degenerate host box | `BANYAN_E_BAD_HOST` |
| a start point inside a host (or below the ground) | `BANYAN_E_START_INSIDE` |
| a start point too far from every host | `BANYAN_E_START_FAR` |
| output past `max_vertices` (or another documented cap) | `BANYAN_E_LIMIT` |
| malformed preset text | `BANYAN_E_PARSE`, `BANYAN_E_TYPE`, `BANYAN_E_UNKNOWN_KEY` |

Choices made where the issue left one open:

- **Degenerate hosts are refused, never repaired.** A box needs a half-extent
  in [1e-6, 1e6] m on every axis, a finite centre within 1e6 m, and a
  rotation whose columns are orthonormal within 1e-3 with determinant +1.
  A scaled, sheared or mirrored rotation is refused with a message asking
  the caller to fold the scale into `half`: repairing it silently would
  change the box the user sees. (A Blender plane has zero thickness, so the
  add-on must give it some before passing it.)
- **Roots: G out of reach.** A germination point farther from every host
  than a main root can ever move (start_radius + (growth_points - 1) x moves
  x hypot(forward_max, lateral) units, plus 4 r) is refused with
  `BANYAN_E_START_FAR`: no root could touch a host.
- **Ivy: a start inside a host is repaired**, as documented since the ivy
  landed: the start is snapped to the nearest host surface (the default
  start lies inside the default wall). A start farther than
  `start_snap_max` from every host is refused with `BANYAN_E_START_FAR`.
- **Segments: a segment far from every axis is not an error**: it is built
  and reported in `stats.unattached` and the `unattached` list.
- **Far from the origin.** Meshes keep float32 positions relative to
  `banyan_mesh.origin` (0 near the world origin, whole metres near the
  plant beyond 4096 m; docs/api.md). What one mesh cannot keep to 1 mm,
  inputs reaching more than 8192 m from that origin (a tube's points,
  segments, an avenue's trees, a roots G or ivy start that far in its host
  set's frame), is refused with `BANYAN_E_RANGE` naming the input and its
  span, asking to split the scene; never silently rounded.
- **Memory.** Every generator has `max_vertices` (default 4,000,000; at most
  2^30). Roots estimate their vertex count before the net is grown; keyaki
  plans the exact count from the skeleton (bounded by `max_nodes`) before
  the mesh; the avenue counts tree by tree and stops counting as soon as
  the sum passes the cap; the one-shot ivy stops growing as soon as its
  buds alone would need more vertices than the cap (the stepping calls are
  bounded by `max_buds`, about 240 bytes per bud); segments count lines
  first; the tube demo refuses past 16,000,000 vertices. `test_limits`
  checks the largest allocation of every refused generation.
- **Out of memory.** `test_limits` also makes each allocation of a roots
  net, a keyaki tree, an avenue, a 160-step ivy, a segment tree and a tube
  fail, one at a time (269 runs): each gives its mesh (where the memory was
  only for speed: the ivy light cache's edges, a larger hash table, the
  final trim of the arrays) or `BANYAN_E_NOMEM` with no mesh, and the ASan
  build finds no leak on any of these paths.
- **Presets** are read by cJSON after a scan of the raw bytes: strict UTF-8
  (no overlong forms, surrogates, code points past U+10FFFF or NUL bytes),
  no `\\u0000` escape, nesting at most 16 deep, at most 4 MiB; then no
  text after the object, known top-level keys only, no key given twice, and
  every value of the right type and range. cJSON is given the length, so it
  never reads past the buffer; its parse calls are serialised because
  cJSON 1.7 records the last error position in a global.
- **Output files are replaced whole or not at all.** The glTF writer, the
  CLI's PNGs and the add-on's presets write a temporary
  `.<name>.XXXXXX.tmp` in the target's folder, sync it and rename it over
  the target; a full disk, a file size limit or an unwritable folder
  leaves the old file byte for byte and no temporary file (a killed
  process may leave the temporary file, never a cut target). A symlink
  stays a link, its target replaced. The CLI checks `-o` (extension,
  folder exists and is writable, not a folder) before generating.
  `test_atomic_write` and `cli_output` check each case
  ([formats.md, Writing files](formats.md#writing-files)).
- **Threads.** Every call is reentrant on distinct arguments; `test_threads`
  runs every generator and the preset reader from 4 threads and compares
  mesh hashes with sequential runs, under ThreadSanitizer as well.
"""


def run_bad_input(build):
    exe = os.path.join(build, "tests", "test_bad_input")
    if not os.path.exists(exe):
        sys.exit("reliability_table: %s not found; build first (or pass --bad-input FILE)" % exe)
    p = subprocess.run([exe, "--table"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    sys.stderr.write(p.stderr)
    if p.returncode != 0:
        sys.exit("reliability_table: test_bad_input failed; fix it before writing the table")
    return p.stdout.splitlines()


def read_lines(path):
    rows = []
    with open(path, encoding="utf-8") as f:
        for line in f:
            line = line.strip()
            if line:
                rows.append(json.loads(line))
    return rows


def md(text, limit=160):
    """A table cell: one line, pipes escaped, long messages shortened."""
    text = str(text).replace("\n", " ").replace("|", "\\|")
    return text if len(text) <= limit else text[:limit - 3] + "..."


def counts(items):
    c = collections.Counter(items)
    return ", ".join("%s %d" % (k, n) for k, n in sorted(c.items(), key=lambda kv: (-kv[1], kv[0])))


def bad_input_section(rows):
    out = []
    total, passed = len(rows), sum(1 for r in rows if r["pass"])
    out.append("## Bad input: every entry point\n")
    out.append("From `test_bad_input --table`: %d cases, %d as wanted (status, a message naming the field, "
               "the out pointer NULL; or a documented repair)." % (total, passed))
    out.append("")
    out.append("| generator | entry point | cases | bad inputs tried | results | as wanted |")
    out.append("|---|---|---|---|---|---|")
    by = collections.OrderedDict()
    for r in rows:
        by.setdefault((r["generator"], r["entry"]), []).append(r)
    order = {g: i for i, g in enumerate(GENERATORS)}
    for (gen, entry), rs in sorted(by.items(), key=lambda kv: (order.get(kv[0][0], 99), kv[0][1])):
        out.append("| %s | `%s` | %d | %s | %s | %d/%d |" % (
            gen, entry, len(rs), md(counts(r["class"] for r in rs), 1000),
            md(counts(r["status"].replace("BANYAN_", "") for r in rs), 1000), sum(r["pass"] for r in rs), len(rs)))
    out.append("")

    sweep = [r for r in rows if r.get("sweep")]
    if sweep:
        out.append("### Every field of every parameter table\n")
        out.append("Each field of each generator's table set, one at a time, to NaN, +-inf, DBL_MAX, just below "
                   "and above its range, zero and a negative value where those are out of range (ints also "
                   "INT32_MIN / INT32_MAX, enums and bools one past their choices), then every entry point of "
                   "that generator called.")
        out.append("")
        out.append("| generator | fields | bad values tried | results | message names the field |")
        out.append("|---|---|---|---|---|")
        for gen in GENERATORS:
            rs = [r for r in sweep if r["generator"] == gen]
            if not rs:
                continue
            fields = {r["input"].split(" = ")[0].split("[")[0] for r in rs}
            out.append("| %s | %d | %s | %s | %d/%d |" % (
                gen, len(fields), md(counts(r["class"] for r in rs), 1000),
                counts(r["status"].replace("BANYAN_", "") for r in rs), sum(r["pass"] for r in rs), len(rs)))
        out.append("")

    hand = [r for r in rows if not r.get("sweep")]
    out.append("### Hand-made cases\n")
    out.append("| generator | entry point | input | result | message |")
    out.append("|---|---|---|---|---|")
    for r in sorted(hand, key=lambda r: (order.get(r["generator"], 99), r["entry"])):
        result = r["status"].replace("BANYAN_", "")
        if not r["pass"]:
            result += " (**wanted %s**)" % r["want"].replace("BANYAN_", "")
        out.append("| %s | `%s` | %s | %s | %s |" % (r["generator"], r["entry"], md(r["input"]), result,
                                                   md(r["message"]) if r["message"] else "(repaired: a mesh)"))
    out.append("")
    return out


def fuzz_section(results):
    out = ["## Fuzzing\n"]
    out.append("libFuzzer with ASan and UBSan (Debian clang), `tools/fuzz.sh`, run by `tools/test.sh`. Every "
               "harness also checks invariants: a failed call has a real status, a message and a NULL out; a "
               "mesh has every index in range, finite positions and normals, parts that cover it; what a "
               "preset reader accepts passes the generators' own checks. Crashers found and fixed are the files "
               "in `tests/fuzz/regressions/<harness>/`, replayed by ctest in every build.")
    out.append("")
    out.append("| harness | runs | fuzzing time | executions | crashes in these runs | crashers found and fixed "
               "| last run |")
    out.append("|---|---|---|---|---|---|---|")
    by = collections.defaultdict(list)
    for r in results:
        by[r["harness"]].append(r)
    tot_s = tot_e = 0
    for h in HARNESSES:
        rs = by.get(h, [])
        secs = sum(r["seconds"] for r in rs)
        execs = sum(r["execs"] for r in rs)
        crashes = sum(r["crashes"] for r in rs)
        tot_s += secs
        tot_e += execs
        reg = os.path.join(HERE, "tests", "fuzz", "regressions", h)
        fixed = len([f for f in os.listdir(reg) if not f.startswith(".")]) if os.path.isdir(reg) else 0
        last = max((r["date"] for r in rs), default="never")
        out.append("| `%s` | %d | %.2f h | %s | %d | %d | %s |" % (h, len(rs), secs / 3600.0, "{:,}".format(execs),
                                                               crashes, fixed, last))
    out.append("| all | | %.2f h | %s | | | |" % (tot_s / 3600.0, "{:,}".format(tot_e)))
    out.append("")
    return out


def addon_section(rows, path):
    out = ["## The add-on: hostile property values\n"]
    if rows is None:
        out.append("No add-on results file (`%s`) was present when this page was generated; the headless Blender "
                   "test writes it." % os.path.relpath(path, HERE))
        out.append("")
        return out
    def kind(r):
        res = r.get("result", "")
        return "ok (objects made on purpose)" if res.endswith("ok") else res

    def unchanged(r):
        u = r.get("scene_unchanged")
        return "n/a (made objects)" if u is None else ("yes" if u else "**no**")

    failed = [r for r in rows if r.get("scene_unchanged") is False]
    out.append("From `%s`: %d operator and API calls with hostile values or scenes. After every refused call "
               "the scene is compared (object, mesh, material, collection and node-group names and counts); "
               "it changed after %d of them." % (os.path.relpath(path, HERE), len(rows), len(failed)))
    out.append("")
    def category(r):
        res = r.get("result", "")
        if res.startswith("raised"):
            return "raised an exception (API)"
        if res.endswith("error report"):
            return "error report"
        if res.endswith("ok"):
            return "ok"
        return res.split(":")[0]  # refused by Blender, poll refused
    cats = ["error report", "raised an exception (API)", "refused by Blender", "poll refused", "ok"]
    cats += sorted({category(r) for r in rows} - set(cats))
    out.append("| operator | calls | " + " | ".join(cats) + " | clamped by Blender first |")
    out.append("|---|---|" + "---|" * (len(cats) + 1))
    by_op = collections.OrderedDict()
    for r in rows:
        by_op.setdefault(r.get("operator", ""), []).append(r)
    for op, rs in by_op.items():
        counts = collections.Counter(category(r) for r in rs)
        clamped = sum(1 for r in rs if r.get("result", "").startswith("clamped"))
        out.append("| `%s` | %d | %s | %d |" % (md(op), len(rs), " | ".join(str(counts[c]) for c in cats), clamped))
    out.append("")
    out.append("<details><summary>Every call (%d rows)</summary>\n" % len(rows))
    out.append("| operator | property | value | result | message | scene unchanged |")
    out.append("|---|---|---|---|---|---|")
    for r in rows:
        out.append("| `%s` | %s | %s | %s | %s | %s |" % (
            md(r.get("operator", "")), md(r.get("property", "")), md(r.get("value", "")), md(kind(r)),
            md(r.get("message", "")), unchanged(r)))
    out.append("\n</details>")
    out.append("")
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--build", default=os.path.join(HERE, "build"))
    ap.add_argument("--bad-input", help="JSON lines of test_bad_input --table (default: run it)")
    ap.add_argument("--fuzz", default=os.path.join(HERE, "out", "fuzz_results.json"))
    ap.add_argument("--addon", default=os.path.join(HERE, "out", "addon_hostile.json"))
    ap.add_argument("--out", default=os.path.join(HERE, "docs", "reliability.md"))
    a = ap.parse_args()

    if a.bad_input:
        lines = open(a.bad_input, encoding="utf-8").read().splitlines()
    else:
        lines = run_bad_input(a.build)
    bad = [json.loads(l) for l in lines if l.strip()]
    fuzz = read_lines(a.fuzz) if os.path.exists(a.fuzz) else []
    addon = None
    if os.path.exists(a.addon):
        with open(a.addon, encoding="utf-8") as f:
            addon = json.load(f)

    try:
        commit = subprocess.run(["git", "-C", HERE, "rev-parse", "--short", "HEAD"], stdout=subprocess.PIPE,
                                stderr=subprocess.DEVNULL, text=True).stdout.strip() or "unknown"
    except OSError:
        commit = "unknown"
    now = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    out = ["# Reliability: what was tried\n",
           "<!-- Generated by tools/reliability_table.py; do not edit by hand: run it again. -->",
           "Generated %s at commit %s by `python3 tools/reliability_table.py` from the bad-input test, "
           "`out/fuzz_results.json` and the add-on's `out/addon_hostile.json`." % (now, commit), ""]
    out.append(POLICY)
    out += bad_input_section(bad)
    out += fuzz_section(fuzz)
    out += addon_section(addon, a.addon)
    with open(a.out, "w", encoding="utf-8") as f:
        f.write("\n".join(out).rstrip() + "\n")
    print("reliability_table: %d bad-input cases, %d fuzz runs, %s add-on rows -> %s" % (
        len(bad), len(fuzz), "no" if addon is None else len(addon), os.path.relpath(a.out, HERE)))
    failed = [r for r in bad if not r["pass"]]
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
