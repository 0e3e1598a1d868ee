//! The extraordinary elements of mixed and polar bi-2 nets (facets, extraordinary vertices,
//! poles) with their local nets, and what the two schemes do when the elements are not
//! separated.
//!
//! # Elements that are not separated (fairsub's documented step)
//!
//! Each element's rings are computed from its local net alone (see
//! [`crate::schemes::bi2::mixed`]), so every vertex around its hole must be regular. PGS and
//! TPS separate their own elements: TPS by whole-net ternary steps ([`tps_complex`]), exact
//! because a ternary step refines the same spline and applies TPS's own rule at the
//! extraordinary vertices; PGS by the refinement of its construction (the first step turns
//! every extraordinary vertex into a facet, and further levels separate touching facets;
//! [`pgs_complex`]). No single net refinement holds binary, ternary and radial rules at once,
//! so `bi2-mixed` and `polar-bi2` take the step of the family member whose elements the net
//! has, when the preparation is on (`--prepare auto`,
//! [`crate::schemes::prepare::Step::Own`]):
//!
//! - a quad net whose elements are all extraordinary vertices (interior, valence 3 or more,
//!   with regular boundary vertices) is a TPS net: its `bi2-mixed` surface is TPS's, and TPS's
//!   whole-net steps separate the vertices (exact, as for `tps`);
//! - any other net gets the PGS step, after which every element is a facet, and a net of
//!   facets under `bi2-mixed` is a PGS net: the surface is PGS's, whose construction takes
//!   that step itself and separates touching facets by its own levels (boundaries included,
//!   by the dual schemes' boundary rules). Poles that are not separated become facets too.
//!
//! The note names the elements that were not separated and the construction taken. Under
//! `--prepare none` the schemes refuse such nets, naming the element.
//!
//! # Semi-sharp features (fairsub's construction)
//!
//! The element rings have no step that spends a finite sharpness; the family's dual step with
//! the dual crease rules does (`crate::schemes::doo_sabin::sharp`, the construction TPS takes as
//! whole-net Doo-Sabin steps, `crate::schemes::prepare`). For the mixed and polar nets that step
//! is PGS's, and after one PGS step every vertex is regular and every element a facet (poles
//! too: a pole's fan becomes triangles around an n-gon): the spent net is a PGS net, and the
//! mixed net of facets is PGS's surface. So [`spent_by_pgs`] builds that surface by PGS's own
//! construction, which takes the same steps with the same crease rules but only near the
//! features, instead of `k` whole-net steps (about `4^k` times the net): equal to the
//! whole-net steps' surface when given `k` more rings, `k` the steps that spend the largest
//! finite sharpness, since a ring of PGS's construction is one such step around its element
//! (tested against the whole-net steps, `crate::schemes::prepare`'s tests).

use super::*;
use crate::schemes::bi2::mixed::{Bi2Element, elements};
use crate::schemes::descriptor::Spec;
use crate::schemes::options::PrepareMode as Mode;

/// The PolBS surface of a polar net, or of a prism-like net whose caps become poles at their
/// centroids or at the given points ([`crate::schemes::bi2::polar::to_polar_layout`]): regular
/// bi-2 patches, `n` patches per ring around every pole, the polar cap. Elements that are not
/// poles (extraordinary vertices, facets that are not prism-like caps) get the rings of
/// `bi2-mixed` (TPS, PGS), reported in the notes.
///
/// Poles and elements that are not separated get the family's own separating construction
/// under [`Mode::Auto`], as in [`mixed_complex`].
///
/// # Errors
/// As [`mixed_complex`].
pub fn polar_complex(
    mesh: &PolyMesh,
    opts: ComplexOptions,
    poles: &[(usize, Point)],
    mode: Mode,
    progress: impl FnMut(usize),
) -> Result<(PatchComplex, Vec<String>)> {
    let name = ids::POLAR_BI2.name();
    let built = boundary_modes(mesh, mode, name)
        .and_then(|()| crate::schemes::bi2::polar::to_polar_layout(mesh, poles))
        .and_then(|net| {
            let named: Vec<(u32, Element)> =
                net.poles.iter().map(|p| (p.vertex, p.element)).collect();
            let (els, notes) = mixed_elements(&net.mesh, name, &named)?;
            Ok((net, els, notes))
        });
    let (net, els, mut notes) = match built {
        Ok(b) => b,
        Err(e) if mode == Mode::None || matches!(e, Error::InvalidArgument(_)) => return Err(e),
        Err(_) => {
            let mut spec = Spec::new(ids::POLAR_BI2);
            spec.params.poles = poles.to_vec();
            let bad = unseparated_polar(mesh, &spec);
            return separated(mesh, opts, name, &bad, progress);
        }
    };
    let (mut c, more) = assemble(&net.mesh, true, None, None, &els, opts, progress)?;
    poles::to_input_faces(mesh, &net, &mut c);
    notes.extend(more);
    Ok((c, notes))
}

