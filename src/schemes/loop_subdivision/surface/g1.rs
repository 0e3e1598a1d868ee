//! The G^1 cap of Loop's last ring.
//!
//! # The cap
//!
//! An extraordinary interior vertex `x` of valence `n` whose cells at the last level are the `n`
//! triangles of its fan, every outer edge of which is shared with an emitted (ring or regular)
//! quartic box-spline triangle of the same level, is closed by the triangle-layout G^1 cap of
//! [`crate::bezier::g1`]:
//!
//! * **hole data**: sector `s` is the fan triangle `[x, E_s, E_(s+1)]` (counter-clockwise, the
//!   faces' orientation), segment `s` its outer edge `E_s -> E_(s+1)`. The segment is read off
//!   the box-spline triangle `[E_(s+1), E_s, X]` across that edge exactly: its boundary is the
//!   triangle's quartic edge curve, its cross derivative the triangle's derivative in the
//!   barycentric direction from `X` to the edge's midpoint (`e_a / 2 + e_b / 2 - e_X`), the
//!   cubic `4 (b_(i+e_a) / 2 + b_(i+e_b) / 2 - b_(i+e_X))` over the edge's degree-3 indices
//!   `i`. In the lattice chart of the ring (the last level's triangles as unit triangles of a
//!   three-direction lattice, valid at every spoke end `E_s`: an edge point of valence 6) that
//!   is the derivative toward the centre required by [`crate::bezier::g1::hole`]. The spline's
//!   2-jet at a valence-6 vertex depends only on its one-ring, so the two segments meeting at a
//!   spoke end are compatible to rounding (also where two holes touch at a spoke end, as on the
//!   tetrahedron after one level); [`crate::bezier::g1::g1_cap_with`] checks every hole;
//! * **centre**: Loop's limit point of `x` (the smooth limit mask `1 - n chi`,
//!   `chi` per neighbour);
//! * **tangent plane**: spanned by Loop's tangent masks ([`super::super::limit::tangent_mask`],
//!   the left eigenvectors of the subdominant pair: `sum cos(2 pi i / n) p_i`,
//!   `sum sin(2 pi i / n) p_i` over the one-ring); the spoke tangents' scale from the ring's
//!   chart in that plane ([`crate::bezier::g1::ring::chart_tangents`]);
//! * **layout, conditions, free parameters**: the hole is split into `n` kites
//!   (`Hole::to_quad_layout`): cap patch `s` is the kite `x, M_s, E_(s+1), M_(s+1)` (`M_s`
//!   the midpoint of segment `s`), covering the half of fan triangle `s` beside `E_(s+1)` and the
//!   half of fan triangle `s + 1` beside `E_(s+1)`, with `(0, 0)` at the centre, spoke `v = 0`
//!   toward `M_s`. The conditions are those of [`crate::bezier::g1`] with the kites' spoke-end
//!   twist `kappa = 1`: C^1 to the ring (the two outer layers exact), centre and tangent plane,
//!   C^0 and the G^1 relation along every spoke, the quadratic jet at the centre where the
//!   degree allows it; the remaining coefficients minimise the fairness functional `F_4`.
//!   Degree: the lowest certified, bi-4 for odd `n` (and `n = 4`), bi-5 for even `n != 4`.
//!
//! * **spoke tangents' scale**: the cubic spoke model of
//!   [`crate::bezier::g1::ring::chart_tangents`] for triangle holes, `(3 e_s - f_s) / 2`.
//!   Measured on a saddle fan (interior vertex of valence `n` in a ring of triangles, 4 rings),
//!   Gauss curvature of the cap against the last ring's:
//!
//!   | `n` | quadratic `2 e - f` | cubic `(3 e - f) / 2` | last ring |
//!   | --- | --- | --- | --- |
//!   | 3 | `[-1.4e5, 2.3e6]` | `[-4.0, 116]` | `[-14, 20]` |
//!   | 4 | `[-0.12, 0.21]` | `[-0.12, 0.24]` | `[-0.30, 0.29]` |
//!   | 5 | `[-0.107, 0.013]` | `[-0.104, 0.016]` | `[-0.20, 0.09]` |
//!   | 7 | `[-1.17, -0.36]` | `[-1.37, -0.44]` | `[-0.79, -0.27]` |
//!   | 8 | `[-2.05, 0.56]` | `[-2.48, 0.025]` | `[-1.29, -0.27]` |
//!
//!   At `n = 3` Loop's subdominant eigenvalue is `1/4`, the ring's spokes grow like `r^2` and
//!   the quadratic model's centre derivative vanishes; elsewhere the two are alike.
//!
//! The kites are evaluated at face parameters by inverting their bilinear map in the fan
//! triangle's lattice chart ([`crate::surface::eval`]); each kite carries the domain of fan
//! triangle `s` with the centre's corner as its `rot`.
//!
//! # Extraordinary boundary vertices: open fans
//!
//! A boundary vertex `x` of `k != 3` triangles (three is Loop's regular boundary) under the
//! plain boundary rule (no sharpness of its own, no sharp edge inside the surface) is closed by
//! the open-fan cap of [`crate::bezier::g1`] ([`crate::bezier::g1::Layout::OpenTriangle`]):
//!
//! * **hole data**: the fan triangles from the outgoing boundary half-edge counter-clockwise,
//!   each segment read off the triangle across its outer edge as above; the spoke ends `E_0`,
//!   `E_k` must be regular boundary vertices (three triangles) under the plain rule, the inner
//!   ones interior lattice points;
//! * **centre**: Loop's limit point of `x`, the boundary curve's `(p_0 + 4 x + p_k) / 6` (a
//!   vertex of one triangle is a corner and stays put);
//! * **tangent plane**: Loop's boundary eigen tangents
//!   ([`crate::schemes::loop_subdivision::limit`]): `p_0 - p_k` along the boundary and the left
//!   eigenvector across it (eigenvalue `3/8 + cos(pi / k) / 4`); at a corner the two boundary
//!   edges;
//! * **layout**: every fan triangle one cap patch with a straight corner at its outer edge's
//!   midpoint (no kites: they would leave half-triangles at the boundary spokes), `k + 1` spokes
//!   over a half-turn (a quarter-turn for a corner), the G^1 relation with `w(1) = -1/2`,
//!   `kappa = 3/2` on the inner spokes; bi-5 (bi-4 for a corner).
//!
//! Measured with `fairsub check` at 3 rings: G^1 between the pieces and to the ring at most
//! 4.3e-13 rad on the two triangulations of the L-shape (the fill measured 1.8e-2 between its
//! pieces and 1.6e-4 to the ring); `tests/it/loop_boundary_caps.rs` covers fans of 1, 2, 4, 5, 6
//! and 7 triangles.
//!
//! # Holes that wait or keep the fill
//!
//! Holes whose ring is not complete after the requested rings (at `--rings 0` the spoke ends
//! are input vertices, which need not be regular; another hole's cells next to it) get up to
//! [`MAX_EXTRA_CAP_LEVELS`](crate::host::adaptive::MAX_EXTRA_CAP_LEVELS) more levels, as do holes whose spoke ends have a sharp feature (a
//! crease through the one-ring: the holes shrink away from it). A centre whose features are
//! all semi-sharp is refined until they are spent (up to level
//! [`SPENT_BY_LEVEL`](crate::schemes::sdc::crease::adaptive::SPENT_BY_LEVEL)), then
//! capped as a plain vertex. A crease vertex gets one open triangle fan per side of two or of
//! four and more triangles ([`crease_caps`]: Catmull-Clark's construction of
//! `catmull_clark::surface::g1::crease` on triangles; each side refines as a boundary fan
//! under OpenSubdiv's crease rules). A dart (one infinitely sharp edge ending at an interior
//! vertex) gets one open triangle fan over the full turn from its sharp edge ([`dart_cap`],
//! [`Fan::Dart`]), centred at the dart's own limit point
//! ([`crate::schemes::loop_subdivision::dart`]). A corner with sharp edges gets one open
//! triangle fan per side of two or more triangles between them ([`corner_caps`]), each run of
//! triangles between OpenSubdiv hole faces one at the full turn's angles ([`wedge_caps`]).
//! A cone point (a corner no two sharp edges cut) gets a closed cap or a dart's fan with zero
//! spoke tangents ([`cone_cap`]). Holes that never have the data (a fan that does not close,
//! still incomplete after the extra levels) keep the C^0 Hermite fill of
//! [`super`].

