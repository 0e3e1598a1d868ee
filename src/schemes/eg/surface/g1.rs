//! The G^1 cap of the d-net schemes' own holes (EG, QAS+ and its accelerated variants; QAS+ at
//! valence 3 runs on EG's rules).
//!
//! # The cap
//!
//! After `K` rings the hole of sector `s` is the square `[0, h]^2` of the last d-net's chart,
//! bounded by the inner sides of the ring's patches `A` and `C` of that sector; the spoke between
//! two sectors is the chart's ray. The cap is the G^1 cap of [`crate::bezier::g1`]:
//!
//! * **hole data**: read off the bi-4 fill of [`super::fill`] (transposed to the mesh chart, as
//!   the rings are): its two outer layers along each outer side are exactly the C^1 continuation
//!   of `A` and `C` (value and first cross derivative at the ring's parameter speed), so
//!   [`crate::bezier::g1::ring::sectors_from_fill`] returns the ring's exact C^1 data. The ring is
//!   one C^2 bi-4 spline in the d-net's chart, so the data are compatible at every corner and
//!   spoke end (tensor grid there, `kappa = 0`);
//! * **centre**: the local vector's source 0, the scheme's limit point (`c0` of EG's (3) / (4);
//!   QAS+'s central point `p = q_1`, which its rings converge to);
//! * **tangent plane**: for EG's rules, spanned by the two left eigenvectors of the subdominant
//!   eigenvalue of the step matrix on the local vector (`crate::linalg::subdominant_left_pair`)
//!   applied to the local vector after the last step: the exact limit tangent plane of a
//!   stationary scheme. For QAS+'s rules (and its accelerated variants) the plane of the
//!   quadratic expansion `q` the rings are attracted to, spanned by the Fourier mode 1 of the
//!   first-order coefficients `q_2^s - p` (the eigenvalue 1/2 of the step is not a double one:
//!   every sector's `q` keeps its own first-order pair, so the eigen route does not apply);
//! * **spoke tangents' scale**: from the ring's chart in that plane
//!   ([`crate::bezier::g1::ring::chart_tangents`]);
//! * **conditions, free parameters, degree**: those of [`crate::bezier::g1`] (C^1 to the ring,
//!   centre and plane, C^0 and the G^1 relation along every spoke, the quadratic jet where the
//!   degree allows it; the rest minimises `F_4`): bi-4 for odd `n`, bi-5 for even `n` (bi-4 at
//!   the regular `n = 4`).
//!
//! Where the cap cannot be built (a degenerate tangent pair) the hole keeps the C^0 fill and the
//! output notes say so.
//!
//! QAS+^3's bi-3 rings are 2 x 2 macro-patches per sector (one C^2 bi-3 spline in the d-net's
//! chart): the hole's sides are piecewise cubics of two pieces each, read directly off the last
//! ring's pieces (no fill needed: [`crate::bezier::g1::ring::split_sector`]), and the cap is the
//! split-sector cap of [`crate::bezier::g1`] ([`crate::bezier::g1::Layout::Split`]`(2)`): each
//! sector a 2 x 2 grid of bi-`d` pieces, C^2 inside the sector, C^1 to the ring piece by
//! piece, G^1 across every spoke piece, same centre and plane as QAS+^4's cap.

use crate::bezier::BezierPatch;
use crate::bezier::complex::CapStep;
use crate::bezier::g1::ring::{cap_step, sectors_from_fill, split_sector};
use crate::bezier::g1::{CapOptions, Hole};
use crate::error::{Error, Result};
use crate::geom::Point;
use crate::stencil::StencilTable;
use nalgebra::DMatrix;
use std::collections::HashMap;
use std::sync::{Mutex, OnceLock};

/// Two weight vectors over the local vector whose values span the limit tangent plane.
pub(super) type TangentMasks = [Vec<f64>; 2];

