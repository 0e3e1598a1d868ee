//! The G^1 caps of sharp vertices (a crease vertex's and a corner's sides, darts, cone points)
//! for Catmull-Clark and Loop alike. The sides come from [`crease_sides`] and
//! [`corner_sides`]; the scheme builds each side's fan
//! (the hole's segments read off its own patches, the cells' cap tags and, at a crease, the
//! tangent across the crease from its own eigen tangent); the rest is written here once: a
//! crease side is centred at the crease's limit point with `T0 = (e_a - e_b) / 2`, the
//! crease's exact derivative, a corner side at the corner in the plane of its sharp edges
//! ([`corner_plane`]); a dart and a cone point check their cells the same way.

use super::{Level, cone_point, corner_plane, corner_sides, crease_sides, dart_halfedge};
use crate::bezier::g1::{Hole, Segment};
use crate::geom::{Point, scale, sub};
use crate::host::adaptive::{CapData, NoCap, Tag};
use std::collections::HashMap;

/// One side's fan as a scheme builds it: the hole's segments and the cells' cap tags (domain
/// turned so that the cap patch's `(0, 0)` is the vertex).
pub(crate) type SideFan = (Vec<Vec<Segment>>, Vec<Tag>);

/// The marked cells' tags by face, which a scheme's side fan reads.
pub(crate) type TagAt = HashMap<u32, Tag>;

/// The caps of the crease vertex `x` whose marked cells are `cells`: `Ok(None)` when `x` is not
/// a crease vertex, else one crease fan per side ([`crease_sides`]; a side of `regular` faces
/// is the scheme's regular crease patches), built by `side` from `(ha, hb, k)` together with
/// its tangent across the crease.
pub(crate) fn crease_caps_by(
    level: &Level,
    x: usize,
    cells: &[(u32, Tag)],
    regular: usize,
    mut side: impl FnMut(&TagAt, (u32, u32, usize)) -> Result<(SideFan, Point), NoCap>,
) -> Result<Option<Vec<CapData>>, NoCap> {
    let Some((centre, sides)) = crease_sides(level, x, cells, regular)? else {
        return Ok(None);
    };
    let m = &level.mesh;
    let e = |h: u32| m.positions()[m.he_to(h) as usize];
    let tag_at: TagAt = cells.iter().copied().collect();
    let mut caps = Vec::with_capacity(sides.len());
    for (ha, hb, k) in sides {
        let ((sectors, tags), across) = side(&tag_at, (ha, hb, k))?;
        let along = scale(sub(e(ha), e(hb)), 0.5);
        caps.push((
            Hole::untangented_crease(centre, sectors),
            [along, across],
            tags,
        ));
    }
    Ok(Some(caps))
}

/// The caps of the corner `x` whose marked cells are `cells`: `Ok(None)` when `x` is not a
/// corner with sharp edges, else one corner fan per side ([`corner_sides`]; a side of
/// `regular` faces is the scheme's regular corner patch) built by `side`, centred at `x` (the
/// corner rule keeps it) in the plane of the two sharp edges' derivatives ([`corner_plane`]).
pub(crate) fn corner_caps_by(
    level: &Level,
    x: usize,
    cells: &[(u32, Tag)],
    regular: usize,
    mut side: impl FnMut(&TagAt, (u32, u32, usize)) -> Result<SideFan, NoCap>,
) -> Result<Option<Vec<CapData>>, NoCap> {
    let Some(sides) = corner_sides(level, x, cells, regular)? else {
        return Ok(None);
    };
    let m = &level.mesh;
    let tag_at: TagAt = cells.iter().copied().collect();
    let mut caps = Vec::with_capacity(sides.len());
    for s in sides {
        let (sectors, tags) = side(&tag_at, s)?;
        let (angle, plane) = corner_plane(m, x, s)?;
        caps.push((
            Hole::untangented_corner(m.positions()[x], sectors, angle),
            plane,
            tags,
        ));
    }
    Ok(Some(caps))
}

/// The cap of the dart `x` whose marked cells are `cells` ([`Fan::Dart`](crate::bezier::g1::Fan)):
/// `Ok(None)` when `x` is not a dart, `Later` while a semi-sharp feature is left at `x`,
/// `Never` without the scheme's dart `masks` at its valence `n`, `count` when its `n` faces are
/// not exactly the cells. `fan` builds, from the masks, the sharp half-edge `h` (spokes `0`
/// and `n`) and `n`, the fan over the full turn with the dart's own limit point and tangent
/// plane.
pub(crate) fn dart_cap_by<M>(
    level: &Level,
    x: usize,
    cells: &[(u32, Tag)],
    masks: impl FnOnce(usize) -> Option<M>,
    count: NoCap,
    fan: impl FnOnce(M, u32, usize, &TagAt) -> Result<(SideFan, Point, [Point; 2]), NoCap>,
) -> Result<Option<CapData>, NoCap> {
    let Some((h, plain)) = dart_halfedge(level, x) else {
        return Ok(None);
    };
    if !plain {
        return Err(NoCap::Later);
    }
    let n = level.mesh.outgoing_halfedges(x).len();
    let masks = masks(n).ok_or(NoCap::Never)?;
    if cells.len() != n {
        return Err(count);
    }
    let tag_at: TagAt = cells.iter().copied().collect();
    let ((sectors, tags), centre, plane) = fan(masks, h, n, &tag_at)?;
    Ok(Some((Hole::untangented_dart(centre, sectors), plane, tags)))
}

/// The cap of the cone point `x` whose marked cells are `cells`
/// ([`Fan::Cone`](crate::bezier::g1::Fan)): `Ok(None)` when `x` is not a cone point
/// ([`cone_point`]), `count` when its faces are not exactly the cells. `fan` builds, from the
/// cone's sharp half-edge (if any) and `x`'s outgoing half-edges, a closed hole or a dart's fan
/// from the sharp edge, centred at `x` itself (the corner rule keeps it), every spoke tangent
/// zero.
pub(crate) fn cone_cap_by(
    level: &Level,
    x: usize,
    cells: &[(u32, Tag)],
    count: NoCap,
    fan: impl FnOnce(Option<u32>, &[u32], &TagAt) -> Result<SideFan, NoCap>,
) -> Result<Option<CapData>, NoCap> {
    let Some(sharp) = cone_point(level, x)? else {
        return Ok(None);
    };
    let m = &level.mesh;
    let hs = m.outgoing_halfedges(x);
    if cells.len() != hs.len() {
        return Err(count);
    }
    let tag_at: TagAt = cells.iter().copied().collect();
    let (sectors, tags) = fan(sharp, &hs, &tag_at)?;
    let centre = m.positions()[x];
    let hole = match sharp {
        Some(_) => Hole::untangented_dart(centre, sectors),
        None => Hole::untangented(centre, sectors),
    };
    Ok(Some((hole.into_cone(), [[0.0; 3]; 2], tags)))
}
