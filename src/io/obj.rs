//! Wavefront OBJ: a hand-written reader and a writer.
//!
//! The reader is hand-written (rather than `tobj`) so that every error names the file line. It
//! reads `v` lines (x y z; an optional w or vertex colour is ignored) and `f` lines (n-gons, in
//! the forms `v`, `v/vt`, `v//vn`, `v/vt/vn`, with positive or negative, i.e. relative, indices),
//! joins lines continued with a trailing backslash, skips `#` comments and ignores every other
//! statement (`vt vn vp g o s usemtl mtllib l p ...`), counting them for one summary warning.
//! Faces are then validated by [`PolyMesh::new`]; its errors are reported at the line of the face
//! or vertex they concern.

use super::{
    ChunkedText, LoadedMesh, Polygons, dropped_warning, io_error, locate_mesh_error, parse_error,
    push_point,
};
use crate::error::Result;
use crate::mesh::PolyMesh;
use std::collections::BTreeMap;
use std::io::{BufRead, Write};
use std::path::Path;

/// How OBJ numbers vertices, for messages about [`PolyMesh`] validation errors.
const NOTE: &str =
    " (faces and vertices are counted from 0 in file order; OBJ vertex numbers are 1 higher)";

/// Reads an OBJ file.
pub fn read_obj(path: &Path) -> Result<LoadedMesh> {
    let file = std::fs::File::open(path).map_err(|e| io_error(path, e))?;
    read_obj_from(std::io::BufReader::with_capacity(1 << 16, file), path)
}

/// Reads OBJ from any buffered reader; `path` is used in messages only.
pub fn read_obj_from<R: BufRead>(mut reader: R, path: &Path) -> Result<LoadedMesh> {
    let mut positions: Vec<[f64; 3]> = Vec::new();
    let mut vertex_line: Vec<u32> = Vec::new();
    let mut face_start: Vec<u32> = vec![0];
    let mut corners: Vec<u32> = Vec::new();
    let mut face_line: Vec<u32> = Vec::new();
    let mut ignored: BTreeMap<String, usize> = BTreeMap::new();
    // Positive indices may refer to vertices defined later; check them at the end.
    let mut max_index: Option<(usize, usize)> = None; // (0-based index, line)

    let mut raw = Vec::new();
    let mut logical = String::new();
    let mut line_no = 0usize;
    let mut start_line = 0usize;
    loop {
        raw.clear();
        let n = reader
            .read_until(b'\n', &mut raw)
            .map_err(|e| io_error(path, e))?;
        if n == 0 {
            if logical.is_empty() {
                break;
            }
        } else {
            line_no += 1;
            if logical.is_empty() {
                start_line = line_no;
            }
            let text = String::from_utf8_lossy(&raw);
            let text = text.trim_end_matches(['\n', '\r']);
            if let Some(head) = text.strip_suffix('\\') {
                logical.push_str(head);
                logical.push(' ');
                continue;
            }
            logical.push_str(text);
        }
        let line = start_line;
        let content = match logical.find('#') {
            Some(i) => &logical[..i],
            None => &logical[..],
        };
        let mut tokens = content.split_whitespace();
        if let Some(keyword) = tokens.next() {
            match keyword {
                "v" => {
                    let mut p = [0.0; 3];
                    for (k, c) in p.iter_mut().enumerate() {
                        let tok = tokens.next().ok_or_else(|| {
                            parse_error(
                                path,
                                line,
                                format!(
                                    "vertex has {k} coordinate{}; a 'v' line needs x y z",
                                    if k == 1 { "" } else { "s" }
                                ),
                            )
                        })?;
                        *c = tok.parse::<f64>().map_err(|_| {
                            parse_error(
                                path,
                                line,
                                format!(
                                    "bad number '{tok}' for the {} coordinate of a vertex",
                                    ["x", "y", "z"][k]
                                ),
                            )
                        })?;
                    }
                    positions.push(p);
                    vertex_line.push(line as u32);
                }
                "f" | "fo" => {
                    let before = corners.len();
                    for tok in tokens {
                        let vpart = tok.split('/').next().unwrap_or("");
                        let idx: i64 = vpart.parse().map_err(|_| {
                            parse_error(
                                path,
                                line,
                                format!("bad vertex reference '{tok}' in face (expected v, v/vt, v//vn or v/vt/vn)"),
                            )
                        })?;
                        let v = if idx > 0 {
                            if idx > u32::MAX as i64 {
                                return Err(parse_error(
                                    path,
                                    line,
                                    format!(
                                        "vertex index {idx} is beyond fairsub's limit of 2^32 - 1 vertices"
                                    ),
                                ));
                            }
                            let v = (idx - 1) as usize;
                            if max_index.is_none_or(|(m, _)| v > m) {
                                max_index = Some((v, line));
                            }
                            v
                        } else if idx < 0 {
                            let back = idx.unsigned_abs() as usize;
                            if back > positions.len() {
                                return Err(parse_error(
                                    path,
                                    line,
                                    format!(
                                        "relative vertex index {idx} reaches before the first vertex ({} vertices are defined above this face)",
                                        positions.len()
                                    ),
                                ));
                            }
                            positions.len() - back
                        } else {
                            return Err(parse_error(
                                path,
                                line,
                                "vertex index 0 in face: OBJ indices start at 1 (or are negative, counting back)",
                            ));
                        };
                        corners.push(v as u32);
                    }
                    let n = corners.len() - before;
                    if n < 3 {
                        return Err(parse_error(
                            path,
                            line,
                            format!("face has {n} vertices; a face needs at least 3"),
                        ));
                    }
                    if corners.len() > u32::MAX as usize {
                        return Err(parse_error(path, line, "more than 2^32 - 1 face corners"));
                    }
                    face_start.push(corners.len() as u32);
                    face_line.push(line as u32);
                }
                other => *ignored.entry(other.to_string()).or_insert(0) += 1,
            }
        }
        logical.clear();
        if n == 0 {
            break;
        }
    }

    if let Some((m, line)) = max_index
        && m >= positions.len()
    {
        return Err(parse_error(
            path,
            line,
            format!(
                "face refers to vertex {}, but the file defines only {} vertices",
                m + 1,
                positions.len()
            ),
        ));
    }
    if face_line.is_empty() {
        return Err(parse_error(
            path,
            0,
            format!(
                "no faces ('f' lines) found ({} vertices read); fairsub needs a polygon mesh",
                positions.len()
            ),
        ));
    }

    let fl = |f: usize| face_line.get(f).map(|&l| l as usize);
    let vl = |v: usize| vertex_line.get(v).map(|&l| l as usize);
    let mesh = PolyMesh::from_flat(positions, face_start, corners)
        .map_err(|e| locate_mesh_error(path, e, &fl, &vl, NOTE))?;
    let mut warnings = Vec::new();
    if let Some(w) = dropped_warning(&mesh, &vl, "counted from 0") {
        warnings.push(w);
    }
    if !ignored.is_empty() {
        let list: Vec<String> = ignored.iter().map(|(k, n)| format!("{n} '{k}'")).collect();
        warnings.push(format!(
            "ignored statements: {} (fairsub reads only 'v' and 'f')",
            list.join(", ")
        ));
    }
    Ok(LoadedMesh { mesh, warnings })
}

