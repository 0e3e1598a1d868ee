//! Regular sub-nets of quad meshes: the 4x4 bi-3 B-spline net around a regular face.
//!
//! Where a quad and its eight neighbours form a regular grid, the net is a uniform bi-3
//! B-spline control net and the face is one exact bi-3 patch (Catmull-Clark's limit there, and the
//! bi-3 surroundings of EG, QAS+ and guided caps). At a boundary the missing grid points are
//! ghosts mirrored across the boundary (`2 b - i`), which makes the boundary curve the cubic
//! B-spline of the boundary polygon and interpolates valence-2 corners: the edge-only boundary
//! rules of Catmull-Clark.

use crate::mesh::PolyMesh;
use crate::stencil::Stencil;

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
pub fn bi3_net(mesh: &PolyMesh, f: usize) -> Option<Vec<Stencil>> {
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

/// The 4x4 net of quad `f` (as [`bi3_net`]) when the edges for which `cut(edge)` holds are
/// boundaries too (infinitely sharp creases: the grid stops there and ghosts `2 b - i` are
/// mirrored across them, so the crease curve is the cubic B-spline of its vertices). The caller
/// checks that every corner's sector between cuts is regular (four quads around, two quads
/// between two cuts, or one quad between two cuts at a corner); `None` when the grid is not
/// consistent.
pub fn bi3_net_cut(mesh: &PolyMesh, f: usize, cut: &dyn Fn(u32) -> bool) -> Option<Vec<Stencil>> {
    if mesh.face_size(f) != 4 {
        return None;
    }
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
    // Ghosts: first whole missing columns (i = 0 or 3), then rows, by linear extrapolation.
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
    net.into_iter().collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interior_and_boundary_nets() {
        let m = crate::mesh::nets::quad_grid(4, |_, _| 0.0);
        // Interior face (1,1): its net is the grid points (0..4) x (0..4) - exact positions.
        let f = 4 + 1;
        let net = bi3_net(&m, f).unwrap();
        for i in 0..4 {
            for j in 0..4 {
                let p = net[i * 4 + j].apply(m.positions());
                assert_eq!(p, [i as f64, j as f64, 0.0]);
            }
        }
        // Corner face (0,0): ghosts extrapolate linearly, so the net is the shifted grid.
        let net = bi3_net(&m, 0).unwrap();
        for i in 0..4 {
            for j in 0..4 {
                let p = net[i * 4 + j].apply(m.positions());
                assert_eq!(p, [i as f64 - 1.0, j as f64 - 1.0, 0.0]);
            }
        }
        // A face with rotated corner order still gives a consistent grid.
        let net = bi3_net(&m, 15).unwrap();
        let p00 = net[0].apply(m.positions());
        assert_eq!(p00, [2.0, 2.0, 0.0]);
    }
}
