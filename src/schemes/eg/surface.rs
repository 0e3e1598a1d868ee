//! EG subdivision surfaces of whole meshes: bi-3 patches on regular faces, an EG cap of `K` bi-4
//! rings at every extraordinary vertex with published rules, and the G^1 cap of `g1` (or the
//! documented fill).
//!
//! Built on Catmull-Clark's adaptive loop ([`crate::schemes::catmull_clark::surface`]): every extraordinary vertex whose c-net is clean
//! (one-ring regular, and every extraordinary vertex of the c-net capped too) gets an EG cap at
//! the current level; the others are refined by one Catmull-Clark step first (the EG paper's
//! "local Catmull-Clark step" where extraordinary vertices are not separated by a regular one).
//! The rules of each valence are chosen by [`super::select`]: the printed ones at 3 and 5,
//! regular bi-4 refinement at 4, fairsub's derived rules at 6..=16 (and at 3, 5 with
//! `--rules derived`), each derived cap named in the notes (`eg (derived rules, n = 7)`). Only
//! valences above 16, which no construction covers, get the fallback the user chose:
//! Catmull-Clark rings and fill, or an error.
//!
//! A cap made at level `L` numbers its rings `L + 1 .. L + K`, so ring indices follow the
//! geometric nesting also after a local Catmull-Clark step.
//!
//! # The EG fill (fairsub's own, documented construction)
//!
//! After `K` rings the hole of each sector is the square `[0, h]^2` of the last d-net's chart.
//! Its fill is one bi-4 patch per sector:
//!
//! * the two outer rows of coefficients along each outer side continue the last ring's patches
//!   C^1 (value and first cross derivative, equal parameter speed), so the fill joins the ring
//!   C^1; the two constraints agree at the corner because the ring is one C^2 spline there;
//! * each spoke (the side along a sector ray, shared by the two sectors there, so the fill is C^0
//!   between sectors) is the cubic from `c0` through the EG surface's point at half the distance
//!   (the corner of the next ring, computed and discarded) to the ring's corner `Q` with the
//!   ring's derivative along the ray at `Q`, raised to degree 4; its last coefficients then
//!   coincide with the C^1 rows above;
//! * the four remaining inner coefficients minimise a discrete thin-plate energy (squared second
//!   differences) of the net.
//!
//! The fill is C^1 to the last ring and C^0 between its sectors (not G^1 at the spokes for
//! `n != 4`). It is written only where the G^1 cap of `g1` (read off the fill's outer
//! layers, in the limit tangent plane) cannot be built, with a note; QAS+^3's bi-3 rings get
//! the split G^1 cap of `g1` (2 x 2 pieces per sector), their C^0 Coons fill (`fill`) only
//! where that cannot be built. `fairsub check` reports the measured defects. `--no-fill`
//! leaves the hole open.
//!
//! # Parameter domain (evaluation)
//!
//! The cap's patches record the part of their input face they cover ([`crate::bezier::domain`]),
//! so `fairsub eval` works for EG and the QAS+ family. The host gives each sector's face as a
//! frame with the vertex at `(0, 0)`, `u` along spoke `s`, `v` along spoke `s + 1`
//! ([`CapBuilder::build`]); that is the d-net's chart at the c-net's spacing, transposed
//! (the EG chart's `u` runs along spoke `s + 1`). Each step halves the d-net spacing, so ring
//! `k` (0-based) covers the band `[0, 2^-k]^2 \ [0, 2^-(k+1)]^2` of the frame: patch `A` on the
//! EG chart's `[1/2, 1] x [0, 1/2]` of that square, `B` on `[1/2, 1]^2`, `C` on
//! `[0, 1/2] x [1/2, 1]` (the cells of [`crate::schemes::eg::build_step`]; QAS+^3's bi-3 rings
//! split each in its 2 x 2 quarters), each patch's own `(u, v)` the frame's, scaled. The cap
//! or fill inside ring `K` covers `[0, 2^-K]^2` with `(0, 0)` at the centre (QAS+^3's split
//! cap or Coons fill: its 2 x 2 quarters). The ratio is the chart's, whatever the scheme's eigenvalue
//! (QAS_0.4 contracts the surface by 0.4 per ring, its chart by 1/2).

