//! Rows over a stack of refinement levels (a factored stencil table): the form an adaptive
//! construction's patch table takes when its rows are recorded beside the points without
//! composing them down to the control points.
//!
//! Level 0 is the control points; level `l >= 1` is given by the refinement's own stencil table
//! over level `l - 1`'s points (the table the construction applied to compute the points). The
//! points of all levels are numbered one after the other ("stacked": level `l`'s point `i` is
//! `offset(l) + i`), and the [`LayeredTable`]'s rows are sparse rows over the stacked points
//! (mostly single entries: a patch's B-spline net is a gather of level points). Applying the
//! table refines level by level, then applies the rows; [`LayeredTable::composed`] gives the same
//! map as one table over the control points (each level's rows composed with its parent's), for
//! readers that want one row per output over the control points.
//!
//! Building it costs nothing beyond the construction (the level tables are the ones it applies,
//! the rows are its nets' own stencils with an index shift), where composing every level's rows
//! down to the control points cost a sparse product per level and per patch.

use super::StencilTable;

/// Rows over the stacked points of a stack of refinement levels (see the module
/// documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct LayeredTable {
    /// Number of control points (level 0).
    num_sources: usize,
    /// Level `l + 1`'s points over level `l`'s points.
    levels: Vec<StencilTable>,
    /// The rows over the stacked points.
    rows: StencilTable,
    /// The stacked index of each level's first point, and the total at the end.
    offsets: Vec<u32>,
}

impl LayeredTable {
    /// No levels yet and no rows, over `n` control points.
    pub fn new(n: usize) -> LayeredTable {
        LayeredTable {
            num_sources: n,
            levels: Vec::new(),
            rows: StencilTable::new(n),
            offsets: vec![0, n as u32],
        }
    }

    /// Adds the next level, given by `step` over the points of the last level, and returns the
    /// stacked index of its first point. Rows pushed from now on may name its points.
    ///
    /// # Panics
    /// When `step` is not over the last level's points, or the stack would exceed `u32` indices.
    pub fn push_level(&mut self, step: StencilTable) -> u32 {
        let last = self.offsets[self.offsets.len() - 1];
        let first = self.offsets[self.offsets.len() - 2];
        assert_eq!(step.num_sources(), (last - first) as usize, "level sizes");
        let total = last as u64 + step.num_rows() as u64;
        assert!(total <= u32::MAX as u64, "{total} stacked points");
        self.offsets.push(total as u32);
        self.levels.push(step);
        self.rows.num_sources = total as usize;
        last
    }

    /// The stacked index of the first point of the last level.
    pub fn last_level_offset(&self) -> u32 {
        self.offsets[self.offsets.len() - 2]
    }

    /// Appends a row over the points of the last level (`(point, weight)` pairs, shifted by
    /// the last level's offset; duplicates merged, exact zeros dropped). `pairs` is left empty.
    pub fn push_level_row(&mut self, pairs: &mut Vec<(u32, f64)>) {
        let shift = self.last_level_offset();
        pairs.iter_mut().for_each(|p| p.0 += shift);
        self.push_row(pairs);
    }

    /// Appends one row per point of `points` (indices over the last level), each that point
    /// alone with weight 1: the rows [`LayeredTable::push_level_row`] appends for `[(i, 1.0)]`.
    pub fn push_level_points(&mut self, points: &[u32]) {
        let shift = self.last_level_offset();
        self.rows.push_points(points.iter().map(|&i| i + shift));
    }

    /// Makes room for `rows` more rows of `entries` entries in all.
    pub fn reserve_rows(&mut self, rows: usize, entries: usize) {
        self.rows.reserve(rows, entries);
    }

    /// Appends a row over the stacked points (duplicates merged, exact zeros dropped). `pairs`
    /// is left empty.
    ///
    /// # Panics
    /// When a pair names a point beyond the stack.
    pub fn push_row(&mut self, pairs: &mut Vec<(u32, f64)>) {
        super::merge_pairs(pairs);
        self.rows.push_pairs(pairs);
        pairs.clear();
    }

