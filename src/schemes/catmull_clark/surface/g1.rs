//! The G^1 cap of Catmull-Clark's last ring (and of the fallback vertices of the cap schemes
//! EG, QAS+ and guided subdivision, which run on this loop).
//!
//! # The cap
//!
//! An extraordinary element whose faces at the last level are the `n` quads around one interior
//! vertex `x` (an input vertex of valence `n`, or the centre of an input `n`-gon from level 1
//! on), every one of whose two outer edges is shared with an emitted (ring or regular) bi-3
//! patch of the same level, is closed by the G^1 cap of [`crate::bezier::g1`]:
//!
//! * **hole data**: sector `s` is the face `[x, p, K, q]`, spoke `s` its edge `x -> p`; segment
//!   `a` is the side `p -> K` of the ring patch across that edge and its derivative out of that
//!   patch, segment `b` the side `q -> K` of the ring patch across it. The ring patches are the
//!   exact bi-3 limit patches of faces of the same level, so the data are exact and C^2
//!   compatible at every spoke end and corner (all of them are regular vertices of the limit);
//! * **centre**: Catmull-Clark's limit point of `x` ([`LimitStencils`]);
//! * **tangent plane**: spanned by the two eigen tangents of Halstead et al.
//!   ([`CatmullClark::tangent_stencils`]); the spoke tangents' scale from the ring's chart in
//!   that plane ([`crate::bezier::g1::ring::chart_tangents`]);
//! * **conditions, free parameters**: those of [`crate::bezier::g1`]: C^1 to the ring (the two
//!   outer layers exact), the centre and tangent plane, C^0 and the G^1 relation along every
//!   spoke, the quadratic jet at the centre where the degree allows it; the remaining
//!   coefficients minimise the fairness functional `F_4`. Degree: the lowest certified, bi-4
//!   for odd `n`, bi-5 for even `n != 4` (bi-4 at `n = 4`, where the cap is the regular case).
//!
//! # Valence 2
//!
//! An interior vertex of two quads (a pentagon's vertex after the first step, a pillow's
//! corners) is closed by the half-plane cap of two bi-5 patches ([`crate::bezier::g1`], "Two
//! sectors"). Its data are those above; its centre and plane come from the local matrix on
//! `v`, `e_0, e_1`, `f_0, f_1` (this 1-ring is invariant at valence 2: the new face points,
//! edge points and vertex use only its points; every edge at `v` lies on both faces). In the
//! antisymmetric modes `e_0 - e_1` and `f_0 - f_1` the step is `1/4` times the identity: a
//! double subdominant eigenvalue 1/4, both differences left eigenvectors, and they span the
//! cap's plane (`cap_plane`; Halstead's masks, which take `cos(2 pi i / n)` and
//! `cos(pi / n)`, vanish at `n = 2`). On the means `v, (e_0 + e_1) / 2, (f_0 + f_1) / 2` the
//! step is `[1, 6, 1; 3, 4, 1; 2, 4, 2] / 8`, eigenvalues 1, 1/8 and -1/4, the left
//! eigenvector of 1 being `(4 v + 4 (e_0 + e_1) + f_0 + f_1) / 14`: the general mask
//! `(n^2 v + 4 sum e + sum f) / (n (n + 5))` at `n = 2`, the point the rings converge to and
//! the cap's centre (`cap_centre`). The limit stencil of [`LimitStencils`] keeps the vertex
//! itself there, as OpenSubdiv's does (it treats valence 2 as a corner), 5e-5 off at 6 rings
//! of the split-edge cube. The eigenvalue -1/4 has the subdominant modulus, so the limit has no
//! tangent plane at a valence-2 vertex: the ring normals oscillate by up to 0.18 rad at every
//! scale (measured with `eval` on [`crate::gallery::split_edge_cube`] from `1e-2` to `1e-6` of
//! a face). The cap is nevertheless G^1 at every join and at its centre (`check`: 2.0e-13 rad
//! at 3 rings, 2.5e-11 at 6), C^1 to the last ring, in the plane of the two subdominant modes.
//! EG, QAS+ and guided subdivision run Catmull-Clark's rings at valence 2 and get this cap.
//!
//! # Extraordinary boundary vertices: open fans
//!
//! A plain boundary vertex `x` of `k >= 3` quads (no sharpness of its own, no sharp edge
//! inside the surface: the boundary crease rule) is closed by the open-fan cap
//! ([`crate::bezier::g1::Layout::OpenQuad`]): the sectors are its `k` quads counter-clockwise
//! from its boundary half-edge, spokes `0` and `k` its boundary edges (free curves of the
//! surface's boundary, C^1 to the ring's boundary curves at their ends through the fixed outer
//! layers), the G^1 relation on the `k - 1` inner spokes with `w(0) = 2 cos(pi / k)`;
//! **centre** the limit point of the boundary curve, `(e_0 + 4 x + e_k) / 6`; **tangent
//! plane** spanned by the boundary curve's tangent `e_0 - e_k` and the subdominant eigen
//! tangent across the boundary
//! ([`crate::schemes::catmull_clark::boundary_tangent`]). Bi-4 for every `k`, tangent plane
//! only (no jet: [`crate::bezier::g1`], "Open fans"). Measured by `check` at 3 rings: 2.4e-14 rad between the cap's
//! pieces on an L-shaped grid (`k = 3`; the fill measured 6.9e-3), 1.1e-13 on `cnet-5-saddle`
//! with a face removed at its centre (0.34 with the fill), 1.1e-14 on OpenSubdiv's
//! `cc_boundary_valences` (`k = 3, 5`; 0.10 with the fill); the cap joins the ring C^1
//! (`tests/it/boundary_caps.rs`).
//!
//! Elements whose hole does not have these data after the requested rings (the faces of two
//! elements still touch, as the cube's after one ring) get up to [`MAX_EXTRA_CAP_LEVELS`](crate::host::adaptive::MAX_EXTRA_CAP_LEVELS) more
//! levels: their rings continue until the holes are separated by ring patches. A centre whose
//! features are all semi-sharp is refined until they are spent (up to level
//! [`SPENT_BY_LEVEL`](crate::schemes::sdc::crease::adaptive::SPENT_BY_LEVEL)), then
//! capped as a plain vertex. A crease vertex (two infinitely sharp edges through an interior
//! vertex) gets one open-fan cap per side of one, or of three or more quads, sharing the
//! crease's exact curve ([`crease`]). A dart (one infinitely sharp edge ending at an interior
//! vertex) gets one fan cap over the full turn from its sharp edge, which is its only C^0
//! spoke, centred at the dart's own limit point in its own tangent plane
//! ([`crate::schemes::catmull_clark::dart`], [`crate::bezier::g1::Fan::Dart`]). A corner with
//! sharp edges gets one open fan per side of two or more quads between them, its sharp spokes
//! the edges' exact curves ([`crease::corner_caps`]); each run of quads between OpenSubdiv hole
//! faces one open fan at the full turn's angles, at a boundary vertex at the open fan's
//! ([`wedge`]). A cone point (a vertex of
//! sharpness infinity without two sharp edges) gets a closed cap, or a dart's fan along its one
//! sharp edge, centred at the vertex with zero spoke tangents ([`crease::cone_cap`],
//! [`crate::bezier::g1::Fan::Cone`]). Elements that never have the data (boundary vertices of more than
//! [`crate::bezier::g1::MAX_CAP_VALENCE`] quads, `--rings 0` around an n-gon) keep the
//! Hermite-Coons fill of [`super`] (C^0).

