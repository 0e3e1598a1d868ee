//! Checks shared by the evaluation tests of the cap, dual and ternary schemes
//! (`tests/it/eval_caps.rs`, `tests/it/eval_dual.rs`, `tests/it/evalmore.rs`, `tests/it/eval_ternary.rs`):
//! random face points, agreement with the written patches, and the largest jump of the
//! evaluation across the lines of a grid of every face.

use super::support::{Lcg, gallery, written};
use fairsub::geom::dist;
use fairsub::mesh::PolyMesh;
use fairsub::schemes::registry::registry;
use fairsub::surface::ComplexOptions;
use fairsub::surface::eval::Surface;

/// `per_face` random points of every face (n-gons on their strip `[0, n] x [0, 1]`), half of
/// them within `2^-6` of a corner (so in the caps of the extraordinary vertices), and each
/// face's corners.
pub fn face_points(mesh: &PolyMesh, per_face: usize, seed: u64) -> Vec<(u32, f64, f64)> {
    let mut r = Lcg(seed);
    let mut pts = Vec::new();
    for f in 0..mesh.num_faces() {
        let n = mesh.face_size(f);
        let width = if n == 4 { 1.0 } else { n as f64 };
        for k in 0..per_face {
            let (mut u, mut v) = (r.next(), r.next());
            if k % 2 == 1 {
                // near corner (0, 0), (1, 0), (1, 1) or (0, 1) of the face or sub-face
                let c = (r.next() * 4.0) as usize;
                let s = 1.0 / 64.0;
                u = if c == 1 || c == 2 { 1.0 - s * u } else { s * u };
                v = if c >= 2 { 1.0 - s * v } else { s * v };
            }
            let sub = if n == 4 {
                0.0
            } else {
                (r.next() * width).floor()
            };
            pts.push((f as u32, sub + u, v));
        }
        for (u, v) in [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)] {
            pts.push((f as u32, u, v));
        }
    }
    pts
}

fn surface(net: &str, scheme: &str, rings: usize) -> (PolyMesh, Surface) {
    surface_of(gallery(net), scheme, rings)
}

/// The surface of `mesh` under `scheme` with `rings` rings and the fill.
pub fn surface_of(mesh: PolyMesh, scheme: &str, rings: usize) -> (PolyMesh, Surface) {
    let spec = registry().lookup(scheme).expect("scheme");
    let s = Surface::build(&spec, &mesh, ComplexOptions { rings, fill: true }).expect("surface");
    (mesh, s)
}

/// Whether a face point `(face, u, v)` of a net is covered by patches with face domains.
pub type Covered = dyn Fn(&PolyMesh, (u32, f64, f64)) -> bool;

/// Writes `subdivide --rings` of `net`, evaluates random points of every face and checks each
/// against the written patch it names; returns the largest difference and how many points fell
/// on cap patches. Points where `covered(mesh, point)` is false must be errors instead (the
/// dual schemes' quarters of faces at boundary vertices).
fn agrees_with_written(net: &str, scheme: &str, rings: usize, covered: &Covered) -> (f64, usize) {
    let written = written(net, scheme, rings);
    let (mesh, s) = surface(net, scheme, rings);
    agrees_with(&written, &mesh, &s, covered)
}

/// [`agrees_with_written`] for the patches `written` of the surface `s` of `mesh`.
pub fn agrees_with(
    written: &fairsub::bezier::complex::PatchComplex,
    mesh: &PolyMesh,
    s: &Surface,
    covered: &Covered,
) -> (f64, usize) {
    agrees_at(written, mesh, s, &face_points(mesh, 60, 23), covered)
}

/// [`agrees_with`] at the face points `pts`.
pub fn agrees_at(
    written: &fairsub::bezier::complex::PatchComplex,
    mesh: &PolyMesh,
    s: &Surface,
    pts: &[(u32, f64, f64)],
    covered: &Covered,
) -> (f64, usize) {
    assert_eq!(s.complex().len(), written.len(), "same patches");
    let mut worst: f64 = 0.0;
    let mut in_caps = 0;
    for &(f, u, v) in pts {
        if !covered(mesh, (f, u, v)) {
            let err = s.evaluate(f, u, v).expect_err("an uncovered point");
            assert!(err.to_string().contains("no patch"), "{err}");
            continue;
        }
        let e = s
            .evaluate(f, u, v)
            .unwrap_or_else(|err| panic!("face {f} at ({u}, {v}): {err}"));
        assert!((0.0..=1.0).contains(&e.patch_uv[0]) && (0.0..=1.0).contains(&e.patch_uv[1]));
        let w = written.patches[e.patch].eval(e.patch_uv[0], e.patch_uv[1]);
        worst = worst.max(dist(w, e.point));
        if matches!(
            s.complex().provenance[e.patch],
            fairsub::bezier::complex::Provenance::Cap { .. }
        ) {
            in_caps += 1;
        }
    }
    (worst, in_caps)
}

