//! Exact patch complexes of Doo-Sabin, DS^CC and Loop: regular patches against independent
//! evaluations (the bi-2 B-spline basis, limit points of uniformly refined nets), C^0 and
//! closedness across every shared boundary of the gallery complexes, C^1 in a common affine
//! chart across regular and ring boundaries, and the documented ring layouts.

use fairsub::PolyMesh;
use fairsub::bezier::{BezierPatch, Side};
use fairsub::gallery::{self, CnetShape};
use fairsub::geom::{self, Point};
use fairsub::schemes::doo_sabin::face_limit_stencils;
use fairsub::schemes::{DooSabin, DooSabinCc, Loop, Scheme};
use fairsub::surface::adjacency::{SharedBoundary, default_tolerance, shared_boundaries};
use fairsub::surface::{self, ComplexOptions, Element, PatchComplex, Provenance};
use std::collections::HashMap;

fn opts(rings: usize) -> ComplexOptions {
    ComplexOptions { rings, fill: true }
}

fn build(scheme: &str, m: &PolyMesh, rings: usize) -> PatchComplex {
    surface::complex(scheme, m, opts(rings), |_| {}).unwrap()
}

const DUAL: [&str; 2] = ["doo-sabin", "doo-sabin-cc"];

fn dual_scheme(name: &str) -> Box<dyn Scheme> {
    match name {
        "doo-sabin" => Box::new(DooSabin),
        _ => Box::new(DooSabinCc),
    }
}

// ---------------------------------------------------------------------------------------------
// Point sets for "is this a limit point" look-ups

struct PointSet {
    cell: f64,
    map: HashMap<[i64; 3], Vec<Point>>,
}

impl PointSet {
    fn new(points: impl IntoIterator<Item = Point>) -> Self {
        let cell = 1e-3;
        let mut map: HashMap<[i64; 3], Vec<Point>> = HashMap::new();
        for p in points {
            map.entry(Self::key(cell, p)).or_default().push(p);
        }
        PointSet { cell, map }
    }

    fn key(cell: f64, p: Point) -> [i64; 3] {
        [0, 1, 2].map(|k| (p[k] / cell).floor() as i64)
    }

    /// Distance to the nearest point (infinite when none is within one cell).
    fn dist(&self, q: Point) -> f64 {
        let k = Self::key(self.cell, q);
        let mut best = f64::INFINITY;
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    if let Some(v) = self.map.get(&[k[0] + dx, k[1] + dy, k[2] + dz]) {
                        for p in v {
                            best = best.min(geom::dist(*p, q));
                        }
                    }
                }
            }
        }
        best
    }
}

/// Refinement level of a patch: 0 for regular patches, the ring number for rings.
fn level_of(p: &Provenance) -> Option<usize> {
    match p {
        Provenance::Regular { .. } => Some(0),
        Provenance::Ring { ring, .. } => Some(*ring as usize),
        _ => None,
    }
}

/// Limit points of a dual net: face centroids, vertex limits (boundary curve points included)
/// and the midpoints of boundary edges (knots of the Chaikin boundary curve).
fn dual_limit_points(scheme: &dyn Scheme, m: &PolyMesh) -> PointSet {
    let mut pts = face_limit_stencils(m).apply(m.positions());
    pts.extend(scheme.limit_stencils(m).unwrap().apply(m.positions()));
    for e in 0..m.num_edges() {
        if m.is_boundary_edge(e) {
            let [a, b] = m.edge(e);
            pts.push(geom::lerp(
                m.position(a as usize),
                m.position(b as usize),
                0.5,
            ));
        }
    }
    PointSet::new(pts)
}

fn uniform_levels(scheme: &dyn Scheme, m: &PolyMesh, levels: usize) -> Vec<PolyMesh> {
    let mut out = vec![m.clone()];
    for _ in 0..levels {
        let next = scheme.refine(out.last().unwrap()).unwrap().mesh;
        out.push(next);
    }
    out
}

// ---------------------------------------------------------------------------------------------
// Nets

