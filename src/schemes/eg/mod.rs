//! Evolving Guide (EG) subdivision (Karciauskas and Peters): bi-4 rings that join the bi-3
//! Catmull-Clark surroundings C^2, by five tabulated rules per valence.
//!
//! # Layout (papers README, reconstructed from the text and checked by the published spectra)
//!
//! Sector `s` of a d-net holds 12 nodes `d^s_ij`, `i = 0..3`, `j = 0..2`, at chart points
//! `(u, v) = (3/2 - j/2, 3/2 - i/2)` of the sector's chart, in units of the c-net's spacing; `d_32`
//! at `(1/2, 0)` is next to the (missing) centre. A chart point with `v < 0` belongs to sector
//! `s + 1` at `(-v, u)`, one with `u <= 0` to sector `s - 1` at `(v, -u)`. fairsub's meshes number
//! sectors counter-clockwise with sector `s` between edges `e_s` and `e_(s+1)` of the
//! extraordinary vertex; the EG chart of sector `s` has its `u` axis along `e_(s+1)` and its `v`
//! axis along `e_s` (a mirror of the mesh chart; every patch is transposed on output so that its
//! normal points outward).
//!
//! Internally, chart coordinates are integers in quarters of the current d-net spacing: old
//! nodes sit at even coordinates, the refined nodes `d~_ij` at `(3 - j, 3 - i)`.
//!
//! * **c-net to d-net (R)**: the c-net's bi-3 C^2 spline rewritten as a C^2 bi-4 spline with
//!   every integer knot doubled, nodes at the Greville points: univariately a node at an integer
//!   `k` is `(c_(k-1) + 10 c_k + c_(k+1)) / 12`, at `k + 1/2` it is `(c_k + c_(k+1)) / 2`
//!   (blossoming), tensored. Checked: the paper's d-net limit-point formula (4) applied to `R c`
//!   reproduces the c-net formula (3) exactly (`tests/it/eg.rs`).
//! * **Regular bi-4 refinement (1)**: univariate rules by position (old spacing 1): a new node at
//!   an integer `k` is `(3, 10, 3)/16` of the old nodes at `k - 1/2, k, k + 1/2`; at `k + 1/4`
//!   `(1, 6, 9)/16` of the same; at `k + 1/2` `(1, 6, 1)/8` of `k, k + 1/2, k + 1`; at `k + 3/4`
//!   `(9, 6, 1)/16` of `k + 1/2, k + 1, k + 3/2`; tensored. They give the outer new nodes
//!   (`i = 0` or `j = 0`) and all nodes the ring patches need outside the new d-net.
//! * **Special rules (7)**: `d~^s_hk = a0 c0 + sum_r sum_ij a^(r,hk)_ij d^(s+r)_ij` for the six
//!   inner nodes, the arrays completed by the structural symmetries of Section 5 and
//!   `a0 = 1 - sum of the weights`.
//! * **Ring output (6)**: three bi-4 patches per sector and step, each from the 5 x 5 new nodes of
//!   its cell by B-to-BB conversion (the shared conversion tables of [`crate::bezier::convert`]).

pub mod derive;
pub mod descriptor;
pub mod entry;
pub mod facts;
pub mod local;
pub mod select;
pub mod surface;
pub use descriptor::DESCRIPTOR;

pub mod tables;

use crate::error::{Error, Result};
use crate::stencil::{Stencil, StencilTable};

/// Sources of the EG local vector: `0` is the limit point `c0`, `1 + 12 s + e` is d-net node `e`
/// (paper order, `e = 4 j + i`) of sector `s`.
pub fn dnet_index(s: usize, i: usize, j: usize) -> usize {
    1 + 12 * s + 4 * j + i
}

/// Index of the special nodes `hk` in [`EgRules::weights`].
pub const SPECIAL: [(usize, usize); 6] = [(1, 1), (2, 2), (2, 1), (1, 2), (3, 1), (3, 2)];

/// The complete EG rules of one valence.
#[derive(Debug, Clone)]
pub struct EgRules {
    /// Valence.
    pub n: usize,
    /// `weights[k][r][e]`: weight of `d^(s+r)_e` in special node `SPECIAL[k]` of sector `s`.
    pub weights: [Vec<[f64; 12]>; 6],
    /// `a0` of each special node: the weight of `c0`.
    pub a0: [f64; 6],
}

