//! Sparse affine maps (stencils) and the one geometry kernel that applies them.
//!
//! Every scheme in fairsub is linear: each new control point or Bezier coefficient is an affine
//! combination of old points. A scheme writes its rules once as [`Stencil`]s collected in a
//! [`StencilTable`]; refinement, patch output and analysis all apply or compose those same tables.
//! A table can be applied to any per-point data of fixed width (`[f64; D]`: positions, colours,
//! 2D parameters) and re-applied to new positions without rebuilding (animation).
//!
//! Rules are written against the [`Terms`] trait, so one rule function both fills a table row
//! (through a [`RowWriter`]) and evaluates a point directly (through an [`Accumulator`]): the
//! one-shot refinement kernels and the tables share their weights. Tables are stored flat
//! (compressed rows: offsets, source indices, weights), built in parallel blocks
//! ([`StencilTable::build_par`]) and applied in parallel over blocks of rows
//! ([`StencilTable::apply_into`]).

use rayon::prelude::*;
use std::ops::Range;

/// `acc += w * p`, coordinate by coordinate: the one multiply-add of every kernel.
#[inline(always)]
pub(crate) fn axpy<const D: usize>(acc: &mut [f64; D], w: f64, p: &[f64; D]) {
    for (a, x) in acc.iter_mut().zip(p) {
        *a += w * x;
    }
}

/// Receives the terms `w * source i` of one affine rule. Schemes write each rule once against
/// this trait; a [`RowWriter`] turns the terms into a table row, an [`Accumulator`] evaluates
/// them on point data.
pub trait Terms {
    /// Adds `w` times source `i`.
    fn add(&mut self, i: u32, w: f64);
}

/// Evaluates a rule on point data: accumulates `sum w * src[i]` over the terms it receives.
#[derive(Debug, Clone, Copy)]
pub struct Accumulator<'a, const D: usize> {
    src: &'a [[f64; D]],
    acc: [f64; D],
}

impl<'a, const D: usize> Accumulator<'a, D> {
    /// A zero accumulator over the source points `src`.
    #[inline]
    pub fn new(src: &'a [[f64; D]]) -> Self {
        Accumulator { src, acc: [0.0; D] }
    }

    /// The accumulated value.
    #[inline]
    pub fn value(&self) -> [f64; D] {
        self.acc
    }

    /// Adds `w * p` for a point that is not one of the sources (an intermediate result).
    #[inline]
    pub fn add_point(&mut self, p: &[f64; D], w: f64) {
        axpy(&mut self.acc, w, p);
    }
}

impl<const D: usize> Terms for Accumulator<'_, D> {
    #[inline]
    fn add(&mut self, i: u32, w: f64) {
        axpy(&mut self.acc, w, &self.src[i as usize]);
    }
}

impl Terms for Stencil {
    #[inline]
    fn add(&mut self, i: u32, w: f64) {
        self.entries.push((i, w));
    }
}

/// Rows up to this many terms are merged by a linear search for each term's source (fewer
/// operations than sorting them when, as in refinement stencils, they have few sources).
const SHORT_ROW: usize = 48;

/// Sorts `(source, weight)` pairs by source (stable: duplicates are summed in the order they were
/// added), merges duplicates and drops exact zeros, in place.
fn merge_pairs(pairs: &mut Vec<(u32, f64)>) {
    if pairs.len() < 2 {
        // sorted and without duplicates already (the common single-term row)
        pairs.retain(|e| e.1 != 0.0);
        return;
    }
    if pairs.len() <= SHORT_ROW {
        // short rows (a refinement stencil through its face points: a few dozen terms over a
        // dozen sources): each term is added to the first term of its source, in the order
        // the terms came, which is the sum the stable sort below forms (the same bits), then
        // the distinct sources are ordered
        let mut k = 0;
        for r in 0..pairs.len() {
            let (i, w) = pairs[r];
            match pairs[..k].iter().position(|e| e.0 == i) {
                Some(at) => pairs[at].1 += w,
                None => {
                    pairs[k] = (i, w);
                    k += 1;
                }
            }
        }
        pairs.truncate(k);
        pairs.sort_unstable_by_key(|e| e.0);
        pairs.retain(|e| e.1 != 0.0);
        return;
    }
    pairs.sort_by_key(|e| e.0);
    let mut k = 0;
    for r in 0..pairs.len() {
        if k > 0 && pairs[k - 1].0 == pairs[r].0 {
            pairs[k - 1].1 += pairs[r].1;
        } else {
            pairs[k] = pairs[r];
            k += 1;
        }
    }
    pairs.truncate(k);
    pairs.retain(|e| e.1 != 0.0);
}

