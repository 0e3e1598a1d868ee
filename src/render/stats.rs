//! Numbers beside the pictures: curvature ranges per ring (sampled on the patches themselves,
//! independent of the camera) and per frame (over the visible samples).
//!
//! A colour map shows where curvature is large; the numbers say how large, ring by ring, so the
//! growth or decay of curvature toward an extraordinary point can be read off directly (the
//! papers' criterion for bounded curvature).

use super::raster::Frame;
use crate::surface::{Element, PatchComplex, Provenance};
use rayon::prelude::*;
use serde::Serialize;
use std::collections::BTreeMap;

/// Coverage and curvature ranges over the covered samples of a frame.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FrameStats {
    /// Samples in the frame.
    pub samples: usize,
    /// Samples that see the surface.
    pub covered: usize,
    /// `covered / samples`.
    pub coverage: f64,
    /// Covered samples at the exact ray intersection (see [`Frame::exact`]).
    pub exact: usize,
    /// `[min, max]` of the Gauss curvature over covered samples where it is defined.
    pub gauss: Option<[f64; 2]>,
    /// `[min, max]` of the mean curvature over covered samples where it is defined.
    pub mean: Option<[f64; 2]>,
}

fn widen(r: &mut Option<[f64; 2]>, x: f64) {
    if x.is_finite() {
        *r = Some(match *r {
            None => [x, x],
            Some([lo, hi]) => [lo.min(x), hi.max(x)],
        });
    }
}

fn merge(a: Option<[f64; 2]>, b: Option<[f64; 2]>) -> Option<[f64; 2]> {
    match (a, b) {
        (None, x) | (x, None) => x,
        (Some([a0, a1]), Some([b0, b1])) => Some([a0.min(b0), a1.max(b1)]),
    }
}

/// An `f32` as the `f64` of its shortest decimal form (`0.17914301`, not
/// `0.1791430115699768`), so reports show the stored precision.
fn short(x: f32) -> f64 {
    x.to_string().parse().unwrap_or(x as f64)
}

impl FrameStats {
    /// The statistics of a frame.
    pub fn of(frame: &Frame) -> FrameStats {
        let (mut gauss, mut mean) = (None, None);
        let mut covered = 0;
        for s in frame.samples.iter().filter(|s| s.is_covered()) {
            covered += 1;
            widen(&mut gauss, s.gauss as f64);
            widen(&mut mean, s.mean as f64);
        }
        let gauss = gauss.map(|r: [f64; 2]| r.map(|x| short(x as f32)));
        let mean = mean.map(|r: [f64; 2]| r.map(|x| short(x as f32)));
        let samples = frame.samples.len();
        FrameStats {
            samples,
            covered,
            coverage: if samples > 0 {
                covered as f64 / samples as f64
            } else {
                0.0
            },
            exact: frame.exact,
            gauss,
            mean,
        }
    }
}

/// Curvature ranges of one provenance group (the regular patches, ring `k` of an element, or
/// its cap).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GroupCurvature {
    /// Group name as in `.bv` files (`regular`, `ring3`, `cap`, `patches`).
    pub group: String,
    /// The extraordinary element of a ring or cap.
    pub element: Option<Element>,
    /// Ring index (1 = outermost) of a ring.
    pub ring: Option<u32>,
    /// Patches in the group.
    pub patches: usize,
    /// `[min, max]` Gauss curvature over the samples.
    pub gauss: Option<[f64; 2]>,
    /// `[min, max]` mean curvature over the samples.
    pub mean: Option<[f64; 2]>,
    /// Largest absolute principal curvature.
    pub max_abs_principal: Option<f64>,
}

/// Gauss range, mean range and largest absolute principal curvature of one patch.
type PatchRanges = (Option<[f64; 2]>, Option<[f64; 2]>, Option<f64>);

/// Curvature ranges per provenance group, from the exact curvatures of every patch at the
/// `(n + 1) x (n + 1)` domain points `(i / n, j / n)` (boundaries included; undefined values
/// skipped). Groups come in the order regular, then by element and ring (cap last), then
/// unknown.
pub fn curvature_by_group(c: &PatchComplex, n: usize) -> Vec<GroupCurvature> {
    let n = n.max(1);
    let per_patch: Vec<PatchRanges> = c
        .patches
        .par_iter()
        .map(|p| {
            let (mut g, mut m, mut k) = (None, None, None::<f64>);
            for i in 0..=n {
                for j in 0..=n {
                    let cv = p.curvatures(i as f64 / n as f64, j as f64 / n as f64);
                    widen(&mut g, cv.gauss);
                    widen(&mut m, cv.mean);
                    let a = cv.k1.abs().max(cv.k2.abs());
                    if a.is_finite() {
                        k = Some(k.map_or(a, |x| x.max(a)));
                    }
                }
            }
            (g, m, k)
        })
        .collect();
    let key = |p: &Provenance| -> (u8, u8, u32, u32) {
        let el = |e: &Element| match *e {
            Element::Vertex(v) => (0u8, v),
            Element::Face(f) => (1u8, f),
        };
        match p {
            Provenance::Regular { .. } => (0, 0, 0, 0),
            Provenance::Ring { element, ring, .. } => {
                let (k, i) = el(element);
                (1, k, i, *ring)
            }
            Provenance::Cap { element, .. } => {
                let (k, i) = el(element);
                (1, k, i, u32::MAX)
            }
            Provenance::Unknown => (2, 0, 0, 0),
        }
    };
    let mut groups: BTreeMap<(u8, u8, u32, u32), GroupCurvature> = BTreeMap::new();
    for (prov, (g, m, k)) in c.provenance.iter().zip(per_patch) {
        let entry = groups.entry(key(prov)).or_insert_with(|| GroupCurvature {
            group: prov.group_name(),
            element: match prov {
                Provenance::Ring { element, .. } | Provenance::Cap { element, .. } => {
                    Some(*element)
                }
                _ => None,
            },
            ring: match prov {
                Provenance::Ring { ring, .. } => Some(*ring),
                _ => None,
            },
            patches: 0,
            gauss: None,
            mean: None,
            max_abs_principal: None,
        });
        entry.patches += 1;
        entry.gauss = merge(entry.gauss, g);
        entry.mean = merge(entry.mean, m);
        entry.max_abs_principal = match (entry.max_abs_principal, k) {
            (Some(a), Some(b)) => Some(a.max(b)),
            (a, b) => a.or(b),
        };
    }
    groups.into_values().collect()
}