/// The surface of a mixed or polar net (scheme `name`) with semi-sharp features under the
/// preparation (see the [module](self) documentation): PGS's construction with
/// `opts.rings + k` rings, `k` the whole-net steps that would spend the largest finite
/// sharpness, so that rings count from the spent net as after any preparation step; with its
/// note.
///
/// # Errors
/// Those of PGS's construction (an infinitely sharp dart, ...).
pub(crate) fn spent_by_pgs(
    mesh: &PolyMesh,
    opts: ComplexOptions,
    name: &str,
    progress: impl FnMut(usize),
) -> Result<(PatchComplex, String)> {
    let steps = crate::schemes::doo_sabin::sharp::spending_steps(mesh);
    let rings = opts.rings + steps;
    let complex = pgs_complex(
        mesh,
        ComplexOptions { rings, ..opts },
        PgsOptions::default(),
        progress,
    )?;
    let poles = if name == ids::POLAR_BI2.name() {
        " (poles included)"
    } else {
        ""
    };
    let note = format!(
        "semi-sharp features under {name}: the family's PGS steps with fairsub's crease \
         construction spend them ({steps} for the largest finite sharpness), after which every \
         element is a facet{poles} and the surface is {p}'s; it is built by {p}'s \
         construction, which takes those steps only near the features, with the {} rings \
         asked for counted from the spent net ({rings} in all)",
        opts.rings,
        p = ids::PGS,
    );
    Ok((complex, note))
}

/// The elements of a mixed net with their local nets; poles named by `named` (else by their
/// vertex). Notes list the elements that are not poles (for `polar-bi2`).
fn mixed_elements(
    mesh: &PolyMesh,
    name: &str,
    named: &[(u32, Element)],
) -> Result<(Vec<RingElement>, Vec<String>)> {
    for v in 0..mesh.num_vertices() {
        if mesh.is_boundary_vertex(v) && !regular(mesh, v) {
            return Err(Error::Unsupported(format!(
                "boundary vertex {v} is not regular (two quads, or one at a corner); {name} \
                 has no boundary rules for it (way out: {} or {})",
                ids::PGS,
                ids::DOO_SABIN
            )));
        }
    }
    let mut notes = Vec::new();
    // a TPS vertex's rings and cap lie in thirds of the quarters of its faces, as in `tps`
    // (the regular patches around it cover the same quarters as TPS's)
    let face_cells = thirds::FaceCells::input(mesh);
    let els = elements(mesh)
        .into_iter()
        .map(|e| match e {
            Bi2Element::Facet(f) => {
                if name == ids::POLAR_BI2.name() {
                    notes.push(format!(
                        "face {f} ({} sides) is not a prism-like cap: PGS rings there, as in \
                         {}",
                        mesh.face_size(f as usize),
                        ids::BI2_MIXED
                    ));
                }
                pgs_element(mesh, f as usize, name)
            }
            Bi2Element::Vertex(v) => {
                if name == ids::POLAR_BI2.name() {
                    notes.push(format!(
                        "vertex {v} (valence {}) is not a pole: TPS rings there, as in {}",
                        mesh.valence(v as usize),
                        ids::BI2_MIXED
                    ));
                }
                let mut el = ternary_element(mesh, v as usize, TernaryRules::TPS, name)?;
                el.sectors = thirds::sector_cells(mesh, &face_cells, v as usize);
                Ok(el)
            }
            Bi2Element::Pole(p) => {
                let element = pole_element(named, p);
                polar_element(mesh, p as usize, element, name)
            }
        })
        .collect::<Result<_>>()?;
    Ok((els, notes))
}

