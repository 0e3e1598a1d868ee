//! The bi-4 characteristic map chi of QAS+ (Section 3 of the QAS+ paper), valences 5..10.
//!
//! In a sector frame whose bisectrix is the x axis (rays at angles `+-alpha/2`,
//! `alpha = 2 pi / n`), the sector is the image of the unit square under
//! `(u, v) -> u (c^, s^) + v (c^, -s^)` (`c^ = cos alpha/2`, `s^ = sin alpha/2`): `(1, 0)` lies on
//! the ray at `+alpha/2`, the corner `(1, 1)` on the bisectrix. The tensor-border `chi_ij`
//! (`i = 0..4` along the outer edge `u = 1` from the corner, `j = 0..2` inwards) is the ansatz (1):
//! `chi_40 = (c^, s^)`, `chi_41 = z0 chi_40`, `chi_42 = z1 chi_40`, `chi_00 = (z2, 0)`,
//! `chi_11 = (z3, 0)`, `chi_22 = (z4, 0)`, `chi_10 = (z5, z6)`, `chi_20 = (z7, z8)`,
//! `chi_21 = (z9, z10)`, mirrored across the bisectrix for `i < j`, and `chi_3j` from C^2 between
//! sectors (`chi_3j = chi_4j + perp(chi_2j) / 2`, `perp` the component normal to the ray). It is
//! the tensor-border of the sector seen as one bi-4 patch `P` with `P[4 - j][4 - i] = chi_ij`.
//!
//! One ring has three bi-4 patches per sector: `A` over `[1/2, 1] x [0, 1/2]`, `B` over
//! `[1/2, 1]^2`, `C` the mirror of `A`. `A`'s rows near `u = 1` subdivide `P`; its rows near
//! `u = 1/2` continue the copy `chi / 2` C^2; both give its middle row, and this overlap, with the
//! overlaps of `B` (from `P` and from `A`), is the linear system the paper solves for
//! `z0, z5, z7, .., z10` given `z1 = 1/2, z2 = sqrt 2` and `z3, z4, z6` (Appendix B).
//!
//! Appendix A gives the solution as `z_i = (nu_2 z2 + nu_3 z3 + nu_4 z4 + nu_6 z6 + nu^) / k_i`.
//! fairsub derives the same system and solves it (see `tests/it/qas.rs`); the printed `nu_2 .. nu_6`
//! agree with the derivation exactly, the printed constants `nu^` do not: the extraction lost the
//! hats of `c^ = cos(alpha/2)`, `s^ = sin(alpha/2)` in that column, and for `i = 7` also a digit
//! (`4 c(18027 + 586 c)` must read `4 c^(180273 + 586 c)`). [`z_values`] uses the corrected
//! constants ([`NU_HAT_ERRATUM`]); with them the formulas solve the system to rounding for
//! n = 5..10 and give back the regular map at n = 4.

use crate::bezier::BezierPatch;
use crate::error::{Error, Result};
use std::f64::consts::{PI, SQRT_2};

/// What the Appendix A erratum changes.
pub const NU_HAT_ERRATUM: &str = "Appendix A, column nu^: the prefactors are c^ = cos(alpha/2) and s^ = sin(alpha/2) \
(printed c and s), and row i = 7 reads 4 c^(180273 + 586 c) (printed 4c(18027+586c))";

/// Appendix B: `(z3, z4, z6)` for n = 5..10.
pub const APPENDIX_B: [(usize, [f64; 3]); 6] = [
    (5, [1.0523486064, 0.6835325141, 0.1409618117]),
    (6, [1.0479628065, 0.6712282471, 0.1171902825]),
    (7, [1.0453666602, 0.6639841979, 0.1002802002]),
    (8, [1.0437024506, 0.6593541908, 0.0876392989]),
    (9, [1.0425713792, 0.6562128317, 0.0778325682]),
    (10, [1.0417674430, 0.6539824091, 0.0700027016]),
];

