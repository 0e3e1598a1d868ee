//! The preparation stage shared by every scheme: what a scheme's rules need of a net, declared
//! in its [`super::Descriptor`] ([`super::Descriptor::preparation`]),
//! and the smallest documented step that gives it, applied here (or, where the scheme's own
//! construction takes that step locally and exactly, named here and taken there).
//!
//! A scheme's rules take some nets and not others: TPS refines quad nets without interior
//! vertices of valence 2 or extraordinary boundary vertices; the dual schemes' patches need
//! every interior vertex of valence 3 or more; the mixed bi-2 net needs its extraordinary
//! elements separated by regular vertices. Each [`Requirement`] pairs a [`Need`] with the
//! [`Step`] that meets it. [`prepare`] tests the needs in the declared order on the net, applies
//! the first unmet need's whole-net steps ([`NetStep`]), and starts over on the prepared net,
//! until every need is met (or a step no longer helps: the scheme then refuses with its own
//! message). What it did is a [`Prepared`]: the prepared net, one note per step naming the
//! step and the elements it was for, and the parameter map from the prepared net's faces to
//! the input faces ([`map`]), through which [`Prepared::lift`] moves the domains of a complex
//! built on the prepared net into the input faces, so evaluation at `(face, u, v)` keeps
//! addressing the user's faces. Every step is linear in the points, so a patch table read off
//! the construction from the input net (`crate::surface::table`) holds the step's stencils.
//!
//! [`Mode::None`] (`--prepare none`) applies nothing: the scheme refuses such nets with its
//! own message, as before the preparation stage existed.
//!
//! # The steps and why they are the smallest
//!
//! * **One Catmull-Clark step** ([`NetStep::CatmullClark`]) makes every face a quad: TPS and
//!   adjustable TPS on nets with triangles or n-gons. No local step can: splitting only the
//!   faces that are not quads puts a new point on the edges they share with quads, which then
//!   become pentagons. The step carries OpenSubdiv's sharp features as Catmull-Clark refines
//!   them (an infinitely sharp crease stays one, a semi-sharp one loses one unit of sharpness).
//! * **One step of the scheme's own dual refinement** ([`NetStep::DooSabin`],
//!   [`NetStep::DooSabinCc`], [`NetStep::Pgs`]) removes interior vertices of valence 2: the
//!   step makes a face of every vertex, and the 2-sided face of such a vertex is left out
//!   (its two neighbouring faces share the edge instead; see `crate::schemes::doo_sabin`), so
//!   the refined net has none. A Catmull-Clark step would not do: it keeps a valence-2 vertex
//!   at valence 2. The step is the scheme's own refinement, so the surface is the scheme's
//!   surface of the input net, refined once.
//! * **One Doo-Sabin step, then one Catmull-Clark step** for TPS at interior vertices of
//!   valence 2 and at extraordinary boundary vertices: no primal step changes a vertex's
//!   valence or moves it off the boundary, and TPS (primal, ternary) has no rules at either.
//!   The dual step removes the valence-2 vertices (above) and turns a boundary vertex with `k`
//!   faces into a `(k + 2)`-sided face whose boundary vertices have two faces each (the dual
//!   schemes' boundary rules); the Catmull-Clark step then makes that face `k + 2` quads around
//!   an interior vertex of valence `k + 2`. Every boundary vertex of the result is regular.
//! * **Spending semi-sharp features** (TPS, adjustable TPS, the mixed and polar nets, whose
//!   element rings have no step that spends sharpness) is taken by the schemes' own
//!   constructions ([`Step::Own`]): the family's dual step with the dual crease rules, near the
//!   features only (`crate::schemes::bi2::surface`: PGS's construction for the mixed and polar
//!   nets, the same surface as whole-net PGS steps, a unit test here; Doo-Sabin's beside TPS's
//!   elements for TPS).
//! * **Separating extraordinary elements** (`bi2-mixed`, `polar-bi2`) is taken by the bi-2
//!   family's own constructions, as PGS and TPS take it for themselves
//!   ([`Step::Own`], documented in `crate::schemes::bi2::surface`).
//!
//! Sharp features. The Catmull-Clark step carries every tag; the dual steps carry boundaries,
//! kept corners (infinitely sharp boundary corners) and creases (the dual crease rules, as the
//! dual schemes' own levels refine them) but no hole. For patches on
//! a net that tags only infinitely sharp features, the needs are tested on the net cut along
//! its creases with its hole faces removed (`crate::schemes::doo_sabin::sharp`, as the bi-2
//! schemes' patches cut it themselves): where that net needs a whole-net step, the cut is the
//! first step (its faces are the input's faces minus the holes, the map picks them) and the
//! steps follow on the cut net, whose crease sides stay one curve (both sides refine the same
//! crease polygon); where it needs none, the net is given to the scheme uncut, which cuts it.
//! Nets with semi-sharp tags get the dual steps with the crease rules where those carry the
//! tags (Doo-Sabin, DS^CC and PGS at interior vertices of valence 2, TPS's Doo-Sabin step
//! there). Nets whose features no step carries or the cut refuses,
//! and nets refined whole (`--levels`) get no dual step: they are given to the scheme as they
//! are, with a note, and the scheme's own sharp-feature rules decide.

