//! PLY per-vertex data: every scalar vertex property other than `x y z` and the texture
//! coordinate pair the net uses (colours `red green blue alpha` as `uchar` or `float`, normals
//! `nx ny nz`, `quality`, any other scalar of any PLY type) becomes the net's
//! [`VertexData`], which refinement carries through the vertex stencils
//! (`crate::schemes::refine_levels`). Written back with the same names and types: integer
//! types rounded to the nearest integer and clamped to their range ([`ScalarKind::stored`]),
//! `float` rounded to single precision. List-typed vertex properties are skipped with a warning
//! that names them.

use super::super::text::{file_error, parse_error};
use crate::error::Result;
use crate::mesh::{PolyMesh, ScalarKind, VertexData};
use ply_rs_bw::ply::{ElementDef, PropertyType, ScalarType};
use std::path::Path;

/// The kind of a PLY scalar type.
fn kind_of(t: &ScalarType) -> ScalarKind {
    match t {
        ScalarType::Char => ScalarKind::I8,
        ScalarType::UChar => ScalarKind::U8,
        ScalarType::Short => ScalarKind::I16,
        ScalarType::UShort => ScalarKind::U16,
        ScalarType::Int => ScalarKind::I32,
        ScalarType::UInt => ScalarKind::U32,
        ScalarType::Float => ScalarKind::F32,
        ScalarType::Double => ScalarKind::F64,
    }
}

/// The PLY name of a kind (the names of the PLY specification, as most writers use them).
pub(super) fn type_name(k: ScalarKind) -> &'static str {
    match k {
        ScalarKind::I8 => "char",
        ScalarKind::U8 => "uchar",
        ScalarKind::I16 => "short",
        ScalarKind::U16 => "ushort",
        ScalarKind::I32 => "int",
        ScalarKind::U32 => "uint",
        ScalarKind::F32 => "float",
        ScalarKind::F64 => "double",
    }
}

/// The per-vertex data of a PLY net: the scalar vertex properties other than `x y z` and the
/// names in `uv_names` (the pair the net's texture coordinates came from), in header order.
/// `extra` holds every scalar property but `x y z`, input vertex after input vertex; vertices a
/// strict read dropped are left out. `None` when no property remains. Warns about list-typed
/// vertex properties (skipped); a value that is not finite is an error naming the vertex, the
/// property and, in an ascii file, the line (`vertex_line`).
pub(super) fn vertex_data(
    mesh: &PolyMesh,
    def: &ElementDef,
    extra: &[f64],
    uv_names: Option<[&str; 2]>,
    vertex_line: &dyn Fn(usize) -> Option<usize>,
    path: &Path,
    warnings: &mut Vec<String>,
) -> Result<Option<VertexData>> {
    let mut lists = Vec::new();
    // (column in `extra`, name, kind) of every kept channel.
    let mut channels = Vec::new();
    let mut columns = 0;
    for (name, p) in &def.properties {
        match &p.data_type {
            PropertyType::List(..) => lists.push(format!("'{name}'")),
            PropertyType::Scalar(_) if matches!(name.as_str(), "x" | "y" | "z") => {}
            PropertyType::Scalar(t) => {
                if !uv_names.is_some_and(|uv| uv.contains(&name.as_str())) {
                    channels.push((columns, name.clone(), kind_of(t)));
                }
                columns += 1;
            }
        }
    }
    if !lists.is_empty() {
        warnings.push(format!(
            "vertex list propert{} {} skipped: only scalar vertex properties are per-vertex data \
             that refinement carries",
            if lists.len() == 1 { "y" } else { "ies" },
            lists.join(", ")
        ));
    }
    if channels.is_empty() || columns == 0 {
        return Ok(None);
    }
    let n_in = extra.len() / columns;
    for (v, row) in extra.chunks_exact(columns).enumerate() {
        if let Some((_, name, _)) = channels.iter().find(|c| !row[c.0].is_finite()) {
            let msg = format!("vertex {v} (counted from 0): property '{name}' is not finite");
            return Err(match vertex_line(v) {
                Some(l) => parse_error(path, l, msg),
                None => file_error(path, msg),
            });
        }
    }
    let width = channels.len();
    let mut values = vec![0.0; mesh.num_vertices() * width];
    for v in 0..n_in {
        if let Some(m) = mesh.input_vertex(v) {
            let row = &extra[v * columns..(v + 1) * columns];
            let out = &mut values[m as usize * width..(m as usize + 1) * width];
            for (o, c) in out.iter_mut().zip(&channels) {
                *o = row[c.0];
            }
        }
    }
    Ok(Some(VertexData {
        names: channels.iter().map(|c| c.1.clone()).collect(),
        kinds: channels.iter().map(|c| c.2).collect(),
        values,
    }))
}

/// The header lines of the data's properties.
pub(super) fn header_lines(d: &VertexData) -> String {
    d.names
        .iter()
        .zip(&d.kinds)
        .map(|(n, &k)| format!("property {} {n}\n", type_name(k)))
        .collect()
}

/// Appends the data of vertex `v` to an ascii line (each value after a space), as its kind
/// stores it: integers as integers, `float` in the shortest form that reads back as the same
/// single-precision value.
pub(super) fn push_ascii(line: &mut String, d: &VertexData, v: usize) {
    use std::fmt::Write as _;
    let w = d.width();
    for (&x, &k) in d.values[v * w..(v + 1) * w].iter().zip(&d.kinds) {
        let x = k.stored(x);
        line.push(' ');
        match k {
            ScalarKind::F64 => super::super::textout::push_f64(line, x),
            ScalarKind::F32 => {
                let _ = write!(line, "{}", x as f32);
            }
            _ => {
                let _ = write!(line, "{}", x as i64);
            }
        }
    }
}

/// Appends the data of vertex `v` in little-endian binary, as its kind stores it.
pub(super) fn push_binary(bytes: &mut Vec<u8>, d: &VertexData, v: usize) {
    let w = d.width();
    for (&x, &k) in d.values[v * w..(v + 1) * w].iter().zip(&d.kinds) {
        let x = k.stored(x);
        match k {
            ScalarKind::I8 => bytes.extend_from_slice(&(x as i8).to_le_bytes()),
            ScalarKind::U8 => bytes.push(x as u8),
            ScalarKind::I16 => bytes.extend_from_slice(&(x as i16).to_le_bytes()),
            ScalarKind::U16 => bytes.extend_from_slice(&(x as u16).to_le_bytes()),
            ScalarKind::I32 => bytes.extend_from_slice(&(x as i32).to_le_bytes()),
            ScalarKind::U32 => bytes.extend_from_slice(&(x as u32).to_le_bytes()),
            ScalarKind::F32 => bytes.extend_from_slice(&(x as f32).to_le_bytes()),
            ScalarKind::F64 => bytes.extend_from_slice(&x.to_le_bytes()),
        }
    }
}
