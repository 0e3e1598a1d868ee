//! Exact patch complexes of the bi-2 family: PGS, TPS, adjustable TPS, polar bi-2 and mixed
//! nets, as regular bi-2 patches plus nested rings around every extraordinary element.
//!
//! # Layout
//!
//! Every vertex with four quads (two on the boundary, one at a corner) carries the exact bi-2
//! patch of its 3x3 net ([`super::ds::regular_vertex_patch`], provenance `Regular`). The
//! patches missing around an extraordinary element leave a hole, which its scheme fills with
//! rings computed from the element's *local net* alone:
//!
//! | element | scheme | local net | ring `l` (`l >= 1`) | patches per ring |
//! | --- | --- | --- | --- | --- |
//! | `n`-gon facet | PGS | DS-net, `9 n` points ([`crate::schemes::bi2::pgs::ds_net`]) | patches of `b, c, d` of the level-`l` DS-net | `3 n` |
//! | vertex of valence `n` | TPS / adjustable TPS | q-net, `1 + 6 n` points (the 2-ring c-net) | patches of `a, b` of the level-`l` q-net | `2 n` |
//! | pole of valence `n` | PolBS | polar net, `1 + 3 n` points ([`crate::schemes::bi2::polar::polar_net`]) | patches of `b` of the level-`l` polar net | `n` |
//!
//! The step from level `l` to `l + 1` is a stencil table on the local net read off the
//! scheme's own whole-mesh refinement of its canonical local net ([`LocalScheme`]), so the
//! rings use exactly the rules of `--levels` and of the analysis. Ring `l` has parameter size
//! `2^-l` (PGS, radially for PolBS), `3^-l` (TPS) or the adjustable pattern, and joins ring
//! `l - 1` C^1 (ring 1 joins the regular patches). `pgs` itself (any polygon mesh, extraordinary
//! vertices becoming facets) goes through the Doo-Sabin machinery of [`super::ds`]
//! ([`pgs_complex`]) and is laid out patch for patch like Doo-Sabin; the local-net rings of
//! [`mixed_complex`] give the same patches on a DS-net (tested).
//!
//! Adjustable TPS rings are bi-2 pieces with non-uniform knots: level 1 has ring width `r`
//! and outer width `r` relative to the centre, later levels `r` and `r^2`
//! (`r = e / (1 - 2e)`, see [`crate::schemes::bi2::ternary`]). Across their sides the rings
//! are C^1 up to the per-piece affine reparametrisation this implies; the conformal C^1 test
//! of [`crate::analysis::continuity`] does not apply to them (nor to polar rings, which halve
//! only radially), [`crate::analysis::bi2::continuity_up_to_scaling`] does.
//!
//! # Fills (fairsub's own, documented constructions)
//!
//! With `fill`, the hole inside the last ring is closed, C^1 to that ring and C^0 inside:
//! - PGS: one bi-2 patch per corner `a_i` of the facet: its 3x3 net's B-spline conversion with
//!   the corner coefficient at the facet replaced by the limit point (7), exactly the centroid
//!   fill of [`super::ds`] with the scheme's limit point;
//! - TPS: one bi-2 patch per sector, the quarter of the centre's bi-2 piece (its blossoms over
//!   the sector's 2x2 block and the neighbouring spokes), whose corner coefficient at the
//!   centre is replaced by the limit point (21);
//! - PolBS: one bi-2 patch per sector with its side at the pole collapsed to the limit point
//!   (16), its middle row the circular quadratic B-spline of the `a` ring and its outer row the
//!   last ring's inner boundary (the `(a + b) / 2` ring).
//!
//! The fills meet at the limit point with tangents towards the first inner coefficients, so
//! they are tangent-continuous there exactly when those are coplanar (always for the
//! characteristic nets; `--no-fill` leaves the holes open).

use super::{ComplexOptions, Element, PatchComplex, Provenance};
use crate::bezier::BezierPatch;
use crate::error::{Error, Result};
use crate::geom::Point;
use crate::mesh::PolyMesh;
use crate::mesh::nets::{self, CnetShape};
use crate::schemes::Scheme;
use crate::schemes::bi2::pgs::{PgsOptions, PgsParams, ds_net, ds_net_chart, ds_net_index};
use crate::schemes::bi2::polar::{polar_net, radial_step_detailed};
use crate::schemes::bi2::ternary::{
    TernaryRules, TpsParams, Widths, edge_child_index, face_child_index, ternary_step,
    uniform_widths,
};
use crate::schemes::bi2::{Pgs, bi2_patch_stencils, blossom_weights, compose};
use crate::stencil::{Stencil, StencilTable};

/// The kind of an element's local scheme.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LocalKind {
    /// PGS at an `n`-gon facet.
    Pgs,
    /// A ternary scheme at a vertex of valence `n`.
    Ternary(TernaryRules),
    /// PolBS at a pole.
    Polar,
}

