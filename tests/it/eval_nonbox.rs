//! Evaluation of non-box subdivision at `(face, u, v)`: a quad face is `[0, 1]^2`, an n-gon
//! (triangles included) the strip of its quad sub-faces, as for Catmull-Clark; every cell of
//! a face is covered by the four cubic S_3^1 triangles of its criss-cross (the cell split by
//! both diagonals, `surface::eval`'s `crisscross`), ring cells by theirs one level down, the
//! G^1 cap sectors by one patch with `(0, 0)` at the extraordinary vertex, the Coons fill
//! cells by one patch with the cell's corners. Tests as for the other schemes: agreement with
//! the patches `subdivide --rings` writes at random points of every face (caps included),
//! continuity across every line of a dyadic grid of every face (a triangle placed in the wrong
//! quarter of its cell jumps there), convergence to the limit point at the scheme's `lambda`
//! per ring, and the centre is the paper's limit point.
//!
//! `nonbox-4dir` on a quasi-four-directional triangle mesh evaluates on its triangles, each
//! the fan triangle `(V_i, V_(i+1), FCV)` of a polygon of the net with FCVs its complex is
//! built on (`bezier::domain::FanTriangle`): tested against the written patches, against
//! `nonbox` on the polygon net, for continuity across the triangles' edges and inside them,
//! and for convergence at `lambda`.

use fairsub::analysis::report;
use fairsub::geom::dist;
use fairsub::mesh::PolyMesh;
use fairsub::schemes::nonbox::{FcvNet, NonBox};
use fairsub::schemes::registry::{ids, registry};
use fairsub::surface::eval::Surface;

use crate::eval_helpers::faces;
use crate::eval_helpers::ratios;
use crate::eval_helpers::support;
use faces::{agrees_at, all_agree, all_continuous, surface_of};
use ratios::converges;
use support::{Lcg, gallery, tmp, toward_ev, written_from};

/// `fairsub analyze`'s subdominant eigenvalue of `scheme` at valence `n`.
fn lambda(scheme: &str, n: usize) -> f64 {
    let spec = registry().lookup(scheme).expect("scheme");
    report::analyze(&spec, n, false)
        .expect("analysis")
        .spectrum
        .lambda
}

#[test]
fn nonbox_eval_agrees_with_the_written_patches() {
    // closed nets (valences 3 to 5, triangles and pentagons, FCVs off the barycentres) and
    // c-nets with a boundary (boundary vertices with more than two faces get the fill)
    all_agree(
        &[ids::NONBOX.name()],
        &[
            "cube",
            "prism-5",
            "tetrahedron",
            "torus-evs",
            "nonbox-cube-fcv-1.5",
            "cnet-5-saddle",
            "cnet-3-saddle",
        ],
        &[1, 2, 3, 1, 2, 2, 3],
        &|_, _| true,
    );
}

#[test]
fn nonbox_evaluation_is_continuous_across_patch_boundaries() {
    all_continuous(
        &[ids::NONBOX.name()],
        &["cube", "prism-5", "tetrahedron", "nonbox-cube-fcv-0.5"],
    );
}

#[test]
fn nonbox_limit_evaluation_converges_at_rate_lambda() {
    let scheme = ids::NONBOX.name();
    for n in [3, 5, 6] {
        let mesh = gallery(&format!("cnet-{n}-saddle"));
        let (ev, at) = toward_ev(&mesh, n);
        let l = lambda(scheme, n);
        let published = 0.5 + (2.0 * std::f64::consts::PI / n as f64).cos() / 4.0;
        assert!((l - published).abs() < 1e-12, "n = {n}: {l} vs {published}");
        let (centre, _) = converges(scheme, &mesh, at, l, 12, &format!("vertex n = {n}"));
        // the cap's centre is the paper's limit point of the vertex
        let net = FcvNet::from_mesh(&mesh);
        let limit = NonBox::limit_stencil(&net, ev).apply(&net.points());
        assert!(
            dist(centre, limit) < 1e-12,
            "n = {n}: centre {centre:?}, limit point {limit:?}"
        );
    }
}

