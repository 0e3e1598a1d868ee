//! G^1 caps at Loop's extraordinary boundary vertices: the open triangle fans of
//! `bezier::g1` (`Layout::OpenTriangle`), each fan triangle one cap patch with a straight
//! corner at the midpoint of its outer edge, centred at the boundary curve's limit point in the
//! plane of Loop's boundary eigen tangents. Until 2026-12-04 these holes kept the C^0 Hermite
//! fill (1.8e-2 rad between its pieces on a triangulated L-shape at 3 rings; 1.6e-4 rad
//! between the fill of a one-triangle corner and the last ring).
//!
//! Tests: `check` finds every join G^1 below 1e-8 rad and every irregular boundary vertex
//! (one, two, four or more triangles) capped by an open fan; the cap's centre is the boundary
//! curve's limit point and its tangent plane does not move with the rings; `eval` agrees with
//! the written patches and is continuous; the probed patch table re-applies to moved points.

use fairsub::analysis::continuity::check;
use fairsub::geom::{dist, dot, norm, sub};
use fairsub::mesh::PolyMesh;
use fairsub::mesh::nets::{loop_net, tri_grid};
use fairsub::surface::{ComplexOptions, complex};

use crate::eval_helpers::faces;
use crate::eval_helpers::open_caps;
use crate::eval_helpers::support;
use faces::{agrees_at, largest_jump, surface_of};
use open_caps::{centre_and_normal, open_caps, table_reapplies};
use support::{Lcg, irregular_boundary_nets, via_obj, written_from};

/// The quads of `m` split along one diagonal (`flip`: the other one).
fn triangulated(m: &PolyMesh, flip: bool) -> PolyMesh {
    let mut faces = Vec::new();
    for f in 0..m.num_faces() {
        let q: Vec<usize> = m.face(f).iter().map(|&v| v as usize).collect();
        if flip {
            faces.push(vec![q[0], q[1], q[3]]);
            faces.push(vec![q[1], q[2], q[3]]);
        } else {
            faces.push(vec![q[0], q[1], q[2]]);
            faces.push(vec![q[0], q[2], q[3]]);
        }
    }
    PolyMesh::new(m.positions().to_vec(), &faces).expect("triangulated")
}

/// Half of Loop's c-net of valence `2 k` (4 rings): a boundary vertex of `k` triangles in a
/// half-disc of regular triangles, with a bump.
fn half_disc(k: usize) -> PolyMesh {
    let full = loop_net(2 * k, 4);
    let per = 16; // triangles per sector of a 4-ring fan
    let faces: Vec<Vec<usize>> = (0..k * per)
        .map(|f| full.face(f).iter().map(|&v| v as usize).collect())
        .collect();
    let mut used = vec![usize::MAX; full.num_vertices()];
    let mut pos = Vec::new();
    for f in &faces {
        for &v in f {
            if used[v] == usize::MAX {
                used[v] = pos.len();
                let [x, y, _] = full.positions()[v];
                pos.push([x, y, 0.05 * x * x - 0.03 * x * y + 0.02 * y * y * y]);
            }
        }
    }
    let faces: Vec<Vec<usize>> = faces
        .iter()
        .map(|f| f.iter().map(|&v| used[v]).collect())
        .collect();
    let m = PolyMesh::new(pos, &faces).expect("half disc");
    assert_eq!(m.vertex_faces(0).len(), k, "the centre's triangles");
    m
}

/// Boundary vertices that are not Loop-regular (three triangles): each gets an open cap.
fn boundary_evs(m: &PolyMesh) -> Vec<usize> {
    (0..m.num_vertices())
        .filter(|&v| m.is_boundary_vertex(v) && m.vertex_faces(v).len() != 3)
        .collect()
}

fn nets() -> Vec<(String, PolyMesh)> {
    let mut out: Vec<(String, PolyMesh)> = Vec::new();
    for (name, m) in irregular_boundary_nets() {
        out.push((format!("{name}, split"), triangulated(&m, false)));
        out.push((
            format!("{name}, split the other way"),
            triangulated(&m, true),
        ));
    }
    out.push(("tri-grid".into(), tri_grid()));
    // (one-triangle corners: the split L-shapes and tri-grid)
    for k in [2, 4, 5, 7] {
        out.push((format!("half-disc of {k}"), half_disc(k)));
    }
    out
}

#[test]
fn every_join_is_g1_and_every_irregular_boundary_vertex_is_capped() {
    for (name, mesh) in nets() {
        let want = boundary_evs(&mesh).len();
        assert!(want > 0, "{name}");
        for rings in [1, 2, 3] {
            let what = format!("{name} under loop, {rings} rings");
            let c = complex("loop", &mesh, ComplexOptions { rings, fill: true }, |_| {})
                .unwrap_or_else(|e| panic!("{what}: {e}"));
            assert_eq!(open_caps(&c), want, "{what}: open caps");
            let r = check(&c);
            for (kind, d) in &r.by_kind {
                assert!(
                    d.g1 < 1e-8,
                    "{what}, {kind}: G^1 {:e} at {:?}",
                    d.g1,
                    d.g1_at
                );
            }
        }
    }
}

