//! The stencil table: compressed rows of stencils, built in parallel, applied to any per-point
//! data, composed and restricted (the form every scheme's rules take).

use super::*;

/// A table of stencils in compressed-row form: row `r` maps the `num_sources` old points to new
/// point `r`.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct StencilTable {
    pub(super) num_sources: usize,
    pub(super) offsets: Vec<u32>,
    pub(super) indices: Vec<u32>,
    pub(super) weights: Vec<f64>,
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
pub(super) fn apply_in_blocks<const D: usize>(
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

    /// Makes room for `rows` more rows of `entries` entries in all (a construction that knows
    /// its size saves the copies of growing by doubling).
    pub fn reserve(&mut self, rows: usize, entries: usize) {
        self.offsets.reserve(rows);
        self.indices.reserve(entries);
        self.weights.reserve(entries);
    }

    /// Appends one row per source in `sources`, each the source alone with weight 1 (a gather:
    /// the same rows as [`StencilTable::push_pairs`] of `[(i, 1.0)]`, without the buffer).
    ///
    /// # Panics
    /// When a source is out of range.
    pub fn push_points(&mut self, sources: impl ExactSizeIterator<Item = u32>) {
        self.indices.reserve(sources.len());
        self.weights.reserve(sources.len());
        self.offsets.reserve(sources.len());
        for i in sources {
            assert!(
                (i as usize) < self.num_sources,
                "stencil source {i} out of range {}",
                self.num_sources
            );
            self.indices.push(i);
            self.weights.push(1.0);
            self.offsets.push(self.indices.len() as u32);
        }
    }

    /// Appends a row (merging duplicate sources first).
    pub fn push(&mut self, s: Stencil) {
        let s = s.merged();
        self.push_pairs(&s.entries);
    }

    /// The table of `rows` over `num_sources` points (rows of about `per_row` entries).
    pub fn from_rows(
        num_sources: usize,
        rows: impl IntoIterator<Item = Stencil>,
        per_row: usize,
    ) -> Self {
        let rows = rows.into_iter();
        let mut table = StencilTable::with_capacity(num_sources, rows.size_hint().0, per_row);
        for s in rows {
            table.push(s);
        }
        table
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

    /// Rows `first..first + out.len()` applied into `out`, on this thread (the values
    /// [`StencilTable::apply_into`] gives those rows, bit for bit): a slice of the table for a
    /// caller that runs its own parallel loop.
    ///
    /// # Panics
    /// When the rows are out of range or `src` has fewer points than the table's sources.
    pub fn apply_rows_into<const D: usize>(
        &self,
        src: &[[f64; D]],
        first: usize,
        out: &mut [[f64; D]],
    ) {
        assert!(first + out.len() <= self.num_rows(), "rows out of range");
        assert!(src.len() >= self.num_sources, "too few source points");
        self.apply_rows(src, first, out);
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
