//! PLY (Stanford polygon format): reader via `ply-rs-bw`, hand-written writers.
//!
//! Reading uses the crate `ply-rs-bw`: a maintained fork of `ply-rs` (it replaced the unsound
//! `linked-hash-map`, forbids `unsafe`, is fuzzed in CI) that parses the header and all three
//! encodings (ascii, binary little and big endian) with every scalar type, and reports ascii
//! errors with line numbers. We parse straight into small structs: `vertex` elements give `x y z`
//! (any scalar type: float, double or integer), `face` elements give `vertex_indices` (or
//! `vertex_index`) lists of any integer type; every other element and property is skipped.
//! Missing elements or properties are named in the error.
//!
//! Writing is done by hand: the binary writer (little endian, `double` coordinates,
//! `property list uchar int vertex_indices`) encodes blocks of vertices and faces into buffers
//! of about 1 MiB in parallel while the calling thread writes the previous batch, so a refined
//! net of hundreds of megabytes is written at the speed of the output, with a few megabytes of
//! buffers.

use super::{
    ChunkedText, LoadedMesh, Polygons, dropped_warning, io_error, locate_mesh_error, parse_error,
    push_point,
};
use crate::error::{Error, Result};
use crate::mesh::PolyMesh;
use ply_rs_bw::parser::{Parser, Reader};
use ply_rs_bw::ply::{
    BeginList, ElementDef, Encoding, Header, Property, PropertyAccess, PropertyAccessResult,
    PropertyType, ScalarType,
};
use std::borrow::Cow;
use std::io::{BufRead, Write};
use std::path::Path;

/// Reads a PLY file.
pub fn read_ply(path: &Path) -> Result<LoadedMesh> {
    let file = std::fs::File::open(path).map_err(|e| io_error(path, e))?;
    read_ply_from(std::io::BufReader::with_capacity(1 << 16, file), path)
}

#[derive(Debug, Default)]
struct Vertex([f64; 3]);

impl PropertyAccess for Vertex {
    fn new() -> Self {
        Vertex::default()
    }
    fn set_property(&mut self, name: &str, p: Property) -> PropertyAccessResult {
        let k = match name {
            "x" => 0,
            "y" => 1,
            "z" => 2,
            _ => return PropertyAccessResult::Ignored,
        };
        let v = match p {
            Property::Char(v) => v as f64,
            Property::UChar(v) => v as f64,
            Property::Short(v) => v as f64,
            Property::UShort(v) => v as f64,
            Property::Int(v) => v as f64,
            Property::UInt(v) => v as f64,
            Property::Float(v) => v as f64,
            Property::Double(v) => v,
            _ => return PropertyAccessResult::UnsupportedType,
        };
        self.0[k] = v;
        PropertyAccessResult::Set
    }
}

/// A face: vertex indices as read. `int` and `uint` lists (the common ones) are filled in place
/// by the parser; other integer types go through `set_property`.
#[derive(Debug, Default)]
struct Face {
    int: Vec<i32>,
    uint: Vec<u32>,
    other: Vec<i64>,
}

/// The name of the face index list this file uses (`vertex_indices` or `vertex_index`).
const INDEX_NAMES: [&str; 2] = ["vertex_indices", "vertex_index"];

