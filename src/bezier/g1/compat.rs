//! The ring's data-compatibility conditions: the linear conditions the canonical quad data
//! must meet for a G^1 cap to exist (see [`compatibility`]).

use super::hole::Fan;
use super::system::{INNER_SMOOTHNESS, QuadData, Row, differences, inner_spokes};

/// The ring's compatibility conditions on canonical data, `G q = 0`: the corner block of each
/// sector is defined consistently by both segments, and at each spoke end the two sectors agree
/// on the end point and the spoke tangent, their boundary tangents satisfy the spoke relation
/// at `u = 1` (opposite where `w1 = 0`: the ring's boundary is C^1 there) and, where `w1 = 0`,
/// their cross-derivative twists satisfy the relation's derivative at `u = 1` (see [`super`];
/// where `w1 != 0` that derivative also holds the cap's own `d_uu P_s(1, 0)`, so it is a
/// condition on the cap, not on the data); for split sectors, the pieces of each side join
/// C^[`INNER_SMOOTHNESS`] in boundary and cross derivative. Each row is labelled with the sector
/// or spoke. An open fan ([`Fan::is_open`]) has no conditions at the ends of its boundary
/// spokes `0` and `n` (one sector each), except that a dart's two sides of its sharp spoke end
/// at one point with one derivative along the spoke (the ring is C^0 along the sharp edge).
pub(crate) fn compatibility(
    n: usize,
    fan: Fan,
    d: usize,
    m: usize,
    (kappa, w1): (f64, f64),
) -> Vec<(String, Row)> {
    let qd = QuadData { d, m };
    // -w'(1) of the last part of the spoke, in its own parameter
    let kappa = kappa / m as f64;
    let mut g = Vec::new();
    for s in 0..n {
        let corner = format!("corner of sector {s}");
        g.extend(corner_rows(qd, s).map(|r| (corner.clone(), r)));
        let q = (s + n - 1) % n;
        let end = format!("end of spoke {s} (sectors {q}, {s})");
        if inner_spokes(n, fan).contains(&s) {
            g.extend(
                spoke_end_rows(qd, q, s, (kappa, w1))
                    .into_iter()
                    .map(|r| (end.clone(), r)),
            );
        }
        knot_rows(qd, s, &mut g);
    }
    if fan.is_dart() {
        // the sharp spoke's two sides end at one point with one derivative along it
        let end = format!("end of the dart's sharp spoke (sectors {}, 0)", n - 1);
        g.push((
            end.clone(),
            vec![(qd.a(0, 0, 0), 1.0), (qd.b(n - 1, 0, 0), -1.0)],
        ));
        g.push((end, vec![(qd.ca(0, 0, 0), 1.0), (qd.cb(n - 1, 0, 0), -1.0)]));
    }
    g
}

/// The four rows by which both segments of sector `s` (the last pieces of its sides `a` and
/// `b`) define its corner block alike: the corner point, the two tangents and the twist.
fn corner_rows(qd: QuadData, s: usize) -> [Row; 4] {
    let (d, l) = (qd.d, qd.m - 1);
    let df = d as f64;
    let (a, ca, b, cb) = (
        |j| qd.a(s, l, j),
        |j| qd.ca(s, l, j),
        |j| qd.b(s, l, j),
        |j| qd.cb(s, l, j),
    );
    [
        vec![(a(d), 1.0), (b(d), -1.0)],
        vec![(a(d - 1), 1.0), (b(d), -1.0), (cb(d), -1.0 / df)],
        vec![(a(d), 1.0), (ca(d), 1.0 / df), (b(d - 1), -1.0)],
        vec![
            (a(d - 1), 1.0),
            (ca(d - 1), 1.0 / df),
            (b(d - 1), -1.0),
            (cb(d - 1), -1.0 / df),
        ],
    ]
}

/// The rows at the end of inner spoke `s` between sectors `q = s - 1` and `s`: one end point,
/// one spoke tangent, the spoke relation at `u = 1` and, where `w1 = 0`, its derivative
/// (`kappa` is `-w'(1)` of the spoke's last part).
fn spoke_end_rows(qd: QuadData, q: usize, s: usize, (kappa, w1): (f64, f64)) -> Vec<Row> {
    let df = qd.d as f64;
    let mut rows = vec![
        vec![(qd.a(s, 0, 0), 1.0), (qd.b(q, 0, 0), -1.0)],
        vec![
            (qd.a(s, 0, 0), 1.0),
            (qd.ca(s, 0, 0), 1.0 / df),
            (qd.b(q, 0, 0), -1.0),
            (qd.cb(q, 0, 0), -1.0 / df),
        ],
    ];
    // R(1) / d = (a_1 - a_0) + (b_1 - b_0) + w1 cross_a(0) / d = 0
    let mut r1 = vec![
        (qd.a(s, 0, 1), 1.0),
        (qd.a(s, 0, 0), -1.0),
        (qd.b(q, 0, 1), 1.0),
        (qd.b(q, 0, 0), -1.0),
    ];
    if w1 != 0.0 {
        r1.push((qd.ca(s, 0, 0), w1 / df));
    }
    rows.push(r1);
    if w1 == 0.0 {
        // R'(1) = -d (dcross_a + dcross_b) - kappa cross_a(0) = 0
        rows.push(vec![
            (qd.ca(s, 0, 1), -df),
            (qd.ca(s, 0, 0), df - kappa),
            (qd.cb(q, 0, 1), -df),
            (qd.cb(q, 0, 0), df),
        ]);
    }
    rows
}

/// The rows joining the pieces of each side of a split sector `s` at their knots: boundary and
/// cross derivative C^[`INNER_SMOOTHNESS`], labelled by knot and side.
fn knot_rows(qd: QuadData, s: usize, g: &mut Vec<(String, Row)>) {
    let d = qd.d;
    for k in 0..qd.m.saturating_sub(1) {
        for (side, name) in [(0, "a"), (1, "b")] {
            let label = format!("knot {} of side {name} of sector {s}", k + 1);
            for l in 0..=INNER_SMOOTHNESS {
                let w = differences(l);
                for cross in [false, true] {
                    let at = |k: usize, j: usize| match (side, cross) {
                        (0, false) => qd.a(s, k, j),
                        (0, true) => qd.ca(s, k, j),
                        (_, false) => qd.b(s, k, j),
                        (_, true) => qd.cb(s, k, j),
                    };
                    let mut row = Vec::new();
                    for (t, &wt) in w.iter().enumerate() {
                        row.push((at(k, d - l + t), wt));
                        row.push((at(k + 1, t), -wt));
                    }
                    g.push((label.clone(), row));
                }
            }
        }
    }
}
