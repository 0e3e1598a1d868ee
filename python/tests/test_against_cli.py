"""The Python package against the `fairsub` command line: refined points, patches, checks,
evaluation, spectra, level stencils, pictures and error messages, for every scheme (the nets
are the golden test's, tests/it/golden.rs)."""

import json
import struct
import zlib

import numpy as np
import pytest

import fairsub

# A net every scheme takes (as in tests/it/golden.rs).
REFINE = {
    "catmull-clark": "cnet-5-saddle",
    "doo-sabin": "prism-5",
    "doo-sabin-cc": "prism-5",
    "loop": "icosahedron",
    "sqrt3": "icosahedron",
    "butterfly": "icosahedron",
    "nonbox": "cnet-5-convex",
    "nonbox-4dir": "nonbox-cube-fcv-1",
    "pgs": "prism-5",
    "pgs-dscc": "prism-5",
    "polar-bi2": "prism-5",
    "tps": "cnet-5-saddle",
    "tps-adjustable": "cnet-3-convex",
    "bi2-mixed": "cube",
}
RINGS = {
    "catmull-clark": "cnet-5-saddle",
    "doo-sabin": "prism-5",
    "doo-sabin-cc": "prism-5",
    "loop": "octahedron",
    "nonbox": "cnet-5-convex",
    "nonbox-4dir": "nonbox-cube-fcv-1",
    "eg": "cnet-5-saddle",
    "qas-plus": "cnet-7-convex",
    "qas-plus-bi3": "cnet-5-saddle",
    "qas-0.4": "cnet-6-saddle",
    "qas-0.5-0.4": "cnet-5-convex",
    "pgs": "prism-5",
    "pgs-dscc": "prism-3",
    "polar-bi2": "prism-5",
    "tps": "cnet-5-saddle",
    "tps-adjustable": "cnet-3-convex",
    "bi2-mixed": "cnet-5-saddle",
    "guided-bi5": "cnet-5-saddle",
    "guided-bi6": "cnet-5-convex",
    "guided-bi4-macro": "cnet-5-saddle",
    "guided-bi3-macro": "cnet-6-convex",
}


def test_every_scheme_is_covered():
    cat = fairsub.schemes()
    assert {s["name"] for s in cat if s["refine"]} == set(REFINE)
    assert {s["name"] for s in cat if s["rings"]} == set(RINGS)


def test_schemes_equal_cli(cli):
    code, out, _ = cli("schemes", "--json")
    assert code == 0
    assert fairsub.schemes() == json.loads(out)


@pytest.mark.parametrize("scheme", sorted(REFINE))
def test_refined_points_equal_cli(scheme, cli, tmp_path):
    net = fairsub.read(f"gallery:{REFINE[scheme]}")
    for limit in (False, True):
        out = tmp_path / "out.off"
        args = ["subdivide", net.source, "--scheme", scheme, "--levels", 2, "-o", out]
        code, _, err = cli(*args, *(["--limit"] if limit else []))
        if code != 0:  # e.g. no limit positions from a mesh: the same message
            with pytest.raises(ValueError) as e:
                fairsub.subdivide(net, scheme, levels=2, limit=limit)
            assert err.strip().splitlines()[-1] == f"error: {e.value}"
            continue
        mine = fairsub.subdivide(net, scheme, levels=2, limit=limit)
        if isinstance(mine, tuple):  # non-box limit mesh with normals
            mine, normals = mine
            assert normals.shape == (mine.num_vertices, 3)
        theirs = fairsub.read(str(out), tolerant=True)  # keeps FCV points no face uses
        assert mine.faces == theirs.faces
        v = mine.vertices
        assert v.dtype == np.float64 and v.flags["C_CONTIGUOUS"]
        # OFF is written with shortest round-trip decimals: exact
        assert np.max(np.abs(v - theirs.vertices)) <= 1e-12


@pytest.mark.parametrize("scheme", sorted(RINGS))
def test_patches_and_check_equal_cli(scheme, cli, tmp_path):
    src = f"gallery:{RINGS[scheme]}"
    theirs = tmp_path / "cli.bv"
    code, _, err = cli("subdivide", src, "--scheme", scheme, "--rings", 3, "-o", theirs)
    assert code == 0, err
    s = fairsub.surface(src, scheme, rings=3)
    mine = tmp_path / "py.bv"
    s.write(str(mine))
    assert mine.read_bytes() == theirs.read_bytes()
    assert len(s.patches) == len(s) > 0
    for p in s.patches:
        assert p.dtype == np.float64 and p.flags["C_CONTIGUOUS"] and p.shape[2] == 3
    assert len(s.provenance) == len(s)
    assert {p["kind"] for p in s.provenance} <= {"regular", "ring", "cap"}
    assert any(p["kind"] == "ring" for p in s.provenance)
    code, out, err = cli("check", src, "--scheme", scheme, "--rings", 3, "--json")
    assert code == 0, err
    assert s.check() == json.loads(out)


