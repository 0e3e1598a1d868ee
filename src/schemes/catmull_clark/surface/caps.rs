//! The cap schemes' caps on Catmull-Clark's loop: where EG, QAS+ or guided subdivision
//! ([`crate::host::caps::CapBuilder`]) replace the rings around an extraordinary vertex by their
//! own construction from the vertex's c-net, and the domain of each of its sectors.

use super::*;

/// Caps every cappable extraordinary corner of the marked faces; returns the faces left.
pub(super) fn apply_caps(
    level: &Level,
    marked: Vec<(u32, Tag)>,
    builder: &dyn CapBuilder,
    l: u32,
    out: &mut PatchComplex,
) -> Result<Vec<(u32, Tag)>> {
    let m = &level.mesh;
    let mut cand: HashMap<u32, Vec<u32>> = HashMap::new();
    // Each corner is examined once: a vertex of valence n is a corner of n marked faces, and
    // its c-net walk costs n, so asking again for every face (as when it is not accepted and
    // so not in `cand`) is n^2.
    let mut seen: HashSet<u32> = HashSet::new();
    for &(f, _) in &marked {
        for &v in m.face(f as usize) {
            if seen.insert(v)
                && let Some(idx) = cappable(level, v, builder)?
            {
                cand.insert(v, idx);
            }
        }
    }
    keep_closed(m, &mut cand);
    let mut capped: Vec<u32> = cand.keys().copied().collect();
    capped.sort_unstable();
    let domains: HashMap<u32, Domain> = if capped.is_empty() {
        HashMap::new()
    } else {
        marked.iter().map(|&(f, tag)| (f, tag.domain)).collect()
    };
    for &v in &capped {
        let idx = &cand[&v];
        // built about the vertex and moved back: the builders' maps (rings by powers of the
        // subdivision matrix, the guide's fit, the caps' solves) have entries far above 1, so
        // in place their rounding grows with the distance from the origin, not with the c-net
        // (OpenSubdiv's bishop under guided-bi5: 5.5e-7 rad inside a cap, 4.8e-7 of it above
        // the normals' rounding floor)
        let o = m.position(v as usize);
        let pts: Vec<Point> = idx
            .iter()
            .map(|&w| crate::geom::sub(m.position(w as usize), o))
            .collect();
        let element = level.info[v as usize].origin.expect("checked above");
        let sectors = sector_domains(m, v, &domains);
        let (first, first_cap) = (out.len(), out.caps.len());
        builder.build(&pts, m.valence(v as usize), element, l + 1, &sectors, out)?;
        out.translate_from(first, first_cap, o);
    }
    Ok(marked
        .into_iter()
        .filter(|&(f, _)| !m.face(f as usize).iter().any(|w| cand.contains_key(w)))
        .collect())
}

/// The c-net (two rings) of the corner `v` when the builder caps it: an interior extraordinary
/// vertex of an input element whose fan and c-net are trusted, away from sharp features (with a
/// note), with a regular complete one-ring, and accepted by the builder at its valence.
fn cappable(level: &Level, v: u32, builder: &dyn CapBuilder) -> Result<Option<Vec<u32>>> {
    let m = &level.mesh;
    let vi = level.info[v as usize];
    if m.is_regular_quad_vertex(v as usize) || m.is_boundary_vertex(v as usize) {
        return Ok(None);
    }
    let Some(element) = vi.origin else {
        return Ok(None);
    };
    if !vi.fan_ok || !vi.pos_ok {
        return Ok(None);
    }
    let Some(idx) = m.cnet_indices(v as usize, 2) else {
        return Ok(None);
    };
    let n = m.valence(v as usize);
    if touches_features(level, &idx) {
        builder.note(format!(
            "{} (valence {n}) is next to a sharp feature (within the two rings of its \
             c-net): Catmull-Clark rings with OpenSubdiv's rules there until it is \
             clear of it, Catmull-Clark's cap if it never is",
            crate::host::caps::describe(element)
        ));
        return Ok(None);
    }
    // The one-ring (chart points (1, 0) and (1, 1) of each sector) must be regular and
    // complete, and the whole c-net trusted.
    let ring1_ok = (0..n).all(|s| {
        [idx[1 + 6 * s], idx[2 + 6 * s]]
            .iter()
            .all(|&w| level.info[w as usize].fan_ok && m.is_regular_quad_vertex(w as usize))
    });
    if !ring1_ok || idx.iter().any(|&w| !level.info[w as usize].pos_ok) {
        return Ok(None);
    }
    Ok(builder.accepts(n, element)?.then_some(idx))
}

/// Keeps a candidate vertex only if every extraordinary vertex of its c-net is a candidate too
/// (dropping one may drop others: repeated until nothing changes).
fn keep_closed(m: &PolyMesh, cand: &mut HashMap<u32, Vec<u32>>) {
    loop {
        let drop: Vec<u32> = cand
            .iter()
            .filter(|(v, idx)| {
                idx.iter().any(|&w| {
                    w != **v && !m.is_regular_quad_vertex(w as usize) && !cand.contains_key(&w)
                })
            })
            .map(|(&v, _)| v)
            .collect();
        if drop.is_empty() {
            break;
        }
        for v in drop {
            cand.remove(&v);
        }
    }
}

/// The domain of each sector's face around the interior vertex `v`, in the sector order of
/// [`PolyMesh::cnet_indices`], rotated to `v`'s corner (the frame [`CapBuilder::build`]
/// documents); [`Domain::UNTRACKED`] for faces without one in `domains`.
fn sector_domains(m: &PolyMesh, v: u32, domains: &HashMap<u32, Domain>) -> Vec<Domain> {
    let h0 = m.vertex_halfedge(v as usize);
    let ring = m.interior_ring_from(h0).unwrap_or_default();
    ring.iter()
        .map(|&h| {
            let f = m.he_face(h);
            let face = m.face(f as usize);
            let to = m.he_to(h);
            let corner = (0..face.len())
                .find(|&c| face[c] == v && face[(c + 1) % face.len()] == to)
                .unwrap_or(0);
            domains
                .get(&f)
                .map_or(Domain::UNTRACKED, |d| d.rotated(corner as u32))
        })
        .collect()
}