/// The quasi-four-directional triangle mesh of gallery net `name` (fanned around its FCVs,
/// the FCVs last), written to an OBJ file and read back (the CLI reads the same file).
fn four_dir_mesh(name: &str) -> (PolyMesh, String) {
    let net = fairsub::schemes::nonbox::fourdir::triangulate(&FcvNet::from_mesh(&gallery(name)));
    let path = tmp("fairsub-eval-nonbox", &format!("{name}-4dir.obj"));
    fairsub::io::write_mesh(&path, &net.mesh, fairsub::io::MeshFormat::Obj).expect("write");
    let back = fairsub::io::read_mesh(&path).expect("read back").mesh;
    (back, path.to_str().expect("utf-8 path").to_string())
}

/// `per_face` random barycentric points of every triangle, half of them within `2^-6` of a
/// corner, and the corners.
fn triangle_points(mesh: &PolyMesh, per_face: usize, seed: u64) -> Vec<(u32, f64, f64)> {
    let mut r = Lcg(seed);
    let mut pts = Vec::new();
    for f in 0..mesh.num_faces() as u32 {
        for k in 0..per_face {
            let (mut u, mut v) = (r.next(), r.next());
            if u + v > 1.0 {
                (u, v) = (1.0 - u, 1.0 - v);
            }
            if k % 2 == 1 {
                let s = 1.0 / 64.0;
                (u, v) = match (r.next() * 3.0) as usize {
                    0 => (s * u, s * v),
                    1 => (1.0 - s * (u + v), s * v),
                    _ => (s * u, 1.0 - s * (u + v)),
                };
            }
            pts.push((f, u, v));
        }
        pts.extend([(f, 0.0, 0.0), (f, 1.0, 0.0), (f, 0.0, 1.0)]);
    }
    pts
}

#[test]
fn nonbox_4dir_eval_agrees_with_the_written_patches() {
    let scheme = ids::NONBOX_4DIR.name();
    for (name, rings) in [("cube", 2), ("prism-5", 2), ("cnet-5-saddle", 3)] {
        let (mesh, src) = four_dir_mesh(name);
        let written = written_from(&src, &format!("{name}-4dir"), scheme, rings);
        let (mesh, s) = surface_of(mesh, scheme, rings);
        let pts = triangle_points(&mesh, 40, 11);
        let (worst, in_caps) = agrees_at(&written, &mesh, &s, &pts, &|_, _| true);
        eprintln!(
            "{name} (4dir) under {scheme}, {rings} rings: largest difference {worst:.3e}, {in_caps} points on caps"
        );
        assert!(worst <= 1e-12, "{name}: {worst:e}");
        assert!(in_caps > 0, "{name}: no point on a cap");
    }
}

