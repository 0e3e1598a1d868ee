//! All new corners of one large face at once, in time linear in its size: the dual schemes'
//! corner rules are circulant on the face, and their rows have only Fourier modes 0 and 1 (plus
//! a few neighbours), so the `n` new corners cost `O(n)` instead of the `n^2` of `n` stencils of
//! `n` entries each. Used by the adaptive host of [`super::surface`] for faces above
//! [`LARGE_FACE`] (an `n`-gon born from a vertex of valence `n`); smaller faces keep their
//! stencils, so outputs on them are unchanged to the bit. The weights are those of
//! [`super::DooSabin::weights`] and [`super::DooSabinCc::weights`], regrouped (tested equal to
//! the stencils in this module's tests).

use crate::error::Result;
use crate::geom::{Point, axpy};
use crate::mesh::PolyMesh;
use crate::schemes::common::RowBuf;

/// Faces with more corners than this get their new corners from [`FaceCorners`] rules.
pub const LARGE_FACE: usize = 32;

/// The new corners of one face, in the face's corner order, and every net point the rule read
/// (whose trust decides the corners' trust).
#[derive(Debug, Clone)]
pub struct FaceCorners {
    /// New corner `i` of the face (the child point of its `i`-th half-edge).
    pub points: Vec<Point>,
    /// The net points read.
    pub reads: Vec<u32>,
}

/// `sum_j v_j`, `sum_j cos(2 pi j / n) v_j` and `sum_j sin(2 pi j / n) v_j` over the corners.
fn modes(pos: &[Point], verts: &[u32]) -> [Point; 3] {
    let n = verts.len();
    let mut m = [[0.0; 3]; 3];
    for (j, &v) in verts.iter().enumerate() {
        let t = std::f64::consts::TAU * j as f64 / n as f64;
        let p = pos[v as usize];
        m[0] = axpy(m[0], 1.0, p);
        m[1] = axpy(m[1], t.cos(), p);
        m[2] = axpy(m[2], t.sin(), p);
    }
    m
}

/// Doo-Sabin's corners of face `f`: `w_ij = 1/4 delta_ij + 3/(4n) + cos(2 pi (i - j)/n)/(2n)`
/// (the module's weights: `1/4 + 5/(4n)` on the diagonal), and
/// `sum_j cos(t (j - i)) v_j = cos(t i) C + sin(t i) S` with the mode-1 sums `C`, `S`.
pub fn doo_sabin(mesh: &PolyMesh, f: usize) -> FaceCorners {
    let verts = mesh.face(f);
    let pos = mesh.positions();
    let n = verts.len();
    let nf = n as f64;
    let [s0, c, s] = modes(pos, verts);
    let points = (0..n)
        .map(|i| {
            let t = std::f64::consts::TAU * i as f64 / nf;
            let mut p = axpy([0.0; 3], 0.25, pos[verts[i] as usize]);
            p = axpy(p, 0.75 / nf, s0);
            p = axpy(p, t.cos() / (2.0 * nf), c);
            axpy(p, t.sin() / (2.0 * nf), s)
        })
        .collect();
    FaceCorners {
        points,
        reads: verts.to_vec(),
    }
}

/// DS^CC's corners of face `f`: `v_i / 2 + (v_(i-1) + v_(i+1)) / 8 + centroid / 4`.
pub fn doo_sabin_cc(mesh: &PolyMesh, f: usize) -> FaceCorners {
    let verts = mesh.face(f);
    let pos = mesh.positions();
    let n = verts.len();
    let [s0, _, _] = modes(pos, verts);
    let points = (0..n)
        .map(|i| {
            let at = |d: usize| pos[verts[(i + d) % n] as usize];
            let mut p = axpy([0.0; 3], 0.5, at(0));
            p = axpy(p, 0.125, at(1));
            p = axpy(p, 0.125, at(n - 1));
            axpy(p, 0.25 / n as f64, s0)
        })
        .collect();
    FaceCorners {
        points,
        reads: verts.to_vec(),
    }
}

