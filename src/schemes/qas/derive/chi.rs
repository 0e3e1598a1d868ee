//! The QAS+ characteristic map `chi` of Section 3 for any valence: the scalars `z3, z4, z6`
//! that Appendix B tabulates for n = 5..10, derived the way Section 3 describes.
//!
//! With `z0 = 3/4`, `z1 = 1/2`, `z2 = sqrt 2` fixed, the C^2 join of the split tensor-border with
//! its half-size copy ([`crate::schemes::qas::chi::sector_ring_residuals`]) is a linear system
//! for `z5, z7, .., z10`; `z3, z4, z6` then minimise `F_4` (sum over `i + j = 4` of
//! `4!/(i! j!) (d^i_s d^j_t f)^2`, integrated over each patch's unit square) over the sector's
//! three bi-4 patches. The patches are affine in the free scalars, so both steps are linear.
//! Measured: Appendix B is reproduced to 6e-11 for n = 5..10, and n = 4 gives the regular map
//! (`tests/it/derive.rs`).

use crate::error::{Error, Result};
use crate::schemes::eg::derive::guide::fairness_gram;
use crate::schemes::qas::chi::{sector_ring_residuals, z_from};
use nalgebra::{DMatrix, DVector};

/// `z` with `z3, z4, z6` given and `z5, z7..z10` solving the C^2 system; and the largest
/// residual of the system.
pub fn solve_join(n: usize, z346: [f64; 3]) -> ([f64; 11], f64) {
    let mut base = z_from(n, z346, true);
    let free = [5, 7, 8, 9, 10];
    for &i in &free {
        base[i] = 0.0;
    }
    let res = |z: &[f64; 11]| DVector::from_vec(sector_ring_residuals(n, z).1);
    let r0 = res(&base);
    let mut m = DMatrix::zeros(r0.len(), free.len());
    for (c, &i) in free.iter().enumerate() {
        let mut z = base;
        z[i] = 1.0;
        m.set_column(c, &(res(&z) - &r0));
    }
    let x = m
        .clone()
        .svd(true, true)
        .solve(&(-&r0), 1e-12)
        .unwrap_or_else(|_| DVector::zeros(free.len()));
    let mut z = base;
    for (c, &i) in free.iter().enumerate() {
        z[i] = x[c];
    }
    let resid = (m * x + r0).amax();
    (z, resid)
}

/// The sector's three bi-4 patches as one vector (patch, coordinate, coefficient).
fn patch_vector(n: usize, z: &[f64; 11]) -> DVector<f64> {
    let (p, _) = sector_ring_residuals(n, z);
    let mut v = Vec::with_capacity(150);
    for patch in &p {
        for comp in 0..2 {
            for a in 0..5 {
                for b in 0..5 {
                    v.push(patch[a][b][comp]);
                }
            }
        }
    }
    DVector::from_vec(v)
}

/// The derived `z0 .. z10` of valence `n` (>= 3) and the residual of the C^2 system.
pub fn derived_z(n: usize) -> Result<([f64; 11], f64)> {
    if n < 3 {
        return Err(Error::InvalidArgument(format!("valence {n}")));
    }
    let base = [1.0, 0.7, 0.1];
    let at = |zf: [f64; 3]| patch_vector(n, &solve_join(n, zf).0);
    let c0 = at(base);
    let mut m = DMatrix::zeros(c0.len(), 3);
    for k in 0..3 {
        let mut zf = base;
        zf[k] += 1.0;
        m.set_column(k, &(at(zf) - &c0));
    }
    let g4 = fairness_gram(4, 4);
    let mut h = DMatrix::zeros(3, 3);
    let mut g = DVector::zeros(3);
    for blk in 0..6 {
        let mk = m.rows(25 * blk, 25);
        let ck = c0.rows(25 * blk, 25);
        h += mk.transpose() * &g4 * mk;
        g += mk.transpose() * &g4 * ck;
    }
    let dz = h
        .lu()
        .solve(&(-g))
        .ok_or_else(|| Error::Unsupported(format!("F_4 of chi is singular at valence {n}")))?;
    let zf = [base[0] + dz[0], base[1] + dz[1], base[2] + dz[2]];
    Ok(solve_join(n, zf))
}

/// The characteristic ring of Section 3 with the derived `z` at any valence `n >= 3`: `3 n`
/// planar bi-4 patches (counter-clockwise, as [`crate::schemes::qas::chi::chi_ring`]) and the
/// construction's consistency defect.
pub fn derived_chi_ring(n: usize) -> Result<(Vec<crate::bezier::BezierPatch>, f64)> {
    let (z, _) = derived_z(n)?;
    let (sector, defect) = crate::schemes::qas::chi::sector_ring(n, &z);
    let mut out = Vec::with_capacity(3 * n);
    for s in 0..n {
        let ang = 2.0 * std::f64::consts::PI * s as f64 / n as f64;
        let (ca, sa) = (ang.cos(), ang.sin());
        for patch in &sector {
            out.push(crate::bezier::BezierPatch::from_fn(4, 4, |i, j| {
                let q = patch[j][i];
                [ca * q[0] - sa * q[1], sa * q[0] + ca * q[1], 0.0]
            }));
        }
    }
    Ok((out, defect))
}
