//! OpenSubdiv's sharp features (creases, corners, their semi-sharp decay) under non-box
//! subdivision: fairsub's construction, documented in `docs/guide/src/creases.md`.
//!
//! Non-box refinement has the topology of Catmull-Clark's ([`crate::schemes::nonbox`]), and its
//! boundary rules are the cubic B-spline rules of the boundary polygon (`(a + 6 v + b) / 8`,
//! `(a + b) / 2`, a corner stays) with ghost FCVs `a + b - F` across boundary edges. So a crease
//! is a boundary on both of its sides, exactly as Catmull-Clark's crease rules are its boundary
//! rules, and OpenSubdiv's rules carry over rule for rule, read through the shared machinery of
//! [`crate::schemes::sdc::crease`] ([`SharpLevel`]):
//!
//! - **V-vertex**: OpenSubdiv's vertex plan with the non-box V-vertex rule as its smooth mask
//!   (crease `3/4 v + 1/8 (a + b)`, corner `v`, the blend while a feature decays);
//! - **E-vertex**: OpenSubdiv's edge plan with the non-box E-vertex rule as its smooth mask
//!   (crease: the midpoint);
//! - **FCV rule**: unchanged (it reads the face alone);
//! - **NFCV**: across a sharp edge the FCV of the face beyond is replaced by the ghost
//!   `a + b - F_0` of the boundary rule, with the weight the edge plan gives the crease rule
//!   (1 while the edge is sharp, its sharpness on the step where it decays): the two sides of
//!   an infinitely sharp crease are then refined exactly as two boundaries with the same
//!   boundary polygon, so they end on the same cubic B-spline curve (no crack).
//!
//! The child's sharpness is OpenSubdiv's (uniform or Chaikin decay of each half edge), on
//! Catmull-Clark's child topology: the half of edge `e` at `v` joins the child V-vertex of `v`
//! and the child E-vertex of `e`.

use crate::mesh::tags::{BoundaryInterpolation, SubdOptions};
use crate::mesh::{Extras, PolyMesh};
use crate::schemes::sdc::crease::{ChildEdge, Emit, LimitPlan, Scratch, SharpLevel};
use crate::stencil::Stencil;

/// The sharp features of one level of a non-box net, when it has any beyond its boundary.
pub(crate) struct NonBoxCreases<'a> {
    sl: SharpLevel<'a>,
    mesh: &'a PolyMesh,
}

