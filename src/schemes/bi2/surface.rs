//! Exact patch complexes of the bi-2 family: PGS, TPS, adjustable TPS, polar bi-2 and mixed
//! nets, as regular bi-2 patches plus nested rings around every extraordinary element.
//!
//! # Layout
//!
//! Every vertex with four quads (two on the boundary, one at a corner) carries the exact bi-2
//! patch of its 3x3 net ([`crate::schemes::doo_sabin::surface::regular_vertex_patch`], provenance `Regular`). The
//! patches missing around an extraordinary element leave a hole, which its scheme fills with
//! rings computed from the element's *local net* alone:
//!
//! | element | scheme | local net | ring `l` (`l >= 1`) | patches per ring |
//! | --- | --- | --- | --- | --- |
//! | `n`-gon facet | PGS | DS-net, `9 n` points ([`crate::schemes::bi2::pgs::ds_net`]) | patches of `b, c, d` of the level-`l` DS-net | `3 n` |
//! | vertex of valence `n` | TPS / adjustable TPS | q-net, `1 + 6 n` points (the 2-ring c-net) | patches of `a, b` of the level-`l` q-net | `2 n` |
//! | pole of valence `n` | PolBS | polar net, `1 + 3 n` points ([`crate::schemes::bi2::polar::polar_net`]) | patches of `b` of the level-`l` polar net | `n` |
//!
//! The step from level `l` to `l + 1` is a stencil table on the local net read off the
//! scheme's own whole-mesh refinement of its canonical local net ([`LocalScheme`]), so the
//! rings use exactly the rules of `--levels` and of the analysis. Ring `l` has parameter size
//! `2^-l` (PGS, radially for PolBS), `3^-l` (TPS) or the adjustable pattern, and joins ring
//! `l - 1` C^1 (ring 1 joins the regular patches). `pgs` itself (any polygon mesh, extraordinary
//! vertices becoming facets) goes through the Doo-Sabin machinery of [`crate::schemes::doo_sabin::surface`]
//! ([`pgs_complex`]) and is laid out patch for patch like Doo-Sabin; the local-net rings of
//! [`mixed_complex`] give the same patches on a DS-net (tested).
//!
//! Adjustable TPS rings are bi-2 pieces with non-uniform knots: level 1 has ring width `r`
//! and outer width `r` relative to the centre, later levels `r` and `r^2`
//! (`r = e / (1 - 2e)`, see [`crate::schemes::bi2::ternary`]). Across their sides the rings
//! are C^1 up to the per-piece affine reparametrisation this implies; the conformal C^1 test
//! of [`crate::analysis::continuity`] does not apply to them (nor to polar rings, which halve
//! only radially), [`crate::analysis::scaled::continuity_up_to_scaling`] does.
//!
//! # Fills (fairsub's own, documented constructions)
//!
//! With `fill`, the hole inside the last ring is closed, C^1 to that ring and C^0 inside:
//! - PGS: one bi-2 patch per corner `a_i` of the facet: its 3x3 net's B-spline conversion with
//!   the corner coefficient at the facet replaced by the limit point (7), exactly the centroid
//!   fill of [`crate::schemes::doo_sabin::surface`] with the scheme's limit point;
//! - TPS: one bi-2 patch per sector, the quarter of the centre's bi-2 piece (its blossoms over
//!   the sector's 2x2 block and the neighbouring spokes), whose corner coefficient at the
//!   centre is replaced by the limit point (21);
//! - PolBS: one bi-2 patch per sector with its side at the pole collapsed to the limit point
//!   (16), its middle row the circular quadratic B-spline of the `a` ring and its outer row the
//!   last ring's inner boundary (the `(a + b) / 2` ring).
//!
//! The fills meet at the limit point with tangents towards the first inner coefficients, so
//! they are tangent-continuous there exactly when those are coplanar (always for the
//! characteristic nets). They are written only where the G^1 cap of `g1` cannot be built
//! (with a note): the cap reads its hole data off the fill's outer layers and closes the hole
//! G^1 in the element's limit tangent plane (quad-layout caps for TPS, adjustable TPS and PGS
//! elements; PolBS's collapsed fill is kept as its cap once checked to be G^1). `--no-fill`
//! leaves the holes open.

