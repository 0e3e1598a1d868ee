//! One whole-net step of a dual scheme on a net with sharp features (`--levels`): the step of
//! [`crate::schemes::doo_sabin::surface::step`] with every face selected, laid out like the
//! plain step of [`crate::schemes::doo_sabin`].
//!
//! # Layout
//!
//! Child points: `h` for the corner of half-edge `h`; then two per sharp edge (boundary edges
//! and creases, in edge order: near the start of its edge half-edge, near its end); then the
//! kept points in vertex order. Child faces: the F-face of parent face `f` (index `f`), the
//! E-faces in edge order (one half per side of a crease), the V-faces (one per sector between
//! sharp edges). The child's extras carry the sharpness of its crease edges and kept points
//! (and its boundary edges, infinitely sharp), already sharpened, and the parent's boundary
//! mode and crease method.

use super::step::Creases;
use crate::error::Result;
use crate::host::adaptive::Info;
use crate::mesh::{PolyMesh, SharpEdges};
use crate::schemes::Refinement;
use crate::schemes::doo_sabin::surface::step::{StepIn, UNSET, dual_step};
use crate::stencil::{Stencil, StencilTable};

/// One step of `mesh` with its creases `creases` and the corner rule `corner` (see the
/// [module](self) documentation).
///
/// # Errors
/// Those of building the child net.
pub(crate) fn refine_creased(
    mesh: &PolyMesh,
    creases: &Creases<'_>,
    corner: &mut dyn FnMut(&PolyMesh, u32) -> Stencil,
) -> Result<Refinement> {
    let info = vec![
        Info {
            pos_ok: true,
            fan_ok: true,
            origin: None,
        };
        mesh.num_vertices()
    ];
    let face_origin = vec![None; mesh.num_faces()];
    let inp = StepIn {
        mesh,
        info: &info,
        rule_free: None,
        face_origin: &face_origin,
        face_corners: None,
    };
    let all: Vec<u32> = (0..mesh.num_faces() as u32).collect();
    let out = dual_step(&inp, all, corner, Some(creases))?;
    // the layout: corners by half-edge, Chaikin points by edge, kept points by vertex
    let mut new = vec![UNSET; out.stencils.len()];
    let mut next = 0u32;
    let mut place = |old: u32| {
        if old != UNSET && new[old as usize] == UNSET {
            new[old as usize] = next;
            next += 1;
        }
    };
    out.corner_pt.iter().for_each(|&p| place(p));
    out.edge_pt.iter().flatten().for_each(|&p| place(p));
    out.kept.iter().for_each(|&p| place(p));
    debug_assert!(!new.contains(&UNSET));
    let mut rows = vec![Stencil::new(); out.stencils.len()];
    for (old, s) in out.composed_stencils().into_iter().enumerate() {
        rows[new[old] as usize] = s;
    }
    let table = StencilTable::from_rows(mesh.num_vertices(), rows, 6);
    let corners: Vec<u32> = out.corners.iter().map(|&p| new[p as usize]).collect();
    let positions = table.apply(mesh.positions());
    let child = PolyMesh::from_refinement(positions, out.face_start.clone(), corners)?;
    let extras = out.extras.map(|mut ex| {
        if let SharpEdges::ByPair(v) = &mut ex.sharp_edges {
            for (p, _) in v.iter_mut() {
                *p = [new[p[0] as usize], new[p[1] as usize]];
            }
        }
        for (v, _) in ex.sharp_vertices.iter_mut() {
            *v = new[*v as usize];
        }
        ex.sharp_vertices.sort_unstable_by_key(|p| p.0);
        ex
    });
    Ok(Refinement {
        mesh: child.with_extras(extras),
        stencils: table,
    })
}