/// An element's local subdivision: the steps between levels of its local net and the patches
/// each level defines. Every table is read off the scheme's whole-mesh refinement of the
/// canonical local net.
#[derive(Debug, Clone)]
pub struct LocalScheme {
    /// The scheme.
    pub kind: LocalKind,
    /// Valence (facet size).
    pub n: usize,
    /// Points of the local net.
    pub size: usize,
    /// The step from level 0 (the input net) to level 1.
    pub first: StencilTable,
    /// The step between later levels.
    pub later: StencilTable,
}

/// Canonical local-net index of q-net chart point `(i, j)` (`i = 1, 2`, `j = 0, 1, 2`) of
/// sector `s`: the layout of [`nets::cnet`] with two rings.
pub fn qnet_index(s: usize, i: usize, j: usize) -> usize {
    1 + 6 * s + 3 * (i - 1) + j
}

/// The q-net point at chart point `(x, y)` of sector `s` (integer coordinates, `|x|, |y| <= 2`;
/// sector `s + 1`'s `(x, y)` lies at `(-y, x)` in sector `s`'s chart), or `None` outside the
/// 2-ring.
pub fn qnet_chart(n: usize, s: usize, x: i64, y: i64) -> Option<usize> {
    if x == 0 && y == 0 {
        return Some(0);
    }
    let (mut s, mut x, mut y) = (s as i64, x, y);
    for _ in 0..3 {
        if x >= 1 && y >= 0 {
            break;
        }
        if y >= 0 {
            // Counter-clockwise: sector s + 1's (x', y') lies at (-y', x').
            (x, y) = (y, -x);
            s += 1;
        } else {
            (x, y) = (-y, x);
            s -= 1;
        }
    }
    if !(1..=2).contains(&x) || !(0..=2).contains(&y) {
        return None;
    }
    Some(qnet_index(
        s.rem_euclid(n as i64) as usize,
        x as usize,
        y as usize,
    ))
}

/// Knot widths of the canonical q-net ([`nets::cnet`] with 2 rings) in a pattern: a vertex
/// at chart `(i, j)` has width `pattern[i]` along its sector's first axis and `pattern[j]`
/// along the second (the centre `pattern[0]` in every direction).
pub fn qnet_widths(net: &PolyMesh, n: usize, pattern: [f64; 3]) -> Widths {
    // Chart coordinates of every vertex in its own sector.
    let mut coord = vec![(0usize, 0i64, 0i64); net.num_vertices()];
    for s in 0..n {
        for i in 1..=2 {
            for j in 0..=2 {
                coord[qnet_index(s, i, j)] = (s, i as i64, j as i64);
            }
        }
    }
    // Coordinates of vertex w in sector s's frame.
    let in_frame = |w: usize, s: usize| -> (i64, i64) {
        if w == 0 {
            return (0, 0);
        }
        let (t, x, y) = coord[w];
        let d = (t as i64 - s as i64).rem_euclid(n as i64);
        match d {
            0 => (x, y),
            1 => (-y, x),
            _ if d == n as i64 - 1 => (y, -x),
            _ => (i64::MAX / 4, 0),
        }
    };
    let width_along = |v: usize, w: usize| -> f64 {
        if v == 0 {
            return pattern[0];
        }
        let (s, x, y) = coord[v];
        let (wx, _) = in_frame(w, s);
        if wx != x {
            pattern[x.unsigned_abs() as usize]
        } else {
            pattern[y.unsigned_abs() as usize]
        }
    };
    (0..net.num_halfedges() as u32)
        .map(|h| {
            let (a, b) = (net.he_from(h) as usize, net.he_to(h) as usize);
            [width_along(a, b), width_along(b, a)]
        })
        .collect()
}

fn select(t: &StencilTable, rows: &[usize], size: usize) -> Result<StencilTable> {
    let sel = t.select_rows(rows);
    let cols: Vec<usize> = (0..size).collect();
    sel.restrict_sources(&cols)
        .ok_or_else(|| Error::Unsupported("a local rule reads beyond its local net".into()))
}

impl LocalScheme {
    /// The local scheme of PGS at an `n`-gon facet: rows of [`Pgs`]'s refinement of
    /// [`ds_net`], in the canonical order.
    pub fn pgs(n: usize) -> Result<LocalScheme> {
        let net = ds_net(n, |_, _| 0.0)?;
        let r = Pgs.refine(&net)?;
        let rows = pgs_rows(&net, n);
        let step = select(&r.stencils, &rows, 9 * n)?;
        Ok(LocalScheme {
            kind: LocalKind::Pgs,
            n,
            size: 9 * n,
            first: step.clone(),
            later: step,
        })
    }

