"""Every fenced ```python example in docs/*.md runs as written: each block
is extracted and run with exec() in a fresh factory scene (the default
cube, camera and light) with the add-on enabled, in a namespace of its own.

A block may be preceded (blank lines aside) by one HTML comment, which a
rendered page does not show, saying what it needs:
    <!-- example: setup: CODE -->  CODE runs first in the block's namespace
                                    (the objects a fragment names: a curve,
                                    a wall)
    <!-- example: continues -->     the block goes on from the one before it
                                    in the same file: same scene, same names
    <!-- example: skip: REASON -->  not run (pseudo-code, a shell session);
                                    listed in this test's output with REASON
A python block with no comment runs as it is."""
import glob
import os
import re
import sys
import time
import traceback

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bt  # noqa: E402

import bpy  # noqa: E402

FENCE = re.compile(r"^(\s*)```(\S*)\s*$")
DIRECTIVE = re.compile(r"^\s*<!--\s*example:\s*(setup|continues|skip)\s*:?\s*(.*?)\s*-->\s*$")


def blocks(path):
    """[(line, info, code, directive, argument)] of the file's fenced blocks
    (info: the fence's language), code dedented by the fence's indent."""
    out = []
    lines = open(path, encoding="utf-8").read().split("\n")
    i = 0
    while i < len(lines):
        m = FENCE.match(lines[i])
        if not m:
            i += 1
            continue
        indent, info, start = m.group(1), m.group(2), i
        body = []
        i += 1
        while i < len(lines) and not (FENCE.match(lines[i]) and FENCE.match(lines[i]).group(2) == ""):
            body.append(lines[i][len(indent):] if lines[i].startswith(indent) else lines[i].lstrip())
            i += 1
        i += 1
        k = start - 1
        while k >= 0 and not lines[k].strip():
            k -= 1
        d = DIRECTIVE.match(lines[k]) if k >= 0 else None
        out.append((start + 1, info, "\n".join(body) + "\n", d.group(1) if d else None, d.group(2) if d else ""))
    return out


def main():
    docs = sorted(glob.glob(os.path.join(bt.SOURCE_DIR, "docs", "*.md")))
    bt.check(docs, "docs/*.md found in %s" % bt.SOURCE_DIR)
    ran, skipped = 0, []
    for path in docs:
        rel = os.path.relpath(path, bt.SOURCE_DIR)
        ns = None
        for line, info, code, directive, arg in blocks(path):
            if info.lower() not in ("python", "py", "python3"):
                bt.check(directive is None, "%s:%d: an example comment before a %r block" % (rel, line, info))
                continue
            where = "%s:%d" % (rel, line)
            if directive == "skip":
                bt.check(arg, "%s: a skipped example says why" % where)
                skipped.append("%s (%s)" % (where, arg))
                ns = None
                continue
            if directive == "continues":
                if not bt.check(ns is not None, "%s: continues a block that ran" % where):
                    continue
            else:
                bt.reset_scene()
                ns = {"__name__": "__docs_example__"}
            t = time.perf_counter()
            try:
                if directive == "setup":
                    exec(compile(arg, where + " (setup)", "exec"), ns)
                exec(compile(code, where, "exec"), ns)
            except Exception:
                traceback.print_exc()
                bt.check(False, "%s: the example raised" % where)
                ns = None
                continue
            ran += 1
            print("%s: ran in %.2f s" % (where, time.perf_counter() - t), flush=True)
    for s in skipped:
        print("SKIP: %s" % s)
    print("docs examples: %d ran, %d skipped" % (ran, len(skipped)))
    bt.check(ran > 0, "some examples ran")


bt.run(main)
bt.done()
