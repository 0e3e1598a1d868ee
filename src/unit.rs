//! The library's unit tests, registered in the library itself (only under the `unit-tests`
//! feature, which the harness in `unit/` turns on; never part of a user's build).
//!
//! A unit test sits beside the code it tests, in a module under
//! `#[cfg(feature = "unit-tests")]`, marked `#[crate::unit::test]` instead of `#[test]`. The
//! attribute (crate `fairsub-unit-macro`) adds the function to [`TESTS`], and `unit/unit.rs` runs
//! that list with libtest's command line (filters, `--ignored`, `--list`). Why not libtest's own
//! `#[cfg(test)]` harness: it is a second compilation of the whole library, which was the
//! largest step of a fresh `cargo test --release` on 2 cores (issue 51); this way the library
//! is compiled once, and the tests run optimised as the library is.

pub use fairsub_unit_macro::test;

/// One unit test: its path below the crate (`bezier::g1::tests::name`), the function, and why it
/// is ignored by default, if it is.
pub struct Test {
    /// `module_path!()` and the function's name.
    pub path: &'static str,
    /// The test; it fails by panicking, as a libtest test does.
    pub run: fn(),
    /// `Some(reason)` for a test marked `#[ignore]` (run with `--ignored`).
    pub ignore: Option<&'static str>,
}

/// Every unit test of the library, gathered at link time.
#[linkme::distributed_slice]
pub static TESTS: [Test];
