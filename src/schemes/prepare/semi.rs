//! Spending semi-sharp features before the schemes whose rules take infinitely sharp ones only
//! (TPS, adjustable TPS): fairsub's semi-sharp construction for them, the step [`Step::Spend`]
//! declares. (The mixed and polar bi-2 nets, whose spending step is PGS's, take PGS's
//! construction instead: see `crate::schemes::bi2::surface`'s elements.)
//!
//! # The construction (fairsub's, not the bi-2 paper's: the paper has no crease rules)
//!
//! The element rings of these schemes are computed from an element's local net alone, and
//! have no step in which a crease could lose sharpness; their infinitely sharp creases are
//! boundaries of the net cut along them (`crate::schemes::doo_sabin::sharp`). TPS's own
//! ternary step cannot carry a crease through the vertices real nets put on creases either:
//! a crease vertex of valence 3 leaves one face on one side, a boundary vertex TPS has no rule
//! for, and a dart ends the crease inside the surface. What the family does have is the dual
//! step with fairsub's crease rules (the Chaikin points of both sides while a crease is sharp,
//! OpenSubdiv's sharpness decay and fractional blend), and that step is the one TPS's
//! preparation already takes (one Doo-Sabin step, then one Catmull-Clark step) and the one the
//! mixed and polar nets take (one PGS step). So the net is refined whole by that step until no
//! finite sharpness is left:
//!
//! * a crease of sharpness `s` is refined by the sharp rules for `floor(s)` steps and by
//!   OpenSubdiv's fractional blend on the next (as Catmull-Clark treats it); from then on it
//!   is smooth, and the scheme's own rules take the net;
//! * an infinitely sharp crease (sharpness 10 or more) stays sharp through the steps; their
//!   sharp rules are the boundary rules of the net cut along it, so it ends as the cut the
//!   scheme makes of a net without semi-sharp features (the preparation then proceeds as for
//!   such a net: the cut, then the steps the cut net needs);
//! * the number of steps is `ceil` of the largest finite sharpness (each step lowers every
//!   finite value by at least one).
//!
//! The surface is the scheme's surface of the refined net: exact and C^1 (G^1 at the elements'
//! caps) wherever the scheme's rules are, with the dual step's rules inside the strips the
//! steps leave along the spent creases. The steps are whole-net steps (linear, mapped back to
//! the input faces like every preparation step), so the net grows about four times per unit of
//! sharpness: [`MAX_FACES`] bounds it, beyond which the net is refused with the element named
//! (Doo-Sabin, DS^CC and PGS refine only near a semi-sharp feature).

use super::map::ParamMap;
use super::{Applied, Kind, NAMED};
use crate::error::{Error, Result};
use crate::mesh::{PolyMesh, SharpEdges};
use crate::schemes::descriptor::Spec;
use crate::schemes::doo_sabin::sharp::{has_semi_sharp, kept_faces, spending_steps, without_holes};
use crate::schemes::needs::{Need, Requirement, Step};
use crate::schemes::sdc::crease::INFINITE;

/// The most faces the spending steps may make (estimated before the first step).
pub const MAX_FACES: usize = 2_000_000;

/// The most steps: every finite sharpness is below 10.
const MAX_STEPS: usize = 10;

/// Whether `s` is a finite positive sharpness.
fn semi(s: f32) -> bool {
    s > 0.0 && s < INFINITE
}

/// The semi-sharp edges of `mesh` by their end points, with their sharpness.
fn semi_sharp_edges(mesh: &PolyMesh) -> Vec<([u32; 2], f32)> {
    match mesh.extras().map(|ex| &ex.sharp_edges) {
        None => Vec::new(),
        Some(SharpEdges::ById(v)) => v
            .iter()
            .filter(|p| semi(p.1))
            .map(|&(e, s)| {
                let h = mesh.edge_halfedge(e as usize);
                ([mesh.he_from(h), mesh.he_to(h)], s)
            })
            .collect(),
        Some(SharpEdges::ByPair(v)) => v.iter().filter(|p| semi(p.1)).copied().collect(),
    }
}

/// The semi-sharp vertex tags of `mesh`, with their sharpness.
fn semi_sharp_tags(mesh: &PolyMesh) -> impl Iterator<Item = (u32, f32)> + '_ {
    mesh.extras()
        .into_iter()
        .flat_map(|ex| ex.sharp_vertices.iter().copied().filter(|p| semi(p.1)))
}

/// The semi-sharp features of `mesh`, named, with their sharpness (edges, then vertices).
pub(super) fn semi_sharp_features(mesh: &PolyMesh) -> Vec<(String, f32)> {
    let edges = semi_sharp_edges(mesh)
        .into_iter()
        .map(|([a, b], s)| (format!("edge {a}-{b}"), s));
    let vertices = semi_sharp_tags(mesh).map(|(v, s)| (format!("vertex {v}"), s));
    edges.chain(vertices).collect()
}