    /// The local scheme of a ternary scheme at a vertex of valence `n`: rows of
    /// [`ternary_step`] on the q-net with uniform widths (first step) and with the stationary
    /// pattern `1, r, r^2` (later steps).
    pub fn ternary(n: usize, rules: TernaryRules) -> Result<LocalScheme> {
        let net = nets::cnet(n, CnetShape::Convex, 2);
        let rows = ternary_rows(&net, n);
        let size = 1 + 6 * n;
        let (r0, _) = ternary_step(&net, &uniform_widths(&net), &rules, "tps")?;
        let r = rules.ring_ratio();
        let w = qnet_widths(&net, n, [1.0, r, r * r]);
        let (r1, _) = ternary_step(&net, &w, &rules, "tps")?;
        Ok(LocalScheme {
            kind: LocalKind::Ternary(rules),
            n,
            size,
            first: select(&r0.stencils, &rows, size)?,
            later: select(&r1.stencils, &rows, size)?,
        })
    }

    /// The local scheme of PolBS at a pole of valence `n`: rows of the radial step of
    /// [`polar_net`].
    pub fn polar(n: usize) -> Result<LocalScheme> {
        let net = polar_net(n, |_, _| 0.0)?;
        let st = radial_step_detailed(&net)?;
        let mut rows = vec![st.pole_point[0] as usize];
        for s in 0..n {
            let (a, b) = (1 + 3 * s, 2 + 3 * s);
            let e0 = edge_between(&net, 0, a)?;
            let e1 = edge_between(&net, a, b)?;
            let end = |e: usize, v: usize| -> usize {
                let h = net.edge_halfedge(e);
                let k = if net.he_from(h) as usize == v { 0 } else { 1 };
                st.spoke_point[e][k] as usize
            };
            rows.extend([end(e0, a), end(e1, a), end(e1, b)]);
        }
        let size = 1 + 3 * n;
        let step = select(&st.refinement.stencils, &rows, size)?;
        Ok(LocalScheme {
            kind: LocalKind::Polar,
            n,
            size,
            first: step.clone(),
            later: step,
        })
    }

    /// The step from level `l` to `l + 1`.
    pub fn step(&self, l: usize) -> &StencilTable {
        if l == 0 { &self.first } else { &self.later }
    }

    /// Relative knot widths `(centre, ring, outer)` of the level-`l` net (all 1 but for
    /// adjustable TPS).
    pub fn pattern(&self, l: usize) -> [f64; 3] {
        match self.kind {
            LocalKind::Ternary(rules) if l > 0 => {
                let r = rules.ring_ratio();
                [1.0, r, if l == 1 { r } else { r * r }]
            }
            _ => [1.0, 1.0, 1.0],
        }
    }

    /// The patches of the ring of the level-`l` local net as coefficient stencils over the
    /// local net, with their sectors.
    pub fn ring(&self, l: usize) -> Vec<(Vec<Stencil>, u32)> {
        let n = self.n;
        let mut out = Vec::new();
        match self.kind {
            LocalKind::Pgs => {
                for s in 0..n {
                    for (cx, cy) in [(3i64, 1i64), (3, 3), (1, 3)] {
                        let net = chart_net(|dx, dy| {
                            ds_net_chart(n, s, cx + 2 * dx, cy + 2 * dy).unwrap_or(0)
                        });
                        out.push((bi2_patch_stencils(&net, [1.0; 3], [1.0; 3]), s as u32));
                    }
                }
            }
            LocalKind::Ternary(_) => {
                let p = self.pattern(l);
                for s in 0..n {
                    for (cx, cy) in [(1i64, 0i64), (1, 1)] {
                        let net =
                            chart_net(|dx, dy| qnet_chart(n, s, cx + dx, cy + dy).unwrap_or(0));
                        let wu = [p[0], p[1], p[2]];
                        let wv = if cy == 0 {
                            [p[1], p[0], p[1]]
                        } else {
                            [p[0], p[1], p[2]]
                        };
                        out.push((bi2_patch_stencils(&net, wu, wv), s as u32));
                    }
                }
            }
            LocalKind::Polar => {
                for s in 0..n {
                    // u radial (a, b, c), v circular (s - 1, s, s + 1).
                    let net = chart_net(|dr, dc| {
                        let t = (s + n).wrapping_add_signed(dc as isize) % n;
                        1 + 3 * t + (1 + dr) as usize
                    });
                    out.push((bi2_patch_stencils(&net, [1.0; 3], [1.0; 3]), s as u32));
                }
            }
        }
        out
    }

