//! Geometric adjacency of the patches of a [`PatchComplex`]: which boundary pieces coincide.
//!
//! Patch complexes from subdivision carry no explicit connectivity between their patches, and
//! their patches need not meet edge to edge: a ring-`k` patch side meets two ring-`k+1` sides
//! that each cover half of it (a T-junction), and polar or cap patches have sides collapsed to a
//! point. Writers that share vertices, the watertight tessellator ([`super::tessellate`]) and
//! continuity checks need to know which pieces of which sides coincide, so this module finds
//! them from the geometry alone:
//!
//! 1. corner points are welded within the tolerance with a spatial hash ([`weld_points`]),
//!    giving vertex ids (linear time, fine for 10^5 patches);
//! 2. starting at each end of every non-collapsed side, a walk follows the sides incident to
//!    the current vertex whose far end lies on the side's curve, checking each candidate by
//!    exact polynomial coincidence: the candidate's coefficients must equal those of the
//!    matching sub-segment of the side (after degree raising) within the tolerance.
//!
//! A full match (side against side) and a T-junction piece (a whole side against a parameter
//! interval of a longer side, any ratio) come out of the same walk. Collapsed sides (all
//! coefficients within the tolerance of one point) take no part: they share a point, not a
//! curve. Partial overlaps where neither side contains the other (staggered sides) are not
//! reported; subdivision complexes do not produce them.

use super::PatchComplex;
use crate::bezier::{Side, curve};
use crate::geom::{Point, dist};
use rayon::prelude::*;
use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

/// Two boundary pieces that coincide: side parameter `t` of side `side_a` of patch `a`, for `t`
/// in `[t[0], t[1]]`, is the same point as side parameter `s` of side `side_b` of patch `b`,
/// with `s` the linear image of `t` (`t[0] -> s[0]`, `t[1] -> s[1]`).
///
/// Side parameters follow [`Side`]: `v` on `U0`/`U1`, `u` on `V0`/`V1`. Always `t[0] < t[1]`;
/// `s[0] > s[1]` when the two sides run in opposite directions (the usual case between two
/// consistently oriented patches). The `b` piece is always a whole side (`s` is `[0, 1]` or
/// `[1, 0]`); the `a` piece is a whole side too for an edge-to-edge match, or part of a longer
/// side at a T-junction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SharedBoundary {
    /// First patch (the longer side at a T-junction).
    pub a: usize,
    /// Side of `a`.
    pub side_a: Side,
    /// Parameter interval on `side_a`, increasing.
    pub t: [f64; 2],
    /// Second patch.
    pub b: usize,
    /// Side of `b`.
    pub side_b: Side,
    /// Parameter interval on `side_b` matching `t[0]`, `t[1]`.
    pub s: [f64; 2],
}

impl SharedBoundary {
    /// Whether the two sides run in opposite directions.
    pub fn is_reversed(&self) -> bool {
        self.s[1] < self.s[0]
    }

    /// Whether both pieces are whole sides (an edge-to-edge match, not a T-junction).
    pub fn is_full(&self) -> bool {
        self.t == [0.0, 1.0]
    }

    /// The parameter on `side_b` of the point at parameter `t` on `side_a`.
    pub fn map_to_b(&self, t: f64) -> f64 {
        self.s[0] + (t - self.t[0]) / (self.t[1] - self.t[0]) * (self.s[1] - self.s[0])
    }

    /// The parameter on `side_a` of the point at parameter `s` on `side_b`.
    pub fn map_to_a(&self, s: f64) -> f64 {
        self.t[0] + (s - self.s[0]) / (self.s[1] - self.s[0]) * (self.t[1] - self.t[0])
    }
}

/// A tolerance suited to exact patch complexes: `1e-9` times the diagonal of the bounding box
/// of all coefficients (`1e-12` for an empty or degenerate complex).
pub fn default_tolerance(c: &PatchComplex) -> f64 {
    let bb = crate::geom::bounding_box(c.patches.iter().flat_map(|p| p.cps.iter().copied()));
    match bb {
        Some((lo, hi)) if dist(lo, hi).is_finite() && dist(lo, hi) > 0.0 => 1e-9 * dist(lo, hi),
        _ => 1e-12,
    }
}