/// A closed fan of `n` triangles around vertex 0, refined twice with Loop: vertex 0 is an
/// isolated extraordinary vertex of valence `n`.
fn loop_fan(n: usize) -> PolyMesh {
    let mut pos = vec![[0.0, 0.0, 0.4]];
    for i in 0..n {
        let a = 2.0 * std::f64::consts::PI * i as f64 / n as f64;
        pos.push([a.cos(), a.sin(), 0.2 * (2.0 * a).cos()]);
    }
    let faces: Vec<Vec<usize>> = (0..n).map(|i| vec![0, i + 1, (i + 1) % n + 1]).collect();
    let m = PolyMesh::new(pos, &faces).unwrap();
    let m = Loop.refine(&m).unwrap().mesh;
    Loop.refine(&m).unwrap().mesh
}

/// The uniform quadratic B-spline centred at 0 (support [-3/2, 3/2]).
fn n2(t: f64) -> f64 {
    let a = t.abs();
    if a <= 0.5 {
        0.75 - a * a
    } else if a <= 1.5 {
        0.5 * (a - 1.5) * (a - 1.5)
    } else {
        0.0
    }
}

// ---------------------------------------------------------------------------------------------
// Exactness

/// On a regular grid whose x, y coordinates are the lattice coordinates, the bi-2 B-spline maps
/// its domain to itself away from the boundary, so a patch point p must have the height
/// `sum z_ij N2(p.x - i) N2(p.y - j)`: an evaluation that uses no conversion table.
#[test]
fn dual_regular_patches_equal_the_bspline_basis_sum() {
    let m = 8;
    let z = |x: f64, y: f64| (0.7 * x).sin() * (0.4 * y).cos() + 0.05 * x * y;
    let net = fairsub::gallery::quad_grid(m, z);
    for scheme in DUAL {
        let c = build(scheme, &net, 2);
        assert_eq!(
            c.len(),
            net.num_vertices(),
            "{scheme}: one patch per vertex"
        );
        let mut checked = 0;
        let mut worst: f64 = 0.0;
        for p in &c.patches {
            let centre = p.eval(0.5, 0.5);
            if centre[0] < 0.9 || centre[0] > m as f64 - 0.9 {
                continue;
            }
            if centre[1] < 0.9 || centre[1] > m as f64 - 0.9 {
                continue;
            }
            for a in 0..=4 {
                for b in 0..=4 {
                    let q = p.eval(a as f64 / 4.0, b as f64 / 4.0);
                    let mut s = 0.0;
                    for j in 0..=m {
                        for i in 0..=m {
                            s += z(i as f64, j as f64) * n2(q[0] - i as f64) * n2(q[1] - j as f64);
                        }
                    }
                    worst = worst.max((s - q[2]).abs());
                    checked += 1;
                }
            }
        }
        assert_eq!(checked, 7 * 7 * 25, "{scheme}");
        eprintln!("{scheme}: bi-2 basis sum vs patches, max |dz| = {worst:.2e}");
        assert!(worst < 1e-13, "{scheme}: {worst}");
    }
}

/// Every point `(a/2, b/2)` of every regular and ring patch of level `l` is a limit point of the
/// uniformly refined net of level `l + 1` (nets with extraordinary vertices, n-gons and
/// boundaries).
#[test]
fn dual_regular_and_ring_patches_are_exact_limits() {
    let nets = [
        ("cnet-5-convex", gallery::cnet(5, CnetShape::Convex, 3), 3),
        ("cnet-3-saddle", gallery::cnet(3, CnetShape::Saddle, 3), 2),
        ("prism-5", gallery::prism(5), 2),
        ("cube", gallery::cube(), 2),
        ("open-pipe", gallery::open_pipe(), 1),
        ("torus-evs", gallery::torus_with_evs(), 2),
    ];
    for scheme in DUAL {
        let s = dual_scheme(scheme);
        for (name, m, rings) in &nets {
            let c = build(scheme, m, *rings);
            let levels = uniform_levels(s.as_ref(), m, rings + 1);
            let sets: Vec<PointSet> = levels
                .iter()
                .map(|l| dual_limit_points(s.as_ref(), l))
                .collect();
            let mut worst: f64 = 0.0;
            let mut n = 0;
            for (p, prov) in c.patches.iter().zip(&c.provenance) {
                let Some(l) = level_of(prov) else { continue };
                for a in 0..3 {
                    for b in 0..3 {
                        let q = p.eval(a as f64 / 2.0, b as f64 / 2.0);
                        worst = worst.max(sets[l + 1].dist(q));
                        n += 1;
                    }
                }
            }
            assert!(n > 0);
            assert!(worst < 1e-12, "{scheme} {name}: {worst}");
        }
    }
}

