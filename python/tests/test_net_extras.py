"""What a net made from arrays carries besides its polygons (creases, corners, holes,
face-varying UVs), the refined values it hands back, the tessellation with exact data, the
scheme options and the curvature colours: each against the command line reading the same
net as an OBJ file with OpenSubdiv tags and `vt` lines."""

import numpy as np
import pytest

import fairsub

CUBE_V = np.array([[x, y, z] for z in (-1.0, 1.0) for y in (-1.0, 1.0) for x in (-1.0, 1.0)])
CUBE_F = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]]
CREASES = (np.array([[0, 1], [1, 3], [4, 5]]), np.array([2.5, 10.0, 0.7]))
CORNERS = (np.array([6, 2]), np.array([3.0, 1.5]))


def uv_of_cube():
    """One UV value per corner, with seams: each face its own square in a 3 x 2 atlas."""
    values, index = [], []
    for f in range(6):
        ox, oy = f % 3, f // 3
        for k, (u, v) in enumerate([(0, 0), (1, 0), (1, 1), (0, 1)]):
            values.append([(ox + 0.1 + 0.8 * u) / 3, (oy + 0.1 + 0.8 * v) / 2])
            index.append(4 * f + k)
    return np.array(values), np.array(index)


def obj_text(uv=None, creases=CREASES, corners=CORNERS, holes=()):
    lines = [f"v {float(x)!r} {float(y)!r} {float(z)!r}" for x, y, z in CUBE_V]
    if uv is not None:
        lines += [f"vt {float(u)!r} {float(v)!r}" for u, v in uv[0]]
    k = 0
    for f in CUBE_F:
        if uv is None:
            lines.append("f " + " ".join(str(v + 1) for v in f))
        else:
            lines.append("f " + " ".join(f"{v + 1}/{uv[1][k + i] + 1}" for i, v in enumerate(f)))
        k += len(f)
    for (a, b), s in zip(*creases):
        lines.append(f"t crease 2/1/0 {a} {b} {float(s)!r}")
    for v, s in zip(*corners):
        lines.append(f"t corner 1/1/0 {v} {float(s)!r}")
    for h in holes:
        lines.append(f"t hole 1/0/0 {h}")
    return "\n".join(lines) + "\n"


@pytest.mark.parametrize("boundary", ["edge-only", "edge-and-corner"])
def test_tags_and_uv_from_arrays_equal_the_obj_reader(boundary, cli, tmp_path):
    uv = uv_of_cube()
    path = tmp_path / "cube.obj"
    path.write_text(obj_text(uv))
    net = fairsub.Net(CUBE_V, CUBE_F, creases=CREASES, corners=CORNERS, uv=uv)
    for fvar in ("all", "boundaries", "none"):
        mine = fairsub.subdivide(net, "catmull-clark", levels=2, boundary=boundary, fvar=fvar)
        theirs = fairsub.subdivide(str(path), "catmull-clark", levels=2, boundary=boundary, fvar=fvar)
        assert mine.faces == theirs.faces
        assert np.abs(mine.vertices - theirs.vertices).max() == 0.0
        for a, b in zip(mine.uv, theirs.uv):
            assert np.array_equal(a, b)
        for a, b in zip(mine.creases, theirs.creases):
            assert np.array_equal(a, b)
        for a, b in zip(mine.corners, theirs.corners):
            assert np.array_equal(a, b)
    out = tmp_path / "cli.obj"
    code, _, err = cli("subdivide", path, "--scheme", "catmull-clark", "--levels", 2,
                       "--boundary", boundary, "-o", out)
    assert code == 0, err
    cli_net = fairsub.read(str(out))
    mine = fairsub.subdivide(net, "catmull-clark", levels=2, boundary=boundary)
    assert np.abs(mine.vertices - cli_net.vertices).max() <= 1e-12
    # the creases change the surface
    plain = fairsub.subdivide(fairsub.Net(CUBE_V, CUBE_F), "catmull-clark", levels=2)
    assert np.abs(plain.vertices - mine.vertices).max() > 0.05


def test_refined_sharpness_decays_by_one_per_level():
    net = fairsub.Net(CUBE_V, CUBE_F, creases=CREASES, corners=CORNERS)
    r = fairsub.subdivide(net, "catmull-clark", levels=1)
    edges, s = r.creases
    assert sorted(s.tolist()) == sorted([1.5, 1.5, 10.0, 10.0])  # 0.7 - 1 < 0 is smooth
    verts, vs = r.corners
    assert sorted(vs.tolist()) == [0.5, 2.0]
    assert edges.dtype == np.uint32 and edges.shape == (4, 2)


