//! B-rep topology of a set of CAD faces, found from their geometry.
//!
//! 1. The faces' corner points are welded within the tolerance into vertices
//!    ([`crate::surface::adjacency::weld_points`]).
//! 2. Every vertex that lies inside a face side (within the tolerance, by closest point on the
//!    side's Bezier pieces) splits that side there: the T-points where a side meets two shorter
//!    sides of finer faces.
//! 3. The pieces of sides between consecutive vertices are paired by their end vertices and a
//!    check that they coincide (the middle of one lies on the other): each pair is one edge,
//!    its curve the piece of the first face's side, used by both faces with opposite senses. A
//!    piece without a partner is a free edge (the net's boundary); a collapsed side (all its
//!    coefficients at one point: a pole, the tip of a triangle) is no edge at all (CAD readers
//!    add their degenerate edges themselves).
//! 4. Each face's loop runs counter-clockwise in its parameters: side `v = 0`, `u = 1`, `v = 1`,
//!    `u = 0`, so the face normal `S_u x S_v` is the loop's left-hand normal.
//! 5. Faces connected through shared edges form a shell; a shell all of whose edges are shared
//!    is closed. When a closed shell encloses a negative volume (its part of the net is
//!    oriented inward), its surfaces are transposed (`u` and `v` swapped) and the topology
//!    built again, so that CAD sees outward solids.

use super::spline::{SplineCurve, SplineSurface};
use crate::bezier::Side;
use crate::geom::{Point, cross, dist, dot};
use crate::surface::adjacency::weld_points;
use rayon::prelude::*;
use std::collections::HashMap;

/// An edge: its two vertices and its curve (from the first vertex to the second).
#[derive(Debug, Clone)]
pub struct Edge {
    /// Start and end vertex.
    pub ends: [u32; 2],
    /// The curve, starting at `ends[0]`.
    pub curve: SplineCurve,
}

/// The topology of a set of faces (see the [module](self) doc).
#[derive(Debug, Clone, Default)]
pub struct Brep {
    /// Vertex positions.
    pub vertices: Vec<Point>,
    /// Edges.
    pub edges: Vec<Edge>,
    /// Each face's outer loop: `(edge, same sense)` in order.
    pub loops: Vec<Vec<(u32, bool)>>,
    /// Edges used by one face only (the net's boundary).
    pub free_edges: usize,
    /// Side pieces that found more than one partner (non-manifold configurations).
    pub nonmanifold: usize,
    /// Edges whose two faces run them the same way (inconsistent orientation).
    pub misoriented: usize,
    /// The connected component (shell) of every face, numbered from 0 in order of first face.
    pub shell_of: Vec<u32>,
    /// Whether each shell is closed (every edge of its faces shared by two of them).
    pub closed: Vec<bool>,
    /// Faces whose surfaces were transposed to make their closed shell enclose a positive
    /// volume.
    pub flipped: usize,
}

impl Brep {
    /// Whether every edge is shared by two faces (every shell closed).
    pub fn is_closed(&self) -> bool {
        self.free_edges == 0 && self.nonmanifold == 0 && !self.edges.is_empty()
    }

    /// Number of shells (connected components of faces).
    pub fn shells(&self) -> usize {
        self.closed.len()
    }

    /// The faces of every shell, in face order.
    pub fn shell_faces(&self) -> Vec<Vec<usize>> {
        let mut out = vec![Vec::new(); self.closed.len()];
        for (f, &s) in self.shell_of.iter().enumerate() {
            out[s as usize].push(f);
        }
        out
    }

