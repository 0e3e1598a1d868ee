//! The two forms of a patch table's rows: expanded (one row per Bezier coefficient over the
//! control points: the probed tables, the tables read from files) and factored (Catmull-Clark's
//! tracked tables: per bi-3 patch the 16 rows of its B-spline net over a stack of refinement
//! levels, [`LayeredTable`], converted to Bezier form at apply by the one conversion,
//! [`bspline_patch`]: the stencils of [`crate::bezier::convert::tensor_stencils`], as the
//! construction applies them). Both give the same values; the factored form
//! expands on demand ([`Rows::expanded`]) for readers that want one row per coefficient (the
//! `--stencils` file, Python's `csr()`), with the same conversion weights
//! ([`crate::bezier::convert::tensor_stencils`]).

use crate::bezier::BezierPatch;
use crate::bezier::convert::{cubic_bspline_matrix, tensor_stencils};
use crate::geom::Point;
use crate::schemes::catmull_clark::surface::{bspline_coefficients, bspline_patch};
use crate::stencil::{LayeredTable, StencilTable};
use rayon::prelude::*;
use std::sync::OnceLock;

/// Rows of the net of one bi-3 B-spline patch.
pub(super) const NET: usize = 16;

/// A patch table's rows (see the [module](self) documentation).
#[derive(Debug, Clone)]
pub(super) enum Rows {
    /// One row per coefficient of every patch (cap patches: empty rows), then the caps' data
    /// rows, over the control points.
    Expanded(StencilTable),
    /// Per patch that is not a cap patch the 16 rows of its bi-3 B-spline net, then the caps'
    /// data rows, over the stacked points of `layered`.
    Nets {
        /// The levels and the rows.
        layered: LayeredTable,
        /// Per patch the first row of its net (unused for cap patches).
        net_first: Vec<u32>,
        /// The expanded rows, once asked for.
        expanded: OnceLock<StencilTable>,
    },
}

/// What the rows need to know of the patches: shape and whether a cap computes each.
pub(super) struct Layout<'a> {
    /// Per patch `(deg_u, deg_v)`.
    pub shapes: &'a [(u32, u32)],
    /// Whether each patch is a cap patch.
    pub in_cap: &'a [bool],
}

impl Rows {
    /// The factored rows of `layered` for patches of `layout`: the net rows of every patch
    /// that is not a cap patch (each must be bi-3), in order, then `data` rows; `None` when the
    /// counts do not match.
    pub(super) fn nets(layered: LayeredTable, layout: &Layout, data: usize) -> Option<Rows> {
        let mut net_first = Vec::with_capacity(layout.shapes.len());
        let mut r = 0u32;
        for (&shape, &cap) in layout.shapes.iter().zip(layout.in_cap) {
            net_first.push(r);
            if !cap {
                if shape != (3, 3) {
                    return None;
                }
                r += NET as u32;
            }
        }
        (layered.num_rows() == r as usize + data).then_some(Rows::Nets {
            layered,
            net_first,
            expanded: OnceLock::new(),
        })
    }

    /// Number of control points read.
    pub(super) fn num_sources(&self) -> usize {
        match self {
            Rows::Expanded(t) => t.num_sources(),
            Rows::Nets { layered, .. } => layered.num_sources(),
        }
    }

    /// Bytes held (the factored form without its expanded copy).
    pub(super) fn heap_bytes(&self) -> usize {
        match self {
            Rows::Expanded(t) => t.heap_bytes(),
            Rows::Nets {
                layered, net_first, ..
            } => layered.heap_bytes() + 4 * net_first.len(),
        }
    }

    /// The rows in expanded form (computed once for the factored form: each stacked point's
    /// row composed down to the control points, each net's rows through the conversion).
    pub(super) fn expanded(&self, layout: &Layout) -> &StencilTable {
        match self {
            Rows::Expanded(t) => t,
            Rows::Nets {
                layered,
                net_first,
                expanded,
            } => expanded.get_or_init(|| expand(layered, net_first, layout)),
        }
    }

    /// The patches' coefficients for control points `pts` (cap patches empty) and the values
    /// of the caps' data rows, without constants.
    pub(super) fn values(&self, layout: &Layout, pts: &[Point]) -> (Vec<BezierPatch>, Vec<Point>) {
        match self {
            Rows::Expanded(t) => {
                let vals = t.apply(pts);
                let (patches, data0) = expanded_patches(layout, &vals);
                (patches, vals[data0..].to_vec())
            }
            Rows::Nets {
                layered, net_first, ..
            } => {
                let vals = layered.apply(pts);
                let patches = (0..layout.shapes.len())
                    .into_par_iter()
                    .map(|p| {
                        if layout.in_cap[p] {
                            let (du, dv) = layout.shapes[p];
                            return empty(du, dv);
                        }
                        let r = net_first[p] as usize;
                        bspline_patch(&vals[r..r + NET])
                    })
                    .collect();
                let data0 = nets_end(net_first, layout);
                (patches, vals[data0..].to_vec())
            }
        }
    }

