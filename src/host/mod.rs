//! The machinery every scheme's exact surface is built with, below the schemes so that each
//! scheme's folder can drive it: the one adaptive level loop ([`adaptive`]) and the caps that
//! replace rings by local constructions ([`caps`]), with the options and outputs they share.

pub mod adaptive;
pub mod caps;
pub mod fans;

use crate::bezier::complex::PatchComplex;
use crate::mesh::Element;

/// What schemes with rules for some valences only (EG, QAS+, guided) do elsewhere.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Fallback {
    /// Catmull-Clark rings and fill (the default).
    #[default]
    CatmullClark,
    /// Stop with an error naming the vertex.
    Error,
}

/// Options for exact patch output of any scheme.
#[derive(Debug, Clone, Copy)]
pub struct ComplexOptions {
    /// Rings per extraordinary element.
    pub rings: usize,
    /// Close the central hole (each scheme documents its fill).
    pub fill: bool,
}

/// A patch complex with what the user should know about it.
#[derive(Debug, Clone, Default)]
pub struct SurfaceOutput {
    /// The surface.
    pub complex: PatchComplex,
    /// Elements that fell back to Catmull-Clark, with their valences.
    pub fell_back: Vec<(Element, usize)>,
    /// Notes for the user (fallbacks and substitutions, per element; input conversions).
    pub notes: Vec<String>,
}

impl SurfaceOutput {
    /// A complex without notes.
    pub fn plain(complex: PatchComplex) -> SurfaceOutput {
        SurfaceOutput {
            complex,
            ..SurfaceOutput::default()
        }
    }
}
