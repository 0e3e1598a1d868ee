//! Watertight triangulation of a [`PatchComplex`].
//!
//! Sampling each patch on its own grid leaves cracks wherever patches do not meet vertex to
//! vertex: at T-junctions between subdivision rings the coarse side's samples miss the fine
//! sides' samples, and independently evaluated copies of one boundary point differ by rounding.
//! [`tessellate`] avoids both:
//!
//! - every patch is sampled on an `(n + 1) x (n + 1)` grid of domain points `(i/n, j/n)`;
//! - from [`shared_boundaries`] every side also receives the samples of the pieces it meets
//!   (a coarse side at a T-junction gets all samples of the finer sides), so both sides of
//!   every shared boundary carry the same points; the boundary quads of the grid that get
//!   extra points are fanned;
//! - boundary samples are identified through the shared-boundary parameter maps, within each
//!   patch at its corners, along collapsed sides, and by welding corner positions within the
//!   tolerance (for patches touching only at a corner), so each surface point on a shared
//!   boundary is one vertex;
//! - triangles run counter-clockwise in the `(u, v)` domain, so they face along the patch
//!   normal `du x dv`.
//!
//! The result is a closed, consistently oriented triangle mesh for a closed, consistently
//! oriented complex.

use super::PatchComplex;
use super::adjacency::{
    SharedBoundary, UnionFind, default_tolerance, shared_boundaries, weld_points,
};
use crate::bezier::Side;
use crate::geom::{Point, add, norm, scale};
use rayon::prelude::*;

/// A triangle mesh sampled from a patch complex.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Tessellation {
    /// Vertex positions.
    pub positions: Vec<Point>,
    /// Unit vertex normals: the patch normal (see [`crate::bezier::BezierPatch::normal`]); for
    /// a vertex shared by several patches the normalised mean of their normals there.
    pub normals: Vec<Point>,
    /// Domain point `(u, v)` of each vertex in patch [`Tessellation::patch_of_vertex`].
    pub uv: Vec<[f64; 2]>,
    /// The patch whose domain `uv` refers to (for a shared vertex: one of its patches).
    pub patch_of_vertex: Vec<u32>,
    /// Triangles, counter-clockwise seen from the side the patch normal points to.
    pub triangles: Vec<[u32; 3]>,
    /// The patch each triangle lies in.
    pub triangle_patch: Vec<u32>,
}

impl Tessellation {
    /// Number of vertices.
    pub fn num_vertices(&self) -> usize {
        self.positions.len()
    }

    /// Number of triangles.
    pub fn num_triangles(&self) -> usize {
        self.triangles.len()
    }

    /// The triangles as flat polygon arrays `(positions, face_start, corners)` for mesh writers
    /// and [`crate::mesh::PolyMesh::from_flat`]: face `f` has corners
    /// `corners[face_start[f]..face_start[f + 1]]`.
    pub fn to_polygons(&self) -> (Vec<Point>, Vec<u32>, Vec<u32>) {
        let face_start = (0..=self.triangles.len() as u32).map(|f| 3 * f).collect();
        let corners = self.triangles.iter().flatten().copied().collect();
        (self.positions.clone(), face_start, corners)
    }
}

/// Triangulates the complex with `n` intervals per patch edge (`n + 1` samples; `n = 0` counts
/// as 1), sharing vertices along shared boundaries within [`default_tolerance`]. See the module
/// notes.
pub fn tessellate(c: &PatchComplex, n: usize) -> Tessellation {
    tessellate_with_tolerance(c, n, default_tolerance(c))
}

/// Parameters closer than this are the same sample.
const PARAM_EPS: f64 = 1e-9;

/// Sample parameters of one side: sorted, with the grid samples `k/n` at `own[k]`.
struct SideSamples {
    params: Vec<f64>,
    own: Vec<usize>,
}

/// Merges the grid samples `k/n` with extra parameters (dropping those within
/// [`PARAM_EPS`] of a kept one, or outside `(0, 1)`).
fn merge_samples(n: usize, mut extra: Vec<f64>) -> SideSamples {
    extra.retain(|&t| t > PARAM_EPS && t < 1.0 - PARAM_EPS);
    extra.sort_by(f64::total_cmp);
    let nf = n as f64;
    let mut params = Vec::with_capacity(n + 1 + extra.len());
    let mut own = Vec::with_capacity(n + 1);
    let mut e = extra.into_iter().peekable();
    for k in 0..=n {
        let g = k as f64 / nf;
        while let Some(&t) = e.peek() {
            if t >= g - PARAM_EPS {
                break;
            }
            e.next();
            if params.last().is_none_or(|&l: &f64| t - l > PARAM_EPS) {
                params.push(t);
            }
        }
        own.push(params.len());
        params.push(g);
        // drop extras equal to this grid sample
        while e.peek().is_some_and(|&t| t <= g + PARAM_EPS) {
            e.next();
        }
    }
    SideSamples { params, own }
}