    /// Number of control points.
    pub fn num_sources(&self) -> usize {
        self.num_sources
    }

    /// Number of rows.
    pub fn num_rows(&self) -> usize {
        self.rows.num_rows()
    }

    /// Number of stacked points (control points and every level's points).
    pub fn num_points(&self) -> usize {
        self.offsets[self.offsets.len() - 1] as usize
    }

    /// Number of refinement levels.
    pub fn num_levels(&self) -> usize {
        self.levels.len()
    }

    /// Weights of the level tables and of the rows.
    pub fn num_entries(&self) -> (usize, usize) {
        let levels = self.levels.iter().map(|t| t.num_entries()).sum();
        (levels, self.rows.num_entries())
    }

    /// The rows over the stacked points.
    pub fn rows(&self) -> &StencilTable {
        &self.rows
    }

    /// Bytes held.
    pub fn heap_bytes(&self) -> usize {
        self.levels.iter().map(|t| t.heap_bytes()).sum::<usize>() + self.rows.heap_bytes()
    }

    /// The stacked points of the control points `src` (one per control point): `src`, then
    /// every level refined from the one before (each in parallel blocks of rows).
    ///
    /// # Panics
    /// When `src` does not have one point per control point.
    pub fn stack<const D: usize>(&self, src: &[[f64; D]]) -> Vec<[f64; D]> {
        assert_eq!(src.len(), self.num_sources, "one point per control point");
        let mut all = vec![[0.0; D]; self.num_points()];
        all[..src.len()].copy_from_slice(src);
        for (l, step) in self.levels.iter().enumerate() {
            let (a, b, c) = (
                self.offsets[l] as usize,
                self.offsets[l + 1] as usize,
                self.offsets[l + 2] as usize,
            );
            let (done, rest) = all.split_at_mut(b);
            step.apply_into(&done[a..b], &mut rest[..c - b]);
        }
        all
    }

    /// The rows applied to the control points `src`.
    ///
    /// # Panics
    /// When `src` does not have one point per control point.
    pub fn apply<const D: usize>(&self, src: &[[f64; D]]) -> Vec<[f64; D]> {
        self.rows.apply(&self.stack(src))
    }

    /// Every stacked point's row over the control points: the identity for level 0, each
    /// level's table composed with its parent level's rows.
    pub fn stacked_rows(&self) -> StencilTable {
        let mut all = StencilTable::identity(self.num_sources);
        let mut parent = StencilTable::identity(self.num_sources);
        for step in &self.levels {
            parent = step.compose(&parent);
            all.extend_rows(&parent);
        }
        all
    }

    /// The same map as one table over the control points (rows in order).
    pub fn composed(&self) -> StencilTable {
        self.rows.compose(&self.stacked_rows())
    }
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    #[crate::unit::test]
    fn stacked_apply_equals_composed_table() {
        // 3 control points, a level of 2 midpoints, a level of 1 midpoint of those
        let mut t = LayeredTable::new(3);
        let mut s1 = StencilTable::new(3);
        s1.push_pairs(&[(0, 0.5), (1, 0.5)]);
        s1.push_pairs(&[(1, 0.5), (2, 0.5)]);
        assert_eq!(t.push_level(s1), 3);
        t.push_level_row(&mut vec![(1, 2.0)]);
        let mut s2 = StencilTable::new(2);
        s2.push_pairs(&[(0, 0.25), (1, 0.75)]);
        assert_eq!(t.push_level(s2), 5);
        t.push_level_row(&mut vec![(0, 0.5), (0, 0.5)]);
        t.push_row(&mut vec![(4, -1.0), (0, 1.0)]);
        let src = [[1.0], [3.0], [7.0]];
        let direct = t.apply(&src);
        // level 1: 2, 5; level 2: 0.5 + 3.75 = 4.25
        assert_eq!(direct, vec![[10.0], [4.25], [1.0 - 5.0]]);
        let composed = t.composed();
        assert_eq!(composed.num_sources(), 3);
        assert_eq!(composed.apply(&src), direct);
    }
}
