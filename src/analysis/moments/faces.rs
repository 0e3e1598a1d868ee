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

use super::{Region, area_moments, size};
use crate::bezier::BezierPatch;
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

/// One integral: `region` of patch `patch` (transposed: its half `v >= u`), over `face`
/// (`None`: over no face).
struct Part {
    patch: usize,
    region: Region,
    transposed: bool,
    face: Option<u32>,
    /// Whether it is a piece's window.
    piece: bool,
}

/// The parts of the complex's patches over their faces (see the module documentation).
fn parts(c: &PatchComplex) -> Vec<Part> {
    let mut out = Vec::new();
    // kites of closed triangle holes: patch -> the next kite
    let mut next_kite: HashMap<usize, usize> = HashMap::new();
    for step in &c.caps {
        if step.hole.sectors.first().is_some_and(|s| s.len() == 1) && !step.hole.is_open() {
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
            transposed: false,
            face: Some(p.domain.face),
            piece: true,
        });
    }
    for i in 0..c.len() {
        if pieced[i] {
            // what no piece covers: the whole minus the pieces (integrated as such below)
            continue;
        }
        let face = c.domain(i).map(|d| d.face);
        match next_kite.get(&i) {
            Some(&next) => {
                let lower = Region::Lower([0.0, 0.0], 1.0);
                out.push(Part {
                    patch: i,
                    region: lower,
                    transposed: false,
                    face,
                    piece: false,
                });
                out.push(Part {
                    patch: i,
                    region: lower,
                    transposed: true,
                    face: c.domain(next).map(|d| d.face),
                    piece: false,
                });
            }
            None => out.push(Part {
                patch: i,
                region: Region::WHOLE,
                transposed: false,
                face,
                piece: false,
            }),
        }
    }
    out
}

/// The area over each of the `num_faces` input faces of the surface `c` (integrated as in
/// [`super::measure`], to relative tolerance `tol`).
pub fn face_areas(c: &PatchComplex, num_faces: usize, tol: f64) -> FaceAreas {
    let parts = parts(c);
    let area_of =
        |patch: &BezierPatch, region: Region| area_moments(patch, region, tol, size(patch)).0[0];
    let areas: Vec<f64> = parts
        .par_iter()
        .map(|p| {
            let patch = &c.patches[p.patch];
            if p.transposed {
                area_of(&patch.transposed(), p.region)
            } else {
                area_of(patch, p.region)
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
