//! G^1 caps at Catmull-Clark's vertices next to OpenSubdiv hole faces.
//!
//! A hole face takes part in refinement but has no surface: the limit surface around an
//! interior vertex `x` with hole faces among its `m` quads is the smooth surface around `x`
//! with those sectors cut away. So each maximal run of `n < m` present quads between hole
//! faces is closed by an open fan over `2 pi n / m` ([`crate::bezier::g1::Hole::wedge`]): the
//! sectors of the closed cap's layout at the angles of the full turn, spokes `0` and `n` free
//! curves on the hole's border (C^1 to the ring's border curves at their ends through the
//! fixed outer layers), the G^1 relation on the `n - 1` inner spokes; **centre** `x`'s limit
//! point and **tangent plane** its eigen tangents, the smooth ones (a hole changes no rule),
//! shared by every run around `x`, so the runs meet at one point in one plane.

use super::super::Level;
use super::segment_across;
use crate::bezier::g1::Hole;
use crate::host::adaptive::{CapData, NoCap, Tag, quad_hole_segments, quad_sectors_around};
use crate::schemes::catmull_clark::crease::adaptive::{cap_feature, is_hole};
use crate::schemes::catmull_clark::{CatmullClark, LimitStencils};
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
    let m = &level.mesh;
    if m.is_boundary_vertex(x) {
        return Ok(None);
    }
    let hs = m.outgoing_halfedges(x);
    if !hs.iter().any(|&h| is_hole(level, m.he_face(h) as usize)) {
        return Ok(None);
    }
    match cap_feature(level, x) {
        Some(true) => return Err(NoCap::Later),
        Some(false) => return Err(NoCap::Never),
        None => {}
    }
    let n = hs.len();
    let all = quad_sectors_around(m, x as u32, m.he_face(hs[0]), n).ok_or(NoCap::Never)?;
    let hole: Vec<bool> = all
        .iter()
        .map(|s| is_hole(level, s.face as usize))
        .collect();
    let tag_at: HashMap<u32, Tag> = faces.iter().copied().collect();
    if faces.len() != hole.iter().filter(|&&h| !h).count() {
        return Err(NoCap::Never);
    }
    let pos = m.positions();
    let centre = limits.limit(x);
    let (t1, t2) = CatmullClark::tangent_stencils(m, x).ok_or(NoCap::Never)?;
    let plane = [t1.apply(pos), t2.apply(pos)];
    let mut caps = Vec::new();
    // each run starts after a hole face
    for start in (0..n).filter(|&s| !hole[s] && hole[(s + n - 1) % n]) {
        let run: Vec<_> = (0..n)
            .map(|i| all[(start + i) % n])
            .take_while(|sec| !is_hole(level, sec.face as usize))
            .collect();
        let tags = super::crease::sector_tags(&run, &tag_at)?;
        let sectors = quad_hole_segments(&run, |he, from| segment_across(level, he, from))?;
        caps.push((Hole::untangented_wedge(centre, sectors, n), plane, tags));
    }
    Ok(Some(caps))
}