pub mod map;
mod semi;
mod steps;

use crate::error::Result;
use crate::mesh::{Element, PolyMesh};
use crate::schemes::descriptor::{Descriptor, Spec};
pub use crate::schemes::options::PrepareMode as Mode;
use serde::Serialize;

pub use crate::schemes::needs::{Need, NetStep, Purpose, Requirement, Step};
pub use map::ParamMap;

/// A step [`prepare`] applied (or found that the scheme will take itself), with the need it
/// met and the elements of the net it was applied to that were in the way.
#[derive(Debug, Clone, Serialize)]
pub struct Applied {
    /// The step in words.
    pub step: String,
    /// The need in words.
    pub need: String,
    /// The elements in the way (of the net the step was applied to), first ones only.
    pub elements: Vec<String>,
    /// How many elements were in the way.
    pub count: usize,
    /// Whether the step was applied here, is taken by the scheme, or could not be applied.
    pub kind: Kind,
    /// Whether the step is the cut along the net's creases that precedes the steps on a
    /// tagged net (its note is the cut's own).
    pub cut: bool,
}

/// What became of a step [`prepare`] found needed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Kind {
    /// Applied to the net here.
    Applied,
    /// Taken by the scheme's own construction ([`Step::Own`]), which notes it.
    Own,
    /// Not applied: the step does not carry the net's sharp-feature tags; the scheme gets the
    /// net as it is.
    Skipped,
}

impl Applied {
    /// The note of this step for scheme `name`.
    pub fn note(&self, name: &str) -> String {
        let more = self.count.saturating_sub(self.elements.len());
        let mut at = self.elements.join(", ");
        if more > 0 {
            at.push_str(&format!(" and {more} more"));
        }
        match self.kind {
            Kind::Applied if self.cut => format!(
                "prepared for {name}: the net is cut along its creases before the steps below, \
                 since {name} {} ({})",
                self.need, self.step
            ),
            Kind::Applied => format!(
                "prepared for {name}: {} first, since {name} {} ({at}); rings and levels count \
                 from the prepared net, and elements named below are the prepared net's",
                self.step, self.need
            ),
            Kind::Own => format!(
                "{name} {} ({at}): {} (taken by its own construction)",
                self.need, self.step
            ),
            Kind::Skipped => format!(
                "not prepared for {name}, which {} ({at}): {} does not carry the net's \
                 sharp-feature tags, so the net is given to {name} as it is",
                self.need, self.step
            ),
        }
    }
}

/// Elements a note names at most.
const NAMED: usize = 4;
/// Whole-net steps at most (a step that does not meet its need is not repeated forever).
const MAX_ROUNDS: usize = 4;

/// A net made ready for a scheme: the net its rules take, what was done, and where its faces
/// lie in the input faces.
#[derive(Debug, Clone)]
pub struct Prepared {
    /// The net the scheme's rules take (the input net when nothing was applied).
    pub mesh: PolyMesh,
    /// The whole-net steps applied, in order, and the steps the scheme takes itself.
    pub applied: Vec<Applied>,
    /// Where the prepared net's faces lie in the input faces (`None`: nothing applied).
    pub map: Option<ParamMap>,
}

impl Prepared {
    /// The input net itself.
    pub fn unchanged(mesh: &PolyMesh) -> Prepared {
        Prepared {
            mesh: mesh.clone(),
            applied: Vec::new(),
            map: None,
        }
    }

    /// Whether a whole-net step was applied.
    pub fn changed(&self) -> bool {
        self.map.is_some()
    }

