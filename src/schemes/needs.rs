//! What a scheme's rules need of a net, and the steps that meet each need: the vocabulary of
//! the preparation stage ([`super::prepare`]), which families use in their descriptors
//! ([`super::Descriptor::preparation`]). It sits below the families; the stage that applies
//! the steps (each a family's own refinement) sits above them.

use crate::mesh::{Element, PolyMesh};
use crate::schemes::options::Spec;

/// What the prepared net is for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Purpose {
    /// Whole-net refinement (`--levels`).
    Refine,
    /// Exact patches (`--rings`), evaluation, patch tables.
    Patches,
}

/// What a scheme's rules need of a net.
#[derive(Debug, Clone, Copy)]
pub enum Need {
    /// Every face a quad.
    Quads,
    /// Every interior vertex of valence 3 or more.
    NoInteriorValence2,
    /// Every boundary vertex regular: two faces, or one at a corner.
    RegularBoundary,
    /// Sharp features infinitely sharp only: no semi-sharp crease or corner (a finite
    /// positive sharpness), which the scheme's element rings have no step to spend.
    InfinitelySharpOnly,
    /// `need` on nets with (`true`) or without (`false`) semi-sharp features only, met
    /// otherwise: a scheme whose construction on semi-sharp nets needs less (TPS, whose
    /// semi-sharp nets are Doo-Sabin's construction beside its elements).
    IfSemiSharp(bool, &'static Need),
    /// A property only the scheme can test: `what` it is (for notes, after "needs"), `test`
    /// the elements where it fails.
    Scheme {
        /// The property in words.
        what: &'static str,
        /// The elements of a net where it fails (empty: met).
        test: fn(&PolyMesh, &Spec) -> Vec<Element>,
    },
}

/// How a need is met.
#[derive(Debug, Clone, Copy)]
pub enum Step {
    /// Whole-net steps applied here, in order.
    Net(&'static [NetStep]),
    /// A step the scheme's own construction takes (locally and exactly, with its own note),
    /// described in words; [`super::prepare::prepare`] leaves the net as it is and reports it.
    Own(&'static str),
}

/// One need of a scheme and the step that meets it.
#[derive(Debug, Clone, Copy)]
pub struct Requirement {
    /// What the rules need.
    pub need: Need,
    /// The step that gives it.
    pub step: Step,
}

impl Need {
    /// The need in words, after the scheme's name ("tps needs ...").
    pub fn words(&self) -> &'static str {
        match self {
            Need::Quads => "needs every face a quad",
            Need::NoInteriorValence2 => "needs every interior vertex of valence 3 or more",
            Need::RegularBoundary => {
                "needs every boundary vertex regular (two faces, or one at a corner it keeps)"
            }
            Need::InfinitelySharpOnly => {
                "takes infinitely sharp creases and corners only (its element rings have no \
                 step that spends a finite sharpness)"
            }
            Need::IfSemiSharp(_, need) => need.words(),
            Need::Scheme { what, .. } => what,
        }
    }
}

/// A whole-net step of the preparation (see the [`super::prepare`] documentation).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NetStep {
    /// One Catmull-Clark step (OpenSubdiv's rules, with the net's options and sharp features).
    CatmullClark,
    /// One Doo-Sabin step (with the dual schemes' boundary rules).
    DooSabin,
    /// One DS^CC step.
    DooSabinCc,
    /// One PGS step (Doo-Sabin's topology, the point-augmented rule at facets).
    Pgs,
}

impl NetStep {
    /// The scheme of the step, by name.
    pub fn name(self) -> &'static str {
        match self {
            NetStep::CatmullClark => "Catmull-Clark",
            NetStep::DooSabin => "Doo-Sabin",
            NetStep::DooSabinCc => "DS^CC",
            NetStep::Pgs => "PGS",
        }
    }

    /// The step in words.
    pub fn words(self) -> &'static str {
        match self {
            NetStep::CatmullClark => "one Catmull-Clark step",
            NetStep::DooSabin => "one Doo-Sabin step",
            NetStep::DooSabinCc => "one DS^CC step",
            NetStep::Pgs => "one PGS step",
        }
    }

    /// Whether the step is dual (a face per vertex; it does not carry sharp-feature tags).
    pub fn is_dual(self) -> bool {
        self != NetStep::CatmullClark
    }
}
