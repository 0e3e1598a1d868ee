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

/// Sorts `(source, weight)` pairs by source (stable: duplicates are summed in the order they were
/// added), merges duplicates and drops exact zeros, in place.
fn merge_pairs(pairs: &mut Vec<(u32, f64)>) {
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

/// A table of stencils in compressed-row form: row `r` maps the `num_sources` old points to new
/// point `r`.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct StencilTable {
    num_sources: usize,
    offsets: Vec<u32>,
    indices: Vec<u32>,
    weights: Vec<f64>,
}

/// Rows per parallel task when applying a table.
const PAR_CHUNK: usize = 2048;

/// The driver both table kinds share: checks the buffer sizes against a table of `num_rows`
/// rows over `num_sources` points, then runs `rows(r0, chunk)` on the output, in parallel blocks
/// of [`PAR_CHUNK`] rows when the table is large (each row is written by one block only, so the
/// result does not depend on the thread count).
///
/// # Panics
/// Panics when the buffer sizes do not match the table.
fn apply_in_blocks<const D: usize>(
    num_sources: usize,
    num_rows: usize,
    src: &[[f64; D]],
    out: &mut [[f64; D]],
    rows: impl Fn(usize, &mut [[f64; D]]) + Sync,
) {
    assert!(
        src.len() >= num_sources,
        "source has {} points, table needs {}",
        src.len(),
        num_sources
    );
    assert_eq!(out.len(), num_rows);
    if out.len() >= 2 * PAR_CHUNK {
        out.par_chunks_mut(PAR_CHUNK)
            .enumerate()
            .for_each(|(c, chunk)| rows(c * PAR_CHUNK, chunk));
    } else {
        rows(0, out);
    }
}

/// Rows per parallel task when building a table.
const BUILD_BLOCK: usize = 4096;

impl StencilTable {
    /// An empty table over `num_sources` source points.
    pub fn new(num_sources: usize) -> Self {
        StencilTable {
            num_sources,
            offsets: vec![0],
            indices: Vec::new(),
            weights: Vec::new(),
        }
    }

    /// An empty table with room for `rows` rows of about `per_row` entries.
    pub fn with_capacity(num_sources: usize, rows: usize, per_row: usize) -> Self {
        let mut offsets = Vec::with_capacity(rows + 1);
        offsets.push(0);
        StencilTable {
            num_sources,
            offsets,
            indices: Vec::with_capacity(rows * per_row),
            weights: Vec::with_capacity(rows * per_row),
        }
    }

    /// Builds a table of `rows` rows over `num_sources` sources in parallel: `fill(range, table)`
    /// appends the rows of `range`, in order, to an empty `table` (one call per block of rows,
    /// each on its own table); the blocks are then joined. `per_row` is the expected number of
    /// entries per row (a capacity hint).
    ///
    /// # Panics
    /// Panics when `fill` appends a different number of rows than asked, or when the table would
    /// have more than `u32::MAX` entries.
    pub fn build_par<F>(num_sources: usize, rows: usize, per_row: usize, fill: F) -> StencilTable
    where
        F: Fn(Range<usize>, &mut StencilTable) + Sync,
    {
        let blocks: Vec<StencilTable> = (0..rows.div_ceil(BUILD_BLOCK))
            .into_par_iter()
            .map(|b| {
                let range = b * BUILD_BLOCK..((b + 1) * BUILD_BLOCK).min(rows);
                let mut t = StencilTable::with_capacity(num_sources, range.len(), per_row);
                fill(range.clone(), &mut t);
                assert_eq!(t.num_rows(), range.len(), "a block filled the wrong rows");
                t
            })
            .collect();
        Self::concat(num_sources, rows, blocks)
    }

