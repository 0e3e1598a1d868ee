//! The G^1 cap of the dual bi-2 schemes' last ring (Doo-Sabin, DS^CC and PGS, which share this
//! host).
//!
//! # The cap
//!
//! After the last level an extraordinary element is one `n`-gon `F` of that level (the F-face
//! of an input facet, the V-face of an input vertex), and the vertices still marked are its `n`
//! corners. When every corner `v_k` is an interior vertex with four faces of which `F` is the
//! only non-quad, and both of its edge neighbours outside `F` are emitted ring vertices of the
//! same level, the hole is closed by the G^1 cap of [`crate::bezier::g1`]:
//!
//! * **hole data**: sector `k` is the region of corner `v_k`'s bi-2 patch (the centroid fill's
//!   patch of the parent module, turned so that its `(0, 0)` is the corner at `F`). Its two
//!   outer sides are the sides shared with the ring patches of the two outer neighbours, and
//!   the fill patch is C^1 to them there (its outer two layers are the B-spline's: only its
//!   `F` corner coefficient differs from the bi-2 B-spline conversion, and it enters neither
//!   the outer sides nor their cross derivatives), so the segments read off the fill patch
//!   ([`crate::bezier::g1::ring::segment_from_inside`]) are the ring's exact C^1 data. The
//!   spoke ends are the centroids of the quads across `F`'s edges, regular points of the bi-2
//!   B-spline, so the data are compatible at every spoke end and corner;
//! * **centre**: the scheme's limit point of the facet (`DualRules::facet_limit`: the centroid
//!   for Doo-Sabin and DS^CC, the point-augmented limit point (7) for PGS);
//! * **tangent plane**: spanned by `sum_k cos(2 pi k / n) v_k` and `sum_k sin(2 pi k / n) v_k`.
//!   For Doo-Sabin and DS^CC the new corners of `F` are a circulant combination of `F`'s
//!   corners alone, so the local subdivision matrix is block-triangular with `F`'s circulant
//!   block first; the left eigenvectors of the subdominant pair (Fourier mode 1 of the
//!   circulant, whose eigenvalue exceeds those of the rest of the matrix) then vanish off `F`
//!   and are these two masks: the exact limit tangent plane. For PGS the corner rule also reads
//!   the quads across `F`'s edges, so the masks are the plane of `F`'s mode 1 at the last level,
//!   not PGS's exact limit tangent plane (the cap is G^1 all the same; see the report of
//!   issue 17). The spoke tangents' scale comes from the ring's chart in that plane
//!   ([`crate::bezier::g1::ring::chart_tangents`]);
//! * **conditions, free parameters, degree**: those of [`crate::bezier::g1`] (C^1 to the ring,
//!   centre and plane, G^1 along every spoke with `kappa = 0`, fairness `F_4` for the rest);
//!   bi-4 for odd `n`, bi-5 for even `n`.
//!
//! Elements that are not of this form after the requested rings (holes that still touch, as
//! the V-faces of the cube after one level, and any hole while semi-sharp creases refine the
//! levels, [`no_cap_yet`]) get up to [`crate::host::adaptive::MAX_EXTRA_CAP_LEVELS`] more
//! levels; those that never are (an `n`-gon at the boundary, corners next to two `n`-gons,
//! `--rings 0`) keep the centroid fill of the parent module (C^0 across the spokes).

use super::{Level, vertex_net};
use crate::bezier::complex::PatchComplex;
use crate::bezier::convert::biquadratic_bspline_stencils;
use crate::bezier::g1::Hole;
use crate::bezier::g1::ring::segment_from_inside;
use crate::bezier::{BezierPatch, Side};
use crate::geom::{Point, axpy};
use crate::host::adaptive::{NoCap, Tag, caps_waiting, g1_cap_elements};
use crate::mesh::Element;
use crate::schemes::doo_sabin::surface::DualRules;
use crate::schemes::sdc::crease::adaptive::CALM;
use std::collections::{HashMap, HashSet};

/// `p` turned (orientation kept) so that its corner `r` (counter-clockwise from `(0, 0)`:
/// `(0, 0), (1, 0), (1, 1), (0, 1)`) becomes `(0, 0)`: `r` times `Q(u, v) = P(1 - v, u)`.
fn turned(p: BezierPatch, r: usize) -> BezierPatch {
    (0..r).fold(p, |q, _| q.transposed().reversed_v())
}

/// Why an element has no cap data at `level`: [`NoCap::Later`] while creases refine the level
/// (a level after a semi-sharp one: its strips, kept points and sector vertices still shape
/// the neighbourhood, and facets they made touch; measured on OpenSubdiv's `catmark_helmet`,
/// whose boundary vertex 2 ends a crease of sharpness 7: its hole had no cap data at level 8
/// and took the centroid fill, 0.30 rad across its spokes, while level 9 caps it G^1), so
/// that up to [`crate::host::adaptive::MAX_EXTRA_CAP_LEVELS`] more levels are taken;
/// [`NoCap::Never`] otherwise.
fn no_cap_yet(level: &Level) -> NoCap {
    if level.calm < CALM {
        NoCap::Later
    } else {
        NoCap::Never
    }
}

