//! PLY (Stanford polygon format): a reader for every encoding and hand-written writers.
//!
//! Reading: the header is read line by line by the text rule (any bytes in `comment` and
//! `obj_info` lines) and parsed by the crate `ply-rs-bw`, a maintained fork of `ply-rs` (it
//! replaced the unsound `linked-hash-map`, forbids `unsafe`, is fuzzed in CI) that knows the
//! header grammar and every scalar type (`header`). The payload (`payload`): binary
//! elements (little and big endian) are read one at a time by the crate; ascii lines are parsed
//! here by the declared property types, so that errors name the file line and the property.
//! `vertex` elements give `x y z` (any scalar type: float, double or integer), `face` elements
//! give `vertex_indices` (or `vertex_index`) lists of any integer type; texture coordinates
//! (per vertex `u v`, `s t`, `texture_u texture_v` or `texture_s texture_t`, or a face
//! `texcoord` float list with 2 values per corner, as MeshLab writes) become the net's
//! face-varying data (`uv`); every other scalar vertex property (colours `red green blue alpha`
//! as `uchar` or `float`, normals `nx ny nz`, `quality`, any scalar of any PLY type) becomes the
//! net's per-vertex data (`data`: `VertexData`), which `subdivide --levels L [--limit]`
//! interpolates with the positions' own stencils (OpenSubdiv's vertex primvars) and writes back
//! with the same names and types (integer types rounded and clamped to their range). Vertex
//! list properties and other elements are skipped with a warning naming them. Missing elements
//! or properties are named in the error, at the header line that declares the element; binary
//! errors name the element and how many were read.
//!
//! Writing (`write`) is done by hand: ascii, and binary little endian (`double` coordinates,
//! `property list uchar int vertex_indices`) encoded in parallel.

mod data;
mod header;
mod payload;
mod uv;
mod write;

use super::text::io_error;
use super::{FileLines, LoadedMesh, finish_mesh, parse_error};
use crate::error::Result;
use std::io::BufRead;
use std::path::Path;

pub(crate) use uv::write_ply_extras_to;
pub(crate) use write::{write_ply_ascii_to, write_ply_binary_to};

/// Reads a PLY file.
pub fn read_ply(path: &Path) -> Result<LoadedMesh> {
    let file = std::fs::File::open(path).map_err(|e| io_error(path, e))?;
    read_ply_from(std::io::BufReader::with_capacity(1 << 16, file), path)
}

/// Reads PLY (any encoding) from a buffered reader; `path` is used in messages only.
pub fn read_ply_from<R: BufRead>(reader: R, path: &Path) -> Result<LoadedMesh> {
    read_ply_with(reader, path, false)
}

/// [`read_ply_from`], tolerantly with `tolerant` (see [`super::read_mesh_as`]).
pub fn read_ply_with<R: BufRead>(mut reader: R, path: &Path, tolerant: bool) -> Result<LoadedMesh> {
    let head = header::read_header(&mut reader, path)?;
    let body = payload::read_payload(&mut reader, &head, path)?;
    let nv = body.positions.len();
    if body.face_start.len() == 1 {
        return Err(parse_error(
            path,
            head.element_line("face"),
            format!("the 'face' element is empty ({nv} vertices); fairsub needs a polygon mesh"),
        ));
    }
    // In an ascii file, element k is on the line of the first element plus k.
    let lines = body.first_lines;
    let face_line = |f: usize| lines.map(|(_, l)| l + f);
    let vertex_line = |v: usize| lines.map(|(l, _)| l + v);
    let at = FileLines {
        face: &face_line,
        vertex: &vertex_line,
        note: " (faces and vertices counted from 0 in file order)",
    };
    let mut warnings = Vec::new();
    let (vertex_uv, corner_uv) = (body.vertex_uv, body.corner_uv);
    let mut mesh = finish_mesh(
        path,
        body.positions,
        body.face_start,
        body.corners,
        &at,
        &mut warnings,
        tolerant,
    )?;
    let pair = head.header.elements.get("vertex").and_then(|d| {
        payload::UV_PAIRS
            .iter()
            .position(|p| p.iter().all(|n| d.properties.contains_key(*n)))
    });
    let (uv, used) = uv::face_varying(&mesh, pair, &vertex_uv, &corner_uv, &mut warnings);
    let vertex_data = match head.header.elements.get("vertex") {
        Some(def) => data::vertex_data(
            &mesh,
            def,
            &body.vertex_extra,
            used.map(|k| payload::UV_PAIRS[k]),
            &vertex_line,
            path,
            &mut warnings,
        )?,
        None => None,
    };
    if uv.is_some() || vertex_data.is_some() {
        let mut ex = mesh.take_extras().unwrap_or_default();
        ex.uv = uv;
        ex.vertex_data = vertex_data;
        mesh.set_extras(Some(ex));
    }
    let others: Vec<&str> = head
        .header
        .elements
        .keys()
        .map(|k| k.as_str())
        .filter(|k| *k != "vertex" && *k != "face")
        .collect();
    if !others.is_empty() {
        warnings.push(format!("ignored PLY elements: {}", others.join(", ")));
    }
    Ok(LoadedMesh { mesh, warnings })
}

#[cfg(feature = "unit-tests")]
mod tests;
