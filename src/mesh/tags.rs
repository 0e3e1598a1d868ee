//! OpenSubdiv's tags: the sharp features a net carries (creases, corners, holes) and the
//! subdivision options it may ask for, with the names OpenSubdiv gives them.
//!
//! An OpenSubdiv-style OBJ file says them in `t` lines (`t crease 2/1/0 3 7 2.5`,
//! `t interpolateboundary 1/0/0 1`, ...; `io::obj` reads them), an OFF or PLY net in a
//! `--creases` side file (`io::creases`), and the command line gives the options too
//! (`--boundary`, `--crease-method`, `--smooth-triangles`, `--fvar`; a command-line option
//! overrides a tag). [`Tags`] holds what a file said, in the file's vertex and face numbering,
//! with the line of each tag so that a tag that does not fit the net is reported where it
//! was written; [`crate::mesh::PolyMesh::with_tags`] attaches them to the net.
//!
//! The options' meaning (OpenSubdiv's `Sdc::Options`) is written in `docs/opensubdiv-rules.md`
//! and applied by the Catmull-Clark and Loop rules.

use std::fmt;

/// How boundary vertices are interpolated (`Sdc::Options::VtxBoundaryInterpolation`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum BoundaryInterpolation {
    /// `none`: faces at a boundary vertex whose boundary edges are not all tagged infinitely
    /// sharp become holes (refined for support, not written).
    None,
    /// `edge-only`: boundary edges are infinitely sharp creases; a vertex with a single face
    /// follows the crease rule along its two boundary edges.
    EdgeOnly,
    /// `edge-and-corner`: as `edge-only`, and a vertex with a single face is an infinitely sharp
    /// corner (it stays put). fairsub's default.
    EdgeAndCorner,
}

/// How semi-sharp creases decay (`Sdc::Options::CreasingMethod`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum CreaseMethod {
    /// `uniform` (the OBJ tag says `normal`): every child edge gets the sharpness minus one.
    Uniform,
    /// `chaikin`: a child edge's sharpness averages the parent's with the neighbouring
    /// semi-sharp edges at its end (3/4, 1/4) before subtracting one.
    Chaikin,
}

/// How Catmull-Clark treats triangles (`Sdc::Options::TriangleSubdivision`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum TriangleSubdivision {
    /// `catmark`: the ordinary rules.
    Catmark,
    /// `smooth`: the edge points of smooth edges next to triangles weigh the triangle's face
    /// point 0.47 instead of 0.25 (Catmull-Clark only).
    Smooth,
}

/// How face-varying data (texture coordinates) is interpolated
/// (`Sdc::Options::FVarLinearInterpolation`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum FvarInterpolation {
    /// `none`: smooth everywhere, fvar boundaries follow the crease rule.
    None,
    /// `corners-only`: as `none`, but values at fvar corners stay.
    CornersOnly,
    /// `corners-plus1`: as `corners-only`, plus corners where more than two values meet.
    CornersPlus1,
    /// `corners-plus2`: as `corners-plus1`, plus the values of darts (seams ending inside).
    CornersPlus2,
    /// `boundaries`: every value on an fvar boundary or seam stays; seam edges are linear.
    Boundaries,
    /// `all`: linear everywhere (bilinear on quads). OpenSubdiv's default and fairsub's.
    All,
}

/// A set of named alternatives: the names are OpenSubdiv's (as the command line spells them).
pub trait Named: Sized + Copy + 'static {
    /// Every value, in OpenSubdiv's order.
    const ALL: &'static [Self];
    /// The name.
    fn name(self) -> &'static str;
    /// The value of a name.
    fn parse(s: &str) -> Option<Self> {
        Self::ALL.iter().copied().find(|v| v.name() == s)
    }
    /// `a | b | c`, for messages.
    fn choices() -> String {
        Self::ALL
            .iter()
            .map(|v| v.name())
            .collect::<Vec<_>>()
            .join(" | ")
    }
}

impl Named for BoundaryInterpolation {
    const ALL: &'static [Self] = &[Self::None, Self::EdgeOnly, Self::EdgeAndCorner];
    fn name(self) -> &'static str {
        match self {
            Self::None => "none",
            Self::EdgeOnly => "edge-only",
            Self::EdgeAndCorner => "edge-and-corner",
        }
    }
}

impl Named for CreaseMethod {
    const ALL: &'static [Self] = &[Self::Uniform, Self::Chaikin];
    fn name(self) -> &'static str {
        match self {
            Self::Uniform => "uniform",
            Self::Chaikin => "chaikin",
        }
    }
}

impl Named for TriangleSubdivision {
    const ALL: &'static [Self] = &[Self::Catmark, Self::Smooth];
    fn name(self) -> &'static str {
        match self {
            Self::Catmark => "catmark",
            Self::Smooth => "smooth",
        }
    }
}

