//! One OBJ statement: its tokens (split in place on ASCII lines) and what each statement
//! keyword (`v`, `vt`, `t`, `f`; any other is counted) adds to what was read so far.

use super::super::ListedMesh;
use super::super::text::{hash_comment, line_text, parse_error};
use super::{NO_UV, ObjData, tags};
use crate::error::Result;
use crate::mesh::tags::Tags;
use std::collections::BTreeMap;
use std::path::Path;

/// The state of the OBJ reader between statements.
pub(super) struct ObjState {
    /// What was read so far.
    pub(super) data: ObjData,
    /// Largest positive index seen: (0-based index, line). Positive indices may refer to
    /// vertices defined later, so they are checked at the end.
    pub(super) max_index: Option<(usize, usize)>,
    /// Largest positive `vt` index seen, as for `max_index`.
    pub(super) max_uv: Option<(usize, usize)>,
    /// Token ranges of the current statement (reused).
    pub(super) tokens: Vec<(usize, usize)>,
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
pub(super) fn parse_i64(s: &[u8]) -> Option<i64> {
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

/// A statement: its text, the ranges of its tokens in it, and the line it starts on.
struct Statement<'t> {
    text: &'t str,
    tokens: &'t [(usize, usize)],
    line: usize,
    path: &'t Path,
}

impl<'t> Statement<'t> {
    /// Token `k` (0: the keyword).
    fn token(&self, k: usize) -> &'t str {
        &self.text[self.tokens[k].0..self.tokens[k].1]
    }
}

