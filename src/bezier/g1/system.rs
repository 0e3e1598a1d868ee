//! The linear system of the cap: its unknowns (all Bezier coefficients of the `n` bi-`d` cap
//! patches, one coordinate at a time), its conditions (fixed coefficients from the data, C^0 and
//! the G^1 relation along every spoke) and the fairness energy (the ring's data-compatibility
//! conditions are in `compat`). All rows are scalar and the same for x, y, z.

use super::centre::{half_plane_rows, is_half_plane, jet_rows};
use super::hole::{CornerAngle, Fan};
use nalgebra::DMatrix;

/// Index of coefficient `(i, j)` of cap patch `p` among the unknowns (`p` the sector in the
/// one-patch layouts, [`piece`] of a split sector).
#[inline]
pub(crate) fn cidx(d: usize, p: usize, i: usize, j: usize) -> usize {
    p * (d + 1) * (d + 1) + i * (d + 1) + j
}

/// The cap patch index of piece `(a, b)` (`a` along `u`) of sector `s` split `m x m`.
#[inline]
pub(crate) fn piece(m: usize, s: usize, a: usize, b: usize) -> usize {
    (s * m + a) * m + b
}

/// Offsets in the canonical quad data vector (centre, T0, T1, then per sector the `m` pieces
/// of `a` (boundary, cross) and the `m` pieces of `b`, of `d + 1` coefficients each).
#[derive(Debug, Clone, Copy)]
pub(crate) struct QuadData {
    pub d: usize,
    /// Pieces per sector side.
    pub m: usize,
}

impl QuadData {
    pub fn len(&self, n: usize) -> usize {
        3 + n * 4 * self.m * (self.d + 1)
    }
    fn base(&self, s: usize) -> usize {
        3 + s * 4 * self.m * (self.d + 1)
    }
    /// Boundary coefficient `j` of piece `k` of segment `a` of sector `s`.
    pub fn a(&self, s: usize, k: usize, j: usize) -> usize {
        self.base(s) + 2 * k * (self.d + 1) + j
    }
    pub fn ca(&self, s: usize, k: usize, j: usize) -> usize {
        self.base(s) + (2 * k + 1) * (self.d + 1) + j
    }
    pub fn b(&self, s: usize, k: usize, i: usize) -> usize {
        self.base(s) + (2 * self.m + 2 * k) * (self.d + 1) + i
    }
    pub fn cb(&self, s: usize, k: usize, i: usize) -> usize {
        self.base(s) + (2 * self.m + 2 * k + 1) * (self.d + 1) + i
    }
}

/// A sparse row.
pub(crate) type Row = Vec<(usize, f64)>;

/// The conditions `E x = F q` on the unknowns `x` for canonical data `q`.
pub(crate) struct Conditions {
    /// Rows of `E` (over the unknowns).
    pub e: Vec<Row>,
    /// Rows of `F` (over the canonical data), one per row of `e`.
    pub f: Vec<Row>,
}

/// The angle between neighbouring spokes at the centre: `2 pi / n` around a closed hole or a
/// dart's fan of `n` sectors, `pi / n` across an open fan of `n` sectors at a boundary vertex
/// or beside a crease (its `n + 1` spokes span a half-turn, spokes `0` and `n` along the
/// boundary).
pub(crate) fn spoke_angle(n: usize, fan: Fan) -> f64 {
    turn(n, fan) / n as f64
}

/// The angle the spokes of a hole of `n` sectors span: a full turn around a closed hole or a
/// dart, `2 pi n / m` across a wedge of `n` of `m` sectors, a quarter-turn (three quarters when
/// reflex) across a corner's sector between two sharp edges, a half-turn across an open fan, a quarter-turn across an open fan of one sector (a
/// corner: its two spokes are the two boundary curves' tangents, `T0` and `T1` themselves).
pub(crate) fn turn(n: usize, fan: Fan) -> f64 {
    match (fan, n) {
        (Fan::Closed | Fan::Dart, _) => 2.0 * std::f64::consts::PI,
        (Fan::Wedge(m), _) => 2.0 * std::f64::consts::PI * n as f64 / m.max(1) as f64,
        (Fan::Corner(CornerAngle::Convex), _) => std::f64::consts::FRAC_PI_2,
        (Fan::Corner(CornerAngle::Reflex), _) => 3.0 * std::f64::consts::FRAC_PI_2,
        // a cone's chart: a half-turn (the cap's sectors near the apex are `z^2` of it)
        (Fan::Cone | Fan::DartCone, _) => std::f64::consts::PI,
        (_, 1) => std::f64::consts::FRAC_PI_2,
        _ => std::f64::consts::PI,
    }
}