/// On the triangles of the four-directional mesh the evaluation is `nonbox`'s on the polygon
/// net at the fan triangle's host point (the same limit surface): on a quad host the triangle
/// `(V_i, V_(i+1), FCV)` is triangle `i` of the cell's criss-cross,
/// `(x, y) = V_i + s (V_(i+1) - V_i) + t (centre - V_i)` at its barycentric `(s, t)`; and it
/// is continuous across the triangles' edges (each edge point evaluated from both triangles).
#[test]
fn nonbox_4dir_triangles_are_fan_triangles_of_the_polygons() {
    let (mesh, _) = four_dir_mesh("cube");
    let (_, tri) = surface_of(mesh.clone(), ids::NONBOX_4DIR.name(), 2);
    let (cube, quad) = surface_of(gallery("cube"), ids::NONBOX.name(), 2);
    // triangle 4 f + i is (c_i, c_(i+1), FCV_f) of cube face f (`triangulate`'s order)
    let corners = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    let mut worst: f64 = 0.0;
    for (t, u, v) in triangle_points(&mesh, 20, 3) {
        let (f, i) = (t as usize / 4, t as usize % 4);
        assert_eq!(cube.face(f)[i], mesh.face(t as usize)[0]);
        let (c, d) = (corners[i], corners[(i + 1) % 4]);
        let x = c[0] + u * (d[0] - c[0]) + v * (0.5 - c[0]);
        let y = c[1] + u * (d[1] - c[1]) + v * (0.5 - c[1]);
        let a = tri.evaluate(t, u, v).expect("triangle point");
        let b = quad.evaluate(f as u32, x, y).expect("quad point");
        worst = worst.max(dist(a.point, b.point));
        // derivatives by the chain rule of the affine map
        let du = fairsub::geom::add(
            fairsub::geom::scale(b.du, d[0] - c[0]),
            fairsub::geom::scale(b.dv, d[1] - c[1]),
        );
        assert!(
            dist(a.du, du) < 1e-10,
            "face {t} at ({u}, {v}): {:?} {du:?}",
            a.du
        );
        if b.gauss.is_finite() {
            assert!((a.gauss - b.gauss).abs() <= 1e-9 * b.gauss.abs().max(1.0));
        }
    }
    eprintln!("4dir triangles vs nonbox quads: largest difference {worst:.3e}");
    assert!(worst < 1e-12, "{worst:e}");
    for name in ["cube", "prism-5", "tetrahedron"] {
        let (mesh, _) = four_dir_mesh(name);
        let (_, s) = surface_of(mesh.clone(), ids::NONBOX_4DIR.name(), 3);
        let jump = edge_jump(&mesh, &s).max(median_jump(&mesh, &s));
        eprintln!("{name} (4dir): largest jump {jump:.3e}");
        assert!(jump < 1e-7, "{name}: jump {jump:e}");
    }
}

/// Largest distance between the evaluations of an edge point from the two triangles at the
/// edge (barycentric: corner `a` at `(0, 0)`, `(1, 0)`, `(0, 1)` for corners 0, 1, 2).
fn edge_jump(mesh: &PolyMesh, s: &Surface) -> f64 {
    let bary = |k: usize, x: f64| -> (f64, f64) {
        // the point at x along edge k -> k + 1
        let c = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
        let (p, q) = (c[k], c[(k + 1) % 3]);
        (p[0] + x * (q[0] - p[0]), p[1] + x * (q[1] - p[1]))
    };
    let mut worst: f64 = 0.0;
    for t in 0..mesh.num_faces() {
        let face = mesh.face(t);
        for k in 0..3 {
            let (a, b) = (face[k], face[(k + 1) % 3]);
            let Some(h) = mesh.find_halfedge(b as usize, a as usize) else {
                continue;
            };
            let g = mesh.he_face(h) as usize;
            let j = mesh.face(g).iter().position(|&w| w == b).expect("corner");
            for i in 0..=16 {
                let x = f64::from(i) / 16.0;
                let (u, v) = bary(k, x);
                let (u2, v2) = bary(j, 1.0 - x);
                let p = s.evaluate(t as u32, u, v).expect("point");
                let q = s.evaluate(g as u32, u2, v2).expect("point");
                worst = worst.max(dist(p.point, q.point));
            }
        }
    }
    worst
}

/// Largest jump across the lines `u = i / 64`, `v = i / 64` and `u + v = i / 64` inside every
/// triangle (points 2e-10 apart): the fan triangle's halves over two sub-faces, the cells of
/// the rings and the caps' edges.
fn median_jump(mesh: &PolyMesh, s: &Surface) -> f64 {
    let d = 1e-10;
    let mut worst: f64 = 0.0;
    for t in 0..mesh.num_faces() as u32 {
        for i in 1..64 {
            let x = f64::from(i) / 64.0;
            for k in 1..16 {
                let y = (1.0 - x) * f64::from(k) / 16.0;
                for (a, b) in [
                    ((x - d, y), (x + d, y)),
                    ((y, x - d), (y, x + d)),
                    ((x - y - d, y), (x - y + d, y)),
                ] {
                    let ok = |p: (f64, f64)| p.0 >= 0.0 && p.1 >= 0.0 && p.0 + p.1 <= 1.0;
                    if !ok(a) || !ok(b) {
                        continue;
                    }
                    let p = s.evaluate(t, a.0, a.1).expect("point");
                    let q = s.evaluate(t, b.0, b.1).expect("point");
                    worst = worst.max(dist(p.point, q.point));
                }
            }
        }
    }
    worst
}