impl ObjState {
    /// The state before the first statement.
    pub(super) fn new() -> ObjState {
        ObjState {
            data: ObjData {
                listed: ListedMesh {
                    positions: Vec::new(),
                    vertex_line: Vec::new(),
                    face_start: vec![0],
                    corners: Vec::new(),
                    face_line: Vec::new(),
                },
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
        }
    }

    /// The data read from a file of `lines` physical lines, once every positive vertex and
    /// texture index is checked against what the whole file defines.
    pub(super) fn finish(self, lines: usize, path: &Path) -> Result<ObjData> {
        let mut data = self.data;
        if let Some((m, line)) = self.max_uv
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
        if let Some((m, line)) = self.max_index
            && m >= data.listed.positions.len()
        {
            return Err(parse_error(
                path,
                line,
                format!(
                    "face refers to vertex {}, but the file defines only {} vertices",
                    m + 1,
                    data.listed.positions.len()
                ),
            ));
        }
        data.lines = lines;
        Ok(data)
    }

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
    pub(super) fn statement(&mut self, bytes: &[u8], line: usize, path: &Path) -> Result<()> {
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

    /// Handles a statement given as token ranges into `text`: a table from the statement's
    /// keyword to what reads it.
    fn tokens_statement(
        &mut self,
        text: &str,
        tokens: &[(usize, usize)],
        line: usize,
        path: &Path,
    ) -> Result<()> {
        let Some(&(ks, ke)) = tokens.first() else {
            return Ok(());
        };
        let s = Statement {
            text,
            tokens,
            line,
            path,
        };
        match &text[ks..ke] {
            "v" => self.vertex(&s)?,
            "vt" => self.texture_coordinate(&s)?,
            "t" => {
                let toks: Vec<&str> = (0..tokens.len()).map(|k| s.token(k)).collect();
                tags::parse_tag(
                    &toks,
                    line,
                    path,
                    &mut self.data.tags,
                    &mut self.data.tag_warnings,
                )?;
            }
            "f" | "fo" => self.face(&s)?,
            other => match self.data.ignored.get_mut(other) {
                Some(n) => *n += 1,
                None => {
                    self.data.ignored.insert(other.to_string(), 1);
                }
            },
        }
        Ok(())
    }

    /// A `v` line: the point x y z (anything after it is ignored).
    fn vertex(&mut self, s: &Statement<'_>) -> Result<()> {
        let (line, path) = (s.line, s.path);
        let mut p = [0.0; 3];
        for (k, c) in p.iter_mut().enumerate() {
            if k + 1 >= s.tokens.len() {
                return Err(parse_error(
                    path,
                    line,
                    format!(
                        "vertex has {k} coordinate{}; a 'v' line needs x y z",
                        if k == 1 { "" } else { "s" }
                    ),
                ));
            }
            let t = s.token(k + 1);
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
        self.data.listed.positions.push(p);
        self.data.listed.vertex_line.push(line as u32);
        Ok(())
    }

    /// A `vt` line: the texture coordinates u [v] (v = 0 when missing; a w is ignored).
    fn texture_coordinate(&mut self, s: &Statement<'_>) -> Result<()> {
        let (line, path) = (s.line, s.path);
        let mut t = [0.0; 2];
        for (k, c) in t.iter_mut().enumerate() {
            if k + 1 >= s.tokens.len() {
                if k == 1 {
                    break; // `vt u`: v = 0
                }
                return Err(parse_error(path, line, "a 'vt' line needs u [v]"));
            }
            let word = s.token(k + 1);
            *c = word
                .parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| {
                    parse_error(
                        path,
                        line,
                        format!("bad texture coordinate '{word}' in a 'vt' line"),
                    )
                })?;
        }
        self.data.uvs.push(t);
        Ok(())
    }

    /// An `f` (or `fo`) line: the face's corners, each with its `vt` index if given; notes a
    /// face whose corners mix corners with and without `vt` indices.
    fn face(&mut self, s: &Statement<'_>) -> Result<()> {
        let (line, path) = (s.line, s.path);
        let before = self.data.listed.corners.len();
        let uv_before = self.data.uv_corners.len();
        for k in 1..s.tokens.len() {
            let t = s.token(k);
            let slash = t.bytes().position(|b| b == b'/');
            let vpart = &t.as_bytes()[..slash.unwrap_or(t.len())];
            let v = self.vertex_index(vpart, t, line, path)?;
            self.data.listed.corners.push(v as u32);
            // The texture index: between the first and the second '/', if any.
            let uv_part = slash.and_then(|i| t[i + 1..].split('/').next());
            let uv = match uv_part.filter(|u| !u.is_empty()) {
                None => NO_UV,
                Some(u) => self.uv_index(u, t, line, path)?,
            };
            self.data.uv_corners.push(uv);
        }
        let n = self.data.listed.corners.len() - before;
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
        if self.data.listed.corners.len() > u32::MAX as usize {
            return Err(parse_error(path, line, "more than 2^32 - 1 face corners"));
        }
        self.data
            .listed
            .face_start
            .push(self.data.listed.corners.len() as u32);
        self.data.listed.face_line.push(line as u32);
        Ok(())
    }

    /// The 0-based vertex of face corner `t` from its vertex part `vpart` (a positive index,
    /// checked at the end of the file, or a relative one, checked here).
    fn vertex_index(&mut self, vpart: &[u8], t: &str, line: usize, path: &Path) -> Result<usize> {
        let idx = parse_i64(vpart).ok_or_else(|| {
            parse_error(
                path,
                line,
                format!("bad vertex reference '{t}' in face (expected v, v/vt, v//vn or v/vt/vn)"),
            )
        })?;
        let positions = self.data.listed.positions.len();
        if idx > 0 {
            if idx > u32::MAX as i64 {
                return Err(parse_error(
                    path,
                    line,
                    format!("vertex index {idx} is beyond fairsub's limit of 2^32 - 1 vertices"),
                ));
            }
            let v = (idx - 1) as usize;
            if self.max_index.is_none_or(|(m, _)| v > m) {
                self.max_index = Some((v, line));
            }
            Ok(v)
        } else if idx < 0 {
            let back = idx.unsigned_abs() as usize;
            if back > positions {
                return Err(parse_error(
                    path,
                    line,
                    format!(
                        "relative vertex index {idx} reaches before the first vertex ({positions} vertices are defined above this face)"
                    ),
                ));
            }
            Ok(positions - back)
        } else {
            Err(parse_error(
                path,
                line,
                "vertex index 0 in face: OBJ indices start at 1 (or are negative, counting back)",
            ))
        }
    }
}
