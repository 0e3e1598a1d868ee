//! The patch of a regular vertex of a dual level: its 3x3 net (phantom copies of boundary
//! points, the slots of non-quad faces), the bi-2 patch read off it where the level's points
//! are trusted, and the pieces of an input vertex's patch (its quarters over the faces around it).

use super::*;

/// The 3x3 net of a vertex as vertex indices (`net[k][l]`, `k` along `u`), phantoms being
/// copies of boundary points, and the coefficient slots whose face is not a quad.
pub(super) struct VertexNet {
    pub(super) net: [[usize; 3]; 3],
    /// `(coefficient index i * 3 + j, face)` for every non-quad face around the vertex.
    pub(super) ngons: Vec<(usize, u32)>,
}

/// The 3x3 net of vertex `v`, or `None` unless `v` is interior with four faces, on the boundary
/// with two faces, or a corner with one face (the face sizes may be anything). `u` runs along
/// the first outgoing half-edge of `v` (its outgoing boundary edge on the boundary), `v`
/// counter-clockwise from it.
pub(super) fn vertex_net(m: &PolyMesh, v: usize) -> Option<VertexNet> {
    let hs = m.outgoing_halfedges(v);
    let boundary = m.is_boundary_vertex(v);
    let ok = if boundary {
        // A kept corner with two faces is not regular: its boundary curve interpolates it; a
        // vertex with one face is regular only when kept (not under edge-only).
        (hs.len() == 1 && crate::schemes::doo_sabin::sharp::is_kept_corner(m, v))
            || (hs.len() == 2 && !crate::schemes::doo_sabin::sharp::is_tagged_corner(m, v))
    } else {
        hs.len() == 4
    };
    if !ok {
        return None;
    }
    const DIRS: [(i32, i32); 4] = [(1, 0), (0, 1), (-1, 0), (0, -1)];
    let mut net = [[usize::MAX; 3]; 3];
    let mut ngons = Vec::new();
    let at = |d: (i32, i32)| ((1 + d.0) as usize, (1 + d.1) as usize);
    net[1][1] = v;
    for (k, &h) in hs.iter().enumerate() {
        let (d, e) = (DIRS[k], DIRS[(k + 1) % 4]);
        let (i, j) = at(d);
        net[i][j] = m.he_to(h) as usize;
        let f = m.he_face(h);
        let (ci, cj) = at((d.0 + e.0, d.1 + e.1));
        if m.face_size(f as usize) == 4 {
            net[ci][cj] = m.he_from(m.he_next(m.he_next(h))) as usize;
        } else {
            // Placeholder: only the corner coefficient uses the diagonal node, and it is
            // replaced by the face's centroid.
            net[ci][cj] = v;
            ngons.push((ci * 3 + cj, f));
        }
        if boundary && k + 1 == hs.len() {
            // The incoming boundary edge's start.
            let (i, j) = at(e);
            net[i][j] = m.he_from(m.he_prev(h)) as usize;
        }
    }
    if boundary {
        // Phantom row j = 0 (and for a corner phantom column i = 0): copies of the boundary.
        if hs.len() == 1 {
            net[0] = net[1];
        }
        for row in &mut net {
            row[0] = row[1];
        }
    }
    Some(VertexNet { net, ngons })
}

fn patch_from(m: &PolyMesh, stencils: &[Stencil]) -> BezierPatch {
    let cps: Vec<Point> = stencils.iter().map(|s| s.apply(m.positions())).collect();
    BezierPatch::new(2, 2, cps)
}

/// The exact bi-2 patch of vertex `v` if it is regular and its net is trusted.
pub(super) fn trusted_patch(level: &Level, v: usize) -> Option<BezierPatch> {
    let m = &level.mesh;
    if !level.info[v].fan_ok {
        return None;
    }
    let vn = vertex_net(m, v)?;
    if !vn.ngons.is_empty() {
        return None;
    }
    let s = biquadratic_bspline_stencils(&vn.net);
    let trusted = s.iter().all(|st| {
        st.entries()
            .iter()
            .all(|&(x, _)| level.info[x as usize].pos_ok)
    });
    trusted.then(|| patch_from(m, &s))
}

/// The quarters of the faces around the input vertex `v` that its patch, the
/// last of `out`, covers ([`crate::bezier::domain`]): `vertex_quarter_pieces` with the input
/// faces' own cells. The regular patches of `bi2-mixed` are laid out the same way.
pub fn input_vertex_pieces(m: &PolyMesh, v: usize, out: &mut PatchComplex) {
    let patch = (out.len() - 1) as u32;
    let cell = |g: usize, k: u32| Domain::polygon(g as u32, m.face_size(g)).child(k);
    vertex_quarter_pieces(m, v, patch, &cell, out);
}

/// The quarters of the faces around the vertex `v` that its bi-2 patch `patch`
/// covers ([`crate::bezier::domain`]), `corner_cell(g, k)` being the cell of face `g`'s
/// quarter at its corner `k` (child `k` of the input face itself, or for TPS of a third of
/// one; for adjustable TPS after a separating step a framed rectangle of an input face,
/// `(0, 0)` at the corner, `u` toward corner `k + 1`): face `i` of `v`'s fan (`u` along its first
/// outgoing half-edge, `v` counter-clockwise) has its centroid at the patch's corner `2 + i`
/// and at corner 2 of its quarter at `v`. At a regular boundary vertex (two faces, or a
/// corner with one) the fan starts at the outgoing boundary edge, as the patch's net does
/// (its phantom row at `v < 1/2`, beyond the boundary edges), so its faces' quarters are
/// recorded alike. Shared by the dual schemes and TPS, whose vertex patches lie alike.
pub(crate) fn vertex_quarter_pieces(
    m: &PolyMesh,
    v: usize,
    patch: u32,
    corner_cell: &dyn Fn(usize, u32) -> Domain,
    out: &mut PatchComplex,
) {
    for (i, h) in m.outgoing_halfedges(v).into_iter().enumerate() {
        let g = m.he_face(h) as usize;
        let k = h - m.face_halfedge(g);
        let cell = corner_cell(g, k);
        out.push_piece(Piece::quarter(patch, ((2 + i) % 4) as u8, cell, 2));
    }
}