mod crease;
mod wedge;

use super::{Level, regular_patch};
use crate::bezier::complex::PatchComplex;
use crate::bezier::g1::ring::{quad_edge_side, segment_from_ring};
use crate::bezier::g1::{Hole, Segment};
use crate::bezier::{BezierPatch, Side};
use crate::host::adaptive::{
    CapData, NoCap, QuadSector, Tag, caps_waiting, fan_centre_from, g1_cap_elements,
    quad_hole_segments, quad_sectors_around, quad_sectors_open,
};
use crate::mesh::{Element, PolyMesh};
use crate::schemes::catmull_clark::{CatmullClark, LimitStencils};
use crate::stencil::{Stencil, linear_weights};
use std::collections::HashMap;
use std::sync::OnceLock;

/// Rows of weights, one `(index, weight)` list per row (stencils over a level's points, or
/// weights over a patch's coefficients).
pub(super) type Rows = Vec<Vec<(u32, f64)>>;

/// Corner index of `v` in face `f`.
fn corner_of(m: &PolyMesh, f: usize, v: u32) -> Option<usize> {
    m.face(f).iter().position(|&w| w == v)
}

/// The segment of the hole along the hole face's half-edge `hole_he`, starting at its end
/// `from`: the side of the emitted patch of the face across that edge, from `from` to the other
/// end, with its outward derivative (`None` at the boundary or while that face has no trusted
/// regular patch). The face across is found through the twin, in O(1) at any valence.
fn segment_across(level: &Level, hole_he: u32, from: u32) -> Option<Segment> {
    let (g, side, range) = across(level, hole_he, from)?;
    let ring = regular_patch(level, g)?;
    Some(segment_from_ring(&ring, side, range, 1.0))
}

