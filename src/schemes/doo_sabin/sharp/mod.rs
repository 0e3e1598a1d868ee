//! Sharp features for the dual (bi-2) schemes' patch output: the net is cut along its
//! infinitely sharp creases, and the ends and junctions of the creases are kept as corners.
//!
//! OpenSubdiv defines sharp features for Catmull-Clark and Loop only; Doo-Sabin has no
//! published crease rules. fairsub's construction (our own, documented here) reuses the dual
//! schemes' boundary rules ([`super`]): a boundary polygon is refined by Chaikin's corner cutting,
//! so the limit boundary is the quadratic B-spline curve of the boundary polygon, and a *kept
//! corner* stays put, so the curve interpolates it (the polygon with the corner doubled).
//!
//! - **Cut.** Every infinitely sharp edge (sharpness at least 10, OpenSubdiv's infinite value)
//!   is made a boundary on both of its sides: the corners of a vertex are grouped into the
//!   sectors between its sharp edges (faces that share a smooth edge at the vertex are in one
//!   sector), and each sector gets its own copy of the vertex (the first keeps the vertex's
//!   index, further copies are numbered after the net's vertices).
//! - **Kept corners.** Both sides of a crease then end on the Chaikin limit of the same polygon.
//!   Where a crease polygon does not simply pass through a vertex (a crease vertex with other
//!   than two sharp edges: a dart, a junction; a crease vertex on the net's boundary; a vertex
//!   tagged as an infinitely sharp corner) the sectors' polygons turn differently, so every copy
//!   of such a vertex is kept as a corner: all sides' curves interpolate it, and the surface
//!   closes along the whole crease (a sharp join, no crack).
//! - **Refused, with the element named:** semi-sharp edges and vertices (sharpness below 10:
//!   no bi-2 rule spends sharpness), darts (a crease ending inside the surface: cut there, the
//!   two sides of the slit would be one curve traced back and forth and the surface would fold
//!   over at its end, where OpenSubdiv's Catmull-Clark dart fades the crease out), an
//!   infinitely sharp corner tag at an interior vertex that no crease reaches (a bi-2 surface
//!   cannot keep an interior point), the boundary mode `none` together with creases (its
//!   trimming would drop the sides of the cut too).
//! - **Boundary modes** ([`super`]): the cut net keeps exactly the vertices above (and, under
//!   edge-and-corner, the net's own corners of one face) as tagged corners and is refined
//!   under edge-only, so a sector of one face that the cut makes where a crease turns around a
//!   single face follows the crease polygon like the other side (kept as a corner it would
//!   crack the crease). TPS, adjustable TPS, polar bi-2 and the mixed scheme refuse `none` and
//!   an `edge-only` corner of one face ([`refuse_boundary_modes`]).
//!   The schemes whose boundary rules keep only single-face corners (TPS, adjustable TPS, polar
//!   bi-2, the mixed scheme) also refuse a kept corner with more faces on one side
//!   ([`refuse_kept_corners_with_faces`]); Doo-Sabin, DS^CC and PGS keep it.
//! - **Holes** (`t hole`) are removed before the cut: a bi-2 patch spans the quarters of the four
//!   faces around its vertex, so a face cannot be kept for support and left unwritten; the
//!   faces around a hole end on the hole's boundary curve instead.

use crate::error::{Error, Result};
use crate::geom::Point;
use crate::mesh::tags::{BoundaryInterpolation, SubdOptions};
use crate::mesh::{Extras, NONE, PolyMesh, SharpEdges};
use crate::schemes::descriptor::SurfaceOutput;
use crate::schemes::sdc::crease::INFINITE;

mod holes;
pub(crate) mod levels;
mod refuse;
mod sides;
pub(crate) mod step;

pub(crate) use holes::{kept_faces, without_holes};
pub use refuse::{kept_corners_with_faces, refuse_boundary_modes, refuse_kept_corners_with_faces};
pub(crate) use sides::keep_crease_sides;

/// A net cut along its creases, with what the cut did (for the notes).
#[derive(Debug)]
pub struct CutNet {
    /// The cut net: creases are boundaries; its extras tag the kept corners (sorted, each with
    /// infinite sharpness) and nothing else.
    pub mesh: PolyMesh,
    /// Notes for the user.
    pub notes: Vec<String>,
}

