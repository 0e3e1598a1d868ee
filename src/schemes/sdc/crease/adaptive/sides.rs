//! A sharp vertex's sides as the G^1 caps of Catmull-Clark and Loop see them: the sharp
//! half-edges of crease vertices, darts and corners, the limit point of a crease, the sides
//! between sharp edges that hold marked cells, and a corner side's chart.

use super::{Level, cap_feature, is_hole, is_inf};
use crate::bezier::g1::CornerAngle;
use crate::geom::{self, Point};
use crate::host::adaptive::{NoCap, Tag};
use crate::host::fans::faces_between;
use crate::mesh::PolyMesh;

/// The infinitely sharp outgoing half-edges of the interior vertex `v` (in the order of its
/// outgoing half-edges), its own sharpness, and whether every other edge of it is smooth
/// (sharpness 0: no semi-sharp edge left); `None` at a boundary vertex or without the level's
/// features.
fn sharp_fan(level: &Level, v: usize) -> Option<(Vec<u32>, f32, bool)> {
    let ft = level.sharp.as_ref()?;
    let m = &level.mesh;
    if m.is_boundary_vertex(v) {
        return None;
    }
    let hs = m.outgoing_halfedges(v);
    let sharpness = |h: u32| ft.edges[m.he_edge(h) as usize];
    let smooth = hs
        .iter()
        .all(|&h| sharpness(h) == 0.0 || is_inf(sharpness(h)));
    Some((
        hs.into_iter().filter(|&h| is_inf(sharpness(h))).collect(),
        ft.vertices[v],
        smooth,
    ))
}

/// The infinitely sharp outgoing half-edges of the interior vertex `v` of finite sharpness
/// ([`sharp_fan`]) and whether it is plain apart from them (its own sharpness and every other
/// edge's 0: no semi-sharp feature left); `None` at a boundary vertex, a vertex of infinite
/// sharpness or without the level's features.
fn sharp_halfedges(level: &Level, v: usize) -> Option<(Vec<u32>, bool)> {
    let (hs, sharpness, smooth) = sharp_fan(level, v)?;
    (!is_inf(sharpness)).then_some((hs, smooth && sharpness == 0.0))
}

/// The two infinitely sharp outgoing half-edges of `v` when it is an interior crease vertex
/// (exactly two of its edges infinitely sharp, its own sharpness finite), and whether it is
/// plain apart from them (no semi-sharp feature left: its rule is the crease rule, and each
/// side of the crease refines as a boundary fan does).
pub(crate) fn crease_halfedges(level: &Level, v: usize) -> Option<([u32; 2], bool)> {
    match sharp_halfedges(level, v)? {
        (hs, plain) if hs.len() == 2 => Some(([hs[0], hs[1]], plain)),
        _ => None,
    }
}

/// The one infinitely sharp outgoing half-edge of `v` when it is an interior dart (exactly one
/// of its edges infinitely sharp, its own sharpness finite), and whether it is plain apart from
/// it (no semi-sharp feature left: the dart's rules, [`crate::schemes::catmull_clark::dart`]).
pub(crate) fn dart_halfedge(level: &Level, v: usize) -> Option<(u32, bool)> {
    match sharp_halfedges(level, v)? {
        (hs, plain) if hs.len() == 1 => Some((hs[0], plain)),
        _ => None,
    }
}

/// The infinitely sharp outgoing half-edge (at most one) of `v` when it is an interior cone
/// point: a vertex of infinite sharpness (the corner rule keeps it) with fewer than two
/// infinitely sharp edges, so no two sharp edges span a tangent plane there
/// ([`crate::bezier::g1::Fan::Cone`]); and whether it is plain apart from it (every other
/// edge's sharpness 0: no semi-sharp feature left).
pub(crate) fn cone_halfedge(level: &Level, v: usize) -> Option<(Option<u32>, bool)> {
    match sharp_fan(level, v)? {
        (_, sharpness, _) if !is_inf(sharpness) => None,
        (hs, _, smooth) if hs.is_empty() => Some((None, smooth)),
        (hs, _, smooth) if hs.len() == 1 => Some((Some(hs[0]), smooth)),
        _ => None,
    }
}

/// The opening of every cone point's cap provider (Catmull-Clark's and Loop's): `Ok(None)`
/// when `v` is not a cone point ([`cone_halfedge`]), `Later` while a semi-sharp edge is left
/// at it, else `Ok(Some(sharp))` with its one infinitely sharp half-edge, if any.
pub(crate) fn cone_point(level: &Level, v: usize) -> Result<Option<Option<u32>>, NoCap> {
    match cone_halfedge(level, v) {
        None => Ok(None),
        Some((_, false)) => Err(NoCap::Later),
        Some((sharp, true)) => Ok(Some(sharp)),
    }
}