use crate::bezier::BezierPatch;
use crate::bezier::complex::{Domain, PatchComplex, Provenance};
use crate::error::{Error, Result};
use crate::geom::Point;
use crate::host::ComplexOptions;
use crate::mesh::Element;
use crate::mesh::PolyMesh;
use crate::schemes::bi2::Pgs;
use crate::schemes::bi2::pgs::{PgsOptions, ds_net_index};
use crate::schemes::bi2::ternary::{TernaryRules, Widths, ternary_step, uniform_widths};
use crate::schemes::doo_sabin::surface as ds;
use crate::schemes::options::ids;
use crate::stencil::Stencil;

use super::local_scheme::{LocalScheme, qnet_index};

mod cells;
mod elements;
mod g1;
mod poles;
mod spent;
mod thirds;
use cells::FacetCells;
pub(crate) use elements::spent_by_pgs;
pub use elements::{mixed_complex, polar_complex, unseparated, unseparated_polar};
use poles::PoleCells;
pub(crate) use spent::tps_spent_locally;
/// One extraordinary element with its local net over the mesh at level `start` of its scheme.
struct RingElement {
    element: Element,
    scheme: LocalScheme,
    local0: Vec<Stencil>,
    /// The scheme's level of `local0` (1 after a whole-net step).
    start: usize,
    /// The quarter of each sector's face at the element, where its rings record face domains
    /// in thirds (TPS) or split at a ratio (adjustable TPS, [`thirds`]); empty otherwise.
    sectors: Vec<Domain>,
    /// How its rings split the hole before them (with `sectors`).
    split: thirds::Split,
    /// Where a PGS facet's rings and cap lie in the input faces ([`cells`]); `None` for the
    /// other elements.
    cells: Option<FacetCells>,
    /// Where a pole's rings and cap lie in its fan triangles and the quads around them
    /// ([`poles`]); `None` for the other elements.
    pole: Option<PoleCells>,
}

fn not_separated(what: String, name: &str) -> Error {
    let (p, t, r, m) = (ids::PGS, ids::TPS, ids::POLAR_BI2, ids::BI2_MIXED);
    let way_out = if name == r.name() {
        format!(
            "{r} takes polar layouts and prism-like caps (each cap vertex with one edge \
             leaving the cap, so that it has valence 4 next to its pole); use {p} or {m} \
             for other facets"
        )
    } else if name == m.name() {
        format!(
            "{m} needs every extraordinary element surrounded by regular vertices (four \
             quads) and facets with a DS-net; refine with {p} first when the net has only facets, \
             or use {p}, {t} or {r} on their own, which separate elements by themselves"
        )
    } else {
        format!(
            "the elements stay too close even after two whole-net steps; use {p}, which \
             separates elements by itself"
        )
    };
    Error::Unsupported(format!("{what}: {way_out}"))
}

fn regular(mesh: &PolyMesh, v: usize) -> bool {
    ds::regular_vertex_patch(mesh, v).is_some()
}

