//! Mixed bi-2 meshes (Section 5 and Fig. 15 of the bi-2 paper): regular bi-2 regions, PGS at
//! extraordinary facets, TPS at extraordinary vertices and PolBS at poles, in one surface.
//!
//! # How binary and ternary rings meet
//!
//! They never have to. Every vertex of a quad net with four quads carries one exact bi-2 patch
//! of the *input* net, and these regular patches leave one hole per extraordinary element: the
//! patches of a facet's corners (PGS), the patch of an extraordinary vertex (TPS), the cap
//! inside the ring next to a pole (PolBS). Each hole is filled by its own scheme's nested rings,
//! computed from the element's local net alone: ring 1 joins the regular patches around the
//! hole exactly as a uniformly refined bi-2 net would (its outer points are bi-2 refinement of
//! the input), and ring `l + 1` joins ring `l` by the scheme's construction. So a binary ring
//! sequence (PGS, contraction `lambda_sub`; PolBS, radial 1/2) and a ternary one (TPS, 1/3 and
//! faster) sit side by side inside the same C^1 bi-2 surface, each joined C^1 to the shared
//! regular patches; no net is refined globally. The elements must be separated: the vertices
//! around each hole must be regular (see [`classify`]); otherwise the error names the vertex.
//!
//! Whole-net refinement of a mixed net is not possible (the paper: "it is difficult to imagine
//! how pure mesh refinement would cope"): [`Bi2Mixed::refine`] refines a net whose elements
//! are all of one kind with that kind's scheme, and refuses a net that mixes kinds.

use super::{Pgs, PolarBi2, Tps};
use crate::error::{Error, Result};
use crate::mesh::PolyMesh;
use crate::schemes::{Refinement, Scheme};
use crate::stencil::StencilTable;

/// An extraordinary element of a bi-2 net and the scheme that fills its hole.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Bi2Element {
    /// A facet that is not a quad (PGS).
    Facet(u32),
    /// An interior vertex of valence `!= 4` surrounded by quads (TPS).
    Vertex(u32),
    /// A pole: an interior vertex surrounded by triangles (PolBS).
    Pole(u32),
}

/// The extraordinary elements of `mesh`: poles ([`super::polar::find_poles`]), facets that are
/// not quads and not in a pole's fan, and interior vertices of valence `!= 4` whose faces are
/// all quads.
pub fn elements(mesh: &PolyMesh) -> Vec<Bi2Element> {
    let poles = super::polar::find_poles(mesh);
    let mut in_fan = vec![false; mesh.num_faces()];
    let mut out = Vec::new();
    for &p in &poles {
        for f in mesh.vertex_faces(p as usize) {
            in_fan[f as usize] = true;
        }
        out.push(Bi2Element::Pole(p));
    }
    for (f, &fan) in in_fan.iter().enumerate() {
        if !fan && mesh.face_size(f) != 4 {
            out.push(Bi2Element::Facet(f as u32));
        }
    }
    for v in 0..mesh.num_vertices() {
        if mesh.is_boundary_vertex(v) || mesh.valence(v) == 4 {
            continue;
        }
        if mesh
            .vertex_faces(v)
            .iter()
            .all(|&f| mesh.face_size(f as usize) == 4)
        {
            out.push(Bi2Element::Vertex(v as u32));
        }
    }
    out
}

/// The kinds of elements present: (facets, vertices, poles).
pub fn classify(mesh: &PolyMesh) -> (bool, bool, bool) {
    let el = elements(mesh);
    (
        el.iter().any(|e| matches!(e, Bi2Element::Facet(_))),
        el.iter().any(|e| matches!(e, Bi2Element::Vertex(_))),
        el.iter().any(|e| matches!(e, Bi2Element::Pole(_))),
    )
}

/// The mixed bi-2 scheme (name `bi2-mixed`). Its exact surface (`--rings K`) takes any mix of
/// elements ([`crate::surface::bi2::mixed_complex`]); its net refinement only a net with one
/// kind of element (see the [module](self) documentation).
#[derive(Debug, Clone, Copy, Default)]
pub struct Bi2Mixed;

/// Which single scheme refines a net under `bi2-mixed`.
fn chosen(mesh: &PolyMesh) -> Result<Box<dyn Scheme>> {
    match classify(mesh) {
        (_, false, false) => Ok(Box::new(Pgs)),
        (false, true, false) => Ok(Box::new(Tps)),
        (false, false, true) => Ok(Box::new(PolarBi2::default())),
        (f, v, p) => {
            let mut kinds = Vec::new();
            if f {
                kinds.push("facets that are not quads (PGS, binary)");
            }
            if v {
                kinds.push("extraordinary vertices (TPS, ternary)");
            }
            if p {
                kinds.push("poles (PolBS, radial only)");
            }
            Err(Error::Unsupported(format!(
                "bi2-mixed: this net has {}; no single net refinement holds binary, ternary and \
                 radial rules at once (the bi-2 paper, Section 5), so there is no refined net: \
                 write the exact surface with --rings K, or refine with pgs, tps or polar-bi2 \
                 alone",
                kinds.join(" and ")
            )))
        }
    }
}

impl Scheme for Bi2Mixed {
    fn name(&self) -> &'static str {
        "bi2-mixed"
    }

    /// One step of the net's single kind of scheme (PGS when there is no element); an error
    /// for a net that mixes kinds.
    fn refine(&self, mesh: &PolyMesh) -> Result<Refinement> {
        chosen(mesh)?.refine(mesh)
    }

    /// `levels` steps of the scheme chosen for the input net.
    fn refine_many(
        &self,
        mesh: &PolyMesh,
        levels: usize,
        progress: &mut dyn FnMut(usize),
    ) -> Result<PolyMesh> {
        chosen(mesh)?.refine_many(mesh, levels, progress)
    }

    /// The limit stencils of the chosen scheme.
    fn limit_stencils(&self, mesh: &PolyMesh) -> Result<StencilTable> {
        chosen(mesh)?.limit_stencils(mesh)
    }
}