use super::select::{self, Selected};
use super::{Eg, EgStep, from_cnet};
use crate::bezier::BezierPatch;
use crate::bezier::complex::{Domain, PatchComplex, Provenance};
use crate::error::{Error, Result};
use crate::geom::Point;
use crate::host::caps::{CapBuilder, CapNotes, RING_CELLS, describe, sector_square};
use crate::host::{ComplexOptions, Fallback, SurfaceOutput};
use crate::mesh::{Element, PolyMesh};
use crate::schemes::catmull_clark::surface::capped_complex;
use crate::schemes::descriptor::{RulesChoice, RulesOrigin};
use crate::schemes::options::ids;
use crate::stencil::StencilTable;
use std::collections::HashMap;
use std::sync::{Mutex, OnceLock};

mod fill;
mod g1;

/// Options of [`eg_complex`].
#[derive(Debug, Clone, Copy)]
pub struct EgOptions {
    /// Rings per cap.
    pub rings: usize,
    /// Close each cap's hole with the EG fill.
    pub fill: bool,
    /// Handling of valences without rules.
    pub fallback: Fallback,
}

impl Default for EgOptions {
    fn default() -> Self {
        EgOptions {
            rings: 8,
            fill: true,
            fallback: Fallback::CatmullClark,
        }
    }
}

/// The rules a d-net cap scheme uses at one valence, as its notes name them.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) enum Used {
    /// The scheme's own printed (or regular) rules: no note.
    Own,
    /// fairsub's derived rules, named (`eg (derived rules, n = 7)`); `chosen` when printed
    /// rules exist at the valence and `--rules derived` picked the derived ones.
    Derived {
        /// The name in notes and reports.
        label: String,
        /// Whether printed rules exist here (the user chose the derived ones).
        chosen: bool,
    },
    /// Another scheme's rules (QAS+ at valence 3 uses EG's), by that scheme's name.
    Borrowed(String),
}

/// Rules of a d-net cap scheme (EG, QAS+) per valence.
pub(crate) trait DnetRules: Sync {
    /// Name of the scheme's own rules (EG's, QAS+'s).
    fn primary(&self) -> &'static str;
    /// The rules used at valence `n` (`None` when no construction covers it).
    fn used(&self, n: usize) -> Result<Option<Used>>;
    /// Stencils of the local vector from the c-net (layout of [`from_cnet`]).
    fn init(&self, n: usize) -> Result<StencilTable>;
    /// The step and ring tables used to make ring `k` (0-based).
    fn step(&self, n: usize, k: usize) -> Result<EgStep>;
    /// Whether [`DnetRules::step`] is the same for every ring (stationary rules): then one
    /// table per valence is built and reused for all rings.
    fn stationary(&self) -> bool {
        false
    }
    /// The message of `--fallback error`.
    fn no_rules(&self, n: usize) -> String;
    /// Two vectors spanning the limit tangent plane, read off the local vector `x` after the
    /// last step, where the rules carry it explicitly (QAS+'s quadratic expansion); `None`
    /// (the default) takes the subdominant left eigenvectors of the step instead.
    fn limit_tangents(&self, _n: usize, _x: &[Point]) -> Result<Option<[Point; 2]>> {
        Ok(None)
    }
    /// Adjusts the initial local vector of one element (user-given data); the default keeps it.
    fn adjust(&self, _n: usize, _element: Element, _x: &mut [Point]) -> Result<()> {
        Ok(())
    }
}

/// EG's rules: printed, regular or derived by valence ([`super::select`]).
pub(crate) struct EgRulesProvider {
    /// Printed or derived rules where both exist.
    pub(crate) choice: RulesChoice,
}

impl EgRulesProvider {
    /// The rules of valence `n` (an error where none exist).
    fn rules(&self, n: usize) -> Result<Selected> {
        select::select(n, self.choice)?.ok_or_else(|| Error::Unsupported(select::no_rules(n)))
    }
}