/// The level-0 local DS-net of facet `f` (its `a, b, c, d`; the outer layer is not read).
fn pgs_element(mesh: &PolyMesh, f: usize, name: &str) -> Result<RingElement> {
    let n = mesh.face_size(f);
    let net = Pgs::facet_net(mesh, f).ok_or_else(|| {
        not_separated(
            format!(
                "facet {f} ({n} sides) has no DS-net (a corner not of valence 4, a boundary edge \
                 or a neighbour that is not a quad)"
            ),
            name,
        )
    })?;
    let a0 = net.a[0] as usize;
    let mut local = vec![Stencil::point(a0); 9 * n];
    let h0 = mesh.face_halfedge(f);
    for s in 0..n {
        let a = net.a[s] as usize;
        // The corner quad: a's face after the quad across edge a_s a_(s+1), counter-clockwise.
        let h = h0 + s as u32;
        let t = mesh
            .he_twin(mesh.he_prev(h))
            .ok_or_else(|| not_separated(format!("facet {f} touches the boundary"), name))?;
        // t leaves a_s into the quad across edge a_(s-1) a_s; the face clockwise of it...
        let g = mesh.he_twin(mesh.he_prev(t)).ok_or_else(|| {
            not_separated(format!("corner {a} of facet {f} is on the boundary"), name)
        })?;
        let cf = mesh.he_face(g) as usize;
        if mesh.face_size(cf) != 4 {
            return Err(not_separated(
                format!("the corner face {cf} at vertex {a} of facet {f} is not a quad"),
                name,
            ));
        }
        let c = mesh.he_to(mesh.he_next(g)) as usize;
        let (b, d) = (net.b[s] as usize, net.d[s] as usize);
        for v in [b, c, d] {
            if !regular(mesh, v) {
                return Err(not_separated(
                    format!("vertex {v} next to facet {f} is not regular"),
                    name,
                ));
            }
        }
        local[ds_net_index(s, 0, 0)] = Stencil::point(a);
        local[ds_net_index(s, 1, 0)] = Stencil::point(b);
        local[ds_net_index(s, 1, 1)] = Stencil::point(c);
        local[ds_net_index(s, 0, 1)] = Stencil::point(d);
    }
    Ok(RingElement {
        element: Element::Face(f as u32),
        scheme: LocalScheme::pgs(n)?,
        local0: local,
        start: 0,
        sectors: Vec::new(),
        split: thirds::Split::Thirds,
        cells: FacetCells::of(mesh, f),
        pole: None,
    })
}

/// The level-0 local q-net of extraordinary vertex `v` (its 1-ring; the second ring is not
/// read).
fn ternary_element(
    mesh: &PolyMesh,
    v: usize,
    rules: TernaryRules,
    name: &str,
) -> Result<RingElement> {
    let idx = mesh.cnet_indices(v, 1).ok_or_else(|| {
        not_separated(
            format!("vertex {v} is not surrounded by a ring of quads"),
            name,
        )
    })?;
    let n = (idx.len() - 1) / 2;
    let mut local = vec![Stencil::point(v); 1 + 6 * n];
    for s in 0..n {
        let (a, b) = (idx[1 + 2 * s] as usize, idx[2 + 2 * s] as usize);
        for x in [a, b] {
            if !regular(mesh, x) {
                return Err(not_separated(
                    format!("vertex {x} next to extraordinary vertex {v} is not regular"),
                    name,
                ));
            }
        }
        local[qnet_index(s, 1, 0)] = Stencil::point(a);
        local[qnet_index(s, 1, 1)] = Stencil::point(b);
    }
    Ok(RingElement {
        element: Element::Vertex(v as u32),
        scheme: LocalScheme::ternary(n, rules)?,
        local0: local,
        start: 0,
        sectors: Vec::new(),
        split: thirds::Split::Thirds,
        cells: None,
        pole: None,
    })
}

/// The level-0 local polar net of pole `p` (its `a, b` rings; `c` is not read).
fn polar_element(mesh: &PolyMesh, p: usize, element: Element, name: &str) -> Result<RingElement> {
    let hs = mesh.outgoing_halfedges(p);
    let n = hs.len();
    let mut local = vec![Stencil::point(p); 1 + 3 * n];
    for (s, &h) in hs.iter().enumerate() {
        let a = mesh.he_to(h) as usize;
        let nb = mesh.vertex_neighbors(a);
        let ring: Vec<usize> = [hs[(s + 1) % n], hs[(s + n - 1) % n]]
            .iter()
            .map(|&g| mesh.he_to(g) as usize)
            .collect();
        let out: Vec<usize> = nb
            .iter()
            .map(|&x| x as usize)
            .filter(|&x| x != p && !ring.contains(&x))
            .collect();
        if mesh.is_boundary_vertex(a) || nb.len() != 4 || out.len() != 1 {
            return Err(not_separated(
                format!("vertex {a} next to pole {p} does not have valence 4 with one spoke"),
                name,
            ));
        }
        let b = out[0];
        if !regular(mesh, b) {
            return Err(not_separated(
                format!("vertex {b} on the second ring around pole {p} is not regular"),
                name,
            ));
        }
        local[1 + 3 * s] = Stencil::point(a);
        local[2 + 3 * s] = Stencil::point(b);
    }
    Ok(RingElement {
        element,
        scheme: LocalScheme::polar(n)?,
        local0: local,
        start: 0,
        sectors: Vec::new(),
        split: thirds::Split::Thirds,
        cells: None,
        pole: PoleCells::of(mesh, &hs),
    })
}

