//! STEP output of `fairsub subdivide`: the CAD faces of a complex ([`crate::surface::cad`]),
//! their topology and the file, with a report of what was written.

use crate::error::{Error, Result};
use crate::surface::PatchComplex;
use crate::surface::cad::{self, FaceMode, brep};
use std::path::Path;

/// The distance accuracy a STEP file states: ten times the welding tolerance (`1e-9` of the
/// model's size), and never below `1e-7` (OpenCASCADE's and most kernels' confusion
/// tolerance, in the file's millimetres).
pub fn step_tolerance(weld: f64) -> f64 {
    (10.0 * weld).max(1e-7)
}

/// Writes `complex` as a STEP file with faces `mode`.
pub fn write_step(complex: &PatchComplex, mode: FaceMode, path: &Path) -> Result<()> {
    let mut faces = cad::faces(complex, mode)?;
    let weld = crate::surface::adjacency::default_tolerance(complex);
    let topo = brep::build(&mut faces.surfaces, weld);
    if topo.nonmanifold > 0 {
        return Err(Error::InvalidArgument(format!(
            "{}: {} face sides meet more than one other side (a non-manifold surface); STEP \
             output needs a manifold net",
            path.display(),
            topo.nonmanifold
        )));
    }
    crate::io::write_step(path, &faces.surfaces, &topo, step_tolerance(weld))?;
    let open = topo.closed.iter().filter(|c| !**c).count();
    let shell = match (topo.shells(), open) {
        (1, 0) => "a closed solid".to_string(),
        (n, 0) => format!("{n} closed solids"),
        (1, 1) => format!("an open shell with {} boundary edges", topo.free_edges),
        (n, k) => format!("{n} shells ({k} open, {} boundary edges)", topo.free_edges),
    };
    eprintln!(
        "STEP: {} faces ({:?}), {} edges, {} vertices: {shell}{}",
        faces.len(),
        mode,
        topo.edges.len(),
        topo.vertices.len(),
        if topo.misoriented > 0 {
            format!("; {} edges with inconsistent orientation", topo.misoriented)
        } else {
            String::new()
        }
    );
    if faces.unmerged > 0 {
        eprintln!(
            "note: {} input faces are not merged into one B-spline (their patches are faces \
             of their own): their patches are triangles, do not tile the face, or a tensor \
             grid across the face would cost more than twice their control points (deep \
             semi-sharp crease refinement)",
            faces.unmerged
        );
    }
    if faces.c0_faces > 0 {
        eprintln!(
            "note: {} merged faces keep every knot at multiplicity p (C^0): the continuity \
             measured across their knot lines did not reproduce their patches to rounding",
            faces.c0_faces
        );
    }
    Ok(())
}
