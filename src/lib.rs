//! # fairsub
//!
//! Subdivision surfaces of high shape quality: the schemes of the five fairsub papers
//! (point-augmented, polar and ternary bi-2, Evolving Guide, QAS+, guided and non-box
//! subdivision) beside the classic Catmull-Clark, Doo-Sabin and Loop schemes, on whole meshes,
//! with exact Bezier-patch output, analysis and shape interrogation.
//!
//! Architecture (`ARCHITECTURE.md` in the repository): a control net ([`mesh::PolyMesh`]) is
//! refined by a scheme ([`schemes`]) whose rules are written once as stencils ([`stencil`]);
//! every scheme has one folder under [`schemes`] and one row in the registry
//! ([`schemes::registry`](mod@schemes::registry)), through which the front ends ([`cli`]) find its rules; exact
//! surfaces are [`surface::PatchComplex`]es of [`bezier::BezierPatch`]es, built by the
//! schemes on the adaptive host ([`host`]) and written by [`io`]. Layers only point down:
//! core ([`geom`], [`error`], [`stencil`], [`linalg`]) < [`mesh`] < [`bezier`] < [`host`] <
//! [`schemes`] < [`surface`] < [`analysis`] < [`io`], [`gallery`] < [`render`] < [`cli`].

#![warn(missing_docs)]
// Index loops mirror the papers' formulas (b_ij, K_lm[a][b], ...); iterator rewrites would hide them.
#![allow(clippy::needless_range_loop)]

pub mod analysis;
pub mod bezier;
pub(crate) mod buffers;
pub mod cli;
pub mod error;
pub mod gallery;
pub mod geom;
pub mod host;
pub mod io;
pub mod linalg;
pub mod mesh;
pub mod render;
pub mod schemes;
pub mod stencil;
pub mod surface;

pub use error::{Error, MeshError, Result};
pub use geom::Point;
pub use mesh::PolyMesh;

/// The Rust snippets of the README and the user guide as doctests (`cargo test --release` runs
/// them): each page that holds a Rust block is the documentation of one item here, compiled
/// only by rustdoc's test run, so normal builds do not read the pages. Every fenced block of a
/// page carries an info string (`docs/check-links.py` checks it): a bare one would be compiled
/// as Rust. `tests/reference_pages.rs` checks that every page with a Rust block is listed.
#[cfg(doctest)]
mod doctests {
    /// README.md
    #[doc = include_str!("../README.md")]
    pub struct Readme;
    /// The guide's Rust library page.
    #[doc = include_str!("../docs/guide/src/library.md")]
    pub struct Library;
    /// The guide's patch-table page.
    #[doc = include_str!("../docs/guide/src/patch-tables.md")]
    pub struct PatchTables;
}