/// Appendix A's rows for `i = 5, 7, 8, 9, 10`: `(i, [nu_2, nu_3, nu_4, nu_6, nu^], k_i)` at
/// valence `n`, with the corrected constants when `corrected` (else as printed).
pub fn appendix_a(n: usize, corrected: bool) -> [(usize, [f64; 5], f64); 5] {
    let a = 2.0 * PI / n as f64;
    let (c, s) = (a.cos(), a.sin());
    let (ch, sh) = if corrected {
        ((a / 2.0).cos(), (a / 2.0).sin())
    } else {
        (c, s)
    };
    let k7 = if corrected { 180273.0 } else { 18027.0 };
    let kb = 123199.0 + 64716.0 * c;
    [
        (
            5,
            [
                127.0 * (1571.0 + 1320.0 * c),
                4.0 * (70789.0 + 18832.0 * c),
                -(5977.0 + 14260.0 * c),
                -19824.0 * s,
                2.0 * ch * (24779.0 + 1240.0 * c),
            ],
            4.0 * kb,
        ),
        (
            7,
            [
                -2667.0 * (793.0 + 40.0 * c),
                3116.0 * (793.0 + 40.0 * c),
                7.0 * (35871.0 - 6548.0 * c),
                -316848.0 * s,
                4.0 * ch * (k7 + 586.0 * c),
            ],
            2.0 * kb,
        ),
        (
            8,
            [
                -53340.0 * s,
                62320.0 * s,
                9440.0 * s,
                42.0 * (7733.0 + 3772.0 * c),
                -sh * (15837.0 - 1172.0 * c),
            ],
            kb,
        ),
        (
            9,
            [
                -2667.0 * (1387.0 + 132.0 * c),
                3116.0 * (1387.0 + 132.0 * c),
                3.0 * (177155.0 - 804.0 * c),
                -501984.0 * s,
                14.0 * ch * (80389.0 - 372.0 * c),
            ],
            4.0 * kb,
        ),
        (
            10,
            [
                -88011.0 * s,
                102828.0 * s,
                15576.0 * s,
                21.0 * (13199.0 + 5976.0 * c),
                -7.0 * sh * (4613.0 + 186.0 * c),
            ],
            kb,
        ),
    ]
}

/// The scalars `z0 .. z10` of valence `n` (5..10): `z0 = 3/4`, `z1 = 1/2`, `z2 = sqrt 2`,
/// Appendix B for `z3, z4, z6` and the corrected Appendix A for the rest.
pub fn z_values(n: usize) -> Result<[f64; 11]> {
    let Some(&(_, b)) = APPENDIX_B.iter().find(|(m, _)| *m == n) else {
        return Err(Error::Unsupported(format!(
            "the QAS+ characteristic map chi is tabulated for valences 5..10, not {n}"
        )));
    };
    Ok(z_from(n, b, true))
}

/// `z0 .. z10` from `(z3, z4, z6)` by Appendix A (`corrected` constants or as printed).
pub fn z_from(n: usize, b: [f64; 3], corrected: bool) -> [f64; 11] {
    let mut z = [0.0; 11];
    z[0] = 0.75;
    z[1] = 0.5;
    z[2] = SQRT_2;
    z[3] = b[0];
    z[4] = b[1];
    z[6] = b[2];
    for (i, nu, k) in appendix_a(n, corrected) {
        z[i] = (nu[0] * z[2] + nu[1] * z[3] + nu[2] * z[4] + nu[3] * z[6] + nu[4]) / k;
    }
    z
}

type P2 = [f64; 2];

fn add(a: P2, b: P2) -> P2 {
    [a[0] + b[0], a[1] + b[1]]
}

fn sc(a: P2, s: f64) -> P2 {
    [a[0] * s, a[1] * s]
}

/// `sum w_k p_k`.
fn comb(terms: &[(f64, P2)]) -> P2 {
    terms
        .iter()
        .fold([0.0, 0.0], |acc, &(w, p)| add(acc, sc(p, w)))
}