/// Largest jump of the evaluation across the lines `u = i / lines` and `v = i / lines`
/// (`0 < i < lines`) of every face: points `delta` apart on either side, at several positions
/// along the line (pairs with a point where `covered` is false are skipped).
pub fn largest_jump(
    mesh: &PolyMesh,
    s: &Surface,
    lines: u32,
    delta: f64,
    covered: &Covered,
) -> f64 {
    let xs: Vec<f64> = (1..lines)
        .map(|i| f64::from(i) / f64::from(lines))
        .collect();
    jump_across(mesh, s, &xs, delta, covered)
}

/// [`largest_jump`] across the lines `u = x` and `v = x` for every `x` of `xs`.
pub fn jump_across(mesh: &PolyMesh, s: &Surface, xs: &[f64], delta: f64, covered: &Covered) -> f64 {
    let mut worst: f64 = 0.0;
    for f in 0..mesh.num_faces() {
        let n = mesh.face_size(f);
        let subs = if n == 4 { 1 } else { n };
        for sub in 0..subs {
            let base = sub as f64;
            for &x in xs {
                for t in 1..16 {
                    let y = (f64::from(t) - 0.5) / 15.0;
                    for (a, b) in [
                        ((x - delta, y), (x + delta, y)),
                        ((y, x - delta), (y, x + delta)),
                    ] {
                        let (pa, pb) = ((f as u32, base + a.0, a.1), (f as u32, base + b.0, b.1));
                        if !covered(mesh, pa) || !covered(mesh, pb) {
                            continue;
                        }
                        let p = s.evaluate(f as u32, base + a.0, a.1).expect("point");
                        let q = s.evaluate(f as u32, base + b.0, b.1).expect("point");
                        worst = worst.max(dist(p.point, q.point));
                    }
                }
            }
        }
    }
    worst
}

/// Every scheme on every net (`rings[k]` rings for the `k`-th) agrees with its written
/// patches to 1e-12 ([`agrees_with_written`]), with some points on caps.
pub fn all_agree(schemes: &[&str], nets: &[&str], rings: &[usize], covered: &Covered) {
    for scheme in schemes {
        for (net, &rings) in nets.iter().zip(rings) {
            let (worst, in_caps) = agrees_with_written(net, scheme, rings, covered);
            eprintln!(
                "{net} under {scheme}, {rings} rings: largest difference {worst:.3e}, {in_caps} points on caps"
            );
            assert!(worst <= 1e-12, "{net} under {scheme}: {worst:e}");
            assert!(in_caps > 0, "{net} under {scheme}: no point on a cap");
        }
    }
}

/// Every scheme's evaluation on every net (3 rings) jumps by less than 1e-7 across the lines
/// `i 2^-6` of every face, for points 2e-10 apart ([`largest_jump`]).
pub fn all_continuous(schemes: &[&str], nets: &[&str]) {
    for scheme in schemes {
        for net in nets {
            let (mesh, s) = surface(net, scheme, 3);
            let jump = largest_jump(&mesh, &s, 1 << 6, 1e-10, &|_, _| true);
            eprintln!("{net} under {scheme}: largest jump {jump:.3e}");
            assert!(jump < 1e-7, "{net} under {scheme}: jump {jump:e}");
        }
    }
}

/// Whether a face point lies in a quarter at an interior vertex (under the boundary mode
/// `none` the dual schemes write no surface over those at boundary vertices; not every test
/// binary uses this): the quarter at corner `floor(u)` of an n-gon, at the nearest corner of
/// a quad.
#[allow(dead_code)]
pub fn at_interior_vertex(mesh: &PolyMesh, (f, u, v): (u32, f64, f64)) -> bool {
    let face = mesh.face(f as usize);
    let k = if face.len() == 4 {
        match (u >= 0.5, v >= 0.5) {
            (false, false) => 0,
            (true, false) => 1,
            (true, true) => 2,
            (false, true) => 3,
        }
    } else {
        (u.floor() as usize).min(face.len() - 1)
    };
    !mesh.is_boundary_vertex(face[k] as usize)
}
