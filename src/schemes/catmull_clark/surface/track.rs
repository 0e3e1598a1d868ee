//! Catmull-Clark's patch stencil table recorded beside the points (issue 17): the table of
//! [`crate::surface::table`] at the cost of one construction, instead of one construction per
//! colour class of the probe.
//!
//! The rows are kept factored, as OpenSubdiv's adaptive patch tables are, in a
//! [`LayeredTable`]: each refinement level is the stencil table `refine_around` applied to
//! compute its points (kept, not composed with its parent's rows), and an emitted regular or
//! ring patch records the 16 stencils of its bi-3 B-spline net over its level's points (a
//! gather of indices, ghost points at boundaries and creases), not its Bezier coefficients: the
//! fixed B-spline to Bezier conversion is applied to the net's points by the table
//! ([`crate::surface::table::PatchTable::apply`], the one `tensor_apply`). A G^1 cap's data
//! (centre, tangent plane, hole segments) are the limit and tangent stencils and the segments
//! of ring patches over the level's points, whose weights are read off the segment code
//! ([`super::g1::hole_rows`]). The steps not tracked (the Hermite-Coons fill, the caps of the
//! cap schemes) leave their patches without rows: [`catmull_clark_tracked`] then returns no
//! table and the caller probes the construction instead.

use super::g1::Rows;
use super::{CcRules, Level, g1};
use crate::bezier::BezierPatch;
use crate::bezier::complex::{PatchComplex, Provenance};
use crate::error::Result;
use crate::geom::Point;
use crate::host::ComplexOptions;
use crate::host::adaptive::{self, Tag, by_element};
use crate::mesh::PolyMesh;
use crate::mesh::tags::SubdOptions;
use crate::schemes::catmull_clark::LimitStencils;
use crate::schemes::catmull_clark::regular::Net;
use crate::stencil::{LayeredTable, Stencil, StencilTable};
use rayon::prelude::*;
use std::cell::RefCell;
use std::sync::OnceLock;

/// The rows recorded while the complex is built.
pub(crate) struct Tracker {
    /// The levels and, per patch so far in the complex's order, its net's 16 rows (none for
    /// G^1 cap patches).
    table: LayeredTable,
    /// The patches whose rows `table` holds.
    patches: usize,
    /// Whether a patch was pushed without rows (an untracked step).
    broken: bool,
    /// The caps' data rows over the stacked points, in the complex's cap order (appended to
    /// the table at the end): entries and the end of each row.
    cap_entries: Vec<(u32, f64)>,
    cap_ends: Vec<usize>,
    /// Caps whose data were tracked.
    tracked_caps: usize,
    /// Reusable buffer.
    scratch: Vec<(u32, f64)>,
}

/// The Catmull-Clark complex of [`super::catmull_clark_complex_with`] and, when every step it
/// took is tracked, its patch table's rows in factored form (16 net rows per bi-3 patch, none
/// for G^1 cap patches, then the caps' data rows: the layout of
/// [`crate::surface::table::PatchTable::from_layered`]).
///
/// # Errors
/// As [`super::catmull_clark_complex_with`].
pub fn catmull_clark_tracked(
    mesh: &PolyMesh,
    opts: ComplexOptions,
    subd: SubdOptions,
) -> Result<(PatchComplex, Option<LayeredTable>)> {
    let rules = CcRules {
        caps: None,
        opts,
        subd: Some(subd),
        track: Some(RefCell::new(Tracker::new(mesh.num_vertices()))),
    };
    let complex = adaptive::run(&rules, mesh, opts, &mut |_| {})?;
    let tracker = rules.track.expect("set above").into_inner();
    let rows = tracker.finish(&complex);
    Ok((complex, rows))
}

/// The conversion of a bi-3 B-spline net (local indices `0..16`) to the Bezier coefficients.
fn conversion() -> &'static [Stencil] {
    static CONV: OnceLock<Vec<Stencil>> = OnceLock::new();
    CONV.get_or_init(|| {
        let m3 = crate::bezier::convert::cubic_bspline_matrix();
        let net: Vec<usize> = (0..16).collect();
        crate::bezier::convert::tensor_stencils(m3, m3, &net)
    })
}

/// The bi-3 Bezier patch of a uniform bi-3 B-spline net's 16 points (`net[k * 4 + l]`, `k`
/// along `u`): [`bspline_coefficients`] into a new patch. The hot path of every regular patch
/// of the construction and of a factored patch table's apply.
///
/// # Panics
/// When `net` has fewer than 16 points.
pub fn bspline_patch(net: &[Point]) -> BezierPatch {
    let net: &[Point; 16] = net[..16].try_into().expect("16 net points");
    let mut cps = vec![[0.0; 3]; 16];
    bspline_coefficients(net, &mut cps);
    BezierPatch::new(3, 3, cps)
}

