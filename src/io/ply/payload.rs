//! The PLY payload. Ascii lines are decoded by the text rule and parsed here by the declared
//! property types, so errors name the file line and the property; binary elements are read one
//! at a time by `ply-rs-bw`, so errors name the element and how many were read. Vertex `x y z`
//! and every other scalar vertex property (any scalar type), the face index list (any integer
//! type) and the face `texcoord` list are kept; every other element and property is checked and
//! skipped.

use super::super::text::{file_error, io_error, line_text, parse_error, strip_line_end};
use super::header::{PlyHeader, crate_message};
use crate::error::{Error, Result};
use crate::geom::Point;
use ply_rs_bw::parser::{ParseError, Parser};
use ply_rs_bw::ply::{
    BeginList, ElementDef, Encoding, Property, PropertyAccess, PropertyAccessResult, PropertyType,
    ScalarType,
};
use std::io::BufRead;
use std::path::Path;

/// The vertices and faces of a PLY payload.
pub(super) struct Payload {
    pub positions: Vec<Point>,
    pub face_start: Vec<u32>,
    pub corners: Vec<u32>,
    /// The lines of the first vertex and of the first face (ascii files only).
    pub first_lines: Option<(usize, usize)>,
    /// Per vertex, the value of each pair of [`UV_PAIRS`] (zero where the file lacks it).
    pub vertex_uv: Vec<[[f64; 2]; 4]>,
    /// Per face corner, the face `texcoord` list's pair (empty without that list).
    pub corner_uv: Vec<[f64; 2]>,
    /// Every scalar vertex property other than `x y z`, vertex after vertex, in header order
    /// (texture coordinates included: the reader decides which of them are per-vertex data).
    pub vertex_extra: Vec<f64>,
}

/// The per-vertex texture coordinate property pairs a PLY file may have, in order of
/// preference.
pub(super) const UV_PAIRS: [[&str; 2]; 4] = [
    ["u", "v"],
    ["s", "t"],
    ["texture_u", "texture_v"],
    ["texture_s", "texture_t"],
];

/// The face property with per-corner texture coordinates (a float list, 2 per corner, as
/// MeshLab writes it).
pub(super) const TEXCOORD: &str = "texcoord";

/// Where a vertex property lands in `[[f64; 2]; 4]` (pair, coordinate), if it is one of
/// [`UV_PAIRS`].
fn uv_slot(name: &str) -> Option<(usize, usize)> {
    UV_PAIRS
        .iter()
        .enumerate()
        .find_map(|(k, pair)| pair.iter().position(|&n| n == name).map(|c| (k, c)))
}

/// Where a face came from, for messages: its ascii line, or none (binary).
#[derive(Clone, Copy)]
enum At {
    Line(usize),
    Binary,
}

/// Reads every element of the payload, in header order.
pub(super) fn read_payload<R: BufRead>(
    reader: &mut R,
    head: &PlyHeader,
    path: &Path,
) -> Result<Payload> {
    let elements = &head.header.elements;
    let nv = elements.get("vertex").map_or(0, |d| d.count);
    if nv > u32::MAX as usize {
        return Err(Error::Unsupported(format!(
            "{}: {nv} vertices are more than fairsub's limit of 2^32 - 1",
            path.display()
        )));
    }
    let nf = elements.get("face").map_or(0, |d| d.count);
    // Counts come from the header: reserve at most what a small file could hold.
    let cap = |n: usize| n.min(1 << 16);
    let mut sink = Sink {
        out: Payload {
            positions: Vec::with_capacity(cap(nv)),
            face_start: Vec::with_capacity(cap(nf) + 1),
            corners: Vec::with_capacity(4 * cap(nf)),
            first_lines: None,
            vertex_uv: Vec::new(),
            corner_uv: Vec::new(),
            vertex_extra: Vec::new(),
        },
        nv,
        index_name: head.index_name,
        has_uv: elements.get("vertex").is_some_and(|d| {
            UV_PAIRS
                .iter()
                .any(|pair| pair.iter().all(|n| d.properties.contains_key(*n)))
        }),
        path,
    };
    sink.out.face_start.push(0);
    let ascii = head.header.encoding == Encoding::Ascii;
    let big = head.header.encoding == Encoding::BinaryBigEndian;
    // The last line read (ascii), and the first lines of the vertices and faces.
    let mut line = head.end_line;
    let mut first = (0, 0);
    for (name, def) in elements {
        let kind = match name.as_str() {
            "vertex" => Kind::Vertex,
            "face" => Kind::Face,
            _ => Kind::Other,
        };
        if ascii {
            match kind {
                Kind::Vertex => first.0 = line + 1,
                Kind::Face => first.1 = line + 1,
                Kind::Other => {}
            }
            sink.ascii(reader, def, kind, &mut line)?;
        } else {
            sink.binary(reader, def, kind, big)?;
        }
    }
    if ascii {
        sink.out.first_lines = Some(first);
    }
    Ok(sink.out)
}

