//! The G^1 cap of non-box subdivision's last ring (`nonbox`, and `nonbox-4dir`, which builds
//! the same complex).
//!
//! # The cap
//!
//! An extraordinary vertex `x` of valence `n` whose cells at the last level are the `n` quads
//! around it, every outer edge of which is shared with an emitted (ring or regular) cell of the
//! same level, is closed by the quad-layout G^1 cap of [`crate::bezier::g1`], one patch per
//! hole cell:
//!
//! * **hole data**: sector `s` is the cell `[x, p, K, q]`, spoke `s` its edge `x -> p` (the
//!   layout of Catmull-Clark's cap). Segment `a` runs along the edge `p -> K`, segment `b` along
//!   `q -> K`; each is read off the cubic S_3^1 triangle of the emitted cell across the edge
//!   (the triangle on that edge, apex at that cell's centre). In the affine chart in which both
//!   cells are unit squares, the triangle's derivative towards its apex at the edge point `t` is
//!   `(1/2 - t) D_t + D_out / 2`, so the derivative out of the hole is
//!   `D_out = 2 D_apex - (1 - 2 t) D_t`; the segment's cross derivative is `-D_out`, a cubic,
//!   interpolated exactly at four points. The S_3^1 spline is C^1 with its mixed derivative
//!   continuous at the lattice vertices of the four-directional mesh (the spoke ends `p, q` and
//!   the corners `K` are regular vertices of the spline), so the data are compatible there
//!   (`kappa = 0`; [`crate::bezier::g1::g1_cap_with`] checks every hole and refuses one that
//!   is not, naming the spoke end);
//! * **centre**: the paper's limit point of `x` (`NonBox::limit_stencil`);
//! * **tangent plane**: spanned by the paper's tangents `u1, u2` (`NonBox::tangent_stencils`,
//!   Fourier mode 1 of the FCVs around `x`; the exact left eigenvectors of the subdominant pair,
//!   tested in `nonbox::local`); the spoke tangents' scale from the ring's chart in that plane;
//! * **conditions, free parameters, degree**: those of [`crate::bezier::g1`]: bi-4 for odd `n`,
//!   bi-5 for even `n` (bi-4 at `n = 4`).
//!
//! **Valence 2** (the octahedron read by `nonbox-4dir` as a pillow of two quads, a pentagon's
//! vertex after the first step): the half-plane cap of two bi-5 patches
//! ([`crate::bezier::g1`], "Two sectors") in the plane of `p_0 - p_1` and `c_0 - c_1`
//! (`two_cell_plane`); G^1 at every join (`check` on the octahedron: 3.2e-14 rad at 3 rings,
//! 2.5e-11 at 8, where the C^0 fill measured 0.11 rad).
//!
//! **Boundary vertices** of `k >= 3` quads get the open-fan cap
//! ([`crate::bezier::g1::Layout::OpenQuad`]; sectors from the boundary half-edge, spokes `0`
//! and `k` free boundary curves), centred at the boundary curve's limit point `(a + 4 v + b) / 6`
//! in the plane of the boundary tangent `a - b` and the eigen tangent across the boundary of the
//! scheme's own local matrix ([`crate::schemes::nonbox::boundary`]).
//!
//! **Kept corners** of a net cut along its creases (a copy of a vertex with three or more sharp
//! edges, on one side of the cut) with `k >= 2` quads get Catmull-Clark's corner cap
//! ([`crate::bezier::g1::Fan::Corner`]): centred at the corner (the rules keep it), in the
//! plane of the two sharp edges' derivatives there, `e_a - x` and `+-(e_b - x)` (non-box's
//! boundary rules are the cubic B-spline rules, so its limit curves are Catmull-Clark's), a
//! quarter-turn, or three on a side with more than half of the corner's faces in the input net
//! (`corner_plane`). Until 2026-12-07 the fill closed them: 0.87 rad on OpenSubdiv's
//! `catmark_inf_crease0`, 0.57 on `catmark_inf_crease1`.
//!
//! **Copies of one cell on a boundary that passes** (where a crease turns at a vertex that is
//! no corner, the cut leaves a copy with one cell on the inner side; a vertex of one face on
//! an edge-only boundary) get Catmull-Clark's crease fan of one sector
//! ([`crate::bezier::g1::Fan::Crease`]): spokes the boundary curve's two halves, `T0` its
//! derivative `(p - q) / 2`, in the plane of that and `F - (a + b) / 2`
//! ([`crate::schemes::nonbox::boundary`], "One quad"). Until 2026-12-07 the fill closed them:
//! 1.1e-3 rad on `catmark_inf_crease0`, 1.6e-3 on `loop_triangle_edgeonly`.
//!
//! **Darts** (an interior vertex where a chain of infinitely sharp creases ends): the level
//! is refined uncut and its patches read off a copy cut along every crease
//! ([`super::sharp`]), where the dart is the end of a slit, an open fan of its `k` cells whose
//! two boundary neighbours are copies of one vertex. It gets the dart fan's cap
//! ([`crate::bezier::g1::Fan::Dart`], as Catmull-Clark's darts): the full turn from the sharp
//! edge back to it, centred at the dart's limit point in its tangent plane, the left
//! eigenvectors of non-box's local matrix of a dart applied to the uncut level's points
//! ([`crate::schemes::nonbox::local::dart`]). Until 2026-12-07 the fill closed a strip along
//! those chains (3.6e-4 rad on a grid with a crease of two edges inside).
//!
//! Holes that touch another element's after the requested rings get up to
//! [`crate::host::adaptive::MAX_EXTRA_CAP_LEVELS`] more levels; holes without the data (non-quad cells, boundary vertices
//! whose two rings are not regular quads, still touching after that) keep the C^0 Coons fill of
//! [`super`].