use super::{Level, is_regular, tri_index, trusted_net};
use crate::bezier::complex::PatchComplex;
use crate::bezier::g1::{Hole, Segment};
use crate::geom::{axpy, scale, sub};
use crate::host::adaptive::{CapData, NoCap, Tag, caps_waiting, fan_centre, g1_cap_elements};
use crate::host::fans::fan_walk;
use crate::mesh::{Element, PolyMesh};
use crate::schemes::common::sin_2pi;
use crate::schemes::loop_subdivision::Rules;
use crate::schemes::loop_subdivision::dart::dart_masks;
use crate::schemes::loop_subdivision::limit::{across_weights, tangent_rows};
use crate::schemes::sdc::crease::adaptive::{
    SideFan, TagAt, beside_holes, cap_feature, cone_cap_by, corner_caps_by, crease_caps_by,
    dart_cap_by, is_plain_boundary, is_special, present_runs,
};
use std::collections::HashMap;

/// The segment of the hole along the outer edge `from -> to` of a fan triangle, read off the
/// emitted triangle across it (see the [module](self) documentation); `None` at the boundary
/// or while that triangle is not emitted.
fn segment_across(level: &Level, he: u32) -> Option<Segment> {
    let m = &level.mesh;
    let h = m.he_twin(he)?;
    let g = m.he_face(h) as usize;
    let tri = trusted_net(level, g)?;
    // the twin runs E_(s+1) -> E_s: corner kb = E_(s+1), ka = E_s, kx the apex
    let kb = (h - m.face_halfedge(g)) as usize;
    let (ka, kx) = ((kb + 1) % 3, (kb + 2) % 3);
    let at = |a: usize, b: usize, x: usize| {
        let mut idx = [0usize; 3];
        idx[ka] = a;
        idx[kb] = b;
        idx[kx] = x;
        tri[tri_index(idx[0], idx[1], idx[2])]
    };
    let boundary = (0..=4).map(|r| at(4 - r, r, 0)).collect();
    let cross = (0..=3)
        .map(|r| {
            let (a, b) = (3 - r, r);
            let mid = scale(axpy(at(a + 1, b, 0), 1.0, at(a, b + 1, 0)), 2.0);
            axpy(mid, -4.0, at(a, b, 1))
        })
        .collect();
    Some(Segment { boundary, cross })
}

