"""Measures how ivy sits on a mesh host, through the add-on as an artist
grows it (docs/ivy.md, "Stems over rounded forms"):

    bash tools/render_docs.sh ivy-mesh -- [--host suzanne|sphere] [--values JSON]

Grows ivy_statue's parameters (docs/render_hosts.py's IVY, the full 450
steps) on Suzanne (size 2, start at its chin) or a UV sphere of radius
1 m, with host shape Surface, then prints:
  - the stem tube vertices' distance to the host's surface (BVHTree):
    shares farther than 3 cm and 10 cm, the median;
  - the share of the host's front silhouette (rays along +y on an 80 x 80
    grid) that the plant hides.
"""
import argparse
import json
import os
import sys

import bpy
import numpy as np
from mathutils import Vector
from mathutils.bvhtree import BVHTree

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import render_scene as RS  # noqa: E402
import render_hosts as RH  # noqa: E402


def bvh_of(ob):
    mw = ob.matrix_world
    return BVHTree.FromPolygons([mw @ v.co for v in ob.data.vertices], [tuple(p.vertices) for p in ob.data.polygons])


def stem_distances(plant, host_bvh):
    me = plant.data
    n = len(me.vertices)
    co = np.empty(3 * n, np.float32)
    me.vertices.foreach_get("co", co)
    part = np.empty(n, np.float32)
    me.attributes["part"].data.foreach_get("value", part)
    mw = plant.matrix_world
    return np.array([host_bvh.find_nearest(mw @ Vector(co[3 * i:3 * i + 3]))[3] for i in np.nonzero(part < 0.5)[0]])


def hidden_share(host, host_bvh, plant_bvh, nx=80):
    lo, hi = RS.bounds([host])
    on_host = hidden = 0
    for ix in range(nx):
        for iz in range(nx):
            o = Vector((lo.x + (hi.x - lo.x) * (ix + 0.5) / nx, lo.y - 1.0, lo.z + (hi.z - lo.z) * (iz + 0.5) / nx))
            hit = host_bvh.ray_cast(o, Vector((0, 1, 0)))
            if hit[0] is None:
                continue
            on_host += 1
            hidden += plant_bvh.ray_cast(o, Vector((0, 1, 0)), hit[3])[0] is not None
    return hidden / max(on_host, 1)


def main():
    ap = argparse.ArgumentParser(prog="measure_ivy_mesh.py")
    ap.add_argument("--host", choices=("suzanne", "sphere"), default="suzanne")
    ap.add_argument("--values", default="{}", help="parameter overrides, JSON")
    a = ap.parse_args(RS.script_args())
    RS.reset()
    host = RH.suzanne() if a.host == "suzanne" else RH.uv_sphere()
    values = dict(RH.IVY)
    if a.host == "suzanne":
        values["start"] = (0.6, -0.5, 0.05)
    values.update(json.loads(a.values))
    plant, _ = RS.grow("ivy", preset="ivy_statue", values=values, hosts=[host], host_shape='SURFACE')
    hb = bvh_of(host)
    d = stem_distances(plant[0], hb)
    print("%s %s: stem vertices > 3 cm off %.1f %%, > 10 cm off %.1f %%, median %.3f m; front silhouette hidden %.1f %%"
          % (a.host, a.values, 100 * (d > 0.03).mean(), 100 * (d > 0.10).mean(), np.median(d),
             100 * hidden_share(host, hb, bvh_of(plant[0]))))


main()
