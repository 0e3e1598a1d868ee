//! Which cap a hole gets: the per-process caches of cap maps and of certificates, the search
//! for the lowest certified degree, and the cap entry points ([`g1_cap`], [`g1_cap_with`],
//! [`cap_choice`]). The maps themselves are built in `map.rs`; this file only decides which one
//! and keeps it (split from `map.rs` by topic).

use super::centre::is_half_plane;
use super::conversion::Conversion;
use super::hole::{Degrees, Fan, Hole, Layout};
use super::map::{CERTIFIED, CapMap, Centre, Solved};
use crate::bezier::BezierPatch;
use crate::error::{Error, Result};
use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

/// The largest distance of a boundary coefficient from the centre (at least the smallest
/// positive normal number).
pub(crate) fn hole_size(hole: &Hole) -> f64 {
    hole.sectors
        .iter()
        .flatten()
        .flat_map(|s| s.boundary.iter())
        .map(|p| crate::geom::dist(*p, hole.centre))
        .fold(f64::MIN_POSITIVE, f64::max)
}

pub(super) type Key = (usize, Layout, Degrees, usize, Centre, Fan);

/// The cap map for the given shape, built once per process and shared.
pub fn cap_map(
    n: usize,
    layout: Layout,
    degrees: Degrees,
    degree: usize,
    centre: Centre,
) -> Result<Arc<CapMap>> {
    cached_map((n, layout, degrees, degree, centre, Fan::Closed.on(layout)))
}

/// The cap map of `hole`'s shape (valence, layout, segment degrees, [`Fan`]) at `degree`
/// with `centre`, built once per process and shared.
pub fn hole_cap_map(hole: &Hole, degree: usize, centre: Centre) -> Result<Arc<CapMap>> {
    let (layout, degrees) = hole.layout()?;
    let fan = hole.fan().on(layout);
    cached_map((hole.valence(), layout, degrees, degree, centre, fan))
}

fn cached_map(key: Key) -> Result<Arc<CapMap>> {
    let cache = MAPS.get_or_init(|| Mutex::new(HashMap::new()));
    if let Some(m) = cache.lock().map_err(poisoned)?.get(&key) {
        return Ok(m.clone());
    }
    // the system the degree search solved, if it is this one
    let last = {
        let mut kept = LAST_SOLVED.lock().map_err(poisoned)?;
        kept.iter()
            .position(|s| s.key == key)
            .map(|i| kept.remove(i))
    };
    let solved = match last {
        Some(s) => s,
        None => Solved::new(key)?,
    };
    let m = Arc::new(solved.finish()?);
    cache.lock().map_err(poisoned)?.insert(key, m.clone());
    Ok(m)
}

static MAPS: OnceLock<Mutex<HashMap<Key, Arc<CapMap>>>> = OnceLock::new();

/// The last two systems [`certificate`] solved, kept for [`cached_map`]: the map that is then
/// built is the degree search's last step (tangent plane) or the centre condition tried after
/// it (quadratic jet, [`cap_choice`]). Two at a time, so the memory they hold is bounded.
static LAST_SOLVED: Mutex<Vec<Solved>> = Mutex::new(Vec::new());
const KEPT_SOLVED: usize = 2;

/// The certificate of a shape ([`CapMap::certificate`]), from the map if it was built, else
/// from its solved conditions alone (cached per process; the energy is left out).
fn certificate(key: Key) -> Result<f64> {
    static CERTS: OnceLock<Mutex<HashMap<Key, f64>>> = OnceLock::new();
    if let Some(m) = MAPS
        .get_or_init(|| Mutex::new(HashMap::new()))
        .lock()
        .map_err(poisoned)?
        .get(&key)
    {
        return Ok(m.certificate);
    }
    let certs = CERTS.get_or_init(|| Mutex::new(HashMap::new()));
    if let Some(&c) = certs.lock().map_err(poisoned)?.get(&key) {
        return Ok(c);
    }
    let s = Solved::new(key)?;
    let c = s.certificate;
    certs.lock().map_err(poisoned)?.insert(key, c);
    let mut kept = LAST_SOLVED.lock().map_err(poisoned)?;
    if kept.len() == KEPT_SOLVED {
        kept.remove(0);
    }
    kept.push(s);
    Ok(c)
}

