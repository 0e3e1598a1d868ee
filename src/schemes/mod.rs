//! Subdivision schemes, one module per family, each written once as stencils.
//!
//! A scheme that refines whole control nets implements [`Scheme`]: one refinement step returns
//! the child net together with the [`StencilTable`](crate::stencil::StencilTable) that computes every child point from the
//! parent points. Applying a scheme to positions, composing several levels, building the local
//! subdivision matrix for analysis or re-applying the step to moved points all reuse that one
//! table, so every rule exists exactly once.
//!
//! The folders, from the bottom up: [`options`] (scheme ids and typed options; imports no
//! scheme), [`sdc`] (OpenSubdiv's rules shared by several schemes: creases, corners, darts,
//! face-varying data), the shared vocabulary ([`descriptor`], [`entry`], [`local`],
//! [`circulant`], [`growth`], the [`Scheme`] trait), the scheme families (one folder each, with
//! its rules, surfaces, analysis, descriptor and registry rows), the preparation stage
//! ([`prepare`], which applies families' steps), and on top the `registry`, which lists the
//! families' rows. Arrows only point down: no family imports the registry or the preparation
//! stage's steps, and there is no import circle between these folders (`tests/architecture.rs`).

pub mod bi2;
pub mod butterfly;
pub mod catmull_clark;
pub mod circulant;
pub mod descriptor;
pub mod doo_sabin;
pub mod eg;
pub mod entry;
pub mod growth;
pub mod guided;
pub mod local;
pub mod loop_subdivision;
pub mod needs;
pub mod nonbox;
pub mod options;
pub mod prepare;
pub mod qas;
pub mod registry;
mod scheme;
pub mod sdc;
pub mod sqrt3;

mod common;
mod split_child;

pub use catmull_clark::CatmullClark;
pub use doo_sabin::{DooSabin, DooSabinCc};
pub use loop_subdivision::Loop;
pub use nonbox::{NonBox, NonBox4Dir};

pub use descriptor::Descriptor;
pub use options::{SchemeId, Spec};
pub use registry::{Registry, SchemeInfo, by_name, catalog, registry};
pub(crate) use scheme::finish_refinement;
pub use scheme::{FcvLayout, Refinement, Scheme, level_stencils, refine_levels};
