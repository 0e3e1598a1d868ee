//! Rational tensor-product patches (BezierView's type 8): a patch with a weight `w_ij > 0` per
//! coefficient is the quotient `X / W` of the polynomial patch `X` of the homogeneous
//! coefficients `w_ij b_ij` and the scalar polynomial patch `W` of the weights. Evaluation and
//! the exact derivatives follow from the quotient rule; splitting, sub-patches, degree raising
//! and reordering apply the polynomial operation to `X` and `W` alike (the homogeneous form),
//! which is exact.

use super::{BezierPatch, Derivatives};
use crate::error::{Error, Result};
use crate::geom::{Point, add, scale, sub};

impl BezierPatch {
    /// A rational patch from its Euclidean control points `cps` (row-major, `i` along `u`, as
    /// [`BezierPatch::new`]) and one weight per point.
    ///
    /// # Errors
    /// When the counts do not match the degrees, or a weight is not a finite positive number.
    ///
    /// ```
    /// use fairsub::bezier::BezierPatch;
    /// // a quarter circle in the plane z = 0, swept along z: weights 1, 1/sqrt(2), 1
    /// let h = std::f64::consts::FRAC_1_SQRT_2;
    /// let cps = vec![[1., 0., 0.], [1., 0., 1.], [1., 1., 0.], [1., 1., 1.], [0., 1., 0.], [0., 1., 1.]];
    /// let p = BezierPatch::rational(2, 1, cps, vec![1., 1., h, h, 1., 1.]).unwrap();
    /// let q = p.eval(0.3, 0.5);
    /// assert!((q[0] * q[0] + q[1] * q[1] - 1.0).abs() < 1e-15);
    /// ```
    pub fn rational(
        deg_u: usize,
        deg_v: usize,
        cps: Vec<Point>,
        weights: Vec<f64>,
    ) -> Result<BezierPatch> {
        let n = (deg_u + 1) * (deg_v + 1);
        if cps.len() != n || weights.len() != n {
            return Err(Error::InvalidArgument(format!(
                "a rational patch of bi-degree ({deg_u}, {deg_v}) has {n} control points and \
                 weights, not {} and {}",
                cps.len(),
                weights.len()
            )));
        }
        if let Some(k) = weights.iter().position(|w| !(w.is_finite() && *w > 0.0)) {
            return Err(Error::InvalidArgument(format!(
                "weight {} of control point {k} of a rational patch is not a positive number",
                weights[k]
            )));
        }
        Ok(BezierPatch {
            deg_u,
            deg_v,
            cps,
            weights: Some(weights),
        })
    }

    /// Whether the patch is rational (carries weights).
    pub fn is_rational(&self) -> bool {
        self.weights.is_some()
    }
}

/// The polynomial patches `X` (homogeneous coefficients `w b`) and `W` (the weights, in the
/// first coordinate) of a rational patch.
fn homogeneous(p: &BezierPatch, w: &[f64]) -> (BezierPatch, BezierPatch) {
    let x = p.cps.iter().zip(w).map(|(&c, &wi)| scale(c, wi)).collect();
    let ws = w.iter().map(|&wi| [wi, 0.0, 0.0]).collect();
    (
        BezierPatch::new(p.deg_u, p.deg_v, x),
        BezierPatch::new(p.deg_u, p.deg_v, ws),
    )
}

/// The rational patch of the homogeneous pair `(X, W)` (see [`homogeneous`]).
fn from_homogeneous(x: BezierPatch, w: BezierPatch) -> BezierPatch {
    let weights: Vec<f64> = w.cps.iter().map(|c| c[0]).collect();
    let cps = x
        .cps
        .iter()
        .zip(&weights)
        .map(|(&c, &wi)| scale(c, 1.0 / wi))
        .collect();
    BezierPatch {
        deg_u: x.deg_u,
        deg_v: x.deg_v,
        cps,
        weights: Some(weights),
    }
}

/// A polynomial operation applied to a rational patch through its homogeneous form.
pub(super) fn map(p: &BezierPatch, f: impl Fn(&BezierPatch) -> BezierPatch) -> BezierPatch {
    let (x, w) = homogeneous(p, p.weights.as_deref().expect("a rational patch"));
    from_homogeneous(f(&x), f(&w))
}

/// [`map`] for an operation that gives two patches (a split).
pub(super) fn map2(
    p: &BezierPatch,
    f: impl Fn(&BezierPatch) -> (BezierPatch, BezierPatch),
) -> (BezierPatch, BezierPatch) {
    let (x, w) = homogeneous(p, p.weights.as_deref().expect("a rational patch"));
    let ((x0, x1), (w0, w1)) = (f(&x), f(&w));
    (from_homogeneous(x0, w0), from_homogeneous(x1, w1))
}

/// The point `X / W` at `(u, v)`.
pub(super) fn eval(p: &BezierPatch, w: &[f64], u: f64, v: f64) -> Point {
    let (x, ws) = homogeneous(p, w);
    scale(x.eval(u, v), 1.0 / ws.eval(u, v)[0])
}