/// The hole of one element, two vectors spanning its limit tangent plane and the tags of its
/// sectors (each fan triangle's domain with the centre's corner as `rot`), or why there is
/// none.
fn hole_of(level: &Level, element: Element, cells: &[(u32, Tag)]) -> Result<CapData, NoCap> {
    let m = &level.mesh;
    let (f0, _) = cells[0];
    let (x, n, open) = fan_centre(m, &level.info, element, f0, 1)?;
    let xu = x as usize;
    match cap_feature(level, xu) {
        Some(true) => return Err(NoCap::Later),
        Some(false) => return Err(NoCap::Never),
        None if !level.info[xu].fan_ok => return Err(NoCap::Never),
        None => {}
    }
    let fan = if open {
        fan_open(m, x, n)
    } else {
        fan_around(m, x, f0, n)
    }
    .ok_or(NoCap::Never)?;
    let tag_at: HashMap<u32, Tag> = cells.iter().copied().collect();
    if cells.len() != n {
        return Err(NoCap::Later);
    }
    let (sectors, tags) = fan_sectors(
        level,
        &fan,
        &tag_at,
        if open { Ends::Open } else { Ends::Closed },
    )?;
    let pos = m.positions();
    // the centre has no feature: the plain limit mask (the boundary curve's at a boundary
    // vertex), the plane spanned by Loop's eigen tangents (across the boundary at an open fan)
    let centre = Rules::plain(m).limit_stencil(xu).apply(pos);
    let mut plane = [[0.0; 3]; 2];
    tangent_rows(m, xu, |k, p, w| {
        plane[k] = axpy(plane[k], w, pos[p as usize])
    });
    let hole = if open {
        Hole::untangented_open(centre, sectors)
    } else {
        Hole::untangented(centre, sectors)
    };
    Ok((hole, plane, tags))
}

/// Which spoke ends of a fan [`fan_sectors`] checks for the lattice the cap's layout assumes.
#[derive(Clone, Copy, PartialEq)]
enum Ends {
    /// Every spoke end an interior regular vertex without a feature.
    Closed,
    /// The inner ones so, the first and last regular boundary vertices under the plain rule.
    Open,
    /// The inner ones so; the first and last lie on a crease, regular on the fan's side when
    /// the ring triangles beside them are regular patches (their segments exist).
    Crease,
    /// Every spoke end, the first and last included, an interior regular vertex without a
    /// feature (a run of triangles between hole faces, [`wedge_caps`]).
    Wedge,
}

