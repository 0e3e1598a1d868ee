//! Wavefront OBJ: a hand-written reader and a writer.
//!
//! The reader is hand-written (rather than `tobj`) so that every error names the file line. It
//! reads `v` lines (x y z; an optional w or vertex colour is ignored), `vt` lines (u v, an
//! optional w ignored), `f` lines (n-gons, in the forms `v`, `v/vt`, `v//vn`, `v/vt/vn`, with
//! positive or negative, i.e. relative, indices; the `vt` indices make the net's face-varying
//! texture coordinates when every face has them) and OpenSubdiv's tag lines `t` (creases,
//! corners, holes and options: `obj/tags.rs`), joins lines continued with a trailing
//! backslash, skips `#` comments and ignores every other statement (`vn vp g o s usemtl mtllib
//! l p ...`), counting them for one summary warning.
//! Text follows the rule of every reader: invalid UTF-8 only inside comments. The faces are
//! then validated as a [`PolyMesh`](crate::mesh::PolyMesh); its errors are reported at the
//! line of the face or vertex they concern.

mod tags;
mod uv;
pub(crate) use uv::write_obj_uv_to;

pub use tags::read_tag_file;

use super::text::{hash_comment, io_error, line_text, parse_error};
use super::textout::ChunkedText;
use super::{ListedMesh, LoadedMesh, Polygons, finish_listed};
use crate::error::Result;
use crate::geom::Point;
use crate::mesh::FaceVarying;
use crate::mesh::tags::Tags;
use std::collections::BTreeMap;
use std::io::{BufRead, Write};
use std::path::Path;

/// How OBJ numbers vertices, for messages about mesh validation errors.
const NOTE: &str =
    " (faces and vertices are counted from 0 in file order; OBJ vertex numbers are 1 higher)";

/// Reads an OBJ file.
pub fn read_obj(path: &Path) -> Result<LoadedMesh> {
    let file = std::fs::File::open(path).map_err(|e| io_error(path, e))?;
    read_obj_from(std::io::BufReader::with_capacity(1 << 16, file), path)
}

/// Marks a face corner without a `vt` index.
const NO_UV: u32 = u32::MAX;

