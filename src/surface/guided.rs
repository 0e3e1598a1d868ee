//! Guided subdivision surfaces of whole meshes: bi-3 patches on regular faces and, at every
//! extraordinary vertex of valence 3 and 5..16, `K` guided rings of `3 n` bi-5 or bi-6 patches
//! and the G^1 bi-6 cap of [`crate::schemes::guided::cap`] (or an open hole). The macro-patch
//! variants write each ring patch as its 2 x 2 bi-4 or 3 x 3 bi-3 pieces and have no cap.
//!
//! Built on the adaptive loop of [`super::cc`] exactly like EG and QAS+: vertices whose c-net is
//! clean get a guided cap at the current level; the others are refined by one Catmull-Clark step
//! first. With the contraction 1/2 ([`ChiKind::Half`]) the QAS+ characteristic map is used,
//! which exists for valences 5..10; other valences fall back to Catmull-Clark's map (a note
//! names them) or stop with an error, as the user chooses.

use super::cc::{CapBuilder, CcComplexOptions, adaptive_complex};
use super::eg::{CapOutput, Fallback};
use super::{Element, PatchComplex, Provenance};
use crate::bezier::BezierPatch;
use crate::error::{Error, Result};
use crate::geom::Point;
use crate::mesh::PolyMesh;
use crate::schemes::guided::cap::CapTables;
use crate::schemes::guided::chi::ChiKind;
use crate::schemes::guided::rings::{Guided, GuidedOptions};
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
    notes: Mutex<Vec<String>>,
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

fn describe(e: Element) -> String {
    match e {
        Element::Vertex(v) => format!("vertex {v}"),
        Element::Face(f) => format!("the centre of face {f}"),
    }
}

impl CapBuilder for GuidedCaps {
    fn accepts(&self, n: usize, element: Element) -> Result<bool> {
        if n == 4 || n > MAX_VALENCE {
            if n > MAX_VALENCE && self.opts.fallback == Fallback::Error {
                return Err(Error::Unsupported(format!(
                    "{} has valence {n}: guided subdivision is tabulated for valences 3..{MAX_VALENCE}; use --fallback catmull-clark",
                    describe(element)
                )));
            }
            if n > MAX_VALENCE {
                let mut notes = self.notes.lock().expect("no poisoning");
                let msg = format!(
                    "{} (valence {n}) is beyond guided subdivision's valences 3..{MAX_VALENCE}: Catmull-Clark rings and fill there",
                    describe(element)
                );
                if !notes.contains(&msg) {
                    notes.push(msg);
                }
            }
            return Ok(false);
        }
        if self.opts.scheme.chi == ChiKind::Half && !(5..=10).contains(&n) {
            if self.opts.fallback == Fallback::Error {
                return Err(Error::Unsupported(format!(
                    "{} has valence {n}: the contraction 1/2 uses the QAS+ characteristic map, tabulated for valences 5..10; use --fallback catmull-clark",
                    describe(element)
                )));
            }
            let mut notes = self.notes.lock().expect("no poisoning");
            let msg = format!(
                "{} (valence {n}): no characteristic map with lambda = 1/2 (QAS+'s is tabulated for 5..10): Catmull-Clark's chi and lambda there",
                describe(element)
            );
            if !notes.contains(&msg) {
                notes.push(msg);
            }
        }
        Ok(true)
    }

    fn build(
        &self,
        cnet: &[Point],
        n: usize,
        element: Element,
        first_ring: u32,
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
        if mk.is_some() && self.opts.cap {
            let mut notes = self.notes.lock().expect("no poisoning");
            let msg = "the macro-patch variants have no cap (the paper's bi-3 / bi-4 caps are in the lost Fig. 17): the hole inside the last ring stays open".to_string();
            if !notes.contains(&msg) {
                notes.push(msg);
            }
        }
        let (rings, guide) = t.scheme.rings(cnet, self.opts.rings)?;
        for (l, ring) in rings.iter().enumerate() {
            for (k, p) in ring.iter().enumerate() {
                let prov = Provenance::Ring {
                    element,
                    ring: first_ring + l as u32,
                    sector: (k / 3) as u32,
                };
                match mk {
                    None => out.push(BezierPatch::new(d, d, p.clone()), prov),
                    Some(kind) => {
                        let e = kind.degree();
                        for piece in kind.pieces_of(p) {
                            out.push(BezierPatch::new(e, e, piece), prov);
                        }
                    }
                }
            }
        }
        if let (Some(cap), Some(last)) = (&t.cap, rings.last()) {
            for (s, p) in cap.cap(&guide, last).into_iter().enumerate() {
                out.push(
                    BezierPatch::new(6, 6, p),
                    Provenance::Cap {
                        element,
                        sector: s as u32,
                    },
                );
            }
        }
        Ok(())
    }
}

