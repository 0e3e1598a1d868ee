//! BezierView `.bv`: the patch format of SurfLab's viewers (writer and reader).
//!
//! # The format, as BezierView reads it
//!
//! Sources: SurfLab's format page (<https://www.cise.ufl.edu/research/SurfLab/bview/#file-format>),
//! `FORMAT.txt` of the BezierView repository (github.com/SurfLab/BezierView, Xiaobin Wu, 2003),
//! and its loader (`src/load.c`: `define_scene`, `get_kind`; `src/QuadBezier.cpp`: `loadFile`,
//! `DeCastel2`, `BBcopy4`; `src/TriBezier.cpp`: `loadFile`, `b2i_i`). The file is read with
//! `fscanf`, so only the order of whitespace-separated tokens matters, not the line breaks.
//!
//! * A file is a sequence of segments; each starts with its type number.
//! * `group <id> <name>` (or `Group`) before a segment makes `<name>` the current group of the
//!   segments that follow. Groups are identified by *name*; `<id>` is the group's colour index.
//!   The rest of the group line is read with `fgets`; ` #k` there sets the group's subdivision
//!   depth. Names are single tokens.
//! * Type `1`, polyhedron: `V F`, then `V` points `x y z`, then `F` faces `n i1 .. in` with
//!   0-based vertex indices (any `n`).
//! * Type `4`, tensor-product patch of equal degrees: `deg`, then `(deg+1)^2` points.
//! * Type `5`, general tensor-product patch: `degu degv`, then `(degu+1)(degv+1)` points in
//!   row-major order of the `(degu+1) x (degv+1)` matrix `p[i][j]`: rows `i` run along `u`,
//!   columns `j` along `v` (`DeCastel2` contracts `j` with `v`, then `i` with `u`). This is
//!   exactly fairsub's [`BezierPatch`](crate::bezier::BezierPatch) layout `cps[i * (deg_v + 1) + j]`, `i` along u, so
//!   coefficients are written and read in storage order with no transposition.
//! * Type `8`, rational tensor-product patch: `degu degv`, points `x y z w` in homogeneous form
//!   (BezierView divides by `w`; weights must be positive). Read as a rational
//!   [`BezierPatch`](crate::bezier::BezierPatch) (its weights kept, its points divided by them),
//!   or as a polynomial patch when all weights are equal. Types 6 (trim curves) and 7 (B-spline
//!   patches) are named in BezierView's sources but not loaded by it; fairsub rejects them as
//!   unknown, naming the line.
//! * Type `3`, triangular (total-degree) patch: `deg`, then `(deg+1)(deg+2)/2` points in
//!   "row-ascending" order: for `deg = 3` the indices are laid out as
//!   ```text
//!         9
//!        7 8
//!       4 5 6
//!      0 1 2 3
//!   ```
//!   i.e. coefficient `b[i][j][k]` (`i + j + k = deg`, barycentric weights `u, v, w`) is point
//!   number `sum_{kk<k} (deg + 1 - kk) + j` (`b2i_i`): rows by `k`, within a row by `j`. See
//!   [`TriPatch::index`].
//! * Types `9` (PN triangle: `deg ndeg`, points, then normal coefficients) and `10` (PN quad:
//!   `degu degv ndegu ndegv`, points, normals) are read as plain patches; the normals are
//!   dropped with a warning.
//!
//! The writer emits `group <id> <name>` whenever the group changes (ids numbered 1.. in order
//! of first appearance, names from [`Provenance::group_name`](crate::surface::Provenance::group_name)), patches as `4 deg` when
//! `deg_u == deg_v` and `5 degu degv` otherwise, one point per line with round-trip precision.
//! The reader is lenient about whitespace and also skips `#` comments (which drops a group's
//! `#k` depth hint, which fairsub does not use); it takes time linear in the size of the file,
//! also with many groups.
//!
//! `write` holds the writer, `read` the reader, `kinds` every kind as tensor-product patches
//! (exact: triangles as collapsed tensor-product patches, polyhedron faces as flat ones), which
//! `check`, `render` and `view` use.

mod kinds;
mod read;
mod write;

pub use kinds::{BvCounts, BvPatches, triangle_as_tensor};

use crate::geom::Point;
use crate::surface::PatchComplex;

pub use read::{parse_bv, read_bv};
pub(crate) use write::check_complex;
pub use write::{bv_mesh_to_string, bv_to_string, write_bv, write_bv_file, write_bv_mesh};

/// Degrees above this are rejected as implausible (protects against garbage input).
const MAX_DEGREE: usize = 64;

/// A triangular (total-degree) Bezier patch in BezierView's coefficient order.
#[derive(Debug, Clone, PartialEq)]
pub struct TriPatch {
    /// Total degree.
    pub deg: usize,
    /// `(deg + 1)(deg + 2) / 2` coefficients; `b[i][j][k]` is at [`TriPatch::index`]`(deg, j, k)`.
    pub cps: Vec<Point>,
}

impl TriPatch {
    /// Position of coefficient `b[deg-j-k][j][k]` in BezierView order:
    /// `sum_{kk<k} (deg + 1 - kk) + j` (rows by `k`, within a row by `j`).
    pub fn index(deg: usize, j: usize, k: usize) -> usize {
        k * (deg + 1) - k * k.saturating_sub(1) / 2 + j
    }

    /// Coefficient `b[i][j][k]` (`i + j + k == deg`).
    pub fn cp(&self, i: usize, j: usize, k: usize) -> Point {
        debug_assert_eq!(i + j + k, self.deg);
        self.cps[Self::index(self.deg, j, k)]
    }

    /// Number of coefficients of a patch of total degree `deg`.
    pub fn count(deg: usize) -> usize {
        (deg + 1) * (deg + 2) / 2
    }
}

/// A group of a `.bv` file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct BvGroup {
    /// The number after `group` (BezierView uses it as the group's colour index).
    pub id: i64,
    /// The group name (identifies the group).
    pub name: String,
}

/// A polyhedron (type 1 segment): vertices and 0-based faces, as in the file.
#[derive(Debug, Clone, PartialEq)]
pub struct BvPolyhedron {
    /// Vertex positions.
    pub positions: Vec<Point>,
    /// Faces as vertex index lists.
    pub faces: Vec<Vec<usize>>,
    /// Index into [`BvFile::groups`] of the group the polyhedron belongs to.
    pub group: Option<usize>,
}

/// The contents of a `.bv` file.
#[derive(Debug, Clone, Default)]
pub struct BvFile {
    /// Groups in order of first appearance.
    pub groups: Vec<BvGroup>,
    /// Tensor-product patches (types 4, 5, 8, 10; rational ones carry their weights), with
    /// [`Provenance::Unknown`](crate::surface::Provenance::Unknown).
    pub patches: PatchComplex,
    /// Group of each tensor-product patch (index into `groups`).
    pub patch_groups: Vec<Option<usize>>,
    /// Triangular patches (types 3, 9).
    pub tri_patches: Vec<TriPatch>,
    /// Group of each triangular patch.
    pub tri_groups: Vec<Option<usize>>,
    /// Polyhedra (type 1).
    pub polyhedra: Vec<BvPolyhedron>,
    /// Notes about what was read but dropped (normals of PN patches) or read differently
    /// (type 8 patches with equal weights read as polynomial ones).
    pub warnings: Vec<String>,
}

#[cfg(feature = "unit-tests")]
mod tests;
