//! The regular patches of a Catmull-Clark level, computed in parallel blocks and pushed in
//! the cells' order ([`emit_all`]), and the one path by which a regular patch enters the
//! complex ([`CcRules::push_regular`]), shared with the per-cell `emit`.

use super::{CcRules, Level, is_hole, net_patch, regular_net, sharp};
use crate::bezier::BezierPatch;
use crate::bezier::complex::{PatchComplex, Provenance};
use crate::host::adaptive::{self, Sink, Tag};
use crate::schemes::catmull_clark::regular::Net;

/// Cells per block of [`emit_all`]'s parallel patch computation (bounds the block's nets and
/// patches held at once).
const EMIT_BLOCK: usize = 4096;

/// The first level reserves room for `1 / LATER_ROOM` of its cells (and 4096) more patches:
/// the later levels add patches around the irregular elements only, and without that room
/// their first push copied the whole of the first level's complex and table into doubled
/// arrays (on cube7, 98k faces and 8 extraordinary vertices, 10 to 15 ms of a 45 ms build).
/// Room that is never used is never touched, so it costs address space, not memory.
const LATER_ROOM: usize = 8;

/// The regular patches (nets and Bezier conversion) are computed in parallel, in blocks of
/// cells, then pushed (and tracked) in the cells' order, each block on this thread while the
/// next is computed (the pushes and the table's rows are serial; overlapping them took cube7's
/// build from 92-112 to 64-73 ms): the complex and table of the per-cell
/// [`AdaptiveRules::emit`](crate::host::adaptive::AdaptiveRules::emit) (one path:
/// [`CcRules::push_regular`]).
pub(super) fn emit_all(
    rules: &CcRules<'_>,
    level: &Level,
    l: usize,
    curves: &mut Vec<(u32, u32)>,
    out: &mut PatchComplex,
) -> Vec<(u32, Tag)> {
    use rayon::prelude::*;
    let mut marked = Vec::new();
    // room for one patch per active cell at once (growing the complex's vectors by
    // doubling copied them, with fresh pages, several times per level), and at the first
    // level for the rings to come: [`LATER_ROOM`]
    let later = if l == 0 {
        level.active.len() / LATER_ROOM + 4096
    } else {
        0
    };
    let room = out.len() + level.active.len() + later;
    out.patches.reserve(room - out.patches.len());
    out.provenance.reserve(room - out.provenance.len());
    out.domains.reserve(room.saturating_sub(out.domains.len()));
    if let Some(t) = &rules.track {
        t.borrow_mut().reserve_regular(level.active.len() + later);
    }
    let tracked = rules.track.is_some();
    let compute = |block: &[(u32, Tag)]| -> Vec<Option<(NetRows, BezierPatch)>> {
        block
            .par_iter()
            .map(|&(f, _)| {
                if is_hole(level, f as usize) {
                    return None;
                }
                let net = regular_net(level, f as usize)?;
                let p = net_patch(level, &net);
                Some((NetRows::of(net, tracked), p))
            })
            .collect()
    };
    // block k is pushed (and tracked) on this thread while block k + 1 is computed
    let blocks: Vec<&[(u32, Tag)]> = level.active.chunks(EMIT_BLOCK).collect();
    let mut built = blocks.first().map(|b| compute(b));
    for (k, block) in blocks.iter().enumerate() {
        let nets = built.take().unwrap_or_default();
        // a rayon scope, not a thread: the caller may be a pool's only worker (`eval` builds
        // inside `rayon::join`; `RAYON_NUM_THREADS=1`), which a blocking join of a thread
        // that needs the pool deadlocked; this thread runs the spawned block itself if no
        // other worker has taken it when the pushes are done
        let mut next = None;
        rayon::in_place_scope(|s| {
            if let Some(b) = blocks.get(k + 1) {
                let next = &mut next;
                s.spawn(move |_| *next = Some(compute(b)));
            }
            for (cell, built) in block.iter().zip(nets) {
                let f = cell.0;
                if is_hole(level, f as usize) {
                    continue;
                }
                let Some((rows, p)) = built else {
                    marked.push(*cell);
                    continue;
                };
                let to = Sink {
                    curves: &mut *curves,
                    out: &mut *out,
                };
                rules.push_regular(level, f, rows, p, adaptive::provenance(l, cell.1), to);
                out.set_domain(out.len() - 1, cell.1.domain);
            }
        });
        built = next;
    }
    marked
}

/// What a pushed regular patch keeps of its B-spline net for the tracker
/// ([`Tracker::regular`]): the 16 point indices of a grid (64 bytes, where the net holds 16
/// `(index, weight)` pairs: each block of [`emit_all`] is written by the workers and read by
/// the pushes, and the 256-byte nets were most of that copying), a ghosted net, or nothing
/// when the table is not tracked.
///
/// [`Tracker::regular`]: super::track::Tracker::regular
pub(crate) enum NetRows {
    /// A grid: one point per slot, weight 1.
    Grid([u32; 16]),
    /// A net with ghost points.
    Ghosted(Box<Net>),
    /// None kept (the table is not tracked).
    Untracked,
}

impl NetRows {
    /// What to keep of `net` (nothing unless `tracked`).
    pub(super) fn of(net: Net, tracked: bool) -> NetRows {
        match net {
            _ if !tracked => NetRows::Untracked,
            Net::Grid(g) => NetRows::Grid(g.map(|(i, _)| i)),
            net => NetRows::Ghosted(Box::new(net)),
        }
    }
}

impl CcRules<'_> {
    /// Pushes the regular patch `p` of cell `f` (`net`: what the tracker keeps of its B-spline
    /// net): tracked, its edge
    /// curves recorded for the fill, its sharp sides marked. The one path of
    /// [`AdaptiveRules::emit`](crate::host::adaptive::AdaptiveRules::emit) and [`AdaptiveRules::emit_all`].
    pub(super) fn push_regular(
        &self,
        level: &Level,
        f: u32,
        net: NetRows,
        p: BezierPatch,
        prov: Provenance,
        to: Sink<Vec<(u32, u32)>>,
    ) {
        if let Some(t) = &self.track {
            t.borrow_mut().regular(to.out.len(), net);
        }
        to.curves.push((f, to.out.len() as u32));
        to.out.push(p, prov);
        sharp::mark_sides(level, f as usize, to.out);
    }
}
