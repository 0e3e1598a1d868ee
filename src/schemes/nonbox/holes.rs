//! OpenSubdiv's hole faces under non-box, read as OpenSubdiv reads them for Catmull-Clark
//! (fairsub's construction; the paper has no holes): a hole face is refined like any other
//! face, its points support the surface around it and the rules never read the tag, and it
//! gets no patches. So the patches over the other faces are exactly those of the net without
//! the tags, and refinement carries the tags to the children of hole faces (the output then
//! leaves those faces out, as for every other scheme).

use crate::bezier::complex::PatchComplex;
use crate::bezier::domain::FanTriangle;
use crate::error::{Error, Result};
use crate::mesh::{Extras, PolyMesh};

/// The hole faces `mesh` tags (increasing; empty for none).
fn hole_faces(mesh: &PolyMesh) -> &[u32] {
    mesh.extras().map_or(&[], |e| e.holes.as_slice())
}

/// `mesh` without its hole tags (every other tag kept), or `None` when it tags no hole.
pub(super) fn without_hole_tags(mesh: &PolyMesh) -> Option<PolyMesh> {
    if hole_faces(mesh).is_empty() {
        return None;
    }
    let mut ex = mesh.extras().cloned().unwrap_or_default();
    ex.holes.clear();
    Some(mesh.clone().with_extras((!ex.is_empty()).then_some(ex)))
}

/// The half-edges of the hole faces of `mesh`, increasing: the hole faces of a net with one
/// face per half-edge, the children of a non-box step (Catmull-Clark's child topology: child
/// face `h` is the quad at half-edge `h`) or the triangles around the FCVs
/// ([`super::fourdir::triangulate`]).
pub(super) fn halfedge_holes(mesh: &PolyMesh) -> Vec<u32> {
    let mut out: Vec<u32> = hole_faces(mesh)
        .iter()
        .flat_map(|&f| {
            let h0 = mesh.face_halfedge(f as usize);
            h0..h0 + mesh.face_size(f as usize) as u32
        })
        .collect();
    out.sort_unstable();
    out
}

/// The child extras of one non-box step of `mesh`, given those of its sharp features
/// (`sharp`): the hole tags move to the children of the hole faces ([`halfedge_holes`]).
pub(super) fn with_child_holes(mesh: &PolyMesh, sharp: Option<Extras>) -> Option<Extras> {
    if hole_faces(mesh).is_empty() {
        return sharp;
    }
    let mut ex = sharp.unwrap_or_else(|| Extras {
        options: mesh.extras().map(|e| e.options).unwrap_or_default(),
        sharpened: true,
        ..Extras::default()
    });
    ex.holes = halfedge_holes(mesh);
    Some(ex)
}

/// A mesh of one triangle per half-edge of `polygons` ([`super::fourdir::triangulate`]'s,
/// such as the limit mesh) without the triangles of its hole faces (vertices kept).
pub(super) fn without_hole_triangles(mesh: PolyMesh, polygons: &PolyMesh) -> PolyMesh {
    let holes = halfedge_holes(polygons);
    if holes.is_empty() {
        return mesh;
    }
    let mut ex = mesh.extras().cloned().unwrap_or_default();
    ex.holes = holes;
    mesh.with_extras(Some(ex)).without_holes()
}

/// A refined net without its hole faces, for output (as [`PolyMesh::without_holes`]): a
/// [layout mesh](super::FcvNet::to_layout_mesh) loses the hole faces' FCVs with them (its
/// vertices are kept, those of hole faces only then in no face).
pub(crate) fn without_hole_faces(m: PolyMesh) -> PolyMesh {
    if hole_faces(&m).is_empty() {
        return m;
    }
    let Some(net) = super::FcvNet::from_layout_mesh(&m) else {
        return m.without_holes();
    };
    let fcv = (0..m.num_faces())
        .filter(|&f| !m.is_hole(f))
        .map(|f| net.fcv[f])
        .collect();
    match super::FcvNet::new(net.mesh.without_holes(), fcv) {
        Ok(net) => net.to_layout_mesh(),
        // (one FCV per kept face: cannot happen)
        Err(_) => m.without_holes(),
    }
}

/// The surface of `mesh` with OpenSubdiv's hole faces: `build` makes the complex of the net
/// without the hole tags (its patches' domains number the faces the complex is built on:
/// the input faces, or the host polygons of `fan`, one per input triangle); the patches over
/// hole faces are left out and a note says so. `None` when the net tags no hole.
///
/// # Errors
/// Those of `build`; [`Error::Unsupported`] when the hole tags cover part of a host polygon
/// only (its patches span all of its triangles).
pub(super) fn leave_out_holes(
    mesh: &PolyMesh,
    fan: Option<&[FanTriangle]>,
    build: &mut dyn FnMut(&PolyMesh) -> Result<PatchComplex>,
) -> Result<Option<(PatchComplex, String)>> {
    let Some(bare) = without_hole_tags(mesh) else {
        return Ok(None);
    };
    let holes = hole_faces(mesh);
    // per face of the complex's net: whether it is a hole
    let hole: Vec<bool> = match fan {
        None => {
            let mut hole = vec![false; mesh.num_faces()];
            for &f in holes {
                hole[f as usize] = true;
            }
            hole
        }
        Some(fan) => {
            let hosts = fan.iter().map(|t| t.host as usize + 1).max().unwrap_or(0);
            let (mut tagged, mut all) = (vec![0usize; hosts], vec![0usize; hosts]);
            for (f, t) in fan.iter().enumerate() {
                all[t.host as usize] += 1;
                tagged[t.host as usize] += usize::from(mesh.is_hole(f));
            }
            if let Some(p) = (0..hosts).find(|&p| tagged[p] != 0 && tagged[p] != all[p]) {
                return Err(Error::Unsupported(format!(
                    "{}: {} of the {} triangles of polygon {p} (around its FCV) are hole faces; \
                     its patches span all of them: tag all or none",
                    crate::schemes::options::ids::NONBOX_4DIR,
                    tagged[p],
                    all[p]
                )));
            }
            tagged.iter().map(|&n| n > 0).collect()
        }
    };
    let complex = build(&bare)?;
    let kept = complex.retain(|i| {
        complex.domain(i).is_none_or(|d| {
            !(d.is_tracked() && hole.get(d.face as usize).copied().unwrap_or(false))
        })
    });
    let note = format!(
        "{} hole faces: refined as any other face (their points support the surface around \
         them, as OpenSubdiv's holes do), their {} patches left out",
        holes.len(),
        complex.len() - kept.len()
    );
    Ok(Some((kept, note)))
}