fn poisoned<T>(_: T) -> Error {
    Error::Unsupported("the cap map cache was poisoned by a panic".into())
}

/// The lowest cap degree certified for this shape, searched from the degree of the quad data
/// (at least 3) up to that plus 4 (`Auto` counts as `TangentPlane`).
pub fn lowest_certified_degree(
    n: usize,
    layout: Layout,
    degrees: Degrees,
    centre: Centre,
) -> Result<usize> {
    lowest_certified_fan(n, layout, degrees, centre, Fan::Closed)
}

/// [`lowest_certified_degree`] for the holes of kind `fan` ([`CapMap::with_fan`]).
pub fn lowest_certified_fan(
    n: usize,
    layout: Layout,
    degrees: Degrees,
    centre: Centre,
    fan: Fan,
) -> Result<usize> {
    let fan = fan.on(layout);
    let centre = if centre == Centre::Auto {
        Centre::TangentPlane
    } else {
        centre
    };
    let lo = Conversion::cached(n, layout, degrees).degree.max(3);
    for d in lo..=lo + 4 {
        if certificate((n, layout, degrees, d, centre, fan))? < CERTIFIED {
            return Ok(d);
        }
    }
    Err(Error::Unsupported(format!(
        "no G^1 cap of degree {lo}..{} is certified for valence {n} ({layout:?})",
        lo + 4
    )))
}

/// Options of [`g1_cap_with`].
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct CapOptions {
    /// The cap's bi-degree; `None`: the lowest certified one.
    pub degree: Option<usize>,
    /// The condition at the centre.
    pub centre: Centre,
}

/// A cap and what was measured while building it.
#[derive(Debug, Clone)]
pub struct Cap {
    /// One bi-`degree` patch per quad sector.
    pub patches: Vec<BezierPatch>,
    /// The cap's bi-degree.
    pub degree: usize,
    /// The centre condition used (never `Auto`).
    pub centre: Centre,
    /// The map's certificate (see [`CapMap::certificate`]).
    pub certificate: f64,
    /// Largest relative violation of the ring's compatibility conditions by the hole's data
    /// (rounding level for a ring that is C^1 in the layout's charts) and where it is.
    pub compatibility: (f64, String),
}

/// Relative compatibility defect above which [`g1_cap`] refuses a hole (or above its
/// `rounding_floor`, if that is larger).
pub const MAX_COMPATIBILITY_DEFECT: f64 = 1e-7;

/// The compatibility defect a hole's data may have from rounding alone, relative to its size:
/// the data are computed from absolute coordinates, through as many levels of stencils as the
/// hole is deep, so their rounding is a few units of `eps |centre|` per level, and relative to
/// the hole that grows as the hole shrinks (measured on OpenSubdiv's rook under PGS at
/// `--rings 11`, coordinates about 3.5, holes about 2e-5 across: relative defects 1.06e-7 to
/// 1.3e-7, about 3 000 times `eps |centre| / size`, and the holes were left to the C^0 fill,
/// 5.6e-2 rad across its spokes; the same net moved to the origin caps them). The floor is
/// `1e4 eps |centre| / size`: far below what data that are not C^1 give (a ring that is not
/// C^1 has a defect of its own size, not of its distance from the origin).
pub(crate) fn rounding_floor(hole: &Hole) -> f64 {
    1e4 * f64::EPSILON * crate::geom::norm(hole.centre) / hole_size(hole)
}

