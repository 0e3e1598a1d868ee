//! QAS+ (Karciauskas and Peters): quadratic-attraction subdivision with contraction ratio 1/2,
//! degree bi-4, on the d-nets of EG subdivision.
//!
//! # Local vector and layout
//!
//! Sources: `0` is the central point `p = q_1`; `1 + 12 s + e` is d-net node `e` of sector `s`
//! (exactly as EG, [`crate::schemes::eg`]); `1 + 12 n + 5 s + (k - 2)` is coefficient `q_k^s`,
//! `k = 2..6`, of the quadratic expansion. Each sector holds the full six BB-coefficients of a
//! quadratic over the unit triangle of its chart (`q_1 = p` corner, `q_2`, `q_3` along the chart's
//! first axis, `q_4`, `q_6` along the second, `q_5` between `q_3` and `q_6`), so the C^2, C^1 and
//! C^1-C^0 kinds of `q` differ only in their initial values ([`QKind`]); the restriction `S` of
//! (8) keeps every kind.
//!
//! The chart of `q`: the T tables weigh `q_6` heavily for the new node `d~_21`, which lies next to
//! the EG chart's `u` axis, and (3) makes sector `s + 1`'s first axis sector `s`'s second one;
//! both say that the q chart is the EG chart mirrored, i.e. fairsub's mesh chart: sector `s` is
//! the plane sector `u e_s + v e_(s+1)`, `e_s = (cos 2 pi s / n, sin 2 pi s / n)`, counter-
//! clockwise.
//!
//! # Rules
//!
//! * Regular bi-4 refinement and ring output as EG ([`crate::schemes::eg::build_step`]).
//! * The six inner nodes by (7) (`i = 1, 2`) and (6) (`i = 3`) of Appendix C, with the K tables
//!   read in the layout reconstructed in the papers README: entry `K_lm[a][b]` is the weight of the
//!   old node at EG chart point `(-1/2 + a/2, 3/2 - b/2)`, in whichever sector that lies; `K_31`,
//!   `K_32` list `v = 3/2 .. 0` and the weight at `(u, -v)` equals the one at `(u, v)`. In (6) the
//!   neighbour sector's expansion enters mirrored (`q_2 <-> q_4`, `q_3 <-> q_6`).
//! * `q~ = S q` by (8), with `lambda = 1/2` (QAS+) or another `lambda` (the accelerated variants
//!   keep the tables and change only `S`, as the paper's Section 7 describes).

pub mod descriptor;
pub mod entry;
pub mod local;
pub mod select;
pub mod surface;
pub use descriptor::{DESCRIPTOR, DESCRIPTOR_04, DESCRIPTOR_05_04, DESCRIPTOR_BI3};

pub mod bi3;
pub mod chi;
pub mod fit;
pub use fit::{characteristic_vectors, expansion_eigenvectors, fit_stencils, from_cnet};
pub mod derive;
pub mod facts;
pub mod qfile;
pub mod tables;

use crate::error::{Error, Result};
use crate::schemes::eg::{self, EgStep};
pub use crate::schemes::options::{QKind, QSpec};
use crate::stencil::Stencil;
use std::f64::consts::PI;

/// Source index of `q_k^s` (`k = 2..6`).
pub fn q_index(n: usize, s: usize, k: usize) -> usize {
    1 + 12 * n + 5 * (s % n) + (k - 2)
}

/// Number of sources of the QAS+ local vector.
pub fn num_sources(n: usize) -> usize {
    1 + 17 * n
}

/// The QAS+ tables of one valence, as weights.
#[derive(Debug, Clone)]
pub struct QasRules {
    /// Valence.
    pub n: usize,
    /// `tau[row][k - 2]`, rows in [`SPECIAL`](crate::schemes::eg::SPECIAL) order (11, 22, 21, 12, 31, 32).
    pub tau: [[f64; 5]; 6],
    /// `K_11, K_22, K_21, K_12` (5 x 5) and `K_31, K_32` (5 x 4, left half).
    pub k4: [[[f64; 5]; 5]; 4],
    /// `K_31, K_32`.
    pub k3: [[[f64; 4]; 5]; 2],
}