/// Whether the interior vertex `x` has OpenSubdiv hole faces around it, so its G^1 caps are
/// wedges (one per run of present faces): `Ok(false)` at a boundary vertex or without holes,
/// `Later` while a semi-sharp feature is left at `x`, `Never` for other features.
pub(crate) fn beside_holes(level: &Level, x: usize) -> Result<bool, NoCap> {
    let m = &level.mesh;
    if m.is_boundary_vertex(x) {
        return Ok(false);
    }
    let hs = m.outgoing_halfedges(x);
    if !hs.iter().any(|&h| is_hole(level, m.he_face(h) as usize)) {
        return Ok(false);
    }
    match cap_feature(level, x) {
        Some(true) => Err(NoCap::Later),
        Some(false) => Err(NoCap::Never),
        None => Ok(true),
    }
}

/// The runs of present faces among a closed fan's `faces` (in fan order) between hole faces,
/// as index lists into `faces`, each starting after a hole; `None` when there are not exactly
/// `cells` present faces (the element's marked cells).
pub(crate) fn present_runs(level: &Level, faces: &[u32], cells: usize) -> Option<Vec<Vec<usize>>> {
    let n = faces.len();
    let hole: Vec<bool> = faces.iter().map(|&f| is_hole(level, f as usize)).collect();
    if hole.iter().filter(|&&h| !h).count() != cells {
        return None;
    }
    Some(
        (0..n)
            .filter(|&s| !hole[s] && hole[(s + n - 1) % n])
            .map(|start| {
                (0..n)
                    .map(|i| (start + i) % n)
                    .take_while(|&i| !hole[i])
                    .collect()
            })
            .collect(),
    )
}

/// The crease fan of one sector ([`Fan::Crease`](crate::bezier::g1::Fan::Crease)) at a
/// boundary vertex `x` of one quad on a boundary that passes (Catmull-Clark's and non-box's
/// boundary rules are the cubic B-spline rules of the boundary polygon): the hole of the
/// quad's `sectors` centred at the curve's limit point [`crease_limit`]`(p, x, q)` (`p`, `q`
/// the ends of its spokes 0 and 1), in the plane of the curve's derivative `(p - q) / 2`
/// along spoke 0 (its `T0`) and `across`, a vector across the boundary in the scheme's
/// tangent plane.
pub(crate) fn one_quad_crease_fan(
    sectors: Vec<Vec<crate::bezier::g1::Segment>>,
    [p, x, q]: [Point; 3],
    across: Point,
) -> (crate::bezier::g1::Hole, [Point; 2]) {
    (
        crate::bezier::g1::Hole::untangented_crease(crease_limit(p, x, q), sectors),
        [geom::scale(geom::sub(p, q), 0.5), across],
    )
}

/// The limit point `(a + 4 x + b) / 6` of a vertex `x` under the crease rule between its
/// crease (or boundary) neighbours `a` and `b`: the cubic B-spline of the crease polygon.
pub(crate) fn crease_limit(a: Point, x: Point, b: Point) -> Point {
    geom::scale(geom::axpy(geom::axpy(a, 4.0, x), 1.0, b), 1.0 / 6.0)
}

/// The sides `(ha, hb, k)` of a vertex between its sharp edges: the `k` faces from the face of
/// the outgoing sharp half-edge `ha` to the one before `hb` ([`crease_sides`],
/// [`corner_sides`]).
pub(crate) type Sides = Vec<(u32, u32, usize)>;

/// The limit point of a crease vertex and its sides ([`crease_sides`]).
pub(crate) type CreaseSides = (Point, Sides);

/// A crease vertex `x` ([`crease_halfedges`]) as its G^1 caps see it, for Catmull-Clark and
/// Loop alike: the crease's limit point `(e_a + 4 x + e_b) / 6` and its sides
/// `(ha, hb, k)` that hold marked `cells` (the `k` faces counter-clockwise from the face of the
/// outgoing crease half-edge `ha` to the one before `hb`). `Ok(None)` when `x` is not a crease
/// vertex; `Later` while a semi-sharp feature is left at `x`, a side is only partly marked or
/// a side of `regular` faces (the scheme's regular crease patches) is still marked; `Never`
/// when the sides do not hold exactly the cells.
pub(crate) fn crease_sides(
    level: &Level,
    x: usize,
    cells: &[(u32, Tag)],
    regular: usize,
) -> Result<Option<CreaseSides>, NoCap> {
    let Some((hs, plain)) = crease_halfedges(level, x) else {
        return Ok(None);
    };
    if !plain {
        return Err(NoCap::Later);
    }
    let m = &level.mesh;
    let pos = m.positions();
    let (ea, eb) = (pos[m.he_to(hs[0]) as usize], pos[m.he_to(hs[1]) as usize]);
    let centre = crease_limit(ea, pos[x], eb);
    let sides = marked_sides(m, &[(hs[0], hs[1]), (hs[1], hs[0])], cells, regular)?;
    Ok(Some((centre, sides)))
}

