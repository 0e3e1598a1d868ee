//! Guided subdivision surfaces of whole meshes: bi-3 patches on regular faces and, at every
//! extraordinary vertex of valence 3 and 5..16, `K` guided rings of `3 n` bi-5 or bi-6 patches
//! and the G^1 bi-6 cap of [`crate::schemes::guided::cap`] (or an open hole). The macro-patch
//! variants write each ring patch as its 2 x 2 bi-4 or 3 x 3 bi-3 pieces and close the hole
//! with the split G^1 cap of [`crate::bezier::g1`] (2 x 2 or 3 x 3 pieces per sector, C^1 to
//! the last ring piece by piece, at the guide's central point in its tangent plane; see
//! `macro_cap`); `--no-fill` leaves the hole open.
//!
//! Built on Catmull-Clark's adaptive loop ([`crate::schemes::catmull_clark::surface`]) exactly
//! like EG and QAS+: vertices whose c-net is
//! clean get a guided cap at the current level; the others are refined by one Catmull-Clark step
//! first. With the contraction 1/2 ([`ChiKind::Half`]) the QAS+ characteristic map is used,
//! which exists for valences 5..10; other valences fall back to Catmull-Clark's map (a note
//! names them) or stop with an error, as the user chooses.
//!
//! # Parameter domain (evaluation)
//!
//! The rings live in the c-net chart of each sector ([`super::rings`]): the sector's face is
//! `[0, 1]^2` with the vertex at `(0, 0)` and `u` along spoke `s` (the frame the host gives,
//! [`CapBuilder::build`]), and ring `l` (0-based) is at scale `2^-l`: `A` on
//! `[1/2, 1] x [0, 1/2]` of `[0, 2^-l]^2`, `B` on `[1/2, 1]^2`, `C` on `[0, 1/2] x [1/2, 1]`,
//! local `(s, t)` the chart's, scaled (the prolongation relations of [`super::rings`] say so:
//! `A`'s point `(s, t)` is the previous `A`'s `((s - 1)/2, t/2)`). The cap covers `[0, 2^-K]^2`,
//! local `(u, v)` = chart / `2^-K`, `(0, 0)` at the centre ([`super::cap`]). The scale is the
//! chart's whatever the characteristic map's `lambda`. Each patch records that square as its
//! domain, so `fairsub eval` works for bi-5 and bi-6. The macro-patch variants write each ring
//! patch's square as its pieces (`piece (a, b)`, `a` along the patch's `u`): `guided-bi4-macro`'s
//! 2 x 2 bi-4 pieces cover the square's dyadic quarters `[a/2, (a+1)/2] x [b/2, (b+1)/2]`
//! (one level deeper), `guided-bi3-macro`'s 3 x 3 bi-3 pieces its thirds
//! `[a/3, (a+1)/3] x [b/3, (b+1)/3]` (a level in thirds, [`Domain::third`]); each piece's own
//! `(u, v)` is its cell's, scaled, axes along the chart's. Their split G^1 caps
//! ([`crate::bezier::g1`], `Layout::Split(m)`) cover `[0, 2^-K]^2` from the centre as an
//! `m x m` grid of pieces in the same way (piece `(a, b)` on `[a/m, (a+1)/m] x [b/m, (b+1)/m]`
//! of the cap's square, `(0, 0)` at the centre), so the bi-3 caps' pieces are thirds too
//! (`piece_cell`).

use super::cap::CapTables;
use super::chi::ChiKind;
use super::macro_patch::MacroKind;
use super::rings::{Guided, GuidedOptions};
use crate::bezier::BezierPatch;
use crate::bezier::complex::{CapStep, Domain, PatchComplex, Provenance};
use crate::bezier::g1::ring::{cap_step, split_sector};
use crate::bezier::g1::{CapOptions, Hole};
use crate::error::{Error, Result};
use crate::geom::Point;
use crate::geom::sub;
use crate::host::caps::{CapBuilder, CapNotes, RING_CELLS, describe, sector_square};
use crate::host::{ComplexOptions, Fallback, SurfaceOutput};
use crate::mesh::{Element, PolyMesh};
use crate::schemes::catmull_clark::surface::capped_complex;
use crate::schemes::options::ids;
use std::collections::HashMap;
use std::sync::{Arc, Mutex};

/// Largest valence with guided rules (the tables are computed, not printed; beyond 16 the
/// c-net fit grows ill-conditioned and is not tested).
pub const MAX_VALENCE: usize = 16;

/// Options of [`guided_complex`].
#[derive(Debug, Clone, Copy)]
pub struct GuidedComplexOptions {
    /// Rings per cap.
    pub rings: usize,
    /// Close each hole with the G^1 bi-6 cap.
    pub cap: bool,
    /// The scheme's options (ring degree, guide degree, chi, fit).
    pub scheme: GuidedOptions,
    /// What to do where the chosen chi has no table (contraction 1/2 outside 5..10).
    pub fallback: Fallback,
}

