//! Reading a hole ([`Hole`]) off the `--no-fill` complex of today's schemes: the open sides of
//! the last ring around input vertex 0, chained counterclockwise, split into sectors, with the
//! ring's cross-boundary derivatives.

use fairsub::bezier::g1::{Hole, Segment};
use fairsub::bezier::{BezierPatch, Side};
use fairsub::geom::{self, Point, add, cross, dot, norm, normalize, scale, sub};
use fairsub::surface::adjacency::{default_tolerance, shared_boundaries};
use fairsub::surface::{Element, PatchComplex, Provenance};

/// One open side of a last-ring patch: its curve in loop order and the cross derivative
/// (Bezier coefficients) pointing out of the ring patch, into the hole.
#[derive(Clone)]
pub struct Open {
    pub curve: Vec<Point>,
    pub cross: Vec<Point>,
    pub normal: Point,
}

pub fn reversed(mut v: Vec<Point>) -> Vec<Point> {
    v.reverse();
    v
}

/// Coefficients of the degree-`d` polynomial with values `f(t_k)` at `t_k = (k + 1/2)/(d + 1)`.
pub fn interpolate(d: usize, f: impl Fn(f64) -> Point) -> Vec<Point> {
    let m = nalgebra::DMatrix::from_fn(d + 1, d + 1, |k, i| {
        let mut b = vec![0.0; d + 1];
        fairsub::bezier::curve::bernstein(d, (k as f64 + 0.5) / (d as f64 + 1.0), &mut b);
        b[i]
    });
    let inv = m.try_inverse().unwrap();
    let vals: Vec<Point> = (0..=d)
        .map(|k| f((k as f64 + 0.5) / (d as f64 + 1.0)))
        .collect();
    (0..=d)
        .map(|i| (0..=d).fold([0.0; 3], |a, k| geom::axpy(a, inv[(i, k)], vals[k])))
        .collect()
}

/// The open side `side` of tensor ring patch `p` (quad rings): the side's curve and the
/// derivative off it, as Bezier curves in the side's parameter.
pub fn quad_open(p: &BezierPatch, side: Side) -> Open {
    let curve = p.boundary(side);
    let d = curve.len() - 1;
    let cross = interpolate(d, |t| {
        let [u, v] = side.domain_point(t);
        let dd = p.derivatives(u, v);
        match side {
            Side::U0 => scale(dd.du, -1.0),
            Side::U1 => dd.du,
            Side::V0 => scale(dd.dv, -1.0),
            Side::V1 => dd.dv,
        }
    });
    let [u, v] = side.domain_point(0.5);
    Open {
        curve,
        cross,
        normal: p.normal(u, v),
    }
}

/// The open side of a Loop ring triangle stored as `X(u, v) = T(u (1 - v), v)`: the side's curve
/// and the derivative of `T` in the direction from the opposite corner to the side's midpoint.
pub fn triangle_open(p: &BezierPatch, side: Side) -> Open {
    let curve = p.boundary(side);
    let dir: [f64; 2] = match side {
        Side::V0 => [0.5, -1.0],
        Side::U0 => [-1.0, 0.5],
        Side::U1 => [0.5, 0.5],
        Side::V1 => panic!("collapsed side"),
    };
    let dc = curve.len() - 2;
    let cross = interpolate(dc, |t| {
        let [u, v] = side.domain_point(t);
        let dd = p.derivatives(u, v);
        let ts = scale(dd.du, 1.0 / (1.0 - v));
        let tt = add(dd.dv, scale(ts, u));
        add(scale(ts, dir[0]), scale(tt, dir[1]))
    });
    let [u, v] = side.domain_point(0.5);
    Open {
        curve,
        cross,
        normal: p.normal(u, v),
    }
}

/// The extraordinary element whose hole is capped: input vertex 0.
pub const EV: Element = Element::Vertex(0);

pub fn last_ring(c: &PatchComplex) -> u32 {
    c.provenance
        .iter()
        .filter_map(|p| match p {
            Provenance::Ring { ring, element, .. } if *element == EV => Some(*ring),
            _ => None,
        })
        .max()
        .expect("rings")
}

