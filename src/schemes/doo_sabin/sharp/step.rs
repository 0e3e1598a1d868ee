//! The crease rules of one dual step (fairsub's construction, documented in the parent module
//! and in `docs/guide/src/creases.md`): which child points a level's sharp
//! features add, how those points blend while a semi-sharp feature decays, how a vertex's
//! V-face splits into the sectors between its sharp edges, and the sharpness of the child's
//! edges and vertices.
//!
//! The sharpness values, their decay (uniform or Chaikin) and the blend weights are
//! OpenSubdiv's, read through the shared machinery of [`crate::schemes::sdc::crease`]
//! ([`SharpLevel`]): a dual step only maps them onto its own child points. A level's boundary
//! edges are infinitely sharp there (OpenSubdiv's sharpening), so the boundary rules of
//! [`crate::schemes::doo_sabin`] are the special case of a sharp edge with one side.

use crate::error::{Error, Result};
use crate::mesh::PolyMesh;
use crate::mesh::dual_split::Sector;
use crate::mesh::tags::BoundaryInterpolation;
use crate::schemes::sdc::crease::{
    INFINITE, Scratch, SharpLevel, VertexMask, VertexPlan, decrement,
};

/// The sharp features of one level of a dual scheme, when the level has one the plain boundary
/// rules do not cover: an edge inside the surface with positive sharpness, or a vertex whose
/// sharpness is finite.
pub(crate) struct Creases<'a> {
    sl: SharpLevel<'a>,
    mesh: &'a PolyMesh,
    /// Per vertex: an edge inside the surface at it is sharp.
    on_crease: Vec<bool>,
}

