#!/usr/bin/env python3
"""Writes the host meshes of the mesh-host presets as glTF binaries:

  presets/hosts/column.glb   a round column / tree trunk, 3.5 m, 48 sides, tapered,
                             flared at the foot, a little irregular (roots_column)
  presets/hosts/statue.glb   a 1.2 m ball on a round pedestal, 2.27 m, one shell
                             (ivy_statue)
  presets/hosts/rock.glb     an irregular rock about 3 m x 2.2 m x 1.4 m: an
                             icosphere displaced by value noise (roots_rock)

Every mesh is closed (each edge shared by exactly two triangles, vertices
shared), wound counter-clockwise from outside, built in banyan's frame (Z up,
metres, ground at z = 0) and written Y up as glTF wants: (x, y, z) -> (x, z, -y).
Plain Python 3 (struct, json), no numpy. The bytes are deterministic:
the noise is an integer hash, coordinates are rounded to 1e-6 m before they
become float32, and the JSON is written with fixed key order.

  python3 tools/make_host_meshes.py            write the files
  python3 tools/make_host_meshes.py --check    exit 1 unless the files in the
                                               repository are what it would write
"""
import json
import math
import os
import struct
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
OUT_DIR = os.path.join(HERE, '..', 'presets', 'hosts')


# ------------------------------------------------------------------ noise

def _hash(ix, iy, iz, seed):
    """A lattice value in [-1, 1] from an integer hash (no platform maths)."""
    h = (ix * 73856093 ^ iy * 19349663 ^ iz * 83492791 ^ seed * 2654435761) & 0xFFFFFFFF
    h ^= h >> 16
    h = (h * 0x7FEB352D) & 0xFFFFFFFF
    h ^= h >> 15
    h = (h * 0x846CA68B) & 0xFFFFFFFF
    h ^= h >> 16
    return h / 2147483647.5 - 1.0


def value_noise(x, y, z, seed):
    """Smoothly interpolated lattice noise, about [-1, 1]."""
    ix, iy, iz = math.floor(x), math.floor(y), math.floor(z)
    fx, fy, fz = x - ix, y - iy, z - iz
    sx, sy, sz = (f * f * (3 - 2 * f) for f in (fx, fy, fz))
    acc = 0.0
    for dz in (0, 1):
        wz = sz if dz else 1 - sz
        for dy in (0, 1):
            wy = sy if dy else 1 - sy
            for dx in (0, 1):
                wx = sx if dx else 1 - sx
                acc += wx * wy * wz * _hash(ix + dx, iy + dy, iz + dz, seed)
    return acc


def fbm(x, y, z, seed, octaves=3):
    total, amp, freq, norm = 0.0, 1.0, 1.0, 0.0
    for o in range(octaves):
        total += amp * value_noise(x * freq, y * freq, z * freq, seed + o)
        norm += amp
        amp *= 0.5
        freq *= 2.0
    return total / norm


# --------------------------------------------------------------- shapes

def lathe(rings, sides, radius_of=None):
    """A closed surface of revolution about the z axis. rings: [(r, z)]
    from bottom to top (r > 0), closed by a pole below the first ring and
    above the last. radius_of(theta, ring index, r, z) may perturb r."""
    verts = [(0.0, 0.0, rings[0][1])]
    for j, (r, z) in enumerate(rings):
        for i in range(sides):
            t = 2 * math.pi * i / sides
            rr = radius_of(t, j, r, z) if radius_of else r
            verts.append((rr * math.cos(t), rr * math.sin(t), z))
    top = len(verts)
    verts.append((0.0, 0.0, rings[-1][1]))

    def ring(j, i):
        return 1 + j * sides + i % sides

    tris = []
    for i in range(sides):
        tris.append((0, ring(0, i + 1), ring(0, i)))
    for j in range(len(rings) - 1):
        for i in range(sides):
            a, b, c, d = ring(j, i), ring(j, i + 1), ring(j + 1, i + 1), ring(j + 1, i)
            tris.append((a, b, c))
            tris.append((a, c, d))
    for i in range(sides):
        tris.append((ring(len(rings) - 1, i), ring(len(rings) - 1, i + 1), top))
    return verts, tris