/// Regular patches of every regular vertex (with knot widths when given), then rings and the
/// G^1 cap of [`g1`] (or the fill, with a note) of every element. With `track` (`mesh` is the
/// input net, no widths) the patches record the input-face cells they cover ([`cells`]); with
/// `face_cells` (where each face of `mesh` lies in the input faces, TPS) the regular patches
/// and the rings and caps of elements with `sectors` record their face domains in thirds
/// ([`thirds`]).
fn assemble(
    mesh: &PolyMesh,
    track: bool,
    widths: Option<&Widths>,
    face_cells: Option<&thirds::FaceCells>,
    elements: &[RingElement],
    opts: ComplexOptions,
    mut progress: impl FnMut(usize),
) -> Result<(PatchComplex, Vec<String>)> {
    let pos = mesh.positions();
    let mut out = PatchComplex::new();
    push_regular_patches(mesh, track, widths, face_cells, &mut out);
    // Each element's local net is carried as positions, not as stencils over the input: a
    // facet's centre reads all n ring points, so composed stencils would grow to n entries
    // per point (n^2 work per level, n^3 with the merges) where positions cost n per level.
    let mut locals: Vec<Vec<Point>> = elements
        .iter()
        .map(|e| e.local0.iter().map(|s| s.apply(pos)).collect())
        .collect();
    for l in 1..=opts.rings {
        for (el, local) in elements.iter().zip(locals.iter_mut()) {
            let step = el.scheme.step(el.start + l - 1);
            *local = step.apply(local);
            push_ring(el, l, local, track, &mut out);
        }
        progress(l);
    }
    let mut notes = Vec::new();
    if opts.fill {
        let mut masks = g1::Masks::default();
        for (el, local) in elements.iter().zip(&locals) {
            push_cap(
                el, opts.rings, local, track, &mut masks, &mut out, &mut notes,
            )?;
        }
    }
    Ok((out, notes))
}

/// The bi-2 patch of the control coefficients `c` over an element's local net `local`.
fn local_patch(c: &[Stencil], local: &[Point]) -> BezierPatch {
    let cps: Vec<Point> = c.iter().map(|s| s.apply(local)).collect();
    BezierPatch::new(2, 2, cps)
}

/// The regular patch of every regular vertex (with knot widths when given), its boundary
/// sides marked and, with `track` or `face_cells`, its input-face pieces recorded.
fn push_regular_patches(
    mesh: &PolyMesh,
    track: bool,
    widths: Option<&Widths>,
    face_cells: Option<&thirds::FaceCells>,
    out: &mut PatchComplex,
) {
    let pos = mesh.positions();
    for v in 0..mesh.num_vertices() {
        let patch = match widths {
            Some(w) => crate::schemes::bi2::ternary::regular_patch(mesh, w, v),
            None => ds::regular_vertex_patch(mesh, v),
        };
        if let Some(c) = patch {
            let face = mesh.vertex_faces(v).first().copied().unwrap_or(0);
            let cps = c.iter().map(|s| s.apply(pos)).collect();
            out.push(BezierPatch::new(2, 2, cps), Provenance::Regular { face });
            ds::mark_boundary_sides(mesh, v, out);
            if track {
                ds::input_vertex_pieces(mesh, v, out);
            } else if let Some(cells) = face_cells {
                thirds::vertex_pieces(mesh, cells, v, (out.len() - 1) as u32, out);
            }
        }
    }
}