/// One whole-net step of a dual scheme when only the child net is wanted (no stencil table
/// kept, as for PGS's DS^CC pre-processing): [`super::refine_dual_with`] with `corner_rule`,
/// but the corners of faces above [`LARGE_FACE`] get empty rows and their positions from
/// `face_corners`, in time linear in the face size.
///
/// # Errors
/// As [`super::refine_dual_with`].
pub(crate) fn refine_net_with(
    mesh: &PolyMesh,
    name: &str,
    mut corner_rule: impl FnMut(&PolyMesh, u32, &mut RowBuf),
    face_corners: fn(&PolyMesh, usize) -> FaceCorners,
) -> Result<PolyMesh> {
    let large = |m: &PolyMesh, h: u32| m.face_size(m.he_face(h) as usize) > LARGE_FACE;
    let r = super::refine_dual_with(mesh, name, |m, h, row| {
        if !large(m, h) {
            corner_rule(m, h, row);
        }
    })?;
    let mut child = r.mesh;
    let big: Vec<usize> = (0..mesh.num_faces())
        .filter(|&f| mesh.face_size(f) > LARGE_FACE)
        .collect();
    if !big.is_empty() {
        // The child point of corner h is child vertex h (the module's layout).
        let mut pos = child.positions().to_vec();
        for f in big {
            let h0 = mesh.face_halfedge(f) as usize;
            for (i, p) in face_corners(mesh, f).points.into_iter().enumerate() {
                pos[h0 + i] = p;
            }
        }
        child.set_positions(pos);
    }
    Ok(child)
}

/// One DS^CC step of the net alone (`refine_net_with` with DS^CC's rules).
///
/// # Errors
/// As `super::refine_dual_with`.
pub fn refine_cc_net(mesh: &PolyMesh) -> Result<PolyMesh> {
    let mut rules = super::RuleCache::new(super::DooSabinCc::weights);
    refine_net_with(
        mesh,
        crate::schemes::options::ids::DOO_SABIN_CC.name(),
        |m, h, row| super::add_corner_point(m, &mut rules, h, 1.0, row),
        doo_sabin_cc,
    )
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;
    use crate::schemes::doo_sabin::{DooSabin, DooSabinCc, corner_point_stencil};

    /// One n-gon with wobbly corners.
    fn ngon(n: usize) -> PolyMesh {
        let pts: Vec<Point> = (0..n)
            .map(|i| {
                let t = std::f64::consts::TAU * i as f64 / n as f64;
                [
                    t.cos() * (1.0 + 0.3 * (3.0 * t).sin()),
                    t.sin(),
                    0.2 * (5.0 * t).cos(),
                ]
            })
            .collect();
        PolyMesh::new(pts, &[(0..n).collect::<Vec<usize>>()]).unwrap()
    }

    #[crate::unit::test]
    fn net_step_equals_the_refinement() {
        use crate::schemes::Scheme;
        for n in [5, 40] {
            let m = ngon(n);
            let a = refine_cc_net(&m).unwrap();
            let b = DooSabinCc.refine(&m).unwrap().mesh;
            assert_eq!(a.num_faces(), b.num_faces());
            for (p, q) in a.positions().iter().zip(b.positions()) {
                for k in 0..3 {
                    assert!((p[k] - q[k]).abs() < 1e-14, "n = {n}");
                }
            }
        }
    }

    #[crate::unit::test]
    fn fourier_corners_equal_the_stencils() {
        for n in [3, 5, 8, 33, 100] {
            let m = ngon(n);
            type Rule = fn(usize) -> Vec<f64>;
            let cases: [(FaceCorners, Rule); 2] = [
                (doo_sabin(&m, 0), DooSabin::weights),
                (doo_sabin_cc(&m, 0), DooSabinCc::weights),
            ];
            for (fc, rule) in cases {
                assert_eq!(fc.reads.len(), n);
                for (i, p) in fc.points.iter().enumerate() {
                    let q = corner_point_stencil(&m, i as u32, rule).apply(m.positions());
                    for k in 0..3 {
                        assert!(
                            (p[k] - q[k]).abs() < 1e-14,
                            "n = {n}, corner {i}: {p:?} {q:?}"
                        );
                    }
                }
            }
        }
    }
}
