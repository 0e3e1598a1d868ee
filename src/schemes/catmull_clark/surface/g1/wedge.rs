//! G^1 caps at Catmull-Clark's vertices next to OpenSubdiv hole faces.
//!
//! A hole face takes part in refinement but has no surface: the limit surface around an
//! interior vertex `x` with hole faces among its `m` quads is the smooth surface around `x`
//! with those sectors cut away. So each maximal run of `n < m` present quads between hole
//! faces is closed by an open fan over `2 pi n / m` ([`crate::bezier::g1::Fan::Wedge`]): the
//! sectors of the closed cap's layout at the angles of the full turn, spokes `0` and `n` free
//! curves on the hole's border (C^1 to the ring's border curves at their ends through the
//! fixed outer layers), the G^1 relation on the `n - 1` inner spokes; **centre** `x`'s limit
//! point and **tangent plane** its eigen tangents, the smooth ones (a hole changes no rule),
//! shared by every run around `x`, so the runs meet at one point in one plane.
//!
//! A plain boundary vertex with hole faces among its `n` quads (OpenSubdiv's boundary mode
//! `none` makes the faces at its boundary vertices holes, beside boundary edges tagged sharp) is
//! the same at the open fan's angles: `pi / n` apart, so a run of `k` quads is `k` of the `2 n`
//! sectors of a wedge, centred at the boundary limit point in the boundary tangent plane (the
//! open fan's, [`super::hole_of`]).

use super::super::Level;
use super::{cap_centre, cap_plane, segment_across};
use crate::bezier::g1::Hole;
use crate::geom::Point;
use crate::host::adaptive::{
    CapData, NoCap, QuadSector, Tag, quad_hole_segments, quad_sectors_around, quad_sectors_open,
};
use crate::schemes::catmull_clark::{CatmullClark, LimitStencils};
use crate::schemes::sdc::crease::adaptive::{beside_holes, cap_feature, is_hole, present_runs};
use std::collections::HashMap;

/// The caps of the interior vertex `x` whose marked cells are `faces`: `Ok(None)` when no face
/// around `x` is a hole (the caller's plain cap applies), one wedge per run of present quads
/// (module documentation), or why there are none (`Later` while a semi-sharp feature is left
/// at `x` or a ring patch is missing, `Never` for other features or when the present quads are
/// not exactly the cells).
pub(in crate::schemes::catmull_clark::surface) fn wedge_caps(
    level: &Level,
    limits: &LimitStencils<'_>,
    x: usize,
    faces: &[(u32, Tag)],
) -> Result<Option<Vec<CapData>>, NoCap> {
    if !beside_holes(level, x)? {
        return Ok(None);
    }
    let m = &level.mesh;
    let n = m.valence(x);
    let f0 = m.he_face(m.vertex_halfedge(x));
    let all = quad_sectors_around(m, x as u32, f0, n).ok_or(NoCap::Never)?;
    let fan: Vec<u32> = all.iter().map(|sec| sec.face).collect();
    let runs = present_runs(level, &fan, faces.len()).ok_or(NoCap::Never)?;
    let pos = m.positions();
    let centre = limits.limit(x);
    let (t1, t2) = CatmullClark::tangent_stencils(m, x).ok_or(NoCap::Never)?;
    let plane = [t1.apply(pos), t2.apply(pos)];
    let runs = runs.iter().map(|run| run.iter().map(|&i| all[i]).collect());
    wedges(level, faces, runs, (centre, plane), n).map(Some)
}

/// One wedge per run of quads (`runs`, in fan order) of the `turn` sectors of a full turn,
/// all centred at `centre` in `plane`, with the tags of the marked cells `faces`.
fn wedges(
    level: &Level,
    faces: &[(u32, Tag)],
    runs: impl Iterator<Item = Vec<QuadSector>>,
    (centre, plane): (Point, [Point; 2]),
    turn: usize,
) -> Result<Vec<CapData>, NoCap> {
    let tag_at: HashMap<u32, Tag> = faces.iter().copied().collect();
    let mut caps = Vec::new();
    for run in runs {
        let tags = super::crease::sector_tags(&run, &tag_at)?;
        let sectors = quad_hole_segments(&run, |he, from| segment_across(level, he, from))?;
        caps.push((Hole::untangented_wedge(centre, sectors, turn), plane, tags));
    }
    Ok(caps)
}

/// The caps of the plain boundary vertex `x` whose marked cells are `faces`: `Ok(None)` when
/// no quad of its open fan is a hole, else one wedge per run of present quads (module
/// documentation); `Later` while a semi-sharp feature is left at `x`, `Never` for other
/// features or when the present quads are not exactly the cells.
pub(in crate::schemes::catmull_clark::surface) fn open_wedge_caps(
    level: &Level,
    limits: &LimitStencils<'_>,
    x: usize,
    faces: &[(u32, Tag)],
) -> Result<Option<Vec<CapData>>, NoCap> {
    let m = &level.mesh;
    let n = m.outgoing(x).count();
    let Some(all) = quad_sectors_open(m, x as u32, n) else {
        return Ok(None);
    };
    let present = all
        .iter()
        .filter(|s| !is_hole(level, s.face as usize))
        .count();
    if present == n {
        return Ok(None);
    }
    match cap_feature(level, x) {
        Some(true) => return Err(NoCap::Later),
        Some(false) => return Err(NoCap::Never),
        None => {}
    }
    if present != faces.len() {
        return Err(NoCap::Never);
    }
    let pos = m.positions();
    let centre = cap_centre(limits, m, x).apply(pos);
    let (t1, t2) = cap_plane(m, x).ok_or(NoCap::Never)?;
    let plane = [t1.apply(pos), t2.apply(pos)];
    // the runs between hole quads, from the boundary; the open fan is half a turn
    let runs = all
        .split(|s| is_hole(level, s.face as usize))
        .filter(|run| !run.is_empty())
        .map(<[QuadSector]>::to_vec);
    wedges(level, faces, runs, (centre, plane), 2 * n).map(Some)
}