def column():
    """A trunk-like column: 3.5 m, radius 0.32 m tapering to 0.29 m, a
    flared foot, bark-scale irregularity of a few centimetres."""
    height, n = 3.5, 35
    rings = []
    for j in range(n + 1):
        z = height * j / n
        r = 0.32 - 0.03 * z / height + 0.12 * math.exp(-z / 0.3)
        rings.append((r, z))

    def bumpy(t, j, r, z):
        c, s = math.cos(t), math.sin(t)
        return r * (1 + 0.06 * fbm(1.6 * c + 5, 1.6 * s + 5, 1.1 * z, 11))

    return lathe(rings, 48, bumpy)


def statue():
    """A ball (radius 0.6 m) on a round pedestal with plinth and cap: one
    closed shell, so it reads as one solid."""
    rings = [(0.50, 0.00), (0.50, 0.10), (0.40, 0.16), (0.38, 0.20), (0.37, 0.50), (0.35, 0.84),
             (0.45, 0.88), (0.45, 0.98), (0.30, 1.02), (0.18, 1.06)]
    R, rn = 0.6, 0.18
    zc = 1.10 + math.sqrt(R * R - rn * rn)
    phi0 = math.pi - math.asin(rn / R)
    steps = 40
    for k in range(steps):
        phi = phi0 * (1 - k / steps)
        rings.append((R * math.sin(phi), zc + R * math.cos(phi)))
    verts, tris = lathe(rings, 64)
    verts[-1] = (0.0, 0.0, zc + R)  # the top pole sits on the ball
    return verts, tris


def icosphere(subdivisions):
    t = (1 + math.sqrt(5)) / 2
    verts = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
             (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    verts = [_unit(v) for v in verts]
    tris = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2),
            (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11),
            (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(subdivisions):
        mid = {}

        def midpoint(a, b):
            key = (a, b) if a < b else (b, a)
            if key not in mid:
                va, vb = verts[a], verts[b]
                verts.append(_unit(((va[0] + vb[0]) / 2, (va[1] + vb[1]) / 2, (va[2] + vb[2]) / 2)))
                mid[key] = len(verts) - 1
            return mid[key]

        nxt = []
        for a, b, c in tris:
            ab, bc, ca = midpoint(a, b), midpoint(b, c), midpoint(c, a)
            nxt += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        tris = nxt
    return verts, tris


def _unit(v):
    n = math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
    return (v[0] / n, v[1] / n, v[2] / n)


def rock():
    """An icosphere stretched to 1.5 x 1.1 x 0.75 m half-axes and pushed in
    and out along its radius by value noise (star-shaped, so it cannot
    fold), then set down so that its lowest point is 0.1 m below ground."""
    dirs, tris = icosphere(4)
    verts = []
    for d in dirs:
        k = 1 + 0.22 * fbm(1.4 * d[0] + 3, 1.4 * d[1] + 3, 1.4 * d[2] + 3, 7, octaves=4)
        verts.append((1.5 * k * d[0], 1.1 * k * d[1], 0.75 * k * d[2]))
    low = min(v[2] for v in verts)
    verts = [(x, y, z - low - 0.1) for x, y, z in verts]
    return verts, tris


# ------------------------------------------------------------ checking

def check_closed(name, verts, tris):
    """Every edge once in each direction (closed, consistently wound) and a
    positive volume (wound counter-clockwise from outside)."""
    edges = {}
    for a, b, c in tris:
        for e in ((a, b), (b, c), (c, a)):
            edges[e] = edges.get(e, 0) + 1
    bad = [e for e, n in edges.items() if n != 1 or edges.get((e[1], e[0])) != 1]
    if bad:
        raise SystemExit('%s: %d edges not shared by exactly two triangles, e.g. %s' % (name, len(bad), bad[:3]))
    vol = 0.0
    for a, b, c in tris:
        (ax, ay, az), (bx, by, bz), (cx, cy, cz) = verts[a], verts[b], verts[c]
        vol += ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx)
    if vol <= 0:
        raise SystemExit('%s: volume %g: triangles are wound inwards' % (name, vol / 6))
    return vol / 6