/// Disjoint-set forest with path halving.
pub(crate) struct UnionFind {
    parent: Vec<u32>,
}

impl UnionFind {
    pub(crate) fn new(n: usize) -> Self {
        UnionFind {
            parent: (0..n as u32).collect(),
        }
    }

    pub(crate) fn find(&mut self, mut x: u32) -> u32 {
        while self.parent[x as usize] != x {
            let g = self.parent[self.parent[x as usize] as usize];
            self.parent[x as usize] = g;
            x = g;
        }
        x
    }

    /// Joins the classes of `a` and `b`; the smaller root survives.
    pub(crate) fn union(&mut self, a: u32, b: u32) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            let (lo, hi) = if ra < rb { (ra, rb) } else { (rb, ra) };
            self.parent[hi as usize] = lo;
        }
    }
}

/// Welds points closer than `tol` (transitively): returns for every point the id of its
/// cluster, ids numbered `0..` in order of first appearance, and the number of clusters.
///
/// A spatial hash with cells of `64 tol` finds the neighbours of a point in one cell, or in up to
/// 8 near cell borders. A point within `tol / 64` of a point already kept is welded to it and
/// not kept itself (kept points are compared with `tol + tol / 64`, so no pair closer than
/// `tol` is missed), so many coincident points (identical patches, the corners of thousands of
/// sectors meeting at one centre) cost one comparison each: welding stays linear in the number
/// of points. `tol <= 0` welds only equal points.
pub fn weld_points(points: &[Point], tol: f64) -> (Vec<u32>, usize) {
    let n = points.len();
    let mut uf = UnionFind::new(n);
    let maxc = points
        .iter()
        .flat_map(|p| p.iter())
        .filter(|x| x.is_finite())
        .fold(0.0f64, |m, x| m.max(x.abs()));
    let tol = if tol.is_finite() { tol.max(0.0) } else { 0.0 };
    let absorb = tol / 64.0;
    let reach = tol + absorb;
    // Cells much larger than `tol`, so the box `p +- reach` usually lies in one cell (one
    // lookup per point), and never finer than the rounding level of the coordinates, so keys
    // cannot overflow.
    let cell = (64.0 * tol).max(maxc * 1e-14).max(f64::MIN_POSITIVE);
    let key = |x: f64| (x / cell).floor() as i64;
    let mut head: HashMap<[i64; 3], u32, BuildHasherDefault<CellHasher>> =
        HashMap::with_capacity_and_hasher(n, BuildHasherDefault::default());
    let mut next = vec![u32::MAX; n];
    for (i, p) in points.iter().enumerate() {
        let lo = [key(p[0] - reach), key(p[1] - reach), key(p[2] - reach)];
        let hi = [key(p[0] + reach), key(p[1] + reach), key(p[2] + reach)];
        let mut absorbed = false;
        for x in lo[0]..=hi[0] {
            for y in lo[1]..=hi[1] {
                for z in lo[2]..=hi[2] {
                    let mut j = head.get(&[x, y, z]).copied().unwrap_or(u32::MAX);
                    while j != u32::MAX {
                        let d = dist(*p, points[j as usize]);
                        if d <= reach || d <= tol {
                            uf.union(i as u32, j);
                            absorbed |= d <= absorb;
                        }
                        j = next[j as usize];
                    }
                }
            }
        }
        if !absorbed {
            let k = [key(p[0]), key(p[1]), key(p[2])];
            let e = head.entry(k).or_insert(u32::MAX);
            next[i] = *e;
            *e = i as u32;
        }
    }
    let mut id_of_root = vec![u32::MAX; n];
    let mut ids = Vec::with_capacity(n);
    let mut count = 0u32;
    for i in 0..n {
        let r = uf.find(i as u32) as usize;
        if id_of_root[r] == u32::MAX {
            id_of_root[r] = count;
            count += 1;
        }
        ids.push(id_of_root[r]);
    }
    (ids, count as usize)
}

/// A fast multiplicative hasher for integer cell keys (the default SipHash dominated welding).
#[derive(Default)]
struct CellHasher(u64);