    /// The limit point of the element as a stencil over the local net: (7), (21) or (16).
    pub fn limit(&self) -> Result<Stencil> {
        let n = self.n;
        match self.kind {
            LocalKind::Pgs => {
                let prm = PgsParams::new(n)?;
                let mut s = Stencil::new();
                for k in 0..n {
                    let (a, b, d) = (
                        ds_net_index(k, 0, 0),
                        ds_net_index(k, 1, 0),
                        ds_net_index(k, 0, 1),
                    );
                    let nf = n as f64;
                    // p from (1), then (1 - tau) p + tau a_mean.
                    s.add(a, (1.0 - prm.tau) * prm.mu / nf + prm.tau / nf);
                    s.add(b, (1.0 - prm.tau) * (1.0 - prm.mu) / (2.0 * nf));
                    s.add(d, (1.0 - prm.tau) * (1.0 - prm.mu) / (2.0 * nf));
                }
                Ok(s.merged())
            }
            LocalKind::Ternary(_) => {
                let p = TpsParams::new(n)?;
                let mut s = Stencil::point(0).scaled(1.0 - p.tau1 - p.tau2);
                for k in 0..n {
                    s.add(qnet_index(k, 1, 0), p.tau1 / n as f64);
                    s.add(qnet_index(k, 1, 1), p.tau2 / n as f64);
                }
                Ok(s.merged())
            }
            LocalKind::Polar => {
                let mut s = Stencil::point(0).scaled(2.0 / 3.0);
                for k in 0..n {
                    s.add(1 + 3 * k, 1.0 / (3.0 * n as f64));
                }
                Ok(s.merged())
            }
        }
    }

    /// The fill patches of the hole inside the ring of the level-`l` local net (see the
    /// [module](self) documentation), over the local net.
    pub fn fill(&self, l: usize) -> Result<Vec<(Vec<Stencil>, u32)>> {
        let n = self.n;
        let lim = self.limit()?;
        let mut out = Vec::new();
        match self.kind {
            LocalKind::Pgs => {
                for s in 0..n {
                    let net = chart_net(|dx, dy| {
                        ds_net_chart(n, s, 1 + 2 * dx, 1 + 2 * dy).unwrap_or(ds_net_index(s, 0, 0))
                    });
                    let mut c = bi2_patch_stencils(&net, [1.0; 3], [1.0; 3]);
                    c[0] = lim.clone();
                    out.push((c, s as u32));
                }
            }
            LocalKind::Ternary(_) => {
                let p = self.pattern(l);
                // Blossoms of the quarter [0, 1/2] of the centre piece [-1/2, 1/2] (neighbours of
                // width p[1]): F(0, 0), F(0, 1/2), F(1/2, 1/2).
                let bl = [
                    blossom_weights(p[1], p[0], p[1], 0.0, 0.0),
                    blossom_weights(p[1], p[0], p[1], 0.0, 0.5 * p[0]),
                    blossom_weights(p[1], p[0], p[1], 0.5 * p[0], 0.5 * p[0]),
                ];
                for s in 0..n {
                    let pt = |x: i64, y: i64| qnet_chart(n, s, x, y);
                    let mut c = Vec::with_capacity(9);
                    for bi in &bl {
                        for bj in &bl {
                            let mut st = Stencil::new();
                            for (k, &wu) in bi.iter().enumerate() {
                                for (m, &wv) in bj.iter().enumerate() {
                                    let w = wu * wv;
                                    if w == 0.0 {
                                        continue;
                                    }
                                    match pt(k as i64 - 1, m as i64 - 1) {
                                        Some(x) => {
                                            st.add(x, w);
                                        }
                                        // The diagonal behind the centre (n != 4) only enters
                                        // the centre coefficient, which is replaced below.
                                        None => {
                                            st.add(0, w);
                                        }
                                    }
                                }
                            }
                            c.push(st.merged());
                        }
                    }
                    c[0] = lim.clone();
                    out.push((c, s as u32));
                }
            }
            LocalKind::Polar => {
                let a = |t: usize| 1 + 3 * (t % n);
                for s in 0..n {
                    let mut c = Vec::with_capacity(9);
                    for i in 0..3 {
                        for j in 0..3 {
                            let t = s + n + j - 1;
                            // Circular Bezier of a ring: (x_(t) + x_(t+1)) / 2 at the ends.
                            let ring = |k: usize| -> Stencil {
                                match i {
                                    1 => Stencil::point(a(k)),
                                    _ => Stencil::from_pairs([(a(k), 0.5), (a(k) + 1, 0.5)]),
                                }
                            };
                            let st = match (i, j) {
                                (0, _) => lim.clone(),
                                (_, 1) => ring(s),
                                (_, 0) => mid(&ring(s), &ring(t)),
                                _ => mid(&ring(s), &ring(t)),
                            };
                            c.push(st);
                        }
                    }
                    out.push((c, s as u32));
                }
            }
        }
        Ok(out)
    }
}

/// The midpoint of two stencils.
fn mid(a: &Stencil, b: &Stencil) -> Stencil {
    let mut s = Stencil::new();
    s.add_scaled(a, 0.5).add_scaled(b, 0.5);
    s.merged()
}

