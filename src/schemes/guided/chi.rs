//! The characteristic ring `chi` that guided subdivision samples through, in fairsub's chart.
//!
//! One sector (sector 0, between the rays `e_0` and `e_1`) of `chi` has three planar patches on
//! the L-shaped domain of the c-net chart: `A` over `[1/2, 1] x [0, 1/2]`, `B` over
//! `[1/2, 1]^2`, `C` over `[0, 1/2] x [1/2, 1]`, each with local parameters `(s, t)` in the unit
//! square increasing with the chart's `(u, v)`. Sector `k` is sector 0 rotated by `2 pi k / n`,
//! so `L_k^-1 o chi_k = L_0^-1 o chi_0` and one table serves every sector. `chi` is normalised so
//! that its outer corner on the ray is `e_0`: the guide's unit square then corresponds to the
//! cap's c-net faces. `chi(x / 2) = lambda chi(x)`: the next ring is `lambda chi`.
//!
//! * [`ChiKind::CatmullClark`]: Catmull-Clark's characteristic ring (eigenvector of the
//!   subdominant eigenvalue on the c-net, one Catmull-Clark step, the bi-3 patches of the
//!   refined cells `(1,0), (1,1), (0,1)`), with Catmull-Clark's lambda.
//! * [`ChiKind::Half`]: the bi-4 characteristic map of QAS+ (Section 3 of the QAS+ paper,
//!   [`crate::schemes::qas::chi`], valences 5..10), lambda = 1/2; the paper's Section 6.3 uses the
//!   map of \[KP09\], which is not in the corpus and has the same role.

use crate::bezier::BezierPatch;
use crate::error::{Error, Result};
use crate::schemes::catmull_clark::catmull_clark_lambda;
pub use crate::schemes::options::ChiKind;
use std::f64::consts::PI;

/// One sector of a characteristic ring with its contraction.
#[derive(Debug, Clone)]
pub struct CharRing {
    /// Valence.
    pub n: usize,
    /// The contraction `lambda` (`chi(x / 2) = lambda chi(x)`).
    pub lambda: f64,
    /// Patches `A, B, C` of sector 0 (planar, `z = 0`).
    pub sector: [BezierPatch; 3],
}

impl CharRing {
    /// The characteristic ring of the given kind at valence `n`.
    pub fn new(n: usize, kind: ChiKind) -> Result<CharRing> {
        match kind {
            ChiKind::CatmullClark => catmull_clark(n),
            ChiKind::Half => qas_half(n),
        }
    }

    /// All `3 n` patches, sector by sector (`A, B, C`), rotated into place.
    pub fn ring(&self) -> Vec<BezierPatch> {
        let mut out = Vec::with_capacity(3 * self.n);
        for k in 0..self.n {
            let a = 2.0 * PI * k as f64 / self.n as f64;
            let (c, s) = (a.cos(), a.sin());
            for p in &self.sector {
                out.push(p.map_points(|q| [c * q[0] - s * q[1], s * q[0] + c * q[1], 0.0]));
            }
        }
        out
    }

    /// Sector 0's patches mapped by `L_0^-1` into the guide's `(u, v)` domain.
    pub fn in_guide_domain(&self) -> [BezierPatch; 3] {
        let a = 2.0 * PI / self.n as f64;
        let (c, s) = (a.cos(), a.sin());
        self.sector
            .clone()
            .map(|p| p.map_points(|q| [q[0] - c / s * q[1], q[1] / s, 0.0]))
    }
}

/// Catmull-Clark's characteristic ring: sector 0 of the one ring builder
/// ([`crate::schemes::catmull_clark::local::characteristic_sector`]), normalised below.
fn catmull_clark(n: usize) -> Result<CharRing> {
    let (cells, _) = crate::schemes::catmull_clark::local::characteristic_sector(n)?;
    let mut sector = cells;
    // Normalise: outer ray corner of A at e_0, sector counter-clockwise.
    let q = sector[0].eval(1.0, 0.0);
    let (r, th) = ((q[0] * q[0] + q[1] * q[1]).sqrt(), q[1].atan2(q[0]));
    let (c, s) = (th.cos(), th.sin());
    let map = |p: &BezierPatch| {
        p.map_points(|x| [(c * x[0] + s * x[1]) / r, (-s * x[0] + c * x[1]) / r, 0.0])
    };
    sector = [map(&sector[0]), map(&sector[1]), map(&sector[2])];
    let e1 = sector[2].eval(0.0, 1.0);
    if e1[1] < 0.0 {
        sector = sector.map(|p| p.map_points(|x| [x[0], -x[1], 0.0]));
    }
    Ok(CharRing {
        n,
        lambda: catmull_clark_lambda(n),
        sector,
    })
}

/// The QAS+ characteristic map (valences 5..10) in fairsub's chart.
fn qas_half(n: usize) -> Result<CharRing> {
    use crate::schemes::qas::chi;
    let z = chi::z_values(n).map_err(|_| {
        Error::Unsupported(format!(
            "valence {n}: the contraction 1/2 uses the QAS+ characteristic map, tabulated for valences 5..10"
        ))
    })?;
    let (frame, _) = chi::sector_ring(n, &z);
    // Frame (u_f, v_f) has v_f along the clockwise ray at -alpha/2; the mesh chart has
    // (u, v) = (v_f, u_f): mesh A = frame C transposed, B = B transposed, C = A transposed.
    let rot = PI / n as f64;
    let (c, s) = (rot.cos(), rot.sin());
    let tr = |p: &[[[f64; 2]; 5]; 5]| {
        BezierPatch::from_fn(4, 4, |i, j| {
            let q = p[j][i];
            [c * q[0] - s * q[1], s * q[0] + c * q[1], 0.0]
        })
    };
    Ok(CharRing {
        n,
        lambda: 0.5,
        sector: [tr(&frame[2]), tr(&frame[1]), tr(&frame[0])],
    })
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    #[crate::unit::test]
    fn rings_are_normalised_and_self_similar() {
        for (n, kind) in [
            (5, ChiKind::CatmullClark),
            (3, ChiKind::CatmullClark),
            (7, ChiKind::Half),
        ] {
            let r = CharRing::new(n, kind).unwrap();
            let q = r.sector[0].eval(1.0, 0.0);
            assert!((q[0] - 1.0).abs() < 1e-12 && q[1].abs() < 1e-12, "{q:?}");
            let a = 2.0 * PI / n as f64;
            let e1 = r.sector[2].eval(0.0, 1.0);
            assert!(
                (e1[0] - a.cos()).abs() < 1e-9 && (e1[1] - a.sin()).abs() < 1e-9,
                "n={n} {e1:?}"
            );
            // The inner corner of A at (1/2, 0) is lambda times the outer one.
            let inner = r.sector[0].eval(0.0, 0.0);
            assert!(
                (inner[0] - r.lambda).abs() < 1e-9,
                "n={n}: {} vs {}",
                inner[0],
                r.lambda
            );
            // C(0, t) joins A(s, 0) of the next sector after rotation: the ray point at 3/4.
            let mid_c = r.sector[2].eval(0.0, 0.5);
            let rot = [
                a.cos() * r.sector[0].eval(0.5, 0.0)[0],
                a.sin() * r.sector[0].eval(0.5, 0.0)[0],
            ];
            assert!((mid_c[0] - rot[0]).abs() < 1e-9 && (mid_c[1] - rot[1]).abs() < 1e-9);
        }
    }
}