/// The sector as one bi-4 patch `P[a][b]` (a along u, b along v), known where the tensor-border
/// defines it (`a >= 2` or `b >= 2`); the unknown block `a, b < 2` is NaN.
pub fn sector_patch(n: usize, z: &[f64; 11]) -> [[P2; 5]; 5] {
    let a = 2.0 * PI / n as f64;
    let (ch, sh) = ((a / 2.0).cos(), (a / 2.0).sin());
    let ray = [ch, sh];
    let perp = [-sh, ch];
    let mirror = |p: P2| [p[0], -p[1]];
    let mut x = [[[f64::NAN; 2]; 3]; 5]; // x[i][j] = chi_ij
    x[4][0] = ray;
    x[4][1] = sc(ray, z[0]);
    x[4][2] = sc(ray, z[1]);
    x[0][0] = [z[2], 0.0];
    x[1][1] = [z[3], 0.0];
    x[2][2] = [z[4], 0.0];
    x[1][0] = [z[5], z[6]];
    x[2][0] = [z[7], z[8]];
    x[2][1] = [z[9], z[10]];
    x[0][1] = mirror(x[1][0]);
    x[0][2] = mirror(x[2][0]);
    x[1][2] = mirror(x[2][1]);
    for j in 0..3 {
        let d = x[2][j][0] * perp[0] + x[2][j][1] * perp[1];
        x[3][j] = add(x[4][j], sc(perp, 0.5 * d));
    }
    let mut p = [[[f64::NAN; 2]; 5]; 5];
    for (i, row) in x.iter().enumerate() {
        for (j, &q) in row.iter().enumerate() {
            p[4 - j][4 - i] = q;
            // Mirror symmetry of the sector: P[b][a] = mirror(P[a][b]).
            p[4 - i][4 - j] = mirror(q);
        }
    }
    p
}

/// de Casteljau halves of a quartic row: `(lower, upper)`.
fn halves(c: &[P2; 5]) -> ([P2; 5], [P2; 5]) {
    let mut lo = [[0.0; 2]; 5];
    let mut hi = [[0.0; 2]; 5];
    let mut cur: Vec<P2> = c.to_vec();
    for k in 0..5 {
        lo[k] = cur[0];
        hi[4 - k] = *cur.last().expect("non-empty");
        cur = cur.windows(2).map(|w| sc(add(w[0], w[1]), 0.5)).collect();
    }
    (lo, hi)
}

/// One ring of the characteristic map: the three patches `A, B, C` of the sector in the frame
/// of the module documentation (BB-nets `[a][b]`, a along u, b along v), and the largest
/// mismatch between coefficients that two parts of the construction both define (0 when the
/// z values solve the paper's system).
pub fn sector_ring(n: usize, z: &[f64; 11]) -> ([[[P2; 5]; 5]; 3], f64) {
    let (patches, res) = sector_ring_residuals(n, z);
    (patches, res.iter().fold(0.0, |m, r| m.max(r.abs())))
}

