//! Loop patch output with OpenSubdiv's sharp features: infinitely sharp creases and corners,
//! semi-sharp ones, the boundary options and holes, as OpenSubdiv's adaptive Loop patches treat
//! them, on the levels of `crate::schemes::sdc::crease::adaptive` (shared with
//! Catmull-Clark).
//!
//! # Regular triangles
//!
//! A triangle is one exact quartic box-spline triangle when each corner's sector (the
//! triangles between the corner's infinitely sharp edges, boundary edges included) is, with
//! all features at the corner of sharpness 0 or infinite, one of
//!
//! * the whole fan of six triangles and no sharp edge (the smooth regular vertex),
//! * three triangles between the vertex's two sharp edges (the crease rule: the regular crease
//!   vertex, whatever lies on the other side),
//! * one triangle between two sharp edges at a corner (the corner rule: a sharp vertex, or
//!   more than two sharp edges).
//!
//! The six neighbours the box-spline net takes at such a corner `v` are, counter-clockwise over
//! the sector's neighbours `w_0, ..`, the smooth fan itself; at a crease `w_0 .. w_3` and the
//! phantoms `v + w_3 - w_2`, `v + w_0 - w_1` (parallelogram completion across each crease edge,
//! as Loop's boundary triangles take it); at a corner `w_0, w_1, v + w_1 - w_0, 2 v - w_0,
//! 2 v - w_1, v + w_0 - w_1` (the net is odd about `v`). These are OpenSubdiv's phantom points
//! of its regular Loop boundary patches (`Far`'s box-spline boundary weights). With them Loop's
//! smooth rules reproduce the sharp rules on the sector: the valence-6 vertex rule becomes the
//! crease rule `(1, 6, 1) / 8` at a crease and `v` at a corner (the corner's ring sums to
//! `6 v`), the edge rule on a crease edge the midpoint, and the refined phantoms are the
//! phantoms of the refined sector, so the triangle's box-spline piece is Loop's limit over it.
//! The crease curve is the cubic B-spline of the crease vertices (ghost `2 c - n` at a corner),
//! shared exactly by the triangles on the two sides (a C^0, sharp join). The integration tests
//! compare every emitted triangle with Loop limit points of the uniformly refined net.
//!
//! Without features (the plain rules on a net whose only features are its boundary) the
//! corner of one triangle is left to the rings and the fill, as before (the outputs of nets
//! without tags do not change).
//!
//! # Everything else
//!
//! Semi-sharp edges and vertices, darts, crease ends, crease vertices with other numbers of
//! triangles, corners of two or more triangles and edge-only boundary corners are refined with
//! their neighbourhood like an extraordinary vertex: semi-sharp values decay by one per level
//! (or by Chaikin's rule) until they are spent and the triangles become regular. What is left
//! after the rings is closed by Loop's Hermite fill (C^0; the derivatives at sharp vertices are
//! the chords of the limit points, crease edges between crease or corner vertices the exact
//! B-spline), never by a G^1 cap (a cap needs a smooth centre and smooth spoke ends). Hole
//! faces (the net's and those that boundary `none` makes) are refined for support but not
//! written.

use super::Level;
use crate::bezier::Side;
use crate::bezier::complex::PatchComplex;
use crate::mesh::PolyMesh;
use crate::schemes::sdc::crease::Rule;
use crate::schemes::sdc::crease::adaptive::{self, Features, sector};
use crate::stencil::Stencil;

/// The sector of corner `v = from(h)` when it is regular for the box spline: its rule and its
/// outgoing half-edges counter-clockwise (see the module documentation). Without features
/// (`ft` `None`) the plain rules: interior vertices of valence 6, boundary vertices with three
/// triangles.
fn regular_sector(m: &PolyMesh, ft: Option<&Features>, h: u32) -> Option<(Rule, Vec<u32>)> {
    let (rule, out, closed) = match ft {
        Some(ft) => {
            // a crease vertex of any valence up to the caps' is regular on a side of three
            // triangles (the side's limit is the crease patch's)
            let s = sector(m, ft, h, crate::bezier::g1::MAX_CAP_VALENCE)?;
            (s.rule, s.out, s.closed)
        }
        None => {
            let v = m.he_from(h) as usize;
            if m.outgoing(v).take(7).count() > 6 {
                return None;
            }
            let closed = !m.is_boundary_vertex(v);
            let rule = if closed { Rule::Smooth } else { Rule::Crease };
            (rule, m.outgoing_halfedges(v), closed)
        }
    };
    match (rule, out.len(), closed) {
        (Rule::Smooth, 6, true) | (Rule::Crease, 3, false) => Some((rule, out)),
        (Rule::Corner, 1, false) if ft.is_some() => Some((rule, out)),
        _ => None,
    }
}

/// The six neighbours of corner `v = from(h)` that the box-spline net takes, counter-clockwise
/// from `to(h)`, phantoms across the sector's cuts (see the module documentation); `None` when
/// the corner is not regular.
pub(super) fn corner_ring(m: &PolyMesh, ft: Option<&Features>, h: u32) -> Option<[Stencil; 6]> {
    let (rule, out) = regular_sector(m, ft, h)?;
    let v = m.he_from(h) as usize;
    let w: Vec<usize> = out.iter().map(|&g| m.he_to(g) as usize).collect();
    let last = m.he_from(m.he_prev(*out.last()?)) as usize;
    let phantom = |a: usize, c: usize| Stencil::from_pairs([(v, 1.0), (a, 1.0), (c, -1.0)]);
    let mirror = |a: usize| Stencil::from_pairs([(v, 2.0), (a, -1.0)]);
    let mut ring: Vec<Stencil> = w.iter().map(|&x| Stencil::point(x)).collect();
    match rule {
        Rule::Crease => {
            ring.push(Stencil::point(last));
            ring.push(phantom(last, w[2]));
            ring.push(phantom(w[0], w[1]));
        }
        Rule::Corner => {
            ring.push(Stencil::point(last));
            ring.push(phantom(last, w[0]));
            ring.push(mirror(w[0]));
            ring.push(mirror(last));
            ring.push(phantom(w[0], last));
        }
        Rule::Smooth | Rule::Dart => {}
    }
    let off = out.iter().position(|&g| g == h)?;
    ring.rotate_left(off);
    ring.try_into().ok()
}

/// Whether vertex `v` of `level` makes its triangles irregular (an extraordinary element for
/// the tags): some triangle at it is not regular there.
pub(super) fn irregular_vertex(level: &Level, v: usize) -> bool {
    let m = &level.mesh;
    let ft = level.sharp.as_ref();
    m.outgoing(v).take(7).count() > 6
        || m.outgoing_halfedges(v)
            .into_iter()
            .any(|h| regular_sector(m, ft, h).is_none())
}

/// Marks the sides of the last patch of `out`, the triangle of face `f` of `level` (stored as
/// in [`super`]: edge `P0 P1` on `v = 0`, `P1 P2` on `u = 1`, `P2 P0` on `u = 0`), that lie on
/// an infinitely sharp edge inside the surface.
pub(super) fn mark_sides(level: &Level, f: usize, out: &mut PatchComplex) {
    adaptive::mark_sides(level, f, &[Side::V0, Side::U1, Side::U0], out);
}
