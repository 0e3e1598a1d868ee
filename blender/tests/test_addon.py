"""The add-on beyond Catmull-Clark parity: the scheme menu and options come from the package,
crease attributes round-trip, the source is left alone, the other schemes give the counts
their structure implies, the exact surface carries its exact data, and the shape tools measure,
colour, render and export."""

import json

import fairsub
import numpy as np
import pytest

from conftest import (
    TOL,
    attribute_values,
    bpy,
    matching,
    modifier_mesh,
    positions,
    primitive,
    size,
    snapshot,
)
from fairsub_blender import catalogue, convert, measure
from test_modifier_parity import crease


def active():
    return bpy.context.active_object


def test_the_scheme_menu_is_the_catalogue(empty):
    items = bpy.ops.fairsub.subdivide.get_rna_type().properties["scheme"].enum_items
    assert [i.identifier for i in items] == [s["name"] for s in fairsub.schemes()]
    # every option of every scheme has a property, except those the operator sets itself
    props = bpy.ops.fairsub.subdivide.get_rna_type().properties
    for s in fairsub.schemes():
        for o in fairsub.scheme_options(s["name"]):
            if o["name"] not in catalogue.OWN:
                assert catalogue.prop_name(o["name"]) in props, (s["name"], o["name"])


def test_a_schemes_option_reaches_fairsub(empty):
    """tps-adjustable's split ratio: 1/3 is TPS; another ratio moves the points."""
    primitive("cube")
    src = active()
    bpy.ops.fairsub.subdivide(scheme="tps-adjustable", levels=1)
    a = positions(active().data)
    bpy.context.view_layer.objects.active = src
    bpy.ops.fairsub.subdivide(scheme="tps-adjustable", levels=1, opt_split_ratio="0.25")
    b = positions(active().data)
    assert a.shape == b.shape and np.abs(a - b).max() > 1e-3


def test_crease_values_round_trip(empty):
    """Blender crease -> OpenSubdiv sharpness (c * c * 10 in single precision, as Blender's
    modifier maps it) -> fairsub's net -> back to a crease of exactly that sharpness, within
    a few units in the last place of the crease itself."""
    ob = primitive("suzanne")
    me = ob.data
    rng = np.random.default_rng(7)
    c_edge = rng.uniform(0.0, 1.0, len(me.edges)).astype(np.float32)
    c_edge[::3] = 0.0
    c_edge[1::11] = 1.0
    c_vert = rng.uniform(0.0, 1.0, len(me.vertices)).astype(np.float32)
    c_vert[::2] = 0.0
    me.attributes.new("crease_edge", "FLOAT", "EDGE").data.foreach_set("value", c_edge)
    me.attributes.new("crease_vert", "FLOAT", "POINT").data.foreach_set("value", c_vert)
    a = convert.MeshArrays(me)
    vertices, faces, kw, kept = convert.net_arguments(a)
    net = fairsub.Net(vertices, faces, tolerant=True, **kw)
    edges, s = net.creases
    expect = convert.crease_to_sharpness(c_edge)
    idx = convert.edge_index(me, kept[edges.astype(np.int64)])
    assert (idx >= 0).all() and len(idx) == np.count_nonzero(expect)
    assert np.array_equal(s, expect[idx])
    back = convert.sharpness_to_crease(s)
    assert np.array_equal(convert.crease_to_sharpness(back), s)
    ulps = np.abs(back.view(np.int32) - c_edge[idx].view(np.int32))
    assert ulps.max() <= 4
    verts, vs = net.corners
    assert np.array_equal(vs, convert.crease_to_sharpness(c_vert)[kept[verts]])
    assert len(vs) == np.count_nonzero(c_vert)


@pytest.mark.parametrize("name", ["cube", "suzanne", "cylinder"])
def test_refined_creases_continue_the_surface(empty, name):
    """The result carries its refined sharpness as creases: one fairsub level, then Blender's
    modifier for one or two more, equals Blender's modifier for two or three levels on the
    source (creased edges and vertices, semi-sharp and sharp)."""
    ob = primitive(name)
    crease(ob)
    for more in (1, 2):
        ref = modifier_mesh(ob, 1 + more, "PRESERVE_CORNERS")
        bpy.context.view_layer.objects.active = ob
        bpy.ops.fairsub.subdivide(scheme="catmull-clark", levels=1, boundary="edge-and-corner")
        res = active()
        assert "crease_edge" in res.data.attributes
        stacked = modifier_mesh(res, more, "PRESERVE_CORNERS")
        idx, dist = matching(ref, stacked)
        assert len(stacked.vertices) == len(ref.vertices)
        assert dist.max() <= TOL * size(ob.data), dist.max()