/// Ring `l` of element `el` from its local net `local` at that level, with the ring's
/// domains (tracked cells, pole cells, or thirds of the sectors).
fn push_ring(el: &RingElement, l: usize, local: &[Point], track: bool, out: &mut PatchComplex) {
    let first = out.len();
    for (i, (c, sector)) in el.scheme.ring(el.start + l).into_iter().enumerate() {
        let prov = Provenance::Ring {
            element: el.element,
            ring: l as u32,
            sector,
        };
        let cell = match (&el.cells, track) {
            (Some(cells), true) => cells.ring(el.start + l, i / 3, i % 3),
            _ => Domain::UNTRACKED,
        };
        out.push_in(local_patch(&c, local), prov, cell);
        if let (Some(pole), true) = (&el.pole, track) {
            pole.ring(el.start + l, i, (out.len() - 1) as u32, out);
        }
    }
    if !el.sectors.is_empty() {
        thirds::ring_pieces(&el.sectors, l, first, el.split, out);
    }
}

/// The G^1 cap of element `el` inside its last ring (`rings`), from its local net there; where
/// the cap cannot be built, the C^0 fill with a note. With the cap's domains as the rings'.
fn push_cap(
    el: &RingElement,
    rings: usize,
    local: &[Point],
    track: bool,
    masks: &mut g1::Masks,
    out: &mut PatchComplex,
    notes: &mut Vec<String>,
) -> Result<()> {
    // The fill reads the local net and, at index `size`, the limit point.
    let l = el.start + rings;
    let mut with_limit = local.to_vec();
    with_limit.push(el.scheme.limit()?.apply(local));
    let fill: Vec<(BezierPatch, u32)> = el
        .scheme
        .fill(l)?
        .iter()
        .map(|(c, sector)| (local_patch(c, &with_limit), *sector))
        .collect();
    let patches: Vec<BezierPatch> = fill.iter().map(|(p, _)| p.clone()).collect();
    let cap = g1::element_cap(&el.scheme, l, local, &patches, masks, out.len());
    let capped: Vec<(BezierPatch, u32)> = match cap {
        Ok((cap, step)) => {
            out.caps.extend(step);
            cap.into_iter().zip(fill.iter().map(|f| f.1)).collect()
        }
        Err(e) => {
            notes.push(format!(
                "{} (valence {}): the C^0 fill closes the hole, no G^1 cap ({e})",
                crate::host::caps::describe(el.element),
                el.scheme.n
            ));
            fill
        }
    };
    let first = out.len();
    for (p, sector) in capped {
        let prov = Provenance::Cap {
            element: el.element,
            sector,
        };
        let cell = match (&el.cells, track) {
            (Some(cells), true) => cells.cap(l, sector as usize),
            _ => Domain::UNTRACKED,
        };
        out.push_in(p, prov, cell);
        if let (Some(pole), true) = (&el.pole, track) {
            pole.cap(l, sector as usize, (out.len() - 1) as u32, out);
        }
    }
    if !el.sectors.is_empty() {
        thirds::cap_domains(&el.sectors, rings, first, el.split, out);
    }
    Ok(())
}

/// The PGS surface of any polygon mesh, through the Doo-Sabin machinery of [`crate::schemes::doo_sabin::surface`]
/// (regular bi-2 patches, `3 n` bi-2 patches per ring around every facet, extraordinary
/// vertices becoming facets after one step, the fill centred at the limit point (7)). With
/// `pgs.dscc_steps > 0` the net is first refined that many times by DS^CC (the paper's prism
/// experiment); the complex is then that of the pre-processed net.
///
/// # Errors
/// As [`crate::schemes::doo_sabin::surface::doo_sabin_complex`].
pub fn pgs_complex(
    mesh: &PolyMesh,
    opts: ComplexOptions,
    pgs: PgsOptions,
    progress: impl FnMut(usize),
) -> Result<PatchComplex> {
    let corner = |m: &PolyMesh, h: u32| Pgs::corner_stencil(m, h);
    let limit = |m: &PolyMesh, f: usize| Pgs::facet_limit_stencil(m, f);
    let rules = ds::DualRules {
        corner: &corner,
        face_corners: &Pgs::face_corners,
        facet_limit: &limit,
    };
    if pgs.dscc_steps == 0 {
        return ds::dual_complex_with(mesh, opts, &rules, ids::PGS.name(), progress);
    }
    // The DS^CC steps carry the input faces' cells down to the refined net's vertices
    // (`pgs-dscc` evaluates on the input's faces, see `crate::bezier::domain`).
    let mut pre = mesh.clone();
    let mut cells: Option<Vec<crate::bezier::domain::Domain>> = None;
    for _ in 0..pgs.dscc_steps {
        let child = crate::schemes::doo_sabin::fourier::refine_cc_net(&pre)?;
        cells = Some(ds::step_cells(&pre, cells.as_deref(), &child));
        pre = child;
    }
    let cells = cells.expect("at least one step");
    ds::dual_complex_in_cells(&pre, &cells, opts, &rules, ids::PGS.name(), progress)
}