/// Which of the elements fairsub reads an element is.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Kind {
    Vertex,
    Face,
    Other,
}

/// Collects the payload, checking faces as they come.
struct Sink<'a> {
    out: Payload,
    /// The vertex count of the header.
    nv: usize,
    index_name: &'static str,
    /// Whether the vertex element has a pair of [`UV_PAIRS`].
    has_uv: bool,
    path: &'a Path,
}

impl Sink<'_> {
    /// Reads the `def.count` lines of an ascii element; `line` is the last line read.
    fn ascii<R: BufRead>(
        &mut self,
        reader: &mut R,
        def: &ElementDef,
        kind: Kind,
        line: &mut usize,
    ) -> Result<()> {
        let (path, name) = (self.path, &def.name);
        let mut raw = Vec::new();
        let mut indices: Vec<i64> = Vec::new();
        let mut texcoord: Vec<f64> = Vec::new();
        for k in 0..def.count {
            raw.clear();
            let n = reader
                .read_until(b'\n', &mut raw)
                .map_err(|e| io_error(path, e))?;
            if n == 0 {
                return Err(parse_error(
                    path,
                    (*line).max(1),
                    format!(
                        "file ends after {k} of the {} '{name}' elements the header announces",
                        def.count
                    ),
                ));
            }
            *line += 1;
            let content = strip_line_end(&raw);
            let text = line_text(content, content.len(), path, *line)?;
            let mut v = Vertex::default();
            indices.clear();
            texcoord.clear();
            let mut lists = (&mut indices, &mut texcoord);
            ascii_element(text, def, kind, self.index_name, &mut v, &mut lists)
                .map_err(|m| parse_error(path, *line, format!("{name} {k}: {m}")))?;
            match kind {
                Kind::Vertex => self.vertex(v),
                Kind::Face => {
                    self.face(k, indices.iter().copied(), At::Line(*line))?;
                    self.texcoord(k, def, &texcoord, At::Line(*line))?;
                }
                Kind::Other => {}
            }
        }
        Ok(())
    }

    /// Reads the `def.count` binary elements of `def`.
    fn binary<R: BufRead>(
        &mut self,
        reader: &mut R,
        def: &ElementDef,
        kind: Kind,
        big_endian: bool,
    ) -> Result<()> {
        let (path, name) = (self.path, &def.name);
        let fail = |k: usize, e: ParseError| {
            if e.kind() == std::io::ErrorKind::UnexpectedEof {
                file_error(
                    path,
                    format!(
                        "binary '{name}' data ends after {k} of the {} elements the header \
                         announces (the file is truncated)",
                        def.count
                    ),
                )
            } else {
                file_error(
                    path,
                    format!(
                        "binary '{name}' element {k} (counted from 0): {}",
                        crate_message(&e)
                    ),
                )
            }
        };
        match kind {
            Kind::Vertex => {
                let parser = Parser::<Vertex>::new();
                for k in 0..def.count {
                    let v =
                        binary_element(&parser, reader, def, big_endian).map_err(|e| fail(k, e))?;
                    self.vertex(v);
                }
            }
            Kind::Face => {
                let parser = Parser::<Face>::new();
                for k in 0..def.count {
                    let f =
                        binary_element(&parser, reader, def, big_endian).map_err(|e| fail(k, e))?;
                    self.face(k, f.indices(), At::Binary)?;
                    self.texcoord(k, def, &f.texcoord, At::Binary)?;
                }
            }
            Kind::Other => {
                let parser = Parser::<Skip>::new();
                for k in 0..def.count {
                    binary_element(&parser, reader, def, big_endian).map_err(|e| fail(k, e))?;
                }
            }
        }
        Ok(())
    }

    /// Appends a vertex (its texture coordinates only when the file has some).
    fn vertex(&mut self, v: Vertex) {
        self.out.positions.push(v.p);
        self.out.vertex_extra.extend_from_slice(&v.extra);
        if self.has_uv {
            self.out.vertex_uv.push(v.uv);
        }
    }

    /// Appends the `texcoord` list of face `f` (just appended), checking that it holds two
    /// values per corner; nothing when the face element has no such list.
    fn texcoord(&mut self, f: usize, def: &ElementDef, list: &[f64], at: At) -> Result<()> {
        if !def.properties.contains_key(TEXCOORD) {
            return Ok(());
        }
        let n = (self.out.face_start[f + 1] - self.out.face_start[f]) as usize;
        if list.len() != 2 * n {
            let what = format!(
                "has {n} corners but its '{TEXCOORD}' list holds {} values (2 per corner expected)",
                list.len()
            );
            return Err(match at {
                At::Line(l) => parse_error(self.path, l, format!("face {f} {what}")),
                At::Binary => file_error(self.path, format!("face {f} (counted from 0) {what}")),
            });
        }
        if let Some(i) = list.iter().position(|x| !x.is_finite()) {
            let what = format!("'{TEXCOORD}' value {i} is not finite");
            return Err(match at {
                At::Line(l) => parse_error(self.path, l, format!("face {f} {what}")),
                At::Binary => file_error(self.path, format!("face {f} (counted from 0) {what}")),
            });
        }
        self.out
            .corner_uv
            .extend(list.chunks_exact(2).map(|c| [c[0], c[1]]));
        Ok(())
    }

    /// Appends face `f`, checking its indices and size.
    fn face(&mut self, f: usize, indices: impl Iterator<Item = i64>, at: At) -> Result<()> {
        let error = |what: String| match at {
            At::Line(l) => parse_error(self.path, l, format!("face {f} {what}")),
            At::Binary => file_error(self.path, format!("face {f} (counted from 0) {what}")),
        };
        let corners = &mut self.out.corners;
        let before = corners.len();
        for v in indices {
            if v < 0 || v as u64 >= self.nv as u64 {
                return Err(error(format!(
                    "refers to vertex {v}, but the file has {} vertices (indices 0..{})",
                    self.nv,
                    self.nv.saturating_sub(1)
                )));
            }
            corners.push(v as u32);
        }
        let n = corners.len() - before;
        if n < 3 {
            return Err(error(format!("has {n} corners; a face needs at least 3")));
        }
        if corners.len() > u32::MAX as usize {
            return Err(Error::Unsupported(format!(
                "{}: more than 2^32 - 1 face corners",
                self.path.display()
            )));
        }
        self.out.face_start.push(corners.len() as u32);
        Ok(())
    }
}

