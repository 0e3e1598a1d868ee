//! Subdivision schemes, one module per family, each written once as stencils.
//!
//! A scheme that refines whole control nets implements [`Scheme`]: one refinement step returns
//! the child net together with the [`StencilTable`] that computes every child point from the
//! parent points. Applying a scheme to positions, composing several levels, building the local
//! subdivision matrix for analysis or re-applying the step to moved points all reuse that one
//! table, so every rule exists exactly once.

pub mod catmull_clark;
pub mod doo_sabin;
pub mod eg;
pub mod loop_subdivision;

mod common;

pub use catmull_clark::CatmullClark;
pub use doo_sabin::{DooSabin, DooSabinCc};
pub use loop_subdivision::Loop;

use crate::error::Result;
use crate::mesh::PolyMesh;
use crate::stencil::StencilTable;

/// The result of one refinement step.
#[derive(Debug, Clone)]
pub struct Refinement {
    /// The child net, its positions already computed by `stencils`.
    pub mesh: PolyMesh,
    /// Row `i` computes child vertex `i` from the parent's vertices.
    pub stencils: StencilTable,
}

/// A subdivision scheme acting on whole control nets.
pub trait Scheme: Sync {
    /// The scheme's name as used on the command line (`catmull-clark`, `loop`, ...).
    fn name(&self) -> &'static str;

    /// One refinement step of the whole net. Errors name the element the scheme cannot handle
    /// (for example a non-triangle face for Loop).
    fn refine(&self, mesh: &PolyMesh) -> Result<Refinement>;

    /// `levels` refinement steps for output: the refined net only. Schemes with a direct kernel
    /// override it to skip the stencil tables, drop each parent level as soon as its child
    /// exists and keep the peak memory close to the size of the result; the default repeats
    /// [`Scheme::refine`]. `progress(level)` is called after each step.
    fn refine_uniform(
        &self,
        mesh: &PolyMesh,
        levels: usize,
        progress: &mut dyn FnMut(usize),
    ) -> Result<PolyMesh> {
        let mut m: Option<PolyMesh> = None;
        for l in 0..levels {
            m = Some(self.refine(m.as_ref().unwrap_or(mesh))?.mesh);
            progress(l + 1);
        }
        Ok(m.unwrap_or_else(|| mesh.clone()))
    }

    /// Stencils of the limit positions of the net's vertices (row `v` for vertex `v`), where the
    /// scheme has closed-form limit masks.
    fn limit_stencils(&self, mesh: &PolyMesh) -> Result<StencilTable> {
        let _ = mesh;
        Err(crate::error::Error::Unsupported(format!(
            "scheme {} has no limit-position masks",
            self.name()
        )))
    }
}

/// Applies `levels` refinement steps ([`Scheme::refine_uniform`]), calling `progress(level)`
/// after each.
pub fn refine_levels(
    scheme: &dyn Scheme,
    mesh: &PolyMesh,
    levels: usize,
    mut progress: impl FnMut(usize),
) -> Result<PolyMesh> {
    scheme.refine_uniform(mesh, levels, &mut progress)
}

/// The stencil table from the control points of `mesh` to the points of its `levels`-th uniform
/// refinement (each step's table composed with the previous ones), with that refined net.
///
/// This is the precomputed form for animation: the topology stays, the control points move, and
/// [`StencilTable::apply_into`] maps new control positions (or any per-point data) straight to
/// the refined level, in parallel over rows and without allocating. `levels = 0` gives the
/// identity.
///
/// # Errors
/// Whatever [`Scheme::refine`] reports (for example a face the scheme cannot handle).
pub fn level_stencils(
    scheme: &dyn Scheme,
    mesh: &PolyMesh,
    levels: usize,
) -> Result<(PolyMesh, StencilTable)> {
    let mut fine: Option<PolyMesh> = None;
    let mut table: Option<StencilTable> = None;
    for _ in 0..levels {
        let r = scheme.refine(fine.as_ref().unwrap_or(mesh))?;
        table = Some(match table {
            None => r.stencils,
            Some(t) => r.stencils.compose(&t),
        });
        fine = Some(r.mesh);
    }
    Ok(match (fine, table) {
        (Some(m), Some(t)) => (m, t),
        _ => (mesh.clone(), StencilTable::identity(mesh.num_vertices())),
    })
}

/// Builds the child mesh from topology and stencils: positions are the stencils applied to the
/// parent positions.
pub(crate) fn finish_refinement(
    parent: &PolyMesh,
    stencils: StencilTable,
    face_start: Vec<u32>,
    corners: Vec<u32>,
) -> Result<Refinement> {
    let positions = stencils.apply(parent.positions());
    let mesh = PolyMesh::from_refinement(positions, face_start, corners)?;
    Ok(Refinement { mesh, stencils })
}