impl Hasher for CellHasher {
    fn finish(&self) -> u64 {
        self.0
    }

    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(u64::from(b));
        }
    }

    fn write_u64(&mut self, x: u64) {
        self.0 = (self.0.rotate_left(5) ^ x).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }

    fn write_i64(&mut self, x: i64) {
        self.write_u64(x as u64);
    }
}

/// Parameters closer than this count as equal.
const PARAM_EPS: f64 = 1e-9;

/// Longest chain of pieces followed along one side.
const MAX_STEPS: usize = 256;

/// One side of one patch, as seen by the walk.
struct SideRec {
    /// Welded vertex ids of the ends at `t = 0` and `t = 1`.
    ends: [u32; 2],
    collapsed: bool,
    cps: Vec<Point>,
    lo: Point,
    hi: Point,
}

/// Corner index `0..4` (bit 0: `u = 1`, bit 1: `v = 1`) of the ends of a side.
fn side_corners(side: Side) -> [usize; 2] {
    match side {
        Side::U0 => [0, 2],
        Side::U1 => [1, 3],
        Side::V0 => [0, 1],
        Side::V1 => [2, 3],
    }
}

/// The four corner points of every patch, corner `c` of patch `p` at `4 p + c`.
pub(crate) fn corner_points(c: &PatchComplex) -> Vec<Point> {
    c.patches
        .iter()
        .flat_map(|p| {
            [
                p.corner(false, false),
                p.corner(true, false),
                p.corner(false, true),
                p.corner(true, true),
            ]
        })
        .collect()
}

/// All coinciding boundary pieces of the complex, within distance `tol` (see
/// [`SharedBoundary`]; [`default_tolerance`] suits exact complexes). An edge-to-edge match is
/// reported once (with `a < b`, or the lower side first within one patch); a T-junction gives
/// one record per piece of the longer side. The result is sorted by `(a, side_a, t[0])`.
pub fn shared_boundaries(c: &PatchComplex, tol: f64) -> Vec<SharedBoundary> {
    let corners = corner_points(c);
    let (vid, nverts) = weld_points(&corners, tol);
    let sides: Vec<SideRec> = c
        .patches
        .par_iter()
        .enumerate()
        .flat_map_iter(|(p, patch)| {
            let vid = &vid;
            Side::ALL.into_iter().map(move |side| {
                let cps = patch.boundary(side);
                let [c0, c1] = side_corners(side);
                let (lo, hi) =
                    crate::geom::bounding_box(cps.iter().copied()).unwrap_or(([0.0; 3], [0.0; 3]));
                SideRec {
                    ends: [vid[4 * p + c0], vid[4 * p + c1]],
                    collapsed: cps.iter().all(|q| dist(*q, cps[0]) <= tol),
                    cps,
                    lo,
                    hi,
                }
            })
        })
        .collect();
    // vertex -> incident non-collapsed sides (compressed rows)
    let mut start = vec![0u32; nverts + 1];
    for s in sides.iter().filter(|s| !s.collapsed) {
        start[s.ends[0] as usize + 1] += 1;
        if s.ends[1] != s.ends[0] {
            start[s.ends[1] as usize + 1] += 1;
        }
    }
    for v in 0..nverts {
        start[v + 1] += start[v];
    }
    let mut fill = start.clone();
    let mut incident = vec![0u32; start[nverts] as usize];
    for (k, s) in sides.iter().enumerate().filter(|(_, s)| !s.collapsed) {
        for (e, &v) in s.ends.iter().enumerate() {
            if e == 1 && v == s.ends[0] {
                break;
            }
            incident[fill[v as usize] as usize] = k as u32;
            fill[v as usize] += 1;
        }
    }
    // non-collapsed sides by their (unordered) pair of end vertices, for edge-to-edge lookups
    let mut by_ends: Vec<([u32; 2], u32)> = sides
        .iter()
        .enumerate()
        .filter(|(_, s)| !s.collapsed)
        .map(|(k, s)| (end_pair(s.ends[0], s.ends[1]), k as u32))
        .collect();
    by_ends.par_sort_unstable();
    let walker = Walker {
        sides: &sides,
        start: &start,
        incident: &incident,
        by_ends: &by_ends,
        tol,
    };
    let mut out: Vec<SharedBoundary> = (0..sides.len())
        .into_par_iter()
        .filter(|&k| !sides[k].collapsed)
        .flat_map_iter(|k| walker.walk(k))
        .collect();
    out.sort_by(|x, y| {
        (x.a, x.side_a)
            .cmp(&(y.a, y.side_a))
            .then(x.t[0].total_cmp(&y.t[0]))
    });
    out
}

