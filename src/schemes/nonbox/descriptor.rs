//! The descriptors of the non-box schemes: mesh rules (on nets with FCVs), exact patches, local
//! analysis.

use super::{NonBox, NonBox4Dir};
use crate::bezier::BezierPatch;
use crate::bezier::complex::PatchComplex;
use crate::bezier::domain::FanTriangle;
use crate::error::Result;
use crate::mesh::PolyMesh;
use crate::schemes::Scheme;
use crate::schemes::circulant::SparseLocal;
use crate::schemes::descriptor::{
    Capabilities, Computed, Descriptor, LocalRules, ParamKind, PatchRules, Published, Spec,
    SurfaceOutput, patch_fn,
};
use crate::schemes::local::LocalMatrix;

/// Non-box subdivision: the quad variant with FCVs (`four_dir = false`) or the
/// four-directional triangle variant.
#[derive(Debug)]
pub struct NonBoxDescriptor {
    /// The four-directional variant.
    pub four_dir: bool,
}

/// The registry's non-box row.
pub static DESCRIPTOR: NonBoxDescriptor = NonBoxDescriptor { four_dir: false };
/// The registry's four-directional non-box row.
pub static DESCRIPTOR_4DIR: NonBoxDescriptor = NonBoxDescriptor { four_dir: true };

impl Descriptor for NonBoxDescriptor {
    /// Both evaluate: `nonbox` on its net's faces (the domains of `super::surface`),
    /// `nonbox-4dir` on the triangles of its input mesh (or the polygons, when the input is a
    /// polygon net; `super::surface::nonbox_4dir_mesh_complex`).
    fn capabilities(&self) -> Capabilities {
        Capabilities {
            eval: true,
            ..Capabilities::REFINE_AND_PATCHES
        }
    }

    /// The FCVs; the net's creases and corners with OpenSubdiv's rules carried over
    /// (`nonbox::sharp`, fairsub's construction); `nonbox` refines hole tags too
    /// (`nonbox::holes`).
    fn params(&self) -> &'static [ParamKind] {
        if self.four_dir {
            &[ParamKind::Fcv, ParamKind::Creases]
        } else {
            &[ParamKind::Fcv, ParamKind::Creases, ParamKind::Holes]
        }
    }

    /// Creases and corners, infinitely sharp and semi-sharp (`nonbox::sharp`).
    fn patches_take_features(&self) -> bool {
        true
    }

    fn mesh_rules(&self, _: &Spec) -> Result<Option<Box<dyn Scheme>>> {
        Ok(Some(if self.four_dir {
            Box::new(NonBox4Dir)
        } else {
            Box::new(NonBox::default())
        }))
    }

    /// Four cubic triangles per regular cell, rings, fill; the notes say how the input's FCVs
    /// were read.
    fn patch_rules(&self, _: &Spec) -> Result<Option<Box<dyn PatchRules>>> {
        let four_dir = self.four_dir;
        patch_fn(move |mesh, opts, mut progress| {
            let mut build = |m: &PolyMesh| -> Result<PatchComplex> {
                let mut complex = if four_dir {
                    super::surface::nonbox_4dir_mesh_complex(m, opts, &mut progress)?
                } else {
                    super::surface::nonbox_mesh_complex(m, opts, &mut progress)?
                };
                if m.extras().is_some_and(|e| e.has_features()) {
                    // the sides marked on the boundary of the cut net: crease sides kept
                    crate::schemes::doo_sabin::sharp::keep_crease_sides(&mut complex);
                }
                Ok(complex)
            };
            let mut notes = super::input_notes(four_dir, mesh);
            // hole faces: the surface of the net without the tags, less their patches
            let fan = match four_dir && mesh.extras().is_some_and(|e| !e.holes.is_empty()) {
                true => super::surface::nonbox_4dir_fan_faces(mesh)?,
                false => None,
            };
            let complex = match super::holes::leave_out_holes(mesh, fan.as_deref(), &mut build)? {
                Some((complex, note)) => {
                    notes.push(note);
                    complex
                }
                None => build(mesh)?,
            };
            Ok(SurfaceOutput {
                complex,
                fell_back: Vec::new(),
                notes,
            })
        })
    }

    /// `nonbox-4dir` on a quasi-four-directional triangle mesh evaluates on its triangles,
    /// fan triangles of the polygons its complex is built on.
    fn eval_faces(&self, _: &Spec, mesh: &PolyMesh) -> Result<Option<Vec<FanTriangle>>> {
        if self.four_dir {
            super::surface::nonbox_4dir_fan_faces(mesh)
        } else {
            Ok(None)
        }
    }

    fn local_rules(&self, _: &Spec) -> Result<Option<Box<dyn LocalRules>>> {
        Ok(Some(Box::new(NonBoxLocal {
            four_dir: self.four_dir,
        })))
    }
}

/// Non-box local analysis (the published numbers and the characteristic ring are the same for
/// both variants: they have the same limit surface).
struct NonBoxLocal {
    four_dir: bool,
}

impl LocalRules for NonBoxLocal {
    fn matrix(&self, n: usize) -> Result<LocalMatrix> {
        if self.four_dir {
            super::local::local_matrix_4dir(n)
        } else {
            super::local::local_matrix(n)
        }
    }

    fn sparse(&self, n: usize) -> Result<Option<SparseLocal>> {
        super::local::local_sparse(n, self.four_dir).map(Some)
    }

    fn characteristic_ring(&self, n: usize) -> Result<(Vec<BezierPatch>, f64)> {
        super::local::characteristic_ring(n)
    }

    fn published(&self, n: usize, _: &Computed<'_>) -> Result<Vec<Published>> {
        super::local::published_comparisons(n)
    }
}