/// The angle of spoke `k` from spoke 0: `k` times [`spoke_angle`] (computed as `turn k / n`;
/// spoke `n` of a dart's fan is its spoke `0`, angle 0 exactly).
pub(crate) fn spoke_angle_at(n: usize, fan: Fan, k: usize) -> f64 {
    let k = if fan.is_dart() { k % n } else { k };
    turn(n, fan) * k as f64 / n as f64
}

/// The spokes that join two sectors (where C^0 and the G^1 relation are imposed): spoke `s`
/// between sectors `s - 1` and `s`, all `n` of a closed hole, the `n - 1` inner ones of an open
/// fan (its spokes `0` and `n` are boundary curves of the surface, or a dart's sharp edge).
pub(crate) fn inner_spokes(n: usize, fan: Fan) -> std::ops::Range<usize> {
    if fan.is_open() { 1..n } else { 0..n }
}

/// `w(u) = 2 c (1 - u)^2 + (2 w1 + kappa) u (1 - u) + w1 u^2`, `c = cos(`[`spoke_angle`]`)`,
/// in Bernstein form of degree 2: `w(0) = 2 c`, `w(1) = w1`, `w'(1) = -kappa`.
pub(crate) fn weight(n: usize, fan: Fan, kappa: f64, w1: f64) -> [f64; 3] {
    let c = spoke_angle(n, fan).cos();
    [2.0 * c, w1 + kappa / 2.0, w1]
}

/// Binomial coefficient as f64.
pub(crate) fn binom(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
}

/// `w` of [`weight`] restricted to the `k`-th of `m` equal parts of the spoke, as a quadratic
/// in the part's own parameter (Bernstein form, by the blossom); `m = 1` is [`weight`] itself.
pub(crate) fn weight_part(
    n: usize,
    fan: Fan,
    (kappa, w1): (f64, f64),
    m: usize,
    k: usize,
) -> [f64; 3] {
    let w = weight(n, fan, kappa, w1);
    if m == 1 {
        return w;
    }
    let blossom = |x: f64, y: f64| {
        w[0] * (1.0 - x) * (1.0 - y) + w[1] * ((1.0 - x) * y + x * (1.0 - y)) + w[2] * x * y
    };
    let (t0, t1) = (k as f64 / m as f64, (k + 1) as f64 / m as f64);
    [blossom(t0, t0), blossom(t0, t1), blossom(t1, t1)]
}

/// The degree-`d + 1` Bernstein coefficients of the spoke relation between patch `ps` (its
/// side `v = 0`) and patch `pq` (its side `u = 0`) with the quadratic weight `w`:
/// `R(u) = d/dv P_ps(u, 0) + d/du P_pq(0, u) - w(u) d/du P_ps(u, 0)`, as rows over the
/// unknowns. For the one-patch layouts `ps = s`, `pq = s - 1`, `w` = [`weight`].
pub(crate) fn spoke_rows(d: usize, w: [f64; 3], ps: usize, pq: usize) -> Vec<Row> {
    let (s, q) = (ps, pq);
    let df = d as f64;
    let mut rows = vec![Vec::new(); d + 2];
    // Degree raising d -> d + 1 of a coefficient at index i: to k = i (weight 1 - i/(d+1)) and
    // k = i + 1 (weight (i+1)/(d+1)).
    let raise = |i: usize| {
        [
            (i, 1.0 - i as f64 / (df + 1.0)),
            (i + 1, (i as f64 + 1.0) / (df + 1.0)),
        ]
    };
    for i in 0..=d {
        for (k, r) in raise(i) {
            // d/dv P_s(u, 0): coefficient i is d (b_i1 - b_i0).
            rows[k].push((cidx(d, s, i, 1), df * r));
            rows[k].push((cidx(d, s, i, 0), -df * r));
            // d/du P_q(0, u): coefficient i is d (b_1i - b_0i).
            rows[k].push((cidx(d, q, 1, i), df * r));
            rows[k].push((cidx(d, q, 0, i), -df * r));
        }
    }
    // w(u) d/du P_s(u, 0): B_i^(d-1) B_l^2 = C(d-1,i) C(2,l) / C(d+1,i+l) B_(i+l)^(d+1).
    for i in 0..d {
        for (l, &wl) in w.iter().enumerate() {
            if wl == 0.0 {
                continue;
            }
            let k = i + l;
            let f = wl * binom(d - 1, i) * binom(2, l) / binom(d + 1, k) * df;
            rows[k].push((cidx(d, s, i + 1, 0), -f));
            rows[k].push((cidx(d, s, i, 0), f));
        }
    }
    rows
}

