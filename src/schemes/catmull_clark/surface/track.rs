//! Catmull-Clark's patch stencil table tracked beside the points (issue 17): the table of
//! [`crate::surface::table`] at the cost of one construction, instead of one construction per
//! colour class of the probe.
//!
//! Every point of a level carries its row over the input net's points
//! ([`Level::rows`](super::Level): the identity at level 0, each refinement's own stencil table
//! composed with its parent's rows in `refine_around`). An emitted regular or ring patch's rows
//! are the fixed B-spline to Bezier conversion ([`tensor_stencils`], the stencils behind
//! [`crate::bezier::convert::tensor_apply`]) of its net's stencils, composed with the level's
//! rows. A G^1 cap's data (centre, tangent plane, hole segments) are the limit and tangent
//! stencils and the segments of ring patches, whose weights are read off the segment code
//! ([`super::g1::hole_rows`]). The steps not tracked (the Hermite-Coons fill, the caps of the
//! cap schemes) leave their patches without rows: [`catmull_clark_tracked`] then returns no
//! table and the caller probes the construction instead.

use super::{CcRules, Level, g1};
use crate::bezier::complex::{PatchComplex, Provenance};
use crate::error::Result;
use crate::host::ComplexOptions;
use crate::host::adaptive::{self, Tag, by_element};
use crate::mesh::PolyMesh;
use crate::mesh::tags::SubdOptions;
use crate::schemes::catmull_clark::LimitStencils;
use crate::stencil::{Stencil, StencilTable};
use std::cell::RefCell;
use std::sync::OnceLock;

/// The rows recorded while the complex is built.
pub(crate) struct Tracker {
    /// Rows of the coefficients of the patches so far, in the complex's order (empty rows for
    /// G^1 cap patches).
    coef: StencilTable,
    /// The patches whose rows `coef` holds.
    patches: usize,
    /// Whether a patch was pushed without rows (an untracked step).
    broken: bool,
    /// The caps' data rows, in the complex's cap order.
    caps: StencilTable,
    /// Caps whose data were tracked.
    tracked_caps: usize,
    /// Reusable buffers.
    terms: Vec<(u32, f64)>,
    scratch: Vec<(u32, f64)>,
}

/// The Catmull-Clark complex of [`super::catmull_clark_complex_with`] and, when every step it
/// took is tracked, its patch table's rows (one per coefficient of each patch, empty for G^1 cap
/// patches, then the caps' data rows: the layout of
/// [`crate::surface::table::PatchTable::from_parts`]).
///
/// # Errors
/// As [`super::catmull_clark_complex_with`].
pub fn catmull_clark_tracked(
    mesh: &PolyMesh,
    opts: ComplexOptions,
    subd: SubdOptions,
) -> Result<(PatchComplex, Option<StencilTable>)> {
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

/// The coefficient rows of the patch of a B-spline net, over the level's points.
fn patch_terms(net: &[Stencil]) -> Vec<Vec<(u32, f64)>> {
    conversion()
        .iter()
        .map(|c| {
            c.entries()
                .iter()
                .flat_map(|&(k, w)| {
                    net[k as usize]
                        .entries()
                        .iter()
                        .map(move |&(v, x)| (v, w * x))
                })
                .collect()
        })
        .collect()
}

impl Tracker {
    /// No rows yet, over `n` input points.
    pub(crate) fn new(n: usize) -> Tracker {
        Tracker {
            coef: StencilTable::with_capacity(n, 0, 0),
            patches: 0,
            broken: false,
            caps: StencilTable::with_capacity(n, 0, 0),
            tracked_caps: 0,
            terms: Vec::new(),
            scratch: Vec::new(),
        }
    }

    /// Whether patch `p` is the next one in order (else a step before it was not tracked).
    fn next(&mut self, p: usize) -> bool {
        self.broken |= p != self.patches;
        !self.broken
    }

    /// Records the rows of the regular patch of the B-spline net `net` (stencils over the
    /// level's points), pushed as patch `p`.
    pub(crate) fn regular(&mut self, p: usize, level: &Level, net: &[Stencil]) {
        let Some(rows) = &level.rows else { return };
        if !self.next(p) {
            return;
        }
        self.patches += 1;
        for c in conversion() {
            self.terms.clear();
            for &(k, w) in c.entries() {
                let s = &net[k as usize];
                self.terms
                    .extend(s.entries().iter().map(|&(v, x)| (v, w * x)));
            }
            self.coef
                .push_combination(rows, &self.terms, &mut self.scratch);
        }
    }

    /// Records the data rows of the G^1 caps `out.caps[first..]` that [`g1::g1_caps`] just
    /// built from the marked faces `marked` of `level`.
    pub(crate) fn caps(
        &mut self,
        level: &Level,
        marked: &[(u32, Tag)],
        out: &PatchComplex,
        first: usize,
    ) {
        let Some(rows) = &level.rows else { return };
        if self.broken || self.tracked_caps != first {
            return;
        }
        let groups = by_element(marked);
        let limits = LimitStencils::new(&level.mesh);
        let patch_rows = |g: usize| super::regular_net(level, g).map(|net| patch_terms(&net));
        for step in &out.caps[first..] {
            let Provenance::Cap { element, .. } = out.provenance[step.first as usize] else {
                return;
            };
            if !self.next(step.first as usize) {
                return;
            }
            let Some((_, cells)) = groups.iter().find(|(e, _)| *e == Some(element)) else {
                return;
            };
            let Some(data) = g1::hole_rows(level, &limits, element, cells, &patch_rows) else {
                return;
            };
            for t in &data {
                self.caps.push_combination(rows, t, &mut self.scratch);
            }
            for p in step.first..step.first + step.count {
                for _ in 0..out.patches[p as usize].cps.len() {
                    self.coef.push_pairs(&[]);
                }
            }
            self.patches += step.count as usize;
            self.tracked_caps += 1;
        }
    }

    /// The table's rows for the complex `c`, or `None` when some patch or cap was not tracked.
    fn finish(mut self, c: &PatchComplex) -> Option<StencilTable> {
        if self.broken || self.patches != c.len() || self.tracked_caps != c.caps.len() {
            return None;
        }
        self.coef.extend_rows(&self.caps);
        Some(self.coef)
    }
}