    /// Joins tables over the same sources, row after row, freeing each block once copied.
    fn concat(num_sources: usize, rows: usize, blocks: Vec<StencilTable>) -> StencilTable {
        let entries: usize = blocks.iter().map(|b| b.num_entries()).sum();
        assert!(
            entries <= u32::MAX as usize,
            "a stencil table with {entries} entries exceeds 32-bit offsets"
        );
        let mut t = StencilTable::with_capacity(num_sources, rows, 0);
        t.indices.reserve_exact(entries);
        t.weights.reserve_exact(entries);
        for b in blocks {
            let base = t.indices.len() as u32;
            t.offsets.extend(b.offsets[1..].iter().map(|&o| o + base));
            t.indices.extend_from_slice(&b.indices);
            t.weights.extend_from_slice(&b.weights);
        }
        t
    }

    /// The identity map on `n` points.
    pub fn identity(n: usize) -> Self {
        let mut t = StencilTable::with_capacity(n, n, 1);
        for i in 0..n {
            t.push_pairs(&[(i as u32, 1.0)]);
        }
        t
    }

    /// Builds a table from a dense row-major matrix (`rows x cols`); zeros are skipped.
    pub fn from_dense(rows: usize, cols: usize, data: &[f64]) -> Self {
        let mut t = StencilTable::with_capacity(cols, rows, 8);
        for r in 0..rows {
            let row = &data[r * cols..(r + 1) * cols];
            for (c, &w) in row.iter().enumerate() {
                if w != 0.0 {
                    t.indices.push(c as u32);
                    t.weights.push(w);
                }
            }
            t.offsets.push(t.indices.len() as u32);
        }
        t
    }

    /// Appends a row given as merged `(source, weight)` pairs.
    ///
    /// # Panics
    /// Panics if a source index is out of range (a programming error in a scheme).
    pub fn push_pairs(&mut self, pairs: &[(u32, f64)]) {
        for &(i, w) in pairs {
            assert!(
                (i as usize) < self.num_sources,
                "stencil source {i} out of range {}",
                self.num_sources
            );
            self.indices.push(i);
            self.weights.push(w);
        }
        self.offsets.push(self.indices.len() as u32);
    }

    /// Appends a row (merging duplicate sources first).
    pub fn push(&mut self, s: Stencil) {
        let s = s.merged();
        self.push_pairs(&s.entries);
    }

    /// Appends all rows of another table over the same sources.
    pub fn extend_rows(&mut self, other: &StencilTable) {
        assert_eq!(self.num_sources, other.num_sources);
        for r in 0..other.num_rows() {
            let (i, w) = other.row(r);
            self.indices.extend_from_slice(i);
            self.weights.extend_from_slice(w);
            self.offsets.push(self.indices.len() as u32);
        }
    }

    /// Number of rows (new points).
    pub fn num_rows(&self) -> usize {
        self.offsets.len() - 1
    }

    /// Number of source points.
    pub fn num_sources(&self) -> usize {
        self.num_sources
    }

    /// Total number of non-zero weights.
    pub fn num_entries(&self) -> usize {
        self.indices.len()
    }

    /// Row `r` as `(sources, weights)`.
    pub fn row(&self, r: usize) -> (&[u32], &[f64]) {
        let (a, b) = (self.offsets[r] as usize, self.offsets[r + 1] as usize);
        (&self.indices[a..b], &self.weights[a..b])
    }

    /// Row `r` as a [`Stencil`].
    pub fn stencil(&self, r: usize) -> Stencil {
        let (i, w) = self.row(r);
        Stencil {
            entries: i.iter().copied().zip(w.iter().copied()).collect(),
        }
    }

    /// Largest deviation of a row sum from 1 (0 for an affine table).
    pub fn max_affine_defect(&self) -> f64 {
        (0..self.num_rows())
            .map(|r| (self.row(r).1.iter().sum::<f64>() - 1.0).abs())
            .fold(0.0, f64::max)
    }