/// The guided surface of a net as a patch complex, with notes for the user.
pub fn guided_complex(
    mesh: &PolyMesh,
    opts: GuidedComplexOptions,
    progress: impl FnMut(usize),
) -> Result<CapOutput> {
    let caps = GuidedCaps {
        opts,
        cache: Mutex::new(HashMap::new()),
        notes: Mutex::new(Vec::new()),
    };
    let complex = adaptive_complex(
        mesh,
        CcComplexOptions {
            rings: opts.rings,
            fill: opts.cap,
        },
        Some(&caps),
        progress,
    )?;
    Ok(CapOutput {
        complex,
        fell_back: Vec::new(),
        notes: caps.notes.into_inner().expect("no poisoning"),
    })
}

/// The scheme options named by a command-line scheme name: `guided-bi5`, `guided-bi6`,
/// `guided-bi4-macro`, `guided-bi3-macro` (Section 6.2, rings only), with the
/// suffixes `-half` (contraction 1/2, the QAS+ characteristic map) and `-g4` / `-g3` (guide of
/// degree bi-4 / bi-3, Section 6.1), in that order (`guided-bi6-g4-half`).
pub fn parse_scheme(name: &str) -> Option<GuidedOptions> {
    use crate::schemes::guided::guide::GuideDegree;
    use crate::schemes::guided::rings::RingDegree;
    let rest = name.strip_prefix("guided-")?;
    let (ring, mut rest) = if let Some(r) = rest.strip_prefix("bi5") {
        (RingDegree::Bi5, r)
    } else if let Some(r) = rest.strip_prefix("bi6") {
        (RingDegree::Bi6, r)
    } else if let Some(r) = rest.strip_prefix("bi4-macro") {
        (RingDegree::Bi4Macro, r)
    } else if let Some(r) = rest.strip_prefix("bi3-macro") {
        (RingDegree::Bi3Macro, r)
    } else {
        return None;
    };
    let mut o = GuidedOptions {
        ring,
        ..GuidedOptions::default()
    };
    if let Some(r) = rest.strip_prefix("-g4") {
        o.guide = GuideDegree::Bi4;
        rest = r;
    } else if let Some(r) = rest.strip_prefix("-g3") {
        o.guide = GuideDegree::Bi3;
        rest = r;
    }
    if let Some(r) = rest.strip_prefix("-half") {
        o.chi = ChiKind::Half;
        rest = r;
    }
    rest.is_empty().then_some(o)
}

/// The scheme name that the command-line option `--lambda` selects: for a guided scheme,
/// `lambda = 0.5` appends `-half` (the QAS+ characteristic map, Section 6.3 of the paper); no
/// `--lambda` keeps the name (Catmull-Clark's chi and lambda, the paper's default). Any other
/// value, or `--lambda` with a scheme that is not guided, is an error naming the way out.
pub fn scheme_with_lambda(name: &str, lambda: Option<f64>) -> Result<String> {
    let Some(l) = lambda else {
        return Ok(name.to_string());
    };
    let Some(o) = parse_scheme(name) else {
        return Err(Error::InvalidArgument(format!(
            "--lambda {l}: only the guided schemes (guided-bi5, guided-bi6, ...) take a contraction; '{name}' has its own"
        )));
    };
    if (l - 0.5).abs() > 1e-12 {
        return Err(Error::InvalidArgument(format!(
            "--lambda {l}: guided subdivision offers lambda = 0.5 (QAS+'s characteristic map, valences 5..10) or, without --lambda, Catmull-Clark's lambda"
        )));
    }
    Ok(if o.chi == ChiKind::Half {
        name.to_string()
    } else {
        format!("{name}-half")
    })
}