/// The vertices at semi-sharp features of `mesh` (the ends of its semi-sharp edges, its
/// semi-sharp vertices), sorted.
pub(super) fn semi_sharp_vertices(mesh: &PolyMesh) -> Vec<u32> {
    let mut out: Vec<u32> = semi_sharp_edges(mesh)
        .into_iter()
        .flat_map(|(ends, _)| ends)
        .chain(semi_sharp_tags(mesh).map(|(v, _)| v))
        .collect();
    out.sort_unstable();
    out.dedup();
    out
}

/// The spending steps for `spec` on `mesh` when its `requirements` declare them
/// ([`Step::Spend`]) and the net tags semi-sharp features: the spent net, the map from its
/// faces to the input faces, and the note. `None` when there is nothing to spend. The dual
/// steps do not carry holes, so hole faces are removed first, as the dual schemes' patches
/// remove them (`crate::schemes::doo_sabin::sharp`: a bi-2 patch spans four faces, the surface
/// ends on the hole's boundary curve); the map then picks the kept faces.
///
/// # Errors
/// [`Error::Unsupported`] when the steps would make more than [`MAX_FACES`] faces, naming the
/// sharpest feature; those of the steps (a boundary mode `none`, a corner tag inside the
/// surface: the dual crease construction's refusals).
pub(super) fn spend(
    requirements: &[Requirement],
    spec: &Spec,
    mesh: &PolyMesh,
) -> Result<Option<(PolyMesh, ParamMap, Applied)>> {
    let Some(step) = requirements.iter().find_map(|r| match r.step {
        Step::Spend(s) => Some(s),
        _ => None,
    }) else {
        return Ok(None);
    };
    if !has_semi_sharp(mesh) {
        return Ok(None);
    }
    let mut features = semi_sharp_features(mesh);
    features.sort_by(|a, b| b.1.total_cmp(&a.1));
    let (sharpest, top) = features[0].clone();
    let steps = spending_steps(mesh).clamp(1, MAX_STEPS);
    // a dual step makes a face per face, edge and vertex; each later one about four per face
    let first = mesh.num_faces() + mesh.num_edges() + mesh.num_vertices();
    let estimate = first.saturating_mul(4usize.saturating_pow(steps as u32 - 1));
    let name = spec.name();
    if estimate > MAX_FACES {
        return Err(Error::Unsupported(format!(
            "the {sharpest} has the semi-sharp value {top}; {name} spends a finite sharpness by \
             whole-net {} steps (fairsub's crease construction, see \
             docs/guide/src/creases.md): its {steps} whole-net steps would make about \
             {estimate} faces (more than {MAX_FACES}): lower the sharpness, tag the crease infinitely sharp (10), or use \
             {}, {} or {}, whose patches refine only near a semi-sharp crease",
            step.name(),
            crate::schemes::options::ids::PGS,
            crate::schemes::options::ids::DOO_SABIN,
            crate::schemes::options::ids::CATMULL_CLARK,
        )));
    }
    let holes = mesh.extras().map_or(0, |e| e.holes.len());
    let mut hole_note = Vec::new();
    let (mut net, mut map) = if holes == 0 {
        (mesh.clone(), None)
    } else {
        (
            without_holes(mesh, holes, name, &mut hole_note),
            Some(ParamMap::input(mesh).select(&kept_faces(mesh))),
        )
    };
    let mut taken = 0;
    while taken < MAX_STEPS && (taken < steps || has_semi_sharp(&net)) {
        let (child, next) = step.apply(spec, &net, map.as_ref())?;
        net = child;
        map = Some(next);
        taken += 1;
    }
    let count = features.len();
    let applied = Applied {
        step: format!(
            "{}{taken} whole-net {} step{} with fairsub's crease construction (the creases' \
             sharp rules while their sharpness lasts, OpenSubdiv's fractional blend on the step \
             it runs out; infinitely sharp creases stay sharp and are cut as without semi-sharp \
             ones; see docs/guide/src/creases.md)",
            hole_note
                .first()
                .map_or(String::new(), |n| format!("{n}; then ")),
            step.name(),
            if taken == 1 { "" } else { "s" }
        ),
        need: Need::InfinitelySharpOnly.words().to_string(),
        elements: features
            .into_iter()
            .take(NAMED)
            .map(|(n, s)| format!("{n} sharpness {s}"))
            .collect(),
        count,
        kind: Kind::Applied,
        cut: false,
    };
    Ok(map.map(|m| (net, m, applied)))
}