    /// Applies the table to point data: `out[r] = sum_k w_rk * src[i_rk]`.
    pub fn apply<const D: usize>(&self, src: &[[f64; D]]) -> Vec<[f64; D]> {
        let mut out = vec![[0.0; D]; self.num_rows()];
        self.apply_into(src, &mut out);
        out
    }

    /// Applies the table into an existing buffer of `num_rows` points (no allocation). Runs in
    /// parallel over blocks of rows on large tables.
    ///
    /// # Panics
    /// Panics when the buffer sizes do not match the table.
    pub fn apply_into<const D: usize>(&self, src: &[[f64; D]], out: &mut [[f64; D]]) {
        apply_in_blocks(self.num_sources, self.num_rows(), src, out, |r0, chunk| {
            self.apply_rows(src, r0, chunk)
        });
    }

    /// The kernel: rows `r0..r0 + out.len()` into `out`, one pass over their entries.
    #[inline]
    fn apply_rows<const D: usize>(&self, src: &[[f64; D]], r0: usize, out: &mut [[f64; D]]) {
        let offsets = &self.offsets[r0..=r0 + out.len()];
        let (first, last) = (offsets[0] as usize, offsets[out.len()] as usize);
        let mut idx = &self.indices[first..last];
        let mut wts = &self.weights[first..last];
        for (o, pair) in out.iter_mut().zip(offsets.windows(2)) {
            let n = (pair[1] - pair[0]) as usize;
            let (ri, rest_i) = idx.split_at(n);
            let (rw, rest_w) = wts.split_at(n);
            let mut acc = [0.0; D];
            for (&i, &w) in ri.iter().zip(rw) {
                axpy(&mut acc, w, &src[i as usize]);
            }
            *o = acc;
            idx = rest_i;
            wts = rest_w;
        }
    }

    /// Composition `self ∘ inner`: applying the result equals applying `inner`, then `self`.
    ///
    /// # Panics
    /// Panics when `self.num_sources() != inner.num_rows()`.
    pub fn compose(&self, inner: &StencilTable) -> StencilTable {
        assert_eq!(
            self.num_sources,
            inner.num_rows(),
            "composition size mismatch"
        );
        StencilTable::build_par(inner.num_sources, self.num_rows(), 16, |range, t| {
            let mut acc: Vec<(u32, f64)> = Vec::new();
            for r in range {
                let (idx, w) = self.row(r);
                for (&i, &wi) in idx.iter().zip(w) {
                    let (jdx, wj) = inner.row(i as usize);
                    acc.extend(jdx.iter().zip(wj).map(|(&j, &w2)| (j, wi * w2)));
                }
                merge_pairs(&mut acc);
                t.push_pairs(&acc);
                acc.clear();
            }
        })
    }

    /// The sub-table of the given rows, in that order.
    pub fn select_rows(&self, rows: &[usize]) -> StencilTable {
        let mut t = StencilTable::with_capacity(self.num_sources, rows.len(), 8);
        for &r in rows {
            let (i, w) = self.row(r);
            t.indices.extend_from_slice(i);
            t.weights.extend_from_slice(w);
            t.offsets.push(t.indices.len() as u32);
        }
        t
    }

    /// Re-expresses the table over a subset of its sources: `sources[k]` becomes source `k`.
    /// Returns `None` when a row uses a source that is not in the list.
    pub fn restrict_sources(&self, sources: &[usize]) -> Option<StencilTable> {
        let mut map = vec![u32::MAX; self.num_sources];
        for (k, &s) in sources.iter().enumerate() {
            map[s] = k as u32;
        }
        let mut t = StencilTable::with_capacity(sources.len(), self.num_rows(), 8);
        for r in 0..self.num_rows() {
            let (i, w) = self.row(r);
            for (&s, &ws) in i.iter().zip(w) {
                let k = map[s as usize];
                if k == u32::MAX {
                    return None;
                }
                t.indices.push(k);
                t.weights.push(ws);
            }
            t.offsets.push(t.indices.len() as u32);
        }
        Some(t)
    }

