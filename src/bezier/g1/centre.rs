//! The centre conditions of a cap beyond the centre point and the spoke tangents: the
//! quadratic jet shared by all sectors ([`jet_rows`], [`super::Centre::QuadraticJet`]) and the
//! half-plane jet of two sectors ([`half_plane_rows`], a valence-2 vertex), each over a few
//! extra unknowns (the jet's free Hessian vectors) after the patches' coefficients.

use super::hole::Fan;
use super::system::{Row, cidx, piece, spoke_angle, spoke_angle_at, weight};

/// Whether a hole of `n` sectors of kind `fan` is closed by the half-plane cap of two sectors
/// ([`half_plane_rows`]; its centre condition whatever the [`super::Centre`]).
pub(crate) fn is_half_plane(n: usize, fan: Fan) -> bool {
    n == 2 && fan == Fan::Closed
}

/// Extra unknowns of the centre condition: the free Hessian vector `H` of the half-plane jet
/// (1), the three Hessian vectors of the quadratic jet (3), or none.
pub(crate) fn centre_unknowns(n: usize, fan: Fan, jet: bool) -> usize {
    if is_half_plane(n, fan) {
        1
    } else if jet {
        3
    } else {
        0
    }
}

/// The chart scale `k` of the half-plane jet: `phi_0(1, 1) = k T1`, and
/// [`super::ring::chart_tangents`] fits `T1` to the sectors' corners at `k = 1`.
pub(crate) const HALF_PLANE_TWIST: f64 = 1.0;

/// The centre condition of two sectors (a valence-2 vertex, [`is_half_plane`]). The spoke
/// tangents are opposite (`t_1 = -t_0 = -T0`), so each sector's corner at the centre is
/// singular and the spokes alone fix no tangent plane. The rows make every sector
/// `P_s = q o phi_s + O(3)` for the half-plane charts
/// `phi_s(u, v) = u e_s + v e_(s+1) + (w'(0) / 4) (u^2 e_s + v^2 e_(s+1)) + k u v f_s`,
/// `e_0 = -e_1 = T0`, `f_0 = -f_1 = T1`, `k` = [`HALF_PLANE_TWIST`], and a quadratic
/// `q(x, y) = C + x T0 + y T1 + x^2 H / 2` whose vector `H` is the one extra unknown (index
/// `n m^2 (d + 1)^2`): `d_uu P_s(0,0) = (w'(0) / 2) e_s + H`, `d_uv P_s(0,0) = k f_s - H`,
/// `d_vv P_s(0,0) = (w'(0) / 2) e_(s+1) + H` (sector `0` covers the half-plane of `T1`, sector
/// `1` the other). The charts satisfy the spoke relation with `w(0) = -2` and its
/// `u`-derivative at the centre, and `det D phi_s = k (u + v) + O(2) > 0`, so the normal of
/// every sector tends to `T0 x T1` from every direction: G^1 at the centre. Given the relation,
/// these rows are also necessary: it leaves two free vectors at the centre, `d_uu P_0` and
/// `d_uv P_0`, and the normal of sector 0 near the centre is
/// `u T0 x (d_uu + d_uv) + v T0 x (d_uv + d_vv)`, which is normal to the plane for every
/// `(u, v)` only if `d_uv P_0 + d_vv P_0` lies in the plane with a positive `T1` part; a
/// linear condition fixes that part, which leaves `H`. Since `phi_s` is singular at the centre
/// the cap's curvature there is not that of `q` (unbounded in general).
pub(crate) fn half_plane_rows(
    n: usize,
    fan: Fan,
    d: usize,
    m: usize,
    (kappa, w1): (f64, f64),
) -> (Vec<Row>, Vec<Row>) {
    let w = weight(n, fan, kappa, w1);
    // w'(0) of the whole spoke, in the sector's parameter
    let dw0 = 2.0 * (w[1] - w[0]);
    // the centre piece of a split sector sees the sector's second derivatives times 1 / m^2
    let sc = 1.0 / (m * m) as f64;
    let df = d as f64;
    let h = n * m * m * (d + 1) * (d + 1);
    let (mut e, mut f) = (Vec::new(), Vec::new());
    for (s, sign) in [(0, 1.0), (1, -1.0)] {
        let p = piece(m, s, 0, 0);
        let along = |i: usize, j: usize, k: usize, l: usize| -> Row {
            vec![
                (cidx(d, p, i, j), df * (df - 1.0)),
                (cidx(d, p, k, l), -2.0 * df * (df - 1.0)),
                (cidx(d, p, 0, 0), df * (df - 1.0)),
                (h, -sc),
            ]
        };
        // d_uu P_s(0,0) - H = (w'(0) / 2) e_s, e_s = sign T0
        e.push(along(2, 0, 1, 0));
        f.push(vec![(1, sign * sc * dw0 / 2.0)]);
        // d_vv P_s(0,0) - H = (w'(0) / 2) e_(s+1) = -(w'(0) / 2) sign T0
        e.push(along(0, 2, 0, 1));
        f.push(vec![(1, -sign * sc * dw0 / 2.0)]);
        // d_uv P_s(0,0) + H = k f_s, f_s = sign T1
        e.push(vec![
            (cidx(d, p, 1, 1), df * df),
            (cidx(d, p, 1, 0), -df * df),
            (cidx(d, p, 0, 1), -df * df),
            (cidx(d, p, 0, 0), df * df),
            (h, sc),
        ]);
        f.push(vec![(2, sign * sc * HALF_PLANE_TWIST)]);
    }
    (e, f)
}