impl<'a> NonBoxCreases<'a> {
    /// The sharp features of `mesh` (its extras; non-box always interpolates its boundary
    /// edge-and-corner, and reads the crease method from the net), or `None` when it tags none
    /// (the plain rules of [`crate::schemes::nonbox`] apply). Hole tags change no rule
    /// (`super::holes`).
    pub fn of(mesh: &'a PolyMesh) -> Option<NonBoxCreases<'a>> {
        let ex = mesh.extras()?;
        // (an edge-only boundary changes the rule at a boundary vertex of one face: the
        // plain rules keep it as a corner)
        let edge_only = ex.options.boundary() == BoundaryInterpolation::EdgeOnly;
        if ex.sharp_edges.is_empty() && ex.sharp_vertices.is_empty() && !edge_only {
            return None;
        }
        // edge-and-corner unless the net says edge-only (a net cut along its creases)
        let opts = SubdOptions {
            boundary: Some(match ex.options.boundary {
                Some(BoundaryInterpolation::EdgeOnly) => BoundaryInterpolation::EdgeOnly,
                _ => BoundaryInterpolation::EdgeAndCorner,
            }),
            crease_method: ex.options.crease_method,
            ..SubdOptions::default()
        };
        SharpLevel::new(mesh, &opts).map(|sl| NonBoxCreases { sl, mesh })
    }

    /// The sharpness of edge `e` (boundary edges are infinitely sharp).
    pub fn edge(&self, e: usize) -> f32 {
        self.sl.edges[e]
    }

    /// The sharpness of vertex `v`.
    pub fn vertex(&self, v: usize) -> f32 {
        self.sl.vertices[v]
    }

    /// Whether `v` is one of OpenSubdiv's corners (a sharp vertex, three or more sharp edges,
    /// boundary edges included): it stays put.
    pub fn is_corner(&self, v: usize) -> bool {
        matches!(
            self.sl.limit_plan(v as u32, &mut Scratch::default()),
            LimitPlan::Corner
        )
    }

    /// The V-vertex of `v`: OpenSubdiv's vertex plan, `smooth` the non-box V-vertex rule.
    pub fn v_vertex(&self, v: usize, smooth: &Stencil, scratch: &mut Scratch) -> Stencil {
        let mut s = Stencil::new();
        self.sl
            .vertex_plan(v as u32, scratch)
            .emit(v as u32, |t| match t {
                Emit::Smooth(w) => {
                    s.add_scaled(smooth, w);
                }
                Emit::Vertex(x, w) => {
                    s.add(x as usize, w);
                }
            });
        s.merged()
    }

    /// The E-vertex of `e`: OpenSubdiv's edge plan, `smooth` the non-box E-vertex rule.
    pub fn e_vertex(&self, e: usize, smooth: &Stencil, scratch: &mut Scratch) -> Stencil {
        let h = self.mesh.edge_halfedge(e);
        let (a, b) = (self.mesh.he_from(h), self.mesh.he_to(h));
        let mut s = Stencil::new();
        self.sl
            .edge_plan(e as u32, scratch)
            .emit(a, b, |t| match t {
                Emit::Smooth(w) => {
                    s.add_scaled(smooth, w);
                }
                Emit::Vertex(x, w) => {
                    s.add(x as usize, w);
                }
            });
        s.merged()
    }

    /// The weight of the crease rule across edge `e` this step (the edge plan's: 1 while it is
    /// sharp, its sharpness on the step where it decays, 0 when smooth).
    pub fn crease_weight(&self, e: usize, scratch: &mut Scratch) -> f64 {
        let h = self.mesh.edge_halfedge(e);
        let mut crease = 0.0;
        self.sl
            .edge_plan(e as u32, scratch)
            .emit(self.mesh.he_from(h), self.mesh.he_to(h), |t| {
                if let Emit::Vertex(_, w) = t {
                    crease += w;
                }
            });
        crease
    }

    /// The child's sharp features: `vid(v)` is the child V-vertex of `v`, `eid(e)` the child
    /// E-vertex of `e` (Catmull-Clark's child topology).
    pub fn child_extras(&self, vid: impl Fn(u32) -> u32, eid: impl Fn(u32) -> u32) -> Extras {
        let m = self.mesh;
        let mut ex = self.sl.child_extras(
            |h, at_to| {
                let v = if at_to { m.he_to(h) } else { m.he_from(h) };
                ChildEdge::Pair([vid(v), eid(m.he_edge(h))])
            },
            |_, _| {},
        );
        // a partial refinement makes the children of the selected faces only
        const UNSET: u32 = u32::MAX;
        if let crate::mesh::SharpEdges::ByPair(v) = &mut ex.sharp_edges {
            v.retain(|(p, _)| p[0] != UNSET && p[1] != UNSET);
        }
        ex.sharp_vertices = ex
            .sharp_vertices
            .into_iter()
            .map(|(v, s)| (vid(v), s))
            .filter(|p| p.0 != UNSET)
            .collect();
        ex.sharp_vertices.sort_unstable_by_key(|p| p.0);
        let options = m.extras().map(|e| e.options).unwrap_or_default();
        ex.options.crease_method = options.crease_method;
        ex.options.boundary = options.boundary;
        ex
    }
}

/// Whether `v` is a regular vertex: interior of valence 4, or on the boundary with two faces
/// and not a corner, or with one face and a corner (see [`is_corner`]), where ghost FCVs
/// complete the net ([`crate::schemes::nonbox::bezier::corner_fcvs`]).
pub fn is_regular(m: &PolyMesh, v: usize) -> bool {
    // At most five half-edges are counted: O(1) at a vertex of high valence too (this is
    // asked for every corner of every cell around it).
    let n = m.outgoing(v).take(5).count();
    match (m.is_boundary_vertex(v), n) {
        (false, n) => n == 4,
        (true, 1) => is_corner(m, v),
        (true, 2) => !is_tagged(m, v),
        _ => false,
    }
}

/// Whether boundary vertex `v` stays put: a vertex the net's extras tag with a sharpness, or a
/// vertex with one face unless the net interpolates its boundary edge-only (a net cut along
/// its creases, where such a copy may lie on a crease that passes).
pub fn is_corner(m: &PolyMesh, v: usize) -> bool {
    let edge_only = m
        .extras()
        .is_some_and(|e| e.options.boundary() == BoundaryInterpolation::EdgeOnly);
    is_tagged(m, v) || (!edge_only && m.outgoing(v).nth(1).is_none())
}

/// Whether the net's extras tag `v` with a sharpness (the tags are sorted by vertex).
fn is_tagged(m: &PolyMesh, v: usize) -> bool {
    m.extras().is_some_and(|e| {
        e.sharp_vertices
            .binary_search_by_key(&(v as u32), |p| p.0)
            .is_ok_and(|i| e.sharp_vertices[i].1 > 0.0)
    })
}
