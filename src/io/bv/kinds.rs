//! Every patch kind of a `.bv` file as tensor-product patches, exactly, so that `check`,
//! `render` and `view` treat all of them alike:
//!
//! - tensor-product patches (types 4, 5, 10) and rational ones (type 8, with their weights) as
//!   they are;
//! - a triangular patch of degree `d` (types 3, 9) as the bi-degree `(d, d)` patch of the map
//!   `(s, t) -> (u, v, w) = (1 - s, s (1 - t), s t)` from the unit square onto its domain
//!   triangle (side `s = 0` collapsed to the corner `u = 1`; orientation kept, since the map's
//!   Jacobian is `s >= 0`). Its coefficients follow from writing `u^i v^j w^k` in the tensor
//!   Bernstein basis: with `m = j + k`,
//!   `c[m][l] = sum_k b[d-m][m-k][k] C(m, k) C(d-m, l-k) / C(d, l)`;
//! - a polyhedron's faces as flat patches: a quad as its bilinear patch, a triangle as a
//!   bilinear patch with one side collapsed, an n-gon as the triangles of a fan from its first
//!   corner. All their sides are marked sharp (polyhedron faces meet with C^0 joins only), so
//!   `check` reports those joins apart from the smooth ones.

use super::{BvFile, TriPatch};
use crate::bezier::BezierPatch;
use crate::geom::Point;
use crate::surface::{PatchComplex, Provenance};

/// What a `.bv` file holds, by kind (the counts `check` reports).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize)]
pub struct BvCounts {
    /// Polynomial tensor-product patches (types 4, 5, 10, and type 8 with equal weights).
    pub tensor: usize,
    /// Rational tensor-product patches (type 8).
    pub rational: usize,
    /// Triangular patches (types 3, 9).
    pub triangular: usize,
    /// Polyhedra (type 1).
    pub polyhedra: usize,
    /// Faces of all polyhedra.
    pub polyhedron_faces: usize,
}

/// A `.bv` file's patches of every kind as one complex (see the module notes).
#[derive(Debug, Clone)]
pub struct BvPatches {
    /// The patches: tensor-product ones in file order, then the triangular ones, then the
    /// polyhedra's faces; provenance [`Provenance::Unknown`].
    pub complex: PatchComplex,
    /// The group (index into [`BvFile::groups`]) of each patch.
    pub groups: Vec<Option<usize>>,
    /// The first patch of each kind: `[triangular, polyhedron faces]` start here.
    pub starts: [usize; 2],
}

impl BvFile {
    /// How many patches of each kind the file holds.
    pub fn counts(&self) -> BvCounts {
        let rational = self
            .patches
            .patches
            .iter()
            .filter(|p| p.is_rational())
            .count();
        BvCounts {
            tensor: self.patches.len() - rational,
            rational,
            triangular: self.tri_patches.len(),
            polyhedra: self.polyhedra.len(),
            polyhedron_faces: self.polyhedra.iter().map(|p| p.faces.len()).sum(),
        }
    }

    /// Every patch of the file as a tensor-product patch (see the module notes); with
    /// `polyhedra` false the polyhedra are left out (a caller that shows them as the net).
    pub fn all_patches(&self, polyhedra: bool) -> BvPatches {
        let mut complex = self.patches.clone();
        let mut groups = self.patch_groups.clone();
        groups.resize(complex.len(), None);
        let tri_start = complex.len();
        for (t, g) in self.tri_patches.iter().zip(&self.tri_groups) {
            complex.push(triangle_as_tensor(t), Provenance::Unknown);
            groups.push(*g);
        }
        let poly_start = complex.len();
        for p in self.polyhedra.iter().filter(|_| polyhedra) {
            for f in &p.faces {
                for patch in face_patches(&p.positions, f) {
                    let k = complex.len() as u32;
                    complex.push(patch, Provenance::Unknown);
                    complex.sharp_sides.push((k, 0b1111));
                    groups.push(p.group);
                }
            }
        }
        BvPatches {
            complex,
            groups,
            starts: [tri_start, poly_start],
        }
    }
}