/// Whether the dual schemes' boundary rules keep vertex `v` as a corner: a boundary vertex the
/// net's extras tag as a sharp vertex (the kept corners of [`cut_along_creases`]; the tags are
/// sorted by vertex), or a boundary vertex with a single face unless the net's boundary mode is
/// `edge-only` ([`super::boundary_mode`]).
pub fn is_kept_corner(mesh: &PolyMesh, v: usize) -> bool {
    mesh.is_boundary_vertex(v)
        && ((mesh.is_corner(v) && super::boundary_mode(mesh) != BoundaryInterpolation::EdgeOnly)
            || is_tagged_corner(mesh, v))
}

/// Whether the extras tag vertex `v` as sharp (the tags are sorted by vertex).
pub(crate) fn is_tagged_corner(mesh: &PolyMesh, v: usize) -> bool {
    mesh.extras().is_some_and(|e| {
        e.sharp_vertices
            .binary_search_by_key(&(v as u32), |p| p.0)
            .is_ok()
    })
}

/// The net cut along its infinitely sharp creases, or `None` when it tags no sharp feature
/// (see the [module](self) documentation). `name` is the scheme's name for messages.
///
/// # Errors
/// [`Error::Unsupported`] for the features the construction cannot take, naming the element.
pub fn cut_along_creases(mesh: &PolyMesh, name: &str) -> Result<Option<CutNet>> {
    let Some(ex) = mesh.extras() else {
        return Ok(None);
    };
    if !ex.has_features() {
        return Ok(None);
    }
    let mode = ex.options.boundary();
    if mode == BoundaryInterpolation::None {
        return Err(Error::Unsupported(format!(
            "the net tags sharp features and asks for the boundary mode none; {name} cuts the \
             net along its creases, and under none the cut would lose its sides like the \
             boundary (not built: choose --boundary edge-only or edge-and-corner, or remove \
             the tags)"
        )));
    }
    let mut notes = Vec::new();
    let mesh = without_holes(mesh, ex.holes.len(), name, &mut notes);
    let ex = mesh.extras().cloned().unwrap_or_default();
    let sharp = sharp_edge_flags(&mesh, &ex, name)?;
    let nv = mesh.num_vertices();

    let Cut {
        positions,
        origin,
        corners,
    } = cut(&mesh, &sharp);
    let crease_valence = crease_valences(&mesh, &sharp);
    let keep = kept_corners(&mesh, &ex, &crease_valence, mode, name)?;
    let face_start = mesh.face_starts().to_vec();
    let kept: Vec<(u32, f32)> = (0..positions.len() as u32)
        .filter(|&v| keep[origin[v as usize] as usize])
        .map(|v| (v, INFINITE))
        .collect();
    let cut_edges = crease_valence.iter().sum::<u32>() / 2;
    let copies = positions.len() - nv;
    let out = PolyMesh::from_flat(positions, face_start, corners)?;
    // the net drops the vertices in no face (those of removed hole faces only): the kept
    // corners follow the renumbering
    let dropped = out.dropped_vertices();
    let kept: Vec<(u32, f32)> = kept
        .into_iter()
        .filter(|p| dropped.binary_search(&(p.0 as usize)).is_err())
        .map(|(v, s)| (v - dropped.partition_point(|&d| d < v as usize) as u32, s))
        .collect();
    let extras = Extras {
        sharp_vertices: kept.clone(),
        options: SubdOptions {
            boundary: Some(BoundaryInterpolation::EdgeOnly),
            ..SubdOptions::default()
        },
        ..Extras::default()
    };
    notes.push(format!(
        "sharp features: the net is cut along its {cut_edges} infinitely sharp edges ({copies} \
         vertex copies, numbered from {nv}); both sides of a crease end on the quadratic \
         B-spline of the crease polygon, which interpolates the {} kept corners (crease ends, \
         junctions, crease vertices on the boundary, corner tags, and under edge-and-corner \
         the net's corners); elements on a crease take the Doo-Sabin boundary rules",
        kept.len()
    ));
    Ok(Some(CutNet {
        mesh: out.with_extras(Some(extras)),
        notes,
    }))
}

/// Per vertex, how many interior sharp edges meet it (a sharp boundary edge is a boundary
/// already).
fn crease_valences(mesh: &PolyMesh, sharp: &[bool]) -> Vec<u32> {
    let mut crease_valence = vec![0u32; mesh.num_vertices()];
    for e in (0..mesh.num_edges()).filter(|&e| sharp[e]) {
        let h = mesh.edge_halfedge(e);
        if mesh.he_twin(h).is_some() {
            crease_valence[mesh.he_from(h) as usize] += 1;
            crease_valence[mesh.he_to(h) as usize] += 1;
        }
    }
    crease_valence
}

