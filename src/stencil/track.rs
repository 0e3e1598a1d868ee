//! Rows tracked beside the points: the weights of a linear step read off the step itself, and
//! rows composed with the rows of the step's inputs.
//!
//! A construction that is linear in its control points (the same weights for every coordinate)
//! can carry, beside each point it computes, the row of weights from the input points: each
//! step's rows are its own weights composed with its inputs' rows. [`linear_weights`] reads a
//! small step's weights off the step's own code (no second copy of its rule), and
//! [`StencilTable::push_combination`] appends a composed row.

use super::{StencilTable, merge_pairs};

/// The weights of a linear map of `m` points to some points (the same weights for x, y and
/// z), read off the map `f` itself: it is applied to unit points, three inputs per call (input
/// `3 c + d` set to the unit vector `e_d`, the others zero), so output `k`'s coordinate `d` is
/// its weight of that input. Returns per output its `(input, weight)` pairs (exact zeros
/// dropped). `f` must be linear (no constant part) and return the same number of points for
/// every call.
pub fn linear_weights(
    m: usize,
    mut f: impl FnMut(&[[f64; 3]]) -> Vec<[f64; 3]>,
) -> Vec<Vec<(u32, f64)>> {
    let mut rows: Vec<Vec<(u32, f64)>> = Vec::new();
    let mut pts = vec![[0.0; 3]; m];
    for c in 0..m.div_ceil(3) {
        for d in 0..3 {
            if let Some(p) = pts.get_mut(3 * c + d) {
                p[d] = 1.0;
            }
        }
        let y = f(&pts);
        rows.resize_with(y.len(), Vec::new);
        for (row, v) in rows.iter_mut().zip(&y) {
            for (d, &w) in v.iter().enumerate() {
                if 3 * c + d < m && w != 0.0 {
                    row.push(((3 * c + d) as u32, w));
                }
            }
        }
        for p in pts.iter_mut().skip(3 * c).take(3) {
            *p = [0.0; 3];
        }
    }
    rows
}

impl StencilTable {
    /// Appends the row `sum w * inner.row(i)` over the terms `(i, w)` (merged, exact zeros
    /// dropped); `scratch` is a reusable buffer.
    ///
    /// # Panics
    /// Panics when a term names a row `inner` does not have, or the tables' sources differ.
    pub fn push_combination(
        &mut self,
        inner: &StencilTable,
        terms: &[(u32, f64)],
        scratch: &mut Vec<(u32, f64)>,
    ) {
        assert_eq!(self.num_sources(), inner.num_sources(), "sources differ");
        scratch.clear();
        for &(i, w) in terms {
            let (idx, wts) = inner.row(i as usize);
            scratch.extend(idx.iter().zip(wts).map(|(&j, &v)| (j, w * v)));
        }
        merge_pairs(scratch);
        self.push_pairs(scratch);
    }
}