/// The open sides of the last ring, chained into a loop counterclockwise about the ring's
/// normal.
pub fn hole_loop(c: &PatchComplex, triangles: bool) -> Vec<Open> {
    let k = last_ring(c);
    let tol = default_tolerance(c);
    let shared = shared_boundaries(c, tol);
    let mut covered = vec![[0.0f64; 4]; c.len()];
    for sb in &shared {
        covered[sb.a][sb.side_a.index()] += sb.t[1] - sb.t[0];
        covered[sb.b][sb.side_b.index()] += 1.0;
    }
    let mut open = Vec::new();
    for (i, p) in c.patches.iter().enumerate() {
        if !matches!(c.provenance[i], Provenance::Ring { ring, element, .. } if ring == k && element == EV)
        {
            continue;
        }
        for side in Side::ALL {
            if !p.is_collapsed(side, tol) && covered[i][side.index()] < 1.0 - 1e-9 {
                open.push(if triangles {
                    triangle_open(p, side)
                } else {
                    quad_open(p, side)
                });
            }
        }
    }
    // chain
    let mut chain = vec![open.swap_remove(0)];
    while !open.is_empty() {
        let end = *chain.last().unwrap().curve.last().unwrap();
        let (i, rev) = open
            .iter()
            .enumerate()
            .find_map(|(i, o)| {
                if geom::dist(o.curve[0], end) < tol {
                    Some((i, false))
                } else if geom::dist(*o.curve.last().unwrap(), end) < tol {
                    Some((i, true))
                } else {
                    None
                }
            })
            .expect("the hole boundary is one closed loop");
        let mut o = open.swap_remove(i);
        if rev {
            o.curve = reversed(o.curve);
            o.cross = reversed(o.cross);
        }
        chain.push(o);
    }
    // orientation: counterclockwise about the ring normal means normal x tangent points inward
    let centroid = scale(
        chain.iter().fold([0.0; 3], |a, o| add(a, o.curve[0])),
        1.0 / chain.len() as f64,
    );
    let o = &chain[0];
    let tangent = sub(o.curve[1], o.curve[0]);
    if dot(cross(o.normal, tangent), sub(centroid, o.curve[0])) < 0.0 {
        chain.reverse();
        for o in &mut chain {
            o.curve = reversed(std::mem::take(&mut o.curve));
            o.cross = reversed(std::mem::take(&mut o.cross));
        }
    }
    chain
}

/// Turning angle between consecutive sides at their common point.
pub fn turn(a: &Open, b: &Open) -> f64 {
    let ta = normalize(sub(a.curve[a.curve.len() - 1], a.curve[a.curve.len() - 2]));
    let tb = normalize(sub(b.curve[1], b.curve[0]));
    norm(cross(ta, tb)).atan2(dot(ta, tb))
}

/// The hole of a `--no-fill` complex around one extraordinary element: quad layout (sectors
/// between straight spoke ends) or triangle layout; centre and unit normal given, tangents
/// `T0, T1` fitted to the spoke ends in that plane.
pub fn hole_of(c: &PatchComplex, triangles: bool, centre: Point, normal: Point) -> Hole {
    let chain = hole_loop(c, triangles);
    let mut n_ring = chain[0].normal;
    n_ring = normalize(n_ring);
    let normal = if dot(normal, n_ring) < 0.0 {
        scale(normal, -1.0)
    } else {
        normal
    };
    let sectors: Vec<Vec<Segment>> = if triangles {
        chain
            .iter()
            .map(|o| {
                vec![Segment {
                    boundary: o.curve.clone(),
                    cross: o.cross.clone(),
                }]
            })
            .collect()
    } else {
        // rotate so that chain[0] starts at a spoke end (straight join with its predecessor)
        let m = chain.len();
        let start = (0..m)
            .find(|&i| turn(&chain[(i + m - 1) % m], &chain[i]) < 1e-6)
            .expect("a spoke end");
        let ch: Vec<Open> = (0..m).map(|i| chain[(start + i) % m].clone()).collect();
        (0..m / 2)
            .map(|s| {
                let a = &ch[2 * s];
                let b = &ch[2 * s + 1];
                vec![
                    Segment {
                        boundary: a.curve.clone(),
                        cross: a.cross.clone(),
                    },
                    Segment {
                        boundary: reversed(b.curve.clone()),
                        cross: reversed(b.cross.clone()),
                    },
                ]
            })
            .collect()
    };
    let n = sectors.len();
    let mut hole = Hole::untangented(centre, sectors);
    // spoke ends of the quad layout, projected into the tangent plane, Fourier mode 1
    let q = hole.to_quad_layout().unwrap();
    let mut t = [[0.0; 3]; 2];
    for (s, sec) in q.hole.sectors.iter().enumerate() {
        let e = sub(sec[0].boundary[0], centre);
        let e = sub(e, scale(normal, dot(e, normal)));
        let th = 2.0 * std::f64::consts::PI * s as f64 / n as f64;
        t[0] = geom::axpy(t[0], 2.0 * th.cos() / n as f64, e);
        t[1] = geom::axpy(t[1], 2.0 * th.sin() / n as f64, e);
    }
    hole.tangents = t;
    hole
}