/// Per vertex, whether the cut keeps it as a corner: crease ends and junctions, crease
/// vertices on the boundary, corner tags and, under edge-and-corner, the net's own corners.
/// Darts, semi-sharp corners and interior corners off any crease are refused.
fn kept_corners(
    mesh: &PolyMesh,
    ex: &Extras,
    crease_valence: &[u32],
    mode: BoundaryInterpolation,
    name: &str,
) -> Result<Vec<bool>> {
    let nv = mesh.num_vertices();
    // Kept corners; darts refused.
    // A vertex only the removed hole faces had is in no face now: nothing to keep there.
    let in_a_face = |v: usize| mesh.vertex_halfedge(v) != NONE;
    let mut keep = vec![false; nv];
    for (v, k) in keep.iter_mut().enumerate() {
        if !in_a_face(v) {
            continue;
        }
        let c = crease_valence[v];
        let boundary = mesh.is_boundary_vertex(v);
        if c == 1 && !boundary {
            return Err(Error::Unsupported(format!(
                "vertex {v} is a dart (a crease ends there, inside the surface); {name}'s \
                 patches cut the net along its creases and cannot fade a crease out: extend \
                 the crease to a boundary or another crease, or refine with Catmull-Clark or \
                 Loop"
            )));
        }
        *k = c > 0 && (c != 2 || boundary);
    }
    for &(v, s) in &ex.sharp_vertices {
        if s < INFINITE {
            return Err(Error::Unsupported(format!(
                "vertex {v} has the semi-sharp corner value {s}; {name}'s patches take \
                 infinitely sharp features only (sharpness 10 or more)"
            )));
        }
        let v = v as usize;
        if !in_a_face(v) {
            continue;
        }
        if crease_valence[v] == 0 && !mesh.is_boundary_vertex(v) {
            return Err(Error::Unsupported(format!(
                "vertex {v} is tagged as a corner but lies inside the surface with no crease \
                 through it; a {name} surface cannot keep an interior point (tag a crease \
                 through it, or refine with Catmull-Clark or Loop)"
            )));
        }
        keep[v] = true;
    }
    // Under edge-and-corner the net's own corners (a boundary vertex with one face) are kept
    // too; the cut net keeps exactly the tagged vertices (its boundary mode is edge-only), so a
    // sector of one face that the cut makes at a crease vertex follows the crease polygon like
    // the other side, instead of staying put as a corner would.
    if mode == BoundaryInterpolation::EdgeAndCorner {
        for (v, k) in keep.iter_mut().enumerate() {
            *k |= in_a_face(v) && mesh.is_boundary_vertex(v) && mesh.is_corner(v);
        }
    }
    Ok(keep)
}

/// Runs `build` on the net cut along its creases ([`cut_along_creases`]; the net itself when it
/// tags no sharp feature) and adds the cut's notes to its output: the patch output of every
/// dual scheme goes through here.
///
/// # Errors
/// Those of the cut and of `build`.
pub fn on_cut_net(
    mesh: &PolyMesh,
    name: &str,
    semi_sharp: bool,
    build: impl FnOnce(&PolyMesh) -> Result<SurfaceOutput>,
) -> Result<SurfaceOutput> {
    // both nets below are built without the hole faces: the domains go back to the input
    // faces, so that evaluation keeps addressing them
    let to_input = |out: &mut SurfaceOutput| {
        if mesh.extras().is_some_and(|e| !e.holes.is_empty()) {
            out.complex.renumber_faces(&kept_faces(mesh));
        }
    };
    if let Some((net, mut notes)) = semi_sharp_net(mesh, name, semi_sharp)? {
        let mut out = build(&net)?;
        keep_crease_sides(&mut out.complex);
        notes.append(&mut out.notes);
        out.notes = notes;
        to_input(&mut out);
        return Ok(out);
    }
    match cut_along_creases(mesh, name)? {
        None => {
            let mut out = build(mesh)?;
            // no crease: the boundary sides the host marked are the surface's boundary
            out.complex.sharp_sides.clear();
            Ok(out)
        }
        Some(cut) => {
            let mut out = build(&cut.mesh)?;
            keep_crease_sides(&mut out.complex);
            let mut notes = cut.notes;
            notes.append(&mut out.notes);
            out.notes = notes;
            to_input(&mut out);
            Ok(out)
        }
    }
}