/// The sides `(ha, hb, k)` among `pairs` of sharp half-edges around a vertex (the `k` faces
/// from the face of `ha` to the one before `hb`) that hold marked `cells`: `Later` while a
/// side is only partly marked or a side of `regular` faces is still marked, `Never` when the
/// sides do not hold exactly the cells.
fn marked_sides(
    m: &PolyMesh,
    pairs: &[(u32, u32)],
    cells: &[(u32, Tag)],
    regular: usize,
) -> Result<Sides, NoCap> {
    let marked: std::collections::HashSet<u32> = cells.iter().map(|&(f, _)| f).collect();
    let mut sides = Vec::new();
    let mut covered = 0;
    for &(ha, hb) in pairs {
        let faces = faces_between(m, ha, hb).ok_or(NoCap::Never)?;
        let (k, count) = (
            faces.len(),
            faces.iter().filter(|f| marked.contains(f)).count(),
        );
        match count {
            0 => continue,
            _ if k == regular || count < k => return Err(NoCap::Later),
            _ => {}
        }
        sides.push((ha, hb, k));
        covered += k;
    }
    if sides.is_empty() || covered != cells.len() {
        return Err(NoCap::Never);
    }
    Ok(sides)
}

/// The chart angle and plane vectors of the corner `x`'s side `(ha, hb, k)` ([`corner_sides`]):
/// [`corner_chart`] of the ends of its sharp edges, reflex when the side holds more than half
/// of the faces around `x`.
pub(crate) fn corner_plane(
    m: &PolyMesh,
    x: usize,
    (ha, hb, k): (u32, u32, usize),
) -> Result<(CornerAngle, [Point; 2]), NoCap> {
    let pos = m.positions();
    corner_chart(
        pos[x],
        pos[m.he_to(ha) as usize],
        pos[m.he_to(hb) as usize],
        2 * k > m.valence(x),
    )
}

/// The chart angle and plane vectors of a corner `x`'s side between the sharp edges to `e_a`
/// and `e_b`: `T0 = e_a - x` and `T1 = +-(e_b - x)`, the derivatives of the two sharp edges'
/// limit curves at the corner (the cubic B-spline of the sharp polygon whose end the corner
/// rule fixes: its phantom point `2 x - e`; Catmull-Clark's, Loop's and non-box's boundary
/// rules alike), `-` on a `reflex` side (more than half of the faces around the corner:
/// topology, not geometry, decides, so a patch table's re-application to moved points takes
/// the same chart). `Never` when the two edges are (nearly) straight through `x` (sine below
/// 1e-3): they span no plane.
pub(crate) fn corner_chart(
    x: Point,
    e_a: Point,
    e_b: Point,
    reflex: bool,
) -> Result<(CornerAngle, [Point; 2]), NoCap> {
    let (ta, tb) = (geom::sub(e_a, x), geom::sub(e_b, x));
    if geom::norm(geom::cross(ta, tb)) <= 1e-3 * geom::norm(ta) * geom::norm(tb) {
        return Err(NoCap::Never);
    }
    Ok(if reflex {
        (CornerAngle::Reflex, [ta, geom::scale(tb, -1.0)])
    } else {
        (CornerAngle::Convex, [ta, tb])
    })
}

/// The sides `(ha, hb, k)` of a corner `x` that hold marked `cells`, for Catmull-Clark and
/// Loop alike: an interior vertex of infinite sharpness with at least two infinitely sharp
/// edges, or of finite sharpness with at least three (OpenSubdiv's corner rule either way, the
/// vertex is its own limit), cut by its sharp edges into sides of `k` faces
/// counter-clockwise from the face of the outgoing sharp half-edge `ha` to the one before `hb`.
/// `Ok(None)` when `x` is not such a corner; `Later` while a semi-sharp feature is left at
/// `x`, a side is only partly marked or a side of `regular` faces (the scheme's regular corner
/// patch) is still marked; `Never` when the sides do not hold exactly the cells.
pub(crate) fn corner_sides(
    level: &Level,
    x: usize,
    cells: &[(u32, Tag)],
    regular: usize,
) -> Result<Option<Sides>, NoCap> {
    let Some(ft) = level.sharp.as_ref() else {
        return Ok(None);
    };
    let m = &level.mesh;
    if m.is_boundary_vertex(x) {
        return Ok(None);
    }
    let hs = m.outgoing_halfedges(x);
    let sharpness = |h: u32| ft.edges[m.he_edge(h) as usize];
    let Some(&h0) = hs.iter().find(|&&h| is_inf(sharpness(h))) else {
        return Ok(None);
    };
    // the sharp half-edges in fan order from h0
    let mut sharp = vec![h0];
    let mut h = h0;
    for _ in 0..hs.len() {
        h = m.he_twin(m.he_prev(h)).ok_or(NoCap::Never)?;
        if h == h0 {
            break;
        }
        if is_inf(sharpness(h)) {
            sharp.push(h);
        }
    }
    let corner = sharp.len() >= 3 || (sharp.len() == 2 && is_inf(ft.vertices[x]));
    if !corner {
        return Ok(None);
    }
    let plain = (ft.vertices[x] == 0.0 || is_inf(ft.vertices[x]))
        && hs
            .iter()
            .all(|&h| sharpness(h) == 0.0 || is_inf(sharpness(h)));
    if !plain {
        return Err(NoCap::Later);
    }
    let pairs: Vec<(u32, u32)> = (0..sharp.len())
        .map(|i| (sharp[i], sharp[(i + 1) % sharp.len()]))
        .collect();
    marked_sides(m, &pairs, cells, regular).map(Some)
}