impl<'a> Creases<'a> {
    /// The crease data of `mesh` (its extras and options), or `None` when the plain rules of
    /// [`crate::schemes::doo_sabin`] give the same step (no sharp edge inside the surface, no
    /// finite vertex sharpness). `name` is the scheme's name for messages.
    ///
    /// # Errors
    /// [`Error::Unsupported`] for what the construction has no rule for, naming the element:
    /// a vertex tag inside the surface (a bi-2 surface cannot keep an interior point), the
    /// boundary mode `none` together with creases.
    pub fn of(mesh: &'a PolyMesh, name: &str) -> Result<Option<Creases<'a>>> {
        let Some(ex) = mesh.extras() else {
            return Ok(None);
        };
        let finite_vertex = ex.sharp_vertices.iter().any(|&(_, s)| s < INFINITE);
        if ex.sharp_edges.is_empty() && !finite_vertex {
            return Ok(None);
        }
        let opts = ex.options;
        let Some(sl) = SharpLevel::new(mesh, &opts) else {
            return Ok(None);
        };
        let mut on_crease = vec![false; mesh.num_vertices()];
        let mut any = false;
        for (e, &s) in sl.edges.iter().enumerate() {
            let h = mesh.edge_halfedge(e);
            if s > 0.0 && mesh.he_twin(h).is_some() {
                on_crease[mesh.he_from(h) as usize] = true;
                on_crease[mesh.he_to(h) as usize] = true;
                any = true;
            }
        }
        let finite = sl.vertices.iter().any(|&s| s > 0.0 && s < INFINITE);
        if !any && !finite {
            return Ok(None);
        }
        if opts.boundary() == BoundaryInterpolation::None {
            return Err(Error::Unsupported(format!(
                "the net tags sharp features and asks for the boundary mode none; {name}'s \
                 creases use the boundary rules on their sides, which none leaves out (not \
                 built: choose --boundary edge-only or edge-and-corner, or remove the tags)"
            )));
        }
        if let Some(v) =
            (0..mesh.num_vertices()).find(|&v| sl.vertices[v] > 0.0 && !mesh.is_boundary_vertex(v))
        {
            return Err(Error::Unsupported(format!(
                "vertex {v} is tagged as a corner (sharpness {}) inside the surface; a {name} \
                 surface cannot keep an interior point, the dual schemes keep corners on the \
                 boundary and on infinitely sharp creases only (remove the tag, tag an \
                 infinitely sharp crease through it, or refine with Catmull-Clark or Loop)",
                sl.vertices[v]
            )));
        }
        Ok(Some(Creases {
            sl,
            mesh,
            on_crease,
        }))
    }

    /// Whether edge `e` is sharp at this level: it gets the Chaikin points of its sides.
    pub fn is_sharp(&self, e: usize) -> bool {
        self.sl.edges[e] > 0.0
    }

    /// Whether edge `e` is a sharp edge inside the surface.
    pub fn is_crease(&self, e: usize) -> bool {
        self.is_sharp(e) && self.mesh.he_twin(self.mesh.edge_halfedge(e)).is_some()
    }

    /// The weight of the sharp rule in the Chaikin points of edge `e`: 1 for sharpness 1 and
    /// more, the sharpness itself below (OpenSubdiv's fractional edge weight; Chaikin decay
    /// never extrapolates here).
    pub fn weight(&self, e: usize) -> f64 {
        f64::from(self.sl.edges[e].min(1.0))
    }

    /// Whether face `f` has a corner on a crease: its corner points are then computed on the
    /// face alone (the net cut along the crease, where those corners are on the boundary).
    pub fn touches(&self, f: usize) -> bool {
        self.mesh
            .face(f)
            .iter()
            .any(|&v| self.on_crease[v as usize])
    }

    /// The plan of the point vertex `v` keeps this step, when its rule is OpenSubdiv's corner
    /// rule (a sharp vertex, three or more sharp edges, boundary edges included):
    /// `VertexPlan::Single(Corner)` (the vertex stays) or a blend from the corner toward the
    /// child's rule. `None` for any other vertex (no kept point).
    pub fn kept(&self, v: usize, scratch: &mut Scratch) -> Option<VertexPlan> {
        match self.sl.vertex_plan(v as u32, scratch) {
            p @ VertexPlan::Single(VertexMask::Corner) => Some(p),
            p @ VertexPlan::Blend {
                parent: VertexMask::Corner,
                ..
            } => Some(p),
            _ => None,
        }
    }

    /// The sectors of vertex `v` between its sharp edges (see [`Sector`]); `hs` are its
    /// outgoing half-edges ([`PolyMesh::outgoing_halfedges`]).
    pub fn sectors(&self, v: usize, hs: &[u32]) -> Vec<Sector> {
        let m = self.mesh;
        let n = hs.len();
        if m.is_boundary_vertex(v) {
            // sharp edges at 0 (the outgoing boundary edge) and at the inner sharp spokes;
            // the last sector ends at the incoming boundary edge
            let last = hs.last().copied().expect("a vertex has a face");
            let incoming = m.he_edge(m.he_prev(last));
            let cuts: Vec<usize> = (0..n)
                .filter(|&i| i == 0 || self.is_sharp(m.he_edge(hs[i]) as usize))
                .collect();
            return cuts
                .iter()
                .enumerate()
                .map(|(k, &i)| {
                    let j = cuts.get(k + 1).copied().unwrap_or(n);
                    let close = if j < n { m.he_edge(hs[j]) } else { incoming };
                    Sector {
                        faces: (i..j).collect(),
                        open: Some(m.he_edge(hs[i])),
                        close: Some(close),
                    }
                })
                .collect();
        }
        let cuts: Vec<usize> = (0..n)
            .filter(|&i| self.is_sharp(m.he_edge(hs[i]) as usize))
            .collect();
        if cuts.is_empty() {
            return vec![Sector {
                faces: (0..n).collect(),
                open: None,
                close: None,
            }];
        }
        cuts.iter()
            .enumerate()
            .map(|(k, &i)| {
                let j = cuts[(k + 1) % cuts.len()];
                let len = (j + n - i - 1) % n + 1;
                Sector {
                    faces: (0..len).map(|d| (i + d) % n).collect(),
                    open: Some(m.he_edge(hs[i])),
                    close: Some(m.he_edge(hs[j])),
                }
            })
            .collect()
    }

    /// The sharpness of the child edge joining the two Chaikin points of sharp edge `e`: the
    /// mean of OpenSubdiv's child sharpness of its two halves (equal under uniform decay).
    pub fn middle(&self, e: usize, scratch: &mut Scratch) -> f32 {
        let h = self.mesh.edge_halfedge(e);
        let (a, b) = (self.mesh.he_from(h), self.mesh.he_to(h));
        let ca = self.sl.child_half(e as u32, a, scratch);
        let cb = self.sl.child_half(e as u32, b, scratch);
        if ca >= INFINITE && cb >= INFINITE {
            INFINITE
        } else {
            0.5 * (ca + cb)
        }
    }

    /// The sharpness of the child edge from the Chaikin point of sharp edge `e` near `v` to
    /// `v`'s kept point: OpenSubdiv's child sharpness of `e`'s half at `v`.
    pub fn half(&self, e: usize, v: usize, scratch: &mut Scratch) -> f32 {
        self.sl.child_half(e as u32, v as u32, scratch)
    }

    /// The sharpness of the chord of a sector without kept point at `v`, from the Chaikin
    /// point of `close` to that of `open` near `v`: the smaller child sharpness of the two
    /// halves at `v` under uniform decay, their mean under Chaikin's (which averages
    /// sharpness along a crease as its points are averaged).
    pub fn chord(&self, open: usize, close: usize, v: usize, scratch: &mut Scratch) -> f32 {
        let a = self.half(open, v, scratch);
        let b = self.half(close, v, scratch);
        if a >= INFINITE && b >= INFINITE {
            INFINITE
        } else if self.sl.chaikin() {
            0.5 * (a + b)
        } else {
            a.min(b)
        }
    }

    /// The sharpness of the kept point of `v` in the child (OpenSubdiv's vertex decay).
    pub fn child_vertex(&self, v: usize) -> f32 {
        decrement(self.sl.vertices[v])
    }

    /// The edge from `v` to its neighbour `to`, for the crease neighbours of a vertex plan.
    pub fn spoke_to(
        &self,
        v: usize,
        to: u32,
        scratch: &mut Vec<crate::schemes::sdc::crease::Spoke>,
    ) -> Option<u32> {
        self.sl.spokes(v as u32, scratch);
        scratch.iter().find(|s| s.other == to).map(|s| s.edge)
    }
}