/// A 3x3 net of point stencils from `f(dx, dy)`, `dx, dy in -1..=1`, `net[k][l]` at
/// `(k - 1, l - 1)`.
fn chart_net(f: impl Fn(i64, i64) -> usize) -> [[Stencil; 3]; 3] {
    std::array::from_fn(|k| std::array::from_fn(|l| Stencil::point(f(k as i64 - 1, l as i64 - 1))))
}

fn edge_between(net: &PolyMesh, a: usize, b: usize) -> Result<usize> {
    net.find_halfedge(a, b)
        .or_else(|| net.find_halfedge(b, a))
        .map(|h| net.he_edge(h) as usize)
        .ok_or_else(|| Error::Unsupported(format!("vertices {a} and {b} are not adjacent")))
}

/// Corner half-edge of vertex `v` in face `f`.
fn corner(net: &PolyMesh, f: usize, v: usize) -> usize {
    let k = net
        .face(f)
        .iter()
        .position(|&x| x as usize == v)
        .expect("the vertex is a corner of the face");
    net.face_halfedge(f) as usize + k
}

/// The rows of the refined DS-net (canonical order) among the children of [`Pgs`]'s step on
/// [`ds_net`]: the child of corner `h` is child point `h`.
pub fn pgs_rows(net: &PolyMesh, n: usize) -> Vec<usize> {
    let inner = |s: usize| 1 + 6 * s;
    let cross = |s: usize| 1 + 6 * (s % n) + 4;
    let mut rows = vec![0; 9 * n];
    for s in 0..n {
        let prev = (s + n - 1) % n;
        let (a, b, c, d) = (
            ds_net_index(s, 0, 0),
            ds_net_index(s, 1, 0),
            ds_net_index(s, 1, 1),
            ds_net_index(s, 0, 1),
        );
        let put = |i: usize, j: usize, f: usize, v: usize, rows: &mut Vec<usize>| {
            rows[ds_net_index(s, i, j)] = corner(net, f, v);
        };
        put(0, 0, 0, a, &mut rows);
        put(1, 0, cross(prev), a, &mut rows);
        put(0, 1, cross(s), a, &mut rows);
        put(1, 1, inner(s), a, &mut rows);
        put(2, 0, cross(prev), b, &mut rows);
        put(2, 1, inner(s), b, &mut rows);
        put(0, 2, cross(s), d, &mut rows);
        put(1, 2, inner(s), d, &mut rows);
        put(2, 2, inner(s), c, &mut rows);
    }
    rows
}

/// The rows of the refined q-net (canonical order) among the children of [`ternary_step`] on
/// the 2-ring c-net.
pub fn ternary_rows(net: &PolyMesh, n: usize) -> Vec<usize> {
    let mut rows = vec![0usize; 1 + 6 * n];
    for s in 0..n {
        let h = net
            .find_halfedge(0, qnet_index(s, 1, 0))
            .expect("the c-net's centre is joined to its first ring");
        let (nx, nn, pv) = (net.he_next(h), net.he_next(net.he_next(h)), net.he_prev(h));
        rows[qnet_index(s, 1, 0)] = edge_child_index(net, h, true);
        rows[qnet_index(s, 2, 0)] = edge_child_index(net, h, false);
        rows[qnet_index(s, 1, 1)] = face_child_index(net, h);
        rows[qnet_index(s, 2, 1)] = face_child_index(net, nx);
        rows[qnet_index(s, 2, 2)] = face_child_index(net, nn);
        rows[qnet_index(s, 1, 2)] = face_child_index(net, pv);
    }
    rows
}

/// One extraordinary element with its local net over the mesh at level `start` of its scheme.
struct RingElement {
    element: Element,
    scheme: LocalScheme,
    local0: Vec<Stencil>,
    /// The scheme's level of `local0` (1 after a whole-net step).
    start: usize,
}

fn not_separated(what: String, name: &str) -> Error {
    let way_out = match name {
        "polar-bi2" => {
            "polar-bi2 takes polar layouts and prism-like caps (each cap vertex with one edge \
             leaving the cap, so that it has valence 4 next to its pole); use pgs or bi2-mixed \
             for other facets"
        }
        "bi2-mixed" => {
            "bi2-mixed needs every extraordinary element surrounded by regular vertices (four \
             quads) and facets with a DS-net; refine with pgs first when the net has only facets, \
             or use pgs, tps or polar-bi2 on their own, which separate elements by themselves"
        }
        _ => {
            "the elements stay too close even after two whole-net steps; use pgs, which \
             separates elements by itself"
        }
    };
    Error::Unsupported(format!("{what}: {way_out}"))
}

fn regular(mesh: &PolyMesh, v: usize) -> bool {
    super::ds::regular_vertex_patch(mesh, v).is_some()
}