impl Default for GuidedComplexOptions {
    fn default() -> Self {
        GuidedComplexOptions {
            rings: 6,
            cap: true,
            scheme: GuidedOptions::default(),
            fallback: Fallback::CatmullClark,
        }
    }
}

struct Tables {
    scheme: Guided,
    cap: Option<CapTables>,
}

struct GuidedCaps {
    opts: GuidedComplexOptions,
    cache: Mutex<HashMap<usize, Arc<Tables>>>,
    notes: CapNotes,
}

impl GuidedCaps {
    fn options_for(&self, n: usize) -> GuidedOptions {
        let mut o = self.opts.scheme;
        if o.chi == ChiKind::Half && !(5..=10).contains(&n) {
            o.chi = ChiKind::CatmullClark;
        }
        o
    }

    fn tables(&self, n: usize) -> Result<Arc<Tables>> {
        if let Some(t) = self.cache.lock().expect("no poisoning").get(&n) {
            return Ok(t.clone());
        }
        let scheme = Guided::new(n, self.options_for(n))?;
        let cap = if self.opts.cap && scheme.opts.ring.macro_kind().is_none() {
            Some(CapTables::new(
                n,
                scheme.degree(),
                scheme.space.degree,
                &scheme.chi,
            )?)
        } else {
            None
        };
        let t = Arc::new(Tables { scheme, cap });
        self.cache
            .lock()
            .expect("no poisoning")
            .insert(n, t.clone());
        Ok(t)
    }
}

impl CapBuilder for GuidedCaps {
    fn accepts(&self, n: usize, element: Element) -> Result<bool> {
        // outside the guided tables (a valence-2 vertex has no guide: its Fourier modes need
        // n >= 3): Catmull-Clark's rings and G^1 cap there, as EG and QAS+ do
        if !(3..=MAX_VALENCE).contains(&n) {
            let (side, limit) = if n < 3 {
                ("below", "starts at valence 3".to_string())
            } else {
                (
                    "beyond",
                    format!("is tabulated for valences 3..{MAX_VALENCE}"),
                )
            };
            if self.opts.fallback == Fallback::Error {
                return Err(Error::UnsupportedValence {
                    valence: n,
                    msg: format!(
                        "{} has valence {n}: guided subdivision {limit}; use --fallback {}",
                        describe(element),
                        ids::CATMULL_CLARK
                    ),
                });
            }
            self.notes.note(format!(
                "{} (valence {n}) is {side} guided subdivision's valences 3..{MAX_VALENCE}: Catmull-Clark rings and cap there",
                describe(element)
            ));
            return Ok(false);
        }
        if n == 4 {
            return Ok(false);
        }
        if self.opts.scheme.chi == ChiKind::Half && !(5..=10).contains(&n) {
            if self.opts.fallback == Fallback::Error {
                return Err(Error::UnsupportedValence {
                    valence: n,
                    msg: format!(
                        "{} has valence {n}: the contraction 1/2 uses the QAS+ characteristic map, tabulated for valences 5..10; use --fallback {}",
                        describe(element),
                        ids::CATMULL_CLARK
                    ),
                });
            }
            self.notes.note(format!(
                "{} (valence {n}): no characteristic map with lambda = 1/2 (QAS+'s is tabulated for 5..10): Catmull-Clark's chi and lambda there",
                describe(element)
            ));
        }
        Ok(true)
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
        if self.opts.cap && self.opts.rings == 0 {
            return Err(Error::InvalidArgument(
                "the guided cap joins the last ring: at least one ring is required (--rings 1)"
                    .into(),
            ));
        }
        let t = self.tables(n)?;
        let d = t.scheme.degree();
        let mk = t.scheme.opts.ring.macro_kind();
        let (rings, guide) = t.scheme.rings(cnet, self.opts.rings)?;
        for (l, ring) in rings.iter().enumerate() {
            for (k, p) in ring.iter().enumerate() {
                let prov = Provenance::Ring {
                    element,
                    ring: first_ring + l as u32,
                    sector: (k / 3) as u32,
                };
                match mk {
                    None => {
                        let (cu, cv) = RING_CELLS[k % 3];
                        let domain = sector_square(sectors, k / 3, l as u8 + 1, cu, cv);
                        out.push_in(BezierPatch::new(d, d, p.clone()), prov, domain);
                    }
                    Some(kind) => {
                        let e = kind.degree();
                        let (cu, cv) = RING_CELLS[k % 3];
                        let domain = sector_square(sectors, k / 3, l as u8 + 1, cu, cv);
                        for (i, piece) in kind.pieces_of(p).into_iter().enumerate() {
                            let cell = piece_cell(kind, domain, i);
                            out.push_in(BezierPatch::new(e, e, piece), prov, cell);
                        }
                    }
                }
            }
        }
        if let (Some(kind), true, Some(last)) = (mk, self.opts.cap, rings.last()) {
            let first = out.len();
            match macro_cap(kind, last, &guide, &t.scheme, first) {
                Ok((patches, step)) => {
                    out.caps.push(step);
                    let per = kind.pieces() * kind.pieces();
                    let level = rings.len() as u8;
                    for (k, p) in patches.into_iter().enumerate() {
                        let s = k / per;
                        let prov = Provenance::Cap {
                            element,
                            sector: s as u32,
                        };
                        let square = sector_square(sectors, s, level, 0, 0);
                        out.push_in(p, prov, piece_cell(kind, square, k % per));
                    }
                }
                Err(e) => self.notes.note(format!(
                    "{} (valence {n}): no G^1 cap, the hole inside the last ring stays open ({e})",
                    describe(element)
                )),
            }
        }
        if let (Some(cap), Some(last)) = (&t.cap, rings.last()) {
            let level = rings.len() as u8;
            for (s, p) in cap.cap(&guide, last).into_iter().enumerate() {
                out.push_in(
                    BezierPatch::new(6, 6, p),
                    Provenance::Cap {
                        element,
                        sector: s as u32,
                    },
                    sector_square(sectors, s, level, 0, 0),
                );
            }
        }
        Ok(())
    }
}