/// The centre's quadratic jet: every cap patch's second derivatives at the centre are those of
/// one quadratic `q` composed with the planar sector maps `phi_s`, whose 2-jets are
/// `phi_s(u, v) = u e_s + v e_(s+1) + k u v (e_s + e_(s+1))` (spokes straight to second order),
/// `k = w'(0) / (2 (1 + c))`, the symmetric solution of the spoke relation's `u`-derivative at the
/// centre for the planar map. With `H` the Hessian of `q` on the tangent plane, three vectors
/// `H00 = H(T0, T0)`, `H01 = H(T0, T1)`, `H11 = H(T1, T1)` (extra unknowns `n (d + 1)^2 + 0..3`):
/// `d_uu P_s(0,0) = H(t_s, t_s)`, `d_uv P_s(0,0) = k (t_s + t_(s+1)) + H(t_s, t_(s+1))`. These
/// satisfy that derivative of the relation identically (the quadratic part cancels because
/// `t_(s+1) + t_(s-1) = 2 c t_s`), so the cap has one quadratic expansion at the centre:
/// curvature continuous there.
pub(crate) fn jet_rows(
    n: usize,
    fan: Fan,
    d: usize,
    m: usize,
    (kappa, w1): (f64, f64),
) -> (Vec<Row>, Vec<Row>) {
    let c = spoke_angle(n, fan).cos();
    // the centre piece of a split sector sees the sector's second derivatives times 1 / m^2
    let sc = 1.0 / (m * m) as f64;
    // w'(0) = 2 (w1 + kappa / 2) - 4 c
    let k = (-4.0 * c + kappa + 2.0 * w1) / (2.0 * (1.0 + c)) * sc;
    let df = d as f64;
    let h0 = n * m * m * (d + 1) * (d + 1);
    let th = |s: usize| spoke_angle_at(n, fan, s);
    let (mut e, mut f) = (Vec::new(), Vec::new());
    for s0 in 0..n {
        let s = piece(m, s0, 0, 0);
        let (a, b) = (th(s0), th(s0 + 1));
        let (ca, sa, cb, sb) = (a.cos(), a.sin(), b.cos(), b.sin());
        // d(d-1)(b20 - 2 b10 + b00) - H(t_s, t_s) = 0
        e.push(vec![
            (cidx(d, s, 2, 0), df * (df - 1.0)),
            (cidx(d, s, 1, 0), -2.0 * df * (df - 1.0)),
            (cidx(d, s, 0, 0), df * (df - 1.0)),
            (h0, -ca * ca * sc),
            (h0 + 1, -2.0 * ca * sa * sc),
            (h0 + 2, -sa * sa * sc),
        ]);
        f.push(Vec::new());
        // d^2 (b11 - b10 - b01 + b00) - H(t_s, t_(s+1)) = k (t_s + t_(s+1))
        e.push(vec![
            (cidx(d, s, 1, 1), df * df),
            (cidx(d, s, 1, 0), -df * df),
            (cidx(d, s, 0, 1), -df * df),
            (cidx(d, s, 0, 0), df * df),
            (h0, -ca * cb * sc),
            (h0 + 1, -(ca * sb + sa * cb) * sc),
            (h0 + 2, -sa * sb * sc),
        ]);
        f.push(vec![(1, k * (ca + cb)), (2, k * (sa + sb))]);
    }
    (e, f)
}
