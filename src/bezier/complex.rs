//! Patch complexes: the exact piecewise-polynomial surfaces fairsub produces.
//!
//! A [`PatchComplex`] holds the Bezier patches of a whole surface, each tagged with its
//! [`Provenance`] (regular region, ring `k` of an extraordinary element, cap / fill), so writers
//! can group them, the renderer can colour them and analysis can report where a defect sits.
//! Where the adaptive host knows it, each patch also has the [`Domain`] of its input face that it
//! covers, for evaluation at `(face, u, v)`.

use super::BezierPatch;
pub use super::domain::{Domain, Piece};
use super::g1::{CapOptions, Hole};
use crate::geom::Point;
use crate::mesh::Element;
use serde::Serialize;

/// Where a patch comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Provenance {
    /// A patch of a regular region of the input net (`face` numbers the input face it lies in,
    /// when known).
    Regular {
        /// Input face the patch lies in.
        face: u32,
    },
    /// A patch of ring `ring` (1 = outermost) around an extraordinary element.
    Ring {
        /// The extraordinary element (vertex or facet of the input net).
        element: Element,
        /// Ring index, 1-based.
        ring: u32,
        /// Sector of the element the patch lies in.
        sector: u32,
    },
    /// A patch of the cap or fill closing the hole left inside the last ring.
    Cap {
        /// The extraordinary element.
        element: Element,
        /// Sector of the element the patch lies in.
        sector: u32,
    },
    /// A patch of unknown origin (read from a file).
    Unknown,
}

impl Provenance {
    /// A short group name used by writers (`regular`, `ring3`, `cap`, ...).
    pub fn group_name(&self) -> String {
        match self {
            Provenance::Regular { .. } => "regular".to_string(),
            Provenance::Ring { ring, .. } => format!("ring{ring}"),
            Provenance::Cap { .. } => "cap".to_string(),
            Provenance::Unknown => "patches".to_string(),
        }
    }
}

/// The patches of a surface with their provenance.
#[derive(Debug, Clone, Default)]
pub struct PatchComplex {
    /// The patches.
    pub patches: Vec<BezierPatch>,
    /// Provenance of each patch (same length as `patches`).
    pub provenance: Vec<Provenance>,
    /// Sides that lie on a sharp feature (an infinitely sharp crease inside the surface), as
    /// `(patch, mask)` with bit [`Side::index`](super::Side::index) set per side; `check`
    /// reports the joins along them apart (sharp joins are C^0, not smooth).
    pub sharp_sides: Vec<(u32, u8)>,
    /// The input-face domain of each patch where known (may be shorter than `patches`: the
    /// missing ones are unknown; see [`PatchComplex::domain`]).
    pub domains: Vec<Option<Domain>>,
    /// Patches that cover parts of several cells (a dual scheme's patch of an input vertex
    /// covers a quarter of each face around it): one [`Piece`] per part, in addition to (and
    /// instead of) `domains`.
    pub pieces: Vec<Piece>,
    /// The G^1 caps among the patches, with the data they were computed from: the one step of
    /// a construction that is not linear in the control points (its tangent plane), which a
    /// patch stencil table ([`crate::surface::table`]) repeats instead of tabulating.
    pub caps: Vec<CapStep>,
    /// Elements whose hole no G^1 cap closes although the scheme caps holes of its kind, with
    /// the reason (a valence below 3 or above the largest cap, ring data that are not
    /// C^1-compatible, ...): the scheme's C^0 fill closes them (`--no-fill` leaves them open).
    /// [`crate::surface::build`] turns them into a note for the user.
    pub uncapped: Vec<(Element, String)>,
}

/// Patches `first .. first + count` of a complex are the G^1 cap
/// ([`crate::bezier::g1::ring::cap_in_plane`]) of `hole` (its tangents unset) in the plane
/// spanned by `plane` (normal `plane[0] x plane[1]`), with `options`. Everything in the step's
/// data is a linear function of the control points; the cap is not (it projects onto the
/// plane).
#[derive(Debug, Clone, PartialEq)]
pub struct CapStep {
    /// The first cap patch.
    pub first: u32,
    /// Number of the cap's patches in the complex: one per sector, or one per sector of
    /// `kept`.
    pub count: u32,
    /// The sectors whose patches the complex holds, in order, when it holds only some of them
    /// (`None`: all): a complex that left out the patches over some faces
    /// ([`PatchComplex::retain`]). The cap is built whole and these sectors kept.
    pub kept: Option<Vec<u32>>,
    /// The hole: centre and ring segments (tangents unset).
    pub hole: Hole,
    /// Two vectors spanning the limit tangent plane.
    pub plane: [Point; 2],
    /// The cap's options.
    pub options: CapOptions,
}

impl PatchComplex {
    /// An empty complex.
    pub fn new() -> Self {
        Self::default()
    }

    /// Moves the patches from `first` on and the holes of the cap steps from `first_cap` on
    /// by `by` (a construction made about a local origin, put back in place).
    pub fn translate_from(&mut self, first: usize, first_cap: usize, by: Point) {
        for p in &mut self.patches[first..] {
            for q in &mut p.cps {
                *q = crate::geom::add(*q, by);
            }
        }
        for step in &mut self.caps[first_cap..] {
            step.hole.translate(by);
        }
    }

    /// Adds a patch.
    pub fn push(&mut self, patch: BezierPatch, provenance: Provenance) {
        self.patches.push(patch);
        self.provenance.push(provenance);
    }