/// The state of the OBJ reader between statements.
struct ObjState {
    /// What was read so far.
    data: ObjData,
    /// Largest positive index seen: (0-based index, line). Positive indices may refer to
    /// vertices defined later, so they are checked at the end.
    max_index: Option<(usize, usize)>,
    /// Largest positive `vt` index seen, as for `max_index`.
    max_uv: Option<(usize, usize)>,
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
    /// The 0-based value of a `vt` index of face corner `t` (positive or relative).
    fn uv_index(&mut self, u: &str, t: &str, line: usize, path: &Path) -> Result<u32> {
        let idx = parse_i64(u.as_bytes()).ok_or_else(|| {
            parse_error(
                path,
                line,
                format!("bad texture index in face corner '{t}'"),
            )
        })?;
        let n = self.data.uvs.len();
        if idx > 0 && idx < u32::MAX as i64 {
            let k = (idx - 1) as usize;
            if self.max_uv.is_none_or(|(m, _)| k > m) {
                self.max_uv = Some((k, line));
            }
            Ok(k as u32)
        } else if idx < 0 && (idx.unsigned_abs() as usize) <= n {
            Ok((n - idx.unsigned_abs() as usize) as u32)
        } else {
            Err(parse_error(
                path,
                line,
                format!(
                    "texture index {idx} in face corner '{t}' is out of range ({n} 'vt' lines above)"
                ),
            ))
        }
    }

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
            // Other text: UTF-8 by the text rule (anything in the comment), Unicode whitespace.
            let content = line_text(bytes, hash_comment(bytes), path, line)?;
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
                self.data.positions.push(p);
                self.data.vertex_line.push(line as u32);
            }
            "vt" => {
                let mut t = [0.0; 2];
                for (k, c) in t.iter_mut().enumerate() {
                    if k + 1 >= tokens.len() {
                        if k == 1 {
                            break; // `vt u`: v = 0
                        }
                        return Err(parse_error(path, line, "a 'vt' line needs u [v]"));
                    }
                    let s = tok(k + 1);
                    *c = s
                        .parse::<f64>()
                        .ok()
                        .filter(|x| x.is_finite())
                        .ok_or_else(|| {
                            parse_error(
                                path,
                                line,
                                format!("bad texture coordinate '{s}' in a 'vt' line"),
                            )
                        })?;
                }
                self.data.uvs.push(t);
            }
            "t" => {
                let toks: Vec<&str> = (0..tokens.len()).map(tok).collect();
                tags::parse_tag(
                    &toks,
                    line,
                    path,
                    &mut self.data.tags,
                    &mut self.data.tag_warnings,
                )?;
            }
            "f" | "fo" => {
                let before = self.data.corners.len();
                let uv_before = self.data.uv_corners.len();
                for k in 1..tokens.len() {
                    let t = tok(k);
                    let slash = t.bytes().position(|b| b == b'/');
                    let vpart = &t.as_bytes()[..slash.unwrap_or(t.len())];
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
                        if back > self.data.positions.len() {
                            return Err(parse_error(
                                path,
                                line,
                                format!(
                                    "relative vertex index {idx} reaches before the first vertex ({} vertices are defined above this face)",
                                    self.data.positions.len()
                                ),
                            ));
                        }
                        self.data.positions.len() - back
                    } else {
                        return Err(parse_error(
                            path,
                            line,
                            "vertex index 0 in face: OBJ indices start at 1 (or are negative, counting back)",
                        ));
                    };
                    self.data.corners.push(v as u32);
                    // The texture index: between the first and the second '/', if any.
                    let uv_part = slash.and_then(|i| t[i + 1..].split('/').next());
                    let uv = match uv_part.filter(|u| !u.is_empty()) {
                        None => NO_UV,
                        Some(u) => self.uv_index(u, t, line, path)?,
                    };
                    self.data.uv_corners.push(uv);
                }
                let n = self.data.corners.len() - before;
                let with_uv = self.data.uv_corners[uv_before..]
                    .iter()
                    .filter(|&&u| u != NO_UV)
                    .count();
                if with_uv != 0 && with_uv != n {
                    self.data.uv_mixed.get_or_insert(line);
                }
                if with_uv == n {
                    self.data.faces_with_uv += 1;
                } else if self.data.faces_with_uv > 0 {
                    self.data.uv_mixed.get_or_insert(line);
                }
                if n < 3 {
                    return Err(parse_error(
                        path,
                        line,
                        format!("face has {n} vertices; a face needs at least 3"),
                    ));
                }
                if self.data.corners.len() > u32::MAX as usize {
                    return Err(parse_error(path, line, "more than 2^32 - 1 face corners"));
                }
                self.data.face_start.push(self.data.corners.len() as u32);
                self.data.face_line.push(line as u32);
            }
            other => match self.data.ignored.get_mut(other) {
                Some(n) => *n += 1,
                None => {
                    self.data.ignored.insert(other.to_string(), 1);
                }
            },
        }
        Ok(())
    }
}

/// Reads OBJ from any buffered reader; `path` is used in messages only.
pub fn read_obj_from<R: BufRead>(reader: R, path: &Path) -> Result<LoadedMesh> {
    read_obj_with(reader, path, false)
}

/// [`read_obj_from`], tolerantly with `tolerant` (see [`super::read_mesh_as`]).
pub fn read_obj_with<R: BufRead>(reader: R, path: &Path, tolerant: bool) -> Result<LoadedMesh> {
    parse_obj(reader, path)?.into_mesh_with(path, tolerant)
}

/// The statements of an OBJ file, before the mesh is built from them.
pub(crate) struct ObjData {
    /// Every `v` line's point, in file order (also those no face uses).
    pub positions: Vec<Point>,
    vertex_line: Vec<u32>,
    face_start: Vec<u32>,
    corners: Vec<u32>,
    face_line: Vec<u32>,
    ignored: BTreeMap<String, usize>,
    /// The number of physical lines.
    lines: usize,
    /// `vt` values.
    uvs: Vec<[f64; 2]>,
    /// The `vt` index of every face corner ([`NO_UV`] where none is given).
    uv_corners: Vec<u32>,
    /// Faces whose every corner has a `vt` index.
    faces_with_uv: usize,
    /// The first line of a face whose corners do not all have `vt` indices while others do.
    uv_mixed: Option<usize>,
    /// OpenSubdiv's tags (`t` lines).
    tags: Tags,
    /// Warnings about tags.
    tag_warnings: Vec<String>,
}