use super::{Level, trusted_cell};
use crate::bezier::complex::PatchComplex;
use crate::bezier::g1::{CornerAngle, Hole, Segment};
use crate::geom::{Point, axpy, scale};
use crate::host::adaptive::{
    NoCap, QuadSector, Tag, caps_waiting, fan_centre_from, g1_cap_elements, quad_hole_segments,
    quad_sectors_around, quad_sectors_open,
};
use crate::mesh::{Element, PolyMesh};
use crate::schemes::nonbox::NonBox;
use crate::schemes::nonbox::bezier::triangle_to_tensor;
use crate::schemes::nonbox::boundary::open_fan_tangents;
use crate::schemes::nonbox::local::dart::dart_masks;
use crate::schemes::nonbox::local::labelled_points;
use crate::schemes::sdc::crease::adaptive::{corner_chart, one_quad_crease_fan};
use crate::stencil::Stencil;
use std::collections::HashMap;

/// The inverse of the cubic Bernstein collocation matrix at `0, 1/3, 2/3, 1`.
const COLLOCATION3: [[f64; 4]; 4] = [
    [1.0, 0.0, 0.0, 0.0],
    [-5.0 / 6.0, 3.0, -1.5, 1.0 / 3.0],
    [1.0 / 3.0, -1.5, 3.0, -5.0 / 6.0],
    [0.0, 0.0, 0.0, 1.0],
];

/// The cubic with values `v` at `0, 1/3, 2/3, 1`.
fn interpolate(v: &[Point; 4]) -> Vec<Point> {
    COLLOCATION3
        .iter()
        .map(|row| {
            row.iter()
                .zip(v)
                .fold([0.0; 3], |acc, (&w, p)| axpy(acc, w, *p))
        })
        .collect()
}

fn corner_of(m: &PolyMesh, f: usize, v: u32) -> Option<usize> {
    m.face(f).iter().position(|&w| w == v)
}