/// The level-0 local DS-net of facet `f` (its `a, b, c, d`; the outer layer is not read).
fn pgs_element(mesh: &PolyMesh, f: usize, name: &str) -> Result<RingElement> {
    let n = mesh.face_size(f);
    let net = Pgs::facet_net(mesh, f).ok_or_else(|| {
        not_separated(
            format!(
                "facet {f} ({n} sides) has no DS-net (a corner not of valence 4, a boundary edge \
                 or a neighbour that is not a quad)"
            ),
            name,
        )
    })?;
    let a0 = net.a[0] as usize;
    let mut local = vec![Stencil::point(a0); 9 * n];
    let h0 = mesh.face_halfedge(f);
    for s in 0..n {
        let a = net.a[s] as usize;
        // The corner quad: a's face after the quad across edge a_s a_(s+1), counter-clockwise.
        let h = h0 + s as u32;
        let t = mesh
            .he_twin(mesh.he_prev(h))
            .ok_or_else(|| not_separated(format!("facet {f} touches the boundary"), name))?;
        // t leaves a_s into the quad across edge a_(s-1) a_s; the face clockwise of it...
        let g = mesh.he_twin(mesh.he_prev(t)).ok_or_else(|| {
            not_separated(format!("corner {a} of facet {f} is on the boundary"), name)
        })?;
        let cf = mesh.he_face(g) as usize;
        if mesh.face_size(cf) != 4 {
            return Err(not_separated(
                format!("the corner face {cf} at vertex {a} of facet {f} is not a quad"),
                name,
            ));
        }
        let c = mesh.he_to(mesh.he_next(g)) as usize;
        let (b, d) = (net.b[s] as usize, net.d[s] as usize);
        for v in [b, c, d] {
            if !regular(mesh, v) {
                return Err(not_separated(
                    format!("vertex {v} next to facet {f} is not regular"),
                    name,
                ));
            }
        }
        local[ds_net_index(s, 0, 0)] = Stencil::point(a);
        local[ds_net_index(s, 1, 0)] = Stencil::point(b);
        local[ds_net_index(s, 1, 1)] = Stencil::point(c);
        local[ds_net_index(s, 0, 1)] = Stencil::point(d);
    }
    Ok(RingElement {
        element: Element::Face(f as u32),
        scheme: LocalScheme::pgs(n)?,
        local0: local,
        start: 0,
    })
}

/// The level-0 local q-net of extraordinary vertex `v` (its 1-ring; the second ring is not
/// read).
fn ternary_element(
    mesh: &PolyMesh,
    v: usize,
    rules: TernaryRules,
    name: &str,
) -> Result<RingElement> {
    let idx = mesh.cnet_indices(v, 1).ok_or_else(|| {
        not_separated(
            format!("vertex {v} is not surrounded by a ring of quads"),
            name,
        )
    })?;
    let n = (idx.len() - 1) / 2;
    let mut local = vec![Stencil::point(v); 1 + 6 * n];
    for s in 0..n {
        let (a, b) = (idx[1 + 2 * s] as usize, idx[2 + 2 * s] as usize);
        for x in [a, b] {
            if !regular(mesh, x) {
                return Err(not_separated(
                    format!("vertex {x} next to extraordinary vertex {v} is not regular"),
                    name,
                ));
            }
        }
        local[qnet_index(s, 1, 0)] = Stencil::point(a);
        local[qnet_index(s, 1, 1)] = Stencil::point(b);
    }
    Ok(RingElement {
        element: Element::Vertex(v as u32),
        scheme: LocalScheme::ternary(n, rules)?,
        local0: local,
        start: 0,
    })
}

/// The level-0 local polar net of pole `p` (its `a, b` rings; `c` is not read).
fn polar_element(mesh: &PolyMesh, p: usize, element: Element, name: &str) -> Result<RingElement> {
    let hs = mesh.outgoing_halfedges(p);
    let n = hs.len();
    let mut local = vec![Stencil::point(p); 1 + 3 * n];
    for (s, &h) in hs.iter().enumerate() {
        let a = mesh.he_to(h) as usize;
        let nb = mesh.vertex_neighbors(a);
        let ring: Vec<usize> = [hs[(s + 1) % n], hs[(s + n - 1) % n]]
            .iter()
            .map(|&g| mesh.he_to(g) as usize)
            .collect();
        let out: Vec<usize> = nb
            .iter()
            .map(|&x| x as usize)
            .filter(|&x| x != p && !ring.contains(&x))
            .collect();
        if mesh.is_boundary_vertex(a) || nb.len() != 4 || out.len() != 1 {
            return Err(not_separated(
                format!("vertex {a} next to pole {p} does not have valence 4 with one spoke"),
                name,
            ));
        }
        let b = out[0];
        if !regular(mesh, b) {
            return Err(not_separated(
                format!("vertex {b} on the second ring around pole {p} is not regular"),
                name,
            ));
        }
        local[1 + 3 * s] = Stencil::point(a);
        local[2 + 3 * s] = Stencil::point(b);
    }
    Ok(RingElement {
        element,
        scheme: LocalScheme::polar(n)?,
        local0: local,
        start: 0,
    })
}

