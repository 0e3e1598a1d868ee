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

/// The state of the OBJ reader between statements.
struct ObjState {
    positions: Vec<[f64; 3]>,
    vertex_line: Vec<u32>,
    face_start: Vec<u32>,
    corners: Vec<u32>,
    face_line: Vec<u32>,
    ignored: BTreeMap<String, usize>,
    /// Largest positive index seen: (0-based index, line). Positive indices may refer to
    /// vertices defined later, so they are checked at the end.
    max_index: Option<(usize, usize)>,
    /// Token ranges of the current statement (reused).
    tokens: Vec<(usize, usize)>,
}

/// Whether `b` is an ASCII character with the Unicode `White_Space` property (what
/// `str::split_whitespace` splits on).
#[inline]
fn is_space(b: u8) -> bool {
    matches!(b, b' ' | b'\t'..=b'\r')
}

/// Parses an integer the way `str::parse::<i64>` does (optional sign, decimal digits, no
/// overflow), directly on bytes.
#[inline]
fn parse_i64(s: &[u8]) -> Option<i64> {
    let (neg, digits) = match s.first()? {
        b'-' => (true, &s[1..]),
        b'+' => (false, &s[1..]),
        _ => (false, s),
    };
    if digits.is_empty() {
        return None;
    }
    let mut x: i64 = 0;
    for &d in digits {
        let d = d.wrapping_sub(b'0');
        if d > 9 {
            return None;
        }
        x = x.checked_mul(10)?;
        x = if neg {
            x.checked_sub(d as i64)?
        } else {
            x.checked_add(d as i64)?
        };
    }
    Some(x)
}

impl ObjState {
    /// Handles one logical line (continuations joined, line ending removed) that starts on
    /// physical line `line`.
    fn statement(&mut self, bytes: &[u8], line: usize, path: &Path) -> Result<()> {
        if bytes.is_ascii() {
            // Fast path: bytes are characters; split on the same whitespace as below.
            let end = bytes.iter().position(|&b| b == b'#').unwrap_or(bytes.len());
            let mut tokens = std::mem::take(&mut self.tokens);
            tokens.clear();
            let mut i = 0;
            while i < end {
                while i < end && is_space(bytes[i]) {
                    i += 1;
                }
                let start = i;
                while i < end && !is_space(bytes[i]) {
                    i += 1;
                }
                if i > start {
                    tokens.push((start, i));
                }
            }
            let text = std::str::from_utf8(bytes).expect("ASCII is UTF-8");
            let r = self.tokens_statement(text, &tokens, line, path);
            self.tokens = tokens;
            r
        } else {
            // Other text: invalid UTF-8 replaced, Unicode whitespace.
            let text = String::from_utf8_lossy(bytes);
            let content = match text.find('#') {
                Some(i) => &text[..i],
                None => &text[..],
            };
            let base = content.as_ptr() as usize;
            let tokens: Vec<(usize, usize)> = content
                .split_whitespace()
                .map(|t| {
                    let s = t.as_ptr() as usize - base;
                    (s, s + t.len())
                })
                .collect();
            self.tokens_statement(content, &tokens, line, path)
        }
    }