/// The conditions of the cap of valence `n` (`fan`: closed, an open fan of `n` sectors, or
/// with its boundary spokes the cubic Hermite interpolants of their end data, [`crease_rows`]),
/// degree `d`, `m x m` pieces per sector, spoke-end twist `kappa` and value `w1`
/// ([`weight`]); with `jet` also the quadratic-jet
/// conditions at the centre over three extra unknowns ([`jet_rows`]). Split sectors (`m > 1`)
/// add C^`r` joins between their pieces ([`inner_rows`], `r` = [`INNER_SMOOTHNESS`]); `m = 1`
/// gives the one-patch rows unchanged.
pub(crate) fn conditions(
    (n, fan): (usize, Fan),
    d: usize,
    m: usize,
    (kappa, w1): (f64, f64),
    jet: bool,
) -> Conditions {
    let qd = QuadData { d, m };
    let df = d as f64;
    let mf = m as f64;
    let mut e: Vec<Row> = Vec::new();
    let mut f: Vec<Row> = Vec::new();
    let mut fix = |e: &mut Vec<Row>, x: usize, row: Row| {
        e.push(vec![(x, 1.0)]);
        f.push(row);
    };
    for s in 0..n {
        for k in 0..m {
            // piece (m - 1, k) along side a, piece (k, m - 1) along side b
            let (pa, pb) = (piece(m, s, m - 1, k), piece(m, s, k, m - 1));
            for j in 0..=d {
                // side u = 1: b_dj = a_j, b_(d-1)j = a_j + cross_a_j / d
                fix(&mut e, cidx(d, pa, d, j), vec![(qd.a(s, k, j), 1.0)]);
                fix(
                    &mut e,
                    cidx(d, pa, d - 1, j),
                    vec![(qd.a(s, k, j), 1.0), (qd.ca(s, k, j), 1.0 / df)],
                );
                // side v = 1: b_id = b_i, b_i(d-1) = b_i + cross_b_i / d
                fix(&mut e, cidx(d, pb, j, d), vec![(qd.b(s, k, j), 1.0)]);
                fix(
                    &mut e,
                    cidx(d, pb, j, d - 1),
                    vec![(qd.b(s, k, j), 1.0), (qd.cb(s, k, j), 1.0 / df)],
                );
            }
        }
        // the centre and the spoke tangents (per unit of the centre piece's parameter)
        let th = |k: usize| spoke_angle_at(n, fan, k);
        let p0 = piece(m, s, 0, 0);
        let dm = df * mf;
        fix(&mut e, cidx(d, p0, 0, 0), vec![(0, 1.0)]);
        let (a0, a1) = (th(s), th(s + 1));
        fix(&mut e, cidx(d, p0, 1, 0), tangent_row(fan, a0, dm));
        fix(&mut e, cidx(d, p0, 0, 1), tangent_row(fan, a1, dm));
    }
    if fan.hermite_ends() && m == 1 {
        for (x, row) in crease_rows(n, d, fan) {
            fix(&mut e, x, row);
        }
    }
    if fan == Fan::DartCone && m == 1 {
        for (x, row) in cone_spoke_rows(n, d) {
            fix(&mut e, x, row);
        }
    }
    for s in inner_spokes(n, fan) {
        let q = (s + n - 1) % n;
        for k in 0..m {
            let (ps, pq) = (piece(m, s, k, 0), piece(m, q, 0, k));
            for i in 0..=d {
                e.push(vec![(cidx(d, ps, i, 0), 1.0), (cidx(d, pq, 0, i), -1.0)]);
                f.push(Vec::new());
            }
            for r in spoke_rows(d, weight_part(n, fan, (kappa, w1), m, k), ps, pq) {
                e.push(r);
                f.push(Vec::new());
            }
        }
    }
    if m > 1 {
        for r in inner_rows(n, d, m, INNER_SMOOTHNESS) {
            e.push(r);
            f.push(Vec::new());
        }
    }
    if is_half_plane(n, fan) {
        let (je, jf) = half_plane_rows(n, fan, d, m, (kappa, w1));
        e.extend(je);
        f.extend(jf);
    } else if jet {
        let (je, jf) = jet_rows(n, fan, d, m, (kappa, w1));
        e.extend(je);
        f.extend(jf);
    }
    Conditions { e, f }
}