    /// Adds a patch covering `domain` of its input face.
    pub fn push_in(&mut self, patch: BezierPatch, provenance: Provenance, domain: Domain) {
        self.push(patch, provenance);
        self.set_domain(self.len() - 1, domain);
    }

    /// Records that patch `i` covers `domain` (ignored when the domain is untracked).
    pub fn set_domain(&mut self, i: usize, domain: Domain) {
        if !domain.is_tracked() {
            return;
        }
        if self.domains.len() <= i {
            self.domains.resize(i + 1, None);
        }
        self.domains[i] = Some(domain);
    }

    /// Records that the part `window` of patch `i` covers `domain` (ignored when the domain
    /// is untracked).
    pub fn push_piece(&mut self, piece: Piece) {
        if piece.domain.is_tracked() {
            self.pieces.push(piece);
        }
    }

    /// The input-face domain of patch `i`, if known.
    pub fn domain(&self, i: usize) -> Option<Domain> {
        self.domains.get(i).copied().flatten()
    }

    /// Number of patches.
    pub fn len(&self) -> usize {
        self.patches.len()
    }

    /// Whether the complex has no patches.
    pub fn is_empty(&self) -> bool {
        self.patches.is_empty()
    }

    /// Appends all patches of another complex.
    pub fn extend(&mut self, other: PatchComplex) {
        let first = self.len();
        for (i, d) in other.domains.into_iter().enumerate() {
            if let Some(d) = d {
                self.set_domain(first + i, d);
            }
        }
        let base = self.patches.len() as u32;
        self.pieces.extend(other.pieces.into_iter().map(|p| Piece {
            patch: p.patch + base,
            ..p
        }));
        self.caps.extend(other.caps.into_iter().map(|c| CapStep {
            first: c.first + base,
            ..c
        }));
        self.patches.extend(other.patches);
        self.provenance.extend(other.provenance);
        self.sharp_sides
            .extend(other.sharp_sides.into_iter().map(|(p, m)| (p + base, m)));
        self.uncapped.extend(other.uncapped);
    }

    /// The complex of the patches `keep` accepts, in order, with their domains, pieces and
    /// sharp sides, the cap steps of the kept cap patches (a cap partly kept records its kept
    /// sectors, [`CapStep::kept`]), and the uncapped elements (a construction that puts
    /// another's patches in place of some of its own, or leaves out the patches over some
    /// faces).
    pub fn retain(&self, keep: impl Fn(usize) -> bool) -> PatchComplex {
        let mut to = vec![None; self.len()];
        let mut out = PatchComplex::new();
        for (i, slot) in to.iter_mut().enumerate() {
            if keep(i) {
                *slot = Some(out.len() as u32);
                out.push(self.patches[i].clone(), self.provenance[i]);
                if let Some(d) = self.domain(i) {
                    out.set_domain(out.len() - 1, d);
                }
            }
        }
        out.pieces = self
            .pieces
            .iter()
            .filter_map(|p| {
                Some(Piece {
                    patch: to[p.patch as usize]?,
                    ..*p
                })
            })
            .collect();
        out.sharp_sides = self
            .sharp_sides
            .iter()
            .filter_map(|&(p, m)| Some((to[p as usize]?, m)))
            .collect();
        out.caps = self
            .caps
            .iter()
            .filter_map(|c| {
                // the kept patches of a cap stay consecutive
                let run: Vec<u32> = (0..c.count)
                    .filter(|&i| to[(c.first + i) as usize].is_some())
                    .collect();
                let first = to[(c.first + *run.first()?) as usize]?;
                let kept = if run.len() == c.count as usize {
                    c.kept.clone()
                } else {
                    Some(match &c.kept {
                        Some(k) => run.iter().map(|&i| k[i as usize]).collect(),
                        None => run.clone(),
                    })
                };
                Some(CapStep {
                    first,
                    count: run.len() as u32,
                    kept,
                    ..c.clone()
                })
            })
            .collect();
        out.uncapped = self.uncapped.clone();
        out
    }

    /// Moves every tracked domain from face `f` of the net the complex was built on to face
    /// `faces[f]` of another net with the same faces (a net whose faces were kept from it in
    /// order, such as a net without its hole faces); a face past `faces` leaves its domain
    /// untracked.
    pub fn renumber_faces(&mut self, faces: &[usize]) {
        let moved = |d: Domain| match faces.get(d.face as usize) {
            Some(&f) if d.is_tracked() => Domain {
                face: f as u32,
                ..d
            },
            _ => Domain::UNTRACKED,
        };
        for d in self.domains.iter_mut().flatten() {
            *d = moved(*d);
        }
        for p in &mut self.pieces {
            p.domain = moved(p.domain);
        }
    }

    /// Marks side `side` (its [`Side::index`](super::Side::index)) of patch `patch` as lying
    /// on a sharp feature.
    pub fn mark_sharp(&mut self, patch: usize, side: usize) {
        match self.sharp_sides.last_mut() {
            Some((p, m)) if *p == patch as u32 => *m |= 1 << side,
            _ => self.sharp_sides.push((patch as u32, 1 << side)),
        }
    }

    /// The sharp-side mask of every patch (bit [`Side::index`](super::Side::index) per side).
    pub fn sharp_masks(&self) -> Vec<u8> {
        let mut out = vec![0u8; self.patches.len()];
        for &(p, m) in &self.sharp_sides {
            if let Some(x) = out.get_mut(p as usize) {
                *x |= m;
            }
        }
        out
    }
}
