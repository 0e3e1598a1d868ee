//! Evaluation at `(face, u, v)` on the G^1 caps of darts and of vertices next to hole faces
//! (`tests/it/dart_caps.rs`, `tests/it/wedge_caps.rs`): agreement with the patches `subdivide
//! --rings` writes at random points of every face (caps included), and continuity of the
//! evaluation across the dyadic lines of every face (a cap patch placed in the wrong sector or
//! with a turned parameter jumps there).

#[allow(dead_code)]
use crate::eval_helpers::faces;
#[allow(dead_code)]
use crate::eval_helpers::support;
use faces::{agrees_at, agrees_with, largest_jump, surface_of};
use support::written_from;

#[test]
fn dart_and_wedge_caps_evaluate_as_written() {
    for (net, scheme) in [
        ("cc_torus_dart", "catmull-clark"),
        ("cc_cube_semisharp", "catmull-clark"),
        ("loop_octa_semisharp", "loop"),
        ("loop_holes_isolated", "loop"),
    ] {
        let path = format!("{}/tests/data/osd/{net}.obj", env!("CARGO_MANIFEST_DIR"));
        let mesh = fairsub::io::read_mesh(std::path::Path::new(&path))
            .expect("net")
            .mesh;
        for rings in [1, 3] {
            let written = written_from(&path, net, scheme, rings);
            let (mesh, s) = surface_of(mesh.clone(), scheme, rings);
            let (worst, in_caps) = if scheme == "loop" {
                // hole faces have no surface: evaluating them is an error
                let covered = |m: &fairsub::mesh::PolyMesh, (f, _, _): (u32, f64, f64)| {
                    !m.is_hole(f as usize)
                };
                agrees_at(&written, &mesh, &s, &triangle_points(&mesh), &covered)
            } else {
                agrees_with(&written, &mesh, &s, &|_, _| true)
            };
            eprintln!("{net}, {rings} rings: {worst:.2e}, {in_caps} points on caps");
            assert!(worst <= 1e-12, "{net}, {rings} rings: {worst:e}");
            assert!(in_caps > 0, "{net}, {rings} rings: no point on a cap");
            if scheme != "loop" {
                let jump = largest_jump(&mesh, &s, 64, 2e-10, &|_, _| true);
                assert!(jump < 1e-7, "{net}, {rings} rings: jump {jump:e}");
            }
        }
    }
}

/// 60 points of every triangle in its barycentric domain `u, v >= 0, u + v <= 1`, half of them
/// within `2^-6` of a corner (in the caps), and the corners.
fn triangle_points(mesh: &fairsub::mesh::PolyMesh) -> Vec<(u32, f64, f64)> {
    let mut rng = support::Lcg(31);
    let mut pts = Vec::new();
    for f in 0..mesh.num_faces() as u32 {
        for k in 0..60 {
            let (mut u, mut v) = (rng.next(), rng.next());
            if u + v > 1.0 {
                (u, v) = (1.0 - u, 1.0 - v);
            }
            if k % 2 == 1 {
                let c = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)][k % 3];
                let t = 1.0 / 64.0;
                (u, v) = (c.0 + t * (u - c.0), c.1 + t * (v - c.1));
            }
            pts.push((f, u, v));
        }
        pts.extend([(f, 0.0, 0.0), (f, 1.0, 0.0), (f, 0.0, 1.0)]);
    }
    pts
}