/// The cell of piece `i` (row-major, `i = a m + b`, `a` along the first parameter: the order
/// of [`MacroKind::pieces_of`] and of the split cap's pieces) of a macro patch or split cap
/// sector covering `square` (a cell with the patch's `(0, 0)` at its corner `rot`): the 2 x 2
/// quarters ([`Domain::square`]) of the bi-4 variant, the 3 x 3 thirds ([`Domain::third`]) of
/// the bi-3 one, each piece's own `(u, v)` the square's scaled.
fn piece_cell(kind: MacroKind, square: Domain, i: usize) -> Domain {
    let m = kind.pieces();
    let (a, b) = (i / m, i % m);
    match kind {
        MacroKind::Bi4 => square.square(1, a as u32, b as u32),
        MacroKind::Bi3 => square.third(a as u8, b as u8),
    }
}

/// The split G^1 cap of a macro-patch variant ([`crate::bezier::g1`],
/// [`crate::bezier::g1::Layout::Split`]`(m)`, `m` the pieces per ring patch side): the hole's
/// sides are read off the last ring's pieces (`A`'s pieces `(0, b)` beside the side `u = 1`, `C`'s
/// pieces `(a, 0)` beside `v = 1`), centred at the guide's central point (the rings' limit point)
/// in the guide's tangent plane there (`g^0_10 - g^0_00`, `g^0_01 - g^0_00`); `first` is the index
/// of the cap's first patch.
fn macro_cap(
    kind: MacroKind,
    last: &[Vec<Point>],
    guide: &nalgebra::DMatrix<f64>,
    scheme: &Guided,
    first: usize,
) -> Result<(Vec<BezierPatch>, CapStep)> {
    let (e, m, n) = (kind.degree(), kind.pieces(), scheme.n);
    let pieces = |p: &[Point]| -> Vec<BezierPatch> {
        kind.pieces_of(p)
            .into_iter()
            .map(|c| BezierPatch::new(e, e, c))
            .collect()
    };
    let sectors = (0..n)
        .map(|s| {
            let (a, c) = (pieces(&last[3 * s]), pieces(&last[3 * s + 2]));
            let a_side: Vec<BezierPatch> = (0..m).map(|b| a[b].clone()).collect();
            let b_side: Vec<BezierPatch> = (0..m).map(|k| c[k * m].clone()).collect();
            split_sector(&a_side, &b_side)
        })
        .collect();
    let row = |i: usize, j: usize| -> Point {
        let r = scheme.space.coeff(0, i, j);
        [guide[(r, 0)], guide[(r, 1)], guide[(r, 2)]]
    };
    let centre = row(0, 0);
    let plane = [sub(row(1, 0), centre), sub(row(0, 1), centre)];
    cap_step(
        Hole::untangented(centre, sectors),
        plane,
        CapOptions::default(),
        first,
    )
}

/// The guided surface of a net as a patch complex, with notes for the user.
pub fn guided_complex(
    mesh: &PolyMesh,
    opts: GuidedComplexOptions,
    mut progress: impl FnMut(usize),
) -> Result<SurfaceOutput> {
    let caps = GuidedCaps {
        opts,
        cache: Mutex::new(HashMap::new()),
        notes: CapNotes::default(),
    };
    let complex = capped_complex(
        mesh,
        ComplexOptions {
            rings: opts.rings,
            fill: opts.cap,
        },
        &caps,
        &mut progress,
    )?;
    let (_, notes) = caps.notes.finish("");
    Ok(SurfaceOutput {
        complex,
        fell_back: Vec::new(),
        notes,
    })
}