/// The row over the canonical data of the spoke's first coefficient after the centre:
/// `C + (cos a T0 + sin a T1) / scale` for the spoke at angle `a`; `C` itself around a cone
/// ([`Fan::is_cone`]: every spoke tangent zero, whatever `T0, T1` the data hold).
fn tangent_row(fan: Fan, a: f64, scale: f64) -> Row {
    if fan.is_cone() {
        vec![(0, 1.0)]
    } else {
        vec![(0, 1.0), (1, a.cos() / scale), (2, a.sin() / scale)]
    }
}

/// The boundary spokes of an open fan of `n` one-patch sectors at degree `d` as the cubic
/// Hermite interpolants of their end data, raised to degree `d`: the rows fixing coefficients
/// `2 ..= d - 2` of spoke `0` (`b_i0` of sector `0`) and of spoke `n` (`b_0i` of sector
/// `n - 1`) over the canonical data. The cubic's control points are `C`, `C + t / 3` (`t` the
/// spoke's tangent at the centre), `E + X / 3` and `E` (`E` the spoke end, `X` the ring's
/// derivative there into the hole, `-d/du` along the spoke). Those coefficients enter no
/// other condition (the relation of the inner spoke next to a boundary spoke reads only the
/// two layers along that inner spoke), so the rows fix free parameters and the certificate is
/// that of the plain open fan. Where the ring's boundary curve is a cubic B-spline (a crease
/// or boundary under OpenSubdiv's rules, whose end data are its own), the spoke is that curve
/// exactly. A dart's fan ([`Fan::Dart`]) gives spoke `n` spoke `0`'s end data (the same
/// point and derivative of a ring that is C^0 along the sharp edge), so both are one curve.
pub(crate) fn crease_rows(n: usize, d: usize, fan: Fan) -> Vec<(usize, Row)> {
    let qd = QuadData { d, m: 1 };
    let mut out = Vec::new();
    for last in [false, true] {
        let (p, k) = if last { (n - 1, n) } else { (0, 0) };
        let th = spoke_angle_at(n, fan, k);
        let (e, x) = if last && !fan.is_dart() {
            (qd.b(p, 0, 0), qd.cb(p, 0, 0))
        } else {
            // spoke 0's end (a dart's spoke n too)
            (qd.a(0, 0, 0), qd.ca(0, 0, 0))
        };
        let h: [Row; 4] = [
            vec![(0, 1.0)],
            tangent_row(fan, th, 3.0),
            vec![(e, 1.0), (x, 1.0 / 3.0)],
            vec![(e, 1.0)],
        ];
        for i in 2..=d.saturating_sub(2) {
            let mut row = Row::new();
            for (j, hj) in h.iter().enumerate() {
                if j <= i && i - j <= d - 3 {
                    let w = binom(3, j) * binom(d - 3, i - j) / binom(d, i);
                    row.extend(hj.iter().map(|&(c, v)| (c, w * v)));
                }
            }
            let unknown = if last {
                cidx(d, p, 0, i)
            } else {
                cidx(d, p, i, 0)
            };
            out.push((unknown, row));
        }
    }
    out
}

/// The inner spokes of a dart's fan around a cone point ([`Fan::DartCone`]) at degree `d`:
/// the rows fixing each one's coefficient `2` (its second-order term at the apex, the first
/// free one: the tangent is zero) to that of the cubic `C, C, E + X / 3, E` of its end data
/// raised to degree `d`, as its sharp spoke is whole ([`crease_rows`]), so every spoke leaves
/// the apex towards its own end. Left to the fairness functional, which barely sees the apex,
/// the inner spokes of Loop's flat valence-3 cone with one sharp edge left it bent 60 degrees
/// towards the sharp one and the middle sector folded over at 1 ring; pinned, the cap folds
/// only where the scheme's own mesh does (`tests/it/cone_caps.rs`). Not for the closed cone: at
/// even `n` the relation at the apex, `b_(s-1) + b_s = 2 w(0) a_s` around the cycle, then asks
/// the data for `sum (-1)^s a_s = 0`, and no cap is certified.
pub(crate) fn cone_spoke_rows(n: usize, d: usize) -> Vec<(usize, Row)> {
    let qd = QuadData { d, m: 1 };
    let k = 3.0 / binom(d, 2);
    (1..n)
        .map(|s| {
            let (end, x) = (qd.a(s, 0, 0), qd.ca(s, 0, 0));
            (cidx(d, s, 2, 0), vec![(0, 1.0 - k), (end, k), (x, k / 3.0)])
        })
        .collect()
}