    /// Handles a statement given as token ranges into `text`.
    fn tokens_statement(
        &mut self,
        text: &str,
        tokens: &[(usize, usize)],
        line: usize,
        path: &Path,
    ) -> Result<()> {
        let tok = |k: usize| &text[tokens[k].0..tokens[k].1];
        let Some(&(ks, ke)) = tokens.first() else {
            return Ok(());
        };
        match &text[ks..ke] {
            "v" => {
                let mut p = [0.0; 3];
                for (k, c) in p.iter_mut().enumerate() {
                    if k + 1 >= tokens.len() {
                        return Err(parse_error(
                            path,
                            line,
                            format!(
                                "vertex has {k} coordinate{}; a 'v' line needs x y z",
                                if k == 1 { "" } else { "s" }
                            ),
                        ));
                    }
                    let t = tok(k + 1);
                    *c = t.parse::<f64>().map_err(|_| {
                        parse_error(
                            path,
                            line,
                            format!(
                                "bad number '{t}' for the {} coordinate of a vertex",
                                ["x", "y", "z"][k]
                            ),
                        )
                    })?;
                }
                self.positions.push(p);
                self.vertex_line.push(line as u32);
            }
            "f" | "fo" => {
                let before = self.corners.len();
                for k in 1..tokens.len() {
                    let t = tok(k);
                    let vpart = t.as_bytes().split(|&b| b == b'/').next().unwrap_or(b"");
                    let idx = parse_i64(vpart).ok_or_else(|| {
                        parse_error(
                            path,
                            line,
                            format!(
                                "bad vertex reference '{t}' in face (expected v, v/vt, v//vn or v/vt/vn)"
                            ),
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
                        if self.max_index.is_none_or(|(m, _)| v > m) {
                            self.max_index = Some((v, line));
                        }
                        v
                    } else if idx < 0 {
                        let back = idx.unsigned_abs() as usize;
                        if back > self.positions.len() {
                            return Err(parse_error(
                                path,
                                line,
                                format!(
                                    "relative vertex index {idx} reaches before the first vertex ({} vertices are defined above this face)",
                                    self.positions.len()
                                ),
                            ));
                        }
                        self.positions.len() - back
                    } else {
                        return Err(parse_error(
                            path,
                            line,
                            "vertex index 0 in face: OBJ indices start at 1 (or are negative, counting back)",
                        ));
                    };
                    self.corners.push(v as u32);
                }
                let n = self.corners.len() - before;
                if n < 3 {
                    return Err(parse_error(
                        path,
                        line,
                        format!("face has {n} vertices; a face needs at least 3"),
                    ));
                }
                if self.corners.len() > u32::MAX as usize {
                    return Err(parse_error(path, line, "more than 2^32 - 1 face corners"));
                }
                self.face_start.push(self.corners.len() as u32);
                self.face_line.push(line as u32);
            }
            other => match self.ignored.get_mut(other) {
                Some(n) => *n += 1,
                None => {
                    self.ignored.insert(other.to_string(), 1);
                }
            },
        }
        Ok(())
    }
}

/// Reads OBJ from any buffered reader; `path` is used in messages only.
///
/// Lines are parsed in place in the reader's buffer (no copy or allocation per line); a line
/// that straddles the end of the buffer, or continues with a trailing backslash, is collected
/// first.
pub fn read_obj_from<R: BufRead>(mut reader: R, path: &Path) -> Result<LoadedMesh> {
    let mut st = ObjState {
        positions: Vec::new(),
        vertex_line: Vec::new(),
        face_start: vec![0],
        corners: Vec::new(),
        face_line: Vec::new(),
        ignored: BTreeMap::new(),
        max_index: None,
        tokens: Vec::new(),
    };
    // A logical line being continued (trailing backslash), and the line it started on.
    let mut logical: Vec<u8> = Vec::new();
    let mut start_line = 0usize;
    let mut line_no = 0usize;
    let mut raw = Vec::new();
    // One physical line, without its line feed.
    let mut physical = |st: &mut ObjState, text: &[u8], logical: &mut Vec<u8>| -> Result<()> {
        line_no += 1;
        let text = match text.iter().rposition(|&b| b != b'\r') {
            Some(i) => &text[..=i],
            None => &text[..0],
        };
        if logical.is_empty() {
            start_line = line_no;
        }
        if let Some(head) = text.strip_suffix(b"\\") {
            logical.extend_from_slice(head);
            logical.push(b' ');
            return Ok(());
        }
        if logical.is_empty() {
            st.statement(text, start_line, path)
        } else {
            logical.extend_from_slice(text);
            let r = st.statement(logical, start_line, path);
            logical.clear();
            r
        }
    };
    loop {
        let buf = reader.fill_buf().map_err(|e| io_error(path, e))?;
        if buf.is_empty() {
            break;
        }
        // Every complete line in the buffer, in place.
        let mut used = 0;
        while let Some(i) = buf[used..].iter().position(|&b| b == b'\n') {
            physical(&mut st, &buf[used..used + i], &mut logical)?;
            used += i + 1;
        }
        if used > 0 {
            reader.consume(used);
            continue;
        }
        // A line longer than the rest of the buffer: collect it.
        raw.clear();
        reader
            .read_until(b'\n', &mut raw)
            .map_err(|e| io_error(path, e))?;
        let text = raw.strip_suffix(b"\n").unwrap_or(&raw);
        physical(&mut st, text, &mut logical)?;
    }
    if !logical.is_empty() {
        // The file ended inside a continued line.
        st.statement(&logical, start_line, path)?;
    }
    let ObjState {
        positions,
        vertex_line,
        face_start,
        corners,
        face_line,
        ignored,
        max_index,
        ..
    } = st;

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

    #[test]
    fn lines_across_buffer_ends_and_unicode_whitespace() {
        // A tiny reader buffer splits most lines; continuations, CRLF and comments survive.
        let src = "# x\nv 0 0 0\r\nv 1 0 0 # c\nv 0 \\\n1 0\nvt 1 1\nvt 2 2\nf 1 2 3\n";
        let m = read_obj_from(
            std::io::BufReader::with_capacity(5, src.as_bytes()),
            Path::new("b"),
        )
        .unwrap();
        assert_eq!(
            m.mesh.positions(),
            &[[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
        );
        assert!(m.warnings[0].contains("2 'vt'"), "{:?}", m.warnings);
        // Non-ASCII lines split on Unicode whitespace (no-break space), as `split_whitespace`.
        let m = read("v 0\u{a0}0 0\nv 1 0 0\nv 0 1 0\nf 1 2\u{2003}3\n").unwrap();
        assert_eq!(m.mesh.face(0), &[0, 1, 2]);
        let (l, msg) = parse_err("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 \u{e9}3\n");
        assert_eq!(l, 4);
        assert!(msg.contains("'\u{e9}3'"), "{msg}");
        // Integer forms accepted like `str::parse::<i64>`.
        assert_eq!(parse_i64(b"+12"), Some(12));
        assert_eq!(parse_i64(b"-9223372036854775808"), Some(i64::MIN));
        assert_eq!(parse_i64(b"9223372036854775808"), None);
        assert_eq!(parse_i64(b"-"), None);
        assert_eq!(parse_i64(b"1x"), None);
    }
}
