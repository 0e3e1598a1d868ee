//! Closest points on the exact surface (`Surface::closest_point`, `fairsub project`): the
//! residual is orthogonal to the surface, the point is never farther than the nearest vertex of
//! a dense tessellation, and `evaluate` at the returned `(face, u, v)` gives the returned point.
//! Nets with n-gons (strips), triangles, caps of every kind, dual schemes' pieces.

use fairsub::geom::{Point, cross, dist, dot, norm, sub};
use fairsub::surface::eval::Surface;

use crate::eval_helpers::faces;
use crate::eval_helpers::support;
use faces::{face_points, surface_of};
use support::{Lcg, gallery};

/// Nets, schemes and rings whose surfaces are closed.
const CASES: [(&str, &str, usize); 8] = [
    ("cube", "catmull-clark", 3),
    ("prism-5", "catmull-clark", 3),
    ("torus-evs", "catmull-clark", 2),
    ("icosahedron", "loop", 3),
    ("cube", "doo-sabin", 3),
    ("cube", "pgs", 3),
    ("cube", "eg", 3),
    ("cube", "guided-bi6", 2),
];

/// Random points around the surface: surface points pushed along their normals by up to
/// `reach` of the surface's size, both ways.
fn query_points(s: &Surface, mesh: &fairsub::mesh::PolyMesh, n: usize, reach: f64) -> Vec<Point> {
    let (lo, hi) = fairsub::geom::bounding_box(
        s.complex()
            .patches
            .iter()
            .flat_map(|p| p.cps.iter().copied()),
    )
    .unwrap();
    let size = dist(lo, hi);
    let mut rng = Lcg(7);
    face_points(mesh, n.div_ceil(mesh.num_faces()).max(1), 11)
        .into_iter()
        .filter_map(|(f, u, v)| s.evaluate(f, u, v).ok())
        .take(n)
        .map(|e| {
            let t = (2.0 * rng.next() - 1.0) * reach * size;
            fairsub::geom::axpy(e.point, t, e.normal)
        })
        .collect()
}