# ------------------------------------------------------------ glTF out

def glb_bytes(name, verts, tris):
    # Round first, so the float32 bits do not hang on the last bit of sin/cos.
    yup = [(round(x, 6), round(z, 6), round(-y, 6)) for x, y, z in verts]
    pos = struct.pack('<%df' % (3 * len(yup)), *[c for v in yup for c in v])
    stored = struct.unpack('<%df' % (3 * len(yup)), pos)
    lo = [min(stored[k::3]) for k in range(3)]
    hi = [max(stored[k::3]) for k in range(3)]
    idx = struct.pack('<%dI' % (3 * len(tris)), *[i for t in tris for i in t])
    doc = {
        'asset': {'version': '2.0', 'generator': 'banyan tools/make_host_meshes.py'},
        'scene': 0,
        'scenes': [{'nodes': [0]}],
        'nodes': [{'mesh': 0, 'name': name}],
        'meshes': [{'name': name, 'primitives': [{'attributes': {'POSITION': 0}, 'indices': 1, 'material': 0,
                                                  'mode': 4}]}],
        'materials': [{'name': 'host', 'pbrMetallicRoughness': {'baseColorFactor': [0.6, 0.6, 0.6, 1.0],
                                                                'metallicFactor': 0.0, 'roughnessFactor': 0.9}}],
        'buffers': [{'byteLength': len(pos) + len(idx)}],
        'bufferViews': [{'buffer': 0, 'byteOffset': 0, 'byteLength': len(pos), 'target': 34962},
                        {'buffer': 0, 'byteOffset': len(pos), 'byteLength': len(idx), 'target': 34963}],
        'accessors': [{'bufferView': 0, 'componentType': 5126, 'count': len(yup), 'type': 'VEC3', 'min': lo,
                       'max': hi},
                      {'bufferView': 1, 'componentType': 5125, 'count': 3 * len(tris), 'type': 'SCALAR'}],
    }
    js = json.dumps(doc, separators=(',', ':')).encode()
    js += b' ' * (-len(js) % 4)
    binary = pos + idx
    binary += b'\0' * (-len(binary) % 4)
    total = 12 + 8 + len(js) + 8 + len(binary)
    return (struct.pack('<4sII', b'glTF', 2, total) + struct.pack('<I4s', len(js), b'JSON') + js +
            struct.pack('<I4s', len(binary), b'BIN\0') + binary)


MESHES = [('column', column), ('statue', statue), ('rock', rock)]


def main(argv):
    check = '--check' in argv[1:]
    os.makedirs(OUT_DIR, exist_ok=True)
    stale = 0
    for name, make in MESHES:
        verts, tris = make()
        vol = check_closed(name, verts, tris)
        data = glb_bytes(name, verts, tris)
        path = os.path.normpath(os.path.join(OUT_DIR, name + '.glb'))
        zs = [v[2] for v in verts]
        what = '%s: %d vertices, %d triangles, closed, volume %.3f m^3, z %.3f .. %.3f m, %d bytes' % (
            path, len(verts), len(tris), vol, min(zs), max(zs), len(data))
        if check:
            try:
                with open(path, 'rb') as f:
                    same = f.read() == data
            except OSError:
                same = False
            print(('ok    ' if same else 'STALE ') + what)
            stale += not same
        else:
            with open(path, 'wb') as f:
                f.write(data)
            print('wrote ' + what)
    if stale:
        print('%d file(s) differ from what tools/make_host_meshes.py writes: rerun it' % stale)
    return 1 if stale else 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))
