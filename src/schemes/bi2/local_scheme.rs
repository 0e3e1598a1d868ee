//! The local subdivision of one extraordinary element of the bi-2 family ([`LocalScheme`]):
//! the steps between levels of its local net (DS-net, q-net, polar net) and the ring patches
//! each level defines, every table read off the scheme's own whole-mesh refinement of its
//! canonical local net; and the layouts of the q-net.

use crate::error::{Error, Result};
use crate::mesh::PolyMesh;
use crate::mesh::nets::{self, CnetShape};
use crate::schemes::Scheme;
use crate::schemes::bi2::pgs::{FacetNet, PgsParams, ds_net, ds_net_chart, ds_net_index};
use crate::schemes::bi2::polar::{polar_net, radial_step_detailed};
use crate::schemes::bi2::ternary::{
    TernaryRules, TpsParams, Widths, edge_child_index, face_child_index, ternary_step,
    uniform_widths,
};
use crate::schemes::bi2::{Pgs, bi2_patch_stencils, blossom_weights};
use crate::schemes::options::ids;
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
        if n < 3 {
            return Err(Error::InvalidArgument(format!(
                "valence {n}: TPS's rule (18) and its q-net need a valence of at least 3"
            )));
        }
        let net = nets::cnet(n, CnetShape::Convex, 2);
        let rows = ternary_rows(&net, n);
        let size = 1 + 6 * n;
        let (r0, _) = ternary_step(&net, &uniform_widths(&net), &rules, ids::TPS.name())?;
        let r = rules.ring_ratio();
        let w = qnet_widths(&net, n, [1.0, r, r * r]);
        let (r1, _) = ternary_step(&net, &w, &rules, ids::TPS.name())?;
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
                let at = |i, j| (0..n).map(|k| ds_net_index(k, i, j) as u32).collect();
                let net = FacetNet {
                    a: at(0, 0),
                    b: at(1, 0),
                    d: at(0, 1),
                };
                // p from (1), then (1 - tau) p + tau a_mean.
                Ok(prm.limit_point(&prm.centre(&net), &net.a))
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
    /// [module](self) documentation), over the local net extended by one point: index
    /// [`LocalScheme::size`] stands for the element's [limit point](Self::limit). Every sector's
    /// patch has that point as its centre coefficient; naming it by one index, instead of
    /// repeating the limit stencil (which reads all `n` ring points) in each of the `n`
    /// patches, keeps the fill linear in the valence. Errors as [`Self::limit`].
    pub fn fill(&self, l: usize) -> Result<Vec<(Vec<Stencil>, u32)>> {
        let n = self.n;
        self.limit()?;
        let lim = Stencil::point(self.size);
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