/// Like [`sector_ring`], returning every mismatch component (the residuals of the paper's
/// linear system for the z values).
pub fn sector_ring_residuals(n: usize, z: &[f64; 11]) -> ([[[P2; 5]; 5]; 3], Vec<f64>) {
    let p = sector_patch(n, z);
    // Rows of P near u = 1 restricted to u in [1/2, 1]: from the end, (P2 + 2 P3 + P4)/4, ...
    let outer_rows: [[P2; 5]; 3] = {
        let mut r = [[[0.0; 2]; 5]; 3];
        for b in 0..5 {
            r[0][b] = comb(&[(0.25, p[2][b]), (0.5, p[3][b]), (0.25, p[4][b])]);
            r[1][b] = comb(&[(0.5, p[3][b]), (0.5, p[4][b])]);
            r[2][b] = p[4][b];
        }
        r
    };
    let mut a_patch = [[[0.0; 2]; 5]; 5];
    let mut b_patch = [[[0.0; 2]; 5]; 5];
    let mut residuals: Vec<f64> = Vec::new();
    let mut diff = |x: P2, y: P2| {
        residuals.push(x[0] - y[0]);
        residuals.push(x[1] - y[1]);
    };
    // A: outer rows (a = 2, 3, 4) from the lower v half of the outer rows.
    let mut a_outer = [[[0.0; 2]; 5]; 3];
    let mut b_outer = [[[0.0; 2]; 5]; 3];
    for (k, row) in outer_rows.iter().enumerate() {
        let (lo, hi) = halves(row);
        a_outer[k] = lo;
        b_outer[k] = hi;
    }
    // A: inner rows (a = 0, 1, 2) continue chi/2 C^2 across u = 1/2.
    for b in 0..5 {
        let (p2, p3, p4) = (p[2][b], p[3][b], p[4][b]);
        a_patch[0][b] = sc(p4, 0.5);
        a_patch[1][b] = comb(&[(1.0, p4), (-0.5, p3)]);
        a_patch[2][b] = comb(&[(2.0, p4), (-2.0, p3), (0.5, p2)]);
        diff(a_patch[2][b], a_outer[0][b]);
        a_patch[3][b] = a_outer[1][b];
        a_patch[4][b] = a_outer[2][b];
    }
    // B: rows a >= 2 from P; columns b <= 2 continue A C^2 across v = 1/2.
    for a in 0..5 {
        let ext = [
            a_patch[a][4],
            comb(&[(2.0, a_patch[a][4]), (-1.0, a_patch[a][3])]),
            comb(&[
                (4.0, a_patch[a][4]),
                (-4.0, a_patch[a][3]),
                (1.0, a_patch[a][2]),
            ]),
        ];
        for b in 0..5 {
            let from_p = if a >= 2 {
                Some(b_outer[a - 2][b])
            } else {
                None
            };
            let from_a = if b <= 2 { Some(ext[b]) } else { None };
            b_patch[a][b] = match (from_p, from_a) {
                (Some(x), Some(y)) => {
                    diff(x, y);
                    x
                }
                (Some(x), None) | (None, Some(x)) => x,
                (None, None) => {
                    // By the mirror symmetry of B: B[a][b] = mirror(B[b][a]) with b >= 2... a < 2,
                    // b > 2: its mirror has a >= 2 and is known from P.
                    let y = b_outer[b - 2][a];
                    [y[0], -y[1]]
                }
            };
        }
    }
    let mut c_patch = [[[0.0; 2]; 5]; 5];
    for a in 0..5 {
        for b in 0..5 {
            let y = a_patch[b][a];
            c_patch[a][b] = [y[0], -y[1]];
        }
    }
    ([a_patch, b_patch, c_patch], residuals)
}

/// The characteristic ring of QAS+ at valence `n` (5..10) as `3 n` planar bi-4 patches
/// (counter-clockwise, sector `s` rotated by `s alpha`), and the construction's consistency
/// defect (see [`sector_ring`]).
pub fn chi_ring(n: usize) -> Result<(Vec<BezierPatch>, f64)> {
    let z = z_values(n)?;
    let (sector, defect) = sector_ring(n, &z);
    let mut out = Vec::with_capacity(3 * n);
    for s in 0..n {
        let ang = 2.0 * PI * s as f64 / n as f64;
        let (ca, sa) = (ang.cos(), ang.sin());
        for patch in &sector {
            // The frame's (u, v) is clockwise: transpose for a counter-clockwise patch.
            let p = BezierPatch::from_fn(4, 4, |i, j| {
                let q = patch[j][i];
                [ca * q[0] - sa * q[1], sa * q[0] + ca * q[1], 0.0]
            });
            out.push(p);
        }
    }
    Ok((out, defect))
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    #[crate::unit::test]
    fn regular_valence_gives_the_regular_map() {
        // n = 4 with the regular z3, z4, z6: the construction is consistent and the corrected
        // Appendix A returns the regular z5, z7..z10.
        let r = 0.5f64.sqrt();
        let b = [0.75 * SQRT_2, 0.5 * SQRT_2, 0.25 * r];
        let z = z_from(4, b, true);
        let expect = [
            (5, 1.75 * r),
            (7, 1.5 * r),
            (8, 0.5 * r),
            (9, 1.25 * r),
            (10, 0.25 * r),
        ];
        for (i, e) in expect {
            assert!((z[i] - e).abs() < 1e-12, "z{i} = {} vs {e}", z[i]);
        }
        let (_, defect) = sector_ring(4, &z);
        assert!(defect < 1e-12);
    }
}
