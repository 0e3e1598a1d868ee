//! The G^1 caps of the adaptive loop: which elements of the marked cells get the cap of
//! [`crate::bezier::g1`] (and how many rings each element wants first), the centre and tangent
//! plane of a hole or fan, and whether a cap is still waiting for more levels. Every scheme
//! whose surface ends in [`crate::bezier::g1`] caps (Catmull-Clark, Loop, Doo-Sabin, non-box)
//! calls these from its [`super::AdaptiveRules::caps`].

use super::{Info, Tag, by_element};
use crate::bezier::complex::{PatchComplex, Provenance};
use crate::geom::Point;
use crate::mesh::{Element, PolyMesh};
use std::collections::HashMap;

/// The hole data of one element's G^1 cap: the hole (centre set), two vectors spanning its
/// limit tangent plane (normal `plane[0] x plane[1]`; both linear in the control points, so a
/// patch stencil table can tabulate them), and the tag of each sector's cell in the hole's
/// sector order.
pub type CapData = (crate::bezier::g1::Hole, [Point; 2], Vec<Tag>);

/// Closes with the G^1 cap of [`crate::bezier::g1`] (spoke tangents from the ring's chart,
/// [`crate::bezier::g1::ring::cap_from_plane`]) every element of the marked cells for which
/// `hole_of` gives the data (one hole, or several: the sectors of a crease vertex, capped all
/// or none); the cap patches are pushed with the sectors' tags (domain and
/// sector), and the cap's data as a [`crate::bezier::complex::CapStep`] of the complex. Returns the cells left for the
/// scheme's C^0 fill. The elements' caps are independent: they are computed in parallel and
/// pushed in the elements' order (the same complex as one after another). An element whose
/// hole data exist but whose cap cannot be built is recorded with the reason in
/// [`PatchComplex::uncapped`] (the user is told; the fill closes it).
pub fn g1_cap_elements<I>(
    marked: &[(u32, Tag)],
    out: &mut PatchComplex,
    hole_of: impl Fn(Element, &[(u32, Tag)]) -> I + Sync,
) -> Vec<(u32, Tag)>
where
    I: IntoIterator<Item = CapData>,
{
    use crate::bezier::g1::{CapOptions, ring::cap_step};
    use rayon::prelude::*;
    let groups = by_element(marked);
    let caps: Vec<_> = groups
        .par_iter()
        .map(|(element, cells)| {
            let e = (*element)?;
            // an element's holes (one, or one per sector of a crease vertex): all or none
            let mut built = Vec::new();
            for (hole, plane, tags) in hole_of(e, cells) {
                match cap_step(hole, plane, CapOptions::default(), 0) {
                    Ok((patches, step)) => built.push((patches, tags, step)),
                    Err(why) => return Some(Err((e, why.to_string()))),
                }
            }
            (!built.is_empty()).then_some(Ok((e, built)))
        })
        .collect();
    let mut left = Vec::new();
    for ((_, cells), capped) in groups.into_iter().zip(caps) {
        let (element, built) = match capped {
            Some(Ok(c)) => c,
            Some(Err(why)) => {
                // the hole is there and the cap failed: the fill closes it, the user is told
                out.uncapped.push(why);
                left.extend(cells);
                continue;
            }
            None => {
                left.extend(cells);
                continue;
            }
        };
        for (patches, tags, mut step) in built {
            let first = out.len();
            step.first = first as u32;
            let sharp_ends = step.hole.fan().hermite_ends();
            out.caps.push(step);
            let count = patches.len();
            for (p, tag) in patches.into_iter().zip(tags) {
                let sector = tag.sector;
                out.push_in(p, Provenance::Cap { element, sector }, tag.domain);
            }
            if sharp_ends {
                // a crease's or a dart's fan: its boundary spokes lie on the sharp edge
                out.mark_sharp(first, crate::bezier::Side::V0.index());
                out.mark_sharp(first + count - 1, crate::bezier::Side::U0.index());
            }
        }
    }
    left
}

/// Per-element ring counts of one construction: the limit surface's evaluation
/// ([`crate::surface::eval::limit_surface`]) refines each extraordinary element only as far as
/// its own points need. Rules that honour them (Catmull-Clark without a scheme's caps) close
/// an element's hole from the level of its count on (its rings are the same patches as with
/// that many rings for all); the others build `max` rings everywhere. Passed down through
/// [`with_ring_targets`] (the construction's options are shared by every scheme and caller).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RingTargets {
    /// Rings of the elements not in `per`.
    pub base: usize,
    /// Rings per element.
    pub per: HashMap<Element, usize>,
}

impl RingTargets {
    /// The rings of `element` (`base` for none or an unlisted one).
    pub fn of(&self, element: Option<Element>) -> usize {
        element
            .and_then(|e| self.per.get(&e).copied())
            .unwrap_or(self.base)
    }