/// Regular patches of every regular vertex (with knot widths when given), then rings and fills
/// of every element.
fn assemble(
    mesh: &PolyMesh,
    widths: Option<&Widths>,
    elements: &[RingElement],
    opts: ComplexOptions,
    mut progress: impl FnMut(usize),
) -> Result<PatchComplex> {
    let pos = mesh.positions();
    let mut out = PatchComplex::new();
    let to_patch = |c: &[Stencil], local: &[Stencil]| -> BezierPatch {
        let cps: Vec<Point> = c.iter().map(|s| compose(s, local).apply(pos)).collect();
        BezierPatch::new(2, 2, cps)
    };
    for v in 0..mesh.num_vertices() {
        let patch = match widths {
            Some(w) => crate::schemes::bi2::ternary::regular_patch(mesh, w, v),
            None => super::ds::regular_vertex_patch(mesh, v),
        };
        if let Some(c) = patch {
            let face = mesh.vertex_faces(v).first().copied().unwrap_or(0);
            let cps = c.iter().map(|s| s.apply(pos)).collect();
            out.push(BezierPatch::new(2, 2, cps), Provenance::Regular { face });
        }
    }
    let mut locals: Vec<Vec<Stencil>> = elements.iter().map(|e| e.local0.clone()).collect();
    for l in 1..=opts.rings {
        for (el, local) in elements.iter().zip(locals.iter_mut()) {
            let step = el.scheme.step(el.start + l - 1);
            *local = (0..step.num_rows())
                .map(|r| compose(&step.stencil(r), local))
                .collect();
            for (c, sector) in el.scheme.ring(el.start + l) {
                out.push(
                    to_patch(&c, local),
                    Provenance::Ring {
                        element: el.element,
                        ring: l as u32,
                        sector,
                    },
                );
            }
        }
        progress(l);
    }
    if opts.fill {
        for (el, local) in elements.iter().zip(&locals) {
            for (c, sector) in el.scheme.fill(el.start + opts.rings)? {
                out.push(
                    to_patch(&c, local),
                    Provenance::Cap {
                        element: el.element,
                        sector,
                    },
                );
            }
        }
    }
    Ok(out)
}

/// The PGS surface of any polygon mesh, through the Doo-Sabin machinery of [`super::ds`]
/// (regular bi-2 patches, `3 n` bi-2 patches per ring around every facet, extraordinary
/// vertices becoming facets after one step, the fill centred at the limit point (7)). With
/// `pgs.dscc_steps > 0` the net is first refined that many times by DS^CC (the paper's prism
/// experiment); the complex is then that of the pre-processed net.
///
/// # Errors
/// As [`super::ds::doo_sabin_complex`].
pub fn pgs_complex(
    mesh: &PolyMesh,
    opts: ComplexOptions,
    pgs: PgsOptions,
    progress: impl FnMut(usize),
) -> Result<PatchComplex> {
    let pre = Pgs::refine_levels_with(mesh, pgs.dscc_steps, pgs)?;
    let corner = |m: &PolyMesh, h: u32| Pgs::corner_stencil(m, h);
    let limit = |m: &PolyMesh, f: usize| Pgs::facet_limit_stencil(m, f);
    let rules = super::ds::DualRules {
        corner: &corner,
        facet_limit: &limit,
    };
    super::ds::dual_complex_with(&pre, opts, &rules, "pgs", progress)
}

/// The TPS surface ([`TernaryRules::TPS`]) or adjustable TPS surface
/// ([`TernaryRules::adjustable`]) of a quad net:
/// regular bi-2 patches, `2 n` patches per ring around every extraordinary vertex, the fill.
/// Extraordinary vertices too close to each other are separated by one or two whole-net steps
/// of the scheme first (exact: the steps carry the knot widths, and the regular patches of the
/// refined net are converted with them), reported in the notes.
///
/// # Errors
/// [`Error::Unsupported`] for non-quad faces and extraordinary boundary vertices, naming the
/// element and the way out.
pub fn tps_complex(
    mesh: &PolyMesh,
    opts: ComplexOptions,
    rules: TernaryRules,
    mut progress: impl FnMut(usize),
) -> Result<(PatchComplex, Vec<String>)> {
    let name = if rules == TernaryRules::TPS {
        "tps"
    } else {
        "tps-adjustable"
    };
    let mut m = mesh.clone();
    let mut w = uniform_widths(mesh);
    let mut notes = Vec::new();
    // Validate the net as the scheme would (quads, boundary rules).
    ternary_step(&m, &w, &rules, name)?;
    for start in 0..=2 {
        let evs: Vec<usize> = (0..m.num_vertices())
            .filter(|&v| !m.is_boundary_vertex(v) && m.valence(v) != 4)
            .collect();
        let built: Result<Vec<RingElement>> = evs
            .iter()
            .map(|&v| {
                let mut el = ternary_element(&m, v, rules, name)?;
                el.start = start;
                Ok(el)
            })
            .collect();
        match built {
            Ok(elements) => {
                let c = assemble(&m, Some(&w), &elements, opts, &mut progress)?;
                return Ok((c, notes));
            }
            Err(_) if start < 2 => {
                notes.push(format!(
                    "extraordinary vertices too close for rings on the given net: applied a \
                     whole-net {name} step first (exact: it refines the same surface); rings \
                     count from the refined net"
                ));
                let (r, nw) = ternary_step(&m, &w, &rules, name)?;
                m = r.mesh;
                w = nw;
            }
            Err(err) => return Err(err),
        }
    }
    unreachable!("the loop returns")
}