/// The non-collapsed sides of the complex's patches that `shared` (its
/// [`shared_boundaries`] at `tol`) does not cover whole: the surface's open boundary, empty
/// for a closed surface. In patch and [`Side::ALL`] order.
pub fn open_sides(c: &PatchComplex, shared: &[SharedBoundary], tol: f64) -> Vec<(usize, Side)> {
    let mut covered: Vec<[f64; 4]> = vec![[0.0; 4]; c.len()];
    for sb in shared {
        covered[sb.a][sb.side_a.index()] += sb.t[1] - sb.t[0];
        covered[sb.b][sb.side_b.index()] += 1.0;
    }
    let mut out = Vec::new();
    for (i, p) in c.patches.iter().enumerate() {
        for side in Side::ALL {
            if covered[i][side.index()] < 1.0 - 1e-9 && !p.is_collapsed(side, tol) {
                out.push((i, side));
            }
        }
    }
    out
}

/// How many of the `shared` pieces join two patches whose orientations (`du x dv`) disagree:
/// along a shared piece, consistently oriented patches run their boundaries (counter-clockwise
/// in their own domains) in opposite directions. 0 on an orientable complex built
/// consistently; a closed surface's enclosed volume needs it.
pub fn orientation_conflicts(shared: &[SharedBoundary]) -> usize {
    // +1 where the counter-clockwise boundary runs with the side's parameter
    let ccw = |s: Side| match s {
        Side::V0 | Side::U1 => 1.0,
        Side::U0 | Side::V1 => -1.0,
    };
    shared
        .iter()
        .filter(|sb| {
            let dir_b = if sb.is_reversed() { -1.0 } else { 1.0 };
            ccw(sb.side_a) == ccw(sb.side_b) * dir_b
        })
        .count()
}

/// A found piece: side `y` covers `[tc, tf]` of the walked side, with `y`'s parameter `sc` at
/// `tc` and `sf` at `tf`; the walk continues at vertex `far`.
struct Piece {
    y: usize,
    tc: f64,
    tf: f64,
    sc: f64,
    sf: f64,
    far: u32,
}

struct Walker<'a> {
    sides: &'a [SideRec],
    start: &'a [u32],
    incident: &'a [u32],
    /// Non-collapsed sides sorted by [`end_pair`] of their ends.
    by_ends: &'a [([u32; 2], u32)],
    tol: f64,
}

/// The unordered pair of vertices `a`, `b` as a sort key.
fn end_pair(a: u32, b: u32) -> [u32; 2] {
    [a.min(b), a.max(b)]
}

/// The orientations in which side `y` leaves vertex `v`: `(s at v, s at the far end, far
/// vertex)` (two for a closed side whose ends are both `v`).
fn orientations(y: &SideRec, v: u32) -> impl Iterator<Item = (f64, f64, u32)> {
    let a = (y.ends[0] == v).then_some((0.0, 1.0, y.ends[1]));
    let b = (y.ends[1] == v).then_some((1.0, 0.0, y.ends[0]));
    a.into_iter().chain(b)
}

