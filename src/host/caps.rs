//! Caps: constructions that replace Catmull-Clark's rings around an extraordinary vertex by a
//! scheme's own rings and fill, built from the vertex's c-net (EG, QAS+, guided subdivision),
//! and the notes a cap scheme leaves for the user where it falls back or substitutes rules.

use super::Fallback;
use crate::bezier::complex::{Domain, PatchComplex};
use crate::error::{Error, Result};
use crate::geom::Point;
use crate::mesh::Element;
use std::sync::Mutex;

/// A scheme that replaces Catmull-Clark's rings around an extraordinary vertex by a cap built
/// from the vertex's c-net (EG, QAS+, guided subdivision). The adaptive loop calls it wherever a
/// vertex has a clean c-net (its one-ring regular) at the current level and every extraordinary
/// vertex of that c-net is capped too; elsewhere it refines with Catmull-Clark first (the local
/// Catmull-Clark step of the EG paper's pseudocode).
pub trait CapBuilder {
    /// Whether vertices of valence `n` get a cap; `Ok(false)` leaves them to Catmull-Clark (the
    /// fallback), an error stops the whole construction (the user asked for no fallback).
    fn accepts(&self, n: usize, element: Element) -> Result<bool>;

    /// Appends the cap of one vertex: `cnet` holds its c-net positions in the order of
    /// [`crate::mesh::PolyMesh::cnet_indices`] with two rings; rings are numbered from `first_ring`.
    /// `sectors[s]` is the input-face domain of sector `s`'s face (the quad between spokes `s`
    /// and `s + 1`), rotated so that the patch frame's `(0, 0)` is the vertex, `u` runs along
    /// spoke `s` and `v` along spoke `s + 1` ([`Domain::UNTRACKED`] where the host does not
    /// track domains); a builder whose patches tile that frame in a known way records their
    /// domains with [`Domain::square`].
    fn build(
        &self,
        cnet: &[Point],
        n: usize,
        element: Element,
        first_ring: u32,
        sectors: &[Domain],
        out: &mut PatchComplex,
    ) -> Result<()>;

    /// Records a note for the user (once), e.g. an element left to Catmull-Clark by the host.
    fn note(&self, msg: String);
}

/// Lower-left corners of the three patches `A`, `B`, `C` of a sector's ring in the ring's
/// chart, in units of half the ring's scale: the L-shaped band `[0, 1]^2 \ [0, 1/2]^2` of the
/// contracting cap schemes (EG's and QAS+'s d-net rings, guided rings; each in its own chart).
pub const RING_CELLS: [(u32, u32); 3] = [(1, 0), (1, 1), (0, 1)];

/// The domain of the dyadic square `(i, j) 2^-level` of sector `s`'s frame
/// ([`CapBuilder::build`]'s `sectors`, [`Domain::square`]); untracked without sector domains.
pub fn sector_square(sectors: &[Domain], s: usize, level: u8, i: u32, j: u32) -> Domain {
    sectors
        .get(s)
        .map_or(Domain::UNTRACKED, |d| d.square(level, i, j))
}

/// How notes and errors name an element that gets a cap: `vertex 3`, `the centre of face 7`.
pub fn describe(e: Element) -> String {
    match e {
        Element::Vertex(v) => format!("vertex {v}"),
        Element::Face(f) => format!("the centre of face {f}"),
    }
}

/// What a cap scheme tells the user, collected while caps are built in parallel: elements
/// that fell back to Catmull-Clark, elements capped by other rules than the scheme's own, and
/// other notes, each recorded once.
#[derive(Debug, Default)]
pub struct CapNotes {
    fell_back: Mutex<Vec<(Element, usize)>>,
    substituted: Mutex<Vec<(Element, usize, String)>>,
    other: Mutex<Vec<String>>,
}

impl CapNotes {
    /// Records that `element` (valence `n`) falls back to Catmull-Clark, or with
    /// [`Fallback::Error`] returns the error `no_rules` describes.
    pub fn fall_back(
        &self,
        fallback: Fallback,
        element: Element,
        n: usize,
        no_rules: impl FnOnce() -> String,
    ) -> Result<()> {
        match fallback {
            Fallback::CatmullClark => {
                let mut fb = self.fell_back.lock().expect("no poisoning");
                if !fb.iter().any(|(e, _)| *e == element) {
                    fb.push((element, n));
                }
                Ok(())
            }
            Fallback::Error => Err(Error::UnsupportedValence {
                valence: n,
                msg: format!("{} has {}", describe(element), no_rules()),
            }),
        }
    }

    /// Records that `element` (valence `n`) is capped by the rules named `rules`.
    pub fn substitute(&self, element: Element, n: usize, rules: &str) {
        let mut sub = self.substituted.lock().expect("no poisoning");
        if !sub.iter().any(|(e, _, _)| *e == element) {
            sub.push((element, n, rules.to_string()));
        }
    }

    /// Records a note (once).
    pub fn note(&self, msg: String) {
        let mut notes = self.other.lock().expect("no poisoning");
        if !notes.contains(&msg) {
            notes.push(msg);
        }
    }

    /// The elements that fell back, and the notes: substitutions, then fallbacks (worded with
    /// the scheme's name `primary`), then the other notes.
    pub fn finish(self, primary: &str) -> (Vec<(Element, usize)>, Vec<String>) {
        let mut notes: Vec<String> = self
            .substituted
            .into_inner()
            .expect("no poisoning")
            .into_iter()
            .map(|(e, n, name)| {
                format!(
                    "{} (valence {n}) has no published {primary} rules: {name} rules there",
                    describe(e)
                )
            })
            .collect();
        let fb = self.fell_back.into_inner().expect("no poisoning");
        for (e, n) in &fb {
            notes.push(format!(
                "{} (valence {n}) has no published {primary} rules: Catmull-Clark rings and fill there",
                describe(*e)
            ));
        }
        notes.extend(self.other.into_inner().expect("no poisoning"));
        (fb, notes)
    }
}
