"""Checks USD layers written by banyan, inside OpenUSD's Python library
(the venv of tools/usd/usd_venv.sh):

    python usd_check.py LAYER.usda [GLB]

Opens the layer, runs every validator OpenUSD registers (what usdchecker
runs), and checks the stage's frame (upAxis Z, metersPerUnit 1), each
Mesh (triangles, indices in range, normals, st and every primvar one value
a vertex), the LOD variant set and the PointInstancer's arrays. With GLB
(the same plant written as .glb by the same run), the layer's first node
(variant lod0) holds the .glb's first mesh: the same vertices in the same
order, points and wind pivots equal after glTF's Y-up turn (1 um), the
origin in the node's translation. Prints one JSON line of counts; exits
1 on the first failure."""
import json
import struct
import sys

from pxr import Usd, UsdGeom, UsdValidation


def fail(msg):
    print("FAIL: " + msg)
    sys.exit(1)


def glb_first_mesh(path):
    """POSITION and _WIND_PIVOT_X/Y/Z of the .glb's first node (its mesh's
    primitives in order, or an instanced plant's variants, its children,
    one after another) and the node's translation."""
    b = open(path, "rb").read()
    n = struct.unpack_from("<I", b, 12)[0]
    j = json.loads(b[20:20 + n])
    binoff = 20 + n + 8
    node = j["nodes"][j["scenes"][0]["nodes"][0]]
    def read(acc):
        a = j["accessors"][acc]
        v = j["bufferViews"][a["bufferView"]]
        k = {"SCALAR": 1, "VEC3": 3}[a["type"]]
        off = binoff + v.get("byteOffset", 0) + a.get("byteOffset", 0)
        stride = v.get("byteStride", 4 * k)
        return [struct.unpack_from("<%df" % k, b, off + i * stride) for i in range(a["count"])]
    pts, piv = [], []
    meshes = [node["mesh"]] if "mesh" in node else [j["nodes"][c]["mesh"] for c in node.get("children", [])]
    for p in [p for m in meshes for p in j["meshes"][m]["primitives"]]:
        at = p["attributes"]
        pts += read(at["POSITION"])
        if "_WIND_PIVOT_X" in at:
            xs, ys, zs = (read(at["_WIND_PIVOT_" + c]) for c in "XYZ")
            piv += [(x[0], y[0], z[0]) for x, y, z in zip(xs, ys, zs)]
    return pts, piv, node.get("translation", [0, 0, 0])


def check_mesh(mesh, counts):
    g = UsdGeom.Mesh(mesh)
    pts = g.GetPointsAttr().Get()
    fvc = g.GetFaceVertexCountsAttr().Get()
    fvi = g.GetFaceVertexIndicesAttr().Get()
    n = len(pts)
    if any(c != 3 for c in fvc) or len(fvi) != 3 * len(fvc):
        fail("%s: not all triangles" % mesh.GetPath())
    if len(fvi) and (min(fvi) < 0 or max(fvi) >= n):
        fail("%s: an index outside [0, %d)" % (mesh.GetPath(), n))
    nrm = g.GetNormalsAttr().Get()
    if nrm is None or len(nrm) != n:
        fail("%s: %s normals for %d points" % (mesh.GetPath(), None if nrm is None else len(nrm), n))
    for pv in UsdGeom.PrimvarsAPI(mesh).GetAuthoredPrimvars():
        if pv.GetInterpolation() != "vertex" or len(pv.Get()) != n:
            fail("%s: primvar %s is not one value a vertex" % (mesh.GetPath(), pv.GetPrimvarName()))
    if not mesh.HasAPI("MaterialBindingAPI"):
        fail("%s: no material binding" % mesh.GetPath())
    counts["meshes"] += 1
    counts["points"] += n
    counts["triangles"] += len(fvc)
    return pts