/// Centre: the boundary curve's limit point (the cubic B-spline of the boundary polygon; a
/// vertex of one triangle is a corner and stays put). Normal: perpendicular to the boundary
/// tangent, the same at 1, 2, 3 and 5 rings (the across-boundary tangent is a left
/// eigenvector of the one-ring matrix: a wrong mask tilts with the level).
#[test]
fn the_cap_sits_at_the_limit_point_in_one_tangent_plane_at_every_level() {
    for (name, mesh) in nets() {
        for x in boundary_evs(&mesh) {
            let nb = mesh.vertex_neighbors(x);
            let pos = mesh.positions();
            let (a, b) = (pos[nb[0] as usize], pos[*nb.last().unwrap() as usize]);
            let corner = mesh.vertex_faces(x).len() == 1;
            let limit: [f64; 3] = if corner {
                pos[x]
            } else {
                std::array::from_fn(|i| (a[i] + 4.0 * pos[x][i] + b[i]) / 6.0)
            };
            let mut normals = Vec::new();
            for rings in [1, 2, 3, 5] {
                let c = complex("loop", &mesh, ComplexOptions { rings, fill: true }, |_| {})
                    .expect("complex");
                let (centre, n) = centre_and_normal(&c, limit);
                let what = format!("{name}, vertex {x}, {rings} rings");
                assert!(dist(centre, limit) < 1e-13, "{what}: centre");
                if corner {
                    // the plane of the two boundary edges
                    for e in [a, b] {
                        let t = sub(e, pos[x]);
                        assert!(dot(n, t).abs() < 1e-12 * norm(t), "{what}: corner plane");
                    }
                } else {
                    assert!(
                        dot(n, sub(a, b)).abs() < 1e-12 * norm(sub(a, b)),
                        "{what}: boundary tangent not in the plane"
                    );
                }
                normals.push(n);
            }
            for n in &normals[1..] {
                assert!(
                    dist(*n, normals[0]) < 1e-12,
                    "{name}, vertex {x}: the plane moves with the level: {n:?} against {:?}",
                    normals[0]
                );
            }
        }
    }
}

/// Points of every triangle `(u, v)`, `u + v <= 1`: random ones, half of them within `2^-6`
/// of a corner (in the caps at an extraordinary corner), and the dyadic points `2^-k (a, b)`,
/// `a, b` in `{0, 1/2, 1}`, among them the midpoints of the fan triangles' outer edges, where
/// the open caps' patches have their straight (singular) corners.
fn triangle_points(mesh: &PolyMesh) -> Vec<(u32, f64, f64)> {
    let mut r = Lcg(29);
    let mut pts = Vec::new();
    for f in 0..mesh.num_faces() as u32 {
        for k in 0..40 {
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
        for k in 1..=4 {
            let h = 0.5f64.powi(k);
            for (a, b) in [(0.5, 0.0), (0.0, 0.5), (0.5, 0.5), (1.0, 0.0), (0.0, 1.0)] {
                for (x, y) in [
                    (a * h, b * h),
                    (1.0 - (a + b) * h, b * h),
                    (a * h, 1.0 - (a + b) * h),
                ] {
                    pts.push((f, x, y));
                }
            }
        }
    }
    pts
}

#[test]
fn eval_agrees_with_the_written_caps_and_is_continuous() {
    for (name, mesh) in nets() {
        let file = name.replace([' ', ','], "-");
        let (mesh, src) = via_obj(&mesh, &format!("loop-open-{file}"));
        let written = written_from(&src, &file, "loop", 3);
        let want = boundary_evs(&mesh).len();
        let (mesh, s) = surface_of(mesh.clone(), "loop", 3);
        assert_eq!(open_caps(s.complex()), want, "{name}");
        let (worst, in_caps) =
            agrees_at(&written, &mesh, &s, &triangle_points(&mesh), &|_, _| true);
        let inside =
            |_: &PolyMesh, (_, u, v): (u32, f64, f64)| u >= 0.0 && v >= 0.0 && u + v <= 1.0;
        let jump = largest_jump(&mesh, &s, 1 << 6, 1e-10, &inside);
        eprintln!(
            "{name}: largest difference {worst:.3e}, {in_caps} points on caps, largest jump \
             {jump:.3e}"
        );
        assert!(worst <= 1e-12, "{name}: {worst:e}");
        assert!(in_caps > 0, "{name}: no point on a cap");
        // finite derivatives, unit normals and finite curvatures everywhere, the caps'
        // straight corners (the dyadic points) included
        for &(f, u, v) in &triangle_points(&mesh) {
            let e = s.evaluate(f, u, v).expect("a point");
            let fin = |p: [f64; 3]| p.iter().all(|x| x.is_finite());
            assert!(
                fin(e.du) && fin(e.dv) && fin(e.duu) && fin(e.duv) && fin(e.dvv),
                "{name}: face {f} ({u}, {v}) derivatives"
            );
            assert!(
                (norm(e.normal) - 1.0).abs() < 1e-12,
                "{name}: normal at {f} ({u}, {v})"
            );
            assert!(
                e.gauss.is_finite() && e.mean.is_finite(),
                "{name}: curvature at {f}"
            );
        }
        assert!(jump < 1e-7, "{name}: jump {jump:e}");
    }
}

/// Loop's tables are probed; the open caps' steps go through them like the closed ones.
#[test]
fn patch_tables_reapply_with_open_caps() {
    for (name, mesh) in nets() {
        table_reapplies("loop", &name, &mesh, boundary_evs(&mesh).len(), 11);
    }
}