impl QasRules {
    /// The rules of valence `n` (5, 6, 7); other valences give an error naming the valence.
    pub fn new(n: usize) -> Result<QasRules> {
        let Some((t, k4, k3)) = tables::printed(n) else {
            return Err(Error::Unsupported(format!(
                "QAS+ has published rules for valences 5, 6 and 7 only (the paper prints T_8 but no K^8), not {n}"
            )));
        };
        let f = |x: i32| x as f64 * 1e-5;
        let mut tau = [[0.0; 5]; 6];
        for (r, row) in t.iter().enumerate() {
            for (c, &x) in row.iter().enumerate() {
                tau[r][c] = f(x);
            }
        }
        let mut kk4 = [[[0.0; 5]; 5]; 4];
        for (m, k) in k4.iter().enumerate() {
            for a in 0..5 {
                for b in 0..5 {
                    kk4[m][a][b] = f(k[a][b]);
                }
            }
        }
        let mut kk3 = [[[0.0; 4]; 5]; 2];
        for (m, k) in k3.iter().enumerate() {
            for a in 0..5 {
                for b in 0..4 {
                    kk3[m][a][b] = f(k[a][b]);
                }
            }
        }
        Ok(QasRules {
            n,
            tau,
            k4: kk4,
            k3: kk3,
        })
    }

    /// Weights of the old d-net nodes in special node `SPECIAL[row]` of sector `s`, as
    /// `(source, weight)`; the K layout of the module documentation.
    pub fn d_weights(&self, s: usize, row: usize) -> Result<Vec<(usize, f64)>> {
        let n = self.n;
        let mut out = Vec::new();
        let mut put = |a: usize, v_half: i32, w: f64| -> Result<()> {
            if w == 0.0 {
                return Ok(());
            }
            // (u, v) = (-1/2 + a/2, v_half / 2) in quarters.
            let (u, v) = (-2 + 2 * a as i32, 2 * v_half);
            let src = eg::dnet_node(n, s, u, v).ok_or_else(|| {
                Error::Unsupported(format!(
                    "QAS+ K entry at ({u}, {v})/4 of sector {s} is not a d-net node"
                ))
            })?;
            out.push((src, w));
            Ok(())
        };
        // SPECIAL order: 11, 22, 21, 12, 31, 32; K4 order: 11, 22, 21, 12.
        if row < 4 {
            for a in 0..5 {
                for b in 0..5 {
                    put(a, 3 - b as i32, self.k4[row][a][b])?;
                }
            }
        } else {
            let k = &self.k3[row - 4];
            for a in 0..5 {
                for b in 0..4 {
                    let vh = 3 - b as i32;
                    put(a, vh, k[a][b])?;
                    if vh > 0 {
                        put(a, -vh, k[a][b])?;
                    }
                }
            }
        }
        Ok(out)
    }

    /// Stencil of special node `SPECIAL[row]` of sector `s` by (7) or (6).
    pub fn special_node(&self, s: usize, row: usize) -> Result<Stencil> {
        let n = self.n;
        let mut st = Stencil::new();
        let mut total = 0.0;
        for (src, w) in self.d_weights(s, row)? {
            st.add(src, w);
            total += w;
        }
        let tau = self.tau[row];
        if row < 4 {
            for k in 2..=6 {
                st.add(q_index(n, s, k), tau[k - 2]);
                total += tau[k - 2];
            }
        } else {
            // (6): half from this sector, half mirrored from the next one.
            let mirror = [4, 6, 2, 5, 3]; // tau_2 -> q_4, tau_3 -> q_6, tau_4 -> q_2, ...
            for k in 2..=6 {
                st.add(q_index(n, s, k), 0.5 * tau[k - 2]);
                st.add(q_index(n, s + 1, mirror[k - 2]), 0.5 * tau[k - 2]);
                total += tau[k - 2];
            }
        }
        st.add(0, 1.0 - total);
        Ok(st.merged())
    }
}