impl DnetRules for EgRulesProvider {
    fn primary(&self) -> &'static str {
        ids::EG.name()
    }

    fn used(&self, n: usize) -> Result<Option<Used>> {
        Ok(select::origin(n, self.choice).map(|o| match o {
            RulesOrigin::Derived => Used::Derived {
                label: select::label(n, o),
                chosen: select::printed_exists(n),
            },
            _ => Used::Own,
        }))
    }

    fn init(&self, n: usize) -> Result<StencilTable> {
        from_cnet(n)
    }

    /// The stationary step of valence `n`, built once per process and rules choice (about a
    /// millisecond each; every complex of the process shares it).
    fn step(&self, n: usize, _k: usize) -> Result<EgStep> {
        static STEPS: OnceLock<Mutex<HashMap<(RulesChoice, usize), EgStep>>> = OnceLock::new();
        let steps = STEPS.get_or_init(|| Mutex::new(HashMap::new()));
        let key = (self.choice, n);
        if let Some(s) = steps.lock().expect("no poisoning").get(&key) {
            return Ok(s.clone());
        }
        let s = Eg::with_rules(self.rules(n)?.rules).step()?;
        steps.lock().expect("no poisoning").insert(key, s.clone());
        Ok(s)
    }

    fn stationary(&self) -> bool {
        true
    }

    fn no_rules(&self, n: usize) -> String {
        select::no_rules(n)
    }
}

/// A cap builder for any [`DnetRules`], caching tables per valence and ring.
pub(crate) struct DnetCaps<'a> {
    rules: &'a dyn DnetRules,
    rings: usize,
    fill: bool,
    fallback: Fallback,
    init: Mutex<HashMap<usize, StencilTable>>,
    steps: Mutex<HashMap<(usize, usize), EgStep>>,
    masks: Mutex<HashMap<(usize, usize), g1::TangentMasks>>,
    notes: CapNotes,
}

impl<'a> DnetCaps<'a> {
    pub(crate) fn new(
        rules: &'a dyn DnetRules,
        rings: usize,
        fill: bool,
        fallback: Fallback,
    ) -> Self {
        DnetCaps {
            rules,
            rings,
            fill,
            fallback,
            init: Mutex::new(HashMap::new()),
            steps: Mutex::new(HashMap::new()),
            masks: Mutex::new(HashMap::new()),
            notes: CapNotes::default(),
        }
    }

    fn step(&self, n: usize, k: usize) -> Result<EgStep> {
        // Stationary rules: one table per valence (building one costs about a millisecond).
        let k = if self.rules.stationary() { 0 } else { k };
        let mut map = self.steps.lock().expect("no poisoning");
        if let Some(s) = map.get(&(n, k)) {
            return Ok(s.clone());
        }
        let s = self.rules.step(n, k)?;
        map.insert((n, k), s.clone());
        Ok(s)
    }

    /// Two vectors spanning the limit tangent plane of the local vector `x` after the last
    /// step ([`g1`]): the rules' own ([`DnetRules::limit_tangents`]) or the subdominant left
    /// eigenvectors of the step that makes the next ring (cached like the steps) applied to `x`.
    fn limit_tangents(&self, n: usize, x: &[Point]) -> Result<[Point; 2]> {
        if let Some(t) = self.rules.limit_tangents(n, x)? {
            return Ok(t);
        }
        let k = if self.rules.stationary() {
            0
        } else {
            self.rings
        };
        let cached = self
            .masks
            .lock()
            .expect("no poisoning")
            .get(&(n, k))
            .cloned();
        let m = match cached {
            Some(m) => m,
            None => {
                let m = g1::tangent_masks(&self.step(n, k)?.step)?;
                self.masks
                    .lock()
                    .expect("no poisoning")
                    .insert((n, k), m.clone());
                m
            }
        };
        Ok(m.map(|w| g1::apply(&w, x)))
    }

    fn init(&self, n: usize) -> Result<StencilTable> {
        let mut map = self.init.lock().expect("no poisoning");
        if let Some(t) = map.get(&n) {
            return Ok(t.clone());
        }
        let t = self.rules.init(n)?;
        map.insert(n, t.clone());
        Ok(t)
    }

    /// Notes for the user: elements that fell back to Catmull-Clark or were capped by other
    /// rules than the scheme's own.
    pub(crate) fn notes(self) -> (Vec<(Element, usize)>, Vec<String>) {
        let primary = self.rules.primary();
        self.notes.finish(primary)
    }
}