/// A reusable buffer for one table row: collects terms, then merges duplicate sources (as
/// [`Stencil::merged`] does) and appends the row to a table, without allocating per row.
#[derive(Debug, Clone, Default)]
pub struct RowWriter {
    pairs: Vec<(u32, f64)>,
}

impl RowWriter {
    /// An empty row.
    pub fn new() -> Self {
        RowWriter::default()
    }

    /// Merges the collected terms, appends them to `table` as one row and clears the buffer.
    pub fn push_into(&mut self, table: &mut StencilTable) {
        merge_pairs(&mut self.pairs);
        table.push_pairs(&self.pairs);
        self.pairs.clear();
    }

    /// Takes the collected terms out as a merged [`Stencil`] and clears the buffer.
    pub fn take_stencil(&mut self) -> Stencil {
        merge_pairs(&mut self.pairs);
        let s = Stencil {
            entries: self.pairs.clone(),
        };
        self.pairs.clear();
        s
    }
}

impl Terms for RowWriter {
    #[inline]
    fn add(&mut self, i: u32, w: f64) {
        self.pairs.push((i, w));
    }
}

/// One affine combination: a list of `(source index, weight)` pairs.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Stencil {
    entries: Vec<(u32, f64)>,
}

impl Stencil {
    /// The empty stencil (the zero map).
    pub fn new() -> Self {
        Stencil {
            entries: Vec::new(),
        }
    }

    /// The stencil that copies source `i`.
    pub fn point(i: usize) -> Self {
        Stencil {
            entries: vec![(i as u32, 1.0)],
        }
    }

    /// Builds a stencil from pairs (duplicates are merged).
    pub fn from_pairs(pairs: impl IntoIterator<Item = (usize, f64)>) -> Self {
        let mut s = Stencil::new();
        for (i, w) in pairs {
            s.add(i, w);
        }
        s.merged()
    }

    /// Adds `w` times source `i`.
    pub fn add(&mut self, i: usize, w: f64) -> &mut Self {
        self.entries.push((i as u32, w));
        self
    }

    /// Adds `s` times another stencil.
    pub fn add_scaled(&mut self, other: &Stencil, s: f64) -> &mut Self {
        self.entries
            .extend(other.entries.iter().map(|&(i, w)| (i, w * s)));
        self
    }

    /// Multiplies every weight by `s`.
    pub fn scaled(mut self, s: f64) -> Self {
        for e in &mut self.entries {
            e.1 *= s;
        }
        self
    }

    /// The [merged](Self::merged) combination `sum_k (weights[k] / denominator) terms[k]` of
    /// stencils with integer weights (zero weights skipped), as used by Bezier coefficient
    /// tables with a common denominator.
    pub fn integer_combination(
        terms: &[Stencil],
        weights: impl IntoIterator<Item = u32>,
        denominator: f64,
    ) -> Self {
        let mut s = Stencil::new();
        for (q, wq) in terms.iter().zip(weights) {
            if wq != 0 {
                s.add_scaled(q, wq as f64 / denominator);
            }
        }
        s.merged()
    }

    /// Sorts by source index, merges duplicates (summing them in the order they were added) and
    /// drops exact zeros.
    pub fn merged(mut self) -> Self {
        merge_pairs(&mut self.entries);
        self
    }

    /// The `(source, weight)` pairs.
    pub fn entries(&self) -> &[(u32, f64)] {
        &self.entries
    }

    /// Sum of the weights (1 for an affine combination).
    pub fn weight_sum(&self) -> f64 {
        self.entries.iter().map(|e| e.1).sum()
    }

    /// Applies the stencil to point data.
    pub fn apply<const D: usize>(&self, src: &[[f64; D]]) -> [f64; D] {
        let mut acc = [0.0; D];
        for &(i, w) in &self.entries {
            let p = &src[i as usize];
            for k in 0..D {
                acc[k] += w * p[k];
            }
        }
        acc
    }
}

mod layered;
mod packed;
mod table;
mod track;

pub use layered::LayeredTable;
pub use packed::PackedStencilTable;
pub use table::StencilTable;
pub use track::linear_weights;

#[cfg(feature = "unit-tests")]
mod tests;
