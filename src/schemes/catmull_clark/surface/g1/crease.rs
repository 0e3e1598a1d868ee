//! G^1 caps at Catmull-Clark's crease vertices (two infinitely sharp edges through an
//! extraordinary interior vertex, OpenSubdiv's crease rule at the vertex).
//!
//! Under the crease rules each side of the crease refines exactly as a boundary fan does: the
//! vertex rule `(e_a + 6 x + e_b) / 8` reads only the two crease neighbours, the crease edges
//! take their midpoints and the smooth edge and face points read faces of their own side. So
//! each side of `k = 1` or `k >= 3` quads is closed by the open-fan cap of a boundary vertex
//! ([`crate::bezier::g1::Layout::OpenQuad`]), with:
//!
//! * **centre**: the crease curve's limit point `(e_a + 4 x + e_b) / 6`;
//! * **tangent plane**: `T0 = (e_a - e_b) / 2`, the crease curve's exact derivative at the
//!   centre along spoke `0` (the cubic B-spline of the crease polygon, per unit of the level's
//!   parameter), and the subdominant eigen tangent across the boundary of a fan of `k` quads
//!   ([`crate::schemes::catmull_clark::boundary_tangent`]) applied to the side's one-ring;
//! * **crease spokes** ([`Fan::Crease`]): `T0` is pinned, not fitted, and the boundary spokes
//!   are the cubic Hermite interpolants of their end data, which are the crease's B-spline
//!   itself: the caps of both sides, a regular crease patch on a side of two quads, and the
//!   ring patches all share the crease curve, so the crease is C^0 exactly (to rounding) and
//!   each side is G^1 inside.
//!
//! A side of one quad is one crease fan of one sector: its two spokes are the crease's halves
//! (`T1 = -T0`, a straight corner at the centre, where the patch's own partials are parallel)
//! and it has no inner spoke, so it is the C^1-to-the-ring patch with the crease's exact curve
//! on its crease sides and the fairest interior (the cube's faces inside a creased edge loop).
//! A side of two quads still marked waits (its faces become regular crease patches at the next
//! level).
//!
//! A boundary vertex of one quad under the crease rule (OpenSubdiv's edge-only boundary
//! interpolation, [`boundary_corner_cap`]) is the same one-sector fan: the boundary curve runs
//! smoothly through it, and its quad is closed by that cap instead of the fill.

use super::super::Level;
use super::segment_across;

use crate::geom::{axpy, scale, sub};
use crate::host::adaptive::{
    CapData, NoCap, QuadSector, Tag, quad_hole_segments, quad_sectors_between, quad_sectors_open,
};
use crate::schemes::catmull_clark::boundary_tangent::across_weights;
use crate::schemes::catmull_clark::dart::dart_masks;
use crate::schemes::sdc::crease::adaptive::{
    SideFan, TagAt, cone_cap_by, corner_caps_by, crease_caps_by, dart_cap_by, is_plain_boundary,
    one_quad_crease_fan,
};
use std::collections::HashMap;

/// The caps of the crease vertex `x` whose marked cells are `faces`: `Ok(None)` when `x` is
/// not a crease vertex (the caller's plain cap applies), one cap per side of one, or of three
/// or more quads (sides of two quads are regular crease patches, not marked;
/// [`crease_sides`]), or why there are none (`Later` while a semi-sharp feature is left or a
/// side's ring is incomplete).
pub(in crate::schemes::catmull_clark::surface) fn crease_caps(
    level: &Level,
    x: usize,
    faces: &[(u32, Tag)],
) -> Result<Option<Vec<CapData>>, NoCap> {
    let m = &level.mesh;
    let pos = m.positions();
    crease_caps_by(level, x, faces, 2, |tag_at, (ha, _, k)| {
        let (quads, fan) = side_fan(level, x, ha, k, tag_at)?;
        let q = pos[quads[k - 1].q as usize];
        let far = |i: usize| {
            let sec = &quads[i];
            pos[m.face(sec.face as usize)[(sec.corner + 2) % 4] as usize]
        };
        let across = match across_weights(k) {
            // the across tangent's weights over x, e_0 .. e_k, d_0 .. d_(k-1)
            Some(w) => {
                let mut t = axpy(scale(pos[x], w.1[0]), w.1[1 + k], q);
                for (i, sec) in quads.iter().enumerate() {
                    t = axpy(t, w.1[1 + i], pos[sec.p as usize]);
                    t = axpy(t, w.1[k + 2 + i], far(i));
                }
                t
            }
            // one face: only its side of the plane matters (`T1 = -T0`), towards its far corner
            None => sub(far(0), pos[x]),
        };
        Ok((fan, across))
    })
}

/// The quads of the side of `k` faces from the face of `ha` around `x`, with their hole
/// segments and cap tags.
fn side_fan(
    level: &Level,
    x: usize,
    ha: u32,
    k: usize,
    tag_at: &TagAt,
) -> Result<(Vec<QuadSector>, SideFan), NoCap> {
    let m = &level.mesh;
    let quads = quad_sectors_between(m, x as u32, m.he_face(ha), k).ok_or(NoCap::Never)?;
    let tags = sector_tags(&quads, tag_at)?;
    let sectors = quad_hole_segments(&quads, |he, from| segment_across(level, he, from))?;
    Ok((quads, (sectors, tags)))
}

