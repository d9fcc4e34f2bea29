#!/usr/bin/env python3
"""`banyan keyaki --stats`: height_m and crown_width_m are the written
mesh's (bark, twigs and leaves): its highest vertex above the trunk base
and twice its largest horizontal distance from the trunk's axis, read
back from the .glb (node translation + positions, glTF's Y up turned to
Z up), to 0.1 mm; skeleton_height_m and skeleton_crown_width_m stay the
skeleton's (banyan_keyaki_stats), which the crown reaches past.
`banyan avenue --stats`: crown_width_min/max/mean_m are the trees'
meshes' in the same way (two trees 20 m apart, each the vertices on its
side of the middle).

    test_keyaki_stats.py <banyan cli> <out dir>
"""
import json
import math
import os
import struct
import subprocess
import sys
from array import array

CASES = (
    ("default", []),
    ("far, 8 levels", ["--set", "position=5000.25,-300,12", "--set", "levels=8"]),
    ("no twigs", ["--set", "levels=10", "--set", "twig_levels=0", "--set", "seed=7"]),
    ("twigs from segments", ["--set", "levels=10", "--set", "twigs_from_segments=1", "--set", "segment_levels=3"]),
)
TOL = 1e-4  # m


def glb_world_points(path):
    """Every POSITION of every primitive, in world metres, Z up."""
    with open(path, "rb") as f:
        data = f.read()
    magic, _, _ = struct.unpack_from("<III", data, 0)
    assert magic == 0x46546C67, "not a glb"
    jlen, _ = struct.unpack_from("<II", data, 12)
    doc = json.loads(data[20:20 + jlen])
    blen, _ = struct.unpack_from("<II", data, 20 + jlen)
    binary = data[28 + jlen:28 + jlen + blen]
    pts = []
    for node in doc["nodes"]:
        if "mesh" not in node:
            continue
        assert not any(k in node for k in ("rotation", "scale", "matrix")), node
        t = node.get("translation", [0.0, 0.0, 0.0])
        seen = set()
        for prim in doc["meshes"][node["mesh"]]["primitives"]:
            a = prim["attributes"]["POSITION"]
            if a in seen:
                continue
            seen.add(a)
            acc = doc["accessors"][a]
            view = doc["bufferViews"][acc["bufferView"]]
            assert acc["componentType"] == 5126 and acc["type"] == "VEC3", acc
            stride = view.get("byteStride", 12)
            start = view.get("byteOffset", 0) + acc.get("byteOffset", 0)
            for i in range(acc["count"]):
                x, y, z = struct.unpack_from("<fff", binary, start + i * stride)
                pts.append((t[0] + x, -(t[2] + z), t[1] + y))  # glTF (x, y, z) -> Z up (x, -z, y)
    return pts


def main():
    cli, out = sys.argv[1], sys.argv[2]
    os.makedirs(out, exist_ok=True)
    failed = 0
    for what, args in CASES:
        path = os.path.join(out, "keyaki_stats_%s.glb" % what.replace(" ", "_").replace(",", ""))
        r = subprocess.run([cli, "keyaki", "--textures", "off", "--stats", "-o", path] + args,
                           capture_output=True, text=True)
        if r.returncode != 0:
            print("FAIL %s: rc %d: %s" % (what, r.returncode, r.stderr))
            failed += 1
            continue
        st = json.loads(r.stdout)
        base = [0.0, 0.0, 0.0]
        for i, a in enumerate(args):
            if a.startswith("position="):
                base = [float(x) for x in a.split("=", 1)[1].split(",")]
        pts = glb_world_points(path)
        height = max(p[2] for p in pts) - base[2]
        width = 2.0 * max(math.hypot(p[0] - base[0], p[1] - base[1]) for p in pts)
        ok = abs(st["height_m"] - height) <= TOL and abs(st["crown_width_m"] - width) <= TOL
        ok = ok and "skeleton_height_m" in st and "skeleton_crown_width_m" in st
        ok = ok and st["skeleton_height_m"] <= height + TOL and st["skeleton_crown_width_m"] <= width + TOL
        print("%s %s: %d vertices; --stats height %.4f m, crown width %.4f m; the mesh's %.4f, %.4f; "
              "the skeleton's %.4f, %.4f" % ("ok  " if ok else "FAIL", what, len(pts), st.get("height_m", -1),
                                             st.get("crown_width_m", -1), height, width,
                                             st.get("skeleton_height_m", -1), st.get("skeleton_crown_width_m", -1)))
        failed += not ok
    failed += avenue(cli, out)
    print("keyaki and avenue --stats vs the mesh: %d cases, %d failed" % (len(CASES) + 1, failed))
    return 1 if failed else 0


def avenue(cli, out):
    """1 when the avenue's crown widths are not its trees' meshes'."""
    path = os.path.join(out, "avenue_stats.glb")
    r = subprocess.run([cli, "avenue", "--textures", "off", "--stats", "-o", path, "--set", "start=0,0,0",
                        "--set", "end=20,0,0", "--set", "rows=1", "--set", "placement=count", "--set", "count=2",
                        "--set", "position_jitter=0", "--set", "tree.levels=8"], capture_output=True, text=True)
    if r.returncode != 0:
        print("FAIL avenue: rc %d: %s" % (r.returncode, r.stderr))
        return 1
    st = json.loads(r.stdout)
    pts = glb_world_points(path)
    widths = [2.0 * max(math.hypot(p[0] - bx, p[1]) for p in pts if (p[0] < 10.0) == (bx == 0.0)) for bx in (0.0, 20.0)]
    ok = (abs(st["crown_width_min_m"] - min(widths)) <= TOL and abs(st["crown_width_max_m"] - max(widths)) <= TOL
          and abs(st["crown_width_mean_m"] - sum(widths) / 2) <= TOL)
    print("%s avenue: crown widths %.4f .. %.4f m, the meshes' %.4f, %.4f" % (
        "ok  " if ok else "FAIL", st["crown_width_min_m"], st["crown_width_max_m"], *widths))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
