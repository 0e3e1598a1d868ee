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

mod statement;
mod tags;
mod uv;
pub(crate) use uv::write_obj_uv_to;

pub use tags::read_tag_file;

use super::text::{io_error, parse_error};
use super::textout::ChunkedText;
use super::{ListedMesh, LoadedMesh, Polygons, finish_listed};
use crate::error::Result;
use crate::mesh::FaceVarying;
use crate::mesh::tags::Tags;
use statement::ObjState;
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
    /// Every `v` line's point, in file order (also those no face uses), and the faces, with
    /// the line of each.
    pub listed: ListedMesh,
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
        self.listed.face_line.len()
    }

    /// Builds and validates the mesh; errors name the line of the face or vertex concerned.
    pub fn into_mesh(self, path: &Path) -> Result<LoadedMesh> {
        self.into_mesh_with(path, false)
    }

    /// [`ObjData::into_mesh`], tolerantly with `tolerant` (see [`super::read_mesh_as`]); the
    /// tags and texture coordinates are attached to the mesh.
    pub fn into_mesh_with(self, path: &Path, tolerant: bool) -> Result<LoadedMesh> {
        let ObjData {
            listed,
            ignored,
            lines,
            uvs,
            uv_corners,
            faces_with_uv,
            uv_mixed,
            tags,
            tag_warnings,
        } = self;
        if listed.face_line.is_empty() {
            return Err(parse_error(
                path,
                lines.max(1),
                format!(
                    "no faces ('f' lines) found ({} vertices read); fairsub needs a polygon mesh",
                    listed.positions.len()
                ),
            ));
        }
        let mut warnings = tag_warnings;
        let nf = listed.face_line.len();
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
    let mut st = ObjState::new();
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
    st.finish(line_no, path)
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