/// The holes of element `element` whose marked vertices are `verts`: one per facet of the
/// element (several for the sectors of a crease vertex, fairsub's crease construction), each
/// with its centre, two vectors spanning its tangent plane, and the tag of each sector (in the
/// hole's sector order). All or none.
fn holes_of(
    level: &Level,
    rules: &DualRules<'_>,
    element: Element,
    verts: &[(u32, Tag)],
    marked: &HashSet<u32>,
) -> Result<Vec<CapHole>, NoCap> {
    let m = &level.mesh;
    let not_yet = no_cap_yet(level);
    let mut facets: Vec<u32> = Vec::new();
    let mut of_facet: HashMap<u32, Vec<(u32, Tag)>> = HashMap::new();
    for &(v, tag) in verts {
        let vn = vertex_net(m, v as usize).ok_or(not_yet)?;
        let &[(_, f)] = vn.ngons.as_slice() else {
            return Err(not_yet);
        };
        if level.face_origin[f as usize] != Some(element) {
            return Err(not_yet);
        }
        of_facet
            .entry(f)
            .or_insert_with(|| {
                facets.push(f);
                Vec::new()
            })
            .push((v, tag));
    }
    facets
        .iter()
        .map(|f| hole_of(level, rules, *f, &of_facet[f], marked))
        .collect()
}

/// One hole's cap data: the hole, two vectors spanning its tangent plane, the sectors' tags.
type CapHole = (Hole, [Point; 2], Vec<Tag>);

/// The hole of facet `f` whose marked corners are `verts`, its centre, two vectors spanning its
/// tangent plane, and the tag of each sector (in the hole's sector order).
fn hole_of(
    level: &Level,
    rules: &DualRules<'_>,
    f: u32,
    verts: &[(u32, Tag)],
    marked: &HashSet<u32>,
) -> Result<CapHole, NoCap> {
    let m = &level.mesh;
    let not_yet = no_cap_yet(level);
    let face = m.face(f as usize).to_vec();
    let n = face.len();
    if verts.len() != n || n < 3 {
        return Err(not_yet);
    }
    // Linear in n: the tags, F's corners and F's limit point are looked up, not searched or
    // recomputed per corner.
    let tag_of: HashMap<u32, Tag> = verts.iter().copied().collect();
    let in_face: HashSet<u32> = face.iter().copied().collect();
    let pos = m.positions();
    let centre = (rules.facet_limit)(m, f as usize).apply(pos);
    let mut sectors = Vec::with_capacity(n);
    let mut tags = Vec::with_capacity(n);
    let mut later = false;
    for &vk in &face {
        let tag = *tag_of.get(&vk).ok_or(not_yet)?;
        let vu = vk as usize;
        if m.is_boundary_vertex(vu) {
            return Err(not_yet);
        }
        let vn = vertex_net(m, vu).ok_or(not_yet)?;
        let &[(c, g)] = vn.ngons.as_slice() else {
            return Err(not_yet);
        };
        if g != f {
            return Err(not_yet);
        }
        // the edge neighbours of v_k outside F hold the ring patches across the outer sides
        let outside = m
            .outgoing_halfedges(vu)
            .iter()
            .map(|&h| m.he_to(h))
            .filter(|w| !in_face.contains(w))
            .collect::<Vec<_>>();
        if outside.len() != 2 {
            return Err(not_yet);
        }
        if outside.iter().any(|w| marked.contains(w)) {
            later = true;
        }
        // corner index (counter-clockwise) of F's coefficient in the 3 x 3 patch
        let r = match c {
            0 => 0,
            6 => 1,
            8 => 2,
            _ => 3,
        };
        // The centroid fill's patch: F's corner coefficient is F's limit point.
        let mut cps: Vec<Point> = biquadratic_bspline_stencils(&vn.net)
            .iter()
            .map(|s| s.apply(pos))
            .collect();
        cps[c] = centre;
        let p = turned(BezierPatch::new(2, 2, cps), r);
        sectors.push(vec![
            segment_from_inside(&p, Side::U1, [0.0, 1.0], 1.0),
            segment_from_inside(&p, Side::V1, [0.0, 1.0], 1.0),
        ]);
        // the cap's sector has the turned patch's frame: (0, 0) at F's corner of the cell
        let rot = u32::from(tag.domain.rot) + r as u32;
        tags.push(Tag {
            domain: tag.domain.rotated(rot),
            ..tag
        });
    }
    if later {
        return Err(NoCap::Later);
    }
    let mut t = [[0.0; 3]; 2];
    for (k, &vk) in face.iter().enumerate() {
        let th = 2.0 * std::f64::consts::PI * k as f64 / n as f64;
        t[0] = axpy(t[0], th.cos(), pos[vk as usize]);
        t[1] = axpy(t[1], th.sin(), pos[vk as usize]);
    }
    let hole = Hole::untangented(centre, sectors);
    Ok((hole, t, tags))
}

/// Whether some element would get its G^1 cap after more levels (its hole still touches
/// another's): the adaptive loop then goes on.
pub(super) fn waiting(level: &Level, rules: &DualRules<'_>, marked: &[(u32, Tag)]) -> bool {
    let set: HashSet<u32> = marked.iter().map(|&(v, _)| v).collect();
    caps_waiting(marked, |e, verts| holes_of(level, rules, e, verts, &set))
}

/// Caps every element of the marked vertices that has its hole data (see the [module](self)
/// documentation); returns the vertices left for the centroid fill.
pub(super) fn g1_caps(
    level: &Level,
    rules: &DualRules<'_>,
    marked: &[(u32, Tag)],
    out: &mut PatchComplex,
) -> Vec<(u32, Tag)> {
    let set: HashSet<u32> = marked.iter().map(|&(v, _)| v).collect();
    g1_cap_elements(marked, out, |e, verts| {
        holes_of(level, rules, e, verts, &set).unwrap_or_default()
    })
}