/// One binary element in the file's byte order.
fn binary_element<E: PropertyAccess, R: BufRead>(
    parser: &Parser<E>,
    reader: &mut R,
    def: &ElementDef,
    big_endian: bool,
) -> std::result::Result<E, ParseError> {
    if big_endian {
        parser.read_big_endian_element(reader, def)
    } else {
        parser.read_little_endian_element(reader, def)
    }
}

/// The PLY name of a scalar type.
fn type_name(t: &ScalarType) -> &'static str {
    match t {
        ScalarType::Char => "char",
        ScalarType::UChar => "uchar",
        ScalarType::Short => "short",
        ScalarType::UShort => "ushort",
        ScalarType::Int => "int",
        ScalarType::UInt => "uint",
        ScalarType::Float => "float",
        ScalarType::Double => "double",
    }
}

/// An ascii token as an integer of type `t` (`None` if it is not one, or `t` is a float type).
fn parse_int(tok: &str, t: &ScalarType) -> Option<i64> {
    match t {
        ScalarType::Char => tok.parse::<i8>().ok().map(i64::from),
        ScalarType::UChar => tok.parse::<u8>().ok().map(i64::from),
        ScalarType::Short => tok.parse::<i16>().ok().map(i64::from),
        ScalarType::UShort => tok.parse::<u16>().ok().map(i64::from),
        ScalarType::Int => tok.parse::<i32>().ok().map(i64::from),
        ScalarType::UInt => tok.parse::<u32>().ok().map(i64::from),
        ScalarType::Float | ScalarType::Double => None,
    }
}

/// An ascii token as a value of type `t`, as a coordinate (a `float` is read as `f32`, as the
/// binary reader does).
fn parse_scalar(tok: &str, t: &ScalarType) -> Option<f64> {
    match t {
        ScalarType::Float => tok.parse::<f32>().ok().map(f64::from),
        ScalarType::Double => tok.parse::<f64>().ok(),
        _ => parse_int(tok, t).map(|v| v as f64),
    }
}