#[test]
fn nonbox_4dir_limit_evaluation_converges_at_rate_lambda() {
    let scheme = ids::NONBOX_4DIR.name();
    for n in [3, 5] {
        let (mesh, _) = four_dir_mesh(&format!("cnet-{n}-saddle"));
        // a type-1 vertex of valence n has 2 n triangle neighbours
        let (_, at) = toward_ev(&mesh, 2 * n);
        let l = lambda(scheme, n);
        converges(scheme, &mesh, at, l, 12, &format!("vertex n = {n} (4dir)"));
    }
}

/// `net` with each vertex moved by up to `amount` in each coordinate (deterministic), so that
/// no symmetry of the net makes two halves of a patch equal in area.
fn perturbed(mut net: PolyMesh, amount: f64, seed: u64) -> PolyMesh {
    let mut r = Lcg(seed);
    let pos = net
        .positions()
        .iter()
        .map(|p| p.map(|x| x + amount * (2.0 * r.next() - 1.0)))
        .collect();
    net.set_positions(pos);
    net
}

/// `measure --json --per-face`'s areas (and the unassigned area, and the total) of the
/// surface of `mesh` under `scheme` with `rings`.
fn per_face_areas(mesh: &PolyMesh, scheme: &str, rings: usize) -> (Vec<f64>, f64, f64) {
    let spec = registry().lookup(scheme).expect("scheme");
    let opts = fairsub::surface::ComplexOptions { rings, fill: true };
    let c = fairsub::surface::build(&spec, mesh, opts, &mut |_| {})
        .expect("complex")
        .complex;
    let json = fairsub::cli::api::measure_json("net", &c, &spec, mesh, true, 1e-14)
        .expect("per-face areas");
    let v: serde_json::Value = serde_json::from_str(&json).expect("json");
    let areas = v["faces"]["areas"]
        .as_array()
        .expect("areas")
        .iter()
        .map(|a| a.as_f64().expect("number"))
        .collect();
    let unassigned = v["faces"]["unassigned"].as_f64().expect("unassigned");
    (areas, unassigned, v["area"].as_f64().expect("area"))
}

/// The area over triangle `t` of the surface `s` of a triangle mesh, from `eval`: the
/// integral of `|du x dv|` over the triangle's barycentric domain, on its `4^levels` corner and
/// middle sub-triangles with the collapsed 6 x 6 Gauss rule each (independent of the
/// patches' areas: the evaluation's own fan-triangle map and chain rule).
fn area_by_eval(s: &Surface, t: u32, levels: u32) -> f64 {
    // 6-point Gauss-Legendre on [0, 1]
    let g = [
        (0.033_765_242_898_424, 0.085_662_246_189_585),
        (0.169_395_306_766_868, 0.180_380_786_524_069),
        (0.380_690_406_958_402, 0.233_956_967_286_346),
        (0.619_309_593_041_598, 0.233_956_967_286_346),
        (0.830_604_693_233_132, 0.180_380_786_524_069),
        (0.966_234_757_101_576, 0.085_662_246_189_585),
    ];
    let m = 1u32 << levels;
    let h = 1.0 / f64::from(m);
    let mut total = 0.0;
    // the sub-triangles (corner a, edge vectors e1, e2): "up" ones and "down" ones
    for i in 0..m {
        for j in 0..m - i {
            let (a, b) = (f64::from(i) * h, f64::from(j) * h);
            let mut tris = vec![([a, b], [h, 0.0], [0.0, h])];
            if i + j + 1 < m {
                tris.push(([a + h, b + h], [-h, 0.0], [0.0, -h]));
            }
            for (o, e1, e2) in tris {
                for &(x, wx) in &g {
                    for &(y, wy) in &g {
                        // the collapsed square: (x, x y) on the triangle x >= y' (Jacobian x)
                        let (p, q) = (x * (1.0 - y), x * y);
                        let u = o[0] + p * e1[0] + q * e2[0];
                        let v = o[1] + p * e1[1] + q * e2[1];
                        let e = s.evaluate(t, u, v).expect("triangle point");
                        let n = fairsub::geom::norm(fairsub::geom::cross(e.du, e.dv));
                        total += wx * wy * x * n * h * h;
                    }
                }
            }
        }
    }
    total
}