/// The segment of the hole along its half-edge `hole_he`, from its end `from` (see the
/// [module](self) documentation); `None` while the cell across has no trusted triangles.
fn segment_across(level: &Level, hole_he: u32, from: u32) -> Option<Segment> {
    let m = &level.net.mesh;
    let h = m.he_twin(hole_he)?;
    let g = m.he_face(h) as usize;
    if m.face_size(g) != 4 {
        return None;
    }
    let tris = trusted_cell(level, g)?;
    let k = corner_of(m, g, m.he_from(h))?;
    let x = triangle_to_tensor(&tris[k]);
    let forward = m.he_from(h) == from;
    let (mut b, mut c) = ([[0.0; 3]; 4], [[0.0; 3]; 4]);
    for j in 0..4 {
        let tau = j as f64 / 3.0;
        let t = if forward { tau } else { 1.0 - tau };
        let d = x.derivatives(t, 0.0);
        b[j] = d.p;
        // -D_out = (1 - 2 t) D_t - 2 D_apex
        c[j] = axpy(scale(d.dv, -2.0), 1.0 - 2.0 * t, d.du);
    }
    Some(Segment {
        boundary: interpolate(&b),
        cross: interpolate(&c),
    })
}

/// The hole of one element, two vectors spanning its limit tangent plane and the tags of its sectors, or why there is none.
fn hole_of(
    level: &Level,
    input: &PolyMesh,
    element: Element,
    cells: &[(u32, Tag)],
) -> Result<(Hole, [Point; 2], Vec<Tag>), NoCap> {
    let m = &level.net.mesh;
    let (f0, _) = cells[0];
    // open fans of two cells only at kept corners (a plain boundary vertex of two cells is
    // regular, so is a corner of one), of one cell only on a boundary that passes (edge-only)
    let (x, n, open) = fan_centre_from(m, &level.info, element, f0, (1, 2))?;
    let xu = x as usize;
    let corner = open && crate::schemes::nonbox::sharp::is_corner(m, xu);
    if cells.len() != n || (open && !corner && n == 2) || (corner && n < 2) {
        return Err(NoCap::Never);
    }
    let tag_at: HashMap<u32, Tag> = cells.iter().copied().collect();
    let quads = if open {
        quad_sectors_open(m, x, n)
    } else {
        quad_sectors_around(m, x, f0, n)
    }
    .ok_or(NoCap::Never)?;
    // the cap patch of a sector has its (0, 0) at x, corner `sec.corner` of the sector's cell
    let tags = quads
        .iter()
        .map(|sec| {
            let tag = tag_at.get(&sec.face).copied().ok_or(NoCap::Never)?;
            Ok(Tag {
                domain: tag.domain.rotated(sec.corner as u32),
                ..tag
            })
        })
        .collect::<Result<Vec<Tag>, NoCap>>()?;
    let sectors = quad_hole_segments(&quads, |he, from| segment_across(level, he, from))?;
    if corner {
        let (angle, plane) = corner_plane(level, input, element, xu, &quads)?;
        let x = level.points[xu];
        return Ok((Hole::untangented_corner(x, sectors, angle), plane, tags));
    }
    if open && n == 1 {
        return one_cell_crease(level, xu, &quads[0], sectors).map(|(h, plane)| (h, plane, tags));
    }
    if open && let Some(frame) = dart_frame(level, xu) {
        let (centre, plane) = frame?;
        return Ok((Hole::untangented_dart(centre, sectors), plane, tags));
    }
    let centre = NonBox::limit_stencil(&level.net, xu).apply(&level.points);
    let (t1, t2) = if open {
        open_fan_tangents(&level.net, xu).ok_or(NoCap::Never)?
    } else if n == 2 {
        two_cell_plane(m, &quads)
    } else {
        NonBox::tangent_stencils(&level.net, xu)
    };
    let plane = [t1.apply(&level.points), t2.apply(&level.points)];
    let hole = if open {
        Hole::untangented_open(centre, sectors)
    } else {
        Hole::untangented(centre, sectors)
    };
    Ok((hole, plane, tags))
}

