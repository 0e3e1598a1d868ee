//! Catmull-Clark patch output with OpenSubdiv's sharp features: infinitely sharp creases and
//! corners, semi-sharp ones, the boundary options and holes, as OpenSubdiv's adaptive patches
//! treat them.
//!
//! The levels carry their sharpness as `crate::schemes::sdc::crease::adaptive`
//! describes (shared with Loop). A quad is one exact bi-3 patch when every corner is regular
//! *with respect to the features*: all its edges and itself of sharpness 0 or infinite, quads
//! around it, and the sector of the face between infinitely sharp edges (or boundary edges)
//! one of
//!
//! * four quads and no sharp edge (the smooth regular vertex),
//! * two quads between the vertex's two sharp edges (the crease rule: the regular crease vertex,
//!   whatever lies on the other side),
//! * one quad between two sharp edges at a corner (the corner rule).
//!
//! The net is then [`bi3_net_cut`]'s: the grid stops at the crease and ghosts `2 b - i` are
//! mirrored across it, so the patch's side on the crease is the cubic B-spline of the crease
//! vertices, and the patches on the two sides share it exactly (C^0, sharp); elsewhere they
//! are C^2. The limit of such a face depends only on its own side of the crease, since crease
//! points are refined from crease points alone.
//!
//! Everything else (semi-sharp edges and vertices, darts, crease ends, the sides of crease
//! vertices other than two quads, corners meeting creases, edge-only boundary corners) is
//! refined with its neighbourhood like an extraordinary element: semi-sharp values decay by
//! one per level (or by Chaikin's rule) until they are spent and the faces become regular; an
//! extraordinary vertex whose features were all semi-sharp then gets its G^1 cap, a crease
//! vertex one G^1 cap per side other than two quads, an edge-only boundary corner a one-piece
//! cap on the boundary curve (`super::g1`); what is left after the
//! rings is closed by the Hermite-Coons fill (C^0; the derivatives at sharp vertices are the
//! chords of the limit points, crease edges between crease or corner vertices the exact
//! B-spline). Hole faces (the net's and those that boundary `none` makes)
//! are refined for support but not written.

use super::Level;
use crate::bezier::Side;
use crate::bezier::complex::PatchComplex;
use crate::mesh::PolyMesh;
use crate::schemes::catmull_clark::Rules;
use crate::schemes::catmull_clark::regular::{Net, bi3_net_cut};
use crate::schemes::sdc::crease::Rule;
use crate::schemes::sdc::crease::adaptive::{self, Features, is_inf, sector};

/// The rules of one refinement step of `level` (its features' options, or the defaults).
pub(super) fn rules(level: &Level) -> Rules<'_> {
    Rules::new(&level.mesh, &level.options())
}

/// Whether the corner `v = from(h)` of the face of `h` is regular with respect to the features
/// (see the module documentation).
fn corner_regular(m: &PolyMesh, ft: &Features, h: u32) -> bool {
    // a crease vertex of any valence up to the caps' is regular on a side of two quads (the
    // side's limit is the crease patch's, whatever lies on the other side)
    let Some(s) = sector(m, ft, h, crate::bezier::g1::MAX_CAP_VALENCE) else {
        return false;
    };
    let v = m.he_from(h) as usize;
    if m.vertex_faces(v)
        .iter()
        .any(|&g| m.face_size(g as usize) != 4)
    {
        return false;
    }
    matches!(
        (s.rule, s.out.len(), s.closed),
        (Rule::Smooth, 4, true) | (Rule::Crease, 2, false) | (Rule::Corner, 1, false)
    )
}

/// The 4x4 net of face `f` when it is one exact bi-3 patch under the features (every corner
/// regular, see the module documentation), the crease edges cut.
pub(super) fn bi3_net(level: &Level, ft: &Features, f: usize) -> Option<Net> {
    let m = &level.mesh;
    if m.face_size(f) != 4 {
        return None;
    }
    let h0 = m.face_halfedge(f);
    if !(h0..h0 + 4).all(|h| corner_regular(m, ft, h)) {
        return None;
    }
    bi3_net_cut(m, f, &|e| is_inf(ft.edges[e as usize]))
}

/// Whether vertex `v` of `level` makes its faces irregular (an extraordinary element for the
/// tags): not a regular quad vertex, or (with features) some face at it not regular there.
pub(super) fn irregular_vertex(level: &Level, v: usize) -> bool {
    let m = &level.mesh;
    match &level.sharp {
        None => !m.is_regular_quad_vertex(v),
        Some(ft) => {
            m.outgoing(v).take(5).count() > 4
                || m.outgoing_halfedges(v)
                    .into_iter()
                    .any(|h| !corner_regular(m, ft, h))
        }
    }
}

/// Marks the sides of the last patch of `out`, the patch of quad `f` of `level` (corner `k` at
/// the domain corner `k` of `(0,0), (1,0), (1,1), (0,1)`), that lie on an infinitely sharp
/// edge inside the surface.
pub(super) fn mark_sides(level: &Level, f: usize, out: &mut PatchComplex) {
    // edge k runs from corner k to corner k + 1: sides V0, U1, V1, U0
    adaptive::mark_sides(level, f, &[Side::V0, Side::U1, Side::V1, Side::U0], out);
}
