//! G^1 caps (`fairsub::bezier::g1`) on the real last rings of today's schemes: the hole data are
//! read off the `--no-fill` complex of a c-net (Catmull-Clark, EG, QAS+, Doo-Sabin, guided bi-5
//! and bi-6) or a triangle fan (Loop), the cap is added, and the project's `check` measures every join. Asserted:
//! C^1 to the ring data (1e-12), G^1 below 1e-8 rad across spokes, at the centre and between ring
//! and cap (`check`), the centre and tangent plane as given; printed: the curvature range of the
//! cap and the G^1 defect of today's fill for comparison (`cargo test --release --test g1cap --
//! --nocapture`).

use fairsub::PolyMesh;
use fairsub::analysis::continuity::check;
use fairsub::bezier::g1::{CapOptions, Hole, Segment, g1_cap_with};
use fairsub::bezier::{BezierCurve, BezierPatch, Side};
use fairsub::gallery::{self, CnetShape};
use fairsub::geom::{self, Point, add, cross, dot, norm, normalize, scale, sub};
use fairsub::schemes::{CatmullClark, Loop, Scheme};
use fairsub::surface::adjacency::{default_tolerance, shared_boundaries};
use fairsub::surface::{self, ComplexOptions, Element, PatchComplex, Provenance};

/// One open side of a last-ring patch: its curve in loop order and the cross derivative
/// (Bezier coefficients) pointing out of the ring patch, into the hole.
#[derive(Clone)]
struct Open {
    curve: Vec<Point>,
    cross: Vec<Point>,
    normal: Point,
}

fn reversed(mut v: Vec<Point>) -> Vec<Point> {
    v.reverse();
    v
}

