"""`Surface.evaluate` (numpy arrays filled in parallel, GIL released) equals the Rust call it
wraps (`Surface::evaluate_into`), bit for bit, on every output; arrays are float64 (face uint32,
patch int64) and C-contiguous; the first failing point by index is the one reported."""

import numpy as np
import pytest

import fairsub

VECS = ["point", "du", "dv", "duu", "duv", "dvv", "normal"]


@pytest.mark.parametrize("scheme,net", [
    ("catmull-clark", "torus-evs"), ("loop", "octahedron"), ("doo-sabin", "cube"),
    ("eg", "cnet-5-saddle"),
])
def test_evaluate_equals_the_rust_call(scheme, net):
    s = fairsub.surface(f"gallery:{net}", scheme, rings=3)
    n_faces = fairsub.read(f"gallery:{net}").num_faces
    rng = np.random.default_rng(3)
    n = 5000  # several parallel tasks, the last one partial
    face = rng.integers(0, n_faces, n)
    u, v = rng.random(n), rng.random(n)
    if scheme == "loop":  # a triangle's domain is u + v <= 1
        u, v = u * 0.5, v * 0.5
    got = s.evaluate(face, u, v)
    want = s._rust_evaluations(face, u, v)
    assert want.shape == (n, 29)
    cols = {"face": 0, "u": 1, "v": 2, "patch": 3, "patch_uv": slice(4, 6),
            "gauss": 27, "mean": 28}
    cols.update({k: slice(6 + 3 * i, 9 + 3 * i) for i, k in enumerate(VECS)})
    assert set(got) == set(cols)
    for k, c in cols.items():
        a = got[k]
        assert a.flags["C_CONTIGUOUS"], k
        assert a.dtype == {"face": np.uint32, "patch": np.int64}.get(k, np.float64), k
        assert a.shape == ((n, 3) if k in VECS else (n, 2) if k == "patch_uv" else (n,)), k
        assert np.array_equal(a.astype(np.float64), want[:, c], equal_nan=True), k
    assert np.array_equal(got["face"], face) and np.array_equal(got["u"], u)


def test_the_first_failing_point_is_reported():
    s = fairsub.surface("gallery:cube", "catmull-clark", rings=2)
    n = 3000
    face = np.zeros(n, dtype=np.int64)
    u = np.full(n, 0.5)
    v = np.full(n, 0.5)
    face[2900] = -1
    u[1700] = 2.0  # outside the domain of a quad
    with pytest.raises(ValueError, match="outside its domain"):
        s.evaluate(face, u, v)
    u[1700] = 0.5
    with pytest.raises(ValueError, match="point 2900: face -1 does not exist"):
        s.evaluate(face, u, v)