/// `n` choose `k` as a float (exact for the degrees `.bv` files allow).
fn choose(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |c, i| c * (n - i) as f64 / (i + 1) as f64)
}

/// The triangular patch as an exact bi-degree `(d, d)` tensor-product patch (module notes).
pub fn triangle_as_tensor(t: &TriPatch) -> BezierPatch {
    let d = t.deg;
    BezierPatch::from_fn(d, d, |m, l| {
        let mut p = [0.0; 3];
        let lo = l.saturating_sub(d - m);
        for k in lo..=m.min(l) {
            let w = choose(m, k) * choose(d - m, l - k) / choose(d, l);
            let b = t.cp(d - m, m - k, k);
            for c in 0..3 {
                p[c] += w * b[c];
            }
        }
        p
    })
}

/// The flat patches of a polyhedron face (module notes).
fn face_patches(pos: &[Point], face: &[usize]) -> Vec<BezierPatch> {
    let at = |k: usize| pos[face[k]];
    match face.len() {
        4 => vec![BezierPatch::new(1, 1, vec![at(0), at(3), at(1), at(2)])],
        n => (1..n - 1)
            .map(|k| {
                triangle_as_tensor(&TriPatch {
                    deg: 1,
                    cps: vec![at(0), at(k), at(k + 1)],
                })
            })
            .collect(),
    }
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;
    use crate::geom::dist;

    /// The triangular patch at barycentric `(u, v, w)` by its Bernstein sum.
    fn tri_eval(t: &TriPatch, u: f64, v: f64, w: f64) -> Point {
        let d = t.deg;
        let mut p = [0.0; 3];
        for k in 0..=d {
            for j in 0..=d - k {
                let i = d - j - k;
                let m = choose(d, i)
                    * choose(d - i, j)
                    * u.powi(i as i32)
                    * v.powi(j as i32)
                    * w.powi(k as i32);
                let b = t.cp(i, j, k);
                for c in 0..3 {
                    p[c] += m * b[c];
                }
            }
        }
        p
    }

    #[crate::unit::test]
    fn triangles_become_exact_tensor_patches() {
        for d in 1..=6 {
            let cps: Vec<Point> = (0..TriPatch::count(d))
                .map(|k| {
                    let x = k as f64;
                    [x.sin(), (1.3 * x).cos(), 0.1 * x * x]
                })
                .collect();
            let t = TriPatch { deg: d, cps };
            let q = triangle_as_tensor(&t);
            assert_eq!((q.deg_u, q.deg_v), (d, d));
            for &(s, tt) in &[(0.0, 0.3), (0.2, 0.7), (0.9, 0.1), (1.0, 1.0), (0.5, 0.0)] {
                let (u, v, w) = (1.0 - s, s * (1.0 - tt), s * tt);
                let e = dist(q.eval(s, tt), tri_eval(&t, u, v, w));
                assert!(e < 1e-13, "degree {d} at ({s}, {tt}): {e}");
            }
            // the side s = 0 is the corner u = 1
            assert!(q.is_collapsed(crate::bezier::Side::U0, 0.0));
        }
    }

    #[crate::unit::test]
    fn polyhedron_faces_are_flat_patches_with_sharp_sides() {
        let f = super::super::parse_bv(
            "1\n5 2\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0.5 1.5 0\n4 0 1 2 3\n3 3 2 4\n",
            std::path::Path::new("p.bv"),
        )
        .unwrap();
        let all = f.all_patches(true);
        assert_eq!(all.complex.len(), 2);
        assert_eq!(all.complex.sharp_sides.len(), 2);
        let n = all.complex.patches[0].normal(0.5, 0.5);
        assert!(dist(n, [0.0, 0.0, 1.0]) < 1e-15, "{n:?}");
        let n = all.complex.patches[1].normal(0.5, 0.5);
        assert!(dist(n, [0.0, 0.0, 1.0]) < 1e-15, "{n:?}");
        assert_eq!(f.counts().polyhedron_faces, 2);
        assert!(f.all_patches(false).complex.is_empty());
    }
}