/// Coefficients of the degree-`d` polynomial with values `f(t_k)` at `t_k = (k + 1/2)/(d + 1)`.
fn interpolate(d: usize, f: impl Fn(f64) -> Point) -> Vec<Point> {
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
fn quad_open(p: &BezierPatch, side: Side) -> Open {
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
fn triangle_open(p: &BezierPatch, side: Side) -> Open {
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
const EV: Element = Element::Vertex(0);

fn last_ring(c: &PatchComplex) -> u32 {
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
fn hole_loop(c: &PatchComplex, triangles: bool) -> Vec<Open> {
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
fn turn(a: &Open, b: &Open) -> f64 {
    let ta = normalize(sub(a.curve[a.curve.len() - 1], a.curve[a.curve.len() - 2]));
    let tb = normalize(sub(b.curve[1], b.curve[0]));
    norm(cross(ta, tb)).atan2(dot(ta, tb))
}

/// The hole of a `--no-fill` complex around one extraordinary element: quad layout (sectors
/// between straight spoke ends) or triangle layout; centre and unit normal given, tangents
/// `T0, T1` fitted to the spoke ends in that plane.
fn hole_of(c: &PatchComplex, triangles: bool, centre: Point, normal: Point) -> Hole {
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
    let mut hole = Hole {
        centre,
        tangents: [[0.0; 3]; 2],
        sectors,
    };
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

fn build(scheme: &str, m: &PolyMesh, rings: usize, fill: bool) -> PatchComplex {
    surface::complex(scheme, m, ComplexOptions { rings, fill }, |_| {}).unwrap()
}

/// The fill's common corner: the point where all cap patches of today's fill meet.
fn fill_centre(c: &PatchComplex) -> Point {
    let caps: Vec<&BezierPatch> = c
        .patches
        .iter()
        .zip(&c.provenance)
        .filter(|(_, p)| matches!(p, Provenance::Cap { element, .. } if *element == EV))
        .map(|(b, _)| b)
        .collect();
    let corners = |p: &BezierPatch| {
        [(false, false), (true, false), (false, true), (true, true)].map(|(a, b)| p.corner(a, b))
    };
    for q in corners(caps[0]) {
        if caps
            .iter()
            .all(|p| corners(p).iter().any(|r| geom::dist(*r, q) < 1e-9))
        {
            return q;
        }
    }
    panic!("no common corner of the fill");
}

/// Result of one case.
struct Measured {
    degree: usize,
    centre: fairsub::bezier::g1::Centre,
    g1_before: f64,
    g1_after: f64,
    ring_cap_c1: f64,
    k_range: (f64, f64),
    ring_k: (f64, f64),
}

fn g1_of(c: &PatchComplex) -> f64 {
    check(c).all.g1
}

/// Builds the cap of `scheme` on `net` (`rings` rings), checks it, returns the measurements.
fn run(
    scheme: &str,
    net: &PolyMesh,
    rings: usize,
    triangles: bool,
    normal: Option<Point>,
) -> Measured {
    let filled = build(scheme, net, rings, true);
    let open = build(scheme, net, rings, false);
    let centre = fill_centre(&filled);
    let normal = match normal {
        Some(n) => normalize(n),
        None => {
            // plane of the innermost spoke ends' Fourier mode 1 (approximate)
            let h = hole_of(&open, triangles, centre, [0.0, 0.0, 1.0]);
            let q = h.to_quad_layout().unwrap();
            let n = q.hole.sectors.len();
            let mut t = [[0.0; 3]; 2];
            for (s, sec) in q.hole.sectors.iter().enumerate() {
                let e = sub(sec[0].boundary[0], centre);
                let th = 2.0 * std::f64::consts::PI * s as f64 / n as f64;
                t[0] = geom::axpy(t[0], th.cos(), e);
                t[1] = geom::axpy(t[1], th.sin(), e);
            }
            normalize(cross(t[0], t[1]))
        }
    };
    let hole = hole_of(&open, triangles, centre, normal);
    let cap = g1_cap_with(&hole, CapOptions::default()).unwrap();
    assert!(
        cap.compatibility.0 < 1e-9,
        "{scheme}: ring data {:?}",
        cap.compatibility
    );
    let q = hole.to_quad_layout().unwrap();
    let n = cap.patches.len();
    let size = q
        .hole
        .sectors
        .iter()
        .map(|s| geom::dist(s[0].boundary[0], centre))
        .fold(0.0, f64::max);
    // C^1 to the (quad) data, centre and tangent plane
    for (s, p) in cap.patches.iter().enumerate() {
        assert!(geom::dist(p.eval(0.0, 0.0), centre) < 1e-12 * size.max(1.0));
        let nc = p.normal(0.0, 0.0);
        assert!(
            norm(cross(nc, normal)) < 1e-10 && dot(nc, normal) > 0.0,
            "{scheme} normal"
        );
        for k in 0..=8 {
            let t = k as f64 / 8.0;
            let (a, b) = (&q.hole.sectors[s][0], &q.hole.sectors[s][1]);
            let da = p.derivatives(1.0, t);
            let db = p.derivatives(t, 1.0);
            let ea = geom::dist(da.p, BezierCurve::new(a.boundary.clone()).eval(t))
                + norm(add(da.du, BezierCurve::new(a.cross.clone()).eval(t)));
            let eb = geom::dist(db.p, BezierCurve::new(b.boundary.clone()).eval(t))
                + norm(add(db.dv, BezierCurve::new(b.cross.clone()).eval(t)));
            assert!(
                ea.max(eb) < 1e-12 * size.max(1.0),
                "{scheme} C^1 {ea:e} {eb:e}"
            );
        }
    }
    // the complex with the cap, measured by check
    let mut with_cap = open.clone();
    for (s, p) in cap.patches.iter().enumerate() {
        with_cap.push(
            p.clone(),
            Provenance::Cap {
                element: EV,
                sector: s as u32,
            },
        );
    }
    let rep = check(&with_cap);
    let mut ring_cap_c1: f64 = 0.0;
    for (kind, d) in &rep.by_kind {
        if kind.contains("cap") {
            assert!(d.g1 < 1e-8, "{scheme} n {n}: {kind} G^1 {:e}", d.g1);
            if kind.contains("ring") {
                ring_cap_c1 = ring_cap_c1.max(d.c1);
            }
        }
    }
    assert!(rep.all.g1 < 1e-8, "{scheme} n {n}: G^1 {:e}", rep.all.g1);
    // the cap closes the hole: as many open sides as with today's fill (the net's boundary)
    assert_eq!(
        rep.open_sides,
        check(&filled).open_sides,
        "{scheme} n {n}: open sides"
    );
    let k = last_ring(&open);
    let ring: Vec<BezierPatch> = open
        .patches
        .iter()
        .zip(&open.provenance)
        .filter(|(_, p)| matches!(p, Provenance::Ring { ring, element, .. } if *ring == k && *element == EV))
        .map(|(b, _)| b.clone())
        .collect();
    let ring_k = gauss_range(&ring);
    let k_range = gauss_range(&cap.patches);
    Measured {
        degree: cap.degree,
        centre: cap.centre,
        g1_before: g1_of(&filled),
        g1_after: rep.all.g1,
        ring_cap_c1,
        k_range,
        ring_k,
    }
}

/// Range of the Gauss curvature over a 17 x 17 grid of every patch (where defined).
fn gauss_range(patches: &[BezierPatch]) -> (f64, f64) {
    let mut k_range = (f64::INFINITY, f64::NEG_INFINITY);
    for p in patches {
        for i in 0..=16 {
            for j in 0..=16 {
                let (u, v) = (i as f64 / 16.0, j as f64 / 16.0);
                let cv = p.curvatures(u, v);
                if cv.gauss.is_finite() {
                    k_range.0 = k_range.0.min(cv.gauss);
                    k_range.1 = k_range.1.max(cv.gauss);
                }
            }
        }
    }
    k_range
}

fn report(scheme: &str, net: &str, n: usize, m: &Measured) {
    eprintln!(
        "{scheme:14} {net:8} n {n}: bi-{} cap ({:?}), G^1 before {:.3e} deg, after {:.3e} deg; \
         ring|cap C^1 (check) {:.1e}; Gauss curvature: cap [{:.3e}, {:.3e}], last ring \
         [{:.3e}, {:.3e}]",
        m.degree,
        m.centre,
        m.g1_before.to_degrees(),
        m.g1_after.to_degrees(),
        m.ring_cap_c1,
        m.k_range.0,
        m.k_range.1,
        m.ring_k.0,
        m.ring_k.1
    );
}

const VALENCES: [usize; 4] = [3, 5, 6, 8];

#[test]
fn catmull_clark_caps() {
    for n in VALENCES {
        for shape in [CnetShape::Saddle, CnetShape::Convex] {
            let net = gallery::cnet(n, shape, 3);
            let nrm = CatmullClark::limit_normals(&net)[0];
            let m = run("catmull-clark", &net, 3, false, Some(nrm));
            report("catmull-clark", shape.name(), n, &m);
            assert!(m.ring_cap_c1 < 1e-10, "C^1 ring|cap {:e}", m.ring_cap_c1);
        }
    }
}

#[test]
fn eg_and_qas_caps() {
    for (scheme, ns) in [("eg", &[3usize, 5][..]), ("qas-plus", &[5, 6, 7][..])] {
        for &n in ns {
            for shape in [CnetShape::Saddle, CnetShape::Convex] {
                let net = gallery::cnet(n, shape, 3);
                let m = run(scheme, &net, 3, false, None);
                report(scheme, shape.name(), n, &m);
                assert!(m.ring_cap_c1 < 1e-10, "C^1 ring|cap {:e}", m.ring_cap_c1);
            }
        }
    }
}

#[test]
fn dual_bi2_caps() {
    for scheme in ["doo-sabin", "doo-sabin-cc", "pgs"] {
        for n in VALENCES {
            for shape in [CnetShape::Saddle, CnetShape::Convex] {
                let net = gallery::cnet(n, shape, 3);
                // Exact limit tangent plane of the n-gon: the centre coefficient of sector s's bi-2
                // patch is the n-gon's vertex a_s = b_1 + cross_1 / 2 of segment a; the n-gon's
                // vertices map among themselves by a circulant, so their Fourier mode 1 spans the
                // subdominant eigenspace's tangent plane at every level.
                let open = build(scheme, &net, 3, false);
                let h = hole_of(&open, false, [0.0; 3], [0.0, 0.0, 1.0]);
                let mut t = [[0.0; 3]; 2];
                for (s, sec) in h.sectors.iter().enumerate() {
                    let a = &sec[0];
                    assert_eq!(a.boundary.len(), 3, "bi-2 ring");
                    let vtx = geom::axpy(a.boundary[1], 0.5, a.cross[1]);
                    let th = 2.0 * std::f64::consts::PI * s as f64 / n as f64;
                    t[0] = geom::axpy(t[0], th.cos(), vtx);
                    t[1] = geom::axpy(t[1], th.sin(), vtx);
                }
                let m = run(scheme, &net, 3, false, Some(cross(t[0], t[1])));
                report(scheme, shape.name(), n, &m);
                assert!(m.ring_cap_c1 < 1e-10, "C^1 ring|cap {:e}", m.ring_cap_c1);
            }
        }
    }
}

/// A fan of `n` triangles around vertex 0 (saddle heights), refined twice with Loop.
fn loop_fan(n: usize) -> PolyMesh {
    let mut pos = vec![[0.0, 0.0, 0.1]];
    for i in 0..n {
        let a = 2.0 * std::f64::consts::PI * i as f64 / n as f64;
        pos.push([a.cos(), a.sin(), 0.3 * (2.0 * a).cos()]);
    }
    let faces: Vec<Vec<usize>> = (0..n).map(|i| vec![0, i + 1, (i + 1) % n + 1]).collect();
    let m = PolyMesh::new(pos, &faces).unwrap();
    let m = Loop.refine(&m).unwrap().mesh;
    Loop.refine(&m).unwrap().mesh
}

#[test]
fn loop_caps() {
    // valence 6 is regular for Loop (no ring, no hole)
    for n in [3, 4, 5, 7, 8] {
        let net = loop_fan(n);
        let nrm = Loop.limit_normals(&net).unwrap()[0];
        let m = run("loop", &net, 3, true, Some(nrm));
        report("loop", "fan", n, &m);
    }
}

/// The regular hole (`n = 4`): the four bi-3 patches of a uniform B-spline surface around one
/// node are removed and capped from their own C^1 boundary data, centre, and tangents. A surface
/// of total degree 3 is reproduced exactly (the fairness `F_4` vanishes on it); a generic one
/// is not, and the deviation is printed.
#[test]
fn regular_hole_reproduction() {
    let cubic = |x: f64, y: f64| 0.05 * x * x * x - 0.1 * x * y * y + 0.2 * x * y - 0.1 * y * y;
    let bumpy = |x: f64, y: f64| 0.3 * (1.3 * x).sin() * (0.9 * y + 0.4).cos();
    for (name, z, exact) in [
        ("cubic", &cubic as &dyn Fn(f64, f64) -> f64, true),
        ("bumpy", &bumpy, false),
    ] {
        // patch of the face [i, i+1] x [j, j+1] (grid node (i, j) at (i, j, z(i, j)))
        let face = |i: i64, j: i64| {
            let net: [[Point; 4]; 4] = std::array::from_fn(|a| {
                std::array::from_fn(|b| {
                    let (x, y) = ((i + a as i64 - 1) as f64, (j + b as i64 - 1) as f64);
                    [x, y, z(x, y)]
                })
            });
            fairsub::bezier::convert::bicubic_bspline_to_bezier(&net)
        };
        let eval = |x: f64, y: f64| {
            let (i, j) = (x.floor().min(0.0), y.floor().min(0.0));
            let (i, j) = (
                if x >= 0.0 { 0.0 } else { i },
                if y >= 0.0 { 0.0 } else { j },
            );
            face(i as i64, j as i64).derivatives(x - i, y - j)
        };
        // sector s: P_s(u, v) = F(u e_s + v e_(s+1)), e_s the quarter turns of (1, 0)
        let e = |s: usize| match s % 4 {
            0 => [1.0, 0.0],
            1 => [0.0, 1.0],
            2 => [-1.0, 0.0],
            _ => [0.0, -1.0],
        };
        let at = |s: usize, u: f64, v: f64| {
            let (a, b) = (e(s), e(s + 1));
            let (x, y) = (u * a[0] + v * b[0], u * a[1] + v * b[1]);
            let d = eval(x, y);
            // derivatives along u and v of the sector map
            let du = add(scale(d.du, a[0]), scale(d.dv, a[1]));
            let dv = add(scale(d.du, b[0]), scale(d.dv, b[1]));
            (d.p, du, dv)
        };
        let sectors = (0..4)
            .map(|s| {
                vec![
                    Segment {
                        boundary: interpolate(3, |t| at(s, 1.0, t).0),
                        cross: interpolate(3, |t| scale(at(s, 1.0, t).1, -1.0)),
                    },
                    Segment {
                        boundary: interpolate(3, |t| at(s, t, 1.0).0),
                        cross: interpolate(3, |t| scale(at(s, t, 1.0).2, -1.0)),
                    },
                ]
            })
            .collect();
        let c = eval(0.0, 0.0);
        let hole = Hole {
            centre: c.p,
            tangents: [c.du, c.dv],
            sectors,
        };
        let cap = g1_cap_with(&hole, CapOptions::default()).unwrap();
        let mut worst: f64 = 0.0;
        for (s, p) in cap.patches.iter().enumerate() {
            for i in 0..=10 {
                for j in 0..=10 {
                    let (u, v) = (i as f64 / 10.0, j as f64 / 10.0);
                    worst = worst.max(geom::dist(p.eval(u, v), at(s, u, v).0));
                }
            }
        }
        eprintln!(
            "regular hole, {name} heights: bi-{} cap, largest distance to the B-spline surface {worst:.3e} \
             (the hole has size 1)",
            cap.degree
        );
        if exact {
            assert!(worst < 1e-12, "{name}: {worst:e}");
        } else {
            assert!(worst > 1e-6 && worst < 0.05, "{name}: {worst:e}");
        }
    }
}

#[test]
fn guided_caps() {
    for scheme in ["guided-bi6", "guided-bi5"] {
        for n in [3, 5, 6] {
            let net = gallery::cnet(n, CnetShape::Saddle, 3);
            let m = run(scheme, &net, 2, false, None);
            report(scheme, "saddle", n, &m);
            assert!(m.ring_cap_c1 < 1e-10, "C^1 ring|cap {:e}", m.ring_cap_c1);
        }
    }
}
