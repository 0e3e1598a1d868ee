//! Non-box subdivision's limit tangent across the boundary at a boundary vertex of `k >= 3`
//! quads, from the scheme's own local matrix (the paper analyses no boundary vertex; its
//! boundary rules are the B-spline rules and fairsub's reconstructed NFCV rule, see
//! [`super`]).
//!
//! # The local net
//!
//! The open fan of `k` sectors around the vertex `V0`, sector `j` from its edge `j` to edge
//! `j + 1` (edge `0` the outgoing boundary half-edge, edge `k` the incoming one), each sector
//! labelled as the interior local net of [`super::local`] (`V1 .. V10` at the chart points
//! `(1, 0), (1/2, 1/2), (2, 0), (3/2, 1/2), (1, 1), (1/2, 3/2), (2, 1), (3/2, 3/2), (1, 2),
//! (2, 2)`), then the two vertices `(0, 1), (0, 2)` of sector `k - 1` on edge `k`: `10 k + 3`
//! points. Its rows of [`NonBox::step`] on the open c-net of two rings read only these
//! points (checked), so the `(10 k + 3)^2` matrix is the local subdivision matrix.
//!
//! # The tangent
//!
//! The left eigenvectors of that matrix, applied to the points, are the limit's derivatives.
//! The boundary curve's tangent `a - b` (the cubic B-spline's, eigenvalue `1/2`) spans one
//! direction; the other is the left eigenvector of the largest eigenvalue below 1 whose
//! derivative on a flat half-disc net points across the boundary (the symmetric mode). Measured
//! (test below): `1/2 + cos(pi / k) / 4` to 1e-12 for `k = 3 .. 8` (`0.6250, 0.6768, 0.7023,
//! 0.7165, 0.7252, 0.7310`), the paper's subdominant eigenvalue of an interior vertex of
//! valence `2 k`: the boundary fan behaves like half of a closed fan of twice its valence.
//! Together they span the plane the open-fan G^1 cap of [`super::surface`] is centred in.
//!
//! # One quad
//!
//! A boundary vertex of one quad on a boundary that passes (a net's edge-only boundary, or a
//! copy of a crease vertex on the side of one quad after the cut) is not a corner: the boundary
//! curve runs through it, and its fan is half a closed fan of valence 2. Its local matrix
//! (`k = 1`, the net tagged edge-only) has the eigenvalues `1, 1/2, 1/4, 1/4, 1/8, ...`: the
//! boundary tangent `a - b` at `1/2`, and at `1/4` both the boundary polygon's bend
//! `v - (a + b) / 2` (the curve's own second difference, no derivative on the flat half-disc)
//! and a mode across the boundary. The double eigenvalue leaves the across vector defined up to
//! the bend; fairsub takes the combination without weight on the vertex itself,
//! `F - (a + b) / 2` (`F` the quad's FCV), a left eigenvector at `1/4` (tested below). The cap
//! there ([`super::surface`]'s one-cell crease fan) is G^1 to its ring whichever combination
//! spans the plane with `a - b`: this choice is fairsub's, not derived from a unique limit
//! tangent plane.

use super::{FcvNet, NonBox};
use crate::mesh::PolyMesh;
use crate::stencil::Stencil;
use nalgebra::DMatrix;
use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

/// The largest number of quads at a boundary vertex for which the tangent is computed (the
/// open-fan caps stop there too).
pub const MAX_BOUNDARY_FACES: usize = crate::bezier::g1::MAX_CAP_VALENCE;

/// The `10 k + 3` point indices (vertices, then FCVs, as in [`FcvNet::points`]) of the open
/// local net around the start vertex of the outgoing boundary half-edge `h`, in the labelling
/// of the [module](self) documentation; `None` when `h` is not on the boundary, the fan has
/// 2 faces (a regular vertex) or the two rings of quads are not regular.
pub fn open_labelled_points(m: &PolyMesh, h: u32) -> Option<Vec<usize>> {
    if m.he_twin(h).is_some() {
        return None;
    }
    let v = m.he_from(h) as usize;
    let hs: Vec<u32> = m.outgoing_halfedges(v);
    if hs.first() != Some(&h) || hs.len() == 2 {
        return None;
    }
    let mut out = vec![v];
    let mut last = None;
    for &g in &hs {
        let (labels, second_edge) = super::local::sector_labels(m, g)?;
        out.extend_from_slice(&labels);
        last = Some(second_edge);
    }
    out.extend(last?);
    Some(out)
}