/// The face across the hole half-edge `hole_he` and the side and range of its patch that give
/// the segment starting at `from`.
fn across(level: &Level, hole_he: u32, from: u32) -> Option<(usize, Side, [f64; 2])> {
    let m = &level.mesh;
    let h = m.he_twin(hole_he)?;
    let forward = m.he_from(h) == from;
    let g = m.he_face(h) as usize;
    let k = corner_of(m, g, m.he_from(h))?;
    let (side, range) = quad_edge_side(k, forward);
    Some((g, side, range))
}

/// The rows of [`segment_across`] over the level's points (boundary, then cross), its weights
/// read off [`segment_from_ring`] itself; `patch_rows` gives a regular face's coefficient rows.
fn segment_rows(
    level: &Level,
    hole_he: u32,
    from: u32,
    patch_rows: &impl Fn(usize) -> Option<Rows>,
) -> Option<Rows> {
    let (g, side, range) = across(level, hole_he, from)?;
    let cps = patch_rows(g)?;
    let weights = segment_weights(side, range);
    Some(
        weights
            .iter()
            .map(|w| {
                w.iter()
                    .flat_map(|&(c, x)| cps[c as usize].iter().map(move |&(v, y)| (v, x * y)))
                    .collect()
            })
            .collect(),
    )
}

/// The weights of [`segment_from_ring`] (boundary, then cross coefficients) over the 16
/// coefficients of a bi-3 ring patch, for the side and range [`quad_edge_side`] gives: read off
/// the segment code once per process for each of the 8 (side, direction) pairs, not once per
/// segment of every cap.
fn segment_weights(side: Side, range: [f64; 2]) -> &'static [Vec<(u32, f64)>] {
    static WEIGHTS: OnceLock<Vec<Rows>> = OnceLock::new();
    let all = WEIGHTS.get_or_init(|| {
        let mut all = Vec::with_capacity(8);
        for side in Side::ALL {
            for range in [[0.0, 1.0], [1.0, 0.0]] {
                all.push(linear_weights(16, |pts| {
                    let p = BezierPatch {
                        deg_u: 3,
                        deg_v: 3,
                        cps: pts.to_vec(),
                        weights: None,
                    };
                    let s = segment_from_ring(&p, side, range, 1.0);
                    [s.boundary, s.cross].concat()
                }));
            }
        }
        all
    });
    debug_assert!(range == [0.0, 1.0] || range == [1.0, 0.0]);
    &all[2 * side.index() + usize::from(range[0] > range[1])]
}

/// Whether `x` is an interior vertex of exactly two faces, both quads: the centre of a
/// half-plane cap ([`crate::bezier::g1`], "Two sectors").
fn two_quads(m: &PolyMesh, x: usize) -> Option<[u32; 2]> {
    if m.is_boundary_vertex(x) {
        return None;
    }
    match m.outgoing_halfedges(x)[..] {
        [a, b]
            if [a, b]
                .iter()
                .all(|&h| m.face_size(m.he_face(h) as usize) == 4) =>
        {
            Some([a, b])
        }
        _ => None,
    }
}