impl Walker<'_> {
    fn side_of(k: usize) -> (usize, Side) {
        (k / 4, Side::ALL[k % 4])
    }

    /// The pieces covering side `k`, walked from both ends.
    fn walk(&self, k: usize) -> Vec<SharedBoundary> {
        let mut pieces = Vec::new();
        // forward from t = 0
        let (mut v, mut t) = (self.sides[k].ends[0], 0.0);
        for _ in 0..MAX_STEPS {
            if t >= 1.0 - PARAM_EPS {
                break;
            }
            match self.step(k, v, t, true) {
                Some(p) => {
                    (v, t) = (p.far, p.tf);
                    pieces.push(p);
                }
                None => break,
            }
        }
        let reached = t;
        // backward from t = 1 over what the forward walk did not cover
        let (mut v, mut t) = (self.sides[k].ends[1], 1.0);
        for _ in 0..MAX_STEPS {
            if t <= reached + PARAM_EPS {
                break;
            }
            match self.step(k, v, t, false) {
                Some(p) => {
                    (v, t) = (p.far, p.tf);
                    pieces.push(p);
                }
                None => break,
            }
        }
        let (a, side_a) = Self::side_of(k);
        pieces
            .into_iter()
            .filter_map(|p| {
                let (t, s) = if p.tc < p.tf {
                    ([p.tc, p.tf], [p.sc, p.sf])
                } else {
                    ([p.tf, p.tc], [p.sf, p.sc])
                };
                let (b, side_b) = Self::side_of(p.y);
                // an edge-to-edge match is found from both sides: keep one
                if t == [0.0, 1.0] && p.y < k {
                    return None;
                }
                Some(SharedBoundary {
                    a,
                    side_a,
                    t,
                    b,
                    side_b,
                    s,
                })
            })
            .collect()
    }

    /// From vertex `v` at parameter `t` of side `k`, the next side covering a piece of `k` in
    /// the direction of increasing (`forward`) or decreasing `t`.
    fn step(&self, k: usize, v: u32, t: f64, forward: bool) -> Option<Piece> {
        let x = &self.sides[k];
        let goal_t = if forward { 1.0 } else { 0.0 };
        let goal_v = x.ends[if forward { 1 } else { 0 }];
        let cands =
            &self.incident[self.start[v as usize] as usize..self.start[v as usize + 1] as usize];
        // first pass: sides ending where side k ends (edge-to-edge or the last piece), looked
        // up by their pair of ends, so a vertex shared by thousands of sides costs no scan
        let pair = end_pair(v, goal_v);
        let lo = self.by_ends.partition_point(|(p, _)| *p < pair);
        for &(p, yk) in &self.by_ends[lo..] {
            if p != pair {
                break;
            }
            let yk = yk as usize;
            if yk == k {
                continue;
            }
            let y = &self.sides[yk];
            for (sc, sf, far) in orientations(y, v) {
                if far == goal_v && self.coincide(x, t, goal_t, y, sc, sf) {
                    return Some(Piece {
                        y: yk,
                        tc: t,
                        tf: goal_t,
                        sc,
                        sf,
                        far,
                    });
                }
            }
        }
        // second pass: sides ending inside side k (T-junction pieces)
        for &yk in cands {
            let yk = yk as usize;
            if yk == k {
                continue;
            }
            let y = &self.sides[yk];
            for (sc, sf, far) in orientations(y, v) {
                if far == goal_v {
                    continue;
                }
                let q = if sf == 1.0 {
                    y.cps[y.cps.len() - 1]
                } else {
                    y.cps[0]
                };
                let inside =
                    (0..3).all(|c| q[c] >= x.lo[c] - self.tol && q[c] <= x.hi[c] + self.tol);
                if !inside {
                    continue;
                }
                let (tf, d) = curve::closest_param(&x.cps, q);
                let ahead = if forward {
                    tf > t + PARAM_EPS
                } else {
                    tf < t - PARAM_EPS
                };
                if d <= self.tol && ahead && self.coincide(x, t, tf, y, sc, sf) {
                    return Some(Piece {
                        y: yk,
                        tc: t,
                        tf,
                        sc,
                        sf,
                        far,
                    });
                }
            }
        }
        None
    }

    /// Whether side `y` run from `sc` to `sf` is the sub-segment `[t0, t1]` of side `x`.
    fn coincide(&self, x: &SideRec, t0: f64, t1: f64, y: &SideRec, sc: f64, sf: f64) -> bool {
        let sub = curve::subsegment(&x.cps, t0, t1);
        let d = if sc < sf {
            curve::coefficient_distance(&sub, &y.cps)
        } else {
            let rev: Vec<Point> = y.cps.iter().rev().copied().collect();
            curve::coefficient_distance(&sub, &rev)
        };
        d <= self.tol
    }
}

#[cfg(feature = "unit-tests")]
mod tests;