@pytest.mark.parametrize("scheme,valence", [("catmull-clark", 5), ("eg", 5), ("loop", 7),
                                            ("guided-bi6", 5), ("pgs", 3), ("nonbox", 6),
                                            ("qas-plus", 6), ("tps-adjustable", 5)])
def test_spectra_equal_cli(scheme, valence, cli):
    code, out, err = cli("analyze", "--scheme", scheme, "--valence", valence, "--json")
    assert code == 0, err
    assert fairsub.analyze(scheme, valence) == json.loads(out)


def test_options_reach_the_rules(cli):
    a = fairsub.analyze("tps-adjustable", 5, split_ratio=0.3)
    code, out, _ = cli("analyze", "--scheme", "tps-adjustable", "--valence", 5,
                       "--split-ratio", 0.3, "--json")
    assert code == 0 and a == json.loads(out)
    assert a != fairsub.analyze("tps-adjustable", 5)


@pytest.mark.parametrize("scheme,net", [
    ("catmull-clark", "cnet-5-saddle"), ("loop", "octahedron"), ("eg", "cnet-5-saddle"),
    ("guided-bi5", "cnet-5-saddle"), ("doo-sabin", "cube"), ("pgs", "prism-5"),
    ("pgs-dscc", "prism-5"), ("tps", "cube"), ("nonbox", "prism-5"),
    ("nonbox-4dir", "nonbox-cube-fcv-1"),
    ("guided-bi4-macro", "cnet-5-saddle"), ("guided-bi3-macro", "cnet-6-convex"),
])
def test_evaluate_equals_cli(scheme, net, cli):
    _evaluate_equals_cli(cli, f"gallery:{net}", scheme)


@pytest.mark.parametrize("refine,levels,scheme", [
    # two PGS steps of the cube: eight separated triangle facets with DS-nets, every vertex
    # of valence 4, so every face's quarter at corner 0 evaluates
    ("pgs", 2, "bi2-mixed"),
    # one step of the four-directional variant writes a quasi-four-directional triangle
    # mesh, whose faces (fan triangles of its polygons) are the evaluation's faces
    ("nonbox-4dir", 1, "nonbox-4dir"),
])
def test_evaluate_equals_cli_on_refined_cubes(refine, levels, scheme, cli, tmp_path):
    src = tmp_path / f"cube-{refine}{levels}.obj"
    code, _, err = cli("subdivide", "gallery:cube", "--scheme", refine, "--levels", levels,
                       "-o", src)
    assert code == 0, err
    _evaluate_equals_cli(cli, str(src), scheme)


def test_evaluate_equals_cli_on_tps_adjustable(cli):
    # the input net's faces whose corner 0 is interior (the quarters at boundary vertices are
    # not evaluated; nets that need a separating step are not either)
    src = "gallery:cnet-5-saddle"
    faces = fairsub.read(src).faces
    count = {}
    for f in faces:
        for a, b in zip(f, f[1:] + f[:1]):
            e = (min(a, b), max(a, b))
            count[e] = count.get(e, 0) + 1
    boundary = {v for e, c in count.items() if c == 1 for v in e}
    inner = [i for i, f in enumerate(faces) if f[0] not in boundary]
    assert len(inner) >= 5
    _evaluate_equals_cli(cli, src, "tps-adjustable", np.array(inner))


def _evaluate_equals_cli(cli, src, scheme, faces=None):
    s = fairsub.surface(src, scheme, rings=3)
    rng = np.random.default_rng(7)
    if faces is None:
        faces = np.arange(fairsub.read(src).num_faces)
    u = rng.random(len(faces)) * 0.5
    v = rng.random(len(faces)) * 0.5
    at = ",".join(f"{f}:{float(a)!r}:{float(b)!r}" for f, a, b in zip(faces, u, v))
    code, out, err = cli("eval", src, "--scheme", scheme, "--rings", 3,
                         "--at", at, "--json")
    assert code == 0, err
    theirs = json.loads(out)
    rows = theirs if isinstance(theirs, list) else theirs["points"]
    mine = s.evaluate(faces, u, v)
    assert mine["point"].shape == (len(faces), 3)
    for i, r in enumerate(rows):
        assert np.max(np.abs(mine["point"][i] - np.array(r["point"]))) <= 1e-12
        assert mine["patch"][i] == r["patch"]
        assert abs(mine["gauss"][i] - r["gauss"]) <= 1e-9 * max(1.0, abs(r["gauss"]))
    one = s.evaluate(int(faces[0]), float(u[0]), float(v[0]))
    assert np.array_equal(one["point"], mine["point"][0])