    /// The most rings of any element.
    pub fn max(&self) -> usize {
        self.per.values().copied().fold(self.base, usize::max)
    }
}

thread_local! {
    static RING_TARGETS: std::cell::RefCell<Option<(std::sync::Arc<RingTargets>, bool)>> =
        const { std::cell::RefCell::new(None) };
}

/// Runs `f` (a construction on this thread) with the per-element ring counts `targets`, and
/// says whether it honoured them ([`honour_ring_targets`]). Call it outside rayon jobs (as the
/// CLI and the tests do): a worker stealing another construction inside `f` would pass it on.
pub fn with_ring_targets<T>(
    targets: std::sync::Arc<RingTargets>,
    f: impl FnOnce() -> T,
) -> (T, bool) {
    let old = RING_TARGETS.with(|t| t.replace(Some((targets, false))));
    let out = f();
    let honoured = RING_TARGETS
        .with(|t| std::mem::replace(&mut *t.borrow_mut(), old))
        .is_some_and(|(_, h)| h);
    (out, honoured)
}

/// The per-element ring counts of the construction running on this thread, if any, noted as
/// honoured: rules that close each element's hole from its own count on call this.
pub fn honour_ring_targets() -> Option<std::sync::Arc<RingTargets>> {
    RING_TARGETS.with(|t| {
        let mut t = t.borrow_mut();
        t.as_mut().map(|(targets, honoured)| {
            *honoured = true;
            targets.clone()
        })
    })
}

/// Levels computed beyond the requested rings, at most, so that holes that still touch
/// separate and get their G^1 caps (Catmull-Clark, the dual bi-2 schemes, non-box).
pub const MAX_EXTRA_CAP_LEVELS: usize = 2;

/// Why an element has no G^1 cap at a level.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NoCap {
    /// More levels would give the data (the element's hole touches another element's).
    Later,
    /// The element's hole never gets the data (boundary, non-quad faces, no single centre).
    Never,
}

/// The centre of an element's hole: the corner of its marked cell `f0` that descends from
/// `element`, and its valence; `NoCap::Never` when there is none, it lies on the boundary or
/// its valence is below 3 (the checks every vertex-centred cap provider starts with).
pub fn hole_centre(
    m: &PolyMesh,
    info: &[Info],
    element: Element,
    f0: u32,
) -> std::result::Result<(u32, usize), NoCap> {
    match fan_centre(m, info, element, f0, 3)? {
        (x, n, false) => Ok((x, n)),
        _ => Err(NoCap::Never),
    }
}

/// [`hole_centre`] that also takes a boundary vertex: the centre, its number of sectors (the
/// valence of an interior vertex, the number of faces, valence - 1, of a boundary vertex) and
/// whether the fan is open (on the boundary); `NoCap::Never` below 3 sectors, or below
/// `min_open` sectors of an open fan (2 for a fan of triangles, whose two sectors span a
/// right angle each in the chart).
pub fn fan_centre(
    m: &PolyMesh,
    info: &[Info],
    element: Element,
    f0: u32,
    min_open: usize,
) -> std::result::Result<(u32, usize, bool), NoCap> {
    fan_centre_from(m, info, element, f0, (min_open, 3))
}

/// [`fan_centre`] with the fewest sectors of an open and of a closed fan: `(min_open, 2)`
/// for the providers that close a valence-2 vertex with the half-plane cap of two quad
/// sectors ([`crate::bezier::g1`], "Two sectors").
pub fn fan_centre_from(
    m: &PolyMesh,
    info: &[Info],
    element: Element,
    f0: u32,
    (min_open, min_closed): (usize, usize),
) -> std::result::Result<(u32, usize, bool), NoCap> {
    let x = m
        .face(f0 as usize)
        .iter()
        .copied()
        .find(|&v| info[v as usize].origin == Some(element))
        .ok_or(NoCap::Never)?;
    let n = m.valence(x as usize);
    let open = m.is_boundary_vertex(x as usize);
    let sectors = if open { n - 1 } else { n };
    if sectors < if open { min_open } else { min_closed } {
        return Err(NoCap::Never);
    }
    Ok((x, sectors, open))
}

/// Whether some element of the marked cells would get its G^1 cap after more levels (`hole`
/// says `NoCap::Later` for it): the adaptive loop then goes on.
pub fn caps_waiting<T>(
    marked: &[(u32, Tag)],
    mut hole: impl FnMut(Element, &[(u32, Tag)]) -> std::result::Result<T, NoCap>,
) -> bool {
    by_element(marked).iter().any(|(e, cells)| match e {
        Some(e) => matches!(hole(*e, cells), Err(NoCap::Later)),
        None => false,
    })
}
