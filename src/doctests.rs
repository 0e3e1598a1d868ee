//! The Rust snippets of the README and the user guide as doctests (`cargo test --release` runs
//! them): each page that holds a ```` ```rust ```` block is the documentation of one item here,
//! compiled only by rustdoc's test run (`cfg(doctest)`), so a snippet that stops compiling or
//! fails fails the tests. Every fenced block of a page must carry an info string
//! (`docs/check-links.py` checks it): a bare one would be compiled as Rust.
//!
//! `tests/reference_pages.rs` checks that every page with a Rust block is listed here.

/// README.md
#[doc = include_str!("../README.md")]
pub struct Readme;
