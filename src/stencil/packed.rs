//! The packed stencil table: a table re-laid for fast repeated application (animation).

use super::table::apply_in_blocks;
use super::*;

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