/// The segments and cap tags of a fan's triangles (`(face, corner of x)` counter-clockwise),
/// or `NoCap::Later` while a spoke end is not a regular lattice point ([`Ends`]) or a segment's
/// ring patch is missing.
fn fan_sectors(
    level: &Level,
    fan: &[(u32, usize)],
    tag_at: &HashMap<u32, Tag>,
    ends: Ends,
) -> Result<(Vec<Vec<Segment>>, Vec<Tag>), NoCap> {
    let m = &level.mesh;
    let n = fan.len();
    let mut tags = Vec::with_capacity(n);
    let mut sectors = Vec::with_capacity(n);
    for (s, &(f, corner)) in fan.iter().enumerate() {
        let tag = *tag_at.get(&f).ok_or(NoCap::Later)?;
        tags.push(Tag {
            domain: tag.domain.rotated(corner as u32),
            ..tag
        });
        let outer = m.face_halfedge(f as usize) + ((corner + 1) % 3) as u32;
        let mut spoke_ends = vec![(s, m.he_from(outer) as usize)];
        if ends != Ends::Closed && s + 1 == n {
            // the last sector of an open fan: its outer edge ends on the boundary too
            spoke_ends.push((n, m.he_to(outer) as usize));
        }
        for (k, y) in spoke_ends {
            // inner spoke ends: interior lattice points; the boundary spokes' ends (open fan):
            // regular boundary vertices under the plain boundary rule
            let ok = match ends {
                Ends::Crease if k == 0 || k == n => true,
                _ if m.is_boundary_vertex(y) => {
                    ends == Ends::Open && is_regular(m, y) && is_plain_boundary(level, y)
                }
                _ => is_regular(m, y) && !is_special(level, y),
            };
            if !ok {
                return Err(NoCap::Later);
            }
        }
        sectors.push(vec![segment_across(level, outer).ok_or(NoCap::Later)?]);
    }
    Ok((sectors, tags))
}

/// The caps of the crease vertex `x` whose marked cells are `cells` (Catmull-Clark's
/// construction, `catmull_clark::surface::g1::crease`, on triangles): `Ok(None)` when `x` is
/// not a crease vertex; one open triangle fan ([`Fan::Crease`]) per side of one, two, or four
/// and more triangles, centred at the crease's limit point `(e_a + 4 x + e_b) / 6`, `T0 = (e_a -
/// e_b) / 2` the crease's exact derivative, the across tangent Loop's boundary eigen tangent of
/// the side's `k` triangles ([`across_weights`]); a side of three triangles is regular crease
/// patches.
fn crease_caps(
    level: &Level,
    x: usize,
    cells: &[(u32, Tag)],
) -> Result<Option<Vec<CapData>>, NoCap> {
    let m = &level.mesh;
    let pos = m.positions();
    crease_caps_by(level, x, cells, 3, |tag_at, (ha, hb, k)| {
        let (_, fan) = side_fan(level, x, ha, k, tag_at)?;
        // the side's neighbours e_0 .. e_k counter-clockwise: e_0 ends ha, e_k ends hb
        let e = |h: u32| pos[m.he_to(h) as usize];
        let (a, b) = across_weights(k);
        let mut across = axpy(axpy(scale(pos[x], a), b, e(ha)), b, e(hb));
        let mut h = ha;
        for i in 1..k {
            h = m.he_twin(m.he_prev(h)).ok_or(NoCap::Never)?;
            across = axpy(across, sin_2pi(i as i64, 2 * k as i64), e(h));
        }
        if k == 1 {
            // one triangle (its spokes the crease's halves, `T1 = -T0`): only its side of
            // the plane matters
            across = sub(axpy(e(ha), 1.0, e(hb)), scale(pos[x], 2.0));
        }
        Ok((fan, across))
    })
}