/// The 16 bi-3 Bezier coefficients of a uniform bi-3 B-spline net into `cps` (row major, as
/// [`BezierPatch::cps`]): the conversion's stencils
/// ([`crate::bezier::convert::tensor_stencils`]) applied, which are the products of
/// [`crate::bezier::convert::tensor_apply`] summed in the same order (bit-identical results)
/// without its loops over the zeros of the matrix. Writes in place, for a table re-applied into
/// an existing complex.
///
/// Four sums at a time run side by side, one term of each per step (`Kernel`), so that the
/// CPU overlaps independent chains of additions instead of waiting on one (summed one
/// coefficient after another, this was the largest single cost of building cube7's complex;
/// side by side, cube7's patch-table build is 1.5 to 3 ms faster; all 16 at once, with
/// accumulators beyond the registers, was slower). Each sum still adds its own terms in its
/// own order; a coefficient of fewer terms starts with terms of weight 0, which leave its sum
/// at the `+0.0` it starts from (for finite net points: the padding reads the stencil's first
/// slot, and an infinite point there gives NaN where the sum alone gave an infinity).
///
/// # Panics
/// When `cps` does not hold 16 points.
pub fn bspline_coefficients(net: &[Point; 16], cps: &mut [Point]) {
    assert_eq!(cps.len(), 16, "a bi-3 patch has 16 coefficients");
    let kernel = kernel();
    for g in 0..4 {
        let mut acc = [[0.0; 3]; 4];
        for (slots, weights) in kernel.slots.iter().zip(&kernel.weights) {
            for (j, a) in acc.iter_mut().enumerate() {
                let (k, w) = (slots[4 * g + j], weights[4 * g + j]);
                let p = &net[usize::from(k & 15)];
                a[0] += w * p[0];
                a[1] += w * p[1];
                a[2] += w * p[2];
            }
        }
        cps[4 * g..4 * g + 4].copy_from_slice(&acc);
    }
}

/// Most terms of one coefficient's stencil (9: the interior coefficients of a bi-3 patch read
/// 3 x 3 net points).
const MAX_TERMS: usize = 9;

/// The conversion's stencils ([`conversion`]) laid out for [`bspline_coefficients`]: step `t`
/// holds term `t` of every coefficient (net slot and weight), the stencils' terms in their
/// order, each stencil's last term at step `MAX_TERMS - 1` and the steps before its first term
/// padded with weight 0 on the stencil's first slot.
struct Kernel {
    slots: [[u8; 16]; MAX_TERMS],
    weights: [[f64; 16]; MAX_TERMS],
}

fn kernel() -> &'static Kernel {
    static KERNEL: OnceLock<Kernel> = OnceLock::new();
    KERNEL.get_or_init(|| {
        let mut kernel = Kernel {
            slots: [[0; 16]; MAX_TERMS],
            weights: [[0.0; 16]; MAX_TERMS],
        };
        for (c, s) in conversion().iter().enumerate() {
            let terms = s.entries();
            assert!(
                !terms.is_empty() && terms.len() <= MAX_TERMS,
                "a conversion stencil has 1 to {MAX_TERMS} terms"
            );
            let pad = MAX_TERMS - terms.len();
            for t in 0..pad {
                kernel.slots[t][c] = terms[0].0 as u8;
            }
            for (t, &(k, w)) in terms.iter().enumerate() {
                kernel.slots[pad + t][c] = k as u8;
                kernel.weights[pad + t][c] = w;
            }
        }
        kernel
    })
}

/// The coefficient rows of the patch of a B-spline net, over the level's points.
fn patch_terms(net: &Net) -> Rows {
    conversion()
        .iter()
        .map(|c| {
            c.entries()
                .iter()
                .flat_map(|&(k, w)| net.row(k as usize).iter().map(move |&(v, x)| (v, w * x)))
                .collect()
        })
        .collect()
}

impl Tracker {
    /// No rows yet, over `n` input points.
    pub(crate) fn new(n: usize) -> Tracker {
        Tracker {
            table: LayeredTable::new(n),
            patches: 0,
            broken: false,
            cap_entries: Vec::new(),
            cap_ends: Vec::new(),
            tracked_caps: 0,
            scratch: Vec::new(),
        }
    }

    /// The next level, `step` over the points of the level before.
    pub(crate) fn level(&mut self, step: StencilTable) {
        self.table.push_level(step);
    }

    /// Whether patch `p` is the next one in order (else a step before it was not tracked).
    fn next(&mut self, p: usize) -> bool {
        self.broken |= p != self.patches;
        !self.broken
    }

    /// Makes room for the rows of `n` more regular nets (16 one-entry rows each).
    pub(crate) fn reserve_regular(&mut self, n: usize) {
        self.table.reserve_rows(16 * n, 16 * n);
    }