/// The surface of a mixed bi-2 net (Fig. 15 of the paper): regular bi-2 patches, PGS rings
/// at facets, TPS rings at extraordinary vertices, polar rings at poles (see
/// [`crate::schemes::bi2::mixed`]), with the notes of holes that keep their fill. Elements that
/// are not separated get the family's own separating construction under [`Mode::Auto`]
/// (TPS's whole-net steps on a net of extraordinary vertices, else PGS's construction).
///
/// # Errors
/// Under [`Mode::None`], [`Error::Unsupported`] when elements are not separated (a vertex next
/// to a hole is not regular) or a facet has no DS-net, naming the element and the way out.
pub fn mixed_complex(
    mesh: &PolyMesh,
    opts: ComplexOptions,
    mode: Mode,
    progress: impl FnMut(usize),
) -> Result<(PatchComplex, Vec<String>)> {
    let name = ids::BI2_MIXED.name();
    let built = boundary_modes(mesh, mode, name).and_then(|()| mixed_elements(mesh, name, &[]));
    match built {
        Ok((els, _)) => assemble(mesh, true, None, None, &els, opts, progress),
        Err(e) if mode == Mode::None => Err(e),
        Err(_) => separated(
            mesh,
            opts,
            name,
            &unseparated(mesh, &Spec::new(ids::BI2_MIXED)),
            progress,
        ),
    }
}

/// The elements of a mixed net whose rings cannot be built: boundary vertices that are not
/// regular, elements not separated by regular vertices, facets without a DS-net (the
/// preparation's test, [`crate::schemes::prepare::Need::Scheme`]).
pub fn unseparated(mesh: &PolyMesh, _: &Spec) -> Vec<Element> {
    unseparated_in(mesh, &[])
}

/// [`unseparated`] for `polar-bi2` (`spec`'s poles): of the net with its prism-like caps
/// turned into poles (elements of that net), every facet when the caps cannot be turned.
pub fn unseparated_polar(mesh: &PolyMesh, spec: &Spec) -> Vec<Element> {
    let poles: Vec<(usize, Point)> = spec.params.poles.clone();
    match crate::schemes::bi2::polar::to_polar_layout(mesh, &poles) {
        Ok(net) => {
            let named: Vec<(u32, Element)> =
                net.poles.iter().map(|p| (p.vertex, p.element)).collect();
            unseparated_in(&net.mesh, &named)
        }
        Err(_) => (0..mesh.num_faces())
            .filter(|&f| mesh.face_size(f) != 4)
            .map(|f| Element::Face(f as u32))
            .collect(),
    }
}

/// The input element pole `p` stands for: the one `named` gives it (a cap's face), else the
/// vertex itself.
fn pole_element(named: &[(u32, Element)], p: u32) -> Element {
    named
        .iter()
        .find(|x| x.0 == p)
        .map(|x| x.1)
        .unwrap_or(Element::Vertex(p))
}

