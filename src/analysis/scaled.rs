//! The C^1 certificate of a complex whose patches may meet with different scalings along and
//! across a shared side (the rings of polar bi-2 and adjustable TPS): C^1 up to a per-piece
//! affine reparametrisation, with the fitted factor per join.

use crate::bezier::BezierPatch;
use crate::bezier::complex::PatchComplex;
use crate::geom::{self, Point};
use serde::Serialize;

/// The C^1 certificate of a complex whose patches may meet with different scalings along and
/// across a shared side (polar rings halve radially only; adjustable TPS rings shrink by
/// different factors along and across): per shared piece, the cross-boundary derivative of the
/// second patch must be a constant multiple `-kappa D_A` of the first's, `kappa > 0`, which is C^1
/// after an affine reparametrisation of the second patch.
#[derive(Debug, Clone, Serialize, Default)]
pub struct ScaledDefects {
    /// Shared pieces measured.
    pub pieces: usize,
    /// Largest positional gap.
    pub c0: f64,
    /// Largest residual `|D_A + kappa D_B| / max |D_A|` over a piece, with the best `kappa`
    /// of the piece (0 for a C^1 join).
    pub c1_relative: f64,
    /// Smallest fitted `kappa` (positive for a C^1 join).
    pub kappa_min: f64,
    /// Largest fitted `kappa`.
    pub kappa_max: f64,
    /// Largest angle between the normals, radians.
    pub g1: f64,
}

impl ScaledDefects {
    fn merge(&mut self, o: &ScaledDefects) {
        if self.pieces == 0 {
            *self = o.clone();
            return;
        }
        self.pieces += o.pieces;
        self.c0 = self.c0.max(o.c0);
        self.c1_relative = self.c1_relative.max(o.c1_relative);
        self.kappa_min = self.kappa_min.min(o.kappa_min);
        self.kappa_max = self.kappa_max.max(o.kappa_max);
        self.g1 = self.g1.max(o.g1);
    }
}

/// [`ScaledDefects`] over a whole complex and per kind of join (`ring1|ring2`, `cap|cap`, ...).
#[derive(Debug, Clone, Serialize, Default)]
pub struct ScaledContinuity {
    /// All shared pieces.
    pub all: ScaledDefects,
    /// Per kind of join.
    pub by_kind: std::collections::BTreeMap<String, ScaledDefects>,
}

/// Measures [`ScaledContinuity`] over all shared boundaries of a complex.
pub fn continuity_up_to_scaling(c: &PatchComplex) -> ScaledContinuity {
    use crate::bezier::Side;
    use crate::surface::adjacency::{default_tolerance, shared_boundaries};
    let tol = default_tolerance(c);
    let across = |p: &BezierPatch, side: Side, t: f64| -> (Point, Point, Point) {
        let [u, v] = side.domain_point(t);
        let d = p.derivatives(u, v);
        let n = p.normal_from(u, v, &d);
        let out = match side {
            Side::U1 => d.du,
            Side::U0 => geom::scale(d.du, -1.0),
            Side::V1 => d.dv,
            Side::V0 => geom::scale(d.dv, -1.0),
        };
        (d.p, out, n)
    };
    const SAMPLES: usize = 9;
    let mut out = ScaledContinuity::default();
    for sb in shared_boundaries(c, tol) {
        let (pa, pb) = (&c.patches[sb.a], &c.patches[sb.b]);
        let mut d = ScaledDefects {
            pieces: 1,
            ..Default::default()
        };
        let mut da = Vec::with_capacity(SAMPLES);
        let mut db = Vec::with_capacity(SAMPLES);
        for k in 0..SAMPLES {
            let t = sb.t[0] + (sb.t[1] - sb.t[0]) * k as f64 / (SAMPLES - 1) as f64;
            let s = sb.map_to_b(t);
            let (xa, a, na) = across(pa, sb.side_a, t);
            let (xb, b, nb) = across(pb, sb.side_b, s);
            d.c0 = d.c0.max(geom::dist(xa, xb));
            if geom::norm(na) > 0.0 && geom::norm(nb) > 0.0 {
                let g = geom::norm(geom::cross(na, nb)).atan2(geom::dot(na, nb));
                d.g1 = d.g1.max(g);
            }
            da.push(a);
            db.push(b);
        }
        let num: f64 = da.iter().zip(&db).map(|(a, b)| geom::dot(*a, *b)).sum();
        let den: f64 = db.iter().map(|b| geom::dot(*b, *b)).sum();
        let scale = da.iter().map(|a| geom::norm(*a)).fold(0.0, f64::max);
        if den > 0.0 && scale > 0.0 {
            let kappa = -num / den;
            d.kappa_min = kappa;
            d.kappa_max = kappa;
            let res = da
                .iter()
                .zip(&db)
                .map(|(a, b)| geom::norm(geom::add(*a, geom::scale(*b, kappa))))
                .fold(0.0, f64::max);
            d.c1_relative = res / scale;
        }
        let (mut ka, mut kb) = (
            c.provenance[sb.a].group_name(),
            c.provenance[sb.b].group_name(),
        );
        if ka > kb {
            std::mem::swap(&mut ka, &mut kb);
        }
        out.by_kind
            .entry(format!("{ka}|{kb}"))
            .or_default()
            .merge(&d);
        out.all.merge(&d);
    }
    out
}