    /// Dense row-major copy (`num_rows x num_sources`), for analysis of small local matrices.
    pub fn to_dense(&self) -> Vec<f64> {
        let mut m = vec![0.0; self.num_rows() * self.num_sources];
        for r in 0..self.num_rows() {
            let (i, w) = self.row(r);
            for (&c, &x) in i.iter().zip(w) {
                m[r * self.num_sources + c as usize] += x;
            }
        }
        m
    }

    /// Bytes held by the table (for memory reports).
    pub fn heap_bytes(&self) -> usize {
        self.offsets.capacity() * 4 + self.indices.capacity() * 4 + self.weights.capacity() * 8
    }
}

/// A stencil table packed for repeated application (animation: the topology stays, the points
/// move every frame): the rows of a [`StencilTable`] with every distinct weight vector stored
/// once.
///
/// Applying a table is bound by memory traffic: 12 bytes per entry (index and weight) against
/// one multiply-add. The rows of a refined net repeat a few weight vectors (every regular
/// neighbourhood of one level has the same stencil), so the packed form reads about 4 bytes
/// per entry plus a small, cache-resident dictionary of weights. A row's weights are reused
/// only when they are bitwise equal, so [`PackedStencilTable::apply_into`] gives exactly the
/// bits of [`StencilTable::apply_into`].
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PackedStencilTable {
    num_sources: usize,
    /// Row `r`'s sources are `indices[offsets[r]..offsets[r + 1]]`.
    offsets: Vec<u32>,
    indices: Vec<u32>,
    /// Row `r`'s weights are `weights[weight_start[r]..]`, as many as its sources.
    weight_start: Vec<u32>,
    weights: Vec<f64>,
}

impl PackedStencilTable {
    /// Packs a table (one pass over its rows, hashing each weight vector).
    pub fn new(table: &StencilTable) -> Self {
        use std::collections::HashMap;
        let rows = table.num_rows();
        let mut first: HashMap<u64, u32> = HashMap::new();
        let mut weights: Vec<f64> = Vec::new();
        let mut weight_start = Vec::with_capacity(rows);
        for r in 0..rows {
            let w = table.row(r).1;
            // FNV-style mix of the weights' bits and the length.
            let h = w
                .iter()
                .fold(0xcbf2_9ce4_8422_2325 ^ w.len() as u64, |h, x| {
                    (h ^ x.to_bits()).wrapping_mul(0x0000_0100_0000_01b3)
                });
            let same = |s: u32| {
                let s = s as usize;
                weights
                    .get(s..s + w.len())
                    .is_some_and(|d| d.iter().zip(w).all(|(a, b)| a.to_bits() == b.to_bits()))
            };
            let start = match first.get(&h) {
                Some(&s) if same(s) => s,
                found => {
                    let s = weights.len() as u32;
                    weights.extend_from_slice(w);
                    if found.is_none() {
                        first.insert(h, s);
                    }
                    s
                }
            };
            weight_start.push(start);
        }
        assert!(
            weights.len() <= u32::MAX as usize,
            "packed weights exceed 32-bit offsets"
        );
        weights.shrink_to_fit();
        PackedStencilTable {
            num_sources: table.num_sources,
            offsets: table.offsets.clone(),
            indices: table.indices.clone(),
            weight_start,
            weights,
        }
    }

    /// Number of rows (new points).
    pub fn num_rows(&self) -> usize {
        self.offsets.len() - 1
    }

    /// Number of distinct weights stored (against [`StencilTable::num_entries`]).
    pub fn num_stored_weights(&self) -> usize {
        self.weights.len()
    }

    /// Bytes held by the packed table.
    pub fn heap_bytes(&self) -> usize {
        4 * (self.offsets.len() + self.indices.len() + self.weight_start.len())
            + 8 * self.weights.len()
    }

