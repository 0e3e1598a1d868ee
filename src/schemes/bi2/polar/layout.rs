//! Polar layouts: finding the poles of a net, turning prism-like caps into poles, and the
//! classification of edges (radial, circular) that polar refinement needs.

use super::*;

/// The pole of a polar net and where it came from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pole {
    /// The pole's vertex in the polar net.
    pub vertex: u32,
    /// The input element it stands for: the cap face it replaced, or the input vertex that
    /// already was a pole.
    pub element: Element,
}

/// A polar net: the mesh and its poles.
#[derive(Debug, Clone)]
pub struct PolarNet {
    /// The mesh (pole fans and quads).
    pub mesh: PolyMesh,
    /// Its poles.
    pub poles: Vec<Pole>,
}

/// Interior vertices all of whose (at least 3) faces are triangles: the poles of a polar net.
pub fn find_poles(mesh: &PolyMesh) -> Vec<u32> {
    (0..mesh.num_vertices())
        .filter(|&v| {
            !mesh.is_boundary_vertex(v) && {
                let fs = mesh.vertex_faces(v);
                fs.len() >= 3 && fs.iter().all(|&f| mesh.face_size(f as usize) == 3)
            }
        })
        .map(|v| v as u32)
        .collect()
}

/// Whether face `f` is a prism-like cap: not a quad, every corner an interior vertex of valence
/// 3 (one edge leaving the cap), so that each corner has valence 4 next to the pole that
/// replaces the cap.
pub fn is_cap(mesh: &PolyMesh, f: usize) -> bool {
    mesh.face_size(f) != 4
        && mesh
            .face(f)
            .iter()
            .all(|&v| !mesh.is_boundary_vertex(v as usize) && mesh.valence(v as usize) == 3)
}

/// Converts every prism-like cap ([`is_cap`]) and every facet named in `poles` into a pole
/// with its fan of triangles: the pole is the facet's centroid, or `poles[k].1` for the facet
/// `poles[k].0` (input face index). Existing poles ([`find_poles`]) are kept; other facets stay
/// (they are PGS facets for [`PolarBi2`]'s patches).
///
/// # Errors
/// [`Error::InvalidArgument`] when a given face index is out of range or names a quad.
pub fn to_polar_layout(mesh: &PolyMesh, poles: &[(usize, Point)]) -> Result<PolarNet> {
    for &(f, _) in poles {
        if f >= mesh.num_faces() {
            return Err(Error::InvalidArgument(format!(
                "pole for face {f}: the net has {} faces",
                mesh.num_faces()
            )));
        }
        if mesh.face_size(f) == 4 {
            return Err(Error::InvalidArgument(format!(
                "pole for face {f}: face {f} is a quad, not a cap (give poles for faces that are \
                 not quads)"
            )));
        }
    }
    let existing = find_poles(mesh);
    let mut in_fan = vec![false; mesh.num_faces()];
    for &p in &existing {
        for f in mesh.vertex_faces(p as usize) {
            in_fan[f as usize] = true;
        }
    }
    let mut pos: Vec<Point> = mesh.positions().to_vec();
    let mut faces: Vec<Vec<usize>> = Vec::new();
    let mut out_poles: Vec<Pole> = existing
        .iter()
        .map(|&v| Pole {
            vertex: v,
            element: Element::Vertex(v),
        })
        .collect();
    for (f, &fan) in in_fan.iter().enumerate() {
        let verts: Vec<usize> = mesh.face(f).iter().map(|&v| v as usize).collect();
        let given = poles.iter().any(|x| x.0 == f);
        if verts.len() == 4 || fan || !(given || is_cap(mesh, f)) {
            faces.push(verts);
            continue;
        }
        let p = poles
            .iter()
            .find(|x| x.0 == f)
            .map(|x| x.1)
            .unwrap_or_else(|| mesh.face_centroid(f));
        let pv = pos.len();
        pos.push(p);
        out_poles.push(Pole {
            vertex: pv as u32,
            element: Element::Face(f as u32),
        });
        let n = verts.len();
        for k in 0..n {
            faces.push(vec![pv, verts[k], verts[(k + 1) % n]]);
        }
    }
    Ok(PolarNet {
        mesh: PolyMesh::new(pos, &faces)?,
        poles: out_poles,
    })
}

/// Kinds of edges of a polar layout.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EdgeKind {
    /// Along a spoke (towards or away from a pole).
    Radial,
    /// Around a pole.
    Circular,
}