    /// The shells (connected through shared edges) and whether each is closed.
    fn find_shells(&mut self) {
        let n = self.loops.len();
        let mut uf = crate::surface::adjacency::UnionFind::new(n);
        let mut first_face = vec![u32::MAX; self.edges.len()];
        let mut uses = vec![0u8; self.edges.len()];
        for (f, lp) in self.loops.iter().enumerate() {
            for &(e, _) in lp {
                let e = e as usize;
                uses[e] = uses[e].saturating_add(1);
                if first_face[e] == u32::MAX {
                    first_face[e] = f as u32;
                } else {
                    uf.union(first_face[e], f as u32);
                }
            }
        }
        let mut id = vec![u32::MAX; n];
        self.shell_of = Vec::with_capacity(n);
        self.closed.clear();
        for f in 0..n {
            let r = uf.find(f as u32) as usize;
            if id[r] == u32::MAX {
                id[r] = self.closed.len() as u32;
                self.closed.push(true);
            }
            self.shell_of.push(id[r]);
        }
        for (f, lp) in self.loops.iter().enumerate() {
            if lp.iter().any(|&(e, _)| uses[e as usize] < 2) || lp.is_empty() {
                self.closed[self.shell_of[f] as usize] = false;
            }
        }
    }
}

/// The sides of a face in loop order, with whether the loop runs them in increasing parameter.
const LOOP: [(Side, bool); 4] = [
    (Side::V0, true),
    (Side::U1, true),
    (Side::V1, false),
    (Side::U0, false),
];

/// A piece of a face side between two vertices.
#[derive(Debug, Clone, Copy)]
struct Segment {
    face: u32,
    /// Position of the side in [`LOOP`].
    side: u8,
    t: [f64; 2],
    v: [u32; 2],
}

/// Builds the topology of `surfaces` with welding tolerance `tol`; transposes the surfaces
/// of a closed shell that comes out inward (see the [module](self) doc).
pub fn build(surfaces: &mut [SplineSurface], tol: f64) -> Brep {
    let b = topology(surfaces, tol);
    let mut flip = vec![false; surfaces.len()];
    let mut flipped = 0;
    for (s, faces) in b.shell_faces().iter().enumerate() {
        if !b.closed[s] {
            continue;
        }
        let own: Vec<SplineSurface> = faces.iter().map(|&f| surfaces[f].clone()).collect();
        if signed_volume(&own) < 0.0 {
            for &f in faces {
                flip[f] = true;
                flipped += 1;
            }
        }
    }
    if flipped == 0 {
        return b;
    }
    surfaces
        .par_iter_mut()
        .zip(flip.par_iter())
        .filter(|(_, f)| **f)
        .for_each(|(s, _)| *s = s.transposed());
    let mut b = topology(surfaces, tol);
    b.flipped = flipped;
    b
}

/// The enclosed volume of closed faces (signed: positive for outward normals), by the
/// divergence theorem with Gauss-Legendre rules exact for the integrand's degree.
pub fn signed_volume(surfaces: &[SplineSurface]) -> f64 {
    surfaces
        .par_iter()
        .map(|s| {
            let mut v = 0.0;
            for (_, b) in s.bezier_pieces() {
                let gu = crate::bezier::bern::gauss_legendre((3 * b.deg_u).div_ceil(2) + 1);
                let gv = crate::bezier::bern::gauss_legendre((3 * b.deg_v).div_ceil(2) + 1);
                for &(x, wx) in &gu {
                    for &(y, wy) in &gv {
                        let d = b.derivatives(x, y);
                        v += wx * wy * dot(d.p, cross(d.du, d.dv)) / 3.0;
                    }
                }
            }
            v
        })
        .sum()
}

/// The four sides of every face in [`LOOP`] order, and whether each is collapsed.
fn sides(surfaces: &[SplineSurface], tol: f64) -> Vec<(SplineCurve, bool)> {
    surfaces
        .par_iter()
        .flat_map_iter(|s| {
            LOOP.iter().map(move |&(side, _)| {
                let c = s.side(side);
                let collapsed = c.cps.iter().all(|p| dist(*p, c.cps[0]) <= tol);
                (c, collapsed)
            })
        })
        .collect()
}