def test_evaluate_refuses_points_without_patches():
    # the hole inside the last ring left open: no patch covers the face next to the vertex
    s = fairsub.surface("gallery:cube", "catmull-clark", rings=1, fill=False)
    with pytest.raises(ValueError, match="no patch of the surface covers face 0"):
        s.evaluate([0], [0.01], [0.01])
    # polar-bi2's TPS rings of a vertex that is not a pole lie in thirds of its quarters
    # (an error before 2026-12-04), as bi2-mixed's
    polar = fairsub.surface("gallery:cnet-5-saddle", "polar-bi2", rings=2)
    mixed = fairsub.surface("gallery:cnet-5-saddle", "bi2-mixed", rings=2)
    a, b = polar.evaluate([0], [0.1], [0.1]), mixed.evaluate([0], [0.1], [0.1])
    assert np.array_equal(a["point"], b["point"])


def test_level_stencils_reproduce_the_refinement():
    net = fairsub.read("gallery:cnet-5-saddle")
    fine, st = fairsub.level_stencils(net, "catmull-clark", levels=2)
    assert st.num_sources == net.num_vertices and st.num_rows == fine.num_vertices
    assert np.max(np.abs(st.apply(net.vertices) - fine.vertices)) <= 1e-12
    moved = net.vertices + np.array([0.0, 0.0, 0.25])
    indptr, idx, w = st.csr()
    dense = np.zeros((st.num_rows, st.num_sources))
    for r in range(st.num_rows):
        dense[r, idx[indptr[r]:indptr[r + 1]]] += w[indptr[r]:indptr[r + 1]]
    assert np.max(np.abs(dense @ moved - st.apply(moved))) <= 1e-12
    # a moved net refines to the moved points
    again = fairsub.subdivide(fairsub.Net(moved, net.faces), "catmull-clark", levels=2)
    assert np.max(np.abs(again.vertices - st.apply(moved))) <= 1e-12


def _png_pixels(path):
    """Decodes an 8-bit RGB PNG (the filters fairsub's encoder uses) into (h, w, 3)."""
    data = path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    pos, idat, w, h = 8, b"", 0, 0
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, colour = struct.unpack(">IIBB", body[:10])
            assert (depth, colour) == (8, 2)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw = zlib.decompress(idat)
    stride = 3 * w
    out = np.zeros((h, stride), dtype=np.int64)
    for y in range(h):
        f = raw[y * (stride + 1)]
        line = np.frombuffer(raw, dtype=np.uint8, count=stride, offset=y * (stride + 1) + 1).astype(np.int64)
        prev = out[y - 1] if y else np.zeros(stride, dtype=np.int64)
        if f == 0:
            out[y] = line
        elif f == 2:
            out[y] = (line + prev) & 255
        else:  # 1 sub, 3 average, 4 paeth: per byte
            cur = np.zeros(stride, dtype=np.int64)
            for x in range(stride):
                a = cur[x - 3] if x >= 3 else 0
                b = prev[x]
                c = prev[x - 3] if x >= 3 else 0
                if f == 1:
                    pred = a
                elif f == 3:
                    pred = (a + b) // 2
                else:
                    p = a + b - c
                    pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                    pred = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                cur[x] = (line[x] + pred) & 255
            out[y] = cur
    return out.reshape(h, w, 3).astype(np.uint8)


def test_render_equals_cli(cli, tmp_path):
    png = tmp_path / "cli.png"
    code, _, err = cli("render", "gallery:cnet-5-saddle", "--scheme", "eg", "--rings", 3,
                       "--mode", "highlight", "--size", "96x64", "-o", png)
    assert code == 0, err
    s = fairsub.surface("gallery:cnet-5-saddle", "eg", rings=3)
    img = fairsub.render(s, "highlight", size=(96, 64))
    assert img.dtype == np.uint8 and img.shape == (64, 96, 3)
    assert np.array_equal(img, _png_pixels(png))


def test_bad_input_raises_the_cli_message(cli, tmp_path):
    bad = tmp_path / "bad.obj"
    bad.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n")
    code, _, err = cli("info", bad)
    assert code == 1
    with pytest.raises(ValueError) as e:
        fairsub.read(str(bad))
    assert err.strip() == f"error: {e.value}"
    code, _, err = cli("subdivide", "gallery:cube", "--scheme", "no-such", "--levels", 1,
                       "-o", tmp_path / "x.obj")
    with pytest.raises(ValueError) as e:
        fairsub.subdivide("gallery:cube", "no-such", levels=1)
    assert err.strip() == f"error: {e.value}"
    with pytest.raises(ValueError, match="shape"):
        fairsub.Net(np.zeros((3, 2)), [[0, 1, 2]])
    with pytest.raises(ValueError):
        fairsub.Net(np.zeros((3, 3)), [[0, 1, 5]])


def test_array_nets_and_file_nets_agree():
    net = fairsub.read("gallery:cube")
    mine = fairsub.Net(net.vertices, net.faces)
    assert mine.source is None and net.source == "gallery:cube"
    a = fairsub.surface(net, "catmull-clark", rings=2)
    b = fairsub.surface(mine, "catmull-clark", rings=2)
    assert all(np.array_equal(p, q) for p, q in zip(a.patches, b.patches))
    assert net.info()["faces"] == 6
    v, f = a.tessellate(4)
    assert v.shape[1] == 3 and f.shape[1] == 3 and f.dtype == np.uint32