impl Named for FvarInterpolation {
    const ALL: &'static [Self] = &[
        Self::None,
        Self::CornersOnly,
        Self::CornersPlus1,
        Self::CornersPlus2,
        Self::Boundaries,
        Self::All,
    ];
    fn name(self) -> &'static str {
        match self {
            Self::None => "none",
            Self::CornersOnly => "corners-only",
            Self::CornersPlus1 => "corners-plus1",
            Self::CornersPlus2 => "corners-plus2",
            Self::Boundaries => "boundaries",
            Self::All => "all",
        }
    }
}

macro_rules! display_named {
    ($($t:ty),*) => {$(
        impl fmt::Display for $t {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str(self.name())
            }
        }
    )*};
}
display_named!(
    BoundaryInterpolation,
    CreaseMethod,
    TriangleSubdivision,
    FvarInterpolation
);

/// Subdivision options as one source gives them (tags of a file, or the command line); an
/// option left `None` falls to the next source ([`SubdOptions::or`]) and finally to the
/// default (edge-and-corner, uniform, catmark, fvar all).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash)]
pub struct SubdOptions {
    /// Boundary interpolation.
    pub boundary: Option<BoundaryInterpolation>,
    /// Crease method.
    pub crease_method: Option<CreaseMethod>,
    /// Triangle subdivision (Catmull-Clark).
    pub triangles: Option<TriangleSubdivision>,
    /// Face-varying interpolation.
    pub fvar: Option<FvarInterpolation>,
}

impl SubdOptions {
    /// These options, with `fallback`'s where these say nothing.
    pub fn or(self, fallback: SubdOptions) -> SubdOptions {
        SubdOptions {
            boundary: self.boundary.or(fallback.boundary),
            crease_method: self.crease_method.or(fallback.crease_method),
            triangles: self.triangles.or(fallback.triangles),
            fvar: self.fvar.or(fallback.fvar),
        }
    }

    /// The boundary interpolation (default edge-and-corner).
    pub fn boundary(&self) -> BoundaryInterpolation {
        self.boundary
            .unwrap_or(BoundaryInterpolation::EdgeAndCorner)
    }

    /// The crease method (default uniform).
    pub fn crease_method(&self) -> CreaseMethod {
        self.crease_method.unwrap_or(CreaseMethod::Uniform)
    }

    /// The triangle subdivision (default catmark).
    pub fn triangles(&self) -> TriangleSubdivision {
        self.triangles.unwrap_or(TriangleSubdivision::Catmark)
    }

    /// The face-varying interpolation (default all).
    pub fn fvar(&self) -> FvarInterpolation {
        self.fvar.unwrap_or(FvarInterpolation::All)
    }

    /// Whether nothing is set.
    pub fn is_empty(&self) -> bool {
        *self == SubdOptions::default()
    }
}

/// A crease tag: the edge between two vertices (file numbering, from 0) and its sharpness.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CreaseTag {
    /// One end.
    pub a: u32,
    /// The other end.
    pub b: u32,
    /// Sharpness (0 smooth, 10 or more infinitely sharp; negative values were read as 0).
    pub sharpness: f32,
    /// Where the tag was written (1-based line; 0 when not known).
    pub line: usize,
}

/// A corner tag: a vertex (file numbering) and its sharpness.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CornerTag {
    /// The vertex.
    pub vertex: u32,
    /// Sharpness.
    pub sharpness: f32,
    /// Where the tag was written.
    pub line: usize,
}

/// A hole tag: a face (file numbering).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct HoleTag {
    /// The face.
    pub face: u32,
    /// Where the tag was written.
    pub line: usize,
}

/// The tags of a file (see the module documentation).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Tags {
    /// Crease tags.
    pub creases: Vec<CreaseTag>,
    /// Corner tags.
    pub corners: Vec<CornerTag>,
    /// Hole tags.
    pub holes: Vec<HoleTag>,
    /// The options the file asks for.
    pub options: SubdOptions,
    /// The first line of a tag that names elements (for messages about schemes without sharp
    /// features), 0 when there is none.
    pub first_line: usize,
}

impl Tags {
    /// Whether the tags name elements (creases, corners or holes).
    pub fn has_elements(&self) -> bool {
        !(self.creases.is_empty() && self.corners.is_empty() && self.holes.is_empty())
    }

    /// Whether there is nothing at all.
    pub fn is_empty(&self) -> bool {
        !self.has_elements() && self.options.is_empty()
    }

    /// Remembers the line of an element tag (the first one is kept).
    pub fn note_line(&mut self, line: usize) {
        if self.first_line == 0 {
            self.first_line = line;
        }
    }
}

/// Reads a sharpness value as OpenSubdiv stores it: single precision, negative values as 0.
pub fn sharpness_value(x: f64) -> f32 {
    (x.max(0.0)) as f32
}