/// Whether all coefficients lie within `tol` of one line: the patch is a curve or a point and
/// covers no area.
fn is_degenerate(p: &crate::bezier::BezierPatch, tol: f64) -> bool {
    use crate::geom::{dist, dot, sub};
    let Some(&p0) = p.cps.first() else {
        return true;
    };
    let far = p
        .cps
        .iter()
        .copied()
        .max_by(|a, b| dist(*a, p0).total_cmp(&dist(*b, p0)))
        .unwrap_or(p0);
    let l = dist(far, p0);
    if l <= tol || l.is_nan() {
        return true;
    }
    let e = scale(sub(far, p0), 1.0 / l);
    p.cps.iter().all(|&q| {
        let r = sub(q, p0);
        let along = dot(r, e);
        norm(sub(r, scale(e, along))) <= tol
    })
}

/// [`tessellate`] with an explicit tolerance for shared boundaries and vertex welding.
///
/// Patches collapsed to a curve or a point (all coefficients within `tol` of a line) cover no
/// area and are skipped.
pub fn tessellate_with_tolerance(c: &PatchComplex, n: usize, tol: f64) -> Tessellation {
    let keep: Vec<usize> = (0..c.len())
        .filter(|&p| !is_degenerate(&c.patches[p], tol))
        .collect();
    if keep.len() == c.len() {
        return tessellate_all(c, n, tol);
    }
    let sub = PatchComplex {
        patches: keep.iter().map(|&p| c.patches[p].clone()).collect(),
        provenance: keep.iter().map(|&p| c.provenance[p]).collect(),
        ..PatchComplex::default()
    };
    let mut t = tessellate_all(&sub, n, tol);
    for p in t
        .patch_of_vertex
        .iter_mut()
        .chain(t.triangle_patch.iter_mut())
    {
        *p = keep[*p as usize] as u32;
    }
    t
}

/// [`tessellate_with_tolerance`] on a complex without degenerate patches.
fn tessellate_all(c: &PatchComplex, n: usize, tol: f64) -> Tessellation {
    let n = n.max(1);
    let shared = shared_boundaries(c, tol);
    let grid: Vec<f64> = (0..=n).map(|k| k as f64 / n as f64).collect();
    let slots = Slots::new(side_samples(c.len(), n, &grid, &shared));
    let slot_eval = evaluate_slots(c, &slots);
    let mut uf = identify_slots(c, &slots, &shared, &slot_eval, tol);
    let mut t = Tessellation::default();
    let vertex_of_slot = boundary_vertices(c, &slots, &mut uf, &slot_eval, &mut t);
    let interior_base = interior_vertices(c, &grid, &mut t);
    for p in 0..c.len() {
        triangulate_patch(c, p, &grid, &slots, &vertex_of_slot, interior_base, &mut t);
    }
    t
}

/// The sample parameters of every side (index `4 p + side`): the grid samples and those the
/// shared boundaries bring from the other side.
fn side_samples(np: usize, n: usize, grid: &[f64], shared: &[SharedBoundary]) -> Vec<SideSamples> {
    let mut extra: Vec<Vec<f64>> = vec![Vec::new(); 4 * np];
    for r in shared {
        let (slo, shi) = (r.s[0].min(r.s[1]), r.s[0].max(r.s[1]));
        let ka = 4 * r.a + r.side_a.index();
        let kb = 4 * r.b + r.side_b.index();
        for &g in grid {
            if g >= slo - PARAM_EPS && g <= shi + PARAM_EPS {
                extra[ka].push(r.map_to_a(g));
            }
            if g >= r.t[0] - PARAM_EPS && g <= r.t[1] + PARAM_EPS {
                extra[kb].push(r.map_to_b(g));
            }
        }
    }
    extra.into_iter().map(|e| merge_samples(n, e)).collect()
}