    /// The notes of the applied steps for scheme `name` (the steps the scheme takes itself
    /// are noted by the scheme).
    pub fn notes(&self, name: &str) -> Vec<String> {
        self.applied
            .iter()
            .filter(|a| a.kind != Kind::Own)
            .map(|a| a.note(name))
            .collect()
    }

    /// Moves the face domains of a complex built on the prepared net into the input faces
    /// ([`map`]); nothing to do when no step was applied.
    pub fn lift(&self, complex: &mut crate::bezier::complex::PatchComplex) {
        if let Some(m) = &self.map {
            m.lift(&self.mesh, complex);
        }
    }
}

/// The elements of `mesh` where `need` fails.
fn unmet(need: &Need, mesh: &PolyMesh, spec: &Spec) -> Vec<Element> {
    let interior = |v: usize| {
        !mesh.is_boundary_vertex(v) && !mesh.is_nonmanifold_vertex(v) && mesh.valence(v) > 0
    };
    match need {
        Need::Quads => (0..mesh.num_faces())
            .filter(|&f| mesh.face_size(f) != 4)
            .map(|f| Element::Face(f as u32))
            .collect(),
        Need::NoInteriorValence2 => (0..mesh.num_vertices())
            .filter(|&v| interior(v) && mesh.valence(v) < 3)
            .map(|v| Element::Vertex(v as u32))
            .collect(),
        // a corner of one face that the boundary mode edge-only does not keep is not regular
        // either: the schemes' rules keep every corner
        Need::RegularBoundary => (0..mesh.num_vertices())
            .filter(|&v| {
                mesh.is_boundary_vertex(v)
                    && !mesh.is_nonmanifold_vertex(v)
                    && match mesh.vertex_faces(v).len() {
                        1 => !crate::schemes::doo_sabin::sharp::is_kept_corner(mesh, v),
                        // a kept corner (a crease end of a cut net) with two faces on one
                        // side: the rules keep corners of one face only
                        2 => crate::schemes::doo_sabin::sharp::is_tagged_corner(mesh, v),
                        _ => true,
                    }
            })
            .map(|v| Element::Vertex(v as u32))
            .collect(),
        // the ends of semi-sharp edges and the semi-sharp vertices
        Need::InfinitelySharpOnly => semi::semi_sharp_vertices(mesh)
            .into_iter()
            .map(Element::Vertex)
            .collect(),
        Need::IfSemiSharp(with, need) => {
            if crate::schemes::doo_sabin::sharp::has_semi_sharp(mesh) == *with {
                unmet(need, mesh, spec)
            } else {
                Vec::new()
            }
        }
        Need::Scheme { test, .. } => test(mesh, spec),
    }
}

/// How an element in the way is named: faces with their sides.
fn name_element(mesh: &PolyMesh, e: Element) -> String {
    match e {
        Element::Vertex(v) => format!("vertex {v}"),
        Element::Face(f) => format!("face {f} ({} sides)", mesh.face_size(f as usize)),
    }
}

/// The net `mesh` made ready for `spec`'s rules for `purpose` (see the [module](self)
/// documentation): nothing under [`Mode::None`] or when every need is met.
///
/// # Errors
/// Those of a step's refinement (a net too large for fairsub's indices, ...).
pub fn prepare(
    desc: &dyn Descriptor,
    spec: &Spec,
    mesh: &PolyMesh,
    purpose: Purpose,
) -> Result<Prepared> {
    let requirements = desc.preparation(spec, purpose);
    if spec.params.prepare == Mode::None || requirements.is_empty() {
        return Ok(Prepared::unchanged(mesh));
    }
    if purpose == Purpose::Patches
        && let Some(cut) = cut_first(spec, mesh)
    {
        // the steps on the cut net; nothing to do there: the scheme cuts the net itself,
        // unless hole faces were removed (the map then keeps addressing the input faces, and
        // the vertices of hole faces only are gone)
        let holes = mesh.extras().is_some_and(|e| !e.holes.is_empty());
        let prepared = run(
            &requirements,
            spec,
            cut.mesh,
            Some(cut.map),
            vec![cut.applied],
        )?;
        // without steps after the cut the scheme gets the net uncut and cuts it itself,
        // marking the crease sides
        if holes
            || prepared
                .applied
                .iter()
                .any(|a| a.kind == Kind::Applied && !a.cut)
        {
            return Ok(prepared);
        }
    }
    run(&requirements, spec, mesh.clone(), None, Vec::new())
}