/// Parses one ascii element line by the properties of `def`: a vertex's `x y z` and texture
/// coordinates go to `v`, a face's index list and `texcoord` list to `lists`; every value is
/// checked against its declared type. The error names the property.
fn ascii_element(
    text: &str,
    def: &ElementDef,
    kind: Kind,
    index_name: &str,
    v: &mut Vertex,
    lists: &mut (&mut Vec<i64>, &mut Vec<f64>),
) -> std::result::Result<(), String> {
    let mut toks = text.split_whitespace();
    let mut next = |prop: &str, t: &ScalarType| {
        toks.next()
            .ok_or_else(|| format!("the line ends before property '{prop}' ({})", type_name(t)))
    };
    let bad = |prop: &str, tok: &str, t: &ScalarType| {
        format!("property '{prop}' is '{tok}', not of type {}", type_name(t))
    };
    for (prop, pd) in &def.properties {
        match &pd.data_type {
            PropertyType::Scalar(t) => {
                let tok = next(prop, t)?;
                let x = parse_scalar(tok, t).ok_or_else(|| bad(prop, tok, t))?;
                if kind == Kind::Vertex {
                    v.set(prop, x);
                }
            }
            PropertyType::List(count_type, item_type) => {
                let tok = next(prop, count_type)?;
                let n = parse_int(tok, count_type)
                    .and_then(|n| usize::try_from(n).ok())
                    .ok_or_else(|| bad(prop, tok, count_type))?;
                let keep = kind == Kind::Face && prop == index_name;
                let uv = kind == Kind::Face && prop == TEXCOORD;
                for i in 0..n {
                    let tok = next(prop, item_type).map_err(|_| {
                        format!("list '{prop}' announces {n} entries but the line has {i}")
                    })?;
                    if keep {
                        lists.0.push(
                            parse_int(tok, item_type).ok_or_else(|| bad(prop, tok, item_type))?,
                        );
                    } else {
                        let x = parse_scalar(tok, item_type)
                            .ok_or_else(|| bad(prop, tok, item_type))?;
                        if uv {
                            lists.1.push(x);
                        }
                    }
                }
            }
        }
    }
    let extra = toks.count();
    if extra > 0 {
        return Err(format!(
            "the line has {extra} more value{} than the properties of element '{}' take",
            if extra == 1 { "" } else { "s" },
            def.name
        ));
    }
    Ok(())
}

/// A vertex: `x y z`, the pairs of [`UV_PAIRS`] and every other scalar property (in header
/// order), of any scalar type. A file without other properties allocates nothing per vertex.
#[derive(Debug, Default)]
struct Vertex {
    p: Point,
    uv: [[f64; 2]; 4],
    extra: Vec<f64>,
}

impl Vertex {
    /// Keeps scalar property `name`: a coordinate, or another property (a texture coordinate
    /// also in its pair's slot).
    fn set(&mut self, name: &str, x: f64) {
        if let Some(c) = ["x", "y", "z"].iter().position(|&c| c == name) {
            self.p[c] = x;
            return;
        }
        if let Some((k, c)) = uv_slot(name) {
            self.uv[k][c] = x;
        }
        self.extra.push(x);
    }
}

impl PropertyAccess for Vertex {
    fn new() -> Self {
        Vertex::default()
    }
    fn set_property(&mut self, name: &str, p: Property) -> PropertyAccessResult {
        let v = match p {
            Property::Char(v) => v as f64,
            Property::UChar(v) => v as f64,
            Property::Short(v) => v as f64,
            Property::UShort(v) => v as f64,
            Property::Int(v) => v as f64,
            Property::UInt(v) => v as f64,
            Property::Float(v) => v as f64,
            Property::Double(v) => v,
            // A list per vertex is skipped (the reader warns, naming it).
            _ => return PropertyAccessResult::Ignored,
        };
        self.set(name, v);
        PropertyAccessResult::Set
    }
}

/// A binary face: vertex indices as read. `int` and `uint` lists (the common ones) are filled
/// in place by the parser; other integer types go through `set_property`.
#[derive(Debug, Default)]
struct Face {
    int: Vec<i32>,
    uint: Vec<u32>,
    other: Vec<i64>,
    /// The `texcoord` list.
    texcoord: Vec<f64>,
}

impl PropertyAccess for Face {
    fn new() -> Self {
        Face::default()
    }
    fn begin_list_int(&mut self, name: &str, _len: usize) -> BeginList<'_, i32> {
        if super::header::INDEX_NAMES.contains(&name) {
            BeginList::Fill(&mut self.int)
        } else {
            BeginList::UseSetter
        }
    }
    fn begin_list_uint(&mut self, name: &str, _len: usize) -> BeginList<'_, u32> {
        if super::header::INDEX_NAMES.contains(&name) {
            BeginList::Fill(&mut self.uint)
        } else {
            BeginList::UseSetter
        }
    }
    fn set_property(&mut self, name: &str, p: Property) -> PropertyAccessResult {
        if name == TEXCOORD {
            self.texcoord = match p {
                Property::ListFloat(v) => v.into_iter().map(f64::from).collect(),
                Property::ListDouble(v) => v,
                _ => return PropertyAccessResult::UnsupportedType,
            };
            return PropertyAccessResult::Set;
        }
        if !super::header::INDEX_NAMES.contains(&name) {
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