def test_creases_matter(empty):
    """Without its creases the result is far from Blender's creased one (so the parity tests
    with creases see them)."""
    ob = primitive("cube")
    crease(ob)
    ref = modifier_mesh(ob, 2, "ALL")
    bpy.ops.fairsub.subdivide(scheme="catmull-clark", levels=2, use_creases=False)
    _, dist = matching(ref, active().data)
    assert dist.max() > 1e-2


def test_the_source_is_left_alone(empty):
    ob = primitive("suzanne")
    crease(ob)
    ob.data.uv_layers.new(name="second")
    before = snapshot(ob)
    for kw in (
        dict(scheme="catmull-clark", levels=2),
        dict(scheme="loop", levels=1),
        dict(scheme="eg", levels=0, rings=2, density=3),
        dict(scheme="catmull-clark", levels=2, use_modifiers=True),
    ):
        bpy.context.view_layer.objects.active = ob
        try:
            bpy.ops.fairsub.subdivide(**kw)
        except RuntimeError:
            pass  # Loop refuses quads (tested below); the source must still be as it was
        assert snapshot(ob) == before
        assert active() is not ob or kw["scheme"] == "loop"
    assert len(bpy.data.objects) == 4


def test_two_uv_maps_are_carried(empty):
    ob = primitive("uv_sphere")
    ob.data.uv_layers.new(name="second")
    ref = modifier_mesh(ob, 1)
    bpy.ops.fairsub.subdivide(scheme="catmull-clark", levels=1)
    res = active().data
    assert [u.name for u in res.uv_layers] == [u.name for u in ref.uv_layers]


def test_loop_counts(empty):
    """Loop on Blender's icosphere (80 triangles): 40 * 4^L + 2 vertices, 80 * 4^L
    triangles."""
    primitive("ico_sphere")
    src = active()
    for levels in (1, 2, 3):
        bpy.context.view_layer.objects.active = src
        bpy.ops.fairsub.subdivide(scheme="loop", levels=levels)
        me = active().data
        assert len(me.vertices) == 40 * 4**levels + 2
        assert len(me.polygons) == 80 * 4**levels
        assert all(p.loop_total == 3 for p in me.polygons)


def test_loop_refuses_quads_with_fairsubs_message(empty):
    primitive("cube")
    with pytest.raises(RuntimeError, match="triangle net"):
        bpy.ops.fairsub.subdivide(scheme="loop", levels=1)


def test_patch_only_schemes_need_levels_zero(empty):
    primitive("cube")
    with pytest.raises(RuntimeError, match="levels to 0"):
        bpy.ops.fairsub.subdivide(scheme="eg", levels=1)


def closed_surface_euler(me):
    """V - E + F of a mesh whose every edge has exactly two faces (else an assertion fails)."""
    le = np.empty(len(me.loops), dtype=np.int32)
    me.loops.foreach_get("edge_index", le)
    assert (np.bincount(le, minlength=len(me.edges)) == 2).all(), "not a closed surface"
    return len(me.vertices) - len(me.edges) + len(me.polygons)


@pytest.mark.parametrize("scheme", ["eg", "guided-bi5", "guided-bi6", "qas-plus"])
@pytest.mark.parametrize("rings", [1, 2, 3])
def test_exact_surface_counts(empty, scheme, rings):
    """The cube's eight valence-3 vertices each own three faces after the first step; every
    ring adds three patches per sector and the cap one per sector: 8 (9 rings + 3) patches.
    The tessellation is a closed sphere (Euler characteristic 2) whose every patch has its
    triangles, 2 n^2 each where no finer neighbour adds points (one ring: everywhere)."""
    primitive("cube")
    n = 3
    bpy.ops.fairsub.subdivide(scheme=scheme, levels=0, rings=rings, density=n)
    me = active().data
    p = 8 * (9 * rings + 3)
    patch = attribute_values(me.attributes["fairsub_patch"]).astype(int)
    per_patch = np.bincount(patch)
    assert len(per_patch) == p and per_patch.min() >= 2 * n * n
    if rings == 1:
        assert (per_patch == 2 * n * n).all() and len(me.vertices) == n * n * p + 2
    assert closed_surface_euler(me) == 2


