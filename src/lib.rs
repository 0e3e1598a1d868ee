//! # fairsub
//!
//! Subdivision surfaces of high shape quality: the schemes of the five fairsub papers
//! (point-augmented, polar and ternary bi-2, Evolving Guide, QAS+, guided and non-box
//! subdivision) beside the classic Catmull-Clark, Doo-Sabin, Loop, sqrt(3) and modified
//! butterfly schemes, on whole meshes, with exact Bezier-patch output, analysis and shape
//! interrogation.
//!
//! ## The library API
//!
//! A control net is a [`PolyMesh`], read with [`read_net`] (OBJ, OFF, PLY or `gallery:NAME`)
//! and written with [`write_net`]. A scheme is named as on the command line (see [`schemes`]
//! for the catalogue) and takes typed [`Options`]. Then:
//!
//! | entry point | gives | command line |
//! | --- | --- | --- |
//! | [`refine`] | the net refined `levels` times, optionally at its limit ([`Refined`]) | `subdivide --levels N [--limit]` |
//! | [`level_stencils`] | the weights from the control points to the refined points ([`StencilTable`]) | |
//! | [`surface`] | the exact Bezier patch complex ([`Surface`], [`PatchComplex`], [`BezierPatch`]) | `subdivide --rings K` |
//! | [`Surface::evaluate`], [`Surface::closest`] | points, derivatives, normals, curvatures at `(face, u, v)`; closest points ([`Evaluation`]) | `eval`, `project` |
//! | [`Surface::stencils`] | the patch stencil table ([`PatchTable`]) | `subdivide --rings K --stencils F` |
//! | [`Surface::check_json`], [`Surface::measure_json`] | continuity defects; area, volume, inertia | `check`, `measure` |
//! | [`Surface::write`], [`Surface::tessellate`] | `.bv`, IGES, STEP, meshes | `subdivide --rings K -o F` |
//! | [`analyze`] | a scheme's spectrum, limit stencil, characteristic map ([`Analysis`]) | `analyze` |
//! | [`render`] | a picture of a surface or net ([`Image`]) with typed [`RenderOptions`] | `render` |
//!
//! Each entry point runs the command's own code path: the same checks, limits and messages.
//!
//! ```
//! use fairsub::{Options, refine, surface};
//! let o = Options::default();
//! let fine = refine("gallery:cube", "catmull-clark", 2, false, &o)?.into_net();
//! assert_eq!(fine.num_faces(), 96);
//! let s = surface("gallery:cnet-5-saddle", "eg", 3, true, &o)?;
//! let at = s.evaluate(&[(0, 0.25, 0.75)])?;
//! assert!(at[0].normal.iter().all(|x| x.is_finite()));
//! # Ok::<(), fairsub::Error>(())
//! ```
//!
//! The modules behind these (`mesh`, `schemes`, `surface`, `analysis`, `io`, `render`, `cli`,
//! ...) stay public for the crate's own tests, benchmarks and front ends but are hidden from
//! this documentation and carry no stability promise. `ARCHITECTURE.md` in the repository
//! describes them: a control net is refined by a scheme whose rules are written once as
//! stencils; every scheme has one folder under `schemes` and one row in its registry; exact
//! surfaces are patch complexes built on the adaptive host. Layers only point down: core
//! (`geom`, `error`, `stencil`, `linalg`) < `mesh` < `bezier` < `host` < `schemes` < `surface`
//! < `analysis` < `io`, `gallery` < `render` < `cli` and this API.

#![warn(missing_docs)]
// Index loops mirror the papers' formulas (b_ij, K_lm[a][b], ...); iterator rewrites would hide them.
#![allow(clippy::needless_range_loop)]

#[doc(hidden)]
pub mod analysis;
#[doc(hidden)]
pub mod bezier;
pub(crate) mod buffers;
#[doc(hidden)]
pub mod cli;
#[doc(hidden)]
pub mod error;
mod facade;
#[doc(hidden)]
pub mod gallery;
#[doc(hidden)]
pub mod geom;
#[doc(hidden)]
pub mod host;
#[doc(hidden)]
pub mod io;
#[doc(hidden)]
pub mod linalg;
#[doc(hidden)]
pub mod mesh;
#[doc(hidden)]
pub mod render;
#[doc(hidden)]
pub mod schemes;
#[doc(hidden)]
pub mod stencil;
#[doc(hidden)]
pub mod surface;
#[cfg(feature = "unit-tests")]
#[doc(hidden)]
pub mod unit;

pub use bezier::BezierPatch;
pub use error::{Error, MeshError, Result};
pub use facade::{
    AlphaRule, Analysis, BadOption, BoundaryInterpolation, CreaseMethod, Drawn, Fallback,
    FvarInterpolation, Image, LookOption, Mode, Options, Overlays, Prepare, Refined, RenderOptions,
    RulesChoice, SchemeRow, ShadeOptions, Source, Surface, View, analyze, level_stencils, read_net,
    refine, render, schemes, surface, write_net,
};
pub use geom::Point;
pub use mesh::{Element, PolyMesh};
pub use schemes::Spec;
pub use stencil::StencilTable;
pub use surface::PatchComplex;
pub use surface::eval::Evaluation;
pub use surface::table::PatchTable;

/// The Rust snippets of the README and the user guide as doctests (`cargo test --release` runs
/// them): each page that holds a Rust block is the documentation of one item here, compiled
/// only by rustdoc's test run, so normal builds do not read the pages. Every fenced block of a
/// page carries an info string (`docs/check-links.py` checks it): a bare one would be compiled
/// as Rust. `tests/it/reference_pages.rs` checks that every page with a Rust block is listed.
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
