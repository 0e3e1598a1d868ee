//! What the derivatives at one point give: whether the tangent plane is determined, the unit
//! normal (also at collapsed edges and corners, as a limit), and the curvatures.

use super::{Curvature, Derivatives};
use crate::geom::{Point, add, cross, dot, norm, scale};

/// Relative size below which a tangent vector counts as vanished (collapsed edge) and a normal
/// as undetermined.
const DEGENERATE_REL: f64 = 1e-10;

/// Smallest sine of the angle between the partials at which [`BezierPatch::curvatures`](super::BezierPatch::curvatures) takes
/// the curvature of a point beside a degenerate one.
pub const WELL_CONDITIONED: f64 = 1e-3;

#[inline]
fn norm_inf(p: Point) -> f64 {
    p[0].abs().max(p[1].abs()).max(p[2].abs())
}

impl Derivatives {
    /// Whether the tangent plane is determined by `du`, `dv` alone: neither vector is negligible
    /// (relative to the other and to the rounding level of the point's coordinates) and they are
    /// not parallel (sine of their angle above `1e-10`).
    pub fn is_regular(&self) -> bool {
        let (a, b) = (norm(self.du), norm(self.dv));
        let floor = 1e-12 * (norm_inf(self.p) + a.max(b));
        a > floor && b > floor && norm(cross(self.du, self.dv)) > DEGENERATE_REL * a * b
    }

    /// The unit normal `du x dv / |du x dv|`. Where that vanishes (a collapsed edge or corner,
    /// see [`Derivatives::is_regular`]) it returns the limit of the normal approached from the
    /// domain direction `toward = (hu, hv)`: with `a = hu duu + hv duv` and `b = hu duv + hv dvv`
    /// (the change of `du` and `dv` along that direction) the normal at parameter offset `s`
    /// is `du x dv + s (a x dv + du x b) + s^2 (a x b) + ...`, and the first term that does not
    /// vanish gives the limit direction. This is exact at a collapsed edge (one partial is zero
    /// along it) and at a corner where both partials vanish. Returns `None` when all three
    /// terms vanish (then [`BezierPatch::normal`](super::BezierPatch::normal) falls back to a small inward offset).
    pub fn normal_toward(&self, toward: [f64; 2]) -> Option<Point> {
        if self.is_regular() {
            return Some(scale(
                cross(self.du, self.dv),
                1.0 / norm(cross(self.du, self.dv)),
            ));
        }
        let [hu, hv] = toward;
        let a = add(scale(self.duu, hu), scale(self.duv, hv));
        let b = add(scale(self.duv, hu), scale(self.dvv, hv));
        let n1 = add(cross(a, self.dv), cross(self.du, b));
        let scale1 = (norm(a) + norm(self.du)) * (norm(b) + norm(self.dv));
        if norm(n1) > DEGENERATE_REL * scale1 && scale1 > 0.0 {
            return Some(scale(n1, 1.0 / norm(n1)));
        }
        let n2 = cross(a, b);
        if norm(n2) > DEGENERATE_REL * norm(a) * norm(b) && norm(n2) > 0.0 {
            return Some(scale(n2, 1.0 / norm(n2)));
        }
        None
    }

    /// Curvatures from the first fundamental form `E, F, G` (of `du`, `dv`) and the second
    /// `L, M, N` (`duu`, `duv`, `dvv` dotted with the unit normal `du x dv / |du x dv|`):
    /// `K = (LN - M^2) / (EG - F^2)`, `H = (EN - 2FM + GL) / (2 (EG - F^2))`,
    /// `k1,2 = H +- sqrt(H^2 - K)` (`k1 >= k2`). Sign convention: see [`Curvature`]. `None` when
    /// the first fundamental form is singular ([`Derivatives::is_regular`] is false).
    pub fn curvature(&self) -> Option<Curvature> {
        if !self.is_regular() {
            return None;
        }
        let n = cross(self.du, self.dv);
        let n = scale(n, 1.0 / norm(n));
        let (e, f, g) = (
            dot(self.du, self.du),
            dot(self.du, self.dv),
            dot(self.dv, self.dv),
        );
        let (l, m, nn) = (dot(self.duu, n), dot(self.duv, n), dot(self.dvv, n));
        let det = e * g - f * f;
        if det <= 0.0 {
            return None;
        }
        let gauss = (l * nn - m * m) / det;
        let mean = (e * nn - 2.0 * f * m + g * l) / (2.0 * det);
        let disc = (mean * mean - gauss).max(0.0).sqrt();
        Some(Curvature {
            gauss,
            mean,
            k1: mean + disc,
            k2: mean - disc,
        })
    }
}