/// The TPS surface ([`TernaryRules::TPS`]) or adjustable TPS surface
/// ([`TernaryRules::adjustable`]) of a quad net:
/// regular bi-2 patches, `2 n` patches per ring around every extraordinary vertex, the fill.
/// Extraordinary vertices too close to each other are separated by one or two whole-net steps
/// of the scheme first (exact: the steps carry the knot widths, and the regular patches of the
/// refined net are converted with them), reported in the notes.
///
/// # Errors
/// [`Error::Unsupported`] for non-quad faces and extraordinary boundary vertices, naming the
/// element and the way out.
pub fn tps_complex(
    mesh: &PolyMesh,
    opts: ComplexOptions,
    rules: TernaryRules,
    mut progress: impl FnMut(usize),
) -> Result<(PatchComplex, Vec<String>)> {
    let name = if rules == TernaryRules::TPS {
        ids::TPS.name()
    } else {
        ids::TPS_ADJUSTABLE.name()
    };
    let mut m = mesh.clone();
    let mut w = uniform_widths(mesh);
    let mut notes = Vec::new();
    // Where each face of `m` lies in the input faces: TPS's refined faces are thirds of the
    // input faces, adjustable TPS's rectangles at the knots (`thirds`).
    let split = if rules == TernaryRules::TPS {
        thirds::Split::Thirds
    } else {
        thirds::Split::At(1.0 - 2.0 * rules.e)
    };
    let mut face_cells = thirds::FaceCells::input(mesh);
    // Validate the net as the scheme would (quads, boundary rules).
    ternary_step(&m, &w, &rules, name)?;
    for start in 0..=2 {
        let evs: Vec<usize> = (0..m.num_vertices())
            .filter(|&v| !m.is_boundary_vertex(v) && m.valence(v) != 4)
            .collect();
        let built: Result<Vec<RingElement>> = evs
            .iter()
            .map(|&v| {
                let mut el = ternary_element(&m, v, rules, name)?;
                el.start = start;
                el.sectors = thirds::sector_cells(&m, &face_cells, v);
                el.split = split;
                Ok(el)
            })
            .collect();
        match built {
            Ok(elements) => {
                let cells = Some(&face_cells);
                let (c, more) =
                    assemble(&m, false, Some(&w), cells, &elements, opts, &mut progress)?;
                notes.extend(more);
                return Ok((c, notes));
            }
            Err(_) if start < 2 => {
                notes.push(format!(
                    "extraordinary vertices too close for rings on the given net: applied a \
                     whole-net {name} step first (exact: it refines the same surface); rings \
                     count from the refined net"
                ));
                let (r, nw) = ternary_step(&m, &w, &rules, name)?;
                face_cells = face_cells.step(split, &m, &w, &r.mesh, &nw, rules.e);
                m = r.mesh;
                w = nw;
            }
            Err(err) => return Err(err),
        }
    }
    unreachable!("the loop returns")
}

/// `n`-valent extraordinary element's ring `l` patches from explicit local-net points (the
/// characteristic ring when the points are the characteristic map's control points).
pub fn ring_patches(scheme: &LocalScheme, l: usize, points: &[Point]) -> Vec<BezierPatch> {
    scheme
        .ring(l)
        .into_iter()
        .map(|(c, _)| local_patch(&c, points))
        .collect()
}
