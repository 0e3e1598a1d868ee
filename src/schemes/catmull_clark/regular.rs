//! Regular sub-nets of quad meshes: the 4x4 bi-3 B-spline net around a regular face.
//!
//! Where a quad and its eight neighbours form a regular grid, the net is a uniform bi-3
//! B-spline control net and the face is one exact bi-3 patch (Catmull-Clark's limit there, and the
//! bi-3 surroundings of EG, QAS+ and guided caps). At a boundary the missing grid points are
//! ghosts mirrored across the boundary (`2 b - i`), which makes the boundary curve the cubic
//! B-spline of the boundary polygon and interpolates valence-2 corners: the edge-only boundary
//! rules of Catmull-Clark.

use crate::geom::Point;
use crate::mesh::PolyMesh;
use crate::stencil::Stencil;

/// A 4x4 bi-3 B-spline net as rows over a mesh's vertices, `row(i * 4 + j)` (see [`bi3_net`]).
///
/// Most nets of a construction are a plain gather of 16 vertices (every face away from
/// boundaries and creases): they are held inline, one `(vertex, 1.0)` term per slot, so the
/// construction allocates nothing per regular face. Nets with ghost points (`2 b - i` at
/// boundaries and cuts) keep one merged [`Stencil`] per slot.
#[derive(Debug, Clone, PartialEq)]
// the grid is inline on purpose: the common net costs no allocation
#[allow(clippy::large_enum_variant)]
pub enum Net {
    /// Every slot is a vertex: the term `(vertex, 1.0)` per slot.
    Grid([(u32, f64); 16]),
    /// Some slots are ghosts: one merged stencil per slot.
    Ghosted(Vec<Stencil>),
}

impl Net {
    /// The terms of slot `k` (`(vertex, weight)`, merged, sorted by vertex).
    #[inline]
    pub fn row(&self, k: usize) -> &[(u32, f64)] {
        match self {
            Net::Grid(g) => std::slice::from_ref(&g[k]),
            Net::Ghosted(s) => s[k].entries(),
        }
    }

    /// The 16 slots' terms in order.
    pub fn rows(&self) -> impl Iterator<Item = &[(u32, f64)]> {
        (0..16).map(move |k| self.row(k))
    }

    /// The net's points for the vertex positions `pos`: each slot's terms summed as
    /// [`Stencil::apply`] sums them (bit-identical).
    pub fn points(&self, pos: &[Point]) -> [Point; 16] {
        let mut pts = [[0.0; 3]; 16];
        for (k, p) in pts.iter_mut().enumerate() {
            for &(i, w) in self.row(k) {
                for (a, x) in p.iter_mut().zip(&pos[i as usize]) {
                    *a += w * x;
                }
            }
        }
        pts
    }

    /// The slots as stencils.
    pub fn stencils(&self) -> Vec<Stencil> {
        self.rows()
            .map(|r| Stencil::from_pairs(r.iter().map(|&(i, w)| (i as usize, w))))
            .collect()
    }
}

/// Grid slot of the 4x4 net, `(i, j)` with `i` along u.
type Slot = (i32, i32);

fn rot(d: Slot) -> Slot {
    (-d.1, d.0)
}

fn rot_cw(d: Slot) -> Slot {
    (d.1, -d.0)
}

/// The 4x4 bi-3 B-spline net of face `f` as stencils over the mesh vertices, `net[i * 4 + j]`
/// with `i` along the face's first edge (corner 0 to corner 1) and `j` along its last edge
/// (corner 0 to corner 3); the face occupies the grid cell `[1, 2] x [1, 2]` and `(u, v)` is
/// oriented like the face (the patch normal points outward).
///
/// Returns `None` unless the face is a quad whose corners are all regular quad vertices
/// (interior valence 4, boundary valence 3, or corner valence 2, with only quads around).
pub fn bi3_net(mesh: &PolyMesh, f: usize) -> Option<Net> {
    if let Some(net) = interior_grid(mesh, f) {
        return Some(net);
    }
    if mesh.face_size(f) != 4
        || mesh
            .face(f)
            .iter()
            .any(|&v| !mesh.is_regular_quad_vertex(v as usize))
    {
        return None;
    }
    bi3_net_cut(mesh, f, &|_| false)
}