/// Writes polygons as OBJ (`v x y z` lines with round-trip precision, `f` lines 1-based).
pub(crate) fn write_obj_to(w: &mut dyn Write, p: &Polygons<'_>) -> std::io::Result<()> {
    use std::fmt::Write as _;
    let mut out = ChunkedText::new(w);
    let _ = writeln!(
        out.buf,
        "# fairsub: {} vertices, {} faces",
        p.positions.len(),
        p.num_faces()
    );
    for &q in p.positions {
        out.buf.push_str("v ");
        push_point(&mut out.buf, q);
        out.buf.push('\n');
        out.maybe_flush()?;
    }
    for f in 0..p.num_faces() {
        out.buf.push('f');
        for &v in p.face(f) {
            let _ = write!(out.buf, " {}", v as u64 + 1);
        }
        out.buf.push('\n');
        out.maybe_flush()?;
    }
    out.finish()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::Error;

    fn read(s: &str) -> Result<LoadedMesh> {
        read_obj_from(s.as_bytes(), Path::new("t.obj"))
    }

    fn parse_err(s: &str) -> (usize, String) {
        match read(s) {
            Err(Error::Parse { line, msg, path }) => {
                assert_eq!(path, Path::new("t.obj"));
                (line, msg)
            }
            other => panic!("expected a parse error, got {other:?}"),
        }
    }

    #[test]
    fn reads_ngons_slash_forms_and_negative_indices() {
        let src = "# a quad and a pentagon sharing an edge\n\
                   mtllib x.mtl\n\
                   o thing\n\
                   v 0 0 0\n\
                   v 1 0 0 1.0\n\
                   v 1 1 0 0.5 0.5 0.5\n\
                   v 0 1 0\n\
                   vt 0 0\n\
                   vn 0 0 1\n\
                   f 1/1 2/1/1 3//1 4\n\
                   v 2 0 0\n\
                   v 2.5 0.5 0\n\
                   v 2 1 0\n\
                   g g1\n\
                   s off\n\
                   usemtl m\n\
                   f -6 -3 -2 -1 -5   # relative: 2 5 6 7 3 (1-based)\n";
        let m = read(src).unwrap();
        assert_eq!(m.mesh.num_vertices(), 7);
        assert_eq!(m.mesh.num_faces(), 2);
        assert_eq!(m.mesh.face(0), &[0, 1, 2, 3]);
        assert_eq!(m.mesh.face(1), &[1, 4, 5, 6, 2]);
        assert_eq!(m.mesh.position(5), [2.5, 0.5, 0.0]);
        assert_eq!(m.mesh.position(1), [1.0, 0.0, 0.0]);
        assert_eq!(m.warnings.len(), 1, "{:?}", m.warnings);
        let w = &m.warnings[0];
        for part in [
            "1 'vt'",
            "1 'vn'",
            "1 'g'",
            "1 'o'",
            "1 's'",
            "1 'usemtl'",
            "1 'mtllib'",
        ] {
            assert!(w.contains(part), "{w}");
        }
    }

    #[test]
    fn line_continuation_and_crlf() {
        let src = "v 0 0 0\r\nv 1 \\\r\n 0 0\r\nv 0 1 0\r\nf 1 2 \\\n3\r\nf 1 2 x\n";
        let (line, msg) = parse_err(src);
        // Physical lines count: the bad face is on line 7.
        assert_eq!(line, 7, "{msg}");
        assert!(msg.contains("'x'"), "{msg}");
        let m = read("v 0 0 0\r\nv 1 \\\r\n 0 0\r\nv 0 1 0\r\nf 1 2 \\\n3\r\n").unwrap();
        assert_eq!(m.mesh.position(1), [1.0, 0.0, 0.0]);
        assert_eq!(m.mesh.face(0), &[0, 1, 2]);
    }

    #[test]
    fn dropped_vertex_is_reported() {
        let m = read("v 0 0 0\nv 9 9 9\nv 1 0 0\nv 0 1 0\nf 1 3 4\n").unwrap();
        assert_eq!(m.mesh.num_vertices(), 3);
        assert_eq!(m.mesh.position(1), [1.0, 0.0, 0.0]);
        assert_eq!(m.warnings.len(), 1);
        assert!(
            m.warnings[0].contains("1 vertices are used by no face"),
            "{}",
            m.warnings[0]
        );
        assert!(
            m.warnings[0].contains("vertex 1 on line 2"),
            "{}",
            m.warnings[0]
        );
    }

    #[test]
    fn errors_name_lines() {
        let (l, m) = parse_err("v 0 0 0\nv 1 0 0\nv 0 1.x 0\n");
        assert_eq!(l, 3);
        assert!(m.contains("'1.x'") && m.contains("y coordinate"), "{m}");
        let (l, m) = parse_err("v 0 0 0\nv 1 0\n");
        assert_eq!(l, 2);
        assert!(m.contains("2 coordinates"), "{m}");
        let (l, m) = parse_err("v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 0\n");
        assert_eq!(l, 5);
        assert!(m.contains("index 0"), "{m}");
        let (l, m) = parse_err("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\nf 1 2 3\n");
        assert_eq!(l, 5);
        assert!(
            m.contains("vertex 9") && m.contains("only 3 vertices"),
            "{m}"
        );
        let (l, m) = parse_err("v 0 0 0\nv 1 0 0\nf 1 -3 2\n");
        assert_eq!(l, 3);
        assert!(m.contains("-3"), "{m}");
        let (l, m) = parse_err("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n");
        assert_eq!(l, 4);
        assert!(m.contains("2 vertices"), "{m}");
        let (l, m) = parse_err("v 0 0 0\n");
        assert_eq!(l, 0);
        assert!(m.contains("no faces"), "{m}");
    }

    #[test]
    fn mesh_validation_errors_point_at_the_face_line() {
        // Third face repeats a vertex.
        let src = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n# c\nf 1 1 2\n";
        let (l, m) = parse_err(src);
        assert_eq!(l, 8);
        assert!(m.contains("face 2 uses vertex 0 more than once"), "{m}");
        // Second face uses edge 1->2 in the same direction as the first.
        let src = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 3 4\n";
        let (l, m) = parse_err(src);
        assert_eq!(l, 6);
        assert!(m.contains("inconsistent orientation"), "{m}");
        // A NaN coordinate names the vertex line.
        let (l, m) = parse_err("v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n");
        assert_eq!(l, 2);
        assert!(m.contains("vertex 1"), "{m}");
    }

    #[test]
    fn writer_roundtrips_exactly() {
        let pos = vec![
            [0.1, -2.0 / 3.0, 1e-300],
            [1.0, 0.0, 12345.678901234567],
            [1.0, 1.0, -0.0],
            [0.0, 1.0, 3.0e20],
        ];
        let p = Polygons::new(&pos, &[0, 4], &[0, 1, 2, 3]).unwrap();
        let mut buf = Vec::new();
        write_obj_to(&mut buf, &p).unwrap();
        let m = read_obj_from(&buf[..], Path::new("w.obj")).unwrap();
        assert_eq!(m.mesh.positions(), &pos[..]);
        assert_eq!(m.mesh.face(0), &[0, 1, 2, 3]);
        assert!(m.warnings.is_empty(), "{:?}", m.warnings);
    }
}
