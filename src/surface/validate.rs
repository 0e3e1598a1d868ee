//! Outputs are valid or not written: the checks that stand between a computed surface and a
//! file.
//!
//! A patch complex is written only when every coefficient is finite ([`check_finite`]); a
//! tessellation only when it is a mesh that fairsub's own readers accept
//! ([`Tessellation::to_mesh`]: non-empty, finite, manifold, consistently oriented, exactly the
//! validation of [`PolyMesh::from_flat`] that every mesh reader ends with). Geometry that breaks
//! this (coordinates overflowing to infinity, patches so small against the extent of the
//! complex that they weld to points, coincident patches) gets an [`Error::InvalidOutput`] that
//! names the patch by its provenance ([`describe_patch`]) and the way out.

use super::PatchComplex;
use super::tessellate::Tessellation;
use crate::bezier::complex::Provenance;
use crate::error::{Error, MeshError, Result};
use crate::mesh::PolyMesh;

/// How messages name patch `k` of `c`: `patch 12 (ring 2 around vertex 5, sector 1)`.
pub fn describe_patch(c: &PatchComplex, k: usize) -> String {
    let what = match c.provenance.get(k) {
        Some(Provenance::Regular { face }) => format!("regular, in face {face}"),
        Some(Provenance::Ring {
            element,
            ring,
            sector,
        }) => format!("ring {ring} around {}, sector {sector}", element.describe()),
        Some(Provenance::Cap { element, sector }) => {
            format!("cap of {}, sector {sector}", element.describe())
        }
        Some(Provenance::Unknown) | None => return format!("patch {k}"),
    };
    format!("patch {k} ({what})")
}

/// Fails when a coefficient of the complex is not finite, naming the first such patch.
pub fn check_finite(c: &PatchComplex) -> Result<()> {
    use rayon::prelude::*;
    let bad = c
        .patches
        .par_iter()
        .position_first(|p| p.cps.iter().any(|q| !q.iter().all(|x| x.is_finite())));
    match bad {
        None => Ok(()),
        Some(k) => {
            let p = &c.patches[k];
            let i = p
                .cps
                .iter()
                .position(|q| !q.iter().all(|x| x.is_finite()))
                .unwrap_or(0);
            Err(Error::InvalidOutput(format!(
                "{} has the coefficient b[{}][{}] = {:?}, which is not finite: the computation \
                 overflowed (the net's coordinates or face control vertices are too large; \
                 scale the input down)",
                describe_patch(c, k),
                i / (p.deg_v + 1),
                i % (p.deg_v + 1),
                p.cps[i]
            )))
        }
    }
}

impl Tessellation {
    /// The tessellation of `c` (which it was made from) as a validated [`PolyMesh`], the mesh
    /// that fairsub's mesh readers would read back from any file written from it (vertices no
    /// triangle uses are dropped, as the readers drop them). Errors name the patch.
    pub fn to_mesh(&self, c: &PatchComplex) -> Result<PolyMesh> {
        if self.triangles.is_empty() {
            return Err(self.empty_error(c));
        }
        if let Some(v) = self
            .positions
            .iter()
            .position(|p| !p.iter().all(|x| x.is_finite()))
        {
            return Err(Error::InvalidOutput(format!(
                "the tessellation of {} has the point {:?}, which is not finite: the \
                 computation overflowed (scale the input down)",
                describe_patch(c, self.patch_of_vertex[v] as usize),
                self.positions[v]
            )));
        }
        let (pos, fs, corners) = self.to_polygons();
        PolyMesh::from_flat(pos, fs, corners).map_err(|e| self.mesh_error(c, e))
    }

    /// The error of an empty tessellation: every patch degenerate at the welding tolerance.
    fn empty_error(&self, c: &PatchComplex) -> Error {
        if c.is_empty() {
            return Error::InvalidOutput("the patch complex has no patches to tessellate".into());
        }
        let tol = super::adjacency::default_tolerance(c);
        Error::InvalidOutput(format!(
            "the tessellation is empty: all {} patches, e.g. {}, are degenerate (within {tol:.3e} \
             of a line, the tolerance of the complex's extent): the coordinates differ too much \
             in scale for double precision; scale the far-out control points (or FCVs) in",
            c.len(),
            describe_patch(c, 0)
        ))
    }