fn topology(surfaces: &[SplineSurface], tol: f64) -> Brep {
    let sides = sides(surfaces, tol);
    // corners: the start of each side in loop order is the corner the loop reaches it at
    let ends: Vec<Point> = sides
        .iter()
        .flat_map(|(c, _)| [c.cps[0], c.cps[c.cps.len() - 1]])
        .collect();
    let (vid, nverts) = weld_points(&ends, tol);
    let mut vertices = vec![[0.0; 3]; nverts];
    for (k, &v) in vid.iter().enumerate().rev() {
        vertices[v as usize] = ends[k];
    }
    let splits = t_points(&sides, &vid, &vertices, tol);
    // segments of every side, in increasing parameter
    let mut segments: Vec<Segment> = Vec::new();
    let mut side_segments: Vec<std::ops::Range<usize>> = Vec::with_capacity(sides.len());
    for (k, (c, collapsed)) in sides.iter().enumerate() {
        let first = segments.len();
        if !collapsed {
            let [t0, t1] = c.range();
            let mut cuts: Vec<(f64, u32)> = vec![(t0, vid[2 * k])];
            cuts.extend(splits[k].iter().copied());
            cuts.push((t1, vid[2 * k + 1]));
            for w in cuts.windows(2) {
                segments.push(Segment {
                    face: (k / 4) as u32,
                    side: (k % 4) as u8,
                    t: [w[0].0, w[1].0],
                    v: [w[0].1, w[1].1],
                });
            }
        }
        side_segments.push(first..segments.len());
    }
    let (partner, nonmanifold) = pair(&segments, &sides, tol);
    let mut brep = Brep {
        vertices,
        nonmanifold,
        ..Brep::default()
    };
    let mut edge_of = vec![u32::MAX; segments.len()];
    for (i, s) in segments.iter().enumerate() {
        if edge_of[i] != u32::MAX {
            continue;
        }
        let curve = sides[s.face as usize * 4 + s.side as usize]
            .0
            .restricted(s.t[0], s.t[1]);
        let e = brep.edges.len() as u32;
        brep.edges.push(Edge { ends: s.v, curve });
        edge_of[i] = e;
        match partner[i] {
            Some(j) => {
                edge_of[j] = e;
            }
            None => brep.free_edges += 1,
        }
    }
    // the loops, and the sense of each use
    let mut direction: Vec<u8> = vec![0; brep.edges.len()];
    for f in 0..surfaces.len() {
        let mut lp = Vec::new();
        for (k, &(_, increasing)) in LOOP.iter().enumerate() {
            let range = side_segments[f * 4 + k].clone();
            let segs: Vec<usize> = if increasing {
                range.collect()
            } else {
                range.rev().collect()
            };
            for i in segs {
                let e = edge_of[i];
                let s = &segments[i];
                let edge = &brep.edges[e as usize];
                // the segment's own increasing direction against the edge's
                let along = if edge.ends[0] != edge.ends[1] {
                    s.v[0] == edge.ends[0]
                } else {
                    same_direction(&edge.curve, &sides[f * 4 + k].0, s.t)
                };
                let sense = along == increasing;
                direction[e as usize] += if sense { 1 } else { 4 };
                lp.push((e, sense));
            }
        }
        brep.loops.push(lp);
    }
    brep.misoriented = direction.iter().filter(|&&d| d == 2 || d == 8).count();
    brep.find_shells();
    brep
}

/// Whether the side piece `side` on `t` runs the same way as `edge` (for an edge whose ends
/// are one vertex): compares the points at a quarter of each.
fn same_direction(edge: &SplineCurve, side: &SplineCurve, t: [f64; 2]) -> bool {
    let [e0, e1] = edge.range();
    let q = edge.eval(e0 + 0.25 * (e1 - e0));
    let a = side.eval(t[0] + 0.25 * (t[1] - t[0]));
    let b = side.eval(t[0] + 0.75 * (t[1] - t[0]));
    dist(q, a) <= dist(q, b)
}

