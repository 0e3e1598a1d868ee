//! Sparse affine maps (stencils) and the one geometry kernel that applies them.
//!
//! Every scheme in fairsub is linear: each new control point or Bezier coefficient is an affine
//! combination of old points. A scheme writes its rules once as [`Stencil`]s collected in a
//! [`StencilTable`]; refinement, patch output and analysis all apply or compose those same tables.
//! A table can be applied to any per-point data of fixed width (`[f64; D]`: positions, colours,
//! 2D parameters) and re-applied to new positions without rebuilding (animation).

use rayon::prelude::*;

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

    /// Sorts by source index, merges duplicates and drops exact zeros.
    pub fn merged(mut self) -> Self {
        self.entries.sort_by_key(|e| e.0);
        let mut out: Vec<(u32, f64)> = Vec::with_capacity(self.entries.len());
        for (i, w) in self.entries {
            match out.last_mut() {
                Some(last) if last.0 == i => last.1 += w,
                _ => out.push((i, w)),
            }
        }
        out.retain(|e| e.1 != 0.0);
        Stencil { entries: out }
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
        assert!(
            src.len() >= self.num_sources,
            "source has {} points, table needs {}",
            src.len(),
            self.num_sources
        );
        assert_eq!(out.len(), self.num_rows());
        let kernel = |r0: usize, chunk: &mut [[f64; D]]| {
            for (k, o) in chunk.iter_mut().enumerate() {
                let r = r0 + k;
                let (a, b) = (self.offsets[r] as usize, self.offsets[r + 1] as usize);
                let mut acc = [0.0; D];
                for e in a..b {
                    let w = self.weights[e];
                    let p = &src[self.indices[e] as usize];
                    for d in 0..D {
                        acc[d] += w * p[d];
                    }
                }
                *o = acc;
            }
        };
        if out.len() >= 2 * PAR_CHUNK {
            out.par_chunks_mut(PAR_CHUNK)
                .enumerate()
                .for_each(|(c, chunk)| kernel(c * PAR_CHUNK, chunk));
        } else {
            kernel(0, out);
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
        let rows: Vec<Vec<(u32, f64)>> = (0..self.num_rows())
            .into_par_iter()
            .map(|r| {
                let mut acc: Vec<(u32, f64)> = Vec::new();
                let (idx, w) = self.row(r);
                for (&i, &wi) in idx.iter().zip(w) {
                    let (jdx, wj) = inner.row(i as usize);
                    acc.extend(jdx.iter().zip(wj).map(|(&j, &w2)| (j, wi * w2)));
                }
                Stencil { entries: acc }.merged().entries
            })
            .collect();
        let mut t = StencilTable::with_capacity(inner.num_sources, rows.len(), 16);
        for r in rows {
            t.push_pairs(&r);
        }
        t
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
