//! CAD faces and B-rep topology of an exact surface: what the STEP and IGES writers hand to a
//! CAD system.
//!
//! A patch complex is a soup of Bezier patches. CAD wants few faces and a watertight shell, so
//! this module turns a complex into [`CadFaces`], polynomial B-spline surfaces
//! ([`spline::SplineSurface`]), in one of three [`FaceMode`]s:
//!
//! * [`FaceMode::Patches`]: one face per patch (what IGES output always was);
//! * [`FaceMode::Input`]: one face per input face, per quad sub-face of an n-gon (the
//!   `merge` submodule: the face's regular patch, its rings and its share of the cap on one
//!   tensor grid in the face's parameters, knot multiplicities from the continuity measured
//!   across each knot line); patches whose domain the scheme does not track, or that are
//!   triangles (Loop, non-box), stay faces of their own;
//! * [`FaceMode::Packed`]: the input faces of the net's regular quad regions merged further
//!   into rectangles of the quad layout (the `pack` submodule), each one B-spline.
//!
//! [`brep::Brep`] then finds the topology from the geometry: corner points welded into
//! vertices, a face side that meets two shorter sides split at the T-point, each edge shared
//! by the two faces that use it with opposite senses.

pub mod brep;
mod merge;
mod pack;
pub mod spline;

use crate::error::{Error, Result};
use crate::surface::PatchComplex;
use spline::SplineSurface;

/// Which faces a CAD file gets (`subdivide --faces`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum FaceMode {
    /// One face per Bezier patch.
    Patches,
    /// One B-spline face per input face (per quad sub-face of an n-gon).
    #[default]
    Input,
    /// The input faces of regular regions merged into rectangles of the quad layout.
    Packed,
}

/// Where a CAD face comes from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FaceSource {
    /// Input face `face` (sub-face `sub` of an n-gon, 0 otherwise): the surface's `(u, v)` are
    /// the face's (sub-face's) parameters ([`crate::bezier::domain`]).
    Input {
        /// The input face.
        face: u32,
        /// The sub-face of an n-gon, 0 for a quad.
        sub: u32,
    },
    /// A rectangle of `size[0] x size[1]` input faces of a regular region, the first (at
    /// `(u, v) = (0, 0)`) input face `face` (sub-face `sub`).
    Packed {
        /// The input face at the rectangle's origin.
        face: u32,
        /// Its sub-face.
        sub: u32,
        /// The rectangle's size in input faces.
        size: [u32; 2],
    },
    /// The part `window` (`[lo, hi]` of its parameters) of patch `patch`, over `[0, 1]^2`.
    Patch {
        /// The patch of the complex.
        patch: u32,
        /// The window of the patch's parameters.
        window: [[f64; 2]; 2],
    },
}

/// The faces of a surface for a CAD file.
#[derive(Debug, Clone, Default)]
pub struct CadFaces {
    /// The surfaces.
    pub surfaces: Vec<SplineSurface>,
    /// Where each comes from.
    pub sources: Vec<FaceSource>,
    /// Largest deviation of a merged face from the patches it holds, at sample points.
    pub deviation: f64,
    /// Input faces (sub-faces) that could not be merged, so their patches are faces of their
    /// own.
    pub unmerged: usize,
    /// Merged faces whose measured knot multiplicities gave a spline off its patches by more
    /// than rounding, so every knot got multiplicity `p` (C^0; exact, more control points).
    pub c0_faces: usize,
}

impl CadFaces {
    /// Number of faces.
    pub fn len(&self) -> usize {
        self.surfaces.len()
    }

    /// Whether there are no faces.
    pub fn is_empty(&self) -> bool {
        self.surfaces.is_empty()
    }

    fn push(&mut self, s: SplineSurface, src: FaceSource) {
        self.surfaces.push(s);
        self.sources.push(src);
    }
}

/// The tolerance of the continuity tests of a merge: `1e-13` of the complex's size.
pub fn merge_tolerance(c: &PatchComplex) -> f64 {
    super::adjacency::default_tolerance(c) * 1e-4
}

/// The faces of `complex` in `mode`.
///
/// # Errors
/// [`Error::InvalidArgument`] for an empty complex.
pub fn faces(complex: &PatchComplex, mode: FaceMode) -> Result<CadFaces> {
    if complex.is_empty() {
        return Err(Error::InvalidArgument(
            "the surface has no patches: nothing to write".into(),
        ));
    }
    match mode {
        FaceMode::Patches => Ok(patch_faces(complex)),
        FaceMode::Input => Ok(input_faces(complex)),
        FaceMode::Packed => Ok(packed_faces(complex)),
    }
}