/// The boundary samples of all sides numbered one after another (side by side, in side
/// index order): slot `slot(p, side, k)` is sample `k` of `side` of patch `p`.
struct Slots {
    samples: Vec<SideSamples>,
    base: Vec<usize>,
}

impl Slots {
    /// Numbers the samples of every side.
    fn new(samples: Vec<SideSamples>) -> Slots {
        let mut base = Vec::with_capacity(samples.len() + 1);
        base.push(0usize);
        for s in &samples {
            base.push(base.last().copied().unwrap_or(0) + s.params.len());
        }
        Slots { samples, base }
    }

    /// Number of slots.
    fn len(&self) -> usize {
        self.base[self.samples.len()]
    }

    /// The samples of `side` of patch `p`.
    fn side(&self, p: usize, side: Side) -> &SideSamples {
        &self.samples[4 * p + side.index()]
    }

    /// The slot of sample `k` of `side` of patch `p`.
    fn slot(&self, p: usize, side: Side, k: usize) -> u32 {
        (self.base[4 * p + side.index()] + k) as u32
    }

    /// The index of the last sample of `side` of patch `p`.
    fn last(&self, p: usize, side: Side) -> usize {
        self.side(p, side).params.len() - 1
    }
}

/// Position and normal at every boundary slot, in slot order.
fn evaluate_slots(c: &PatchComplex, slots: &Slots) -> Vec<(Point, Point)> {
    (0..c.len())
        .into_par_iter()
        .flat_map_iter(|p| {
            let patch = &c.patches[p];
            Side::ALL.into_iter().flat_map(move |side| {
                slots.side(p, side).params.iter().map(move |&t| {
                    let [u, v] = side.domain_point(t);
                    let d = patch.derivatives(u, v);
                    (d.p, patch.normal_from(u, v, &d))
                })
            })
        })
        .collect()
}

/// Unites the slots that are one surface point: the corners of each patch, collapsed sides,
/// the two sides of shared boundaries, and corners welded within `tol`.
fn identify_slots(
    c: &PatchComplex,
    slots: &Slots,
    shared: &[SharedBoundary],
    slot_eval: &[(Point, Point)],
    tol: f64,
) -> UnionFind {
    let mut uf = UnionFind::new(slots.len());
    let slot = |p: usize, side: Side, k: usize| slots.slot(p, side, k);
    for (p, patch) in c.patches.iter().enumerate() {
        let last = |side: Side| slots.last(p, side);
        uf.union(slot(p, Side::U0, 0), slot(p, Side::V0, 0));
        uf.union(slot(p, Side::V0, last(Side::V0)), slot(p, Side::U1, 0));
        uf.union(slot(p, Side::U0, last(Side::U0)), slot(p, Side::V1, 0));
        uf.union(
            slot(p, Side::U1, last(Side::U1)),
            slot(p, Side::V1, last(Side::V1)),
        );
        for side in Side::ALL {
            if patch.is_collapsed(side, tol) {
                for k in 1..=last(side) {
                    uf.union(slot(p, side, 0), slot(p, side, k));
                }
            }
        }
    }
    for r in shared {
        join_shared(r, &slots.samples, &slot, &mut uf);
    }
    weld_corners(c.len(), slots, slot_eval, tol, &mut uf);
    uf
}

/// Joins patches that touch only at a corner (no shared side around it) by welding the corner
/// samples. Samples inside sides need no welding: a side piece without a partner is an open
/// boundary, where welding isolated points would only pinch the mesh.
fn weld_corners(
    np: usize,
    slots: &Slots,
    slot_eval: &[(Point, Point)],
    tol: f64,
    uf: &mut UnionFind,
) {
    let corner_slots: Vec<u32> = (0..np)
        .flat_map(|p| {
            [
                slots.slot(p, Side::V0, 0),
                slots.slot(p, Side::V0, slots.last(p, Side::V0)),
                slots.slot(p, Side::V1, 0),
                slots.slot(p, Side::V1, slots.last(p, Side::V1)),
            ]
        })
        .collect();
    let corner_points: Vec<Point> = corner_slots
        .iter()
        .map(|&s| slot_eval[s as usize].0)
        .collect();
    let (weld, nweld) = weld_points(&corner_points, tol);
    let mut first_of_weld = vec![u32::MAX; nweld];
    for (k, &w) in weld.iter().enumerate() {
        if first_of_weld[w as usize] == u32::MAX {
            first_of_weld[w as usize] = corner_slots[k];
        } else {
            uf.union(first_of_weld[w as usize], corner_slots[k]);
        }
    }
}