    /// A validation error of the triangle mesh, told in patches.
    fn mesh_error(&self, c: &PatchComplex, e: Error) -> Error {
        let Error::Mesh(me) = e else { return e };
        let of_tri = |t: usize| describe_patch(c, self.triangle_patch[t] as usize);
        let of_vertex = |v: usize| describe_patch(c, self.patch_of_vertex[v] as usize);
        let (where_, what) = match &me {
            MeshError::NonManifoldEdge { faces, .. } => (
                faces
                    .iter()
                    .map(|&t| of_tri(t))
                    .collect::<Vec<_>>()
                    .join(", "),
                "more than two triangles share an edge",
            ),
            MeshError::InconsistentOrientation { faces, .. } => (
                format!("{} and {}", of_tri(faces[0]), of_tri(faces[1])),
                "neighbouring triangles disagree in orientation",
            ),
            MeshError::NonManifoldVertex { vertex, .. } => (
                of_vertex(*vertex),
                "the triangles around a point form several fans",
            ),
            MeshError::NonFiniteCoordinate { vertex } => {
                (of_vertex(*vertex), "a point is not finite")
            }
            MeshError::RepeatedVertex { face, .. } | MeshError::FaceTooSmall { face, .. } => {
                (of_tri(*face), "a triangle is degenerate")
            }
            MeshError::IndexOutOfRange { face, .. } => (of_tri(*face), "a corner is out of range"),
            MeshError::Empty => return self.empty_error(c),
        };
        Error::InvalidOutput(format!(
            "the tessellation would not be a valid mesh ({what}: {me}) at {where_}: patches that \
             coincide or collapse within the welding tolerance (the geometry is degenerate, or \
             its coordinates differ too much in scale); write the patches themselves (.bv, \
             .igs) or fix the net"
        ))
    }
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;
    use crate::bezier::BezierPatch;
    use crate::mesh::Element;

    fn square(x: f64, y: f64, s: f64) -> BezierPatch {
        let cps = (0..2)
            .flat_map(|i| (0..2).map(move |j| [x + s * i as f64, y + s * j as f64, 0.0]))
            .collect();
        BezierPatch::new(1, 1, cps)
    }

    #[crate::unit::test]
    fn patches_are_named_by_provenance() {
        let c = PatchComplex {
            patches: vec![square(0.0, 0.0, 1.0); 3],
            provenance: vec![
                Provenance::Regular { face: 4 },
                Provenance::Ring {
                    element: Element::Vertex(5),
                    ring: 2,
                    sector: 1,
                },
                Provenance::Cap {
                    element: Element::Face(3),
                    sector: 0,
                },
            ],
            ..PatchComplex::default()
        };
        assert_eq!(describe_patch(&c, 0), "patch 0 (regular, in face 4)");
        assert_eq!(
            describe_patch(&c, 1),
            "patch 1 (ring 2 around vertex 5, sector 1)"
        );
        assert_eq!(describe_patch(&c, 2), "patch 2 (cap of face 3, sector 0)");
    }

    #[crate::unit::test]
    fn non_finite_coefficients_are_refused_by_patch() {
        let mut p = square(0.0, 0.0, 1.0);
        p.cps[3] = [f64::INFINITY, 0.0, 0.0];
        let c = PatchComplex {
            patches: vec![square(0.0, 0.0, 1.0), p],
            provenance: vec![Provenance::Unknown; 2],
            ..PatchComplex::default()
        };
        let e = check_finite(&c).unwrap_err().to_string();
        assert!(
            e.starts_with("invalid output: patch 1 has the coefficient b[1][1]"),
            "{e}"
        );
    }

    #[crate::unit::test]
    fn a_valid_tessellation_becomes_the_mesh_a_reader_would_read() {
        let c = PatchComplex {
            patches: vec![square(0.0, 0.0, 1.0), square(1.0, 0.0, 1.0)],
            provenance: vec![Provenance::Unknown; 2],
            ..PatchComplex::default()
        };
        let t = crate::surface::tessellate::tessellate(&c, 2);
        let m = t.to_mesh(&c).unwrap();
        assert_eq!((m.num_vertices(), m.num_faces()), (15, 16));
    }

    #[crate::unit::test]
    fn coincident_patches_are_refused_naming_them() {
        // Three copies of one square: every inner edge is shared by three triangles.
        let c = PatchComplex {
            patches: vec![square(0.0, 0.0, 1.0); 3],
            provenance: vec![Provenance::Regular { face: 0 }; 3],
            ..PatchComplex::default()
        };
        let t = crate::surface::tessellate::tessellate(&c, 2);
        let e = t.to_mesh(&c).unwrap_err().to_string();
        assert!(
            e.starts_with("invalid output: the tessellation would not be a valid mesh")
                && e.contains("patch 0 (regular, in face 0)"),
            "{e}"
        );
    }

    #[crate::unit::test]
    fn an_all_degenerate_complex_is_refused() {
        // A patch collapsed to a point covers nothing and is skipped; a complex of such
        // patches only tessellates to nothing.
        let c = PatchComplex {
            patches: vec![square(0.0, 0.0, 1.0), square(0.0, 0.0, 0.0)],
            provenance: vec![Provenance::Unknown; 2],
            ..PatchComplex::default()
        };
        let t = crate::surface::tessellate::tessellate(&c, 2);
        assert!(t.to_mesh(&c).is_ok());
        let d = PatchComplex {
            patches: vec![square(0.0, 0.0, 0.0); 2],
            provenance: vec![Provenance::Unknown; 2],
            ..PatchComplex::default()
        };
        let t = crate::surface::tessellate::tessellate(&d, 2);
        let e = t.to_mesh(&d).unwrap_err().to_string();
        assert!(
            e.contains("the tessellation is empty: all 2 patches"),
            "{e}"
        );
    }
}
