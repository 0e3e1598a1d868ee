//! Semi-sharp features under TPS and adjustable TPS, without whole-net steps (fairsub's
//! construction; the bi-2 paper has no crease rules).
//!
//! TPS's element rings are computed from a vertex's q-net alone and have no step in which a
//! crease could lose sharpness; the family's dual step with fairsub's crease rules does
//! (`crate::schemes::doo_sabin::sharp`). The whole-net form of that construction
//! (`crate::schemes::prepare`'s spend: Doo-Sabin steps until every finite sharpness is spent,
//! then TPS on the refined net) grows the net about four times per unit of sharpness, so
//! OpenSubdiv's bishop, car and pawn (sharpness 6) were refused. This construction takes the
//! dual steps only where the features reach:
//!
//! * where no feature reaches, a quad net's bi-2 spline is one surface under every member of
//!   the family: every regular vertex carries the same exact bi-2 patch of its 3x3 net
//!   ([`crate::schemes::doo_sabin::surface::regular_vertex_patch`]) under Doo-Sabin and TPS;
//! * an extraordinary vertex `v` whose neighbourhood is clean, no sharp feature (a crease of any
//!   sharpness, a sharp vertex tag) at a vertex of its faces or of the faces around those, and
//!   whose q-net TPS takes (separated by regular vertices), gets TPS's rings and cap, which fill
//!   `v`'s cell (the quarters of its faces at `v`) from its q-net alone and join the regular
//!   patches around the cell C^1, as in [`super::tps_complex`];
//! * everything else (the strips along semi-sharp and infinitely sharp features, the
//!   extraordinary elements they reach, vertices that are not separated, faces that are not
//!   quads) is Doo-Sabin's adaptive construction with the crease rules, which refines only near
//!   the elements and features, with `k` more rings (`k` the steps that spend the largest
//!   finite sharpness, so that its rings count from the spent net as after a preparation step).
//!
//! Doo-Sabin's refinement of a cell next to a clean one uses face-local corner rules, so on
//! quads around regular vertices without features it refines the bi-2 spline itself: the
//! patches it writes beside a TPS cell are that spline's, and the TPS rings join them as they
//! join the regular patches. The surface is TPS's wherever a TPS element has room, Doo-Sabin's
//! crease construction elsewhere: G^1 everywhere the two schemes are, closed along the
//! features, and equal to the infinitely sharp crease's surface at sharpness 10 away from the
//! features' ends (tested in `tests/it/semisharp_rings.rs`).

use super::*;
use std::collections::HashSet;

/// Per vertex of `mesh`: whether a sharp feature touches it (an end of an edge of positive
/// sharpness, a vertex of positive sharpness).
///
/// # Errors
/// A tagged pair that is not an edge of the net.
fn feature_vertices(mesh: &PolyMesh) -> Result<Vec<bool>> {
    let mut at = vec![false; mesh.num_vertices()];
    let Some(ex) = mesh.extras() else {
        return Ok(at);
    };
    let edges = crate::schemes::doo_sabin::sharp::edge_sharpness(mesh, ex)?;
    for (e, _) in edges.iter().enumerate().filter(|(_, s)| **s > 0.0) {
        let h = mesh.edge_halfedge(e);
        at[mesh.he_from(h) as usize] = true;
        at[mesh.he_to(h) as usize] = true;
    }
    for &(v, s) in &ex.sharp_vertices {
        if s > 0.0
            && let Some(x) = at.get_mut(v as usize)
        {
            *x = true;
        }
    }
    Ok(at)
}

/// Whether no feature touches a vertex of the faces around `v` or of the faces around those,
/// and all those faces are quads (the module documentation's clean neighbourhood).
fn clean(mesh: &PolyMesh, features: &[bool], v: usize) -> bool {
    let ring: HashSet<u32> = mesh
        .vertex_faces(v)
        .iter()
        .flat_map(|&f| mesh.face(f as usize).iter().copied())
        .collect();
    ring.iter().all(|&w| {
        mesh.vertex_faces(w as usize).iter().all(|&f| {
            let face = mesh.face(f as usize);
            face.len() == 4 && face.iter().all(|&x| !features[x as usize])
        })
    })
}

/// The TPS (`rules`) surface of a quad net with semi-sharp features by the construction of the
/// [module](self) documentation, with its notes; `name` is the scheme's.
///
/// # Errors
/// Those of Doo-Sabin's crease construction (a boundary mode `none`, an infinitely sharp dart,
/// ...) and of the TPS elements' tables.
pub(crate) fn tps_spent_locally(
    mesh: &PolyMesh,
    opts: ComplexOptions,
    rules: TernaryRules,
    name: &str,
    progress: impl FnMut(usize),
) -> Result<(PatchComplex, Vec<String>)> {
    let steps = crate::schemes::doo_sabin::sharp::spending_steps(mesh);
    let features = feature_vertices(mesh)?;
    let face_cells = thirds::FaceCells::input(mesh);
    let split = if rules == TernaryRules::TPS {
        thirds::Split::Thirds
    } else {
        thirds::Split::At(1.0 - 2.0 * rules.e)
    };
    let (mut elements, mut dual) = (Vec::new(), 0usize);
    for v in 0..mesh.num_vertices() {
        if mesh.is_boundary_vertex(v) || mesh.valence(v) == 4 {
            continue;
        }
        let el = clean(mesh, &features, v)
            .then(|| ternary_element(mesh, v, rules, name).ok())
            .flatten();
        match el {
            Some(mut el) => {
                el.sectors = thirds::sector_cells(mesh, &face_cells, v);
                el.split = split;
                elements.push(el);
            }
            None => dual += 1,
        }
    }
    let facets = (0..mesh.num_faces())
        .filter(|&f| mesh.face_size(f) != 4)
        .count();
    let rings = opts.rings + steps;
    let ds_opts = ComplexOptions { rings, ..opts };
    let spent = ds::doo_sabin_complex(mesh, ds_opts, progress)?;
    let mine: HashSet<Element> = elements.iter().map(|e| e.element).collect();
    let of_mine = |p: &Provenance| match p {
        Provenance::Ring { element, .. } | Provenance::Cap { element, .. } => {
            mine.contains(element)
        }
        _ => false,
    };
    let mut out = spent.retain(|i| !of_mine(&spent.provenance[i]));
    out.uncapped.retain(|(e, _)| !mine.contains(e));
    let widths = uniform_widths(mesh);
    let (tps, mut notes) = assemble(
        mesh,
        false,
        Some(&widths),
        Some(&face_cells),
        &elements,
        opts,
        |_| {},
    )?;
    out.extend(tps.retain(|i| of_mine(&tps.provenance[i])));
    notes.insert(
        0,
        format!(
            "semi-sharp features under {name}, spent with fairsub's crease construction near the \
             features only (docs/guide/src/creases.md): {} extraordinary vertices clear of the features \
             get {name}'s rings and cap ({} rings); the strips along the features, the {dual} \
             extraordinary vertices they reach (or that are not separated) and the {facets} \
             faces that are not quads are {}'s crease construction, refined only there, with the {} rings asked for counted from the \
             spent net ({rings} in all, {steps} spend the largest finite sharpness)",
            elements.len(),
            opts.rings,
            ids::DOO_SABIN,
            opts.rings,
        ),
    );
    Ok((out, notes))
}