/// Whether `mesh` tags a semi-sharp feature (a finite positive sharpness).
pub fn has_semi_sharp(mesh: &PolyMesh) -> bool {
    spending_steps(mesh) > 0
}

/// How many dual steps spend every finite sharpness of `mesh`: the ceiling of the largest
/// finite positive sharpness (each step lowers every finite value by one, OpenSubdiv's
/// fractional blend taking the last fraction); 0 without one.
pub(crate) fn spending_steps(mesh: &PolyMesh) -> usize {
    let Some(ex) = mesh.extras() else {
        return 0;
    };
    let edges: Box<dyn Iterator<Item = f32>> = match &ex.sharp_edges {
        SharpEdges::ById(v) => Box::new(v.iter().map(|p| p.1)),
        SharpEdges::ByPair(v) => Box::new(v.iter().map(|p| p.1)),
    };
    let top = edges
        .chain(ex.sharp_vertices.iter().map(|p| p.1))
        .filter(|&s| crate::schemes::sdc::crease::adaptive::is_semi(s))
        .fold(0.0f32, f32::max);
    top.ceil() as usize
}

/// For a net with semi-sharp features: the net the builder refines with its creases in place
/// (holes removed, as for the cut), with the notes; `None` for a net without them (it is cut
/// along its infinitely sharp creases instead). `takes` says whether the scheme's patches take
/// semi-sharp features; a scheme whose patches do not refuses the net, naming an element.
///
/// # Errors
/// [`Error::Unsupported`] for a scheme without semi-sharp patches, and for infinitely sharp
/// darts, which the patches cannot finish (they are refined forever).
fn semi_sharp_net(
    mesh: &PolyMesh,
    name: &str,
    takes: bool,
) -> Result<Option<(PolyMesh, Vec<String>)>> {
    if !has_semi_sharp(mesh) {
        return Ok(None);
    }
    let ex = mesh.extras().cloned().unwrap_or_default();
    if !takes {
        // the first semi-sharp edge or vertex names the refusal, as before
        sharp_edge_flags(mesh, &ex, name)?;
        if let Some(&(v, s)) = ex.sharp_vertices.iter().find(|p| p.1 < INFINITE) {
            return Err(Error::Unsupported(format!(
                "vertex {v} has the semi-sharp corner value {s}; {name}'s patches take \
                 infinitely sharp features only (sharpness 10 or more)"
            )));
        }
    }
    let mut notes = Vec::new();
    let net = without_holes(mesh, ex.holes.len(), name, &mut notes);
    let sharpness = edge_sharpness(&net, &net.extras().cloned().unwrap_or_default())?;
    let mut infinite = vec![0u32; net.num_vertices()];
    for (e, &s) in sharpness.iter().enumerate() {
        let h = net.edge_halfedge(e);
        if s >= INFINITE && net.he_twin(h).is_some() {
            infinite[net.he_from(h) as usize] += 1;
            infinite[net.he_to(h) as usize] += 1;
        }
    }
    if let Some(v) =
        (0..net.num_vertices()).find(|&v| infinite[v] == 1 && !net.is_boundary_vertex(v))
    {
        return Err(Error::Unsupported(format!(
            "vertex {v} is a dart of an infinitely sharp crease (it ends there, inside the \
             surface); {name}'s patches cannot fade an infinitely sharp crease out: extend the \
             crease to a boundary or another crease, give it a finite sharpness, or refine \
             with Catmull-Clark or Loop"
        )));
    }
    notes.push(format!(
        "semi-sharp features: fairsub's crease construction for {name} (the creases' sharp \
         rules, the Chaikin points of both sides, for as many levels as their sharpness, \
         OpenSubdiv's fractional blend on the last; see docs/guide/src/creases.md); \
         the patches are refined until every finite sharpness is spent"
    ));
    Ok(Some((net, notes)))
}

/// Where one level of the adaptive host has creases (sharp edges inside the surface).
#[derive(Debug, Clone)]
pub(crate) struct LevelCreases {
    /// Per face: it has a crease edge.
    pub faces: Vec<bool>,
    /// Per vertex: it is an end of a crease edge.
    pub vertices: Vec<bool>,
}

