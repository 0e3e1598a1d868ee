//! Curvature behaviour near extraordinary elements: Gauss and mean curvature ranges per ring.
//!
//! "Curvature bounded" and "curvature diverges" become numbers: for every extraordinary element
//! of a patch complex, the range of Gauss and mean curvature over the patches of each ring
//! (sampled on a grid per patch, with the exact Bezier second derivatives). Bounded curvature
//! shows as ranges that converge with the ring index; Catmull-Clark's grow or oscillate for
//! valences other than 4.

use crate::surface::{Element, PatchComplex, Provenance};
use serde::Serialize;
use std::collections::BTreeMap;

/// Curvature range over one ring (or the cap) of one element.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct RingCurvature {
    /// Ring index (1 = outermost); 0 for the cap.
    pub ring: u32,
    /// Patches in the ring.
    pub patches: usize,
    /// Minimum Gauss curvature.
    pub gauss_min: f64,
    /// Maximum Gauss curvature.
    pub gauss_max: f64,
    /// Minimum mean curvature.
    pub mean_min: f64,
    /// Maximum mean curvature.
    pub mean_max: f64,
}

/// Per-ring curvature of one extraordinary element.
#[derive(Debug, Clone, Serialize)]
pub struct ElementCurvature {
    /// The element.
    pub element: Element,
    /// Rings in increasing index, then the cap (ring 0) if present.
    pub rings: Vec<RingCurvature>,
}

/// Samples per patch direction.
const GRID: usize = 7;

/// Curvature ranges per ring for every element with rings in the complex.
pub fn ring_curvature(c: &PatchComplex) -> Vec<ElementCurvature> {
    let mut map: BTreeMap<(u8, u32), BTreeMap<u32, RingCurvature>> = BTreeMap::new();
    for (p, prov) in c.patches.iter().zip(&c.provenance) {
        let (element, ring) = match prov {
            Provenance::Ring { element, ring, .. } => (*element, *ring),
            Provenance::Cap { element, .. } => (*element, 0),
            _ => continue,
        };
        let key = match element {
            Element::Vertex(v) => (0u8, v),
            Element::Face(f) => (1u8, f),
        };
        let e = map
            .entry(key)
            .or_default()
            .entry(ring)
            .or_insert(RingCurvature {
                ring,
                patches: 0,
                gauss_min: f64::INFINITY,
                gauss_max: f64::NEG_INFINITY,
                mean_min: f64::INFINITY,
                mean_max: f64::NEG_INFINITY,
            });
        e.patches += 1;
        for i in 0..GRID {
            for j in 0..GRID {
                let (u, v) = (i as f64 / (GRID - 1) as f64, j as f64 / (GRID - 1) as f64);
                let k = p.curvatures(u, v);
                if k.gauss.is_finite() && k.mean.is_finite() {
                    e.gauss_min = e.gauss_min.min(k.gauss);
                    e.gauss_max = e.gauss_max.max(k.gauss);
                    e.mean_min = e.mean_min.min(k.mean);
                    e.mean_max = e.mean_max.max(k.mean);
                }
            }
        }
    }
    map.into_iter()
        .map(|((kind, idx), rings)| {
            let mut rs: Vec<RingCurvature> = rings.into_values().collect();
            // Rings 1.. first, the cap (0) last.
            rs.sort_by_key(|r| if r.ring == 0 { u32::MAX } else { r.ring });
            ElementCurvature {
                element: if kind == 0 {
                    Element::Vertex(idx)
                } else {
                    Element::Face(idx)
                },
                rings: rs,
            }
        })
        .collect()
}
