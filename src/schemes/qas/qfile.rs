//! A q-file checked against the net it is applied to.
//!
//! [`super::parse_q_file`] reads the file on its own (syntax, numbers, kinds); which vertices
//! it may name depends on the net, known only once the net is read. [`check_q_file`] then
//! refuses, at the line that names them, a vertex the net does not have, a boundary vertex, a
//! regular vertex (QAS+ keeps its bi-3 patches there: the expansion would be ignored without a
//! word), a vertex whose valence has no QAS+ rules ([`super::tables::COMPLETE_VALENCES`]), and a
//! sector the vertex does not have.

use crate::error::{Error, Result};
use crate::mesh::PolyMesh;
use std::path::Path;

/// Checks every `vertex V` and `q SECTOR ...` line of the q-file `text` (already parsed by
/// [`super::parse_q_file`]) against `mesh`; errors name the file line.
pub fn check_q_file(text: &str, path: &Path, mesh: &PolyMesh) -> Result<()> {
    let err = |line: usize, msg: String| Error::Parse {
        path: path.to_path_buf(),
        line,
        msg,
    };
    // (vertex, valence) of the current section
    let mut cur: Option<(usize, usize)> = None;
    for (ln, raw) in text.lines().enumerate() {
        let line = ln + 1;
        let t = raw.split('#').next().unwrap_or("").trim();
        let f: Vec<&str> = t.split_whitespace().collect();
        match f.as_slice() {
            ["vertex", v] => {
                let Ok(v) = v.parse::<usize>() else {
                    continue; // the parser reported it
                };
                let n = check_vertex(mesh, v).map_err(|m| err(line, m))?;
                cur = Some((v, n));
            }
            ["q", s, ..] => {
                let (Some((v, n)), Ok(s)) = (cur, s.parse::<usize>()) else {
                    continue;
                };
                if s >= n {
                    return Err(err(
                        line,
                        format!(
                            "sector {s} of vertex {v}: the vertex has valence {n}, so its \
                             sectors are 0..{}",
                            n - 1
                        ),
                    ));
                }
            }
            _ => {}
        }
    }
    Ok(())
}

/// The valence of vertex `v` if QAS+ takes an expansion there, else what is wrong.
fn check_vertex(mesh: &PolyMesh, v: usize) -> std::result::Result<usize, String> {
    let nv = mesh.num_vertices();
    if v >= nv {
        return Err(format!(
            "vertex {v} does not exist: the net has {nv} vertices (0..{})",
            nv.saturating_sub(1)
        ));
    }
    if mesh.is_boundary_vertex(v) {
        return Err(format!(
            "vertex {v} lies on the boundary: QAS+ expansions apply at interior extraordinary \
             vertices"
        ));
    }
    if mesh.is_regular_quad_vertex(v) {
        return Err(format!(
            "vertex {v} is regular (valence 4, quads around it): QAS+ keeps the regular bi-3 \
             patches there, so an expansion for it would be ignored; name an extraordinary \
             vertex"
        ));
    }
    let n = mesh.valence(v);
    if !super::tables::COMPLETE_VALENCES.contains(&n) {
        return Err(format!(
            "vertex {v} has valence {n}: QAS+ has rules (and takes expansions) at valences \
             {:?} only",
            super::tables::COMPLETE_VALENCES
        ));
    }
    Ok(n)
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;
    use crate::mesh::nets::{CnetShape, cnet};

    fn check(text: &str) -> std::result::Result<(), String> {
        let net = cnet(5, CnetShape::Convex, 3);
        check_q_file(text, Path::new("e.q"), &net).map_err(|e| e.to_string())
    }

    #[crate::unit::test]
    fn the_extraordinary_vertex_and_its_sectors_pass() {
        assert_eq!(check("vertex 0\nkind c2\np 0 0 0\nq 4 2 1 0 0\n"), Ok(()));
    }

    #[crate::unit::test]
    fn unknown_regular_and_boundary_vertices_are_refused_at_their_line() {
        let e = check("# expansions\nvertex 9999\n").unwrap_err();
        assert!(
            e.starts_with("e.q:2: vertex 9999 does not exist: the net has 61 vertices"),
            "{e}"
        );
        // chart point (2, 0) of sector 0 is interior and regular
        let e = check("vertex 0\nvertex 5\n").unwrap_err();
        assert!(e.starts_with("e.q:2: vertex 5 is regular"), "{e}");
        // chart point (3, 3) of sector 0 is on the boundary
        let e = check("vertex 12\n").unwrap_err();
        assert!(
            e.starts_with("e.q:1: vertex 12 lies on the boundary"),
            "{e}"
        );
    }

    #[crate::unit::test]
    fn a_sector_beyond_the_valence_is_refused() {
        let e = check("vertex 0\nq 5 2 1 0 0\n").unwrap_err();
        assert!(
            e.starts_with("e.q:2: sector 5 of vertex 0: the vertex has valence 5"),
            "{e}"
        );
    }

    #[crate::unit::test]
    fn a_valence_without_rules_is_refused() {
        let net = cnet(9, CnetShape::Convex, 3);
        let e = check_q_file("vertex 0\n", Path::new("e.q"), &net).unwrap_err();
        assert!(e.to_string().contains("vertex 0 has valence 9"), "{e}");
    }
}