/// The net of quad `f` when each of its corners is an interior vertex with a closed fan of
/// exactly four quads (the common case): [`bi3_net_cut`]'s walk without ghosts or cuts, on the
/// mesh's flat arrays, with the same slots and the same consistency checks. `None` whenever a
/// corner is not such a vertex or the grid is not full: the general walk decides then.
fn interior_grid(mesh: &PolyMesh, f: usize) -> Option<Net> {
    const UNSET: u32 = u32::MAX;
    let m = mesh.view();
    let mut slot = [UNSET; 16];
    let mut put = |s: Slot, v: u32| -> bool {
        if !(0..4).contains(&s.0) || !(0..4).contains(&s.1) {
            return true;
        }
        let cell = &mut slot[(s.0 * 4 + s.1) as usize];
        if *cell == UNSET {
            *cell = v;
        }
        *cell == v
    };
    let corner_pos: [Slot; 4] = [(1, 1), (2, 1), (2, 2), (1, 2)];
    let mut dir: Slot = (1, 0);
    let h0 = mesh.face_halfedge(f);
    for (k, &c) in corner_pos.iter().enumerate() {
        let h = h0 + k as u32;
        let v = m.from(h);
        if !put(c, v) {
            return None;
        }
        // the fan must be the vertex's own (the one `is_regular_quad_vertex` walks)
        let mut own = false;
        let (mut g, mut d) = (h, dir);
        for i in 0..4 {
            if m.face_corners(m.face(g) as usize).len() != 4 {
                return None;
            }
            own |= g == m.vert_he[v as usize];
            let nd = rot(d);
            let diag = m.from(m.faces.next(m.faces.next(g)));
            if !put((c.0 + d.0, c.1 + d.1), m.to(g))
                || !put((c.0 + d.0 + nd.0, c.1 + d.1 + nd.1), diag)
            {
                return None;
            }
            let t = m.twin(m.faces.prev(g));
            if t == crate::mesh::NONE || (t == h) != (i == 3) {
                return None;
            }
            (g, d) = (t, nd);
        }
        if !own {
            return None;
        }
        dir = rot(dir);
    }
    if slot.contains(&UNSET) {
        return None;
    }
    let mut grid = [(0u32, 1.0); 16];
    for (g, &v) in grid.iter_mut().zip(&slot) {
        g.0 = v;
    }
    Some(Net::Grid(grid))
}

/// The 4x4 net of quad `f` (as [`bi3_net`]) when the edges for which `cut(edge)` holds are
/// boundaries too (infinitely sharp creases: the grid stops there and ghosts `2 b - i` are
/// mirrored across them, so the crease curve is the cubic B-spline of its vertices). The caller
/// checks that every corner's sector between cuts is regular (four quads around, two quads
/// between two cuts, or one quad between two cuts at a corner); `None` when the grid is not
/// consistent.
pub fn bi3_net_cut(mesh: &PolyMesh, f: usize, cut: &dyn Fn(u32) -> bool) -> Option<Net> {
    if mesh.face_size(f) != 4 {
        return None;
    }
    net_of_slots(&cut_slots(mesh, f, cut)?)
}

/// The 4x4 grid of quad `f`'s neighbourhood gathered around its corners with the edges for
/// which `cut(edge)` holds as boundaries: `None` at a cell where the grid would disagree with
/// itself (degenerate topology); cells beyond a boundary or a cut stay empty.
fn cut_slots(
    mesh: &PolyMesh,
    f: usize,
    cut: &dyn Fn(u32) -> bool,
) -> Option<[[Option<u32>; 4]; 4]> {
    let twin = |h: u32| mesh.he_twin(h).filter(|_| !cut(mesh.he_edge(h)));
    let mut slot: [[Option<u32>; 4]; 4] = [[None; 4]; 4];
    let corner_pos: [Slot; 4] = [(1, 1), (2, 1), (2, 2), (1, 2)];
    let mut dir: Slot = (1, 0);
    let h0 = mesh.face_halfedge(f);
    let put = |s: Slot, v: u32, slot: &mut [[Option<u32>; 4]; 4]| -> Option<()> {
        if !(0..4).contains(&s.0) || !(0..4).contains(&s.1) {
            return Some(());
        }
        let cell = &mut slot[s.0 as usize][s.1 as usize];
        match cell {
            Some(w) if *w != v => None, // inconsistent grid (degenerate topology)
            _ => {
                *cell = Some(v);
                Some(())
            }
        }
    };
    for (k, &c) in corner_pos.iter().enumerate() {
        let h = h0 + k as u32;
        let v = mesh.he_from(h);
        put(c, v, &mut slot)?;
        // Counter-clockwise from the face's outgoing half-edge.
        let mut g = h;
        let mut d = dir;
        let mut bounded = false;
        loop {
            put((c.0 + d.0, c.1 + d.1), mesh.he_to(g), &mut slot)?;
            let nd = rot(d);
            let diag = mesh.he_from(mesh.he_next(mesh.he_next(g)));
            put((c.0 + d.0 + nd.0, c.1 + d.1 + nd.1), diag, &mut slot)?;
            let p = mesh.he_prev(g);
            match twin(p) {
                Some(t) if t != h => {
                    g = t;
                    d = nd;
                }
                Some(_) => break,
                None => {
                    // Boundary reached: the last edge neighbour is the incoming boundary edge's
                    // start.
                    put((c.0 + nd.0, c.1 + nd.1), mesh.he_from(p), &mut slot)?;
                    bounded = true;
                    break;
                }
            }
        }
        // Clockwise from the face's outgoing half-edge (only needed at a boundary or cut).
        if bounded {
            let mut g = h;
            let mut d = dir;
            while let Some(t) = twin(g) {
                let gn = mesh.he_next(t);
                let nd = rot_cw(d);
                put((c.0 + nd.0, c.1 + nd.1), mesh.he_to(gn), &mut slot)?;
                let diag = mesh.he_from(mesh.he_next(mesh.he_next(gn)));
                put((c.0 + d.0 + nd.0, c.1 + d.1 + nd.1), diag, &mut slot)?;
                g = gn;
                d = nd;
            }
        }
        dir = rot(dir);
    }
    Some(slot)
}