/// `measure --per-face` under `nonbox-4dir` on a quasi-four-directional triangle mesh: one
/// area per triangle, each the surface over the fan triangle `(V_i, V_(i+1), FCV)` of its
/// polygon (the G^1 caps and Coons fills halved along the diagonal the triangles' side
/// follows). On the perturbed cube, prism-5 and tetrahedron (no symmetry makes two halves
/// equal) and on cnet-5-saddle (boundary fills): the triangles' areas add up to the surface's
/// to 1e-12, a polygon's triangles to `nonbox`'s area over that polygon of the polygon net
/// (the same surface) to 1e-12, and each triangle's area equals an integration of `eval`'s
/// `|du x dv|` over the triangle (see the assertion for the bound).
#[test]
fn nonbox_4dir_per_face_areas_split_the_polygons() {
    let nets = [
        ("cube", perturbed(gallery("cube"), 0.15, 1), 1),
        ("prism-5", perturbed(gallery("prism-5"), 0.1, 2), 2),
        ("tetrahedron", perturbed(gallery("tetrahedron"), 0.1, 3), 1),
        ("cnet-5-saddle", gallery("cnet-5-saddle"), 2),
    ];
    for (name, poly, rings) in nets {
        let tri = fairsub::schemes::nonbox::fourdir::triangulate(&FcvNet::from_mesh(&poly));
        let (tri, _) = support::via_obj(&tri.mesh, &format!("{name}-perturbed-4dir"));
        let (areas, unassigned, total) = per_face_areas(&tri, ids::NONBOX_4DIR.name(), rings);
        assert_eq!(
            areas.len(),
            tri.num_faces(),
            "{name}: one area per triangle"
        );
        let sum: f64 = areas.iter().sum();
        assert_eq!(unassigned, 0.0, "{name}");
        assert!(
            (sum - total).abs() <= 1e-12 * total,
            "{name}: triangles {sum} vs area {total}"
        );
        // per polygon: its triangles are consecutive (`triangulate`'s order)
        let (polys, _, poly_total) = per_face_areas(&poly, ids::NONBOX.name(), rings);
        assert!((poly_total - total).abs() <= 1e-12 * total, "{name}");
        let mut t = 0;
        for (f, &a) in polys.iter().enumerate() {
            let n = poly.face(f).len();
            let mine: f64 = areas[t..t + n].iter().sum();
            assert!(
                (mine - a).abs() <= 1e-12 * a,
                "{name}: polygon {f}: triangles {mine} vs nonbox {a}"
            );
            t += n;
        }
        // per triangle against eval
        let (_, s) = surface_of(tri.clone(), ids::NONBOX_4DIR.name(), rings);
        let mut worst: f64 = 0.0;
        for (t, &a) in areas.iter().enumerate() {
            assert!(a > 0.0, "{name}: triangle {t}: area {a}");
            let e = area_by_eval(&s, t as u32, 3);
            worst = worst.max((e - a).abs() / a);
        }
        eprintln!("{name} (4dir, {rings} rings): per-triangle areas vs eval: {worst:.2e}");
        assert!(
            worst < 1e-3,
            "{name}: per-triangle areas off eval's by {worst:e}"
        );
    }
}