impl ObjData {
    /// Number of `f` lines.
    pub fn num_faces(&self) -> usize {
        self.face_line.len()
    }

    /// Builds and validates the mesh; errors name the line of the face or vertex concerned.
    pub fn into_mesh(self, path: &Path) -> Result<LoadedMesh> {
        self.into_mesh_with(path, false)
    }

    /// [`ObjData::into_mesh`], tolerantly with `tolerant` (see [`super::read_mesh_as`]); the
    /// tags and texture coordinates are attached to the mesh.
    pub fn into_mesh_with(self, path: &Path, tolerant: bool) -> Result<LoadedMesh> {
        let ObjData {
            positions,
            vertex_line,
            face_start,
            corners,
            face_line,
            ignored,
            lines,
            uvs,
            uv_corners,
            faces_with_uv,
            uv_mixed,
            tags,
            tag_warnings,
        } = self;
        if face_line.is_empty() {
            return Err(parse_error(
                path,
                lines.max(1),
                format!(
                    "no faces ('f' lines) found ({} vertices read); fairsub needs a polygon mesh",
                    positions.len()
                ),
            ));
        }
        let mut warnings = tag_warnings;
        let nf = face_line.len();
        let listed = ListedMesh {
            positions,
            face_start,
            corners,
            vertex_line,
            face_line,
        };
        let mesh = finish_listed(path, listed, NOTE, &mut warnings, tolerant)?;
        let mut mesh = mesh.with_tags(&tags, path)?;
        if let Some(line) = uv_mixed {
            warnings.push(format!(
                "texture coordinates ignored: the face on line {line} has corners without 'vt' \
                 indices while other faces have them"
            ));
        } else if faces_with_uv == nf && nf > 0 {
            let mut ex = mesh.take_extras().unwrap_or_default();
            ex.uv = Some(FaceVarying {
                values: uvs,
                corners: uv_corners,
                names: ["u".into(), "v".into()],
                classes: Vec::new(),
            });
            mesh.set_extras(Some(ex));
        }
        if !ignored.is_empty() {
            let list: Vec<String> = ignored.iter().map(|(k, n)| format!("{n} '{k}'")).collect();
            warnings.push(format!(
                "ignored statements: {} (fairsub reads only 'v', 'vt', 'f' and 't')",
                list.join(", ")
            ));
        }
        Ok(LoadedMesh { mesh, warnings })
    }
}

/// Reads the statements of an OBJ file (see [`read_obj_from`]); the mesh is not built yet.
///
/// Lines are parsed in place in the reader's buffer (no copy or allocation per line); a line
/// that straddles the end of the buffer, or continues with a trailing backslash, is collected
/// first.
pub(crate) fn parse_obj<R: BufRead>(mut reader: R, path: &Path) -> Result<ObjData> {
    let mut st = ObjState {
        data: ObjData {
            positions: Vec::new(),
            vertex_line: Vec::new(),
            face_start: vec![0],
            corners: Vec::new(),
            face_line: Vec::new(),
            ignored: BTreeMap::new(),
            lines: 0,
            uvs: Vec::new(),
            uv_corners: Vec::new(),
            faces_with_uv: 0,
            uv_mixed: None,
            tags: Tags::default(),
            tag_warnings: Vec::new(),
        },
        max_index: None,
        max_uv: None,
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
    let mut data = st.data;
    if let Some((m, line)) = st.max_uv
        && m >= data.uvs.len()
    {
        return Err(parse_error(
            path,
            line,
            format!(
                "face refers to texture coordinate {}, but the file defines only {} 'vt' lines",
                m + 1,
                data.uvs.len()
            ),
        ));
    }
    if let Some((m, line)) = st.max_index
        && m >= data.positions.len()
    {
        return Err(parse_error(
            path,
            line,
            format!(
                "face refers to vertex {}, but the file defines only {} vertices",
                m + 1,
                data.positions.len()
            ),
        ));
    }
    data.lines = line_no;
    Ok(data)
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
    out.point_lines("v ", p.positions)?;
    for face in p.faces() {
        out.buf.push('f');
        for &v in face {
            let _ = write!(out.buf, " {}", v as u64 + 1);
        }
        out.buf.push('\n');
        out.maybe_flush()?;
    }
    out.finish()
}

#[cfg(feature = "unit-tests")]
mod tests;
