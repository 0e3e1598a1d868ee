//! PLY texture coordinates: read into the net's face-varying data (one channel, as OBJ `vt`)
//! and written back, per vertex (`property double u`, `v`, or the names the values came from)
//! when every vertex has one value, else as the face `texcoord` list (`property list uchar
//! double texcoord`, 2 per corner, in MeshLab's layout; double so the values round-trip). The
//! one writer of PLY extras: per-vertex data ([`super::data`]) follows on the vertex lines.

use super::super::Polygons;
use super::super::textout::{ChunkedText, push_f64};
use super::payload::UV_PAIRS;
use crate::mesh::{FaceVarying, PolyMesh, VertexData};
use std::collections::HashMap;
use std::io::Write;

/// The face-varying data of a PLY net: from the face `texcoord` lists when the file has them
/// (corners of one vertex with the same pair share one value, so seams are where the pairs
/// differ), else from the per-vertex pair `UV_PAIRS[pair]`; `None` without either. A file with
/// both gets a note that the per-vertex pair is kept as per-vertex data instead. Also returns
/// the per-vertex pair used, if one is.
pub(super) fn face_varying(
    mesh: &PolyMesh,
    pair: Option<usize>,
    vertex_uv: &[[[f64; 2]; 4]],
    corner_uv: &[[f64; 2]],
    warnings: &mut Vec<String>,
) -> (Option<FaceVarying>, Option<usize>) {
    let corners = mesh.corners();
    if !corner_uv.is_empty() && corner_uv.len() == corners.len() {
        if let Some(k) = pair {
            warnings.push(format!(
                "the per-vertex texture coordinates '{} {}' are kept as per-vertex data, not \
                 used as texture coordinates: the faces' 'texcoord' lists give those per corner",
                UV_PAIRS[k][0], UV_PAIRS[k][1]
            ));
        }
        let mut index: HashMap<(u32, u64, u64), u32> = HashMap::new();
        let mut values = Vec::new();
        let ids = corners
            .iter()
            .zip(corner_uv)
            .map(|(&v, t)| {
                *index
                    .entry((v, t[0].to_bits(), t[1].to_bits()))
                    .or_insert_with(|| {
                        values.push(*t);
                        values.len() as u32 - 1
                    })
            })
            .collect();
        let fv = FaceVarying {
            values,
            corners: ids,
            names: ["u".into(), "v".into()],
            classes: Vec::new(),
        };
        return (Some(fv), None);
    }
    let Some(k) = pair else {
        return (None, None);
    };
    // Per mesh vertex (the input vertices a strict read dropped are skipped).
    let mut values = vec![[0.0; 2]; mesh.num_vertices()];
    for (v, uv) in vertex_uv.iter().enumerate() {
        if let Some(m) = mesh.input_vertex(v) {
            values[m as usize] = uv[k];
        }
    }
    let fv = FaceVarying {
        values,
        corners: corners.to_vec(),
        names: UV_PAIRS[k].map(String::from),
        classes: Vec::new(),
    };
    (Some(fv), Some(k))
}

/// The value of every vertex when each vertex's corners share one value (`None` otherwise, or
/// when a vertex is used by no corner).
fn per_vertex(p: &Polygons<'_>, uv: &FaceVarying) -> Option<Vec<[f64; 2]>> {
    let mut of: Vec<Option<u32>> = vec![None; p.positions.len()];
    let mut k = 0;
    for face in p.faces() {
        for &v in face {
            let val = uv.corners[k];
            k += 1;
            match of[v as usize] {
                None => of[v as usize] = Some(val),
                Some(x) if uv.values[x as usize] == uv.values[val as usize] => {}
                Some(_) => return None,
            }
        }
    }
    of.into_iter()
        .map(|x| x.map(|i| uv.values[i as usize]))
        .collect()
}

/// Writes polygons with texture coordinates and / or per-vertex data as PLY (ascii, or binary
/// little endian with `binary`): texture coordinates per vertex when they are
/// vertex-consistent, else per face corner; the data after them with its own names and types
/// (`data`).
pub(crate) fn write_ply_extras_to(
    w: &mut dyn Write,
    p: &Polygons<'_>,
    uv: Option<&FaceVarying>,
    data: Option<&VertexData>,
    binary: bool,
) -> std::io::Result<()> {
    // Without texture coordinates: no texcoord list, no per-vertex pair.
    let none = FaceVarying {
        values: Vec::new(),
        corners: Vec::new(),
        names: [String::new(), String::new()],
        classes: Vec::new(),
    };
    let has_uv = uv.is_some();
    let uv = uv.unwrap_or(&none);
    let vertex = if has_uv {
        per_vertex(p, uv)
    } else {
        Some(Vec::new())
    };
    let mut head = extras_header(p, uv, has_uv, vertex.as_deref(), data, binary);
    let mut bytes: Vec<u8> = Vec::new();
    if binary {
        w.write_all(head.as_bytes())?;
        head.clear();
    }
    let mut out = ChunkedText::new(w);
    out.buf.push_str(&head);
    write_vertex_rows((&mut out, &mut bytes), p, vertex.as_deref(), data, binary)?;
    write_face_rows((&mut out, &mut bytes), p, uv, vertex.is_none(), binary)?;
    flush_bytes(&mut out, &mut bytes)?;
    out.finish()
}

