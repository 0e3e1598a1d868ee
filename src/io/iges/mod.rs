//! IGES 5.3 output: one rational B-spline surface entity (type 128) per Bezier patch, and a
//! validating reader for exactly such files.
//!
//! # What is written
//!
//! An IGES file is a sequence of 80-column ASCII records in five sections, each record ending
//! with its section letter (column 73) and its sequence number within the section (74-80):
//!
//! * **Start (S)**: free text (columns 1-72) saying what the file holds.
//! * **Global (G)**: 25 parameters, `,` as parameter and `;` as record delimiter, strings as
//!   Hollerith constants `nH...`: delimiters, product id (the file stem), file name, native system
//!   id `fairsub`, preprocessor version, 32 integer bits, single precision 38 / 6 and double
//!   precision 308 / 15 (max power of ten / significant digits), receiver product id, model
//!   scale 1.0, **unit flag 2 = millimetres** (`2HMM`; fairsub coordinates are unitless, and a
//!   CAD system needs *some* unit, so one model unit is one millimetre), 1 line-weight gradation,
//!   max line width 1.0, generation date `15HYYYYMMDD.HHNNSS` (UTC; `SOURCE_DATE_EPOCH` is
//!   honoured for reproducible output), minimum resolution `1e-6 * max(1, max |coordinate|)`,
//!   max coordinate, author and organisation left empty (their default), **version flag 11
//!   (IGES 5.3)**, drafting standard 0 (none), model date (= generation date). The optional 26th
//!   parameter (application protocol) is omitted. Strings are ASCII, at most 60 characters, and
//!   no parameter is split across records.
//! * **Directory entry (D)**: two records per entity, ten 8-column fields each: entity type
//!   128, pointer to the first parameter record, structure 0, line font 0, level 0, view 0,
//!   transformation 0, label display 0, status `00000000` (visible, independent, geometry,
//!   top-down); then 128, line weight 0, colour 0, parameter record count, form 0, two reserved
//!   blank fields, entity label (the provenance group name, at most 8 characters) and entity
//!   subscript (1-based number of the patch within its group).
//! * **Parameter data (P)**: the entity's free-format parameters in columns 1-64, column 65
//!   blank, the directory entry's sequence number in 66-72.
//! * **Terminate (T)**: one record with the record counts `S0000001G0000003D...P...`.
//!
//! Entity 128 (IGES 5.3 section 4.24) holds `K1, K2` (upper indices of the sums, here the
//! degrees), `M1, M2` (degrees), `PROP1..5` = `0, 0, 1, 0, 0` (open, polynomial, non-periodic),
//! the knots `S(-M1)..S(N1+M1)` and `T(-M2)..T(N2+M2)` (here `0` repeated `deg+1` times, then
//! `1` repeated `deg+1` times: a single Bezier span), the weights `W(0,0), W(1,0), ...` (all 1),
//! the control points `X(0,0), Y(0,0), Z(0,0), X(1,0), ...` and the parameter range `U(0),
//! U(1), V(0), V(1)` = `0, 1, 0, 1`. In both the weights and the control points the *first*
//! index (along u) varies fastest (as in OpenCASCADE's `IGESGeom_ToolBSplineSurface`), so
//! fairsub's `b[i][j]` (stored row-major, `j` fastest) is written in the order `j` outer,
//! `i` inner. Reals are written in shortest round-trip form with a `D` exponent
//! (`-1.25D-3`, `1.0D0`), so coefficients read back bit for bit. A patch of degree 0 in a
//! direction is written degree-raised to 1 (exactly), since CAD systems expect degree >= 1.
//!
//! `write` holds the writer; `read` the reader, which checks the record structure, and
//! `entity` the parameter data and entity 128.

mod entity;
mod read;
mod write;

pub use read::{parse_iges, read_iges};
pub(crate) use write::now_date as file_date;
pub use write::{iges_faces_to_string, iges_to_string, write_iges, write_iges_faces};

#[cfg(feature = "unit-tests")]
mod tests;
