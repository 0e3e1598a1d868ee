//! Geomview OFF: reader and writer (ascii).
//!
//! The reader accepts the header keywords `OFF`, `COFF`, `NOFF`, `CNOFF`, `STOFF` and the like
//! (per-vertex colours, normals and texture coordinates after x y z are ignored, as is per-face
//! colour after the indices), `#` comments, blank lines, counts on the header line or the next
//! one, and a file without header keyword that starts with the counts. It reads line by line (one
//! vertex or face per line, as every OFF writer does), so errors name the line. `4OFF`, `nOFF`
//! (other dimensions) and `OFF BINARY` are rejected as unsupported.

use super::{
    ChunkedText, LoadedMesh, Polygons, dropped_warning, io_error, locate_mesh_error, parse_error,
    push_point, read_to_string_lossy,
};
use crate::error::{Error, Result};
use crate::mesh::PolyMesh;
use std::io::{Read, Write};
use std::path::Path;

/// Reads an OFF file.
pub fn read_off(path: &Path) -> Result<LoadedMesh> {
    let file = std::fs::File::open(path).map_err(|e| io_error(path, e))?;
    read_off_from(std::io::BufReader::with_capacity(1 << 16, file), path)
}

/// Reads OFF from any reader; `path` is used in messages only.
pub fn read_off_from<R: Read>(reader: R, path: &Path) -> Result<LoadedMesh> {
    let text = read_to_string_lossy(reader, path)?;
    // Non-empty content lines (comments stripped) with their 1-based numbers.
    let mut lines = text.lines().enumerate().filter_map(|(i, l)| {
        let l = match l.find('#') {
            Some(k) => &l[..k],
            None => l,
        };
        let l = l.trim();
        (!l.is_empty()).then_some((i + 1, l))
    });

    let (first_line, first) = lines
        .next()
        .ok_or_else(|| parse_error(path, 0, "empty file: expected an 'OFF' header"))?;
    let mut toks: Vec<&str> = first.split_whitespace().collect();
    let mut warnings = Vec::new();
    let mut counts_line = first_line;
    if toks[0].parse::<u64>().is_err() {
        let kw = toks[0];
        let Some(prefix) = kw.strip_suffix("OFF") else {
            return Err(parse_error(
                path,
                first_line,
                format!("expected the header keyword 'OFF' (or COFF, NOFF, ...), found '{kw}'"),
            ));
        };
        if prefix.contains('4') || prefix.contains('n') {
            return Err(Error::Unsupported(format!(
                "{}:{first_line}: '{kw}' files (points of other dimension than 3) are not supported",
                path.display()
            )));
        }
        if let Some(bad) = prefix.chars().find(|c| !matches!(c, 'S' | 'T' | 'C' | 'N')) {
            return Err(parse_error(
                path,
                first_line,
                format!("unknown OFF header keyword '{kw}' (unexpected '{bad}')"),
            ));
        }
        toks.remove(0);
        if toks
            .first()
            .is_some_and(|t| t.eq_ignore_ascii_case("BINARY"))
        {
            return Err(Error::Unsupported(format!(
                "{}:{first_line}: binary OFF is not supported; convert it to ascii OFF, OBJ or PLY",
                path.display()
            )));
        }
        if toks.is_empty() {
            let (l, t) = lines.next().ok_or_else(|| {
                parse_error(
                    path,
                    first_line,
                    "file ends after the header: expected the counts line 'vertices faces edges'",
                )
            })?;
            counts_line = l;
            toks = t.split_whitespace().collect();
        }
    } else {
        warnings.push("no 'OFF' header keyword; the first line was read as the counts".to_string());
    }
    if toks.len() < 2 {
        return Err(parse_error(
            path,
            counts_line,
            "expected the counts 'vertices faces [edges]'",
        ));
    }
    let count = |k: usize, what: &str| -> Result<usize> {
        toks[k].parse::<usize>().map_err(|_| {
            parse_error(
                path,
                counts_line,
                format!(
                    "bad {what} count '{}' (expected a non-negative integer)",
                    toks[k]
                ),
            )
        })
    };
    let nv = count(0, "vertex")?;
    if nv > u32::MAX as usize {
        return Err(parse_error(
            path,
            counts_line,
            format!("{nv} vertices are more than fairsub's limit of 2^32 - 1"),
        ));
    }
    let nf = count(1, "face")?;

    // Counts come from the file: never reserve more than its size can hold (a vertex or face
    // line has at least 6 bytes), so a garbage count cannot trigger a huge allocation.
    let cap = |n: usize| n.min(text.len() / 6 + 1);
    let mut positions = Vec::with_capacity(cap(nv));
    let mut vertex_line = Vec::with_capacity(cap(nv));
    for k in 0..nv {
        let (l, t) = lines
            .next()
            .ok_or_else(|| parse_error(path, 0, format!("file ends after {k} of {nv} vertices")))?;
        let mut it = t.split_whitespace();
        let mut p = [0.0; 3];
        for (c, slot) in p.iter_mut().enumerate() {
            let tok = it.next().ok_or_else(|| {
                parse_error(
                    path,
                    l,
                    format!("vertex {k} has {c} coordinates; expected x y z"),
                )
            })?;
            *slot = tok.parse().map_err(|_| {
                parse_error(
                    path,
                    l,
                    format!(
                        "bad number '{tok}' for the {} coordinate of vertex {k}",
                        ["x", "y", "z"][c]
                    ),
                )
            })?;
        }
        positions.push(p);
        vertex_line.push(l as u32);
    }

    let mut face_start: Vec<u32> = Vec::with_capacity(cap(nf) + 1);
    face_start.push(0);
    let mut corners: Vec<u32> = Vec::with_capacity(3 * cap(nf));
    let mut face_line = Vec::with_capacity(cap(nf));
    for k in 0..nf {
        let (l, t) = lines
            .next()
            .ok_or_else(|| parse_error(path, 0, format!("file ends after {k} of {nf} faces")))?;
        let mut it = t.split_whitespace();
        let n_tok = it.next().unwrap_or("");
        let n: usize = n_tok
            .parse()
            .map_err(|_| parse_error(path, l, format!("bad corner count '{n_tok}' of face {k}")))?;
        if n < 3 {
            return Err(parse_error(
                path,
                l,
                format!("face {k} has {n} corners; a face needs at least 3"),
            ));
        }
        for c in 0..n {
            let tok = it.next().ok_or_else(|| {
                parse_error(
                    path,
                    l,
                    format!("face {k} announces {n} corners but lists {c}"),
                )
            })?;
            let v: usize = tok.parse().map_err(|_| {
                parse_error(path, l, format!("bad vertex index '{tok}' in face {k}"))
            })?;
            if v >= nv {
                return Err(parse_error(
                    path,
                    l,
                    format!(
                        "face {k} refers to vertex {v}, but the file has {nv} vertices (indices 0..{})",
                        nv.saturating_sub(1)
                    ),
                ));
            }
            corners.push(v as u32);
        }
        if corners.len() > u32::MAX as usize {
            return Err(parse_error(path, l, "more than 2^32 - 1 face corners"));
        }
        face_start.push(corners.len() as u32);
        face_line.push(l as u32);
    }
    if let Some((l, _)) = lines.next() {
        warnings.push(format!(
            "ignored content after the last face, from line {l} on"
        ));
    }
    if face_line.is_empty() {
        return Err(parse_error(
            path,
            counts_line,
            format!("no faces ({nv} vertices); fairsub needs a polygon mesh"),
        ));
    }
    let fl = |f: usize| face_line.get(f).map(|&l| l as usize);
    let vl = |v: usize| vertex_line.get(v).map(|&l| l as usize);
    let mesh = PolyMesh::from_flat(positions, face_start, corners).map_err(|e| {
        locate_mesh_error(
            path,
            e,
            &fl,
            &vl,
            " (faces and vertices counted from 0 in file order)",
        )
    })?;
    if let Some(w) = dropped_warning(&mesh, &vl, "counted from 0") {
        warnings.push(w);
    }
    Ok(LoadedMesh { mesh, warnings })
}