/// The centre of `x`'s cap: its limit point ([`LimitStencils`]), except at an interior vertex
/// of two quads, whose limit stencil is the vertex itself (as OpenSubdiv's, which treats it as a
/// corner) while the rings converge to the eigen limit `(4 v + 4 (e_0 + e_1) + f_0 + f_1) / 14`:
/// the left eigenvector of eigenvalue 1 of the local matrix on `v, e_i, f_i`, which `n^2 v + 4
/// sum e + sum f` over `n (n + 5)` continues to `n = 2` (derivation in the module
/// documentation, "Valence 2").
fn cap_centre(limits: &LimitStencils<'_>, m: &PolyMesh, x: usize) -> Stencil {
    match two_quads(m, x) {
        Some(hs) => {
            let mut s = Stencil::new();
            s.add(x, 4.0 / 14.0);
            for h in hs {
                s.add(m.he_to(h) as usize, 4.0 / 14.0)
                    .add(opposite(m, h), 1.0 / 14.0);
            }
            s.merged()
        }
        None => limits.stencil(x),
    }
}

/// The corner of the face of `x`'s outgoing half-edge `h` opposite `x` (a quad's).
fn opposite(m: &PolyMesh, h: u32) -> usize {
    m.he_from(m.he_next(m.he_next(h))) as usize
}

/// The two vectors that span the plane of `x`'s cap: the limit tangents
/// ([`CatmullClark::tangent_stencils`]), except at an interior vertex of two quads, where
/// Halstead's masks vanish: there `e_0 - e_1` (along the spokes) and `f_0 - f_1` (across
/// them, towards sector 0), the two left eigenvectors of the double eigenvalue 1/4 (module
/// documentation, "Valence 2").
fn cap_plane(m: &PolyMesh, x: usize) -> Option<(Stencil, Stencil)> {
    match two_quads(m, x) {
        Some([a, b]) => {
            let mut along = Stencil::new();
            along
                .add(m.he_to(a) as usize, 1.0)
                .add(m.he_to(b) as usize, -1.0);
            let mut across = Stencil::new();
            across.add(opposite(m, a), 1.0).add(opposite(m, b), -1.0);
            Some((along, across))
        }
        None => CatmullClark::tangent_stencils(m, x),
    }
}

/// The hole of one element: its centre vertex and the sectors in counter-clockwise order with
/// the marked face (and tag) of each, or why there is none.
fn hole_of(
    level: &Level,
    limits: &LimitStencils<'_>,
    element: Element,
    faces: &[(u32, Tag)],
) -> Result<CapData, NoCap> {
    let (x, quads, tags, open) = hole_sectors(level, element, faces)?;
    let sectors = quad_hole_segments(&quads, |he, from| segment_across(level, he, from))?;
    let m = &level.mesh;
    let pos = m.positions();
    let centre = cap_centre(limits, m, x).apply(pos);
    let (t1, t2) = cap_plane(m, x).ok_or(NoCap::Never)?;
    let plane = [t1.apply(pos), t2.apply(pos)];
    let hole = if open {
        Hole::untangented_open(centre, sectors)
    } else {
        Hole::untangented(centre, sectors)
    };
    Ok((hole, plane, tags))
}

/// The rows of the data of [`hole_of`] over the level's points, in the order of the patch
/// table's cap data (centre, the two plane vectors, per sector and segment the boundary then the
/// cross coefficients): the same walk, the limit and tangent stencils themselves, and the
/// segments' weights read off the segment code ([`segment_rows`]).
pub(super) fn hole_rows(
    level: &Level,
    limits: &LimitStencils<'_>,
    element: Element,
    faces: &[(u32, Tag)],
    patch_rows: &impl Fn(usize) -> Option<Rows>,
) -> Option<Rows> {
    let (x, quads, _, _) = hole_sectors(level, element, faces).ok()?;
    let sectors =
        quad_hole_segments(&quads, |he, from| segment_rows(level, he, from, patch_rows)).ok()?;
    let (t1, t2) = cap_plane(&level.mesh, x)?;
    let mut rows = vec![cap_centre(limits, &level.mesh, x), t1, t2]
        .into_iter()
        .map(|s| s.entries().to_vec())
        .collect::<Vec<_>>();
    rows.extend(sectors.into_iter().flatten().flatten());
    Some(rows)
}

