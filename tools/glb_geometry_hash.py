#!/usr/bin/env python3
"""Hashes the geometry of .glb files: POSITION, NORMAL and indices of every
primitive, in order, and nothing else (uvs, colours, materials, images
are left out). Changes to materials or uvs must leave these hashes alone.

    tools/glb_geometry_hash.py FILE.glb...   -> "md5  positions  normals  indices  FILE" per file
"""
import hashlib
import json
import struct
import sys


def read_glb(path):
    with open(path, "rb") as f:
        data = f.read()
    magic, _version, _length = struct.unpack_from("<III", data, 0)
    if magic != 0x46546C67:
        raise ValueError("%s: not a .glb" % path)
    off, doc, binary = 12, None, b""
    while off < len(data):
        n, kind = struct.unpack_from("<II", data, off)
        chunk = data[off + 8:off + 8 + n]
        if kind == 0x4E4F534A:
            doc = json.loads(chunk)
        elif kind == 0x004E4942:
            binary = chunk
        off += 8 + n
    return doc, binary


def accessor_bytes(doc, binary, index):
    a = doc["accessors"][index]
    v = doc["bufferViews"][a["bufferView"]]
    size = {5126: 4, 5125: 4, 5123: 2, 5121: 1}[a["componentType"]]
    width = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}[a["type"]]
    start = v.get("byteOffset", 0) + a.get("byteOffset", 0)
    return binary[start:start + a["count"] * size * width]


def geometry_hashes(path):
    doc, binary = read_glb(path)
    h = {k: hashlib.md5() for k in ("all", "POSITION", "NORMAL", "indices")}
    for mesh in doc.get("meshes", []):
        for prim in mesh["primitives"]:
            for key in ("POSITION", "NORMAL"):
                if key in prim["attributes"]:
                    b = accessor_bytes(doc, binary, prim["attributes"][key])
                    h[key].update(b)
                    h["all"].update(b)
            if "indices" in prim:
                b = accessor_bytes(doc, binary, prim["indices"])
                h["indices"].update(b)
                h["all"].update(b)
    return [h[k].hexdigest()[:12] for k in ("all", "POSITION", "NORMAL", "indices")]


def main(argv):
    if not argv:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    for path in argv:
        print("  ".join(geometry_hashes(path) + [path]))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