/// One vertex per class of identified slots, in slot order, with the mean normal of its slots
/// (the first patch's where they cancel); returns the vertex of every slot.
fn boundary_vertices(
    c: &PatchComplex,
    slots: &Slots,
    uf: &mut UnionFind,
    slot_eval: &[(Point, Point)],
    t: &mut Tessellation,
) -> Vec<u32> {
    let mut vertex_of_slot = vec![0u32; slots.len()];
    let mut vertex_of_root = vec![u32::MAX; slots.len()];
    let mut normal_sum: Vec<Point> = Vec::new();
    for p in 0..c.len() {
        for side in Side::ALL {
            for (k, &tp) in slots.side(p, side).params.iter().enumerate() {
                let s = slots.slot(p, side, k) as usize;
                let r = uf.find(s as u32) as usize;
                if vertex_of_root[r] == u32::MAX {
                    vertex_of_root[r] = t.positions.len() as u32;
                    t.positions.push(slot_eval[s].0);
                    t.uv.push(side.domain_point(tp));
                    t.patch_of_vertex.push(p as u32);
                    normal_sum.push([0.0; 3]);
                }
                let v = vertex_of_root[r];
                vertex_of_slot[s] = v;
                normal_sum[v as usize] = add(normal_sum[v as usize], slot_eval[s].1);
            }
        }
    }
    for (v, sum) in normal_sum.iter().enumerate() {
        let l = norm(*sum);
        t.normals.push(if l > 1e-8 {
            scale(*sum, 1.0 / l)
        } else {
            // normals cancel (a fin): keep the first patch's
            let p = t.patch_of_vertex[v] as usize;
            let [u, w] = t.uv[v];
            c.patches[p].normal(u, w)
        });
    }
    vertex_of_slot
}

/// Appends the interior grid points of every patch (`(n - 1)^2` per patch, row by row);
/// returns the index of the first.
fn interior_vertices(c: &PatchComplex, grid: &[f64], t: &mut Tessellation) -> usize {
    let n = grid.len() - 1;
    let m = n - 1; // interior points per row
    let interior_base = t.positions.len();
    let interior: Vec<(Point, Point)> = (0..c.len())
        .into_par_iter()
        .flat_map_iter(|p| {
            let patch = &c.patches[p];
            (1..n).flat_map(move |i| {
                (1..n).map(move |j| {
                    let d = patch.derivatives(grid[i], grid[j]);
                    (d.p, patch.normal_from(grid[i], grid[j], &d))
                })
            })
        })
        .collect();
    for (k, (pos, nor)) in interior.iter().enumerate() {
        let (p, ij) = (k / (m * m), k % (m * m));
        t.positions.push(*pos);
        t.normals.push(*nor);
        t.uv.push([grid[ij / m + 1], grid[ij % m + 1]]);
        t.patch_of_vertex.push(p as u32);
    }
    interior_base
}

/// The triangles of patch `p`, grid quad by grid quad, each boundary quad with the extra
/// boundary points of its sides.
fn triangulate_patch(
    c: &PatchComplex,
    p: usize,
    grid: &[f64],
    slots: &Slots,
    vertex_of_slot: &[u32],
    interior_base: usize,
    t: &mut Tessellation,
) {
    let n = grid.len() - 1;
    let m = n - 1;
    let side_slots = |side: Side, a: usize, b: usize| -> Vec<u32> {
        // vertices of the samples strictly between grid samples a and b of the side
        let ss = slots.side(p, side);
        (ss.own[a] + 1..ss.own[b])
            .map(|k| vertex_of_slot[slots.slot(p, side, k) as usize])
            .collect()
    };
    let gid = |i: usize, j: usize| -> u32 {
        let on = |side: Side, k: usize| {
            vertex_of_slot[slots.slot(p, side, slots.side(p, side).own[k]) as usize]
        };
        if j == 0 {
            on(Side::V0, i)
        } else if j == n {
            on(Side::V1, i)
        } else if i == 0 {
            on(Side::U0, j)
        } else if i == n {
            on(Side::U1, j)
        } else {
            (interior_base + p * m * m + (i - 1) * m + (j - 1)) as u32
        }
    };
    for i in 0..n {
        for j in 0..n {
            // the quad's four edges counter-clockwise, each with its extra boundary points
            let mut edges: [(u32, Vec<u32>); 4] = [
                (gid(i, j), Vec::new()),
                (gid(i + 1, j), Vec::new()),
                (gid(i + 1, j + 1), Vec::new()),
                (gid(i, j + 1), Vec::new()),
            ];
            if j == 0 {
                edges[0].1 = side_slots(Side::V0, i, i + 1);
            }
            if i + 1 == n {
                edges[1].1 = side_slots(Side::U1, j, j + 1);
            }
            if j + 1 == n {
                edges[2].1 = side_slots(Side::V1, i, i + 1);
                edges[2].1.reverse();
            }
            if i == 0 {
                edges[3].1 = side_slots(Side::U0, j, j + 1);
                edges[3].1.reverse();
            }
            let centre = || {
                let (u, v) = ((grid[i] + grid[i + 1]) / 2.0, (grid[j] + grid[j + 1]) / 2.0);
                let d = c.patches[p].derivatives(u, v);
                (d.p, c.patches[p].normal_from(u, v, &d), [u, v])
            };
            triangulate_quad(&edges, centre, p as u32, t);
        }
    }
}