/// The largest valence a cap is built for: the cap map is a dense null-space and
/// pseudo-inverse computation on `O(n)` coefficients (time `O(n^3)`), so larger holes are
/// refused and their providers keep their C^0 fill. Measured on the 2-core test machine, a
/// Catmull-Clark pole (bi-5 cap) of valence 32 builds in 0.6 s, of 48 in 1.7 s and of 64 in
/// 4.0 s and 360 MB: a UV sphere of 64 segments gets G^1 poles. (The split caps of the guided
/// macro-patch schemes, whose maps are larger, are built for valence 16 at most: guided
/// subdivision's own valences.)
pub const MAX_CAP_VALENCE: usize = 64;

/// Refuses a valence above [`MAX_CAP_VALENCE`] before anything of size `n^2` is allocated.
pub fn check_cap_valence(n: usize) -> Result<()> {
    if n > MAX_CAP_VALENCE {
        return Err(Error::Unsupported(format!(
            "a G^1 cap of valence {n}: at most {MAX_CAP_VALENCE} (the cap map's dense solve \
             grows like n^3)"
        )));
    }
    Ok(())
}

/// The G^1 cap of a hole at the lowest certified degree (or at `degree` if given).
///
/// Errors name the sector or spoke end whose data are not compatible with a C^1 ring, or a
/// valence above [`MAX_CAP_VALENCE`].
pub fn g1_cap_with(hole: &Hole, opts: CapOptions) -> Result<Cap> {
    let (_, _, d, centre) = cap_choice(hole, opts)?;
    let map = hole_cap_map(hole, d, centre)?;
    let compat = map.compatibility_defect(hole);
    if compat.0 > MAX_COMPATIBILITY_DEFECT.max(rounding_floor(hole)) {
        return Err(Error::InvalidArgument(format!(
            "the hole's ring data are not C^1-compatible at the {} (relative defect {:.3e}); \
             no C^1 + G^1 cap exists for them",
            compat.1, compat.0
        )));
    }
    Ok(Cap {
        patches: map.apply(hole)?,
        degree: d,
        centre,
        certificate: map.certificate,
        compatibility: compat,
    })
}

/// The hole's layout and the degree and centre condition [`g1_cap_with`] chooses for it under
/// `opts`: they depend on the hole's valence, layout and segment degrees only (not on its
/// points), so a patch stencil table can learn them without building the cap again.
///
/// # Errors
/// As [`g1_cap_with`] for an unsupported valence or layout, or when no certified degree exists.
pub fn cap_choice(hole: &Hole, opts: CapOptions) -> Result<(Layout, Degrees, usize, Centre)> {
    let n = hole.valence();
    check_cap_valence(n)?;
    let (layout, degrees) = hole.layout()?;
    let fan = hole.fan();
    // a cone point has no tangent plane, let alone a quadratic expansion to share; two
    // sectors always take the half-plane jet, which the plain plane names
    let requested = if fan.is_cone() || is_half_plane(n, fan.on(layout)) {
        Centre::TangentPlane
    } else {
        opts.centre
    };
    let (d, centre) = match requested {
        Centre::Auto => {
            let d = match opts.degree {
                Some(d) => d,
                None => lowest_certified_fan(n, layout, degrees, Centre::TangentPlane, fan)?,
            };
            // an open fan keeps the plane: the limit at a boundary vertex has no bounded
            // quadratic expansion to share (see the module documentation, "Open fans")
            let jet = !layout.is_open()
                && certificate((
                    n,
                    layout,
                    degrees,
                    d,
                    Centre::QuadraticJet,
                    Fan::Closed.on(layout),
                ))? < CERTIFIED;
            let c = if jet {
                Centre::QuadraticJet
            } else {
                Centre::TangentPlane
            };
            (d, c)
        }
        c => match opts.degree {
            Some(d) => (d, c),
            None => (lowest_certified_fan(n, layout, degrees, c, fan)?, c),
        },
    };
    Ok((layout, degrees, d, centre))
}

/// The G^1 cap of a hole: one patch per (quad) sector, at the lowest certified degree.
pub fn g1_cap(hole: &Hole) -> Result<Vec<BezierPatch>> {
    g1_cap_with(hole, CapOptions::default()).map(|c| c.patches)
}
