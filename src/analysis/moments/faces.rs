//! The area of the surface over each input face (`fairsub measure --json --per-face`), from the
//! faces' domains the patches carry ([`crate::bezier::domain`]).
//!
//! A patch with a [`Domain`](crate::bezier::domain::Domain) lies in that domain's face (the
//! sub-faces of an n-gon add up to the n-gon). A patch cut into [`Piece`]s (the dual schemes'
//! patches of vertices, a quarter over each face around the vertex) gives each piece's window
//! to the piece's face; what of such a patch no piece covers (a boundary vertex's half-face
//! strip beyond the net's boundary edges) is reported as `unassigned`. A kite of Loop's G^1 cap
//! (`crate::surface::eval`'s `kite`) covers halves of two fan triangles: its half `u >= v`
//! lies in its own domain's face, its half `v >= u` in the next kite's. Patches without a
//! domain (schemes without `eval`) are unassigned too.
//!
//! When the input faces are fan triangles of the polygons the patches' domains refer to
//! (`nonbox-4dir` on a quasi-four-directional triangle mesh), [`fan_face_areas`] gives each
//! part to the fan triangle that holds it, or halves it first (the `fans` module).

mod fans;

pub use fans::fan_face_areas;

use super::{Region, area_moments, size};
use crate::bezier::BezierPatch;
use crate::bezier::domain::{Affine, Domain};
use crate::surface::PatchComplex;
use rayon::prelude::*;
use serde::Serialize;
use std::collections::HashMap;

/// Area per input face ([`face_areas`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FaceAreas {
    /// The area over each input face.
    pub areas: Vec<f64>,
    /// The area of the parts of the surface over no input face (patches without a domain,
    /// dual boundary strips).
    pub unassigned: f64,
}

/// How a part reads its patch: as stored, or through a symmetry of the parameter square
/// (each keeps the area; `region` is in the symmetric patch's parameters).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum View {
    /// `X(u, v)`.
    Plain,
    /// `X(v, u)`: its [`Region::Lower`] half is `X`'s half `u <= v`.
    Transposed,
    /// `X(1 - u, v)`: its lower half is `X`'s half `u + v <= 1`.
    ReversedU,
    /// `X(1 - v, u)`: its lower half is `X`'s half `u + v >= 1`.
    ReversedUTransposed,
}

impl View {
    /// The patch read this way.
    fn of(self, p: &BezierPatch) -> BezierPatch {
        match self {
            View::Plain => p.clone(),
            View::Transposed => p.transposed(),
            View::ReversedU => p.reversed_u(),
            View::ReversedUTransposed => p.reversed_u().transposed(),
        }
    }

    /// The stored patch's parameters of the point `q` of the view's.
    fn stored(self, [a, b]: [f64; 2]) -> [f64; 2] {
        match self {
            View::Plain => [a, b],
            View::Transposed => [b, a],
            View::ReversedU => [1.0 - a, b],
            View::ReversedUTransposed => [1.0 - b, a],
        }
    }
}

/// One integral: `region` of patch `patch` read through `view`, over `face` (`None`: over no
/// face).
#[derive(Clone, Copy)]
struct Part {
    patch: usize,
    region: Region,
    view: View,
    face: Option<u32>,
    /// Whether it is a piece's window.
    piece: bool,
    /// The cell the part lies in, and the map from the stored patch's parameters to the
    /// domain's patch parameters (a piece's window to `[0, 1]^2`; the identity otherwise).
    cell: Option<(Domain, Affine)>,
}

/// The parts of the complex's patches over their faces (see the module documentation).
fn parts(c: &PatchComplex) -> Vec<Part> {
    let mut out = Vec::new();
    // kites of closed triangle holes: patch -> the next kite
    let mut next_kite: HashMap<usize, usize> = HashMap::new();
    for step in &c.caps {
        if step.hole.sectors.first().is_some_and(|s| s.len() == 1)
            && !step.hole.is_open()
            && step.kept.is_none()
        {
            let (first, n) = (step.first as usize, step.count as usize);
            for s in 0..n {
                next_kite.insert(first + s, first + (s + 1) % n);
            }
        }
    }
    let mut pieced = vec![false; c.len()];
    for p in &c.pieces {
        pieced[p.patch as usize] = true;
        let [lo, hi] = p.window;
        out.push(Part {
            patch: p.patch as usize,
            region: Region::Rect(lo, hi),
            view: View::Plain,
            face: Some(p.domain.face),
            piece: true,
            cell: Some((p.domain, p.window_map().inverse())),
        });
    }
    for i in 0..c.len() {
        if pieced[i] {
            // what no piece covers: the whole minus the pieces (integrated as such below)
            continue;
        }
        let face = c.domain(i).map(|d| d.face);
        let cell = c.domain(i).map(|d| (d, Affine::IDENTITY));
        match next_kite.get(&i) {
            Some(&next) => {
                let lower = Region::Lower([0.0, 0.0], 1.0);
                out.push(Part {
                    patch: i,
                    region: lower,
                    view: View::Plain,
                    face,
                    piece: false,
                    cell,
                });
                out.push(Part {
                    patch: i,
                    region: lower,
                    view: View::Transposed,
                    face: c.domain(next).map(|d| d.face),
                    piece: false,
                    cell,
                });
            }
            None => out.push(Part {
                patch: i,
                region: Region::WHOLE,
                view: View::Plain,
                face,
                piece: false,
                cell,
            }),
        }
    }
    out
}

/// The area over each of the `num_faces` input faces of the surface `c` (integrated as in
/// [`super::measure`], to relative tolerance `tol`).
pub fn face_areas(c: &PatchComplex, num_faces: usize, tol: f64) -> FaceAreas {
    sum_parts(c, &parts(c), num_faces, tol)
}

/// The area of each part, summed per face (`num_faces` of them).
fn sum_parts(c: &PatchComplex, parts: &[Part], num_faces: usize, tol: f64) -> FaceAreas {
    let area_of =
        |patch: &BezierPatch, region: Region| area_moments(patch, region, tol, size(patch)).0[0];
    let areas: Vec<f64> = parts
        .par_iter()
        .map(|p| {
            let patch = &c.patches[p.patch];
            if p.view == View::Plain {
                area_of(patch, p.region)
            } else {
                area_of(&p.view.of(patch), p.region)
            }
        })
        .collect();
    // the patches cut into pieces: their whole area, less the pieces', is over no face
    let mut pieced_total: HashMap<usize, f64> = HashMap::new();
    let mut out = FaceAreas {
        areas: vec![0.0; num_faces],
        unassigned: 0.0,
    };
    for (p, a) in parts.iter().zip(&areas) {
        match p.face {
            Some(f) if (f as usize) < num_faces => out.areas[f as usize] += a,
            _ => out.unassigned += a,
        }
        if p.piece {
            *pieced_total.entry(p.patch).or_default() += a;
        }
    }
    let rest: f64 = pieced_total
        .par_iter()
        .map(|(&i, &covered)| (area_of(&c.patches[i], Region::WHOLE) - covered).max(0.0))
        .sum();
    out.unassigned += rest;
    out
}