/// The same for Loop: corners and half-lattice points of a level-`l` triangle are limit points
/// of level `l + 1`, quarter-lattice points of level `l + 2`.
#[test]
fn loop_regular_and_ring_patches_are_exact_limits() {
    let nets = [
        ("icosahedron", gallery::icosahedron(), 2),
        ("tetrahedron", gallery::tetrahedron(), 2),
        ("octahedron", gallery::octahedron(), 1),
        ("tri-grid", gallery::tri_grid(), 2),
        ("fan-5", loop_fan(5), 2),
    ];
    for (name, m, rings) in &nets {
        let c = build("loop", m, *rings);
        let levels = uniform_levels(&Loop, m, rings + 2);
        let sets: Vec<PointSet> = levels
            .iter()
            .map(|l| PointSet::new(Loop.limit_stencils(l).unwrap().apply(l.positions())))
            .collect();
        let mut worst: f64 = 0.0;
        let samples = [
            (0.0, 0.0, 1),
            (1.0, 0.0, 1),
            (0.5, 0.0, 1),
            (0.0, 0.5, 1),
            (1.0, 0.5, 1),
            (0.0, 1.0, 1),
            (1.0 / 3.0, 0.25, 2),
            (0.5, 0.5, 2),
            (0.25, 0.0, 2),
        ];
        let mut n = 0;
        for (p, prov) in c.patches.iter().zip(&c.provenance) {
            let Some(l) = level_of(prov) else { continue };
            for &(u, v, d) in &samples {
                worst = worst.max(sets[l + d].dist(p.eval(u, v)));
                n += 1;
            }
        }
        assert!(n > 0, "{name}");
        eprintln!("loop {name}: {n} samples, max distance to Loop limit points {worst:.2e}");
        assert!(worst < 1e-12, "loop {name}: {worst}");
    }
}

// ---------------------------------------------------------------------------------------------
// C^0, closedness

fn side_point(p: &BezierPatch, side: Side, t: f64) -> Point {
    let [u, v] = side.domain_point(t);
    p.eval(u, v)
}

/// Largest distance between the two sides of a shared boundary, sampled.
fn c0_gap(c: &PatchComplex, r: &SharedBoundary) -> f64 {
    let (pa, pb) = (&c.patches[r.a], &c.patches[r.b]);
    (0..=6)
        .map(|k| {
            let t = r.t[0] + (r.t[1] - r.t[0]) * k as f64 / 6.0;
            geom::dist(
                side_point(pa, r.side_a, t),
                side_point(pb, r.side_b, r.map_to_b(t)),
            )
        })
        .fold(0.0, f64::max)
}

/// Number of non-collapsed patch sides that the shared boundaries do not cover completely.
fn uncovered_sides(c: &PatchComplex, shared: &[SharedBoundary], tol: f64) -> usize {
    let mut iv: HashMap<(usize, Side), Vec<(f64, f64)>> = HashMap::new();
    for r in shared {
        iv.entry((r.a, r.side_a))
            .or_default()
            .push((r.t[0], r.t[1]));
        let (s0, s1) = (r.s[0].min(r.s[1]), r.s[0].max(r.s[1]));
        iv.entry((r.b, r.side_b)).or_default().push((s0, s1));
    }
    let mut uncovered = 0;
    for (k, p) in c.patches.iter().enumerate() {
        for side in Side::ALL {
            if p.is_collapsed(side, tol) {
                continue;
            }
            let mut v = iv.get(&(k, side)).cloned().unwrap_or_default();
            v.sort_by(|a, b| a.0.total_cmp(&b.0));
            let mut reach = 0.0f64;
            for (a, b) in v {
                if a <= reach + 1e-9 {
                    reach = reach.max(b);
                }
            }
            if reach < 1.0 - 1e-9 {
                uncovered += 1;
            }
        }
    }
    uncovered
}