/// The restriction matrix `S(lambda)` of (8) (rows and columns `q_1 .. q_6`).
pub fn restriction(lambda: f64) -> [[f64; 6]; 6] {
    let (l, m) = (lambda, 1.0 - lambda);
    [
        [1.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [m, l, 0.0, 0.0, 0.0, 0.0],
        [m * m, 2.0 * m * l, l * l, 0.0, 0.0, 0.0],
        [m, 0.0, 0.0, l, 0.0, 0.0],
        [m * m, m * l, 0.0, m * l, l * l, 0.0],
        [m * m, 0.0, 0.0, 2.0 * m * l, 0.0, l * l],
    ]
}

/// The QAS+^4 scheme at one valence.
#[derive(Debug, Clone)]
pub struct Qas {
    rules: QasRules,
}

impl Qas {
    /// The scheme at valence `n` (5, 6, 7).
    pub fn new(n: usize) -> Result<Qas> {
        Ok(Qas {
            rules: QasRules::new(n)?,
        })
    }

    /// The scheme with given tables (e.g. [`derive::derived_rules`]).
    pub fn with_rules(rules: QasRules) -> Qas {
        Qas { rules }
    }

    /// Valence.
    pub fn n(&self) -> usize {
        self.rules.n
    }

    /// The rules.
    pub fn rules(&self) -> &QasRules {
        &self.rules
    }

    /// Step and ring tables with contraction `lambda` in `S` (1/2 for QAS+).
    pub fn step(&self, lambda: f64) -> Result<EgStep> {
        let n = self.n();
        let sm = restriction(lambda);
        let mut tail = Vec::with_capacity(5 * n);
        for s in 0..n {
            for k in 2..=6 {
                let mut st = Stencil::new();
                st.add(0, sm[k - 1][0]);
                for c in 2..=6 {
                    let w = sm[k - 1][c - 1];
                    if w != 0.0 {
                        st.add(q_index(n, s, c), w);
                    }
                }
                tail.push(st.merged());
            }
        }
        eg::build_step(
            n,
            num_sources(n),
            &|s, row| self.rules.special_node(s, row),
            tail,
        )
    }
}

/// `e_s = (cos 2 pi s / n, sin 2 pi s / n)`.
fn axis(n: usize, s: usize) -> [f64; 2] {
    let a = 2.0 * PI * (s % n) as f64 / n as f64;
    [a.cos(), a.sin()]
}

/// The BB-coefficients `q_1 .. q_6` of sector `s` of the quadratic
/// `Q(x) = p + L x + x^T C x` (per coordinate: `lin = [L_x, L_y]`, `quad = [C_xx, C_xy, C_yy]`
/// meaning `C_xx x^2 + C_xy x y + C_yy y^2`), over the triangle `0, e_s, e_(s+1)`: the blossom
/// values at the domain points.
pub fn quadratic_bb(n: usize, s: usize, p: f64, lin: [f64; 2], quad: [f64; 3]) -> [f64; 6] {
    let (e0, e1) = (axis(n, s), axis(n, s + 1));
    let blossom = |a: [f64; 2], b: [f64; 2]| {
        p + 0.5 * (lin[0] * (a[0] + b[0]) + lin[1] * (a[1] + b[1]))
            + quad[0] * a[0] * b[0]
            + 0.5 * quad[1] * (a[0] * b[1] + a[1] * b[0])
            + quad[2] * a[1] * b[1]
    };
    let z = [0.0, 0.0];
    [
        blossom(z, z),
        blossom(z, e0),
        blossom(e0, e0),
        blossom(z, e1),
        blossom(e0, e1),
        blossom(e1, e1),
    ]
}

/// Parses a q file: lines `vertex V` (starts the section of input vertex `V`), `kind c2|c1|c1-c0`,
/// `p X Y Z`, `q SECTOR K X Y Z` (`K = 2..6`); `#` starts a comment. Coefficients not given keep
/// the values of the `qas-fit` rule. Errors name the line.
pub fn parse_q_file(
    text: &str,
    path: &std::path::Path,
) -> Result<std::collections::BTreeMap<u32, QSpec>> {
    let mut out: std::collections::BTreeMap<u32, QSpec> = std::collections::BTreeMap::new();
    let mut cur: Option<u32> = None;
    let err = |line: usize, msg: String| Error::Parse {
        path: path.to_path_buf(),
        line,
        msg,
    };
    for (ln, raw) in text.lines().enumerate() {
        let line = ln + 1;
        let t = raw.split('#').next().unwrap_or("").trim();
        if t.is_empty() {
            continue;
        }
        let f: Vec<&str> = t.split_whitespace().collect();
        let num = |s: &str| -> Result<f64> {
            s.parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| err(line, format!("'{s}' is not a finite number")))
        };
        let need_vertex = || -> Result<u32> {
            cur.ok_or_else(|| err(line, "a 'vertex V' line must come first".into()))
        };
        match f[0] {
            "vertex" if f.len() == 2 => {
                let v: u32 = f[1]
                    .parse()
                    .map_err(|_| err(line, format!("'{}' is not a vertex index", f[1])))?;
                let spec = out.entry(v).or_default();
                if spec.line == 0 {
                    spec.line = line;
                    spec.path = path.to_path_buf();
                }
                cur = Some(v);
            }
            "kind" if f.len() == 2 => {
                let k = match f[1] {
                    "c2" => QKind::C2,
                    "c1" => QKind::C1,
                    "c1-c0" | "c1c0" => QKind::C1C0,
                    other => {
                        return Err(err(line, format!("unknown kind '{other}' (c2, c1, c1-c0)")));
                    }
                };
                let v = need_vertex()?;
                out.entry(v).or_default().kind = k;
            }
            "p" if f.len() == 4 => {
                let p = [num(f[1])?, num(f[2])?, num(f[3])?];
                let v = need_vertex()?;
                out.entry(v).or_default().p = Some(p);
            }
            "q" if f.len() == 6 => {
                let s: usize = f[1]
                    .parse()
                    .map_err(|_| err(line, format!("'{}' is not a sector", f[1])))?;
                let k: usize = f[2]
                    .parse()
                    .map_err(|_| err(line, format!("'{}' is not a coefficient index", f[2])))?;
                if !(2..=6).contains(&k) {
                    return Err(err(
                        line,
                        format!("coefficient q_{k}: only q_2 .. q_6 are given (q_1 is p)"),
                    ));
                }
                let x = [num(f[3])?, num(f[4])?, num(f[5])?];
                let v = need_vertex()?;
                let spec = out.entry(v).or_default();
                spec.q.push((s, k, x));
                spec.q_lines.push(line);
            }
            _ => {
                return Err(err(
                    line,
                    format!(
                        "cannot read '{t}' (expected 'vertex V', 'kind c2|c1|c1-c0', 'p X Y Z' or 'q S K X Y Z')"
                    ),
                ));
            }
        }
    }
    Ok(out)
}