/// The `k` triangles `(face, corner of x)` from the face of `ha` around `x` (a crease or
/// corner side, or a dart's full turn: [`Ends::Crease`]), with their hole segments and cap
/// tags.
fn side_fan(
    level: &Level,
    x: usize,
    ha: u32,
    k: usize,
    tag_at: &TagAt,
) -> Result<(Vec<(u32, usize)>, SideFan), NoCap> {
    let m = &level.mesh;
    let fan = tri_fan(m, x as u32, m.he_face(ha), k, None).ok_or(NoCap::Never)?;
    let sides = fan_sectors(level, &fan, tag_at, Ends::Crease)?;
    Ok((fan, sides))
}

/// The cap of the dart `x` whose marked cells are `cells` (Catmull-Clark's construction,
/// `catmull_clark::surface::g1::crease::dart_cap`, on triangles): `Ok(None)` when `x` is not a
/// dart; one open triangle fan over the full turn ([`Fan::Dart`]) from the sharp edge (its
/// spokes `0` and `n`, one Hermite cubic), centred at the dart's own limit point in the plane of
/// its own eigen tangents ([`dart_masks`]).
fn dart_cap(level: &Level, x: usize, cells: &[(u32, Tag)]) -> Result<Option<CapData>, NoCap> {
    dart_cap_by(
        level,
        x,
        cells,
        dart_masks,
        NoCap::Later,
        |masks, h, n, tag_at| {
            let (fan, sides) = side_fan(level, x, h, n, tag_at)?;
            let m = &level.mesh;
            let pos = m.positions();
            // the masks' points: x, e_0 .. e_(n-1) (each fan triangle's corner after x)
            let ring: Vec<_> = std::iter::once(pos[x])
                .chain(
                    fan.iter()
                        .map(|&(f, c)| pos[m.face(f as usize)[(c + 1) % 3] as usize]),
                )
                .collect();
            let (centre, plane) = masks.apply(&ring);
            Ok((sides, centre, plane))
        },
    )
}

/// The cap of the cone point `x` whose marked cells are `cells` (Catmull-Clark's
/// construction, `catmull_clark::surface::g1::crease::cone_cap`, on triangles): `Ok(None)` when
/// `x` is not a cone point; a closed triangle hole, or an open triangle fan over the full turn
/// from its one sharp edge, centred at `x` (the corner rule keeps it), every spoke tangent zero
/// ([`Fan::Cone`]).
fn cone_cap(level: &Level, x: usize, cells: &[(u32, Tag)]) -> Result<Option<CapData>, NoCap> {
    cone_cap_by(level, x, cells, NoCap::Later, |sharp, hs, tag_at| {
        let m = &level.mesh;
        let n = hs.len();
        let (fan, ends) = match sharp {
            Some(h) => (tri_fan(m, x as u32, m.he_face(h), n, None), Ends::Crease),
            None => (fan_around(m, x as u32, m.he_face(hs[0]), n), Ends::Closed),
        };
        fan_sectors(level, &fan.ok_or(NoCap::Never)?, tag_at, ends)
    })
}

/// The caps of the interior vertex `x` whose marked cells are `cells` next to OpenSubdiv hole
/// faces (Catmull-Clark's construction, `catmull_clark::surface::g1::wedge`, on triangles):
/// `Ok(None)` when no triangle around `x` is a hole; one open triangle fan ([`Fan::Wedge`])
/// per run of `k` present triangles between holes, over `2 pi k / n`, its first and last
/// spokes free on the holes' border, centred at `x`'s plain limit point in the plane of its
/// eigen tangents (a hole changes no rule).
fn wedge_caps(
    level: &Level,
    x: usize,
    cells: &[(u32, Tag)],
) -> Result<Option<Vec<CapData>>, NoCap> {
    if !beside_holes(level, x)? {
        return Ok(None);
    }
    let m = &level.mesh;
    let n = m.valence(x);
    let all = fan_around(m, x as u32, m.he_face(m.vertex_halfedge(x)), n).ok_or(NoCap::Never)?;
    let fan: Vec<u32> = all.iter().map(|&(f, _)| f).collect();
    let runs = present_runs(level, &fan, cells.len()).ok_or(NoCap::Later)?;
    let tag_at: HashMap<u32, Tag> = cells.iter().copied().collect();
    let pos = m.positions();
    let centre = Rules::plain(m).limit_stencil(x).apply(pos);
    let mut plane = [[0.0; 3]; 2];
    tangent_rows(m, x, |k, p, w| {
        plane[k] = axpy(plane[k], w, pos[p as usize])
    });
    let mut caps = Vec::new();
    for run in runs {
        let run: Vec<(u32, usize)> = run.into_iter().map(|i| all[i]).collect();
        let (sectors, tags) = fan_sectors(level, &run, &tag_at, Ends::Wedge)?;
        caps.push((Hole::untangented_wedge(centre, sectors, n), plane, tags));
    }
    Ok(Some(caps))
}