impl PropertyAccess for Face {
    fn new() -> Self {
        Face::default()
    }
    fn begin_list_int(&mut self, name: &str, _len: usize) -> BeginList<'_, i32> {
        if INDEX_NAMES.contains(&name) {
            BeginList::Fill(&mut self.int)
        } else {
            BeginList::UseSetter
        }
    }
    fn begin_list_uint(&mut self, name: &str, _len: usize) -> BeginList<'_, u32> {
        if INDEX_NAMES.contains(&name) {
            BeginList::Fill(&mut self.uint)
        } else {
            BeginList::UseSetter
        }
    }
    fn set_property(&mut self, name: &str, p: Property) -> PropertyAccessResult {
        if !INDEX_NAMES.contains(&name) {
            return PropertyAccessResult::Ignored;
        }
        self.other = match p {
            Property::ListChar(v) => v.into_iter().map(i64::from).collect(),
            Property::ListUChar(v) => v.into_iter().map(i64::from).collect(),
            Property::ListShort(v) => v.into_iter().map(i64::from).collect(),
            Property::ListUShort(v) => v.into_iter().map(i64::from).collect(),
            Property::ListInt(v) => v.into_iter().map(i64::from).collect(),
            Property::ListUInt(v) => v.into_iter().map(i64::from).collect(),
            _ => return PropertyAccessResult::UnsupportedType,
        };
        PropertyAccessResult::Set
    }
}

impl Face {
    /// The indices, whatever list type carried them.
    fn indices(&self) -> Box<dyn Iterator<Item = i64> + '_> {
        if !self.int.is_empty() {
            Box::new(self.int.iter().map(|&v| v as i64))
        } else if !self.uint.is_empty() {
            Box::new(self.uint.iter().map(|&v| v as i64))
        } else {
            Box::new(self.other.iter().copied())
        }
    }
}

/// Skips every property of an element fairsub does not read.
#[derive(Debug, Default)]
struct Skip;

impl PropertyAccess for Skip {
    fn new() -> Self {
        Skip
    }
}

fn is_int(t: &ScalarType) -> bool {
    !matches!(t, ScalarType::Float | ScalarType::Double)
}