/// The PolBS surface of a polar net, or of a prism-like net whose caps become poles at their
/// centroids or at the given points ([`crate::schemes::bi2::polar::to_polar_layout`]): regular
/// bi-2 patches, `n` patches per ring around every pole, the polar cap. Elements that are not
/// poles (extraordinary vertices, facets that are not prism-like caps) get the rings of
/// `bi2-mixed` (TPS, PGS), reported in the notes.
///
/// # Errors
/// As [`mixed_complex`].
pub fn polar_complex(
    mesh: &PolyMesh,
    opts: ComplexOptions,
    poles: &[(usize, Point)],
    progress: impl FnMut(usize),
) -> Result<(PatchComplex, Vec<String>)> {
    let net = crate::schemes::bi2::polar::to_polar_layout(mesh, poles)?;
    let named: Vec<(u32, Element)> = net.poles.iter().map(|p| (p.vertex, p.element)).collect();
    let (els, notes) = mixed_elements(&net.mesh, "polar-bi2", &named)?;
    Ok((assemble(&net.mesh, None, &els, opts, progress)?, notes))
}

/// The elements of a mixed net with their local nets; poles named by `named` (else by their
/// vertex). Notes list the elements that are not poles (for `polar-bi2`).
fn mixed_elements(
    mesh: &PolyMesh,
    name: &str,
    named: &[(u32, Element)],
) -> Result<(Vec<RingElement>, Vec<String>)> {
    use crate::schemes::bi2::mixed::{Bi2Element, elements};
    for v in 0..mesh.num_vertices() {
        if mesh.is_boundary_vertex(v) && !regular(mesh, v) {
            return Err(Error::Unsupported(format!(
                "boundary vertex {v} is not regular (two quads, or one at a corner); {name} \
                 has no boundary rules for it (way out: pgs or doo-sabin)"
            )));
        }
    }
    let mut notes = Vec::new();
    let els = elements(mesh)
        .into_iter()
        .map(|e| match e {
            Bi2Element::Facet(f) => {
                if name == "polar-bi2" {
                    notes.push(format!(
                        "face {f} ({} sides) is not a prism-like cap: PGS rings there, as in \
                         bi2-mixed",
                        mesh.face_size(f as usize)
                    ));
                }
                pgs_element(mesh, f as usize, name)
            }
            Bi2Element::Vertex(v) => {
                if name == "polar-bi2" {
                    notes.push(format!(
                        "vertex {v} (valence {}) is not a pole: TPS rings there, as in bi2-mixed",
                        mesh.valence(v as usize)
                    ));
                }
                ternary_element(mesh, v as usize, TernaryRules::TPS, name)
            }
            Bi2Element::Pole(p) => {
                let element = named
                    .iter()
                    .find(|x| x.0 == p)
                    .map(|x| x.1)
                    .unwrap_or(Element::Vertex(p));
                polar_element(mesh, p as usize, element, name)
            }
        })
        .collect::<Result<_>>()?;
    Ok((els, notes))
}

/// The surface of a mixed bi-2 net (Fig. 15 of the paper): regular bi-2 patches, PGS rings
/// at facets, TPS rings at extraordinary vertices, polar rings at poles (see
/// [`crate::schemes::bi2::mixed`]).
///
/// # Errors
/// [`Error::Unsupported`] when elements are not separated (a vertex next to a hole is not
/// regular) or a facet has no DS-net, naming the element and the way out.
pub fn mixed_complex(
    mesh: &PolyMesh,
    opts: ComplexOptions,
    progress: impl FnMut(usize),
) -> Result<PatchComplex> {
    let (els, _) = mixed_elements(mesh, "bi2-mixed", &[])?;
    assemble(mesh, None, &els, opts, progress)
}

/// `n`-valent extraordinary element's ring `l` patches from explicit local-net points (the
/// characteristic ring when the points are the characteristic map's control points).
pub fn ring_patches(scheme: &LocalScheme, l: usize, points: &[Point]) -> Vec<BezierPatch> {
    scheme
        .ring(l)
        .into_iter()
        .map(|(c, _)| BezierPatch::new(2, 2, c.iter().map(|s| s.apply(points)).collect()))
        .collect()
}