/// Smoothness of the joins between the pieces of a split sector: C^2, like the macro-patch
/// rings the split caps join (QAS+^3's and guided-bi3-macro's pieces are C^2,
/// guided-bi4-macro's C^3), so a sector is one C^2 spline on its `m x m` grid.
pub(crate) const INNER_SMOOTHNESS: usize = 2;

/// `l`-th difference weights `(-1)^(l - t) C(l, t)`, `t = 0..=l`.
pub(crate) fn differences(l: usize) -> Vec<f64> {
    (0..=l)
        .map(|t| {
            if (l - t).is_multiple_of(2) {
                binom(l, t)
            } else {
                -binom(l, t)
            }
        })
        .collect()
}

/// C^`r` across the inner grid lines of every split sector: for pieces `(a, b)`, `(a + 1, b)`
/// (and `(a, b)`, `(a, b + 1)`) the derivatives of order `0..=r` across the common side agree
/// (equal piece sizes: the `l`-th differences of the coefficients at the two sides agree).
pub(crate) fn inner_rows(n: usize, d: usize, m: usize, r: usize) -> Vec<Row> {
    let mut rows = Vec::new();
    for s in 0..n {
        for a in 0..m {
            for b in 0..m {
                let p = piece(m, s, a, b);
                for (next, along_u) in [(a + 1 < m, true), (b + 1 < m, false)] {
                    if !next {
                        continue;
                    }
                    let p2 = if along_u {
                        piece(m, s, a + 1, b)
                    } else {
                        piece(m, s, a, b + 1)
                    };
                    for l in 0..=r {
                        let w = differences(l);
                        for j in 0..=d {
                            let mut row = Vec::with_capacity(2 * l + 2);
                            for (t, &wt) in w.iter().enumerate() {
                                let (i1, i2) = (d - l + t, t);
                                let (x1, x2) = if along_u {
                                    (cidx(d, p, i1, j), cidx(d, p2, i2, j))
                                } else {
                                    (cidx(d, p, j, i1), cidx(d, p2, j, i2))
                                };
                                row.push((x1, wt));
                                row.push((x2, -wt));
                            }
                            rows.push(row);
                        }
                    }
                }
            }
        }
    }
    rows
}

/// Gram matrix `int_0^1 B_i^p B_j^p`.
fn gram(p: usize) -> DMatrix<f64> {
    DMatrix::from_fn(p + 1, p + 1, |i, j| {
        binom(p, i) * binom(p, j) / ((2 * p + 1) as f64 * binom(2 * p, i + j))
    })
}

/// `k`-th derivative matrix: degree-`d` coefficients to degree-`d - k` coefficients.
fn deriv(d: usize, k: usize) -> DMatrix<f64> {
    let mut m = DMatrix::identity(d + 1, d + 1);
    for l in 0..k {
        let p = d - l;
        let step = DMatrix::from_fn(p, p + 1, |i, j| {
            if j == i + 1 {
                p as f64
            } else if j == i {
                -(p as f64)
            } else {
                0.0
            }
        });
        m = step * m;
    }
    m
}

/// The energy `F_k(P) = int sum_(a+b=k) C(k,a) |d_u^a d_v^b P|^2` of one bi-`d` patch as a
/// quadratic form on its `(d + 1)^2` coefficients (row-major, `i` along `u`).
pub(crate) fn patch_energy(d: usize, k: usize) -> DMatrix<f64> {
    let m = (d + 1) * (d + 1);
    let mut h = DMatrix::zeros(m, m);
    for a in 0..=k.min(d) {
        let b = k - a;
        if b > d {
            continue;
        }
        let (du, dv) = (deriv(d, a), deriv(d, b));
        let gu = du.transpose() * gram(d - a) * &du;
        let gv = dv.transpose() * gram(d - b) * &dv;
        h += gu.kronecker(&gv) * binom(k, a);
    }
    h
}

/// Dense matrix of sparse rows over `cols` columns.
pub(crate) fn dense(rows: &[Row], cols: usize) -> DMatrix<f64> {
    let mut m = DMatrix::zeros(rows.len(), cols);
    for (r, row) in rows.iter().enumerate() {
        for &(c, w) in row {
            m[(r, c)] += w;
        }
    }
    m
}