/// The header: the plain polygons' one with the texture coordinates (per vertex, after z, when
/// `vertex` has them or there are none; else the face `texcoord` list) and the per-vertex
/// data's properties.
fn extras_header(
    p: &Polygons<'_>,
    uv: &FaceVarying,
    has_uv: bool,
    vertex: Option<&[[f64; 2]]>,
    data: Option<&VertexData>,
    binary: bool,
) -> String {
    let wide_tex = 2 * p.max_face > u8::MAX as usize;
    let format = if binary {
        "binary_little_endian"
    } else {
        "ascii"
    };
    let mut head = super::write::header_text(p, format);
    let names = match vertex {
        Some(_) => {
            let ok = UV_PAIRS
                .iter()
                .any(|q| q[0] == uv.names[0] && q[1] == uv.names[1]);
            if ok {
                [uv.names[0].as_str(), uv.names[1].as_str()]
            } else {
                UV_PAIRS[0]
            }
        }
        None => UV_PAIRS[0],
    };
    let data_lines = data.map(super::data::header_lines).unwrap_or_default();
    if vertex.is_none() {
        head = head.replacen(
            "property double z\n",
            &format!("property double z\n{data_lines}"),
            1,
        );
    }
    let extra = match vertex {
        Some(_) if !has_uv => (
            "property double z\n",
            format!("property double z\n{data_lines}"),
        ),
        Some(_) => (
            "property double z\n",
            format!(
                "property double z\nproperty double {}\nproperty double {}\n{data_lines}",
                names[0], names[1]
            ),
        ),
        None => (
            "end_header\n",
            format!(
                "property list {} double texcoord\nend_header\n",
                if wide_tex { "int" } else { "uchar" }
            ),
        ),
    };
    head = head.replacen(extra.0, &extra.1, 1);
    head
}

/// The vertex lines (ascii) or rows (binary, into `bytes`): x y z, the texture coordinates
/// when they are per vertex, then the per-vertex data.
fn write_vertex_rows(
    (out, bytes): (&mut ChunkedText<'_>, &mut Vec<u8>),
    p: &Polygons<'_>,
    vertex: Option<&[[f64; 2]]>,
    data: Option<&VertexData>,
    binary: bool,
) -> std::io::Result<()> {
    for (i, q) in p.positions.iter().enumerate() {
        let t = vertex.and_then(|vals| vals.get(i).copied());
        let row = q.iter().copied().chain(t.into_iter().flatten());
        if binary {
            row.for_each(|x| bytes.extend_from_slice(&x.to_le_bytes()));
            if let Some(d) = data {
                super::data::push_binary(bytes, d, i);
            }
        } else {
            for (j, x) in row.enumerate() {
                if j > 0 {
                    out.buf.push(' ');
                }
                push_f64(&mut out.buf, x);
            }
            if let Some(d) = data {
                super::data::push_ascii(&mut out.buf, d, i);
            }
            out.buf.push('\n');
            out.maybe_flush()?;
        }
        if bytes.len() >= 1 << 20 {
            flush_bytes(out, bytes)?;
        }
    }
    Ok(())
}

/// The face lines (ascii) or rows (binary, into `bytes`): the corner count and corners, then
/// the corners' texture coordinates when they are per corner (`per_corner`).
fn write_face_rows(
    (out, bytes): (&mut ChunkedText<'_>, &mut Vec<u8>),
    p: &Polygons<'_>,
    uv: &FaceVarying,
    per_corner: bool,
    binary: bool,
) -> std::io::Result<()> {
    let wide_tex = 2 * p.max_face > u8::MAX as usize;
    let wide_count = p.max_face > u8::MAX as usize;
    let mut k = 0;
    for face in p.faces() {
        let n = face.len();
        let tex = per_corner
            .then(|| &uv.corners[k..k + n])
            .into_iter()
            .flatten()
            .flat_map(|&c| uv.values[c as usize]);
        k += n;
        if binary {
            if wide_count {
                bytes.extend_from_slice(&(n as i32).to_le_bytes());
            } else {
                bytes.push(n as u8);
            }
            face.iter()
                .for_each(|v| bytes.extend_from_slice(&v.to_le_bytes()));
            if per_corner {
                if wide_tex {
                    bytes.extend_from_slice(&(2 * n as i32).to_le_bytes());
                } else {
                    bytes.push((2 * n) as u8);
                }
                tex.for_each(|x| bytes.extend_from_slice(&x.to_le_bytes()));
            }
            if bytes.len() >= 1 << 20 {
                flush_bytes(out, bytes)?;
            }
        } else {
            use std::fmt::Write as _;
            let _ = write!(out.buf, "{n}");
            for &v in face {
                let _ = write!(out.buf, " {v}");
            }
            if per_corner {
                let _ = write!(out.buf, " {}", 2 * n);
                for x in tex {
                    out.buf.push(' ');
                    push_f64(&mut out.buf, x);
                }
            }
            out.buf.push('\n');
            out.maybe_flush()?;
        }
    }
    Ok(())
}

/// Writes the binary bytes gathered so far (the text buffer is empty in binary mode).
fn flush_bytes(out: &mut ChunkedText<'_>, bytes: &mut Vec<u8>) -> std::io::Result<()> {
    out.write_bytes(bytes)?;
    bytes.clear();
    Ok(())
}