/// One face per patch.
fn patch_faces(c: &PatchComplex) -> CadFaces {
    let mut out = CadFaces::default();
    for (i, p) in c.patches.iter().enumerate() {
        out.push(
            SplineSurface::from_bezier(p),
            FaceSource::Patch {
                patch: i as u32,
                window: [[0.0, 0.0], [1.0, 1.0]],
            },
        );
    }
    out
}

/// One face per input face where the pieces merge, the rest per patch (or per part of one).
fn input_faces(c: &PatchComplex) -> CadFaces {
    use rayon::prelude::*;
    let tol = merge_tolerance(c);
    // a merged face may differ from its patches by rounding only
    let limit = 10.0 * tol;
    let grouped = merge::group(c);
    let groups: Vec<_> = grouped.groups.into_iter().collect();
    let merged: Vec<Option<merge::Merged>> = groups
        .par_iter()
        .map(|(_, pieces)| merge::merge_face(pieces, tol, limit))
        .collect();
    let mut out = CadFaces::default();
    let mut extra: Vec<(usize, [[f64; 2]; 2])> = Vec::new();
    for ((key, pieces), m) in groups.iter().zip(merged) {
        match m {
            Some(m) => {
                out.deviation = out.deviation.max(m.deviation);
                out.c0_faces += usize::from(m.c0);
                out.push(
                    m.surface,
                    FaceSource::Input {
                        face: key.0,
                        sub: key.1,
                    },
                );
            }
            None => {
                out.unmerged += 1;
                extra.extend(pieces.iter().map(|p| (p.patch, p.window)));
            }
        }
    }
    for (i, rest) in grouped.leftover.iter().enumerate() {
        extra.extend(rest.iter().map(|w| (i, *w)));
    }
    extra.sort_by(|a, b| {
        a.0.cmp(&b.0)
            .then(a.1[0][0].total_cmp(&b.1[0][0]))
            .then(a.1[0][1].total_cmp(&b.1[0][1]))
    });
    for (i, w) in extra {
        let p = &c.patches[i];
        let part = if w == [[0.0, 0.0], [1.0, 1.0]] {
            p.clone()
        } else {
            p.subpatch(w[0][0], w[1][0], w[0][1], w[1][1])
        };
        out.push(
            SplineSurface::from_bezier(&part),
            FaceSource::Patch {
                patch: i as u32,
                window: w,
            },
        );
    }
    out
}

/// The input faces, with those of regular regions (one polynomial piece each) packed into
/// rectangles of the quad layout.
fn packed_faces(c: &PatchComplex) -> CadFaces {
    let input = input_faces(c);
    let regular: Vec<bool> = input
        .surfaces
        .iter()
        .zip(&input.sources)
        .map(|(s, src)| matches!(src, FaceSource::Input { .. }) && pack::is_single_span(s))
        .collect();
    let tol = merge_tolerance(c);
    let weld = super::adjacency::default_tolerance(c);
    let packs = pack::pack(&input.surfaces, &regular, weld, tol, 10.0 * tol);
    let mut out = CadFaces {
        deviation: input.deviation,
        unmerged: input.unmerged,
        c0_faces: input.c0_faces,
        ..CadFaces::default()
    };
    let mut placed = vec![false; input.len()];
    for p in packs {
        for &f in &p.faces {
            placed[f] = true;
        }
        match p.surface {
            Some(s) => {
                out.deviation = out.deviation.max(p.deviation);
                let (face, sub) = match input.sources[p.faces[0]] {
                    FaceSource::Input { face, sub } => (face, sub),
                    _ => unreachable!("only input faces are packed"),
                };
                let size = [p.size[0] as u32, p.size[1] as u32];
                out.push(s, FaceSource::Packed { face, sub, size });
            }
            None => {
                for &f in &p.faces {
                    out.push(input.surfaces[f].clone(), input.sources[f]);
                }
            }
        }
    }
    for (f, done) in placed.iter().enumerate() {
        if !done {
            out.push(input.surfaces[f].clone(), input.sources[f]);
        }
    }
    out
}