/// Checks that full per-sector coefficients `q[s][k - 1]` (`k = 1..6`, `q_1 = p`) form an
/// expansion of the given kind: the constraints (3) (C^2), its first five rows and the C^1
/// relation of the paper (C^1), or the tangent plane and C^0 between sectors (C^1-C^0). Returns
/// the first violated relation, naming the sector and coefficient.
pub fn check_kind(
    n: usize,
    q: &[[[f64; 3]; 6]],
    kind: QKind,
    tol: f64,
) -> std::result::Result<(), String> {
    let c = (2.0 * PI / n as f64).cos();
    let close = |a: [f64; 3], b: [f64; 3]| (0..3).all(|i| (a[i] - b[i]).abs() <= tol);
    let lin = |terms: &[(f64, [f64; 3])]| {
        let mut r = [0.0; 3];
        for &(w, v) in terms {
            for i in 0..3 {
                r[i] += w * v[i];
            }
        }
        r
    };
    for s in 0..n {
        let (a, b) = (q[s], q[(s + 1) % n]);
        let mut rules: Vec<(usize, [f64; 3], &str)> = vec![
            (2, a[3], "q_2^(s+1) = q_4^s"),
            (
                4,
                lin(&[(2.0 * (1.0 - c), a[0]), (-1.0, a[1]), (2.0 * c, a[3])]),
                "tangent plane",
            ),
            (3, a[5], "C^0: q_3^(s+1) = q_6^s"),
        ];
        if kind != QKind::C1C0 {
            rules.push((
                5,
                lin(&[(2.0 * (1.0 - c), a[3]), (-1.0, a[4]), (2.0 * c, a[5])]),
                "C^1",
            ));
        }
        if kind == QKind::C2 {
            rules.push((
                6,
                lin(&[
                    (4.0 * (1.0 - c).powi(2), a[0]),
                    (4.0 * (c - 1.0), a[1]),
                    (1.0, a[2]),
                    (8.0 * c * (1.0 - c), a[3]),
                    (-4.0 * c, a[4]),
                    (4.0 * c * c, a[5]),
                ]),
                "C^2",
            ));
        }
        for (k, expect, what) in rules {
            if !close(b[k - 1], expect) {
                return Err(format!(
                    "q_{k} of sector {} violates {what} (from sector {s}): it is {:?}, the constraint asks {:?}",
                    (s + 1) % n,
                    b[k - 1],
                    expect
                ));
            }
        }
    }
    Ok(())
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    #[crate::unit::test]
    fn quadratic_bb_satisfies_the_c2_sector_constraints() {
        // (3): q^(s+1) = A q^s for a C^2 quadratic.
        let n = 5;
        let c = (2.0 * PI / n as f64).cos();
        let (lin, quad) = ([0.3, -0.7], [0.5, 0.2, -0.4]);
        for s in 0..n {
            let q = quadratic_bb(n, s, 1.5, lin, quad);
            let r = quadratic_bb(n, s + 1, 1.5, lin, quad);
            let expect = [
                q[0],
                q[3],
                q[5],
                2.0 * (1.0 - c) * q[0] - q[1] + 2.0 * c * q[3],
                2.0 * (1.0 - c) * q[3] - q[4] + 2.0 * c * q[5],
                4.0 * (1.0 - c).powi(2) * q[0]
                    + 4.0 * (c - 1.0) * q[1]
                    + q[2]
                    + 8.0 * c * (1.0 - c) * q[3]
                    - 4.0 * c * q[4]
                    + 4.0 * c * c * q[5],
            ];
            for k in 0..6 {
                assert!((r[k] - expect[k]).abs() < 1e-12, "s={s} k={k}");
            }
        }
    }
}