/// The two left eigenvectors of the subdominant eigenvalue of a step matrix (rows over the
/// local vector), or why there are none.
///
/// The eigen-decomposition is the costly part of a cap (more than the rings), so the masks are
/// kept for the process, keyed by the matrix itself (its size and the bits of its entries): the
/// complexes of one process share them, and equal steps of different rules choices coincide.
pub(super) fn tangent_masks(step: &StencilTable) -> Result<TangentMasks> {
    type Cache = HashMap<(usize, Vec<u64>), TangentMasks>;
    /// Masks kept at most (each key is the dense matrix, `(12 n + 1)^2` entries).
    const MAX_CACHED: usize = 64;
    static CACHE: OnceLock<Mutex<Cache>> = OnceLock::new();
    let (r, c) = (step.num_rows(), step.num_sources());
    if r != c {
        return Err(Error::Unsupported(format!(
            "the step matrix is {r} x {c}, not square"
        )));
    }
    let dense = step.to_dense();
    let key = (r, dense.iter().map(|w| w.to_bits()).collect::<Vec<u64>>());
    let cache = CACHE.get_or_init(|| Mutex::new(HashMap::new()));
    if let Some(m) = cache.lock().expect("no poisoning").get(&key) {
        return Ok(m.clone());
    }
    let m = DMatrix::from_row_slice(r, c, &dense);
    let (_, [a, b]) = crate::linalg::subdominant_left_pair(&m).ok_or_else(|| {
        Error::Unsupported(
            "the step matrix has no real double subdominant eigenvalue (no tangent pair)".into(),
        )
    })?;
    let masks: TangentMasks = [a.iter().copied().collect(), b.iter().copied().collect()];
    let mut map = cache.lock().expect("no poisoning");
    if map.len() >= MAX_CACHED {
        map.clear();
    }
    map.insert(key, masks.clone());
    Ok(masks)
}

/// `mask . x`.
pub(super) fn apply(mask: &[f64], x: &[Point]) -> Point {
    let mut p = [0.0; 3];
    for (w, q) in mask.iter().zip(x) {
        for k in 0..3 {
            p[k] += w * q[k];
        }
    }
    p
}

/// The G^1 cap of a d-net hole: `fill` the bi-4 fill's patches per sector (mesh chart),
/// `centre` the limit point, `tangents` two vectors spanning the limit tangent plane; with the
/// cap's [`CapStep`] for a patch stencil table, its first patch at index `first`.
pub(super) fn dnet_cap(
    fill: &[BezierPatch],
    centre: Point,
    tangents: [Point; 2],
    first: usize,
) -> Result<(Vec<BezierPatch>, CapStep)> {
    let hole = Hole::untangented(centre, sectors_from_fill(fill));
    cap_step(hole, tangents, CapOptions::default(), first)
}

/// The split G^1 cap of a QAS+^3 hole: `ring` the last bi-3 ring (12 pieces per sector, EG
/// chart), the cap's pieces per sector `(a, b)` row-major in the mesh chart (`a` along spoke
/// `s`), with its [`CapStep`].
pub(super) fn bi3_cap(
    ring: &[Point],
    n: usize,
    centre: Point,
    tangents: [Point; 2],
    first: usize,
) -> Result<(Vec<BezierPatch>, CapStep)> {
    // In the mesh chart (transposed) the hole's side u = 1 borders C (its quarters (0, k):
    // EG sub-patch k), the side v = 1 borders A (quarters (k, 0): EG sub-patch 2 k).
    let sectors = (0..n)
        .map(|s| {
            let a: Vec<BezierPatch> = (0..2)
                .map(|k| super::ring_patch3(ring, s, 2, k).transposed())
                .collect();
            let b: Vec<BezierPatch> = (0..2)
                .map(|k| super::ring_patch3(ring, s, 0, 2 * k).transposed())
                .collect();
            split_sector(&a, &b)
        })
        .collect();
    cap_step(
        Hole::untangented(centre, sectors),
        tangents,
        CapOptions::default(),
        first,
    )
}