/// The open c-net of `k` quad sectors with two rings, on a half-disc (sector `j` spans the
/// angles `pi j / k .. pi (j + 1) / k`), with barycentric FCVs.
fn open_cnet(k: usize) -> Option<FcvNet> {
    let mut pos = vec![[0.0; 3]];
    let mut at: HashMap<(usize, usize, usize), usize> = HashMap::new();
    let mut id = |j: usize, a: usize, b: usize, pos: &mut Vec<[f64; 3]>| -> usize {
        // a point on edge j (b = 0) belongs to sector j - 1 as (0, a)
        let key = if b == 0 && j > 0 {
            (j - 1, 0, a)
        } else {
            (j, a, b)
        };
        if (a, b) == (0, 0) {
            return 0;
        }
        *at.entry(key).or_insert_with(|| {
            let (j, a, b) = key;
            let r = a.max(b) as f64;
            let t = std::f64::consts::PI * (j as f64 + b as f64 / (a + b) as f64) / k as f64;
            pos.push([r * t.cos(), r * t.sin(), 0.0]);
            pos.len() - 1
        })
    };
    let mut faces = Vec::new();
    for j in 0..k {
        for a in 0..2 {
            for b in 0..2 {
                faces.push(vec![
                    id(j, a, b, &mut pos),
                    id(j, a + 1, b, &mut pos),
                    id(j, a + 1, b + 1, &mut pos),
                    id(j, a, b + 1, &mut pos),
                ]);
            }
        }
    }
    let mesh = PolyMesh::new(pos, &faces).ok()?;
    // one quad: a boundary that passes (edge-only), not a corner
    let edge_only = crate::mesh::Extras {
        options: crate::mesh::tags::SubdOptions {
            boundary: Some(crate::mesh::tags::BoundaryInterpolation::EdgeOnly),
            ..Default::default()
        },
        ..Default::default()
    };
    Some(FcvNet::barycentric(
        mesh.with_extras((k == 1).then_some(edge_only)),
    ))
}

/// The local matrix of the open fan of `k` quads ([module](self) documentation) and the flat
/// net's labelled points.
fn open_local(k: usize) -> Option<(DMatrix<f64>, Vec<[f64; 3]>)> {
    let net = open_cnet(k)?;
    let h0 = net.mesh.vertex_halfedge(0);
    let cols = open_labelled_points(&net.mesh, h0)?;
    let step = NonBox::step(&net).ok()?;
    // child face h is the quad of parent corner h; its first half-edge leaves the V-vertex
    // along the child of the parent's edge h (see `super::local`)
    let rows = open_labelled_points(&step.net.mesh, 4 * h0)?;
    let t = step.stencils.select_rows(&rows).restrict_sources(&cols)?;
    let n = cols.len();
    let s = DMatrix::from_row_slice(n, n, &t.to_dense());
    let pts = net.points();
    Some((s, cols.iter().map(|&c| pts[c]).collect()))
}

/// The eigenvalue and the weights (over the labelled points of [`open_labelled_points`],
/// largest weight 1, pointing into the fan) of the limit tangent across the boundary; `None`
/// for `k < 3`, above [`MAX_BOUNDARY_FACES`], or when the local net is not invariant.
pub fn across_weights(k: usize) -> Option<Arc<(f64, Vec<f64>)>> {
    if !(3..=MAX_BOUNDARY_FACES).contains(&k) {
        return None;
    }
    type Cache = Mutex<HashMap<usize, Option<Arc<(f64, Vec<f64>)>>>>;
    static CACHE: OnceLock<Cache> = OnceLock::new();
    let cache = CACHE.get_or_init(|| Mutex::new(HashMap::new()));
    if let Some(w) = cache.lock().ok()?.get(&k) {
        return w.clone();
    }
    let out = compute_across(k).map(Arc::new);
    cache.lock().ok()?.insert(k, out.clone());
    out
}

fn compute_across(k: usize) -> Option<(f64, Vec<f64>)> {
    let (s, flat) = open_local(k)?;
    let n = s.nrows();
    // left eigenvectors: the eigenvectors of the transpose (faer's general eigen-solver; the
    // matrix is defective at its zero eigenvalues, where nalgebra's Schur iteration does not
    // return)
    let st = faer::Mat::<f64>::from_fn(n, n, |i, j| s[(j, i)]);
    let eig = st.eigen().ok()?;
    let (vals, vecs) = (eig.S().column_vector(), eig.U());
    let mut order: Vec<usize> = (0..n)
        .filter(|&i| {
            let z = vals[i];
            z.im.abs() < 1e-9 && z.re < 1.0 - 1e-9 && z.re > 1e-6
        })
        .collect();
    order.sort_by(|&a, &b| vals[b].re.total_cmp(&vals[a].re));
    for i in order {
        let lambda = vals[i].re;
        let col: Vec<faer::c64> = (0..n).map(|r| vecs[(r, i)]).collect();
        // a real eigenvector up to a complex factor: rotate by the phase of its largest entry
        let big = col
            .iter()
            .copied()
            .max_by(|a, b| a.norm().total_cmp(&b.norm()))?;
        let phase = big.conj() * (1.0 / big.norm());
        let mut w: Vec<f64> = col.iter().map(|z| (*z * phase).re).collect();
        let t = w
            .iter()
            .zip(&flat)
            .fold([0.0; 3], |acc, (&x, p)| crate::geom::axpy(acc, x, *p));
        // across the boundary of the flat half-disc: along y, not x
        if t[1].abs() > 1e-6 && t[0].abs() < 1e-9 * t[1].abs().max(1.0) {
            let big = w.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            let sign = t[1].signum();
            w.iter_mut().for_each(|x| *x *= sign / big);
            return Some((lambda, w));
        }
    }
    None
}