def test_flat_faces_and_holes():
    sizes = np.full(6, 4)
    flat = np.array(CUBE_F).reshape(-1)
    a = fairsub.Net(CUBE_V, (sizes, flat), holes=[2])
    b = fairsub.Net(CUBE_V, CUBE_F, holes=[2])
    assert a.faces == b.faces and list(a.holes) == [2]
    s, f = a.face_arrays
    assert list(s) == [4] * 6 and list(f) == flat.tolist()
    r = fairsub.subdivide(a, "catmull-clark", levels=1)
    assert r.num_faces == 20  # the hole's four children are not written


@pytest.mark.parametrize("kwargs,message", [
    (dict(creases=([[0, 7]], [1.0])), "vertices 0 and 7, which share no edge"),
    (dict(creases=([[0, 9]], [1.0])), "crease edges[0] is 9"),
    (dict(creases=([[0, 1]], [1.0, 2.0])), "1 crease edges but 2 sharpness values"),
    (dict(corners=([1], [float("nan")])), "corner sharpness[0] is NaN"),
    (dict(holes=[6]), "holes[0] is 6"),
    (dict(uv=(np.zeros((4, 2)), np.zeros(23))), "one value per face corner (24), not 23"),
    (dict(uv=(np.zeros((4, 2)), np.full(24, 4))), "uv indices[0] is 4"),
    (dict(creases=[[0, 1, 2.0]]), "creases must be a pair"),
])
def test_bad_extras_are_named(kwargs, message):
    with pytest.raises(ValueError) as e:
        fairsub.Net(CUBE_V, CUBE_F, **kwargs)
    assert message in str(e.value)


def test_tolerant_nets_keep_unused_vertices():
    v = np.vstack([CUBE_V, [[5.0, 5.0, 5.0]]])
    assert fairsub.Net(v, CUBE_F).num_vertices == 8
    assert fairsub.Net(v, CUBE_F, tolerant=True).num_vertices == 9


def test_tessellation_data():
    s = fairsub.surface("gallery:cnet-5-saddle", "catmull-clark", rings=2)
    t = s.tessellation(4)
    v, tri = s.tessellate(4)
    assert np.array_equal(t["vertices"], v) and np.array_equal(t["triangles"], tri)
    assert t["normals"].shape == v.shape and t["patch_uv"].shape == (len(v), 2)
    assert np.allclose(np.linalg.norm(t["normals"], axis=1), 1.0)
    assert t["triangle_patch"].max() == len(s) - 1
    # a vertex's point is its patch at its domain point
    for k in range(0, len(v), 37):
        p = s.patches[t["patch"][k]]
        u, w = t["patch_uv"][k]
        du, dv = p.shape[0] - 1, p.shape[1] - 1
        from math import comb
        bu = np.array([comb(du, i) * u**i * (1 - u) ** (du - i) for i in range(du + 1)])
        bv = np.array([comb(dv, j) * w**j * (1 - w) ** (dv - j) for j in range(dv + 1)])
        assert np.abs(np.einsum("i,ijc,j->c", bu, p, bv) - v[k]).max() < 1e-12
    assert np.isfinite(t["gauss"]).all() and np.isfinite(t["mean"]).all()


def test_scheme_options_are_the_commands(cli):
    code, out, _ = cli("subdivide", "--help")
    assert code == 0
    for s in fairsub.schemes():
        for o in fairsub.scheme_options(s["name"]):
            assert f"--{o['name']}" in out
    names = [o["name"] for o in fairsub.scheme_options("tps-adjustable")]
    assert names == ["split-ratio", "alpha-rule"]
    with pytest.raises(ValueError):
        fairsub.scheme_options("no-such-scheme")


def test_curvature_colours():
    c, r = fairsub.curvature_colours([-2.0, 0.0, 1.0, 2.0, float("nan")], range=2.0)
    assert r == 2.0
    assert np.allclose(c[0], [0.12, 0.20, 0.55]) and np.allclose(c[3], [0.60, 0.08, 0.10])
    assert np.allclose(c[1], [0.97, 0.97, 0.97]) and np.allclose(c[4], c[1])
    assert np.allclose(c[2], [0.93, 0.50, 0.32])
    _, auto = fairsub.curvature_colours(np.linspace(-1, 1, 101))
    assert auto == 0.98  # the 98th percentile of |value| (index 98 of 101), rounded up
    with pytest.raises(ValueError):
        fairsub.curvature_colours([1.0], range=-1.0)