/// Unites the slots of the two sides of a shared boundary that are the same parameter.
fn join_shared(
    r: &SharedBoundary,
    samples: &[SideSamples],
    slot: &impl Fn(usize, Side, usize) -> u32,
    uf: &mut UnionFind,
) {
    let sa = &samples[4 * r.a + r.side_a.index()].params;
    let sb = &samples[4 * r.b + r.side_b.index()].params;
    for (k, &ta) in sa.iter().enumerate() {
        if ta < r.t[0] - PARAM_EPS || ta > r.t[1] + PARAM_EPS {
            continue;
        }
        let s = r.map_to_b(ta);
        let j = sb.partition_point(|&x| x < s - PARAM_EPS);
        if j < sb.len() && (sb[j] - s).abs() <= 2.0 * PARAM_EPS {
            uf.union(slot(r.a, r.side_a, k), slot(r.b, r.side_b, j));
        }
    }
}

/// Triangulates one grid quad given as four counter-clockwise corners, each followed by the
/// extra points on the edge to the next corner. Without extras: two triangles; extras on one
/// edge: fans from the two opposite corners; on more edges: a fan around a new centre vertex.
/// Triangles with a repeated vertex (at collapsed sides) are dropped.
fn triangulate_quad(
    edges: &[(u32, Vec<u32>); 4],
    centre: impl FnOnce() -> (Point, Point, [f64; 2]),
    patch: u32,
    t: &mut Tessellation,
) {
    let emit = |a: u32, b: u32, c: u32, t: &mut Tessellation| {
        if a != b && b != c && a != c {
            t.triangles.push([a, b, c]);
            t.triangle_patch.push(patch);
        }
    };
    let with_extras: Vec<usize> = (0..4).filter(|&e| !edges[e].1.is_empty()).collect();
    match with_extras.as_slice() {
        [] => {
            let [a, b, c, d] = [edges[0].0, edges[1].0, edges[2].0, edges[3].0];
            emit(a, b, c, t);
            emit(a, c, d, t);
        }
        &[e] => {
            // chain A = x_0, x_1, ..., x_m = B along the edge; C, D the other corners
            let mut chain = vec![edges[e].0];
            chain.extend_from_slice(&edges[e].1);
            chain.push(edges[(e + 1) % 4].0);
            let (cc, dd) = (edges[(e + 2) % 4].0, edges[(e + 3) % 4].0);
            let split = chain.len() / 2;
            for q in 0..split {
                emit(chain[q], chain[q + 1], dd, t);
            }
            emit(chain[split], cc, dd, t);
            for q in split..chain.len() - 1 {
                emit(chain[q], chain[q + 1], cc, t);
            }
        }
        _ => {
            let (pos, nor, uv) = centre();
            let z = t.positions.len() as u32;
            t.positions.push(pos);
            t.normals.push(nor);
            t.uv.push(uv);
            t.patch_of_vertex.push(patch);
            let ring: Vec<u32> = edges
                .iter()
                .flat_map(|(c, ex)| std::iter::once(*c).chain(ex.iter().copied()))
                .collect();
            for q in 0..ring.len() {
                emit(ring[q], ring[(q + 1) % ring.len()], z, t);
            }
        }
    }
}

#[cfg(feature = "unit-tests")]
mod tests;