/// The stencils `(along, across)` of the limit tangents at boundary vertex `v` of `k >= 3`
/// quads: the boundary curve's `a - b` and [`across_weights`] over its labelled points;
/// `None` where the two rings around `v` are not regular quads. At a vertex of one quad on a
/// boundary that passes: `a - b` and `F - (a + b) / 2` ([module](self) documentation, "One
/// quad").
pub fn open_fan_tangents(net: &FcvNet, v: usize) -> Option<(Stencil, Stencil)> {
    let m = &net.mesh;
    let h = m.vertex_halfedge(v);
    let nb = m.vertex_neighbors(v);
    let (a, b) = (nb[0] as usize, nb[nb.len() - 1] as usize);
    let along = Stencil::from_pairs([(a, 1.0), (b, -1.0)]);
    let faces = m.vertex_faces(v);
    if faces.len() == 1 && m.he_twin(h).is_none() {
        // one quad (module documentation)
        let f = net.fcv_point(faces[0] as usize);
        return Some((along, Stencil::from_pairs([(f, 1.0), (a, -0.5), (b, -0.5)])));
    }
    let pts = open_labelled_points(m, h)?;
    let w = across_weights(faces.len())?;
    let across = Stencil::from_pairs(pts.iter().copied().zip(w.1.iter().copied()));
    Some((along, across.merged()))
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    /// One quad on an edge-only boundary: eigenvalues `1, 1/2, 1/4, 1/4, 1/8 ...`; `a - b` a
    /// left eigenvector at `1/2`; the bend `v - (a + b) / 2` and `F - (a + b) / 2` left
    /// eigenvectors at `1/4` (labelled points: `v` 0, `a` 1, `F` 2, `b` 11).
    #[crate::unit::test]
    fn one_quad_local_matrix() {
        let (s, _) = open_local(1).expect("invariant");
        assert_eq!(s.nrows(), 13);
        let n = s.nrows();
        let st = faer::Mat::<f64>::from_fn(n, n, |i, j| s[(j, i)]);
        let eig = st.eigen().expect("eigenvalues");
        let vals = eig.S().column_vector();
        let mut v: Vec<f64> = (0..n).map(|i| vals[i].re).collect();
        v.sort_by(|a, b| b.total_cmp(a));
        for (got, want) in v.iter().zip([1.0, 0.5, 0.25, 0.25, 0.125]) {
            assert!((got - want).abs() < 1e-9, "{v:?}");
        }
        let left = |pairs: &[(usize, f64)], lambda: f64| {
            let mut x = nalgebra::DVector::zeros(n);
            for &(i, w) in pairs {
                x[i] = w;
            }
            (s.transpose() * &x - &x * lambda).amax()
        };
        assert!(left(&[(1, 1.0), (11, -1.0)], 0.5) < 1e-12);
        assert!(left(&[(0, 1.0), (1, -0.5), (11, -0.5)], 0.25) < 1e-12);
        assert!(left(&[(2, 1.0), (1, -0.5), (11, -0.5)], 0.25) < 1e-12);
    }

    #[crate::unit::test]
    fn open_local_matrix_and_across_tangents() {
        let mut found = Vec::new();
        for k in 3..=8 {
            let (s, _) = open_local(k).expect("invariant");
            assert_eq!(s.nrows(), 10 * k + 3);
            // rows of a subdivision step: weights sum to 1
            for r in 0..s.nrows() {
                assert!((s.row(r).sum() - 1.0).abs() < 1e-12, "k {k} row {r}");
            }
            let w = across_weights(k).expect("an across tangent");
            let x = nalgebra::DVector::from_vec(w.1.clone());
            assert!((s.transpose() * &x - &x * w.0).amax() < 1e-10, "k {k}");
            assert!(w.1.iter().sum::<f64>().abs() < 1e-10, "k {k}: a tangent");
            let half = 0.5 + (std::f64::consts::PI / k as f64).cos() / 4.0;
            assert!((w.0 - half).abs() < 1e-12, "k {k}: {} against {half}", w.0);
            found.push(format!("{k}: {:.4}", w.0));
        }
        eprintln!("non-box across-boundary eigenvalues: {}", found.join(", "));
    }
}