/// [`unseparated`] with poles named by `named`.
fn unseparated_in(mesh: &PolyMesh, named: &[(u32, Element)]) -> Vec<Element> {
    let name = ids::BI2_MIXED.name();
    let mut out: Vec<Element> = (0..mesh.num_vertices())
        .filter(|&v| mesh.is_boundary_vertex(v) && !(regular(mesh, v) && takes_mode(mesh, v)))
        .map(|v| Element::Vertex(v as u32))
        .collect();
    for e in elements(mesh) {
        let (built, element) = match e {
            Bi2Element::Facet(f) => (
                pgs_element(mesh, f as usize, name).is_ok(),
                Element::Face(f),
            ),
            Bi2Element::Vertex(v) => (
                mesh.valence(v as usize) >= 3
                    && ternary_element(mesh, v as usize, TernaryRules::TPS, name).is_ok(),
                Element::Vertex(v),
            ),
            Bi2Element::Pole(p) => {
                let element = pole_element(named, p);
                (
                    polar_element(mesh, p as usize, element, name).is_ok(),
                    element,
                )
            }
        };
        if !built {
            out.push(element);
        }
    }
    out
}

/// Under [`Mode::Auto`], an error when the boundary mode asks for what the mixed net's
/// boundary rules do not do (the construction then goes to PGS's, which takes the modes);
/// under [`Mode::None`] the descriptor has refused such nets already.
fn boundary_modes(mesh: &PolyMesh, mode: Mode, name: &str) -> Result<()> {
    match (0..mesh.num_vertices()).find(|&v| mesh.is_boundary_vertex(v) && !takes_mode(mesh, v)) {
        Some(v) if mode == Mode::Auto => Err(Error::Unsupported(format!(
            "boundary vertex {v}: {name}'s boundary rules do not take the boundary mode {}",
            crate::mesh::tags::Named::name(crate::schemes::doo_sabin::boundary_mode(mesh))
        ))),
        _ => Ok(()),
    }
}

/// Whether the boundary mode leaves boundary vertex `v` to the mixed net's boundary rules, which
/// keep every corner of one face and write every boundary patch (see
/// [`crate::schemes::doo_sabin::sharp::refuse_boundary_modes`]).
fn takes_mode(mesh: &PolyMesh, v: usize) -> bool {
    use crate::mesh::tags::BoundaryInterpolation;
    use crate::schemes::doo_sabin::{boundary_mode, sharp::is_kept_corner};
    match boundary_mode(mesh) {
        BoundaryInterpolation::None => false,
        _ => !mesh.is_corner(v) || is_kept_corner(mesh, v),
    }
}

/// The surface of a mixed or polar net whose elements `bad` are not separated: TPS's when the
/// net is a TPS net, else PGS's, with the note.
fn separated(
    mesh: &PolyMesh,
    opts: ComplexOptions,
    name: &str,
    bad: &[Element],
    progress: impl FnMut(usize),
) -> Result<(PatchComplex, Vec<String>)> {
    let els = elements(mesh);
    let tps_net = mesh.is_all_quads()
        && els.iter().all(|e| matches!(e, Bi2Element::Vertex(_)))
        && (0..mesh.num_vertices()).all(|v| {
            if mesh.is_boundary_vertex(v) {
                (1..=2).contains(&mesh.vertex_faces(v).len()) && takes_mode(mesh, v)
            } else {
                mesh.valence(v) >= 3
            }
        });
    let mut named: Vec<String> = bad.iter().take(4).map(|e| e.describe()).collect();
    if bad.len() > 4 {
        named.push(format!("{} more", bad.len() - 4));
    }
    let at = named.join(", ");
    if tps_net {
        let (c, mut notes) = tps_complex(mesh, opts, TernaryRules::TPS, progress)?;
        notes.insert(
            0,
            format!(
                "{name}: the extraordinary vertices are not separated ({at}); a net whose \
                 elements are all extraordinary vertices is a {} net, and its whole-net steps \
                 separate them (exact)",
                ids::TPS
            ),
        );
        return Ok((c, notes));
    }
    let c = pgs_complex(mesh, opts, PgsOptions::default(), progress)?;
    let note = format!(
        "{name}: the elements are not separated ({at}); one {} step makes every element a \
         facet, and a net of facets is a {} net: its construction takes that step and \
         separates touching facets itself",
        ids::PGS,
        ids::PGS
    );
    Ok((c, vec![note]))
}