/// The nearest of the tessellation's vertices (points of the surface).
fn brute_force(points: &[Point], q: Point) -> f64 {
    points
        .iter()
        .map(|p| dist(*p, q))
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn closest_points_are_orthogonal_exact_and_never_beaten_by_a_dense_sampling() {
    for (net, scheme, rings) in CASES {
        let (mesh, s) = surface_of(gallery(net), scheme, rings);
        let dense = fairsub::surface::tessellate::tessellate(s.complex(), 24).positions;
        let size = {
            let (lo, hi) = fairsub::geom::bounding_box(dense.iter().copied()).unwrap();
            dist(lo, hi)
        };
        let qs = query_points(&s, &mesh, 120, 0.15);
        let found = s.closest_points(&qs);
        let (mut worst_ortho, mut worst_eval, mut worst_gain) = (0.0f64, 0.0f64, 0.0f64);
        for (q, c) in qs.iter().zip(&found) {
            let c = c.unwrap_or_else(|| panic!("{net} {scheme}: no closest point for {q:?}"));
            assert!(
                !c.on_boundary,
                "{net} {scheme}: {c:?} on a boundary of a closed surface"
            );
            // evaluate at the returned parameters gives the returned point
            let e = s
                .evaluate(c.face, c.u, c.v)
                .expect("returned parameters evaluate");
            worst_eval = worst_eval.max(dist(e.point, c.point) / size);
            // the residual is orthogonal to the surface: its part along the tangent plane
            let r = sub(*q, c.point);
            if norm(r) > 1e-6 * size {
                let tangential = norm(cross(cross(e.normal, r), e.normal));
                worst_ortho = worst_ortho.max(tangential / norm(r));
            }
            assert!((c.distance - norm(r)).abs() <= 1e-14 * size);
            // never farther than the nearest of the dense tessellation's surface points
            worst_gain = worst_gain.max(c.distance - brute_force(&dense, *q));
        }
        eprintln!(
            "{net} {scheme}: ortho {worst_ortho:.1e}, eval {worst_eval:.1e}, vs dense \
             {worst_gain:.1e}"
        );
        assert!(
            worst_ortho < 1e-9,
            "{net} {scheme}: residual {worst_ortho:e} off normal"
        );
        assert!(
            worst_eval < 1e-12,
            "{net} {scheme}: eval differs by {worst_eval:e}"
        );
        assert!(
            worst_gain <= 1e-12 * size,
            "{net} {scheme}: {worst_gain:e} farther"
        );
    }
}

#[test]
fn points_of_the_surface_project_onto_themselves() {
    for (net, scheme, rings) in CASES {
        let (mesh, s) = surface_of(gallery(net), scheme, rings);
        let pts: Vec<Point> = face_points(&mesh, 4, 3)
            .into_iter()
            .filter_map(|(f, u, v)| s.evaluate(f, u, v).ok())
            .map(|e| e.point)
            .collect();
        for (p, c) in pts.iter().zip(s.closest_points(&pts)) {
            let c = c.expect("closest");
            assert!(c.distance < 1e-11, "{net} {scheme}: {p:?} -> {c:?}");
            let e = s.evaluate(c.face, c.u, c.v).unwrap();
            assert!(dist(e.point, *p) < 1e-11);
        }
    }
}

#[test]
fn an_open_surface_holds_far_points_on_its_boundary() {
    let (_, s) = surface_of(gallery("open-grid"), "catmull-clark", 2);
    let (lo, hi) = fairsub::geom::bounding_box(
        s.complex()
            .patches
            .iter()
            .flat_map(|p| p.cps.iter().copied()),
    )
    .unwrap();
    // far beyond the grid's side in x: the closest point is on the boundary curve, where the
    // residual is orthogonal to that curve, not to the surface
    let q = [hi[0] + 10.0, 0.5 * (lo[1] + hi[1]) + 0.1, 0.0];
    let c = s.closest_point(q).unwrap();
    assert!(c.on_boundary, "{c:?}");
    let e = s.evaluate(c.face, c.u, c.v).unwrap();
    let r = sub(q, c.point);
    // orthogonal to the boundary curve's tangent (one of du, dv)
    let along = dot(r, e.du).abs().min(dot(r, e.dv).abs());
    assert!(
        along < 1e-9 * norm(r) * norm(e.du).max(norm(e.dv)),
        "{along}"
    );
}

#[test]
fn the_project_command_reads_text_and_binary_points() {
    let dir = std::env::temp_dir().join(format!("fairsub-project-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let text = dir.join("p.txt");
    std::fs::write(&text, "# two points\n0 0 2\n1.5, 0.2, 0.1\n").unwrap();
    let run = |path: &std::path::Path| {
        let words = [
            "fairsub",
            "project",
            "gallery:cube",
            "--scheme",
            "catmull-clark",
            "--rings",
            "3",
            "--json",
            "--points",
            path.to_str().unwrap(),
        ];
        let (r, out) = fairsub::cli::capture(|| fairsub::cli::run_words(words));
        r.unwrap();
        let v: serde_json::Value = serde_json::from_str(&out).unwrap();
        v.as_array().unwrap().clone()
    };
    let a = run(&text);
    assert_eq!(a.len(), 2);
    // the top of the cube's surface, straight below (0, 0, 2)
    let d = a[0]["distance"].as_f64().unwrap();
    let z = a[0]["point"][2].as_f64().unwrap();
    assert!((d + z - 2.0).abs() < 1e-14 && a[0]["normal"][2].as_f64().unwrap() > 0.999999);
    let bin = dir.join("p.bin");
    let bytes: Vec<u8> = [0.0f64, 0.0, 2.0, 1.5, 0.2, 0.1]
        .iter()
        .flat_map(|x| x.to_le_bytes())
        .collect();
    std::fs::write(&bin, bytes).unwrap();
    assert_eq!(run(&bin), a);
    // a bad line is named
    std::fs::write(&text, "0 0 2\n1 2\n").unwrap();
    let words = [
        "fairsub",
        "project",
        "gallery:cube",
        "--scheme",
        "catmull-clark",
        "--points",
        text.to_str().unwrap(),
    ];
    let e = fairsub::cli::run_words(words).unwrap_err().to_string();
    assert!(e.contains("p.txt:2") && e.contains("expected X Y Z"), "{e}");
    std::fs::remove_dir_all(&dir).ok();
}