/// The note of a cap made with derived rules.
fn derived_note(element: Element, n: usize, label: &str, chosen: bool, primary: &str) -> String {
    let why = if chosen {
        format!("chosen by --rules derived (the paper prints {primary} rules here)")
    } else {
        format!(
            "fairsub's reconstruction; the paper prints no complete {primary} rules for this valence"
        )
    };
    format!("{} (valence {n}): {label}, {why}", describe(element))
}

impl CapBuilder for DnetCaps<'_> {
    fn accepts(&self, n: usize, element: Element) -> Result<bool> {
        match self.rules.used(n)? {
            Some(Used::Own) => Ok(true),
            Some(Used::Borrowed(name)) => {
                self.notes.substitute(element, n, &name);
                Ok(true)
            }
            Some(Used::Derived { label, chosen }) => {
                self.notes.note(derived_note(
                    element,
                    n,
                    &label,
                    chosen,
                    self.rules.primary(),
                ));
                Ok(true)
            }
            None => {
                self.notes
                    .fall_back(self.fallback, element, n, || self.rules.no_rules(n))?;
                Ok(false)
            }
        }
    }

    fn note(&self, msg: String) {
        self.notes.note(msg);
    }

    fn build(
        &self,
        cnet: &[Point],
        n: usize,
        element: Element,
        first_ring: u32,
        sectors: &[Domain],
        out: &mut PatchComplex,
    ) -> Result<()> {
        if self.fill && self.rings == 0 {
            return Err(Error::InvalidArgument(
                "the fill of a d-net cap needs at least one ring (--rings 1)".into(),
            ));
        }
        let mut x = self.init(n)?.apply(cnet);
        self.rules.adjust(n, element, &mut x)?;
        let mut last = None;
        for k in 0..self.rings {
            let step = self.step(n, k)?;
            let ring = step.ring.apply(&x);
            push_ring(&ring, n, element, (first_ring, k), sectors, out);
            last = Some(ring);
            x = step.step.apply(&x);
        }
        if let (true, Some(ring)) = (self.fill, last) {
            let next = self.step(n, self.rings)?.ring.apply(&x);
            let (patches, per_sector) = if is_bi3_ring(&ring, n) {
                let cap = self
                    .limit_tangents(n, &x)
                    .and_then(|t| g1::bi3_cap(&ring, n, x[0], t, out.len()));
                match cap {
                    Ok((cap, step)) => {
                        out.caps.push(step);
                        (cap, 4)
                    }
                    Err(e) => {
                        self.notes.note(format!(
                            "{} (valence {n}): the C^0 bi-3 Coons fill closes the hole, no G^1 \
                             cap ({e})",
                            describe(element)
                        ));
                        (fill::fill_bi3(&ring, &next, x[0], n), 4)
                    }
                }
            } else {
                let c0 = fill::fill(&ring, &next, x[0], n);
                let cap = self
                    .limit_tangents(n, &x)
                    .and_then(|t| g1::dnet_cap(&c0, x[0], t, out.len()));
                match cap {
                    Ok((cap, step)) => {
                        out.caps.push(step);
                        (cap, 1)
                    }
                    Err(e) => {
                        self.notes.note(format!(
                            "{} (valence {n}): the C^0 fill closes the hole, no G^1 cap ({e})",
                            describe(element)
                        ));
                        (c0, 1)
                    }
                }
            };
            let rings = self.rings as u8;
            for (k, p) in patches.into_iter().enumerate() {
                let s = k / per_sector;
                // one patch on the square [0, 2^-K]^2 of the sector's frame, or QAS+^3's 2 x 2
                // (cap pieces (a, b) and the Coons fill's quarters alike: index 2 a + b)
                let domain = match per_sector {
                    1 => sector_square(sectors, s, rings, 0, 0),
                    _ => {
                        let (cu, cv) = ((k % 4 % 2) as u32, (k % 4 / 2) as u32);
                        sector_square(sectors, s, rings + 1, cv, cu)
                    }
                };
                let prov = Provenance::Cap {
                    element,
                    sector: s as u32,
                };
                out.push_in(p, prov, domain);
            }
        }
        Ok(())
    }
}

