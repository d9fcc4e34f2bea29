#!/usr/bin/env python3
"""The docs carry no hand-typed timings.

Measurements live in docs/benchmarks.md, written by the scripts that take
them (tests/bench/, tools/); docs/reliability.md is generated too. Every
other page (docs/*.md and README.md) links the section of benchmarks.md
that holds a figure instead of quoting it. This check scans those pages,
outside the blocks that scripts write (`<!-- figures: ... -->` ..
`<!-- end figures -->`, `<!-- params:... -->` .. `<!-- /params -->`), for
a number followed by a unit of time or speed (ms, s, us, seconds,
minutes, M tris/s, GB/s, "3x faster", ...) or of memory (MB, GB, ...),
and fails naming file:line. It also checks that every link with an
anchor (`[..](page.md#anchor)`, `[..](#anchor)`) names a heading of its
page, so the links into benchmarks.md that stand for the figures hold.

A line that names a header's constant in backticks (`BANYAN_...`) states
a limit of the code and passes; ALLOW lists the few other figures that
are not measurements (a parameter's range or default, a block size); an
entry that no longer matches anything fails too, so the list stays short
and true.

Usage: hand_typed_figures.py [REPO_ROOT]
"""
import os
import re
import sys

SKIP = {"benchmarks.md", "reliability.md"}  # generated pages
BLOCKS = [("<!-- figures:", "<!-- end figures -->"), ("<!-- params:", "<!-- /params -->")]

ONE = r"(?:\d{1,3}(?:,\d{3})+(?!\d)|\d+)(?:\.\d+)?(?:e[+-]?\d+)?"
NUM = r"(?<![\w.])" + ONE + r"(?:\s*(?:-|to|\.\.|->|/)\s*" + ONE + r")*"
UNITS = (r"ms|s|sec|secs|seconds|µs|us|ns|minutes?|mins?|hours?"  # "2 second" is an ordinal
         r"|[kKMGT]i?B|fps"
         r"|[kKMG]?\s*[A-Za-z]+/s")  # any rate: GB/s, M tris/s, segments/s
FIGURE = re.compile(NUM + r"\s*(?:" + UNITS + r")(?![\w/(])")
FASTER = re.compile(r"\d(?:\.\d+)?\s*(?:x|×|times)\s+(?:faster|slower|quicker)", re.I)

# (page, text on the line): figures that are not measurements.
ALLOW = [
    # budget parameters' ranges and defaults (csrc/include/banyan.h)
    ("docs/api.md", "0.01 .. 604800 s, default 600"),
    ("docs/api.md", "1048576 MB, default 8192"),
    ("docs/api.md", "stopped after 2.00 s, past max_seconds = 2 (0.01 .. 604800)"),
    ("docs/api.md", "ivy growth needs 55 MB, past"),
    ("docs/keyaki.md", "(0.01 .. 604800 s, default"),
    ("docs/keyaki.md", "(16 .. 1,048,576 MB, default 16,384)"),
    # how often the budget is read (csrc/base/progress.c)
    ("docs/api.md", "the resident size every 20 ms"),
    ("docs/keyaki.md", "read every 20 ms"),
    ("docs/api.md", "at most once every 0.1 s while it moves slower"),
    # a test's bound (tests/c/robustness/test_budget_keyaki.c)
    ("docs/keyaki.md", "`max_seconds` = 2 stop within 2.5 s"),
    # the thread pool's join sleeps (csrc/base/pool.c)
    ("docs/keyaki.md", "in sleeps of 50 us growing to 2 ms"),
    # limits and block sizes stated by the code
    ("docs/gltf.md", "a few 512 KiB blocks ahead"),
    # the .glb reader's JSON cap and read piece (csrc/gltf/gltf_reader.cpp)
    ("docs/api.md", "(at most 64 MB), from which"),
    ("docs/formats.md", "then the JSON chunk (at most 64 MB) is read"),
    ("docs/api.md", "every 8 MB read and every 65,536"),
    ("docs/gltf.md", "on the file every 64 MiB"),
    # a viewer call's argument
    ("docs/game-engines.md", "freeze the clock at 2.5 s"),
]


# A line naming a constant of the library's headers (`BANYAN_...`) states
# a limit the code sets, not a measurement.
CONSTANT = re.compile(r"`BANYAN_[A-Z0-9_]+`")


def pages(root):
    docs = os.path.join(root, "docs")
    out = [os.path.join(docs, n) for n in sorted(os.listdir(docs)) if n.endswith(".md") and n not in SKIP]
    return out + [os.path.join(root, "README.md")]


def headings(path, cache={}):
    """GitHub's anchors of a page's headings (outside fenced code)."""
    if path not in cache:
        anchors, fenced = set(), False
        with open(path, encoding="utf-8") as f:
            for line in f:
                if line.startswith("```"):
                    fenced = not fenced
                m = None if fenced else re.match(r"#{1,6}\s+(.*?)\s*$", line)
                if m:
                    text = re.sub(r"[^\w\- ]", "", m.group(1).strip().lower())
                    anchors.add(text.replace(" ", "-"))
        cache[path] = anchors
    return cache[path]


def scan(root):
    problems, used = [], set()
    for path in pages(root):
        rel = os.path.relpath(path, root)
        end = None
        with open(path, encoding="utf-8") as f:
            lines = f.read().split("\n")
        for no, line in enumerate(lines, 1):
            if end is not None:
                if line.strip().startswith(end):
                    end = None
                continue
            opened = [e for s, e in BLOCKS if line.strip().startswith(s)]
            if opened:
                end = opened[0]
                continue
            for m in re.finditer(r"\]\(([\w./-]*\.md)?#([\w\-]+)\)", line):
                target = os.path.normpath(os.path.join(os.path.dirname(path), m.group(1))) if m.group(1) else path
                if not os.path.exists(target) or m.group(2) not in headings(target):
                    problems.append("%s:%d: no heading in %s for the link #%s"
                                    % (rel, no, os.path.relpath(target, root), m.group(2)))
            hits = [m.group(0) for m in FIGURE.finditer(line)] + [m.group(0) for m in FASTER.finditer(line)]
            if not hits:
                continue
            if CONSTANT.search(line):
                continue  # a limit quoted beside the code's own name for it
            allowed = [i for i, (page, text) in enumerate(ALLOW) if page == rel and text in line]
            if allowed:
                used.update(allowed)
                continue
            problems.append("%s:%d: hand-typed figure %s: link the docs/benchmarks.md section that measures it"
                            % (rel, no, ", ".join(repr(h) for h in hits)))
        if end is not None:
            problems.append("%s: generated block not closed (%s)" % (rel, end))
    for i, (page, text) in enumerate(ALLOW):
        if i not in used:
            problems.append("tests/docs/hand_typed_figures.py: ALLOW entry (%s, %r) matches no line" % (page, text))
    return problems


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.dirname(os.path.dirname(
        os.path.abspath(__file__))))
    problems = scan(root)
    for p in problems:
        print(p)
    if problems:
        print("hand_typed_figures: %d problem(s)" % len(problems))
        return 1
    print("hand_typed_figures: no hand-typed timings in %d pages" % len(pages(root)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