/// For every side, the vertices inside it (not at its ends) within `tol`, by increasing
/// parameter.
fn t_points(
    sides: &[(SplineCurve, bool)],
    vid: &[u32],
    vertices: &[Point],
    tol: f64,
) -> Vec<Vec<(f64, u32)>> {
    // a uniform grid of the vertices, cells about the size of an average side
    let boxes: Vec<(Point, Point)> = sides
        .iter()
        .map(|(c, _)| {
            crate::geom::bounding_box(c.cps.iter().copied()).unwrap_or(([0.0; 3], [0.0; 3]))
        })
        .collect();
    let mean = boxes.iter().map(|(lo, hi)| dist(*lo, *hi)).sum::<f64>() / boxes.len().max(1) as f64;
    let cell = mean.max(tol * 64.0).max(f64::MIN_POSITIVE);
    let key = |x: f64| (x / cell).floor() as i64;
    let mut grid: HashMap<[i64; 3], Vec<u32>> = HashMap::new();
    for (v, p) in vertices.iter().enumerate() {
        grid.entry([key(p[0]), key(p[1]), key(p[2])])
            .or_default()
            .push(v as u32);
    }
    sides
        .par_iter()
        .enumerate()
        .map(|(k, (c, collapsed))| {
            if *collapsed {
                return Vec::new();
            }
            let (lo, hi) = boxes[k];
            let [t0, t1] = c.range();
            let eps = 1e-9 * (t1 - t0);
            let mut found: Vec<(f64, u32)> = Vec::new();
            let (klo, khi) = (lo.map(|x| key(x - tol)), hi.map(|x| key(x + tol)));
            let cells = (khi[0] - klo[0] + 1) * (khi[1] - klo[1] + 1) * (khi[2] - klo[2] + 1);
            let mut candidates: Vec<u32> = Vec::new();
            if cells > 4096 {
                candidates.extend(0..vertices.len() as u32);
            } else {
                for x in klo[0]..=khi[0] {
                    for y in klo[1]..=khi[1] {
                        for z in klo[2]..=khi[2] {
                            if let Some(vs) = grid.get(&[x, y, z]) {
                                candidates.extend_from_slice(vs);
                            }
                        }
                    }
                }
            }
            let pieces = c.bezier_pieces();
            for v in candidates {
                if v == vid[2 * k] || v == vid[2 * k + 1] {
                    continue;
                }
                let q = vertices[v as usize];
                if (0..3).any(|i| q[i] < lo[i] - tol || q[i] > hi[i] + tol) {
                    continue;
                }
                for ([a, b], cps) in &pieces {
                    let (t, d) = crate::bezier::curve::closest_param(cps, q);
                    let t = a + t * (b - a);
                    if d <= tol && t > t0 + eps && t < t1 - eps {
                        found.push((t, v));
                        break;
                    }
                }
            }
            found.sort_by(|a, b| a.0.total_cmp(&b.0));
            found.dedup_by(|a, b| a.1 == b.1);
            found
        })
        .collect()
}

/// Pairs segments with the same end vertices that coincide: the partner of each segment, and
/// the number of segments with more than one candidate left over.
fn pair(
    segments: &[Segment],
    sides: &[(SplineCurve, bool)],
    tol: f64,
) -> (Vec<Option<usize>>, usize) {
    let mut by_ends: HashMap<[u32; 2], Vec<usize>> = HashMap::new();
    for (i, s) in segments.iter().enumerate() {
        let key = [s.v[0].min(s.v[1]), s.v[0].max(s.v[1])];
        by_ends.entry(key).or_default().push(i);
    }
    let mut partner = vec![None; segments.len()];
    let mut nonmanifold = 0;
    let curve = |i: usize| &sides[segments[i].face as usize * 4 + segments[i].side as usize].0;
    for group in by_ends.values() {
        for (x, &i) in group.iter().enumerate() {
            if partner[i].is_some() {
                continue;
            }
            let s = &segments[i];
            let mid = curve(i).eval(0.5 * (s.t[0] + s.t[1]));
            for &j in &group[x + 1..] {
                if partner[j].is_some() {
                    continue;
                }
                let sj = &segments[j];
                let cj = curve(j).restricted(sj.t[0], sj.t[1]);
                if cj.closest(mid).1 <= 10.0 * tol {
                    partner[i] = Some(j);
                    partner[j] = Some(i);
                    break;
                }
            }
        }
        let open = group.iter().filter(|&&i| partner[i].is_none()).count();
        if open > 1 {
            nonmanifold += open;
        }
    }
    (partner, nonmanifold)
}