/// A net cut along its infinitely sharp creases (hole faces removed) before the steps, with
/// the map from its faces to the input faces and the note of the cut.
struct CutFirst {
    mesh: PolyMesh,
    map: ParamMap,
    applied: Applied,
}

/// For patches on a net tagging sharp features: the net cut along its infinitely sharp creases,
/// as the dual schemes' patches cut it (`crate::schemes::doo_sabin::sharp`), so that the dual
/// steps, which carry the cut net's kept corners but no crease or hole, can be applied. `None`
/// where the net tags nothing, tags semi-sharp features (the steps would lose them) or has
/// features the cut refuses (the scheme refuses them with its own message).
fn cut_first(spec: &Spec, mesh: &PolyMesh) -> Option<CutFirst> {
    use crate::schemes::doo_sabin::sharp;
    if !has_features(mesh) || sharp::has_semi_sharp(mesh) {
        return None;
    }
    let cut = sharp::cut_along_creases(mesh, spec.name()).ok()??;
    Some(CutFirst {
        map: ParamMap::input(mesh).select(&sharp::kept_faces(mesh)),
        applied: Applied {
            step: cut.notes.join("; "),
            need: "needs its steps to carry the net's sharp features (the dual steps carry \
                   boundaries and kept corners, not creases or holes)"
                .to_string(),
            elements: Vec::new(),
            count: 0,
            kind: Kind::Applied,
            cut: true,
        },
        mesh: cut.mesh,
    })
}

/// [`prepare`]'s rounds on `net` (whose faces lie in the input faces as `map` says; `None`:
/// `net` is the input net), after the steps `applied` already.
fn run(
    requirements: &[Requirement],
    spec: &Spec,
    mut net: PolyMesh,
    mut map: Option<ParamMap>,
    mut applied: Vec<Applied>,
) -> Result<Prepared> {
    let mut own = Vec::new();
    'rounds: for _ in 0..MAX_ROUNDS {
        own.clear();
        for r in requirements {
            let bad = unmet(&r.need, &net, spec);
            if bad.is_empty() {
                continue;
            }
            let record = |step: String, kind: Kind| Applied {
                step,
                need: r.need.words().to_string(),
                elements: bad
                    .iter()
                    .take(NAMED)
                    .map(|&e| name_element(&net, e))
                    .collect(),
                count: bad.len(),
                kind,
                cut: false,
            };
            match r.step {
                Step::Own(words) => own.push(record(words.to_string(), Kind::Own)),
                Step::Net(steps) => {
                    if steps.iter().any(|s| s.is_dual()) && !dual_carries(&net) {
                        own.push(record(steps::words(steps), Kind::Skipped));
                        continue;
                    }
                    applied.push(record(steps::words(steps), Kind::Applied));
                    for &s in steps {
                        let (child, next) = s.apply(spec, &net, map.as_ref())?;
                        net = child;
                        map = Some(next);
                    }
                    continue 'rounds;
                }
            }
        }
        break;
    }
    applied.extend(own);
    Ok(Prepared {
        mesh: net,
        applied,
        map,
    })
}

/// Whether the net tags sharp features (creases, corners, holes).
fn has_features(mesh: &PolyMesh) -> bool {
    mesh.extras().is_some_and(|e| e.has_features())
}

/// Whether the dual steps carry the net's sharp features: none; infinitely sharp corners on
/// the boundary (the kept corners of a net cut along its creases, which a dual step keeps; see
/// `crate::schemes::doo_sabin`); creases of any sharpness, which the dual step's crease rules
/// refine as the dual schemes' own levels do (`crate::schemes::doo_sabin::sharp::step`: an
/// infinitely sharp crease stays one, a semi-sharp one loses a unit), except under the
/// boundary mode `none`, for which those rules have no counterpart. Not holes.
fn dual_carries(mesh: &PolyMesh) -> bool {
    let Some(ex) = mesh.extras().filter(|e| e.has_features()) else {
        return true;
    };
    let none = ex.options.boundary() == crate::mesh::tags::BoundaryInterpolation::None;
    ex.holes.is_empty()
        && (ex.sharp_edges.is_empty() || !none)
        && ex.sharp_vertices.iter().all(|&(v, s)| {
            s >= crate::schemes::sdc::crease::INFINITE && mesh.is_boundary_vertex(v as usize)
        })
}

#[cfg(feature = "unit-tests")]
mod tests;