/// The caps of the corner `x` whose marked cells are `cells` (Catmull-Clark's construction,
/// `catmull_clark::surface::g1::crease::corner_caps`, on triangles): `Ok(None)` when `x` is not
/// a corner with sharp edges; one open triangle fan ([`Fan::Corner`]) per side between
/// consecutive sharp edges (one triangle included: its spokes `T0` and `T1` themselves),
/// centred at `x` in the plane of the sharp edges' derivatives ([`corner_plane`]).
fn corner_caps(
    level: &Level,
    x: usize,
    cells: &[(u32, Tag)],
) -> Result<Option<Vec<CapData>>, NoCap> {
    corner_caps_by(level, x, cells, usize::MAX, |tag_at, (ha, _, k)| {
        Ok(side_fan(level, x, ha, k, tag_at)?.1)
    })
}

/// The holes of one element: those of a crease vertex's sides ([`crease_caps`]), of a dart
/// ([`dart_cap`]), of a corner's sides ([`corner_caps`]), of a cone point ([`cone_cap`]) or of
/// the runs of triangles between hole faces ([`wedge_caps`]), else the
/// one of [`hole_of`].
fn holes_of(level: &Level, element: Element, cells: &[(u32, Tag)]) -> Result<Vec<CapData>, NoCap> {
    let (x, _, open) = fan_centre(&level.mesh, &level.info, element, cells[0].0, 1)?;
    if !open && let Some(caps) = crease_caps(level, x as usize, cells)? {
        return Ok(caps);
    }
    if !open && let Some(cap) = dart_cap(level, x as usize, cells)? {
        return Ok(vec![cap]);
    }
    if !open && let Some(caps) = corner_caps(level, x as usize, cells)? {
        return Ok(caps);
    }
    if !open && let Some(cap) = cone_cap(level, x as usize, cells)? {
        return Ok(vec![cap]);
    }
    if !open && let Some(caps) = wedge_caps(level, x as usize, cells)? {
        return Ok(caps);
    }
    hole_of(level, element, cells).map(|c| vec![c])
}

/// The `n` triangles around vertex `x` counter-clockwise from face `f0`, each with the corner of
/// `x` in it, or `None` when one is not a triangle or the walk does not close after `n` faces.
fn fan_around(m: &PolyMesh, x: u32, f0: u32, n: usize) -> Option<Vec<(u32, usize)>> {
    tri_fan(m, x, f0, n, Some(false))
}

/// The `n` triangles around boundary vertex `x` counter-clockwise from its outgoing boundary
/// half-edge, each with the corner of `x` in it, or `None` when one is not a triangle or the
/// fan does not end on the boundary after `n` faces.
fn fan_open(m: &PolyMesh, x: u32, n: usize) -> Option<Vec<(u32, usize)>> {
    let h = m.vertex_halfedge(x as usize);
    if m.he_twin(h).is_some() {
        return None;
    }
    tri_fan(m, x, m.he_face(h), n, Some(true))
}

/// The walk of [`fan_around`] (`open = Some(false)`: closing at `f0`), [`fan_open`]
/// (`Some(true)`: ending at the boundary) and of a crease vertex's side (`None`: `n` faces).
fn tri_fan(
    m: &PolyMesh,
    x: u32,
    f0: u32,
    n: usize,
    open: Option<bool>,
) -> Option<Vec<(u32, usize)>> {
    fan_walk(m, x, f0, n, open, 3)
}

/// Whether some marked element would get its cap after more levels.
pub(super) fn waiting(level: &Level, marked: &[(u32, Tag)]) -> bool {
    caps_waiting(marked, |e, cells| holes_of(level, e, cells))
}

/// Caps every element of the marked cells that has its hole data; returns the cells left for
/// the Hermite fill.
pub(super) fn g1_caps(
    level: &Level,
    marked: &[(u32, Tag)],
    out: &mut PatchComplex,
) -> Vec<(u32, Tag)> {
    g1_cap_elements(marked, out, |e, cells| {
        holes_of(level, e, cells).unwrap_or_default()
    })
}