/// Every gallery net each scheme accepts: the complex (1 and 2 rings for the dual schemes, 0 and
/// 2 for Loop, filled) is C^0 to 1e-12 across
/// every shared boundary and, for closed nets, closed: every non-collapsed side is covered.
#[test]
fn gallery_complexes_are_c0_and_closed() {
    let mut total = 0;
    let (mut worst, mut pieces) = (0.0f64, 0usize);
    for (name, m) in gallery::all() {
        let mut schemes: Vec<&str> = DUAL.to_vec();
        if m.is_all_triangles() {
            schemes.push("loop");
        }
        let closed = m.boundary_loops().is_empty();
        for (scheme, rings) in schemes
            .into_iter()
            .flat_map(|s| [(s, if s == "loop" { 0 } else { 1 }), (s, 2)])
        {
            let c = build(scheme, &m, rings);
            let tol = default_tolerance(&c);
            let shared = shared_boundaries(&c, tol);
            let gap = shared.iter().map(|r| c0_gap(&c, r)).fold(0.0, f64::max);
            assert!(gap < 1e-12, "{scheme} {name} rings {rings}: C^0 gap {gap}");
            worst = worst.max(gap);
            pieces += shared.len();
            let open = uncovered_sides(&c, &shared, tol);
            if closed {
                assert_eq!(open, 0, "{scheme} {name} rings {rings}: uncovered sides");
            } else {
                assert!(open > 0, "{scheme} {name}: an open net has boundary sides");
            }
            total += 1;
        }
    }
    // Two dual schemes on every net, Loop on the triangle nets, two ring counts each.
    let triangle_nets = gallery::all()
        .iter()
        .filter(|(_, m)| m.is_all_triangles())
        .count();
    assert_eq!(total, 2 * (2 * gallery::all().len() + triangle_nets));
    eprintln!("{total} complexes, {pieces} shared boundary pieces, max C^0 gap {worst:.1e}");
}

// ---------------------------------------------------------------------------------------------
// C^1 in a common affine chart

/// Chart of a patch: the unit square (tensor patches), or the triangle
/// `(1-u)(1-v) c0 + u(1-v) c1 + v c2` (Loop's degenerate patches).
#[derive(Clone, Copy)]
enum Chart {
    Quad { du: [f64; 2], dv: [f64; 2] },
    Tri([[f64; 2]; 3]),
}

impl Chart {
    /// Jacobian columns `(x_u, x_v)` of the chart map at `(u, v)`.
    fn jacobian(&self, u: f64, v: f64) -> [[f64; 2]; 2] {
        match *self {
            Chart::Quad { du, dv, .. } => [du, dv],
            Chart::Tri([c0, c1, c2]) => {
                let xu = [(1.0 - v) * (c1[0] - c0[0]), (1.0 - v) * (c1[1] - c0[1])];
                let xv = [0, 1].map(|k| -(1.0 - u) * c0[k] - u * c1[k] + c2[k]);
                [xu, xv]
            }
        }
    }
}

/// Surface Jacobian in chart coordinates: `[P_u P_v] [x_u x_v]^-1` (two columns).
fn surface_jacobian(p: &BezierPatch, chart: &Chart, u: f64, v: f64) -> [Point; 2] {
    let d = p.derivatives(u, v);
    let [xu, xv] = chart.jacobian(u, v);
    let det = xu[0] * xv[1] - xv[0] * xu[1];
    // inverse rows: [ xv[1], -xv[0] ] / det ; [ -xu[1], xu[0] ] / det
    [
        [0, 1, 2].map(|k| (d.du[k] * xv[1] - d.dv[k] * xu[1]) / det),
        [0, 1, 2].map(|k| (-d.du[k] * xv[0] + d.dv[k] * xu[0]) / det),
    ]
}