/// Paper entry index of node `(i, j)`.
fn entry(i: usize, j: usize) -> usize {
    4 * j + i
}

/// Transposes the node indices of a row: entry `(i, j)` takes entry `(j, i)` for `i, j <= 2`; the
/// entries `i = 3` are left for the caller.
fn transposed(row: &[f64; 12]) -> [f64; 12] {
    let mut out = [0.0; 12];
    for i in 0..3 {
        for j in 0..3 {
            out[entry(i, j)] = row[entry(j, i)];
        }
    }
    out
}

/// Expands printed rows (times 10^5) of one array into all `n` rows by the Section 5 symmetries:
/// `kind` 0 for hk in {11, 22} (listed r = 0..N), 1 for 21 (all rows), 2 for 31/32 (r = 0..M).
fn expand(n: usize, printed: &[[f64; 12]], kind: u8) -> Result<Vec<[f64; 12]>> {
    let need = match kind {
        0 => n / 2 + 1,
        1 => n,
        _ => n.div_ceil(2) + 1,
    };
    if printed.len() < need {
        return Err(Error::Unsupported(format!(
            "EG rules for valence {n} are incomplete in the paper's text ({} of {need} rows printed)",
            printed.len()
        )));
    }
    let mut rows = vec![[0.0; 12]; n];
    for r in 0..n {
        if r < printed.len() && r < need {
            rows[r] = printed[r];
            continue;
        }
        let (rt, r3) = match kind {
            // a^r_ij = a^(-r)_ji, a^r_3j = a^(-r-1)_3j.
            0 => ((n - r) % n, (2 * n - r - 1) % n),
            // 31/32: a^r_ij = a^(1-r)_ji, a^r_3j = a^(-r)_3j.
            _ => ((n + 1 - r) % n, (n - r) % n),
        };
        let mut row = transposed(&rows[rt]);
        for j in 0..3 {
            row[entry(3, j)] = rows[r3][entry(3, j)];
        }
        rows[r] = row;
    }
    Ok(rows)
}

impl EgRules {
    /// The complete rules of valence `n`: n = 3 and 5 from the paper (with [`tables::ERRATA`]
    /// applied), n = 4 as plain bi-4 refinement (see [`EgRules::regular`]); other valences are
    /// incomplete in the text and give an error naming the valence.
    pub fn new(n: usize) -> Result<EgRules> {
        Self::from_tables(n, true)
    }

    /// Like [`EgRules::new`], choosing whether the [`tables::ERRATA`] are applied (`false`
    /// reproduces the arrays exactly as printed, to show what the errata change).
    pub fn from_tables(n: usize, apply_errata: bool) -> Result<EgRules> {
        if n == 4 {
            return Ok(Self::regular());
        }
        let Some(printed) = tables::printed(n) else {
            return Err(Error::Unsupported(format!(
                "EG subdivision has no rules for valence {n} (the paper tabulates 3 and 5..10)"
            )));
        };
        if !tables::COMPLETE_VALENCES.contains(&n) {
            return Err(Error::Unsupported(format!(
                "EG rules for valence {n} are incomplete in the paper's text (only the first row of each \
                 array survived); published EG rules exist here for valences 3 and 5"
            )));
        }
        let names = ["11", "22", "21", "31", "32"];
        let to_f = |k: usize| -> Vec<[f64; 12]> {
            printed[k]
                .iter()
                .enumerate()
                .map(|(r, row)| {
                    let mut out = [0.0; 12];
                    for (e, &x) in row.iter().enumerate() {
                        let mut x = x;
                        for er in tables::ERRATA.iter().filter(|_| apply_errata) {
                            if er.n == n && er.array == names[k] && er.row == r && er.entry == e {
                                x = er.corrected;
                            }
                        }
                        out[e] = x as f64 * 1e-5;
                    }
                    out
                })
                .collect()
        };
        let a11 = expand(n, &to_f(0), 0)?;
        let a22 = expand(n, &to_f(1), 0)?;
        let a21 = expand(n, &to_f(2), 1)?;
        let a31 = expand(n, &to_f(3), 2)?;
        let a32 = expand(n, &to_f(4), 2)?;
        // 12 from 21: a^(r,12)_ij = a^(-r,21)_ji, a^(r,12)_3j = a^(-r-1,21)_3j.
        let a12: Vec<[f64; 12]> = (0..n)
            .map(|r| {
                let mut row = transposed(&a21[(n - r) % n]);
                for j in 0..3 {
                    row[entry(3, j)] = a21[(2 * n - r - 1) % n][entry(3, j)];
                }
                row
            })
            .collect();
        let weights = [a11, a22, a21, a12, a31, a32];
        let mut a0 = [0.0; 6];
        for (k, w) in weights.iter().enumerate() {
            a0[k] = 1.0 - w.iter().flat_map(|r| r.iter()).sum::<f64>();
        }
        Ok(EgRules { n, weights, a0 })
    }

