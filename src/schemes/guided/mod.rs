//! Guided subdivision (Karciauskas and Peters, "Guided subdivision surfaces: modeling, shape and
//! refinability"): C^2 bi-6 and curvature-bounded bi-5 rings sampled from a G^2 guide.
//!
//! A well-shaped guide surface `g` ([`guide`]) is sampled ring by ring through the contracting
//! characteristic reparameterization `L^-1 o lambda^l chi` ([`chi`]), by corner jets
//! ([`jets`]); the outer layers of every ring are the C^2 prolongation of the previous ring
//! (of the surrounding bi-3 surface for the first ring) ([`rings`]). The G^1 bi-6 cap is in
//! [`cap`], the bi-4 / bi-3 macro-patch variants of Section 6.2 in [`macro_patch`]. The Bernstein-Bezier matrices they use are in [`crate::bezier::bern`].

pub mod cap;
pub mod chi;
pub mod descriptor;
pub mod entry;
pub mod fourier;
pub mod guide;
pub mod jets;
pub mod local;
pub mod macro_patch;
pub mod rings;
pub mod surface;
