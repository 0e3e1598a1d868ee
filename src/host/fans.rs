//! The fans of quad sectors around a hole's centre vertex that the quad-layout G^1 caps of
//! Catmull-Clark (and its cap schemes' fallbacks) and non-box read their holes off: closed
//! around an interior vertex, open at a boundary vertex, or between the two infinitely sharp
//! edges of a crease vertex; and the hole's segments over such a fan.

use super::adaptive::NoCap;
use crate::mesh::PolyMesh;

/// One sector of a quad-layout hole around a vertex `x`: the quad `face = [x, p, K, q]` with
/// `x` at corner `corner`, and the half-edges `p -> K` and `K -> q` across which the hole's
/// segments `a` (from `p`) and `b` (from `q`) are read.
#[derive(Debug, Clone, Copy)]
pub struct QuadSector {
    /// The face.
    pub face: u32,
    /// Corner of `x` in the face.
    pub corner: usize,
    /// The corner after `x` (end of spoke `s`).
    pub p: u32,
    /// The corner before `x` (end of spoke `s + 1`).
    pub q: u32,
    /// The half-edge `p -> K`.
    pub pk: u32,
    /// The half-edge `K -> q`.
    pub kq: u32,
}

/// The faces counter-clockwise around `from(ha)` from the face of `ha` to the one whose edge
/// into the vertex is the twin of `hb` (at most the valence); `None` at the boundary.
pub fn faces_between(m: &PolyMesh, ha: u32, hb: u32) -> Option<Vec<u32>> {
    let mut h = ha;
    let mut faces = Vec::new();
    for _ in 0..m.valence(m.he_from(ha) as usize) {
        faces.push(m.he_face(h));
        let out = m.he_twin(m.he_prev(h))?;
        if out == hb {
            return Some(faces);
        }
        h = out;
    }
    None
}

/// The `n` quads around vertex `x` counter-clockwise from face `f0` (Catmull-Clark's and
/// non-box's cap sectors), or `None` when one is not a quad or the walk does not close after
/// `n` faces (a boundary).
pub fn quad_sectors_around(m: &PolyMesh, x: u32, f0: u32, n: usize) -> Option<Vec<QuadSector>> {
    quad_fan(m, x, f0, n, Some(false))
}

/// The `n` quads around boundary vertex `x` counter-clockwise from its boundary half-edge (an
/// open fan: spoke 0 of sector 0 and spoke `n` of sector `n - 1` are its boundary edges), or
/// `None` when one is not a quad or the fan does not have `n` faces.
pub fn quad_sectors_open(m: &PolyMesh, x: u32, n: usize) -> Option<Vec<QuadSector>> {
    let h = m.vertex_halfedge(x as usize);
    if m.he_twin(h).is_some() {
        return None;
    }
    quad_fan(m, x, m.he_face(h), n, Some(true))
}

/// The `k` quads around vertex `x` counter-clockwise from face `f0`, without asking where the
/// walk ends: a sector between two infinitely sharp edges of a crease vertex (spoke 0 the edge
/// `x -> p` of `f0`, spoke `k` the edge `x -> q` of the last face); `None` when one is not a
/// quad or the fan ends before.
pub fn quad_sectors_between(m: &PolyMesh, x: u32, f0: u32, k: usize) -> Option<Vec<QuadSector>> {
    quad_fan(m, x, f0, k, None)
}

/// The walk of [`quad_sectors_around`] (`open = Some(false)`: closing at `f0`),
/// [`quad_sectors_open`] (`Some(true)`: ending at the boundary) and [`quad_sectors_between`]
/// (`None`: `n` faces), on [`fan_walk`].
fn quad_fan(
    m: &PolyMesh,
    x: u32,
    f0: u32,
    n: usize,
    open: Option<bool>,
) -> Option<Vec<QuadSector>> {
    let fan = fan_walk(m, x, f0, n, open, 4)?;
    Some(
        fan.into_iter()
            .map(|(f, k)| {
                let face = m.face(f as usize);
                // The face's half-edges from corner c run to corner c + 1: p -> K, K -> q.
                let he = |c: usize| m.face_halfedge(f as usize) + ((k + c) % 4) as u32;
                QuadSector {
                    face: f,
                    corner: k,
                    p: face[(k + 1) % 4],
                    q: face[(k + 3) % 4],
                    pk: he(1),
                    kq: he(2),
                }
            })
            .collect(),
    )
}

/// The `n` faces of `sides` corners around vertex `x` counter-clockwise from face `f0`, each
/// with the corner of `x` in it: closing at `f0` (`open = Some(false)`), ending on the
/// boundary after `n` faces (`Some(true)`), or just `n` faces (`None`: a side of a crease
/// vertex); `None` when a face has another size or the walk does not end as asked. The one
/// walk of the quad fans here and of Loop's triangle fans.
pub fn fan_walk(
    m: &PolyMesh,
    x: u32,
    f0: u32,
    n: usize,
    open: Option<bool>,
    sides: usize,
) -> Option<Vec<(u32, usize)>> {
    let mut out = Vec::with_capacity(n);
    let mut f = f0;
    for s in 0..n {
        let face = m.face(f as usize);
        if face.len() != sides {
            return None;
        }
        let k = face.iter().position(|&v| v == x)?;
        out.push((f, k));
        // the next face counter-clockwise holds the twin of the face's half-edge into x
        let back = m.face_halfedge(f as usize) + ((k + sides - 1) % sides) as u32;
        match m.he_twin(back) {
            Some(t) => f = m.he_face(t),
            // an open fan ends at its last face, on the boundary
            None => return (open == Some(true) && s + 1 == n).then_some(out),
        }
    }
    match open {
        Some(true) => None,
        Some(false) => (f == f0).then_some(out),
        None => Some(out),
    }
}

/// The segments of a quad-layout hole over its sectors: `across(half_edge, from)` reads the
/// segment along a hole half-edge starting at its end `from` off the ring (`None` while the
/// ring there is not emitted yet); segment `a` of a sector runs from `p` along `p -> K`,
/// segment `b` from `q` along `K -> q`. `NoCap::Later` when some segment is missing.
/// (Generic in what a segment is: its points, or the rows of a tracked patch table.)
pub fn quad_hole_segments<T>(
    sectors: &[QuadSector],
    mut across: impl FnMut(u32, u32) -> Option<T>,
) -> std::result::Result<Vec<Vec<T>>, NoCap> {
    let mut out = Vec::with_capacity(sectors.len());
    for sec in sectors {
        match (across(sec.pk, sec.p), across(sec.kq, sec.q)) {
            (Some(a), Some(b)) => out.push(vec![a, b]),
            _ => return Err(NoCap::Later),
        }
    }
    Ok(out)
}
