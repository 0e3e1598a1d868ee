//! Non-box subdivision's limit point and tangent plane at a dart: an interior vertex `V0` of
//! valence `k` with exactly one infinitely sharp edge (a crease ending inside the surface).
//! fairsub's construction on the rules of [`crate::schemes::nonbox::sharp`] (the paper has no
//! creases).
//!
//! Under OpenSubdiv's rules, which non-box's sharp features follow rule for rule, the dart's
//! V-vertex takes the smooth rule (`(1 - a_k) V0` plus `a_k` on the mean of its FCVs), the
//! sharp edge's E-vertex the midpoint and the NFCVs beside it the ghost `a + b - F`. The local
//! net of [`super`] (`10 k + 1` points) with its sector-0 edge `V0 V1` and the next edge
//! `V1 V3` along that spoke sharp is mapped onto itself by one step ([`NonBox::step`] on the
//! tagged c-net, rows restricted to the labelled points; checked), so its matrix's left
//! eigenvectors are the dart's masks: of `1` the limit, of the two largest eigenvalues below
//! it (real; the rest of the spectrum strictly below, checked) the tangent plane. The
//! spectrum, computed (tested below): `1`, then `0.4452` and `0.3750` at `k = 3`, `1/2` double
//! at `k = 4`, `0.5773` and `0.5432` at `k = 5`, `0.6768` and `0.6305` at `k = 8`. One of the
//! pair is always the smooth vertex's subdominant eigenvalue `1/2 + cos(2 pi / k) / 4` (the
//! paper's): the mode antisymmetric about the sharp edge does not see its rule, as at
//! Catmull-Clark's darts ([`crate::schemes::catmull_clark::dart`]).

use super::{SECTOR, labelled_points, local_fcv_net};
use crate::mesh::{Extras, SharpEdges};
use crate::schemes::nonbox::{FcvNet, NonBox};
use crate::schemes::sdc::crease::INFINITE;
use crate::schemes::sdc::dart::{DartMasks, MaskCache, MasksOf, cached_masks_with, masks_at};
use nalgebra::DMatrix;
use std::sync::{Arc, OnceLock};

/// The `(10 k + 1)^2` local matrix of a non-box dart of valence `k` (module documentation);
/// `None` when the tagged local net is not invariant.
pub(crate) fn dart_local(k: usize) -> Option<DMatrix<f64>> {
    let net = local_fcv_net(k, 2);
    let m = &net.mesh;
    let h0 = m.vertex_halfedge(0);
    let cols = labelled_points(m, h0)?;
    let (v1, v3) = (cols[1] as u32, cols[3] as u32);
    let sharp = vec![
        (m.find_edge(0, v1)?, INFINITE),
        (m.find_edge(v1, v3)?, INFINITE),
    ];
    let mesh = m.clone().with_extras(Some(Extras {
        sharp_edges: SharpEdges::ById(sharp),
        ..Extras::default()
    }));
    let tagged = FcvNet {
        mesh,
        fcv: net.fcv.clone(),
    };
    let step = NonBox::step(&tagged).ok()?;
    // child face h is the quad of parent corner h (see `super::local_sparse`)
    let rows = labelled_points(&step.net.mesh, 4 * h0)?;
    let t = step.stencils.select_rows(&rows).restrict_sources(&cols)?;
    let n = cols.len();
    debug_assert_eq!(n, SECTOR * k + 1);
    Some(DMatrix::from_row_slice(n, n, &t.to_dense()))
}

/// The two largest eigenvalues below 1 of `s` when they are real and positive, `1` is an
/// eigenvalue and the rest of the spectrum lies strictly below both (faer's general solver:
/// the matrix is defective at its zero eigenvalues, see [`crate::schemes::nonbox::boundary`]).
fn subdominant_pair(s: &DMatrix<f64>) -> Option<(f64, f64)> {
    let n = s.nrows();
    let m = faer::Mat::<f64>::from_fn(n, n, |i, j| s[(i, j)]);
    let vals = m.eigenvalues().ok()?;
    let mut by_modulus: Vec<(f64, f64)> = vals.iter().map(|z| (z.norm(), z.im)).collect();
    by_modulus.sort_by(|a, b| b.0.total_cmp(&a.0));
    let one = by_modulus.first()?;
    let (a, b, rest) = (by_modulus.get(1)?, by_modulus.get(2)?, by_modulus.get(3)?);
    let real = |z: &(f64, f64)| z.1.abs() < 1e-9;
    ((one.0 - 1.0).abs() < 1e-9 && real(a) && real(b) && a.0 < 1.0 - 1e-9 && rest.0 < b.0 - 1e-9)
        .then_some((a.0, b.0))
}

/// The masks of a non-box dart of valence `k` over the labelled points of [`labelled_points`]
/// taken from its sharp edge (`None` below 3, above [`MAX_DART_VALENCE`](crate::schemes::sdc::dart::MAX_DART_VALENCE), or where the spectrum
/// is not as the module documentation says); computed once per valence.
pub(crate) fn dart_masks(k: usize) -> Option<Arc<DartMasks>> {
    static CACHE: MaskCache = OnceLock::new();
    let masks: MasksOf = |s| {
        let (la, lb) = subdominant_pair(s)?;
        masks_at(s, la, lb)
    };
    // (an empty matrix where the local net is not invariant: no masks)
    cached_masks_with(&CACHE, k, (3, masks), |k| {
        dart_local(k).unwrap_or_else(|| DMatrix::zeros(0, 0))
    })
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    /// The masks are left eigenvectors of the dart's local matrix (limit summing to 1, tangents
    /// to 0) at every valence, one eigenvalue the smooth vertex's.
    #[crate::unit::test]
    fn dart_masks_are_left_eigenvectors() {
        let mut found = Vec::new();
        for k in 3..=12 {
            let s = dart_local(k).expect("invariant");
            for r in 0..s.nrows() {
                assert!((s.row(r).sum() - 1.0).abs() < 1e-12, "k {k} row {r}");
            }
            let m = dart_masks(k).unwrap_or_else(|| panic!("k {k}: masks"));
            crate::schemes::sdc::dart::assert_left_eigenvectors(&s, &m, &format!("k {k}"));
            // the antisymmetric mode keeps the smooth vertex's subdominant eigenvalue
            let smooth = 0.5 + (2.0 * std::f64::consts::PI / k as f64).cos() / 4.0;
            assert!(
                m.lambda.iter().any(|l| (l - smooth).abs() < 1e-9),
                "k {k}: {:?} against {smooth}",
                m.lambda
            );
            found.push(format!("{k}: {:.4} {:.4}", m.lambda[0], m.lambda[1]));
        }
        eprintln!("non-box dart eigenvalues: {}", found.join(", "));
    }
}