/// The crease data of one level of the adaptive host (`None` when it has no crease), and the
/// level's `calm` after a parent level with `parent_calm` (0 when it holds a semi-sharp value).
pub(crate) fn level_creases(mesh: &PolyMesh, parent_calm: usize) -> (Option<LevelCreases>, usize) {
    use crate::schemes::sdc::crease::adaptive::calm_after;
    let Some(ex) = mesh.extras() else {
        return (None, calm_after(parent_calm, &[], &[]));
    };
    let mut values = Vec::new();
    let mut at = LevelCreases {
        faces: vec![false; mesh.num_faces()],
        vertices: vec![false; mesh.num_vertices()],
    };
    let mut any = false;
    let mut mark = |e: Option<u32>, s: f32| {
        values.push(s);
        let Some(e) = e else { return };
        let h = mesh.edge_halfedge(e as usize);
        if let (true, Some(t)) = (s > 0.0, mesh.he_twin(h)) {
            at.faces[mesh.he_face(h) as usize] = true;
            at.faces[mesh.he_face(t) as usize] = true;
            at.vertices[mesh.he_from(h) as usize] = true;
            at.vertices[mesh.he_to(h) as usize] = true;
            any = true;
        }
    };
    match &ex.sharp_edges {
        SharpEdges::ById(v) => v.iter().for_each(|&(e, s)| mark(Some(e), s)),
        SharpEdges::ByPair(v) => v
            .iter()
            .for_each(|&([a, b], s)| mark(mesh.find_edge(a, b), s)),
    }
    let vertices: Vec<f32> = ex.sharp_vertices.iter().map(|p| p.1).collect();
    let calm = calm_after(parent_calm, &values, &vertices);
    (any.then_some(at), calm)
}

/// Per edge: infinitely sharp. Semi-sharp edges are refused.
fn sharp_edge_flags(mesh: &PolyMesh, ex: &Extras, name: &str) -> Result<Vec<bool>> {
    let values = edge_sharpness(mesh, ex)?;
    let mut sharp = vec![false; values.len()];
    for (e, &s) in values.iter().enumerate() {
        if s > 0.0 && s < INFINITE {
            let h = mesh.edge_halfedge(e);
            let (a, b) = (mesh.he_from(h), mesh.he_to(h));
            return Err(Error::Unsupported(format!(
                "the edge {a}-{b} has the semi-sharp crease value {s}; {name}'s patches take \
                 infinitely sharp creases only (sharpness 10 or more); for semi-sharp \
                 creases use {}, {}, {} or {} (fairsub's crease construction), or \
                 Catmull-Clark or Loop",
                crate::schemes::options::ids::DOO_SABIN,
                crate::schemes::options::ids::DOO_SABIN_CC,
                crate::schemes::options::ids::PGS,
                crate::schemes::options::ids::NONBOX
            )));
        }
        sharp[e] = s > 0.0;
    }
    Ok(sharp)
}

/// The sharpness of every edge as the extras tag it (0 where they do not).
///
/// # Errors
/// [`Error::Unsupported`] for a tagged pair that is not an edge of the net.
pub(crate) fn edge_sharpness(mesh: &PolyMesh, ex: &Extras) -> Result<Vec<f32>> {
    let mut out = vec![0f32; mesh.num_edges()];
    match &ex.sharp_edges {
        SharpEdges::ById(v) => {
            for &(e, s) in v {
                out[e as usize] = s;
            }
        }
        SharpEdges::ByPair(v) => {
            for &([a, b], s) in v {
                let e = mesh.find_edge(a, b).ok_or_else(|| {
                    Error::Unsupported(format!("the sharp edge {a}-{b} is not an edge of the net"))
                })?;
                out[e as usize] = s;
            }
        }
    }
    Ok(out)
}

/// A net cut along some of its edges: a vertex per sector between the cut edges.
pub(crate) struct Cut {
    /// Positions: the net's, then one copy per further sector of a vertex.
    pub positions: Vec<Point>,
    /// The net's vertex of each vertex of the cut net.
    pub origin: Vec<u32>,
    /// The face corners (the net's faces in order).
    pub corners: Vec<u32>,
}