/// The centre vertex of an element's hole, its sectors counter-clockwise (from the boundary at
/// a boundary vertex), the tag of each sector's cap patch and whether the fan is open, or why
/// there is none.
fn hole_sectors(
    level: &Level,
    element: Element,
    faces: &[(u32, Tag)],
) -> Result<(usize, Vec<QuadSector>, Vec<Tag>, bool), NoCap> {
    use crate::schemes::sdc::crease::adaptive::cap_feature;
    let m = &level.mesh;
    let (f0, _) = faces[0];
    let (x, n, open) = fan_centre_from(m, &level.info, element, f0, (3, 2))?;
    let xu = x as usize;
    match cap_feature(level, xu) {
        Some(true) => return Err(NoCap::Later),
        Some(false) => return Err(NoCap::Never),
        None if faces.len() != n => return Err(NoCap::Never),
        None => {}
    }
    let tag_at: HashMap<u32, Tag> = faces.iter().copied().collect();
    let quads = if open {
        quad_sectors_open(m, x, n)
    } else {
        quad_sectors_around(m, x, f0, n)
    }
    .ok_or(NoCap::Never)?;
    let mut tags = Vec::with_capacity(n);
    for sec in &quads {
        // the cap patch of this sector has its (0, 0) at x, corner k of the sector's face
        let tag = *tag_at.get(&sec.face).ok_or(NoCap::Never)?;
        tags.push(Tag {
            domain: tag.domain.rotated(sec.corner as u32),
            ..tag
        });
    }
    Ok((xu, quads, tags, open))
}

/// [`g1_caps`] of the marked cells whose elements' ring counts `targets` are reached at level
/// `l` (the limit surface's evaluation); returns the cells left, those of the other elements
/// after them (refined further).
pub(super) fn g1_caps_by_targets(
    level: &Level,
    marked: Vec<(u32, Tag)>,
    l: usize,
    targets: &crate::host::adaptive::RingTargets,
    out: &mut PatchComplex,
) -> Vec<(u32, Tag)> {
    let (now, later): (Vec<_>, Vec<_>) = marked
        .into_iter()
        .partition(|(_, tag)| l >= targets.of(tag.element));
    let mut left = g1_caps(level, &now, out);
    left.extend(later);
    left
}

/// The holes of one element: those of a crease vertex's sides ([`crease::crease_caps`]), of a
/// dart ([`crease::dart_cap`]), of a corner's sides ([`crease::corner_caps`]), of the runs of
/// quads between hole faces ([`wedge::wedge_caps`], at a boundary vertex
/// [`wedge::open_wedge_caps`]), else the one of [`hole_of`].
fn holes_of(
    level: &Level,
    limits: &LimitStencils<'_>,
    element: Element,
    faces: &[(u32, Tag)],
) -> Result<Vec<CapData>, NoCap> {
    let (x, n, open) = fan_centre_from(&level.mesh, &level.info, element, faces[0].0, (1, 2))?;
    if open && let Some(caps) = wedge::open_wedge_caps(level, limits, x as usize, faces)? {
        return Ok(caps);
    }
    if open && n == 1 {
        return crease::boundary_corner_cap(level, x as usize, faces).map(|c| vec![c]);
    }
    if !open && let Some(caps) = crease::crease_caps(level, x as usize, faces)? {
        return Ok(caps);
    }
    if !open && let Some(cap) = crease::dart_cap(level, x as usize, faces)? {
        return Ok(vec![cap]);
    }
    if !open && let Some(caps) = crease::corner_caps(level, x as usize, faces)? {
        return Ok(caps);
    }
    if !open && let Some(cap) = crease::cone_cap(level, x as usize, faces)? {
        return Ok(vec![cap]);
    }
    if !open && let Some(caps) = wedge::wedge_caps(level, limits, x as usize, faces)? {
        return Ok(caps);
    }
    hole_of(level, limits, element, faces).map(|c| vec![c])
}

/// Whether some marked element would get its G^1 cap after more levels (its faces still touch
/// another element's): the adaptive loop then goes on.
pub(super) fn waiting(level: &Level, marked: &[(u32, Tag)]) -> bool {
    let limits = LimitStencils::new(&level.mesh);
    caps_waiting(marked, |e, faces| holes_of(level, &limits, e, faces))
}

/// Caps every element of the marked faces that has its hole data (see the [module](self)
/// documentation); returns the faces left for the C^0 fill.
pub(super) fn g1_caps(
    level: &Level,
    marked: &[(u32, Tag)],
    out: &mut PatchComplex,
) -> Vec<(u32, Tag)> {
    let limits = LimitStencils::new(&level.mesh);
    g1_cap_elements(marked, out, |e, faces| {
        holes_of(level, &limits, e, faces).unwrap_or_default()
    })
}