/// Whether `x` is the end of a slit that the cut along a crease chain ending at a dart made
/// (its two boundary neighbours are copies of one vertex of the uncut level): then the dart's
/// limit point and two vectors spanning its tangent plane, from the masks of
/// [`crate::schemes::nonbox::local::dart`] applied to the uncut level's points; inside,
/// `Later` while its two rings are not regular quads, `Never` where no masks are computed at
/// its valence.
fn dart_frame(level: &Level, x: usize) -> Option<Result<(Point, [Point; 2]), NoCap>> {
    let u = level.uncut_net.as_ref()?;
    let nb = level.net.mesh.vertex_neighbors(x);
    let (a, b) = (*nb.first()? as usize, *nb.last()? as usize);
    if a == b || u.origin[a] != u.origin[b] {
        return None;
    }
    let um = &u.net.mesh;
    let (x0, e0) = (u.origin[x] as usize, u.origin[a]);
    let frame = || {
        let masks = dart_masks(um.vertex_faces(x0).len()).ok_or(NoCap::Never)?;
        let h = um
            .outgoing_halfedges(x0)
            .into_iter()
            .find(|&h| um.he_to(h) == e0)
            .ok_or(NoCap::Never)?;
        let ring: Vec<Point> = labelled_points(um, h)
            .ok_or(NoCap::Later)?
            .iter()
            .map(|&i| u.points[i])
            .collect();
        Ok(masks.apply(&ring))
    };
    Some(frame())
}

/// The hole of a boundary vertex `x` of one cell `sec` (its `sectors`) on a boundary that
/// passes (a net's edge-only boundary, or a copy on one side of a crease cut where the crease
/// turns): Catmull-Clark's crease fan of one sector
/// ([`one_quad_crease_fan`]: non-box's boundary rules are the cubic B-spline rules too, and
/// its limit point there `NonBox::limit_stencil`'s `(a + 4 v + b) / 6`), across the boundary
/// the tangent of non-box's own local matrix of one quad
/// ([`crate::schemes::nonbox::boundary::open_fan_tangents`]).
fn one_cell_crease(
    level: &Level,
    x: usize,
    sec: &QuadSector,
    sectors: Vec<Vec<Segment>>,
) -> Result<(Hole, [Point; 2]), NoCap> {
    let (_, across) = open_fan_tangents(&level.net, x).ok_or(NoCap::Never)?;
    let p = &level.points;
    let ends = [p[sec.p as usize], p[x], p[sec.q as usize]];
    Ok(one_quad_crease_fan(sectors, ends, across.apply(p)))
}

/// The chart angle and plane vectors of a kept corner's open fan `quads` around `x` (a copy of
/// a corner on one side of the cut along its creases, [`super::sharp`]): Catmull-Clark's corner
/// chart of the ends of its boundary spokes (`crate::schemes::sdc::crease::adaptive::
/// corner_chart`; non-box's boundary rules are the cubic B-spline rules, so its limit curves at
/// the corner are Catmull-Clark's), reflex on a side with more than half of the corner's faces
/// in the input net `input` (the cut net's copy has only its own side). `Never` as the chart
/// says, or when the element is not an input vertex.
fn corner_plane(
    level: &Level,
    input: &PolyMesh,
    element: Element,
    x: usize,
    quads: &[QuadSector],
) -> Result<(CornerAngle, [Point; 2]), NoCap> {
    let (Element::Vertex(v0), Some(first), Some(last)) = (element, quads.first(), quads.last())
    else {
        return Err(NoCap::Never);
    };
    let p = &level.points;
    let around = input.vertex_faces(v0 as usize).len();
    corner_chart(
        p[x],
        p[first.p as usize],
        p[last.q as usize],
        2 * quads.len() > around,
    )
}

/// The plane of the half-plane cap of a vertex of two cells ([`crate::bezier::g1`], "Two
/// sectors"): `p_0 - p_1` along the spokes (their ends) and `c_0 - c_1` across them towards
/// sector 0 (the cells' FCVs). The paper's tangents are Fourier mode 1 of the FCVs, of which
/// two FCVs have only the cosine part: `c_0 - c_1` is the left eigenvector of the vertex's
/// invariant ring `x, c_0, c_1` at the subdominant eigenvalue `1/2 + cos(pi) / 4 = 1/4`; the
/// direction along the spokes lies outside that ring and is taken from the spoke ends at the
/// last level (their chord through the centre).
fn two_cell_plane(m: &PolyMesh, quads: &[QuadSector]) -> (Stencil, Stencil) {
    let nv = m.num_vertices();
    let along = Stencil::from_pairs([(quads[0].p as usize, 1.0), (quads[1].p as usize, -1.0)]);
    let across = Stencil::from_pairs([
        (nv + quads[0].face as usize, 1.0),
        (nv + quads[1].face as usize, -1.0),
    ]);
    (along, across)
}