/// The bi-3 net of a gathered grid ([`cut_slots`]): the 16 vertices themselves when the grid
/// is full, else with its empty cells filled by ghosts.
fn net_of_slots(slot: &[[Option<u32>; 4]; 4]) -> Option<Net> {
    // A full grid (no ghosts): a gather of 16 vertices, held inline.
    if slot.iter().flatten().all(|s| s.is_some()) {
        let mut grid = [(0u32, 1.0); 16];
        for (k, g) in grid.iter_mut().enumerate() {
            g.0 = slot[k / 4][k % 4].expect("checked above");
        }
        return Some(Net::Grid(grid));
    }
    ghosted(slot)
}

/// A grid with empty cells: ghosts `2 b - i` fill first whole missing columns (i = 0 or 3),
/// then rows, by linear extrapolation; `None` when a cell stays empty.
fn ghosted(slot: &[[Option<u32>; 4]; 4]) -> Option<Net> {
    let mut net: Vec<Option<Stencil>> = (0..16)
        .map(|k| slot[k / 4][k % 4].map(|v| Stencil::point(v as usize)))
        .collect();
    let ghost = |a: &Stencil, b: &Stencil| {
        let mut s = Stencil::new();
        s.add_scaled(a, 2.0).add_scaled(b, -1.0);
        s.merged()
    };
    for (i, i1, i2) in [(0usize, 1usize, 2usize), (3, 2, 1)] {
        for j in 0..4 {
            if net[i * 4 + j].is_none()
                && let (Some(a), Some(b)) = (&net[i1 * 4 + j], &net[i2 * 4 + j])
            {
                net[i * 4 + j] = Some(ghost(a, b));
            }
        }
    }
    for (j, j1, j2) in [(0usize, 1usize, 2usize), (3, 2, 1)] {
        for i in 0..4 {
            if net[i * 4 + j].is_none()
                && let (Some(a), Some(b)) = (&net[i * 4 + j1], &net[i * 4 + j2])
            {
                net[i * 4 + j] = Some(ghost(a, b));
            }
        }
    }
    net.into_iter()
        .collect::<Option<Vec<_>>>()
        .map(Net::Ghosted)
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    #[crate::unit::test]
    fn interior_and_boundary_nets() {
        let m = crate::mesh::nets::quad_grid(4, |_, _| 0.0);
        // Interior face (1,1): its net is the grid points (0..4) x (0..4) - exact positions.
        let f = 4 + 1;
        let net = bi3_net(&m, f).unwrap();
        assert!(matches!(net, Net::Grid(_)));
        let pts = net.points(m.positions());
        for i in 0..4 {
            for j in 0..4 {
                let p = pts[i * 4 + j];
                assert_eq!(p, [i as f64, j as f64, 0.0]);
            }
        }
        // Corner face (0,0): ghosts extrapolate linearly, so the net is the shifted grid.
        let net = bi3_net(&m, 0).unwrap();
        assert!(matches!(net, Net::Ghosted(_)));
        let pts = net.points(m.positions());
        for i in 0..4 {
            for j in 0..4 {
                let p = pts[i * 4 + j];
                assert_eq!(p, [i as f64 - 1.0, j as f64 - 1.0, 0.0]);
            }
        }
        // A face with rotated corner order still gives a consistent grid.
        let net = bi3_net(&m, 15).unwrap();
        let p00 = net.points(m.positions())[0];
        assert_eq!(p00, [2.0, 2.0, 0.0]);
    }
}