fn lerp2(a: [f64; 2], b: [f64; 2], t: f64) -> [f64; 2] {
    [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]
}

/// Corner indices (start, end, apex) of a triangle side in the chart `[P0, P1, P2]`.
fn tri_side(side: Side) -> (usize, usize, usize) {
    match side {
        Side::V0 => (0, 1, 2),
        Side::U0 => (0, 2, 1),
        Side::U1 => (1, 2, 0),
        Side::V1 => unreachable!("collapsed side"),
    }
}

/// The chart of patch `b` placed beside patch `a` (whose chart is the standard one) so that the
/// shared pieces coincide: for squares the neighbour square of side `t1 - t0` across the side;
/// for triangles the lattice triangle across the side piece.
fn neighbour_chart(r: &SharedBoundary, tri: bool) -> (Chart, Chart) {
    let h = r.t[1] - r.t[0];
    if tri {
        let a = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
        let (s, e, x) = tri_side(r.side_a);
        let p = lerp2(a[s], a[e], r.t[0]);
        let q = lerp2(a[s], a[e], r.t[1]);
        let rr = [
            p[0] + h * (a[x][0] - a[s][0]),
            p[1] + h * (a[x][1] - a[s][1]),
        ];
        let apex = [p[0] + q[0] - rr[0], p[1] + q[1] - rr[1]];
        let (s2, e2, x2) = tri_side(r.side_b);
        let mut b = [[0.0; 2]; 3];
        if r.s[0] < r.s[1] {
            b[s2] = p;
            b[e2] = q;
        } else {
            b[e2] = p;
            b[s2] = q;
        }
        b[x2] = apex;
        return (Chart::Tri(a), Chart::Tri(b));
    }
    let tau = |s: Side| match s {
        Side::U0 | Side::U1 => [0.0, 1.0],
        Side::V0 | Side::V1 => [1.0, 0.0],
    };
    let outward = match r.side_a {
        Side::U0 => [-1.0, 0.0],
        Side::U1 => [1.0, 0.0],
        Side::V0 => [0.0, -1.0],
        Side::V1 => [0.0, 1.0],
    };
    let dtds = (r.t[1] - r.t[0]) / (r.s[1] - r.s[0]);
    let ta = tau(r.side_a);
    let along = [dtds * ta[0], dtds * ta[1]];
    let deeper = [h * outward[0], h * outward[1]];
    // B's own (u, v): along its side and into it.
    let (du, dv) = match r.side_b {
        Side::U0 => (deeper, along),
        Side::U1 => ([-deeper[0], -deeper[1]], along),
        Side::V0 => (along, deeper),
        Side::V1 => (along, [-deeper[0], -deeper[1]]),
    };
    let a = Chart::Quad {
        du: [1.0, 0.0],
        dv: [0.0, 1.0],
    };
    (a, Chart::Quad { du, dv })
}

/// Largest relative difference of the surface Jacobians of the two patches of a shared
/// boundary in the common chart, sampled inside the shared piece.
fn c1_defect(c: &PatchComplex, r: &SharedBoundary, tri: bool) -> f64 {
    let (ca, cb) = neighbour_chart(r, tri);
    let mut worst: f64 = 0.0;
    for k in 1..=5 {
        let t = r.t[0] + (r.t[1] - r.t[0]) * (0.1 + 0.8 * (k - 1) as f64 / 4.0);
        let [ua, va] = r.side_a.domain_point(t);
        let [ub, vb] = r.side_b.domain_point(r.map_to_b(t));
        let ja = surface_jacobian(&c.patches[r.a], &ca, ua, va);
        let jb = surface_jacobian(&c.patches[r.b], &cb, ub, vb);
        let scale = ja
            .iter()
            .flat_map(|x| x.iter())
            .fold(0.0f64, |m, x| m.max(x.abs()))
            .max(1e-300);
        for col in 0..2 {
            for d in 0..3 {
                worst = worst.max((ja[col][d] - jb[col][d]).abs() / scale);
            }
        }
    }
    worst
}