    /// Valence 4: the special nodes follow regular bi-4 refinement (weights read off the regular
    /// rules; the omitted centre node enters through `c0`), so EG reduces to uniform C^2 bi-4
    /// refinement.
    pub fn regular() -> EgRules {
        let n = 4;
        let mut weights: [Vec<[f64; 12]>; 6] = Default::default();
        let mut a0 = [0.0; 6];
        for (k, &(h, kk)) in SPECIAL.iter().enumerate() {
            let st = regular_node(n, 0, 3 - kk as i32, 3 - h as i32)
                .expect("regular rule inside the d-net");
            let mut rows = vec![[0.0; 12]; n];
            for &(src, w) in st.entries() {
                match src as usize {
                    0 => a0[k] += w,
                    src => rows[((src - 1) / 12) % n][(src - 1) % 12] += w,
                }
            }
            weights[k] = rows;
        }
        EgRules { n, weights, a0 }
    }
}

/// Normalises a chart point (quarter units) of sector `s` into its owning sector (`u > 0`,
/// `v >= 0`); `None` for the centre.
pub fn normalize(n: usize, mut s: usize, mut u: i32, mut v: i32) -> Option<(usize, i32, i32)> {
    for _ in 0..4 {
        if u > 0 && v >= 0 {
            return Some((s % n, u, v));
        }
        if u == 0 && v == 0 {
            return None;
        }
        if v < 0 {
            (s, u, v) = (s + 1, -v, u);
        } else {
            (s, u, v) = (s + n - 1, v, -u);
        }
    }
    None
}

/// Stencil of the old d-net node at chart point `(u, v)` (quarters, even) of sector `s`. At
/// valence 4 the centre node, which the d-net omits, is expressed by `c0` and its eight
/// neighbours: `c0` is the corner coefficient `(1, 2, 1) x (1, 2, 1) / 16` of the nodes around it
/// (5), so the centre node is `4 c0 - (corners + 2 edge neighbours) / 4`.
fn old_node(n: usize, s: usize, u: i32, v: i32) -> Result<Stencil> {
    let Some((s, u, v)) = normalize(n, s, u, v) else {
        if n != 4 {
            return Err(Error::Unsupported("EG rule reaches the centre".into()));
        }
        let mut st = Stencil::new();
        st.add(0, 4.0);
        for du in [-2, 0, 2] {
            for dv in [-2, 0, 2] {
                if (du, dv) != (0, 0) {
                    let w = if du == 0 || dv == 0 { -0.5 } else { -0.25 };
                    st.add_scaled(&old_node(n, 0, du, dv)?, w);
                }
            }
        }
        return Ok(st.merged());
    };
    if u % 2 != 0 || v % 2 != 0 || !(2..=6).contains(&u) || v > 6 {
        return Err(Error::Unsupported(format!(
            "EG rule reaches chart point ({u}, {v})/4 outside the d-net"
        )));
    }
    Ok(Stencil::point(dnet_index(
        s,
        (3 - v / 2) as usize,
        (3 - u / 2) as usize,
    )))
}

/// Source index of the d-net node at chart point `(u, v)` (quarters of the d-net spacing, even)
/// of sector `s`, resolved to its owning sector; `None` for the centre or points outside the
/// d-net.
pub fn dnet_node(n: usize, s: usize, u: i32, v: i32) -> Option<usize> {
    let (s, u, v) = normalize(n, s, u, v)?;
    if u % 2 != 0 || v % 2 != 0 || !(2..=6).contains(&u) || v > 6 {
        return None;
    }
    Some(dnet_index(s, (3 - v / 2) as usize, (3 - u / 2) as usize))
}