/// The exact derivatives of `P = X / W` by the quotient rule: `W P_u = X_u - W_u P`,
/// `W P_uu = X_uu - 2 W_u P_u - W_uu P`, `W P_uv = X_uv - W_u P_v - W_v P_u - W_uv P`, and
/// likewise in `v`.
pub(super) fn derivatives(p: &BezierPatch, w: &[f64], u: f64, v: f64) -> Derivatives {
    let (x, ws) = homogeneous(p, w);
    let dx = x.derivatives(u, v);
    let dw = ws.derivatives(u, v);
    let (w0, wu, wv) = (dw.p[0], dw.du[0], dw.dv[0]);
    let (wuu, wuv, wvv) = (dw.duu[0], dw.duv[0], dw.dvv[0]);
    let r = 1.0 / w0;
    let pt = scale(dx.p, r);
    let du = scale(sub(dx.du, scale(pt, wu)), r);
    let dv = scale(sub(dx.dv, scale(pt, wv)), r);
    let duu = scale(sub(dx.duu, add(scale(du, 2.0 * wu), scale(pt, wuu))), r);
    let dvv = scale(sub(dx.dvv, add(scale(dv, 2.0 * wv), scale(pt, wvv))), r);
    let duv = scale(
        sub(
            dx.duv,
            add(add(scale(dv, wu), scale(du, wv)), scale(pt, wuv)),
        ),
        r,
    );
    Derivatives {
        p: pt,
        du,
        dv,
        duu,
        duv,
        dvv,
    }
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;
    use crate::geom::norm;

    /// An octant of the unit sphere as a bi-quadratic rational patch (one side collapsed to
    /// the pole): the quarter circle in u times the quarter circle in v.
    pub(crate) fn sphere_octant() -> BezierPatch {
        let h = std::f64::consts::FRAC_1_SQRT_2;
        // meridian quarter circle from the equator (1,0,0)/(0,1,0)... as a tensor product of
        // two quarter circles: (cos a cos b, sin a cos b, sin b)
        let circle = [([1.0, 0.0], 1.0), ([1.0, 1.0], h), ([0.0, 1.0], 1.0)];
        let mut cps = Vec::new();
        let mut ws = Vec::new();
        for &(a, wa) in &circle {
            for &(b, wb) in &circle {
                cps.push([a[0] * b[0], a[1] * b[0], b[1]]);
                ws.push(wa * wb);
            }
        }
        BezierPatch::rational(2, 2, cps, ws).unwrap()
    }

    #[crate::unit::test]
    fn sphere_octant_is_exact() {
        let p = sphere_octant();
        for &(u, v) in &[(0.1, 0.2), (0.5, 0.5), (0.9, 0.3), (0.0, 0.7)] {
            let q = p.eval(u, v);
            assert!((norm(q) - 1.0).abs() < 1e-15, "{q:?}");
            let d = p.derivatives(u, v);
            assert!(crate::geom::dist(d.p, q) < 1e-15);
            // unit sphere with outward normal: k1 = k2 = -1 when du x dv points outward
            let c = d.curvature().expect("regular");
            let n = p.normal(u, v);
            let s = crate::geom::dot(n, q).signum();
            assert!((c.gauss - 1.0).abs() < 1e-12, "{c:?}");
            assert!((c.mean + s).abs() < 1e-12, "{c:?}");
        }
    }

    #[crate::unit::test]
    fn derivatives_match_differences() {
        let p = sphere_octant();
        let (u, v, h) = (0.37, 0.61, 1e-5);
        let d = p.derivatives(u, v);
        let fd = |a: Point, b: Point| scale(sub(a, b), 0.5 / h);
        let close = |a: Point, b: Point| norm(sub(a, b)) < 1e-8;
        assert!(close(d.du, fd(p.eval(u + h, v), p.eval(u - h, v))));
        assert!(close(d.dv, fd(p.eval(u, v + h), p.eval(u, v - h))));
        let du = |u: f64, v: f64| p.derivatives(u, v).du;
        assert!(close(d.duu, fd(du(u + h, v), du(u - h, v))));
        assert!(close(d.duv, fd(du(u, v + h), du(u, v - h))));
        let dv = |u: f64, v: f64| p.derivatives(u, v).dv;
        assert!(close(d.dvv, fd(dv(u, v + h), dv(u, v - h))));
    }

    #[crate::unit::test]
    fn homogeneous_operations_keep_the_surface() {
        let p = sphere_octant();
        let (a, b) = p.split_u(0.3);
        assert!(crate::geom::dist(a.eval(0.5, 0.4), p.eval(0.15, 0.4)) < 1e-15);
        assert!(crate::geom::dist(b.eval(0.5, 0.4), p.eval(0.65, 0.4)) < 1e-15);
        let r = p.raised_to(3, 4).unwrap();
        assert!(crate::geom::dist(r.eval(0.2, 0.9), p.eval(0.2, 0.9)) < 1e-15);
        let t = p.transposed();
        assert!(crate::geom::dist(t.eval(0.2, 0.9), p.eval(0.9, 0.2)) < 1e-15);
        let s = p.subpatch(0.25, 0.5, 0.1, 0.2);
        assert!(crate::geom::dist(s.eval(0.5, 0.5), p.eval(0.375, 0.15)) < 1e-15);
        assert!(BezierPatch::rational(1, 1, vec![[0.0; 3]; 4], vec![1.0, 0.0, 1.0, 1.0]).is_err());
    }
}
