"""`Surface.measure` and `Surface.closest` against `fairsub measure` and `fairsub project`
(the same code path: equal to the last bit), and against facts: the residual of a closest
point is orthogonal to the surface, evaluating at the returned parameters gives the returned
point, and a point of the surface projects onto itself."""

import json

import numpy as np

import fairsub


def test_measure_equals_cli(cli):
    for net, scheme in [("gallery:cube", "catmull-clark"), ("gallery:icosahedron", "loop")]:
        s = fairsub.surface(net, scheme, rings=2)
        code, out, err = cli("measure", net, "--scheme", scheme, "--rings", 2, "--json")
        assert code == 0, err
        mine = s.measure()
        assert mine == json.loads(out)
        assert mine["closed"] and mine["volume"]["volume"] > 0
        assert abs(mine["closure"]) < 1e-13
    # per face: the areas add up to the surface's
    s = fairsub.surface("gallery:cube", "catmull-clark", rings=2)
    m = s.measure(per_face=True)
    assert len(m["faces"]["areas"]) == 6
    assert abs(sum(m["faces"]["areas"]) - m["area"]) < 1e-12 * m["area"]


def test_closest_equals_cli_and_is_orthogonal(cli, tmp_path):
    s = fairsub.surface("gallery:cube", "catmull-clark", rings=3)
    rng = np.random.default_rng(46)
    pts = rng.uniform(-1.5, 1.5, size=(40, 3))
    path = tmp_path / "p.txt"
    path.write_text("".join(f"{float(x)!r} {float(y)!r} {float(z)!r}\n" for x, y, z in pts))
    code, out, err = cli(
        "project", "gallery:cube", "--scheme", "catmull-clark", "--rings", 3,
        "--json", "--points", path,
    )
    assert code == 0, err
    theirs = json.loads(out)
    r = s.closest(pts)
    assert r["face"].dtype == np.uint32 and r["point"].shape == (40, 3)
    for k, c in enumerate(theirs):
        assert int(r["face"][k]) == c["face"]
        assert r["u"][k] == c["u"] and r["v"][k] == c["v"]
        assert list(r["point"][k]) == c["point"] and r["distance"][k] == c["distance"]
    # the residual is along the normal; evaluate at (face, u, v) is the point
    res = pts - r["point"]
    along = np.abs(np.einsum("ij,ij->i", res, r["normal"]))
    assert np.allclose(along, r["distance"], rtol=1e-9, atol=1e-12)
    e = s.evaluate(r["face"], r["u"], r["v"])
    assert np.abs(e["point"] - r["point"]).max() < 1e-14
    # a single point, and a point of the surface onto itself
    one = s.closest(e["point"][3])
    assert one["distance"] < 1e-11