fn is_cap(p: &Provenance) -> bool {
    matches!(p, Provenance::Cap { .. })
}

/// C^1 across every shared boundary between regular and ring patches (T-junctions between
/// rings included), in the common affine chart; for the dual schemes also from the centroid
/// fill to the last ring. The spokes of the fills are only C^0: their defect is printed.
#[test]
fn regular_and_ring_boundaries_are_c1() {
    for (name, m) in gallery::all() {
        let mut schemes: Vec<&str> = DUAL.to_vec();
        if m.is_all_triangles() {
            schemes.push("loop");
        }
        for scheme in schemes {
            let tri = scheme == "loop";
            let c = build(scheme, &m, 3);
            let shared = shared_boundaries(&c, default_tolerance(&c));
            let (mut rr, mut cap_ring, mut cap_cap) = (0.0f64, 0.0f64, 0.0f64);
            let mut n = 0;
            for r in &shared {
                let (pa, pb) = (&c.provenance[r.a], &c.provenance[r.b]);
                let kite = |i: usize| {
                    c.caps
                        .iter()
                        .any(|s| (s.first as usize..(s.first + s.count) as usize).contains(&i))
                };
                if tri && (kite(r.a) || kite(r.b)) {
                    // Loop's G^1 caps are kites, not triangles: their C^1 to the ring (in the
                    // lattice chart) is measured by g1cap_schemes::loop_caps.
                    continue;
                }
                let d = c1_defect(&c, r, tri);
                match (is_cap(pa), is_cap(pb)) {
                    (false, false) => {
                        rr = rr.max(d);
                        n += 1;
                    }
                    (true, true) => cap_cap = cap_cap.max(d),
                    _ => cap_ring = cap_ring.max(d),
                }
            }
            assert!(
                rr < 1e-10,
                "{scheme} {name}: C^1 defect {rr} (regular/ring)"
            );
            if !tri {
                assert!(cap_ring < 1e-10, "{scheme} {name}: fill to ring {cap_ring}");
            }
            if name == "cnet-5-convex" || name == "icosahedron" || name == "prism-5" {
                eprintln!(
                    "{scheme} {name}: {n} regular/ring boundaries, C^1 defect {rr:.1e}; \
                     fill-ring {cap_ring:.1e}; fill-fill {cap_cap:.1e}"
                );
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Layouts

fn ring_counts(c: &PatchComplex, element: Element) -> (Vec<usize>, usize, Vec<usize>) {
    let mut rings = Vec::new();
    let mut caps = 0;
    let mut sectors = Vec::new();
    for p in &c.provenance {
        match *p {
            Provenance::Ring {
                element: e,
                ring,
                sector,
            } if e == element => {
                let r = ring as usize;
                if rings.len() < r {
                    rings.resize(r, 0);
                }
                rings[r - 1] += 1;
                if ring == 2 {
                    if sectors.len() <= sector as usize {
                        sectors.resize(sector as usize + 1, 0);
                    }
                    sectors[sector as usize] += 1;
                }
            }
            Provenance::Cap { element: e, .. } if e == element => caps += 1,
            _ => {}
        }
    }
    (rings, caps, sectors)
}

/// Dual schemes: an input vertex of valence n has an empty ring 1 and 3n patches in every later
/// ring; an isolated n-gon (the V-face of the once refined c-net) has 3n patches in every ring;
/// both get n fill patches, and every other vertex is one regular patch.
#[test]
fn dual_ring_layouts() {
    let k = 3;
    for scheme in DUAL {
        for n in [3, 5, 6, 8] {
            let m = gallery::cnet(n, CnetShape::Saddle, 3);
            let c = build(scheme, &m, k);
            let (rings, caps, sectors) = ring_counts(&c, Element::Vertex(0));
            assert_eq!(rings, vec![0, 3 * n, 3 * n], "{scheme} n={n}");
            assert_eq!(sectors, vec![3; n], "{scheme} n={n}");
            assert_eq!(caps, n);
            let regular = c
                .provenance
                .iter()
                .filter(|p| matches!(p, Provenance::Regular { .. }))
                .count();
            assert_eq!(regular, m.num_vertices() - 1);
            assert_eq!(c.len(), regular + 6 * n + n);

            let d = dual_scheme(scheme).refine(&m).unwrap().mesh;
            let f = (0..d.num_faces()).find(|&f| d.face_size(f) != 4).unwrap();
            assert_eq!(d.face_size(f), n);
            let c = build(scheme, &d, k);
            let (rings, caps, sectors) = ring_counts(&c, Element::Face(f as u32));
            assert_eq!(rings, vec![3 * n; k], "{scheme} n-gon n={n}");
            assert_eq!(sectors, vec![3; n]);
            assert_eq!(caps, n);
            assert_eq!(c.len(), d.num_vertices() - n + 3 * n * k + n);
        }
    }
}

/// Loop: an isolated vertex of valence n has 3n triangles in every ring (3 per sector) and n
/// fill triangles; the icosahedron's 12 vertices of valence 5 share its 20 triangles at level 0.
#[test]
fn loop_ring_layouts() {
    let k = 3;
    for n in [3, 4, 5, 7, 8] {
        let m = loop_fan(n);
        assert_eq!(m.valence(0), n);
        let c = build("loop", &m, k);
        let (rings, caps, sectors) = ring_counts(&c, Element::Vertex(0));
        assert_eq!(rings, vec![3 * n; k], "n={n}");
        assert_eq!(sectors, vec![3; n]);
        assert_eq!(caps, n);
    }
    let c = build("loop", &gallery::icosahedron(), 2);
    let count = |f: &dyn Fn(&Provenance) -> bool| c.provenance.iter().filter(|p| f(p)).count();
    assert_eq!(
        count(&|p| matches!(p, Provenance::Ring { ring: 1, .. })),
        20
    );
    assert_eq!(
        count(&|p| matches!(p, Provenance::Ring { ring: 2, .. })),
        12 * 15
    );
    assert_eq!(count(&|p| matches!(p, Provenance::Cap { .. })), 12 * 5);
}

// ---------------------------------------------------------------------------------------------
// API

#[test]
fn complex_names_and_errors() {
    let cnet = gallery::default_net();
    let ds = build("doo-sabin", &cnet, 2);
    let dscc = build("doo-sabin-cc", &cnet, 2);
    assert_eq!(ds.len(), dscc.len());
    // Regular patches agree (both are the bi-2 B-spline), rings differ with the corner rule.
    let mut same_regular = true;
    let mut ring_diff: f64 = 0.0;
    for k in 0..ds.len() {
        let d = ds.patches[k]
            .cps
            .iter()
            .zip(&dscc.patches[k].cps)
            .map(|(a, b)| geom::dist(*a, *b))
            .fold(0.0, f64::max);
        match ds.provenance[k] {
            Provenance::Regular { .. } => same_regular &= d == 0.0,
            _ => ring_diff = ring_diff.max(d),
        }
    }
    assert!(same_regular);
    assert!(ring_diff > 1e-3, "{ring_diff}");
    assert!(surface::complex("ds", &cnet, opts(1), |_| {}).is_ok());
    assert!(surface::complex("ds-cc", &cnet, opts(1), |_| {}).is_ok());
    let e = surface::complex("loop", &cnet, opts(1), |_| {})
        .unwrap_err()
        .to_string();
    assert!(e.contains("face 0 has 4 corners"), "{e}");
    let e = surface::complex("doo-sabin", &gallery::cube(), opts(0), |_| {})
        .unwrap_err()
        .to_string();
    assert!(e.contains("vertex 0") && e.contains("--rings 1"), "{e}");
    for name in ["doo-sabin", "doo-sabin-cc", "loop"] {
        let info = fairsub::schemes::catalog()
            .into_iter()
            .find(|s| s.name == name)
            .unwrap();
        assert!(info.rings && info.status == "available", "{name}");
    }
    // Progress is reported once per level.
    let mut levels = Vec::new();
    surface::complex("loop", &gallery::icosahedron(), opts(3), |l| levels.push(l)).unwrap();
    assert_eq!(levels, vec![1, 2, 3]);
}