    /// Applies the table into an existing buffer of `num_rows` points (no allocation), in
    /// parallel over blocks of rows on large tables; the result equals
    /// [`StencilTable::apply_into`] bit for bit.
    ///
    /// # Panics
    /// Panics when the buffer sizes do not match the table.
    pub fn apply_into<const D: usize>(&self, src: &[[f64; D]], out: &mut [[f64; D]]) {
        apply_in_blocks(self.num_sources, self.num_rows(), src, out, |r0, chunk| {
            self.apply_rows(src, r0, chunk)
        });
    }

    /// The kernel: rows `r0..r0 + out.len()` into `out`.
    #[inline]
    fn apply_rows<const D: usize>(&self, src: &[[f64; D]], r0: usize, out: &mut [[f64; D]]) {
        let offsets = &self.offsets[r0..=r0 + out.len()];
        let starts = &self.weight_start[r0..r0 + out.len()];
        for ((o, pair), &ws) in out.iter_mut().zip(offsets.windows(2)).zip(starts) {
            let ri = &self.indices[pair[0] as usize..pair[1] as usize];
            let rw = &self.weights[ws as usize..ws as usize + ri.len()];
            let mut acc = [0.0; D];
            for (&i, &w) in ri.iter().zip(rw) {
                axpy(&mut acc, w, &src[i as usize]);
            }
            *o = acc;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn apply_and_compose() {
        let mut a = StencilTable::new(3);
        a.push(Stencil::from_pairs([(0, 0.5), (1, 0.5)]));
        a.push(Stencil::from_pairs([(1, 0.5), (2, 0.5)]));
        let mut b = StencilTable::new(2);
        b.push(Stencil::from_pairs([(0, 0.5), (1, 0.5)]));
        let src = [[0.0, 0.0], [2.0, 4.0], [4.0, 0.0]];
        let ab = b.compose(&a);
        assert_eq!(ab.apply(&src), b.apply(&a.apply(&src)));
        assert_eq!(ab.apply(&src)[0], [2.0, 2.0]);
        assert_eq!(ab.max_affine_defect(), 0.0);
        let sub = a.restrict_sources(&[0, 1]).map(|t| t.num_rows());
        assert_eq!(sub, None);
        let s = Stencil::from_pairs([(2, 1.0), (0, 0.25), (2, -1.0), (0, 0.75)]);
        assert_eq!(s.entries(), &[(0, 1.0)]);
    }

    #[test]
    fn packed_tables_share_weights_and_give_the_same_bits() {
        // Rows 0..n repeat one weight vector, except row 5 (its own weights).
        let n = 10_000;
        let mut t = StencilTable::new(n);
        for r in 0..n {
            let w = if r == 5 { 0.5 } else { 0.25 };
            t.push(Stencil::from_pairs([(r, w), ((r + 1) % n, 1.0 - w)]));
        }
        let p = PackedStencilTable::new(&t);
        // The wrap-around row sorts its sources the other way: a third weight vector.
        assert_eq!(p.num_stored_weights(), 6);
        let src: Vec<[f64; 2]> = (0..n).map(|i| [i as f64, (i * i) as f64 * 0.1]).collect();
        let mut a = vec![[0.0; 2]; n];
        let mut b = vec![[0.0; 2]; n];
        t.apply_into(&src, &mut a);
        p.apply_into(&src, &mut b);
        assert_eq!(a, b);
    }

    #[test]
    fn parallel_apply_matches_serial() {
        let n = 10_000;
        let mut t = StencilTable::new(n);
        for r in 0..n {
            t.push(Stencil::from_pairs([(r, 0.25), ((r + 1) % n, 0.75)]));
        }
        let src: Vec<[f64; 1]> = (0..n).map(|i| [i as f64]).collect();
        let out = t.apply(&src);
        for (r, o) in out.iter().enumerate() {
            assert_eq!(o[0], 0.25 * r as f64 + 0.75 * ((r + 1) % n) as f64);
        }
    }
}
