//! G^1 caps: close the hole inside the last ring of a patch complex with `n` tensor-product
//! patches that join the ring C^1 and each other G^1, centred at a given point with a given
//! tangent plane, for every scheme that writes patches.
//!
//! The hole is described scheme-independently by [`Hole`] (conventions in [`hole`]); the cap is
//! one fixed linear map of the hole's data per (valence, layout, segment degrees, cap degree),
//! [`CapMap`], built once and cached ([`cap_map`]), whose matrix a stencil table can reuse.
//!
//! (Construction, conditions, free parameters and the degree argument: see below.)

pub mod hole;
mod map;
mod system;
#[cfg(test)]
mod tests;

pub use hole::{Degrees, Hole, Layout, QuadHole, Segment, spoke_tangent};
pub use map::{
    CERTIFIED, Cap, CapMap, CapOptions, Centre, FAIRNESS_ORDER, MAX_COMPATIBILITY_DEFECT, cap_map,
    g1_cap, g1_cap_with, lowest_certified_degree,
};
