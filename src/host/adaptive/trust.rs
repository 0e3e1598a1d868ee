//! The trust rule of the child points of one step over selected faces (a sparse split): a
//! child point's position equals full refinement's when every point its rule reads does (and,
//! for a vertex or edge point, when the ring it reads is the true one); a child vertex's
//! one-ring is the true one when its parent's was and every face around it is refined. Written
//! once for the quad split (Catmull-Clark, non-box), the triangle split (Loop) and the dual
//! split (the Doo-Sabin family), whose schemes only say what their rules read.

use super::Info;
use crate::mesh::{Element, PolyMesh};
use crate::stencil::Stencil;

/// The trust of the child points of one step of `mesh` (a level whose points have trust
/// `info`) over the selected faces `sel` (see the [module](self) documentation).
pub(crate) struct SplitTrust<'a> {
    mesh: &'a PolyMesh,
    info: &'a [Info],
    sel: &'a [bool],
}

impl<'a> SplitTrust<'a> {
    /// The rule for one step of `mesh` over the faces `sel` (one flag per face).
    pub(crate) fn new(mesh: &'a PolyMesh, info: &'a [Info], sel: &'a [bool]) -> Self {
        SplitTrust { mesh, info, sel }
    }

    /// Whether every point `s` reads is trusted.
    pub(crate) fn reads_ok(&self, s: &Stencil) -> bool {
        s.entries()
            .iter()
            .all(|&(x, _)| self.info[x as usize].pos_ok)
    }

    /// Whether every corner of face `f` is trusted.
    pub(crate) fn face_ok(&self, f: u32) -> bool {
        self.mesh
            .face(f as usize)
            .iter()
            .all(|&x| self.info[x as usize].pos_ok)
    }

    /// Whether vertex `v` has its true fan and every face of it is refined: its child's
    /// one-ring is the true one.
    pub(crate) fn whole_fan(&self, v: usize) -> bool {
        let m = self.mesh;
        self.info[v].fan_ok && m.outgoing(v).all(|h| self.sel[m.he_face(h) as usize])
    }

    /// Whether the end of an edge at half-edge `h` has its true fan, or the edge a second face:
    /// then whether the edge lies on the boundary is known (the plain rule; sharpness that
    /// decays may need both ends).
    pub(crate) fn edge_side_known(&self, h: u32) -> bool {
        let m = self.mesh;
        m.he_twin(h).is_some()
            || self.info[m.he_from(h) as usize].fan_ok
            || self.info[m.he_to(h) as usize].fan_ok
    }

    /// The vertex point of parent vertex `v` whose rule reads trusted points (`reads_ok`): it
    /// keeps `v`'s origin.
    pub(crate) fn vertex(&self, v: usize, reads_ok: bool) -> Info {
        Info {
            pos_ok: self.info[v].fan_ok && reads_ok,
            fan_ok: self.whole_fan(v),
            origin: self.info[v].origin,
        }
    }

    /// The edge point of parent edge `e`, `known` when the edge's boundary status and sharpness
    /// are those of the whole net: its one-ring is the true one when both faces of the edge
    /// are refined.
    pub(crate) fn edge(&self, e: usize, known: bool, reads_ok: bool) -> Info {
        let m = self.mesh;
        let h = m.edge_halfedge(e);
        let both = self.sel[m.he_face(h) as usize]
            && m.he_twin(h).is_none_or(|t| self.sel[m.he_face(t) as usize]);
        Info {
            pos_ok: known && reads_ok,
            fan_ok: known && both,
            origin: None,
        }
    }

    /// A point inside a parent face that no one-ring of the rules has as its centre (a face
    /// point, a face control vertex), with its input `origin` (a non-quad face's centre).
    pub(crate) fn face_point(&self, reads_ok: bool, origin: Option<Element>) -> Info {
        Info {
            pos_ok: reads_ok,
            fan_ok: true,
            origin,
        }
    }

    /// A point of the dual split beside parent vertex `v` (a corner point of a face at `v`, a
    /// Chaikin point of an edge at `v`, `v`'s kept point): its fan in the child is the one of
    /// `v`, true when `v`'s whole fan is refined.
    pub(crate) fn dual_point(&self, v: usize, reads_ok: bool) -> Info {
        Info {
            pos_ok: reads_ok,
            fan_ok: self.whole_fan(v),
            origin: None,
        }
    }
}