    /// [`Rows::values`] written into `patches` (the layout's patches, their coefficient vectors
    /// reused; cap patches untouched): the same values bit for bit. The factored form computes
    /// each net on the stack and converts it in place, so a moved net costs no allocation but
    /// the stacked points; the expanded form computes [`Rows::values`] and copies.
    pub(super) fn values_into(
        &self,
        layout: &Layout,
        pts: &[Point],
        patches: &mut [BezierPatch],
    ) -> Vec<Point> {
        match self {
            Rows::Expanded(_) => {
                let (fresh, data) = self.values(layout, pts);
                for ((p, f), &cap) in patches.iter_mut().zip(fresh).zip(layout.in_cap) {
                    if !cap {
                        p.cps = f.cps;
                    }
                }
                data
            }
            Rows::Nets {
                layered, net_first, ..
            } => {
                let stacked = layered.stack(pts);
                let rows = layered.rows();
                patches
                    .par_iter_mut()
                    .enumerate()
                    .filter(|&(p, _)| !layout.in_cap[p])
                    .for_each(|(p, patch)| {
                        let mut net = [[0.0; 3]; NET];
                        rows.apply_rows_into(&stacked, net_first[p] as usize, &mut net);
                        bspline_coefficients(&net, &mut patch.cps);
                    });
                let data0 = nets_end(net_first, layout);
                let mut data = vec![[0.0; 3]; rows.num_rows() - data0];
                rows.apply_rows_into(&stacked, data0, &mut data);
                data
            }
        }
    }
}

/// A patch with no coefficients yet.
fn empty(du: u32, dv: u32) -> BezierPatch {
    BezierPatch {
        deg_u: du as usize,
        deg_v: dv as usize,
        cps: Vec::new(),
        weights: None,
    }
}

/// The patches of expanded rows' values (cap patches empty) and the first data row.
pub(super) fn expanded_patches(layout: &Layout, vals: &[Point]) -> (Vec<BezierPatch>, usize) {
    let mut r = 0;
    let patches = layout
        .shapes
        .iter()
        .zip(layout.in_cap)
        .map(|(&(du, dv), &cap)| {
            let n = ((du + 1) * (dv + 1)) as usize;
            let mut p = empty(du, dv);
            if !cap {
                p.cps = vals[r..r + n].to_vec();
            }
            r += n;
            p
        })
        .collect();
    (patches, r)
}

/// One past the last net row.
fn nets_end(net_first: &[u32], layout: &Layout) -> usize {
    match (net_first.last(), layout.in_cap.last()) {
        (Some(&r), Some(&cap)) => r as usize + if cap { 0 } else { NET },
        _ => 0,
    }
}

/// The expanded rows of a factored table.
fn expand(layered: &LayeredTable, net_first: &[u32], layout: &Layout) -> StencilTable {
    let composed = layered.composed();
    let node: Vec<usize> = (0..NET).collect();
    let m3 = cubic_bspline_matrix();
    let conversion = tensor_stencils(m3, m3, &node);
    let n = layered.num_sources();
    let coefficients: usize = layout
        .shapes
        .iter()
        .map(|&(du, dv)| ((du + 1) * (dv + 1)) as usize)
        .sum();
    let mut t = StencilTable::with_capacity(n, coefficients, 16);
    let (mut terms, mut scratch) = (Vec::new(), Vec::new());
    for (p, (&(du, dv), &cap)) in layout.shapes.iter().zip(layout.in_cap).enumerate() {
        if cap {
            for _ in 0..(du + 1) * (dv + 1) {
                t.push_pairs(&[]);
            }
            continue;
        }
        for c in &conversion {
            terms.clear();
            terms.extend(c.entries().iter().map(|&(k, w)| (net_first[p] + k, w)));
            t.push_combination(&composed, &terms, &mut scratch);
        }
    }
    for r in nets_end(net_first, layout)..composed.num_rows() {
        let (i, w) = composed.row(r);
        let pairs: Vec<(u32, f64)> = i.iter().copied().zip(w.iter().copied()).collect();
        t.push_pairs(&pairs);
    }
    t
}