/// The edge kinds of a polar layout, propagated from the poles across quads (a quad's opposite
/// edges have the same kind, adjacent edges different kinds).
///
/// # Errors
/// [`Error::Unsupported`] naming the face, edge or vertex that breaks the polar layout.
pub fn edge_kinds(mesh: &PolyMesh, poles: &[u32]) -> Result<Vec<EdgeKind>> {
    if poles.is_empty() {
        return Err(not_polar("the net has no pole and no cap".into()));
    }
    let mut is_pole = vec![false; mesh.num_vertices()];
    for &p in poles {
        is_pole[p as usize] = true;
    }
    let mut kind: Vec<Option<EdgeKind>> = vec![None; mesh.num_edges()];
    fan_kinds(mesh, &is_pole, &mut kind)?;
    // Propagate across quads until nothing changes.
    while propagate_across_quads(mesh, &mut kind)? {}
    let mut out = Vec::with_capacity(kind.len());
    for (e, k) in kind.into_iter().enumerate() {
        match k {
            Some(k) => out.push(k),
            None => {
                return Err(not_polar(format!("edge {e} is not reachable from a pole")));
            }
        }
    }
    for (e, &k) in out.iter().enumerate() {
        if mesh.is_boundary_edge(e) && k == EdgeKind::Radial {
            return Err(not_polar(format!(
                "boundary edge {e} runs along a spoke (only circular boundaries are supported)"
            )));
        }
    }
    Ok(out)
}

/// The error for a net that is not a polar layout: `what` breaks it, and the way out.
fn not_polar(what: String) -> Error {
    Error::Unsupported(format!(
        "{what}: {} refines polar layouts (poles with fans of triangles and rings of \
         quads around them); write the exact surface of other nets with {} --rings K",
        ids::POLAR_BI2,
        ids::BI2_MIXED
    ))
}

/// Gives edge `e` the kind `k`: `true` when it had none, `false` when it had `k`, an error
/// when it had the other kind.
fn set_kind(e: usize, k: EdgeKind, kind: &mut [Option<EdgeKind>]) -> Result<bool> {
    match kind[e] {
        Some(x) if x != k => Err(not_polar(format!(
            "edge {e} would be both radial and circular"
        ))),
        Some(_) => Ok(false),
        None => {
            kind[e] = Some(k);
            Ok(true)
        }
    }
}

/// The kinds of the fan triangles' edges (the two at the pole radial, the third circular);
/// an error for a triangle without exactly one pole and for faces neither triangles nor
/// quads.
fn fan_kinds(mesh: &PolyMesh, is_pole: &[bool], kind: &mut [Option<EdgeKind>]) -> Result<()> {
    for f in 0..mesh.num_faces() {
        let n = mesh.face_size(f);
        let h0 = mesh.face_halfedge(f);
        if n == 3 {
            let hs = [h0, h0 + 1, h0 + 2];
            let pk: Vec<usize> = (0..3)
                .filter(|&k| is_pole[mesh.he_from(hs[k]) as usize])
                .collect();
            if pk.len() != 1 {
                return Err(not_polar(format!(
                    "triangle {f} has {} poles (a fan triangle has exactly one)",
                    pk.len()
                )));
            }
            let k = pk[0];
            set_kind(mesh.he_edge(hs[k]) as usize, EdgeKind::Radial, kind)?;
            set_kind(
                mesh.he_edge(hs[(k + 2) % 3]) as usize,
                EdgeKind::Radial,
                kind,
            )?;
            set_kind(
                mesh.he_edge(hs[(k + 1) % 3]) as usize,
                EdgeKind::Circular,
                kind,
            )?;
        } else if n != 4 {
            return Err(not_polar(format!("face {f} has {n} sides")));
        }
    }
    Ok(())
}

/// One pass over the quads: a quad with an edge of known kind gives its opposite edge the
/// same kind and its adjacent edges the other. Returns whether any edge got a kind.
fn propagate_across_quads(mesh: &PolyMesh, kind: &mut [Option<EdgeKind>]) -> Result<bool> {
    let mut changed = false;
    for f in 0..mesh.num_faces() {
        if mesh.face_size(f) != 4 {
            continue;
        }
        let h0 = mesh.face_halfedge(f);
        let es: Vec<usize> = (0..4).map(|k| mesh.he_edge(h0 + k) as usize).collect();
        let known = (0..4).find_map(|k| kind[es[k]].map(|x| (k, x)));
        if let Some((k, x)) = known {
            let other = match x {
                EdgeKind::Radial => EdgeKind::Circular,
                EdgeKind::Circular => EdgeKind::Radial,
            };
            for (j, &ej) in es.iter().enumerate() {
                let want = if (j + 4 - k) % 2 == 0 { x } else { other };
                changed |= set_kind(ej, want, kind)?;
            }
        }
    }
    Ok(changed)
}