/// Patch `k` (0 = A, 1 = B, 2 = C) of sector `s` of a ring, in the EG chart's `(u, v)`.
fn ring_patch(ring: &[Point], s: usize, k: usize) -> BezierPatch {
    let base = 25 * (3 * s + k);
    BezierPatch::new(4, 4, ring[base..base + 25].to_vec())
}

/// Appends ring `at.1` (0-based; numbered `at.0 + at.1` in the provenance) of a cap, each patch
/// with its domain in its sector's face (the module's "Parameter domain"): the patches are
/// written transposed (mesh chart), so their first parameter runs along spoke `s`, as the
/// sector frame's `u` does.
fn push_ring(
    ring: &[Point],
    n: usize,
    element: Element,
    at: (u32, usize),
    sectors: &[Domain],
    out: &mut PatchComplex,
) {
    let bi3 = is_bi3_ring(ring, n);
    let level = at.1 as u8 + 1;
    for s in 0..n {
        for k in 0..if bi3 { 12 } else { 3 } {
            // The EG chart mirrors the mesh chart: transpose so the normal points outward.
            let (p, domain) = if bi3 {
                let (cu, cv) = RING_CELLS[k / 4];
                let (su, sv) = ((k % 4 % 2) as u32, (k % 4 / 2) as u32);
                let d = sector_square(sectors, s, level + 1, 2 * cv + sv, 2 * cu + su);
                (ring_patch3(ring, s, k / 4, k % 4), d)
            } else {
                let (cu, cv) = RING_CELLS[k];
                (
                    ring_patch(ring, s, k),
                    sector_square(sectors, s, level, cv, cu),
                )
            };
            let prov = Provenance::Ring {
                element,
                ring: at.0 + at.1 as u32,
                sector: s as u32,
            };
            out.push_in(p.transposed(), prov, domain);
        }
    }
}

/// Whether a ring table holds 12 bi-3 patches per sector (QAS+^3) rather than 3 bi-4 patches.
fn is_bi3_ring(ring: &[Point], n: usize) -> bool {
    ring.len() == 192 * n
}

/// Sub-patch `sub` ((0,0), (1,0), (0,1), (1,1) of the EG chart) of macro-patch `k` (A, B, C) of
/// sector `s` of a bi-3 ring.
fn ring_patch3(ring: &[Point], s: usize, k: usize, sub: usize) -> BezierPatch {
    let base = 16 * (12 * s + 4 * k + sub);
    BezierPatch::new(3, 3, ring[base..base + 16].to_vec())
}

/// The EG surface of a net as a patch complex (printed rules where they exist, derived ones
/// elsewhere). Also returns the vertices that fell back to Catmull-Clark (element and valence).
pub fn eg_complex(
    mesh: &PolyMesh,
    opts: EgOptions,
    progress: impl FnMut(usize),
) -> Result<(PatchComplex, Vec<(Element, usize)>)> {
    eg_complex_with(mesh, opts, RulesChoice::Printed, progress).map(|o| (o.complex, o.fell_back))
}

/// The EG surface of a net with the rules `choice` (printed or derived where both exist), with
/// the elements that fell back and the notes (which caps use derived rules).
pub fn eg_complex_with(
    mesh: &PolyMesh,
    opts: EgOptions,
    choice: RulesChoice,
    progress: impl FnMut(usize),
) -> Result<SurfaceOutput> {
    dnet_complex(&EgRulesProvider { choice }, mesh, opts, progress)
}

/// The surface of a net with caps of a d-net scheme (shared by EG and QAS+).
pub(crate) fn dnet_complex(
    rules: &dyn DnetRules,
    mesh: &PolyMesh,
    opts: EgOptions,
    mut progress: impl FnMut(usize),
) -> Result<SurfaceOutput> {
    let caps = DnetCaps::new(rules, opts.rings, opts.fill, opts.fallback);
    let c = capped_complex(
        mesh,
        ComplexOptions {
            rings: opts.rings,
            fill: opts.fill,
        },
        &caps,
        &mut progress,
    )?;
    let (fell_back, notes) = caps.notes();
    Ok(SurfaceOutput {
        complex: c,
        fell_back,
        notes,
    })
}