/// Univariate regular bi-4 refinement weights of a new node at `x` (quarters of the old
/// spacing): old positions and weights.
fn univariate(x: i32) -> [(i32, f64); 3] {
    match x.rem_euclid(4) {
        0 => [(x - 2, 3.0 / 16.0), (x, 10.0 / 16.0), (x + 2, 3.0 / 16.0)],
        1 => [
            (x - 3, 1.0 / 16.0),
            (x - 1, 6.0 / 16.0),
            (x + 1, 9.0 / 16.0),
        ],
        2 => [(x - 2, 1.0 / 8.0), (x, 6.0 / 8.0), (x + 2, 1.0 / 8.0)],
        _ => [
            (x - 1, 9.0 / 16.0),
            (x + 1, 6.0 / 16.0),
            (x + 3, 1.0 / 16.0),
        ],
    }
}

/// The regular (knot-insertion) stencil of a new node at chart point `(u, v)` (quarters of the
/// old spacing) of sector `s`, over the EG sources.
pub fn regular_node(n: usize, s: usize, u: i32, v: i32) -> Result<Stencil> {
    let mut st = Stencil::new();
    for (pu, wu) in univariate(u) {
        for (pv, wv) in univariate(v) {
            st.add_scaled(&old_node(n, s, pu, pv)?, wu * wv);
        }
    }
    Ok(st.merged())
}

/// The EG scheme at one valence: rules as stencils over the local vector `(c0, d-net)`.
#[derive(Debug, Clone)]
pub struct Eg {
    rules: EgRules,
}

/// One refinement step of the local vector and the ring it outputs.
#[derive(Debug, Clone)]
pub struct EgStep {
    /// `(12 n + 1)` rows: the refined local vector (row 0 keeps `c0`).
    pub step: StencilTable,
    /// `3 n * 25` rows: the ring's bi-4 Bezier coefficients (patch `3 s + k`, coefficient
    /// `b[a][b]` at `25 (3 s + k) + 5 a + b`, in the EG chart's `(u, v)`), from the old vector.
    pub ring: StencilTable,
}

impl Eg {
    /// The scheme at valence `n` (errors for valences without complete rules).
    pub fn new(n: usize) -> Result<Eg> {
        Ok(Eg {
            rules: EgRules::new(n)?,
        })
    }

    /// The scheme with given rules.
    pub fn with_rules(rules: EgRules) -> Eg {
        Eg { rules }
    }

    /// The rules.
    pub fn rules(&self) -> &EgRules {
        &self.rules
    }

    /// Valence.
    pub fn n(&self) -> usize {
        self.rules.n
    }

    /// Stencil of special node `SPECIAL[k]` of sector `s` by (7).
    pub fn special_node(&self, s: usize, k: usize) -> Stencil {
        let n = self.n();
        let mut st = Stencil::new();
        st.add(0, self.rules.a0[k]);
        for r in 0..n {
            for e in 0..12 {
                let w = self.rules.weights[k][r][e];
                if w != 0.0 {
                    st.add(1 + 12 * ((s + r) % n) + e, w);
                }
            }
        }
        st.merged()
    }

    /// The step and ring tables.
    pub fn step(&self) -> Result<EgStep> {
        build_step(
            self.n(),
            12 * self.n() + 1,
            &|s, k| Ok(self.special_node(s, k)),
            Vec::new(),
        )
    }
}

/// Stencil of the new node at chart point `(u, v)` (quarters of the old spacing) of sector `s`:
/// `special(s', k)` for the six inner nodes (after normalising to the owning sector `s'`),
/// regular refinement otherwise.
pub fn new_node(
    n: usize,
    special: &dyn Fn(usize, usize) -> Result<Stencil>,
    s: usize,
    u: i32,
    v: i32,
) -> Result<Stencil> {
    let (s, u, v) =
        normalize(n, s, u, v).ok_or_else(|| Error::Unsupported("no node at the centre".into()))?;
    if let Some(k) = SPECIAL
        .iter()
        .position(|&(h, kk)| (3 - kk as i32, 3 - h as i32) == (u, v))
    {
        return special(s, k);
    }
    regular_node(n, s, u, v)
}