def test_torus_is_regular(empty):
    """The torus's 576 quads are all regular: one bicubic patch each, 2 n^2 triangles per
    patch, genus 1 (Euler characteristic 0, n^2 P vertices)."""
    primitive("torus")
    bpy.ops.fairsub.subdivide(scheme="eg", levels=0, rings=2, density=2)
    me = active().data
    assert len(me.polygons) == 2 * 4 * 576 and len(me.vertices) == 4 * 576
    assert closed_surface_euler(me) == 0


def test_exact_surface_data(empty):
    """The exact surface's normals and curvatures: at the vertices of the UV sphere's exact
    Catmull-Clark surface, the Gauss and mean curvature attributes are those of the vertex's
    patch at its domain point, recomputed here from the Bezier coefficients (Bernstein
    derivatives, fundamental forms), and the custom normals are the exact normals."""
    primitive("uv_sphere")
    bpy.ops.fairsub.subdivide(scheme="catmull-clark", levels=0, rings=2, density=3)
    me = active().data
    assert me.has_custom_normals and "fairsub_curvature" in me.color_attributes
    s = fairsub.surface(_net_of(bpy.data.objects["Sphere"]), "catmull-clark", rings=2, boundary="edge-only")
    t = s.tessellation(3)
    assert np.abs(positions(me) - t["vertices"]).max() < 1e-6
    gauss = attribute_values(me.attributes["fairsub_gauss"])
    mean = attribute_values(me.attributes["fairsub_mean"])
    lv = np.empty(len(me.loops), dtype=np.int32)
    me.loops.foreach_get("vertex_index", lv)
    cn = np.empty(len(me.loops) * 3, dtype=np.float32)
    me.corner_normals.foreach_get("vector", cn)
    normal = np.zeros((len(me.vertices), 3))
    normal[lv] = cn.reshape(-1, 3)
    patches = s.patches
    worst = [0.0, 0.0]
    for v in range(0, len(me.vertices), 7):
        cps = patches[t["patch"][v]]
        (u, w) = t["patch_uv"][v]
        bu, dbu = measure._bernstein(cps.shape[0] - 1, [u])
        bv, dbv = measure._bernstein(cps.shape[1] - 1, [w])
        ddu = _second(cps.shape[0] - 1, u)
        ddv = _second(cps.shape[1] - 1, w)
        xu = np.einsum("i,ijc,j->c", dbu[0], cps, bv[0])
        xv = np.einsum("i,ijc,j->c", bu[0], cps, dbv[0])
        xuu = np.einsum("i,ijc,j->c", ddu, cps, bv[0])
        xuv = np.einsum("i,ijc,j->c", dbu[0], cps, dbv[0])
        xvv = np.einsum("i,ijc,j->c", bu[0], cps, ddv)
        n = np.cross(xu, xv)
        if np.linalg.norm(n) < 1e-9 * np.linalg.norm(xu) * np.linalg.norm(xv):
            continue  # a collapsed corner: fairsub steps inside the patch there
        n /= np.linalg.norm(n)
        E, F, G = xu @ xu, xu @ xv, xv @ xv
        L, M, N = xuu @ n, xuv @ n, xvv @ n
        K = (L * N - M * M) / (E * G - F * F)
        H = (E * N - 2 * F * M + G * L) / (2 * (E * G - F * F))
        worst[0] = max(worst[0], abs(K - gauss[v]) / max(1.0, abs(K)))
        worst[1] = max(worst[1], abs(H - mean[v]) / max(1.0, abs(H)))
    assert worst[0] < 1e-5 and worst[1] < 1e-5, worst
    # Blender keeps custom normals compressed (16-bit values in each corner's normal space):
    # 5.8e-4 measured here
    assert np.abs(normal - t["normals"]).max() < 1e-3


def _second(d, t):
    """Second derivatives of the Bernstein polynomials of degree d at t."""
    if d < 2:
        return np.zeros(d + 1)
    b = measure._bernstein(d - 2, [t])[0][0]
    out = np.zeros(d + 1)
    out[:-2] += b
    out[1:-1] -= 2 * b
    out[2:] += b
    return d * (d - 1) * out


def test_measure_a_flat_grid_exactly(empty):
    """The grid's exact surface with corners kept is the flat 2 x 2 square: area 4."""
    primitive("grid")
    bpy.context.scene.fairsub.boundary = "edge-and-corner"
    bpy.ops.fairsub.subdivide(scheme="catmull-clark", levels=0, rings=2, boundary="edge-and-corner")
    bpy.ops.fairsub.measure()
    m = json.loads(active()["fairsub_measure"])
    assert abs(m["area"] - 4.0) < 1e-12 and not m["closed"] and m["volume"] is None