def main():
    path = sys.argv[1]
    stage = Usd.Stage.Open(path)
    if stage is None:
        fail("cannot open " + path)
    if UsdGeom.GetStageUpAxis(stage) != "Z" or UsdGeom.GetStageMetersPerUnit(stage) != 1.0:
        fail("stage frame: upAxis %s, metersPerUnit %s" % (UsdGeom.GetStageUpAxis(stage),
                                                         UsdGeom.GetStageMetersPerUnit(stage)))
    reg = UsdValidation.ValidationRegistry()
    errors = UsdValidation.ValidationContext(reg.GetOrLoadAllValidators()).Validate(stage)
    if errors:
        fail("%d validator errors, first: %s: %s" % (len(errors), errors[0].GetName(), errors[0].GetMessage()))
    root = stage.GetDefaultPrim()
    if not root:
        fail("no defaultPrim")
    counts = {"meshes": 0, "points": 0, "triangles": 0, "instances": 0, "lods": 0, "curves": 0}
    lod = root.GetVariantSets().GetVariantSet("LOD") if root.GetVariantSets().HasVariantSet("LOD") else None
    if lod is not None:
        names = lod.GetVariantNames()
        if names[0] != "lod0" or lod.GetVariantSelection() != "lod0":
            fail("LOD variants %s, selected %s" % (names, lod.GetVariantSelection()))
        counts["lods"] = len(names)
    first_pts, first_piv = [], []
    for prim in stage.Traverse():
        if prim.IsA(UsdGeom.Mesh):
            pts = check_mesh(prim, counts)
            if prim.GetPath().HasPrefix(root.GetPath()):
                first_pts += list(pts)
                pv = UsdGeom.PrimvarsAPI(prim).GetPrimvar("wind_pivot")
                if pv:
                    first_piv += list(pv.Get())
        elif prim.IsA(UsdGeom.PointInstancer):
            pi = UsdGeom.PointInstancer(prim)
            idx = pi.GetProtoIndicesAttr().Get()
            n = len(idx)
            protos = pi.GetPrototypesRel().GetTargets()
            if not all(0 <= i < len(protos) for i in idx):
                fail("%s: a protoIndex outside the %d prototypes" % (prim.GetPath(), len(protos)))
            for a in (pi.GetPositionsAttr(), pi.GetOrientationsAttr(), pi.GetScalesAttr()):
                if len(a.Get()) != n:
                    fail("%s: %s has %d values for %d instances" % (prim.GetPath(), a.GetName(), len(a.Get()), n))
            counts["instances"] += n
        elif prim.IsA(UsdGeom.BasisCurves):
            counts["curves"] += len(UsdGeom.BasisCurves(prim).GetCurveVertexCountsAttr().Get())
    if len(sys.argv) > 2:
        pts, piv, origin = glb_first_mesh(sys.argv[2])
        if len(pts) != len(first_pts):
            fail("%d points against the .glb's %d" % (len(first_pts), len(pts)))
        for a, b in zip(first_pts, pts):
            if max(abs(a[0] - b[0]), abs(a[1] + b[2]), abs(a[2] - b[1])) > 1e-6:
                fail("point %s against the .glb's %s (Y up)" % (tuple(a), b))
        if len(piv) != len(first_piv):
            fail("%d wind pivots against the .glb's %d" % (len(first_piv), len(piv)))
        for a, b in zip(first_piv, piv):
            if max(abs(a[0] - b[0]), abs(a[1] + b[2]), abs(a[2] - b[1])) > 1e-6:
                fail("wind pivot %s against the .glb's %s (Y up)" % (tuple(a), b))
        t = UsdGeom.Xformable(root).GetLocalTransformation().ExtractTranslation()
        if max(abs(t[0] - origin[0]), abs(t[1] + origin[2]), abs(t[2] - origin[1])) > 1e-9:
            fail("translation %s against the .glb node's %s" % (tuple(t), origin))
        counts["matched_glb_points"] = len(pts)
    print(json.dumps(counts))


main()