/// The marked cells in batches that hold at most one centre per element. A net cut along
/// its infinitely sharp creases ([`super::sharp`]) has a copy of a crease vertex on each side
/// of the cut, all with the vertex's element: each copy is a hole of its own (an open fan),
/// while the host groups cells by element. Batch `k` holds the cells around the `k`-th copy
/// of every element met (in the order of `marked`), the cells without an element in batch 0.
fn copy_batches(level: &Level, marked: &[(u32, Tag)]) -> Vec<Vec<(u32, Tag)>> {
    let m = &level.net.mesh;
    let mut copies: HashMap<Element, Vec<u32>> = HashMap::new();
    let mut batches: Vec<Vec<(u32, Tag)>> = vec![Vec::new()];
    for &(f, tag) in marked {
        let k = tag.element.map_or(0, |e| {
            // the copy a cell belongs to: its first corner from the element (as the hole's
            // centre is found, `fan_centre_from`)
            let Some(x) = m
                .face(f as usize)
                .iter()
                .copied()
                .find(|&v| level.info[v as usize].origin == Some(e))
            else {
                return 0;
            };
            let seen = copies.entry(e).or_default();
            seen.iter().position(|&y| y == x).unwrap_or_else(|| {
                seen.push(x);
                seen.len() - 1
            })
        });
        if batches.len() <= k {
            batches.resize_with(k + 1, Vec::new);
        }
        batches[k].push((f, tag));
    }
    batches
}

/// Whether some marked element would get its cap after more levels.
pub(super) fn waiting(level: &Level, input: &PolyMesh, marked: &[(u32, Tag)]) -> bool {
    copy_batches(level, marked)
        .iter()
        .any(|b| caps_waiting(b, |e, cells| hole_of(level, input, e, cells)))
}

/// Caps every element of the marked cells that has its hole data (every copy of a vertex
/// that the cut along its creases made, on its own: [`copy_batches`]); returns the cells left
/// for the Coons fill. A copy left to the fill beside a capped copy of the same vertex is
/// named in the complex's uncapped elements (with the copy's sectors), as the host names the
/// elements it cannot cap.
pub(super) fn g1_caps(
    level: &Level,
    input: &PolyMesh,
    marked: &[(u32, Tag)],
    out: &mut PatchComplex,
) -> Vec<(u32, Tag)> {
    let batches = copy_batches(level, marked);
    if batches.len() == 1 {
        return g1_cap_elements(marked, out, |e, cells| hole_of(level, input, e, cells).ok());
    }
    let mut left = Vec::new();
    for batch in &batches {
        left.extend(g1_cap_elements(batch, out, |e, cells| {
            hole_of(level, input, e, cells).ok()
        }));
    }
    let capped: std::collections::HashSet<Element> = out
        .caps
        .iter()
        .filter_map(|c| match out.provenance.get(c.first as usize) {
            Some(crate::bezier::complex::Provenance::Cap { element, .. }) => Some(*element),
            _ => None,
        })
        .collect();
    let mut named: Vec<(Element, usize)> = Vec::new();
    for &(_, tag) in &left {
        if let Some(e) = tag.element.filter(|e| capped.contains(e)) {
            match named.iter_mut().find(|(x, _)| *x == e) {
                Some((_, k)) => *k += 1,
                None => named.push((e, 1)),
            }
        }
    }
    for (e, k) in named {
        if !out.uncapped.iter().any(|(x, _)| *x == e) {
            out.uncapped.push((
                e,
                format!(
                    "its copy on one side of an infinitely sharp crease has {k} cell(s), a \
                     fan this scheme's G^1 caps do not take (the copy on the other side is \
                     capped)"
                ),
            ));
        }
    }
    left
}