    /// Records the rows of the regular patch pushed as patch `p`, whose B-spline net (stencils
    /// over the level's points) the push kept as `net`.
    pub(crate) fn regular(&mut self, p: usize, net: super::emit::NetRows) {
        use super::emit::NetRows;
        if !self.next(p) {
            return;
        }
        let net = match net {
            NetRows::Grid(g) => {
                self.patches += 1;
                self.table.push_level_points(&g);
                return;
            }
            NetRows::Ghosted(net) => net,
            // a push without rows: the table is broken from here on
            NetRows::Untracked => {
                self.broken = true;
                return;
            }
        };
        self.patches += 1;
        for r in net.rows() {
            self.scratch.extend_from_slice(r);
            self.table.push_level_row(&mut self.scratch);
        }
    }

    /// Records the data rows of the G^1 caps `out.caps[first..]` that [`g1::g1_caps`] just
    /// built from the marked faces `marked` of `level` (the last level pushed).
    pub(crate) fn caps(
        &mut self,
        level: &Level,
        marked: &[(u32, Tag)],
        out: &PatchComplex,
        first: usize,
    ) {
        if self.broken || self.tracked_caps != first {
            return;
        }
        let groups = by_element(marked);
        let cells_of: std::collections::HashMap<_, &[(u32, Tag)]> =
            groups.iter().map(|(e, c)| (*e, c.as_slice())).collect();
        let limits = LimitStencils::new(&level.mesh);
        let patch_rows = |g: usize| super::regular_net(level, g).map(|net| patch_terms(&net));
        let shift = self.table.last_level_offset();
        // the caps' rows are independent: computed in parallel, appended in the caps' order
        let data: Vec<Option<Rows>> = out.caps[first..]
            .par_iter()
            .map(|step| {
                let Provenance::Cap { element, .. } = out.provenance[step.first as usize] else {
                    return None;
                };
                let cells = cells_of.get(&Some(element))?;
                g1::hole_rows(level, &limits, element, cells, &patch_rows)
            })
            .collect();
        for (step, data) in out.caps[first..].iter().zip(data) {
            if !self.next(step.first as usize) {
                return;
            }
            let Some(data) = data else {
                return;
            };
            for t in &data {
                self.cap_entries
                    .extend(t.iter().map(|&(v, w)| (v + shift, w)));
                self.cap_ends.push(self.cap_entries.len());
            }
            self.patches += step.count as usize;
            self.tracked_caps += 1;
        }
    }

    /// The table's rows for the complex `c`, or `None` when some patch or cap was not tracked.
    fn finish(mut self, c: &PatchComplex) -> Option<LayeredTable> {
        if self.broken || self.patches != c.len() || self.tracked_caps != c.caps.len() {
            return None;
        }
        let mut start = 0;
        for &end in &self.cap_ends {
            self.scratch
                .extend_from_slice(&self.cap_entries[start..end]);
            self.table.push_row(&mut self.scratch);
            start = end;
        }
        Some(self.table)
    }
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    /// The side-by-side sums are the conversion's stencils applied one after another, bit for
    /// bit, and `tensor_apply`'s products: on nets of mixed signs, magnitudes and zeros.
    #[crate::unit::test]
    fn coefficients_are_the_stencils_bit_for_bit() {
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        for trial in 0..200 {
            let net: [Point; 16] = std::array::from_fn(|_| {
                std::array::from_fn(|_| {
                    let r = next();
                    let x = (r >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
                    match (r & 7, trial % 3) {
                        (0, _) => 0.0,
                        (1, _) => -0.0,
                        (_, 0) => x,
                        (_, 1) => x * 1e6,
                        _ => x * 1e-9 + 3.0,
                    }
                })
            });
            let mut fast = [[0.0; 3]; 16];
            bspline_coefficients(&net, &mut fast);
            for (c, s) in conversion().iter().enumerate() {
                let mut want = [0.0; 3];
                for &(k, w) in s.entries() {
                    for (a, x) in want.iter_mut().zip(&net[k as usize]) {
                        *a += w * x;
                    }
                }
                let bits = |p: &Point| p.map(f64::to_bits);
                assert_eq!(
                    bits(&fast[c]),
                    bits(&want),
                    "trial {trial}, coefficient {c}"
                );
            }
            let m3 = crate::bezier::convert::cubic_bspline_matrix();
            let t = crate::bezier::convert::tensor_apply(m3, m3, &net);
            for (c, p) in t.cps.iter().enumerate() {
                let bits = |p: &Point| p.map(f64::to_bits);
                assert_eq!(bits(&fast[c]), bits(p), "trial {trial}, tensor_apply {c}");
            }
        }
    }
}
