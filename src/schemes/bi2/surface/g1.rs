//! The G^1 caps of the bi-2 family's element rings (TPS and adjustable TPS at vertices, PolBS
//! at poles, PGS at the facets of `bi2-mixed` and of polar nets).
//!
//! # The caps
//!
//! After the last ring an element's hole is read off its fill ([`super`]): every fill patch is
//! its sector's bi-2 piece of the last local net with only the coefficient at the centre
//! replaced, so its two outer layers are the ring's exact C^1 continuation.
//!
//! * **TPS, adjustable TPS, PGS**: the quad-layout G^1 cap of [`crate::bezier::g1`]. Sector `s`
//!   is the fill patch of sector `s` (the quarter of the centre's bi-2 piece for TPS, the
//!   corner patch for PGS), whose side `v = 0` lies on spoke `s` and side `u = 0` on spoke
//!   `s + 1` ([`crate::bezier::g1::ring::sectors_from_fill`]). The spoke ends (edge midpoints
//!   of the last q-net's centre piece, centres of the DS-net's edge quads) are interior points
//!   of one bi-2 piece and the corners regular grid points of the bi-2 spline, so the data are
//!   compatible (`kappa = 0`). For adjustable TPS the fill has the centre piece's knot width,
//!   so the cap joins the ring C^1 up to the same per-piece affine reparametrisation as the
//!   rings join each other. Conditions, free parameters (fairness `F_4`) and degrees (bi-4 odd
//!   `n`, bi-5 even `n`) are those of [`crate::bezier::g1`].
//! * **PolBS**: the collapsed bi-2 fill of [`super`] is already a G^1 cap once a ring was made:
//!   its outer two rows are the ring's C^1 continuation, every row is a C^1 quadratic spline
//!   around the pole (so the fill is C^1 across the spokes), and its first row (the `a` ring of
//!   the last polar net) lies in the limit tangent plane through the limit point (16), so the
//!   normal at the pole is the plane's from every direction (measured on perturbed prisms:
//!   4e-15 rad between the normals at the pole, equal to the eigen-plane's normal to 1e-12;
//!   `tests/it/g1cap_schemes.rs::polar_bi2`). It is kept (bi-2, the lowest degree) after that check;
//!   a first row off the plane (beyond `1e-9` of its size) keeps the fill with a note.
//!
//! Centre: the element's limit point ((7), (21), (16): `LocalScheme::limit`). Tangent plane:
//! the two left eigenvectors of the subdominant eigenvalue of the element's stationary local
//! step (`LocalScheme::step(l)` for `l >= 1`; `crate::linalg::subdominant_left_pair`) applied
//! to the last local net (after the first step when no ring was made): the exact limit tangent
//! plane. Where a cap cannot be built (no double subdominant eigenvalue, degenerate tangents,
//! a polar first row off the plane, valence above the cap's bound) the fill stays, with a note.

use crate::bezier::BezierPatch;
use crate::bezier::complex::CapStep;
use crate::bezier::g1::ring::{cap_step, sectors_from_fill};
use crate::bezier::g1::{CapOptions, Hole};
use crate::error::{Error, Result};
use crate::geom::{Point, cross, dot, norm, normalize, sub};
use crate::schemes::bi2::local_scheme::{LocalKind, LocalScheme};
use nalgebra::DMatrix;

/// Tangent masks over an element's local net, cached per local scheme.
#[derive(Default)]
pub(super) struct Masks {
    cache: Vec<(LocalKind, usize, [Vec<f64>; 2])>,
}

impl Masks {
    /// The two subdominant left eigenvectors of `scheme`'s stationary step.
    fn of(&mut self, scheme: &LocalScheme) -> Result<&[Vec<f64>; 2]> {
        let pos = self
            .cache
            .iter()
            .position(|(k, n, _)| *k == scheme.kind && *n == scheme.n);
        let i = match pos {
            Some(i) => i,
            None => {
                let st = scheme.step(1);
                let rows = crate::linalg::MAX_DENSE_EIGEN_ROWS;
                if st.num_rows() > rows {
                    return Err(Error::Unsupported(format!(
                        "its tangent masks need the eigenvectors of a {} x {} local step, above \
                         the {rows} rows of a dense eigen-decomposition",
                        st.num_rows(),
                        st.num_sources()
                    )));
                }
                let m = DMatrix::from_row_slice(st.num_rows(), st.num_sources(), &st.to_dense());
                let (_, [a, b]) = crate::linalg::subdominant_left_pair(&m).ok_or_else(|| {
                    Error::Unsupported(
                        "the local step has no real double subdominant eigenvalue".into(),
                    )
                })?;
                let masks = [a.iter().copied().collect(), b.iter().copied().collect()];
                self.cache.push((scheme.kind, scheme.n, masks));
                self.cache.len() - 1
            }
        };
        Ok(&self.cache[i].2)
    }
}

/// `mask . x`.
fn apply(mask: &[f64], x: &[Point]) -> Point {
    mask.iter()
        .zip(x)
        .fold([0.0; 3], |acc, (&w, p)| crate::geom::axpy(acc, w, *p))
}

/// The G^1 cap of an element whose local net at level `l` has the points `pts` and whose fill
/// patches (per sector) are `fill` (see the [module](self) documentation).
pub(super) fn element_cap(
    scheme: &LocalScheme,
    l: usize,
    pts: &[Point],
    fill: &[BezierPatch],
    masks: &mut Masks,
    first: usize,
) -> Result<(Vec<BezierPatch>, Option<CapStep>)> {
    let centre = scheme.limit()?.apply(pts);
    let next;
    let at = if l == 0 {
        next = scheme.step(0).apply(pts);
        &next
    } else {
        pts
    };
    let m = masks.of(scheme)?;
    let plane = [apply(&m[0], at), apply(&m[1], at)];
    match scheme.kind {
        LocalKind::Polar => {
            let nrm = normalize(cross(plane[0], plane[1]));
            for (s, p) in fill.iter().enumerate() {
                for j in 0..=p.deg_v {
                    let d = sub(p.cp(1, j), centre);
                    if dot(d, nrm).abs() > 1e-9 * norm(d) {
                        return Err(Error::Unsupported(format!(
                            "the first row of the collapsed fill is not in the limit tangent \
                             plane (sector {s})"
                        )));
                    }
                }
            }
            Ok((fill.to_vec(), None))
        }
        _ => {
            let hole = Hole::untangented(centre, sectors_from_fill(fill));
            let (patches, step) = cap_step(hole, plane, CapOptions::default(), first)?;
            Ok((patches, Some(step)))
        }
    }
}