/// What `fairsub schemes` tells about a scheme.
#[derive(Debug, Clone, serde::Serialize)]
pub struct SchemeInfo {
    /// Command-line name.
    pub name: &'static str,
    /// Family and paper.
    pub family: &'static str,
    /// Input nets it accepts.
    pub input: &'static str,
    /// Patches it outputs (degree and layout), if it has exact patch output.
    pub patches: &'static str,
    /// Smoothness claimed by its paper (or the classical result).
    pub smoothness: &'static str,
    /// Valences / element sizes with rules.
    pub valences: &'static str,
    /// Whether refinement (`--levels`) is available.
    pub refine: bool,
    /// Whether exact patch output (`--rings`) is available.
    pub rings: bool,
    /// Implementation status.
    pub status: &'static str,
}

/// Every scheme fairsub knows, implemented or planned, with its properties.
pub fn catalog() -> Vec<SchemeInfo> {
    vec![
        SchemeInfo {
            name: "catmull-clark",
            family: "classic primal quad scheme [CC78]",
            input: "any polygon mesh (one step makes it all quads); boundaries with edge-only interpolation",
            patches: "bi-3 on regular quads; rings of 3n bi-3 patches per extraordinary vertex; Hermite-Coons fill",
            smoothness: "C^2 on regular parts, C^1 at extraordinary vertices",
            valences: "all",
            refine: true,
            rings: true,
            status: "available",
        },
        SchemeInfo {
            name: "doo-sabin",
            family: "classic dual quad scheme [DS78], weights of the Doo-Sabin paper",
            input: "any polygon mesh; boundaries: Chaikin points on boundary edges (fairsub's rules)",
            patches: "bi-2 per regular vertex (Chaikin boundaries via doubled boundary layer); rings of 3n bi-2 patches per n-gon (from level 2 for an n-valent vertex); centroid fill",
            smoothness: "C^1 (bi-2 on regular parts)",
            valences: "all facet sizes",
            refine: true,
            rings: true,
            status: "available",
        },
        SchemeInfo {
            name: "doo-sabin-cc",
            family: "DS^CC: face-corner point = mean of vertex, face centroid and the two edge midpoints",
            input: "any polygon mesh; boundaries as doo-sabin",
            patches: "as doo-sabin: bi-2 per regular vertex; rings of 3n bi-2 patches per n-gon; centroid fill",
            smoothness: "C^1",
            valences: "all facet sizes",
            refine: true,
            rings: true,
            status: "available",
        },
        SchemeInfo {
            name: "loop",
            family: "classic triangle scheme [Loo87], Loop's original beta",
            input: "triangle meshes; boundaries as OpenSubdiv (corners stay put)",
            patches: "quartic box-spline triangles (as degenerate bi-4 patches), regular boundary triangles included; rings of 3n triangles per extraordinary vertex; Hermite fill",
            smoothness: "C^2 on regular parts, C^1 at extraordinary vertices",
            valences: "all",
            refine: true,
            rings: true,
            status: "available",
        },
        SchemeInfo {
            name: "eg",
            family: "Evolving Guide subdivision [Karciauskas-Peters]: bi-4 rings joining bi-3 surroundings C^2",
            input: "Catmull-Clark nets (quads; one local Catmull-Clark step where extraordinary vertices touch or n-gons occur)",
            patches: "bi-3 on regular quads; K rings of 3n bi-4 patches per extraordinary vertex; bi-4 fill C^1 to the last ring",
            smoothness: "C^2 rings and joins, C^1 at the extraordinary point; mu/lambda^2 = 1.00015 (n=3), 1.00016 (n=5)",
            valences: "3, 5 published (4 = bi-4 refinement); 6..10 lost in the text: Catmull-Clark fallback or error",
            refine: false,
            rings: true,
            status: "available (patches; valences 3 and 5)",
        },
    ]
}

/// The refinement scheme of a command-line name; the error lists the available names.
pub fn by_name(name: &str) -> Result<Box<dyn Scheme>> {
    match name {
        "catmull-clark" | "cc" => Ok(Box::new(CatmullClark)),
        "doo-sabin" | "ds" => Ok(Box::new(DooSabin)),
        "doo-sabin-cc" | "ds-cc" => Ok(Box::new(DooSabinCc)),
        "loop" => Ok(Box::new(Loop)),
        _ => {
            let names: Vec<&str> = catalog()
                .iter()
                .filter(|s| s.refine)
                .map(|s| s.name)
                .collect();
            Err(crate::error::Error::InvalidArgument(format!(
                "unknown scheme '{name}' (available for refinement: {})",
                names.join(", ")
            )))
        }
    }
}