/// Checks the header for the elements and properties we need; returns the face list's name.
fn check_header(header: &Header, path: &Path) -> Result<&'static str> {
    let names = || {
        header
            .elements
            .keys()
            .map(|k| format!("'{k}'"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let vertex = header.elements.get("vertex").ok_or_else(|| {
        parse_error(
            path,
            0,
            format!(
                "no 'vertex' element in the PLY header (elements: {})",
                names()
            ),
        )
    })?;
    for c in ["x", "y", "z"] {
        match vertex.properties.get(c) {
            Some(p) if matches!(p.data_type, PropertyType::Scalar(_)) => {}
            Some(_) => {
                return Err(parse_error(
                    path,
                    0,
                    format!("property '{c}' of element 'vertex' is a list; expected a number"),
                ));
            }
            None => {
                return Err(parse_error(
                    path,
                    0,
                    format!("element 'vertex' has no property '{c}'"),
                ));
            }
        }
    }
    let face = header.elements.get("face").ok_or_else(|| {
        parse_error(
            path,
            0,
            format!(
                "no 'face' element in the PLY header (elements: {}); a point cloud is not a polygon mesh",
                names()
            ),
        )
    })?;
    for name in INDEX_NAMES {
        if let Some(p) = face.properties.get(name) {
            return match &p.data_type {
                PropertyType::List(_, t) if is_int(t) => Ok(name),
                other => Err(parse_error(
                    path,
                    0,
                    format!(
                        "property '{name}' of element 'face' has type {other:?}; expected a list of integers"
                    ),
                )),
            };
        }
    }
    Err(parse_error(
        path,
        0,
        "element 'face' has neither a 'vertex_indices' nor a 'vertex_index' list property",
    ))
}

/// Reads PLY (any encoding) from a buffered reader; `path` is used in messages only.
pub fn read_ply_from<R: BufRead>(reader: R, path: &Path) -> Result<LoadedMesh> {
    let mut r = Reader::new(reader);
    let ply_err = |e: ply_rs_bw::parser::ParseError| {
        let line = e.line().unwrap_or(0);
        let msg = e.to_string();
        // The crate prefixes "Line N: "; our error shows the line itself.
        let msg = match msg.split_once(": ") {
            Some((head, rest)) if head.starts_with("Line ") => rest.to_string(),
            _ => msg,
        };
        parse_error(path, line, format!("PLY: {msg}"))
    };
    let header = Parser::<Skip>::new().read_header(&mut r).map_err(ply_err)?;
    check_header(&header, path)?;
    let ascii = header.encoding == Encoding::Ascii;
    // In an ascii file, element k of the payload is on this line + k.
    let mut payload_line = r.line();
    let mut first_face_line = None;

    let mut verts: Vec<Vertex> = Vec::new();
    let mut faces: Vec<Face> = Vec::new();
    for (name, def) in &header.elements {
        let def: &ElementDef = def;
        match name.as_str() {
            "vertex" => {
                verts = Parser::<Vertex>::new()
                    .read_payload_for_element(&mut r, def, &header)
                    .map_err(ply_err)?;
            }
            "face" => {
                first_face_line = Some(payload_line);
                faces = Parser::<Face>::new()
                    .read_payload_for_element(&mut r, def, &header)
                    .map_err(ply_err)?;
            }
            _ => {
                Parser::<Skip>::new()
                    .read_payload_for_element(&mut r, def, &header)
                    .map_err(ply_err)?;
            }
        }
        payload_line += def.count;
    }
    let face_line = |f: usize| -> Option<usize> {
        if ascii {
            first_face_line.map(|l| l + f)
        } else {
            None
        }
    };
    let where_face = |f: usize| match face_line(f) {
        Some(l) => (l, format!("face {f}")),
        None => (0, format!("face {f} (counted from 0)")),
    };
    let nv = verts.len();
    if nv > u32::MAX as usize {
        return Err(Error::Unsupported(format!(
            "{}: {nv} vertices are more than fairsub's limit of 2^32 - 1",
            path.display()
        )));
    }
    let mut face_start: Vec<u32> = Vec::with_capacity(faces.len() + 1);
    face_start.push(0);
    let mut corners: Vec<u32> = Vec::with_capacity(faces.len() * 4);
    for (f, face) in faces.iter().enumerate() {
        let before = corners.len();
        for v in face.indices() {
            if v < 0 || v as u64 >= nv as u64 {
                let (l, what) = where_face(f);
                return Err(parse_error(
                    path,
                    l,
                    format!(
                        "{what} refers to vertex {v}, but the file has {nv} vertices (indices 0..{})",
                        nv.saturating_sub(1)
                    ),
                ));
            }
            corners.push(v as u32);
        }
        let n = corners.len() - before;
        if n < 3 {
            let (l, what) = where_face(f);
            return Err(parse_error(
                path,
                l,
                format!("{what} has {n} corners; a face needs at least 3"),
            ));
        }
        if corners.len() > u32::MAX as usize {
            return Err(Error::Unsupported(format!(
                "{}: more than 2^32 - 1 face corners",
                path.display()
            )));
        }
        face_start.push(corners.len() as u32);
    }
    drop(faces);
    if face_start.len() == 1 {
        return Err(parse_error(
            path,
            0,
            format!("the 'face' element is empty ({nv} vertices); fairsub needs a polygon mesh"),
        ));
    }
    let positions: Vec<[f64; 3]> = verts.into_iter().map(|v| v.0).collect();
    let vertex_line = |_v: usize| None;
    let mesh = PolyMesh::from_flat(positions, face_start, corners).map_err(|e| {
        locate_mesh_error(
            path,
            e,
            &face_line,
            &vertex_line,
            " (faces and vertices counted from 0 in file order)",
        )
    })?;
    let mut warnings = Vec::new();
    if let Some(w) = dropped_warning(&mesh, &vertex_line, "counted from 0") {
        warnings.push(w);
    }
    let others: Vec<&str> = header
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

/// The PLY header for `p`; `format` is the `format` line's encoding name.
fn header_text(p: &Polygons<'_>, format: &str) -> String {
    let count_type = if p.max_face <= u8::MAX as usize {
        "uchar"
    } else {
        "int"
    };
    let index_type = if p.positions.len() <= i32::MAX as usize {
        "int"
    } else {
        "uint"
    };
    format!(
        "ply\nformat {format} 1.0\ncomment written by fairsub\nelement vertex {}\n\
         property double x\nproperty double y\nproperty double z\nelement face {}\n\
         property list {count_type} {index_type} vertex_indices\nend_header\n",
        p.positions.len(),
        p.num_faces()
    )
}

/// Writes polygons as ascii PLY with round-trip precision.
pub(crate) fn write_ply_ascii_to(w: &mut dyn Write, p: &Polygons<'_>) -> std::io::Result<()> {
    use std::fmt::Write as _;
    let mut out = ChunkedText::new(w);
    out.buf.push_str(&header_text(p, "ascii"));
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

/// Bytes of output per encoding job of the binary writer (above the 1 MiB of the atomic
/// writer's buffer, so jobs go straight to the file without another copy).
const JOB_BYTES: usize = 2 << 20;
/// Jobs encoded in parallel while the previous batch is written.
const JOBS_PER_BATCH: usize = 4;

/// The bytes of points (`3 x f64` each, no padding), in memory order.
#[cfg(target_endian = "little")]
fn point_bytes(points: &[crate::geom::Point]) -> &[u8] {
    // SAFETY: `[f64; 3]` has size 24, no padding and no invalid bit patterns as bytes; the
    // returned slice borrows `points` for its whole length, with byte alignment.
    unsafe { std::slice::from_raw_parts(points.as_ptr().cast::<u8>(), size_of_val(points)) }
}

/// Writes polygons as binary little-endian PLY (double coordinates).
///
/// The body is cut into jobs of about [`JOB_BYTES`]; batches of jobs are encoded in parallel
/// (rayon) while the calling thread writes the batch before, so encoding and writing overlap
/// and the buffers in flight stay at two batches.
pub(crate) fn write_ply_binary_to(w: &mut dyn Write, p: &Polygons<'_>) -> std::io::Result<()> {
    use rayon::prelude::*;
    w.write_all(header_text(p, "binary_little_endian").as_bytes())?;
    let wide_count = p.max_face > u8::MAX as usize;
    // Jobs: ranges of vertices, then ranges of faces.
    enum Job {
        Vertices(usize, usize),
        Faces(usize, usize),
    }
    let nv = p.positions.len();
    let nf = p.num_faces();
    let per_vertex = JOB_BYTES / 24;
    let mut jobs: Vec<Job> = (0..nv.div_ceil(per_vertex))
        .map(|k| Job::Vertices(k * per_vertex, ((k + 1) * per_vertex).min(nv)))
        .collect();
    let mut f = 0;
    while f < nf {
        // Cut face ranges by their encoded size (count byte(s) and 4 bytes per corner).
        let target = p.face_offset(f) + JOB_BYTES / 5;
        let g = if p.uniform != 0 {
            (f + (JOB_BYTES / 5).div_ceil(p.uniform)).min(nf)
        } else {
            let rest = &p.face_start[f + 1..];
            (f + 1 + rest.partition_point(|&s| (s as usize) < target)).min(nf)
        };
        jobs.push(Job::Faces(f, g));
        f = g;
    }
    let encode = |job: &Job| -> Cow<'_, [u8]> {
        match *job {
            // On a little-endian machine the points are already the file's bytes: written
            // straight from the mesh, no copy.
            #[cfg(target_endian = "little")]
            Job::Vertices(a, b) => Cow::Borrowed(point_bytes(&p.positions[a..b])),
            #[cfg(not(target_endian = "little"))]
            Job::Vertices(a, b) => {
                let mut buf = Vec::with_capacity(24 * (b - a));
                for q in &p.positions[a..b] {
                    buf.extend_from_slice(&q[0].to_le_bytes());
                    buf.extend_from_slice(&q[1].to_le_bytes());
                    buf.extend_from_slice(&q[2].to_le_bytes());
                }
                Cow::Owned(buf)
            }
            Job::Faces(a, b) => {
                let corners = p.face_offset(b) - p.face_offset(a);
                let count = if wide_count { 4 } else { 1 };
                let mut buf = Vec::with_capacity(count * (b - a) + 4 * corners);
                for f in a..b {
                    let face = p.face(f);
                    if wide_count {
                        buf.extend_from_slice(&(face.len() as i32).to_le_bytes());
                    } else {
                        buf.push(face.len() as u8);
                    }
                    for &v in face {
                        // `int` when the vertex count fits, else `uint`: same four bytes for
                        // valid indices.
                        buf.extend_from_slice(&v.to_le_bytes());
                    }
                }
                Cow::Owned(buf)
            }
        }
    };
    let encode_batch =
        |batch: &[Job]| -> Vec<Cow<'_, [u8]>> { batch.par_iter().map(encode).collect() };
    let mut batches = jobs.chunks(JOBS_PER_BATCH);
    let mut ready = batches.next().map(encode_batch).unwrap_or_default();
    loop {
        let next = batches.next();
        let mut encoded = None;
        let mut result = Ok(());
        rayon::in_place_scope(|s| {
            if let Some(batch) = next {
                let slot = &mut encoded;
                s.spawn(move |_| *slot = Some(encode_batch(batch)));
            }
            for buf in &ready {
                if result.is_ok() {
                    result = w.write_all(buf);
                }
            }
        });
        result?;
        match encoded {
            Some(e) => ready = e,
            None => return Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ply_rs_bw::ply::{Addable, DefaultElement, Ply, PropertyDef};
    use ply_rs_bw::writer::Writer;

    fn read(bytes: &[u8]) -> Result<LoadedMesh> {
        read_ply_from(bytes, Path::new("t.ply"))
    }

    /// A PLY built with ply-rs-bw's own writer: float coordinates, ushort-counted uint lists,
    /// an extra element and extra properties.
    fn crate_written(encoding: Encoding, double: bool) -> Vec<u8> {
        let mut ply = Ply::<DefaultElement>::new();
        ply.header.encoding = encoding;
        let mut v = ElementDef::new("vertex".to_string());
        let st = if double {
            ScalarType::Double
        } else {
            ScalarType::Float
        };
        for c in ["x", "y", "z"] {
            v.properties.add(PropertyDef::new(
                c.to_string(),
                PropertyType::Scalar(st.clone()),
            ));
        }
        v.properties.add(PropertyDef::new(
            "red".to_string(),
            PropertyType::Scalar(ScalarType::UChar),
        ));
        ply.header.elements.add(v);
        let mut f = ElementDef::new("face".to_string());
        f.properties.add(PropertyDef::new(
            "vertex_index".to_string(),
            PropertyType::List(ScalarType::UShort, ScalarType::UInt),
        ));
        ply.header.elements.add(f);
        let mut e = ElementDef::new("edge".to_string());
        e.properties.add(PropertyDef::new(
            "vertex1".to_string(),
            PropertyType::Scalar(ScalarType::Int),
        ));
        ply.header.elements.add(e);
        let pts = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.5],
            [0.0, 1.0, 0.0],
            [0.5, 2.0, 0.25],
        ];
        let verts: Vec<DefaultElement> = pts
            .iter()
            .map(|p| {
                let mut el = DefaultElement::new();
                for (k, c) in ["x", "y", "z"].into_iter().enumerate() {
                    let prop = if double {
                        Property::Double(p[k])
                    } else {
                        Property::Float(p[k] as f32)
                    };
                    el.insert(c.to_string(), prop);
                }
                el.insert("red".to_string(), Property::UChar(200));
                el
            })
            .collect();
        ply.payload.insert("vertex".to_string(), verts);
        let faces: Vec<DefaultElement> = [vec![0u32, 1, 2, 3], vec![3, 2, 4]]
            .into_iter()
            .map(|f| {
                let mut el = DefaultElement::new();
                el.insert("vertex_index".to_string(), Property::ListUInt(f));
                el
            })
            .collect();
        ply.payload.insert("face".to_string(), faces);
        let mut edge = DefaultElement::new();
        edge.insert("vertex1".to_string(), Property::Int(3));
        ply.payload.insert("edge".to_string(), vec![edge]);
        let mut buf = Vec::new();
        Writer::new().write_ply(&mut buf, &mut ply).unwrap();
        buf
    }

    fn check_five(m: &LoadedMesh) {
        assert_eq!(m.mesh.num_vertices(), 5);
        assert_eq!(m.mesh.face(0), &[0, 1, 2, 3]);
        assert_eq!(m.mesh.face(1), &[3, 2, 4]);
        assert_eq!(m.mesh.position(2), [1.0, 1.0, 0.5]);
        assert_eq!(m.mesh.position(4), [0.5, 2.0, 0.25]);
        assert_eq!(m.warnings, vec!["ignored PLY elements: edge".to_string()]);
    }

    #[test]
    fn reads_all_encodings_written_by_ply_rs() {
        for enc in [
            Encoding::Ascii,
            Encoding::BinaryLittleEndian,
            Encoding::BinaryBigEndian,
        ] {
            for double in [false, true] {
                let bytes = crate_written(enc, double);
                let m = read(&bytes).unwrap_or_else(|e| panic!("{enc:?} {double}: {e}"));
                check_five(&m);
            }
        }
    }

    #[test]
    fn reads_hand_written_big_endian_with_int_coordinates() {
        let mut b = b"ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty short x\n\
                      property int y\nproperty uchar z\nelement face 1\n\
                      property list uchar short vertex_indices\nend_header\n"
            .to_vec();
        for (x, y, z) in [(-1i16, 0i32, 7u8), (1, 0, 7), (0, 2, 9)] {
            b.extend_from_slice(&x.to_be_bytes());
            b.extend_from_slice(&y.to_be_bytes());
            b.push(z);
        }
        b.push(3);
        for v in [0i16, 1, 2] {
            b.extend_from_slice(&v.to_be_bytes());
        }
        let m = read(&b).unwrap();
        assert_eq!(
            m.mesh.positions(),
            &[[-1.0, 0.0, 7.0], [1.0, 0.0, 7.0], [0.0, 2.0, 9.0]]
        );
        assert_eq!(m.mesh.face(0), &[0, 1, 2]);
    }

    #[test]
    fn missing_elements_and_properties_are_named() {
        let msg = |s: &str| read(s.as_bytes()).unwrap_err().to_string();
        let m = msg("ply\nformat ascii 1.0\nelement point 1\nproperty float x\nend_header\n1\n");
        assert!(
            m.contains("no 'vertex' element") && m.contains("'point'"),
            "{m}"
        );
        let m = msg(
            "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n1 2\n",
        );
        assert!(m.contains("no property 'z'"), "{m}");
        let m = msg(
            "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n1 2 3\n",
        );
        assert!(m.contains("no 'face' element"), "{m}");
        let m = msg(
            "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nelement face 0\nproperty list uchar int idx\nend_header\n1 2 3\n",
        );
        assert!(
            m.contains("neither a 'vertex_indices' nor a 'vertex_index'"),
            "{m}"
        );
        let m = msg(
            "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nelement face 0\nproperty list uchar float vertex_indices\nend_header\n1 2 3\n",
        );
        assert!(m.contains("list of integers"), "{m}");
    }

    #[test]
    fn ascii_errors_have_lines() {
        let head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
                    property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n";
        // Line 10..12 vertices, 13..14 faces.
        let e =
            read(format!("{head}0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 5\n").as_bytes()).unwrap_err();
        match e {
            Error::Parse { line, msg, .. } => {
                assert_eq!(line, 14, "{msg}");
                assert!(msg.contains("face 1 refers to vertex 5"), "{msg}");
            }
            other => panic!("{other:?}"),
        }
        let e =
            read(format!("{head}0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2\n").as_bytes()).unwrap_err();
        match e {
            Error::Parse { line, msg, .. } => {
                assert_eq!(line, 14, "{msg}");
                assert!(msg.contains("inconsistent orientation"), "{msg}");
            }
            other => panic!("{other:?}"),
        }
        let e = read(format!("{head}0 0 0\n1 zz 0\n").as_bytes()).unwrap_err();
        match e {
            Error::Parse { line, .. } => assert_eq!(line, 11, "{e}"),
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn binary_negative_index_is_rejected() {
        let mut b = b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n\
                      property float y\nproperty float z\nelement face 1\n\
                      property list uchar int vertex_indices\nend_header\n"
            .to_vec();
        for p in [[0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]] {
            for c in p {
                b.extend_from_slice(&c.to_le_bytes());
            }
        }
        b.push(3);
        for v in [0i32, -1, 2] {
            b.extend_from_slice(&v.to_le_bytes());
        }
        let m = read(&b).unwrap_err().to_string();
        assert!(
            m.contains("face 0 (counted from 0) refers to vertex -1"),
            "{m}"
        );
        // Truncated payload.
        let m = read(&b[..b.len() - 3]).unwrap_err().to_string();
        assert!(m.starts_with("t.ply:"), "{m}");
    }

    #[test]
    fn writers_roundtrip_exactly() {
        let pos = vec![
            [0.1, -2.0 / 3.0, 1e-300],
            [1.0, 0.0, 12345.678901234567],
            [1.0, 1.0, -7.5],
            [0.0, 1.0, 3.0e20],
            [0.5, 2.0, 0.0],
        ];
        let p = Polygons::new(&pos, &[0, 4, 7], &[0, 1, 2, 3, 3, 2, 4]).unwrap();
        for binary in [false, true] {
            let mut buf = Vec::new();
            if binary {
                write_ply_binary_to(&mut buf, &p).unwrap();
                // header + 5 * 24 bytes + (1 + 16) + (1 + 12)
                let header = header_text(&p, "binary_little_endian");
                assert!(header.contains("property list uchar int vertex_indices"));
                assert_eq!(buf.len(), header.len() + 5 * 24 + 17 + 13);
            } else {
                write_ply_ascii_to(&mut buf, &p).unwrap();
            }
            let m = read(&buf).unwrap();
            assert_eq!(m.mesh.positions(), &pos[..]);
            assert_eq!(m.mesh.face(0), &[0, 1, 2, 3]);
            assert_eq!(m.mesh.face(1), &[3, 2, 4]);
            assert!(m.warnings.is_empty());
        }
    }

    #[test]
    fn parallel_binary_writer_equals_a_plain_encoding() {
        // Enough vertices and faces for many jobs and batches; mixed face sizes.
        let n = 300_000;
        let pos: Vec<[f64; 3]> = (0..n)
            .map(|i| [i as f64, (i as f64).sqrt(), -(i as f64) / 7.0])
            .collect();
        let mut fs = vec![0u32];
        let mut corners = Vec::new();
        let mut v = 0u32;
        while (v as usize) + 5 < n {
            let k = 3 + (v % 3);
            corners.extend(v..v + k);
            fs.push(corners.len() as u32);
            v += 2;
        }
        let p = Polygons::new(&pos, &fs, &corners).unwrap();
        let mut fast = Vec::new();
        write_ply_binary_to(&mut fast, &p).unwrap();
        let mut plain = header_text(&p, "binary_little_endian").into_bytes();
        for q in &pos {
            for c in q {
                plain.extend_from_slice(&c.to_le_bytes());
            }
        }
        for f in 0..p.num_faces() {
            plain.push(p.face(f).len() as u8);
            for &v in p.face(f) {
                plain.extend_from_slice(&v.to_le_bytes());
            }
        }
        assert!(fast == plain, "encodings differ");
    }
}
