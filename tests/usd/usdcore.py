"""Pixar's usd-core (PyPI) as the peer of fairsub's USD reader and writer (tests/it/usd.rs).

    usdcore.py make DIR      write control nets with usd-core (usda, usdc, usdz) and the same
                             nets as OBJ files with OpenSubdiv's tag lines, for fairsub to read
    usdcore.py inspect FILE  open FILE in a usd-core stage, print its first Mesh's attributes
                             and every UsdValidation validator's errors as JSON
"""

import json
import os
import sys

from pxr import Sdf, Usd, UsdGeom, UsdUtils, UsdValidation, Vt

# Nets: points (exact in float32), faces, creases (chains, one sharpness per chain), corners,
# holes, options, st (face-varying, indexed).
CUBE = {
    "points": [(-1, -1, 1), (1, -1, 1), (-1, 1, 1), (1, 1, 1), (-1, 1, -1), (1, 1, -1),
               (-1, -1, -1), (1, -1, -1)],
    "faces": [[0, 1, 3, 2], [2, 3, 5, 4], [4, 5, 7, 6], [6, 7, 1, 0], [1, 7, 5, 3], [6, 0, 2, 4]],
    "creases": [([0, 1, 3], 2.5), ([4, 5], 10.0)],
    "corners": [(6, 3.0)],
    "holes": [],
    "boundary": None,
    "fvar": None,
    "triangles": None,
}

# A 4 x 3 grid of quads with a bump, a hole, a crease, a corner, boundary edge-only and
# texture coordinates (seams: the st indices differ across the middle column).
def grid():
    pts = [(i, j, 0.5 * ((i * j) % 3)) for j in range(4) for i in range(5)]
    faces = [[5 * j + i, 5 * j + i + 1, 5 * j + i + 6, 5 * j + i + 5] for j in range(3) for i in range(4)]
    return {
        "points": pts,
        "faces": faces,
        "creases": [([6, 7, 8], 1.5)],
        "corners": [(12, 2.0)],
        "holes": [10],
        "boundary": "edgeOnly",
        "fvar": "cornersPlus1",
        "triangles": None,
        "st": True,
    }

# Triangles and a pentagon: Catmull-Clark's smooth triangle rule.
MIXED = {
    "points": [(0, 0, 0), (2, 0, 0), (3, 2, 0), (1, 3, 0.5), (-1, 2, 0), (1, 1, 2)],
    "faces": [[0, 1, 5], [1, 2, 5], [2, 3, 5], [3, 4, 5], [4, 0, 5], [0, 4, 3, 2, 1]],
    "creases": [],
    "corners": [],
    "holes": [],
    "boundary": "edgeAndCorner",
    "fvar": None,
    "triangles": "smooth",
}

BOUNDARY_CODE = {"none": 0, "edgeAndCorner": 1, "edgeOnly": 2}
FVAR_CODE = {"none": 0, "cornersOnly": 1, "cornersPlus1": 2, "cornersPlus2": 3, "boundaries": 4, "all": 5}


def st_of(net):
    """Per-corner texture values: (u, v) of the point, but the middle column's corners of the
    faces right of x = 2 get their own values (a seam)."""
    values, index, seen = [], [], {}
    for f in net["faces"]:
        right = min(net["points"][v][0] for v in f) >= 2
        for v in f:
            x, y, _ = net["points"][v]
            key = (v, right and x == 2)
            if key not in seen:
                seen[key] = len(values)
                values.append((x / 4.0 + (0.125 if key[1] else 0.0), y / 3.0))
            index.append(seen[key])
    return values, index


def write_usd(net, path):
    stage = Usd.Stage.CreateNew(path)
    UsdGeom.SetStageUpAxis(stage, UsdGeom.Tokens.z)
    UsdGeom.SetStageMetersPerUnit(stage, 0.01)
    root = UsdGeom.Xform.Define(stage, "/Root")
    stage.SetDefaultPrim(root.GetPrim())
    m = UsdGeom.Mesh.Define(stage, "/Root/Net")
    m.CreatePointsAttr([tuple(float(c) for c in p) for p in net["points"]])
    m.CreateFaceVertexCountsAttr([len(f) for f in net["faces"]])
    m.CreateFaceVertexIndicesAttr([v for f in net["faces"] for v in f])
    m.CreateSubdivisionSchemeAttr("catmullClark")
    if net["creases"]:
        m.CreateCreaseIndicesAttr([v for c, _ in net["creases"] for v in c])
        m.CreateCreaseLengthsAttr([len(c) for c, _ in net["creases"]])
        m.CreateCreaseSharpnessesAttr([s for _, s in net["creases"]])
    if net["corners"]:
        m.CreateCornerIndicesAttr([v for v, _ in net["corners"]])
        m.CreateCornerSharpnessesAttr([s for _, s in net["corners"]])
    if net["holes"]:
        m.CreateHoleIndicesAttr(net["holes"])
    if net["boundary"]:
        m.CreateInterpolateBoundaryAttr(net["boundary"])
    if net["fvar"]:
        m.CreateFaceVaryingLinearInterpolationAttr(net["fvar"])
    if net["triangles"]:
        m.CreateTriangleSubdivisionRuleAttr(net["triangles"])
    if net.get("st"):
        values, index = st_of(net)
        pv = UsdGeom.PrimvarsAPI(m).CreatePrimvar(
            "st", Sdf.ValueTypeNames.TexCoord2fArray, UsdGeom.Tokens.faceVarying)
        pv.Set(values)
        pv.SetIndices(Vt.IntArray(index))
    stage.GetRootLayer().Save()


