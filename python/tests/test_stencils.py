"""Patch stencil tables from Python (``Surface.stencils()``): for every scheme that writes
patches, the table equals the command line's ``subdivide --rings K --stencils FILE`` weight for
weight, and re-applied to moved control points it equals the surface recomputed from the moved
net to 1e-12 (same patches, degrees, coefficients)."""

import math

import numpy as np
import pytest

import fairsub
from test_against_cli import RINGS


def read_table(path):
    """The patch table file as the README documents it: (patch lines, CSR arrays)."""
    lines = path.read_text().splitlines()
    assert lines[0] == "fairsub-patch-table 2"
    head = dict(l.split() for l in lines[1:8])
    npatch, nrows, ncaps, nmaps = (int(head[k]) for k in ("patches", "rows", "caps", "capmaps"))
    k = 8
    patches = [l.split() for l in lines[k:k + npatch]]
    k += npatch + ncaps
    for _ in range(nmaps):
        k += 1 + int(lines[k].split()[3])
    indptr, idx, w = [0], [], []
    for l in lines[k:k + nrows]:
        t = l.split()
        assert t[0] == "r"
        idx += [int(x) for x in t[2::2]]
        w += [float(x) for x in t[3::2]]
        indptr.append(len(idx))
    assert lines[-1] == "end"
    return patches, np.array(indptr), np.array(idx), np.array(w)


def moved(vertices, seed, size=0.1):
    rng = np.random.default_rng(seed)
    return vertices + size * rng.uniform(-1.0, 1.0, vertices.shape)


@pytest.mark.parametrize("scheme", sorted(RINGS))
def test_table_equals_cli_and_recomputed_surfaces(scheme, cli, tmp_path):
    src = f"gallery:{RINGS[scheme]}"
    bv, tab = tmp_path / "s.bv", tmp_path / "s.tab"
    code, _, err = cli("subdivide", src, "--scheme", scheme, "--rings", 2, "-o", bv,
                       "--stencils", tab)
    assert code == 0, err
    s = fairsub.surface(src, scheme, rings=2)
    t = s.stencils()
    assert len(t) == len(s)
    # the CLI's file, weight for weight (shortest round-trip decimals read back exactly)
    patches, indptr, idx, w = read_table(tab)
    mine = t.csr()
    assert np.array_equal(mine[0], indptr)
    assert np.array_equal(mine[1], idx)
    assert np.array_equal(mine[2], w)
    assert [(int(p[1]), int(p[2])) for p in patches] == list(t.shapes)
    assert [p[4] == "cap" for p in patches] == t.cap_patches
    # written from Python: the same bytes
    py_tab = tmp_path / "py.tab"
    t.write(str(py_tab))
    assert py_tab.read_bytes() == tab.read_bytes()
    # at the net's points: the surface itself
    net = fairsub.read(src)
    for a, b in zip(t.apply(net.vertices), s.patches):
        assert a.shape == b.shape and a.dtype == np.float64 and a.flags["C_CONTIGUOUS"]
        assert np.max(np.abs(a - b)) <= 1e-12
    # at moved points: the surface recomputed from the moved net
    for seed in (1, 2):
        pts = moved(net.vertices, seed)
        again = fairsub.surface(fairsub.Net(pts, net.faces), scheme, rings=2)
        got = t.apply(pts)
        assert len(got) == len(again.patches)
        assert again.provenance == s.provenance
        for a, b in zip(got, again.patches):
            assert a.shape == b.shape
            assert np.max(np.abs(a - b)) <= 1e-12


def test_per_point_data_and_the_csr_rows():
    s = fairsub.surface("gallery:torus-evs", "catmull-clark", rings=2)
    t = s.stencils()
    net = fairsub.read("gallery:torus-evs")
    n = t.num_sources
    assert n == net.num_vertices
    # the linear rows are the CSR matrix applied to the points
    indptr, idx, w = t.csr()
    rows = np.zeros((t.num_rows, 3))
    for r in range(t.num_rows):
        a, b = indptr[r], indptr[r + 1]
        rows[r] = w[a:b] @ net.vertices[idx[a:b]]
    first = t.first_rows
    for p, (patch, cap) in enumerate(zip(t.apply(net.vertices), t.cap_patches)):
        if not cap:
            m = patch.shape[0] * patch.shape[1]
            assert np.max(np.abs(rows[first[p]:first[p] + m] - patch.reshape(m, 3))) <= 1e-12
    # data of any width: constants stay constant, caps included
    data = np.column_stack([np.full(n, 2.5), np.arange(n, dtype=float)])
    out = t.apply(data)
    assert all(o.shape[2] == 2 for o in out)
    assert max(np.max(np.abs(o[:, :, 0] - 2.5)) for o in out) <= 1e-11
    with pytest.raises(ValueError, match=f"takes {n} points, not 3"):
        t.apply(net.vertices[:3])


def test_tables_the_construction_cannot_give_raise(tmp_path):
    # non-box's fill at a boundary vertex of more quads (65) than a G^1 cap takes projects a
    # chord onto a plane: no table (tri-grid's corners get open-fan caps since 2026-12-04)
    k = 65
    lines = ["v 0 0 0"]
    for i in range(2 * k + 1):
        t = math.pi * i / (2 * k)
        r = 1.0 if i % 2 == 0 else 1.4
        lines.append(f"v {r * math.cos(t)} {r * math.sin(t)} {0.1 * math.sin(3 * t)}")
    lines += [f"f 1 {2 * j + 2} {2 * j + 3} {2 * j + 4}" for j in range(k)]
    fan = tmp_path / "fan.obj"
    fan.write_text("\n".join(lines) + "\n")
    s = fairsub.surface(str(fan), "nonbox", rings=2)
    with pytest.raises(ValueError, match="not linear in the control points"):
        s.stencils()