/// The cap of a boundary vertex `x` of one quad under the crease rule (edge-only boundary: its
/// vertex sharpness 0, no sharp edge inside): one crease fan of one sector (module
/// documentation) centred at the boundary curve's limit point `(e_a + 4 x + e_b) / 6`, its
/// spokes the boundary curve's two halves.
pub(in crate::schemes::catmull_clark::surface) fn boundary_corner_cap(
    level: &Level,
    x: usize,
    faces: &[(u32, Tag)],
) -> Result<CapData, NoCap> {
    let m = &level.mesh;
    if !is_plain_boundary(level, x) || faces.len() != 1 {
        return Err(NoCap::Never);
    }
    let quads = quad_sectors_open(m, x as u32, 1).ok_or(NoCap::Never)?;
    let sec = &quads[0];
    if sec.face != faces[0].0 {
        return Err(NoCap::Never);
    }
    let tag = Tag {
        domain: faces[0].1.domain.rotated(sec.corner as u32),
        ..faces[0].1
    };
    let sectors = quad_hole_segments(&quads, |he, from| segment_across(level, he, from))?;
    let pos = m.positions();
    let far = pos[m.face(sec.face as usize)[(sec.corner + 2) % 4] as usize];
    let ends = [pos[sec.p as usize], pos[x], pos[sec.q as usize]];
    let (hole, plane) = one_quad_crease_fan(sectors, ends, sub(far, pos[x]));
    Ok((hole, plane, vec![tag]))
}

/// The cap of the dart `x` whose marked cells are `faces` ([`Fan::Dart`]): `Ok(None)` when
/// `x` is not a dart, `Later` while a semi-sharp feature is left at `x`, `Never` when its `n`
/// faces are not exactly the cells or not all quads. The fan starts at the sharp edge (spoke
/// `0` and spoke `n`); centre and tangent plane are the dart's own limit and eigen tangents
/// ([`dart_masks`]); `T0, T1` are fitted in that plane over the full turn.
pub(in crate::schemes::catmull_clark::surface) fn dart_cap(
    level: &Level,
    x: usize,
    faces: &[(u32, Tag)],
) -> Result<Option<CapData>, NoCap> {
    dart_cap_by(
        level,
        x,
        faces,
        dart_masks,
        NoCap::Never,
        |masks, h, n, tag_at| {
            let (quads, fan) = side_fan(level, x, h, n, tag_at)?;
            let m = &level.mesh;
            let pos = m.positions();
            // the masks' points: x, e_0 .. e_(n-1), f_0 .. f_(n-1)
            let ring: Vec<_> = std::iter::once(pos[x])
                .chain(quads.iter().map(|sec| pos[sec.p as usize]))
                .chain(
                    quads
                        .iter()
                        .map(|sec| pos[m.face(sec.face as usize)[(sec.corner + 2) % 4] as usize]),
                )
                .collect();
            let (centre, plane) = masks.apply(&ring);
            Ok((fan, centre, plane))
        },
    )
}

/// The cap of the cone point `x` whose marked cells are `faces` ([`Fan::Cone`]): `Ok(None)`
/// when `x` is not a cone point ([`cone_point`]), `Later` while a semi-sharp edge is left at
/// `x`, `Never` when its `n` faces are not exactly the cells or not all quads. A closed hole
/// (no sharp edge) or a dart's fan from its one sharp edge, centred at `x` itself (the corner
/// rule keeps it), every spoke tangent zero.
pub(in crate::schemes::catmull_clark::surface) fn cone_cap(
    level: &Level,
    x: usize,
    faces: &[(u32, Tag)],
) -> Result<Option<CapData>, NoCap> {
    cone_cap_by(level, x, faces, NoCap::Never, |sharp, hs, tag_at| {
        Ok(side_fan(level, x, sharp.unwrap_or(hs[0]), hs.len(), tag_at)?.1)
    })
}

/// The cap tags of a fan's quads: each marked face's tag with its domain turned so that the cap
/// patch's `(0, 0)` is the fan's centre; `Never` when a quad is not marked.
pub(super) fn sector_tags(
    quads: &[QuadSector],
    tag_at: &HashMap<u32, Tag>,
) -> Result<Vec<Tag>, NoCap> {
    quads
        .iter()
        .map(|sec| {
            let tag = tag_at.get(&sec.face).ok_or(NoCap::Never)?;
            Ok(Tag {
                domain: tag.domain.rotated(sec.corner as u32),
                ..*tag
            })
        })
        .collect()
}

/// The caps of the corner `x` whose marked cells are `faces` ([`Fan::Corner`]): `Ok(None)`
/// when `x` is not a corner with sharp edges ([`corner_sides`]); one cap per side of two or
/// more quads between consecutive sharp edges (a side of one quad is a regular corner patch),
/// centred at `x` (the corner rule keeps it) in the plane of the two sharp edges' derivatives
/// there ([`corner_plane`]; a reflex side's chart turns three quarters), its boundary spokes
/// those edges' limit curves' first segments, exactly.
pub(in crate::schemes::catmull_clark::surface) fn corner_caps(
    level: &Level,
    x: usize,
    faces: &[(u32, Tag)],
) -> Result<Option<Vec<CapData>>, NoCap> {
    corner_caps_by(level, x, faces, 1, |tag_at, (ha, _, k)| {
        Ok(side_fan(level, x, ha, k, tag_at)?.1)
    })
}