/// `mesh` cut along the edges inside the surface that `sharp` flags: the corners of a vertex
/// are grouped into the sectors between its cut edges (faces that share an uncut edge at the
/// vertex are in one sector), and each sector gets its own copy of the vertex (the first keeps
/// the vertex's index, further copies are numbered after the net's vertices).
pub(crate) fn cut(mesh: &PolyMesh, sharp: &[bool]) -> Cut {
    let (nh, nv) = (mesh.num_halfedges(), mesh.num_vertices());
    // Sectors: union the two corners of every smooth interior edge at each of its ends.
    let mut parent: Vec<u32> = (0..nh as u32).collect();
    for e in 0..mesh.num_edges() {
        let h = mesh.edge_halfedge(e);
        let Some(t) = mesh.he_twin(h) else { continue };
        if sharp[e] {
            continue;
        }
        union(&mut parent, h, mesh.he_next(t));
        union(&mut parent, t, mesh.he_next(h));
    }
    // A vertex per sector: the first sector of a vertex keeps its index.
    let mut id = vec![NONE; nh];
    let mut used = vec![false; nv];
    let mut positions = mesh.positions().to_vec();
    let mut origin: Vec<u32> = (0..nv as u32).collect();
    let mut corners = Vec::with_capacity(nh);
    for h in 0..nh as u32 {
        let r = find(&mut parent, h) as usize;
        if id[r] == NONE {
            let v = mesh.he_from(h) as usize;
            id[r] = if used[v] {
                positions.push(positions[v]);
                origin.push(v as u32);
                (positions.len() - 1) as u32
            } else {
                used[v] = true;
                v as u32
            };
        }
        // half-edges are numbered face after face, corner after corner
        corners.push(id[r]);
    }
    Cut {
        positions,
        origin,
        corners,
    }
}

/// The level of the adaptive host cut along its creases once all of them are infinitely sharp
/// (the last semi-sharp value spent): from there on its crease sides are boundaries, refined
/// by the boundary rules and patched like boundaries, as the net cut along its creases at the
/// start is ([`cut_along_creases`]). Returns the cut net, the net's vertex of each of its
/// vertices, and the cut net's extras (its kept corners: the vertices OpenSubdiv's rules make
/// corners, tagged infinitely sharp; the boundary mode edge-only).
///
/// # Errors
/// [`Error::Unsupported`] for a dart of an infinitely sharp crease (a semi-sharp crease that
/// carried it on has been spent) and those of building the cut net.
pub(crate) fn cut_level(mesh: &PolyMesh, name: &str) -> Result<(PolyMesh, Vec<u32>)> {
    let ex = mesh.extras().cloned().unwrap_or_default();
    let values = edge_sharpness(mesh, &ex)?;
    let sharp: Vec<bool> = (0..mesh.num_edges())
        .map(|e| values[e] > 0.0 && mesh.he_twin(mesh.edge_halfedge(e)).is_some())
        .collect();
    let mut crease_valence = vec![0u32; mesh.num_vertices()];
    for e in (0..mesh.num_edges()).filter(|&e| sharp[e]) {
        let h = mesh.edge_halfedge(e);
        crease_valence[mesh.he_from(h) as usize] += 1;
        crease_valence[mesh.he_to(h) as usize] += 1;
    }
    let tagged = |v: usize| is_tagged_corner(mesh, v);
    let keep: Vec<bool> = (0..mesh.num_vertices())
        .map(|v| {
            let c = crease_valence[v];
            tagged(v) || (c > 0 && (c != 2 || mesh.is_boundary_vertex(v)))
        })
        .collect();
    if let Some(v) =
        (0..mesh.num_vertices()).find(|&v| crease_valence[v] == 1 && !mesh.is_boundary_vertex(v))
    {
        return Err(Error::Unsupported(format!(
            "a semi-sharp crease carried an infinitely sharp one on at a point that becomes a \
             dart (vertex {v} of a refined level); {name}'s patches cannot fade an infinitely \
             sharp crease out: extend it to a boundary or another infinitely sharp crease"
        )));
    }
    let Cut {
        positions,
        origin,
        corners,
    } = cut(mesh, &sharp);
    let kept: Vec<(u32, f32)> = (0..positions.len() as u32)
        .filter(|&v| keep[origin[v as usize] as usize])
        .map(|v| (v, INFINITE))
        .collect();
    let out = PolyMesh::from_partial_refinement(positions, mesh.face_starts().to_vec(), corners)?;
    let extras = Extras {
        sharp_vertices: kept,
        options: SubdOptions {
            boundary: Some(BoundaryInterpolation::EdgeOnly),
            ..SubdOptions::default()
        },
        sharpened: true,
        ..Extras::default()
    };
    Ok((out.with_extras(Some(extras)), origin))
}

fn find(parent: &mut [u32], mut x: u32) -> u32 {
    while parent[x as usize] != x {
        let p = parent[parent[x as usize] as usize];
        parent[x as usize] = p;
        x = p;
    }
    x
}

fn union(parent: &mut [u32], a: u32, b: u32) {
    let (ra, rb) = (find(parent, a), find(parent, b));
    if ra != rb {
        parent[ra.max(rb) as usize] = ra.min(rb);
    }
}