/// Builds the step and ring tables of a d-net scheme (EG, QAS+) over `m` sources whose first
/// `12 n + 1` are `(c0 or p, d-net)`: row 0 keeps source 0, rows `1..=12 n` are the refined d-net
/// (`special` gives the six inner nodes of a sector, regular bi-4 refinement the rest), then
/// `tail` (further state, e.g. the quadratic expansion of QAS+). The ring has three bi-4 patches
/// per sector from the refined nodes by B-to-BB conversion (6).
pub fn build_step(
    n: usize,
    m: usize,
    special: &dyn Fn(usize, usize) -> Result<Stencil>,
    tail: Vec<Stencil>,
) -> Result<EgStep> {
    let mut step = StencilTable::with_capacity(m, m, 40);
    step.push(Stencil::point(0));
    for s in 0..n {
        for j in 0..3 {
            for i in 0..4 {
                step.push(new_node(n, special, s, 3 - j, 3 - i)?);
            }
        }
    }
    for t in tail {
        step.push(t);
    }
    let mut ring = StencilTable::with_capacity(m, 75 * n, 40);
    let m4 = crate::bezier::convert::quartic_c2_matrix();
    for s in 0..n {
        // Cells of the three patches (lower-left corner in quarters): A, B, C.
        for (cu, cv) in [(2, 0), (2, 2), (0, 2)] {
            let mut net = Vec::with_capacity(25);
            for a in 0..5 {
                for b in 0..5 {
                    net.push(new_node(n, special, s, cu - 1 + a, cv - 1 + b)?);
                }
            }
            for k in 0..5 {
                for l in 0..5 {
                    let mut st = Stencil::new();
                    for a in 0..5 {
                        for b in 0..5 {
                            let w = m4[(k, a)] * m4[(l, b)];
                            if w != 0.0 {
                                st.add_scaled(&net[5 * a + b], w);
                            }
                        }
                    }
                    ring.push(st);
                }
            }
        }
    }
    Ok(EgStep { step, ring })
}

/// Stencils of the EG local vector `(c0, d-net)` from the c-net of valence `n` in fairsub's
/// layout ([`crate::mesh::PolyMesh::cnet_indices`] with 2 rings: centre, then per sector the
/// chart points `(i, j)`, `i = 1, 2`, `j = 0..2`): row 0 is `c0` by (3), rows `1 + 12 s + e` the
/// degree-raised d-net `R c`.
pub fn from_cnet(n: usize) -> Result<StencilTable> {
    if n < 3 {
        return Err(Error::InvalidArgument(format!("valence {n}")));
    }
    let m = 6 * n + 1;
    // c-net point at EG chart (a, b) (integers) of sector s.
    let cnet = |s: usize, a: i32, b: i32| -> Result<usize> {
        let (s, a, b) = match normalize(n, s, 4 * a, 4 * b) {
            Some((s, a, b)) => (s, a / 4, b / 4),
            None => return Ok(0),
        };
        if !(1..=2).contains(&a) || !(0..=2).contains(&b) {
            return Err(Error::Unsupported(format!(
                "c-net point ({a}, {b}) outside the 2-ring"
            )));
        }
        // EG (a, b) is the mesh chart (u, v) = (b, a); u = 0 lies in the next mesh sector.
        Ok(if b == 0 {
            1 + ((s + 1) % n) * 6 + (a as usize - 1) * 3
        } else {
            1 + s * 6 + (b as usize - 1) * 3 + a as usize
        })
    };
    // Univariate degree raising at a node x (halves): integer -> (1,10,1)/12, half -> (1,1)/2.
    let raise = |x: i32| -> Vec<(i32, f64)> {
        if x % 2 == 0 {
            vec![
                (x / 2 - 1, 1.0 / 12.0),
                (x / 2, 10.0 / 12.0),
                (x / 2 + 1, 1.0 / 12.0),
            ]
        } else {
            vec![((x - 1) / 2, 0.5), ((x + 1) / 2, 0.5)]
        }
    };
    let mut t = StencilTable::with_capacity(m, 12 * n + 1, 9);
    t.push(c0_from_cnet(n));
    for s in 0..n {
        for j in 0..3 {
            for i in 0..4 {
                // Node at (u, v) = (3/2 - j/2, 3/2 - i/2): in halves (3 - j, 3 - i).
                let (hu, hv) = (3 - j, 3 - i);
                let mut st = Stencil::new();
                for (a, wa) in raise(hu) {
                    for (b, wb) in raise(hv) {
                        st.add(cnet(s, a, b)?, wa * wb);
                    }
                }
                t.push(st);
            }
        }
    }
    Ok(t)
}