def write_obj(net, path):
    lines = [f"v {x!r} {y!r} {z!r}" for x, y, z in
             ((float(a), float(b), float(c)) for a, b, c in net["points"])]
    if net.get("st"):
        values, index = st_of(net)
        # the values as usd-core stores them (float32), printed exactly
        lines += [f"vt {float(Vt.Vec2fArray([v])[0][0])!r} {float(Vt.Vec2fArray([v])[0][1])!r}"
                  for v in values]
        k = 0
        for f in net["faces"]:
            lines.append("f " + " ".join(f"{v + 1}/{index[k + i] + 1}" for i, v in enumerate(f)))
            k += len(f)
    else:
        lines += ["f " + " ".join(str(v + 1) for v in f) for f in net["faces"]]
    for chain, s in net["creases"]:
        for a, b in zip(chain, chain[1:]):
            lines.append(f"t crease 2/1/0 {a} {b} {s!r}")
    for v, s in net["corners"]:
        lines.append(f"t corner 1/1/0 {v} {s!r}")
    for h in net["holes"]:
        lines.append(f"t hole 1/0/0 {h}")
    if net["boundary"]:
        lines.append(f"t interpolateboundary 1/0/0 {BOUNDARY_CODE[net['boundary']]}")
    # USD's fallback for face-varying data is cornersPlus1 (OpenSubdiv's is all)
    fvar = net["fvar"] or "cornersPlus1"
    if net.get("st"):
        lines.append(f"t facevaryinginterpolateboundary 1/0/0 {FVAR_CODE[fvar]}")
    if net["triangles"] == "smooth":
        lines.append("t smoothtriangles 0/0/1 smooth")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def make(out):
    os.makedirs(out, exist_ok=True)
    for name, net in [("cube", CUBE), ("grid", grid()), ("mixed", MIXED)]:
        for ext in ["usda", "usdc"]:
            write_usd(net, os.path.join(out, f"{name}.{ext}"))
        UsdUtils.CreateNewUsdzPackage(os.path.join(out, f"{name}.usdc"), os.path.join(out, f"{name}.usdz"))
        write_obj(net, os.path.join(out, f"{name}.obj"))
    print(json.dumps({"written": sorted(os.listdir(out))}))


def plain(v):
    """A Vt value as JSON."""
    if v is None:
        return None
    if isinstance(v, (str, int, float, bool)):
        return v
    try:
        return [plain(x) for x in v]
    except TypeError:
        return str(v)


def inspect(path):
    stage = Usd.Stage.Open(path)
    if stage is None:
        print(json.dumps({"opened": False}))
        return
    meshes = [p for p in stage.Traverse() if p.IsA(UsdGeom.Mesh)]
    out = {"opened": True, "meshes": [str(p.GetPath()) for p in meshes],
           "defaultPrim": str(stage.GetDefaultPrim().GetPath()),
           "upAxis": UsdGeom.GetStageUpAxis(stage),
           "metersPerUnit": UsdGeom.GetStageMetersPerUnit(stage)}
    if meshes:
        m = UsdGeom.Mesh(meshes[0])
        attrs = {}
        for a in meshes[0].GetAttributes():
            if not a.HasAuthoredValue():
                continue
            attrs[a.GetName()] = {
                "type": str(a.GetTypeName()),
                "variability": str(a.GetVariability()),
                "value": plain(a.Get()),
            }
        out["attributes"] = attrs
        out["primvars"] = {
            pv.GetPrimvarName(): {"interpolation": pv.GetInterpolation(),
                                  "indexed": pv.IsIndexed(),
                                  "flattened": len(pv.ComputeFlattened() or [])}
            for pv in UsdGeom.PrimvarsAPI(m).GetPrimvars() if pv.HasAuthoredValue()}
        out["normalsInterpolation"] = m.GetNormalsInterpolation()
        out["validTopology"] = list(UsdGeom.Mesh.ValidateTopology(
            m.GetFaceVertexIndicesAttr().Get(), m.GetFaceVertexCountsAttr().Get(),
            len(m.GetPointsAttr().Get())))
    validators = UsdValidation.ValidationRegistry().GetOrLoadAllValidators()
    errors = UsdValidation.ValidationContext(validators).Validate(stage)
    out["validators"] = len(validators)
    out["errors"] = [{"type": str(e.GetType()), "name": str(e.GetName()), "message": e.GetMessage()}
                     for e in errors]
    print(json.dumps(out))


if __name__ == "__main__":
    {"make": make, "inspect": inspect}[sys.argv[1]](sys.argv[2])