/// Writes polygons as ascii OFF with round-trip precision.
pub(crate) fn write_off_to(w: &mut dyn Write, p: &Polygons<'_>) -> std::io::Result<()> {
    use std::fmt::Write as _;
    let mut out = ChunkedText::new(w);
    let _ = writeln!(out.buf, "OFF\n{} {} 0", p.positions.len(), p.num_faces());
    for &q in p.positions {
        push_point(&mut out.buf, q);
        out.buf.push('\n');
        out.maybe_flush()?;
    }
    for f in 0..p.num_faces() {
        let face = p.face(f);
        let _ = write!(out.buf, "{}", face.len());
        for &v in face {
            let _ = write!(out.buf, " {v}");
        }
        out.buf.push('\n');
        out.maybe_flush()?;
    }
    out.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(s: &str) -> Result<LoadedMesh> {
        read_off_from(s.as_bytes(), Path::new("t.off"))
    }

    fn parse_err(s: &str) -> (usize, String) {
        match read(s) {
            Err(Error::Parse { line, msg, .. }) => (line, msg),
            other => panic!("expected a parse error, got {other:?}"),
        }
    }

    #[test]
    fn reads_off_with_comments_and_ngons() {
        let src = "OFF # header\n# a comment\n\n5 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0.5 2 0.25\n\
                   4 0 1 2 3\n3 3 2 4\n";
        let m = read(src).unwrap();
        assert_eq!(m.mesh.num_faces(), 2);
        assert_eq!(m.mesh.face(0), &[0, 1, 2, 3]);
        assert_eq!(m.mesh.face(1), &[3, 2, 4]);
        assert_eq!(m.mesh.position(4), [0.5, 2.0, 0.25]);
        assert!(m.warnings.is_empty(), "{:?}", m.warnings);
    }

    #[test]
    fn reads_coff_noff_and_counts_on_header_line() {
        let src = "COFF 3 1 3\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n0 1 0 0 0 255 255\n3 0 1 2 10 20 30\n";
        let m = read(src).unwrap();
        assert_eq!(m.mesh.position(1), [1.0, 0.0, 0.0]);
        assert_eq!(m.mesh.face(0), &[0, 1, 2]);
        let src = "NOFF\n3 1 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n";
        let m = read(src).unwrap();
        assert_eq!(m.mesh.position(2), [0.0, 1.0, 0.0]);
        let m = read("3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 2 0 1\n").unwrap();
        assert_eq!(m.mesh.face(0), &[2, 0, 1]);
        assert_eq!(m.warnings.len(), 1);
        assert!(m.warnings[0].contains("no 'OFF' header"));
    }

    #[test]
    fn errors_name_lines() {
        let (l, m) = parse_err("OFF\n3 1 0\n0 0 0\n1 0 zz\n0 1 0\n3 0 1 2\n");
        assert_eq!(l, 4);
        assert!(m.contains("'zz'") && m.contains("vertex 1"), "{m}");
        let (l, m) = parse_err("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n");
        assert_eq!(l, 6);
        assert!(m.contains("vertex 3") && m.contains("3 vertices"), "{m}");
        let (l, m) = parse_err("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n");
        assert_eq!(l, 6);
        assert!(m.contains("announces 4 corners but lists 3"), "{m}");
        let (_, m) = parse_err("OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n");
        assert!(m.contains("after 3 of 4 vertices"), "{m}");
        let (l, m) = parse_err("OFF\n3 x 0\n");
        assert_eq!(l, 2);
        assert!(m.contains("face count 'x'"), "{m}");
        let (l, m) = parse_err("PLY\n");
        assert_eq!(l, 1);
        assert!(m.contains("'PLY'"), "{m}");
        let (l, m) = parse_err("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n");
        assert_eq!(l, 6);
        assert!(m.contains("2 corners"), "{m}");
        assert!(matches!(read("4OFF\n"), Err(Error::Unsupported(_))));
        // A huge count in a tiny file fails cleanly (and allocates nothing big).
        let (_, m) = parse_err("OFF\n4000000000 4000000000 0\n0 0 0\n");
        assert!(m.contains("after 1 of 4000000000 vertices"), "{m}");
        assert!(matches!(read("OFF BINARY\n"), Err(Error::Unsupported(_))));
        // Validation error mapped to the face line.
        let (l, m) = parse_err("OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 2 3\n");
        assert_eq!(l, 8);
        assert!(m.contains("inconsistent orientation"), "{m}");
    }

    #[test]
    fn writer_roundtrips_exactly() {
        let pos = vec![
            [0.1, -2.0 / 3.0, 1e-300],
            [1.0, 0.0, 12345.678901234567],
            [1.0, 1.0, -7.5],
            [0.0, 1.0, 3.0e20],
            [0.5, 2.0, 0.0],
        ];
        let p = Polygons::new(&pos, &[0, 4, 7], &[0, 1, 2, 3, 3, 2, 4]).unwrap();
        let mut buf = Vec::new();
        write_off_to(&mut buf, &p).unwrap();
        let m = read_off_from(&buf[..], Path::new("w.off")).unwrap();
        assert_eq!(m.mesh.positions(), &pos[..]);
        assert_eq!(m.mesh.face(0), &[0, 1, 2, 3]);
        assert_eq!(m.mesh.face(1), &[3, 2, 4]);
        assert!(m.warnings.is_empty());
    }
}