/// The limit point `c0` from a c-net (3): Catmull-Clark's limit for `n > 4`, the corrected
/// weights `11/32, 1/6, 5/96` for `n = 3` (over the c-net layout of [`from_cnet`]).
pub fn c0_from_cnet(n: usize) -> Stencil {
    if n == 3 {
        let mut st = Stencil::new();
        st.add(0, 11.0 / 32.0);
        for s in 0..n {
            st.add(1 + 6 * s, 1.0 / 6.0); // edge neighbour (1, 0)
            st.add(1 + 6 * s + 1, 5.0 / 96.0); // face neighbour (1, 1)
        }
        return st.merged();
    }
    // Catmull-Clark's own limit rule on the canonical c-net, whose numbering is [`from_cnet`]'s.
    let net = crate::mesh::nets::cnet(n, crate::mesh::nets::CnetShape::Convex, 2);
    crate::schemes::CatmullClark::limit_stencil(&net, 0)
}

/// The limit point `c0` from a bare d-net (4), as weights of the d-net sources (index 0 unused).
pub fn c0_from_dnet(n: usize) -> Stencil {
    let nf = n as f64;
    let mut e = [[0.0f64; 3]; 4]; // e[i][j]
    let gamma;
    if n == 3 {
        gamma = 93120.0;
        e[0][0] = 11.0;
        e[2][0] = -73.0;
        e[1][1] = 396.0;
        e[2][2] = 10643.0;
        e[3][2] = 19062.0;
        e[1][0] = -6.0 * e[0][0];
        e[3][0] = e[1][0];
        e[3][1] = e[1][1];
    } else {
        gamma = 178480.0 * nf * (nf + 5.0);
        // Printed: e_32 := (gamma_n / delta_n)(8483 n - 5008) with delta_n := 11185 n (n + 5).
        // That ratio (15.957...) breaks the partition of unity; it must be 48, see C0_DNET_ERRATUM.
        let delta = gamma / 48.0;
        e[2][0] = 19339.0 * nf - 53929.0;
        e[3][0] = 336.0 * (153.0 * nf - 448.0);
        e[2][2] = 157051.0 * nf + 50279.0;
        e[3][2] = gamma / delta * (8483.0 * nf - 5008.0);
        e[0][0] = 2587.0 * nf - 8377.0;
        e[1][1] = 36.0 * e[0][0];
        e[3][1] = -6.0 * e[3][0];
        e[1][0] = -6.0 * e[0][0];
    }
    e[0][1] = e[1][0];
    e[0][2] = e[2][0];
    e[2][1] = -6.0 * e[2][0];
    e[1][2] = e[2][1];
    let mut st = Stencil::new();
    for s in 0..n {
        for (i, row) in e.iter().enumerate() {
            for (j, &w) in row.iter().enumerate() {
                st.add(dnet_index(s, i, j), w / gamma);
            }
        }
    }
    st.merged()
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    #[crate::unit::test]
    fn rows_and_partition_of_unity() {
        for n in [3, 4, 5] {
            let r = EgRules::new(n).unwrap();
            for k in 0..6 {
                let total: f64 = r.weights[k].iter().flat_map(|x| x.iter()).sum::<f64>() + r.a0[k];
                assert!((total - 1.0).abs() < 1e-12);
            }
        }
        assert!(EgRules::new(6).is_err());
        assert!(EgRules::new(11).is_err());
    }

    #[crate::unit::test]
    fn step_rows_are_affine() {
        for n in [3, 4, 5] {
            let st = Eg::new(n).unwrap().step().unwrap();
            assert!(st.step.max_affine_defect() < 1e-12, "n={n}");
            assert!(st.ring.max_affine_defect() < 1e-12, "n={n}");
        }
        assert!(from_cnet(5).unwrap().max_affine_defect() < 1e-12);
    }
}