@pytest.mark.parametrize("name", ["cube", "torus"])
def test_measure_agrees_with_fine_tessellations(empty, name):
    """Area, volume and centroid of the closed exact surface against those of its watertight
    tessellations at densities 16 and 32, extrapolated (their error falls as 1 / n^2)."""
    src = primitive(name)
    bpy.ops.fairsub.subdivide(scheme="catmull-clark", levels=0, rings=4, density=4)
    bpy.ops.fairsub.measure()
    m = json.loads(active()["fairsub_measure"])
    assert m["closed"]
    s = fairsub.surface(_net_of(src), "catmull-clark", rings=4, boundary="edge-only")
    assert m == dict(measure.measure(s), scheme="catmull-clark", rings=4)
    est = {}
    for n in (16, 32):
        t = s.tessellation(n)
        v, tri = t["vertices"], t["triangles"]
        a, b, c = v[tri[:, 0]], v[tri[:, 1]], v[tri[:, 2]]
        cr = np.cross(b - a, c - a)
        vol6 = np.einsum("ij,ij->i", a, np.cross(b, c))
        est[n] = (
            np.linalg.norm(cr, axis=1).sum() / 2,
            vol6.sum() / 6,
            ((a + b + c) / 4 * vol6[:, None] / 6).sum(axis=0) / (vol6.sum() / 6),
        )
    rich = [(4 * x - y) / 3 for x, y in zip(est[32], est[16])]
    assert abs(rich[0] - m["area"]) < 1e-6 * m["area"]
    assert abs(rich[1] - m["volume"]) < 1e-6 * abs(m["volume"])
    assert np.abs(rich[2] - np.array(m["centroid"])).max() < 1e-6 * size(src.data)


def _net_of(ob):
    a = convert.MeshArrays(ob.data)
    vertices, faces, kw, _ = convert.net_arguments(a)
    return fairsub.Net(vertices, faces, tolerant=True, **kw)


def test_shape_tools(empty, tmp_path):
    primitive("suzanne")
    bpy.ops.fairsub.subdivide(scheme="catmull-clark", levels=0, rings=2, density=3)
    res = active()
    assert bpy.ops.fairsub.curvature(kind="gauss") == {"FINISHED"}
    info = json.loads(res["fairsub_curvature"])
    assert info["kind"] == "gauss" and info["range"] > 0
    assert res.data.materials[0].name == "fairsub curvature"
    colours = attribute_values(res.data.color_attributes["fairsub_curvature"]).reshape(-1, 4)
    gauss = attribute_values(res.data.attributes["fairsub_gauss"])
    assert (colours[gauss > 0.5 * info["range"], 0] > colours[gauss > 0.5 * info["range"], 2]).all()
    assert bpy.ops.fairsub.highlight_lines() == {"FINISHED"}
    assert res.data.materials[0].name == "fairsub highlight lines"
    assert bpy.ops.fairsub.render(mode="highlight", width=120, height=90) == {"FINISHED"}
    img = bpy.data.images[f"fairsub {res.name} highlight"]
    px = np.empty(120 * 90 * 4, dtype=np.float32)
    img.pixels.foreach_get(px)
    assert tuple(img.size) == (120, 90) and px.reshape(-1, 4)[:, :3].std() > 0.05
    path = tmp_path / "suzanne.igs"
    assert bpy.ops.fairsub.export(filepath=str(path)) == {"FINISHED"}
    text = path.read_text()
    assert "Bezier patches as IGES 5.3 entity 128" in text.splitlines()[0]


def test_curvature_needs_the_exact_surface(empty):
    primitive("cube")
    bpy.ops.fairsub.subdivide(scheme="catmull-clark", levels=1)
    with pytest.raises(RuntimeError, match="levels 0"):
        bpy.ops.fairsub.curvature()


def test_the_subdivide_panel_settings(empty):
    """The scene's settings hold the same properties as the operator (the panel's button
    copies them over)."""
    s = bpy.context.scene.fairsub
    op = bpy.ops.fairsub.subdivide.get_rna_type().properties
    for key in s.bl_rna.properties.keys():
        if key not in ("rna_type", "name"):
            assert key in op
    assert s.boundary == "edge-only" and s.fvar == "boundaries"  # Blender's defaults
    assert s.levels == 1
