//! The PLY header: read line by line by the text rule (a `comment` or `obj_info` line may hold
//! any bytes, every other line must be UTF-8), parsed by `ply-rs-bw`, and checked for the
//! elements and properties fairsub needs. Errors name the header line concerned.

use super::super::text::{io_error, line_text, parse_error, strip_line_end};
use crate::error::Result;
use ply_rs_bw::parser::{ParseError, Parser, Reader};
use ply_rs_bw::ply::{DefaultElement, Header, PropertyType, ScalarType};
use std::io::BufRead;
use std::path::Path;

/// The names a face's vertex index list may have (`vertex_indices` is the usual one).
pub(super) const INDEX_NAMES: [&str; 2] = ["vertex_indices", "vertex_index"];

/// A parsed and checked PLY header, with the file lines that messages need.
pub(super) struct PlyHeader {
    /// The header as `ply-rs-bw` parsed it.
    pub header: Header,
    /// The name of the face index list (one of [`INDEX_NAMES`]).
    pub index_name: &'static str,
    /// The line of `end_header`; an ascii payload starts on the next line.
    pub end_line: usize,
    /// The line of each `element` declaration.
    element_lines: Vec<(String, usize)>,
}

impl PlyHeader {
    /// The line that declares element `name` (the `end_header` line if none does).
    pub fn element_line(&self, name: &str) -> usize {
        self.element_lines
            .iter()
            .find(|(n, _)| n == name)
            .map_or(self.end_line, |&(_, l)| l)
    }
}

/// The message of a `ply-rs-bw` error on one line, without the crate's `Line N: ` prefix and
/// its indented details (the caller says where).
pub(super) fn crate_message(e: &ParseError) -> String {
    let s = e.to_string();
    let s = match s.split_once(": ") {
        Some((head, rest)) if head.starts_with("Line ") => rest,
        _ => &s,
    };
    let first = s.lines().next().unwrap_or("").trim();
    first.strip_suffix('.').unwrap_or(first).to_string()
}

/// Reads the header from `reader` and checks it; `reader` is left at the first payload byte.
pub(super) fn read_header<R: BufRead>(reader: &mut R, path: &Path) -> Result<PlyHeader> {
    // The header as text for the crate (comment bytes made valid, line ends normalised), and
    // each line for messages.
    let mut text = String::new();
    let mut shown: Vec<String> = Vec::new();
    let mut element_lines = Vec::new();
    let mut raw = Vec::new();
    loop {
        raw.clear();
        let n = reader
            .read_until(b'\n', &mut raw)
            .map_err(|e| io_error(path, e))?;
        let line = shown.len() + 1;
        if n == 0 {
            let msg = if shown.is_empty() {
                "empty file: expected the PLY header ('ply' on the first line)"
            } else {
                "file ends in the PLY header: no 'end_header' line"
            };
            return Err(parse_error(path, shown.len().max(1), msg));
        }
        let content = strip_line_end(&raw);
        if line == 1 && content.trim_ascii() != b"ply" {
            let start: String = String::from_utf8_lossy(content).chars().take(40).collect();
            return Err(parse_error(
                path,
                1,
                format!("not a PLY file: the first line is '{start}', not 'ply'"),
            ));
        }
        let mut words = content
            .split(|b| b.is_ascii_whitespace())
            .filter(|w| !w.is_empty());
        let keyword = words.next().unwrap_or(b"");
        let decoded = if keyword == b"comment" || keyword == b"obj_info" {
            String::from_utf8_lossy(content).into_owned()
        } else {
            line_text(content, content.len(), path, line)?.to_string()
        };
        if keyword == b"element" {
            let name = words.next().unwrap_or(b"");
            element_lines.push((String::from_utf8_lossy(name).into_owned(), line));
        }
        text.push_str(&decoded);
        text.push('\n');
        shown.push(decoded);
        if content.trim_ascii() == b"end_header" {
            break;
        }
    }
    let end_line = shown.len();
    let header = Parser::<DefaultElement>::new()
        .read_header(&mut Reader::new(text.as_bytes()))
        .map_err(|e| {
            let msg = crate_message(&e);
            match e.line().filter(|&l| (1..=end_line).contains(&l)) {
                Some(l) => parse_error(path, l, format!("PLY header: {msg}: '{}'", shown[l - 1])),
                None => parse_error(path, end_line, format!("PLY header: {msg}")),
            }
        })?;
    let mut head = PlyHeader {
        header,
        index_name: INDEX_NAMES[0],
        end_line,
        element_lines,
    };
    head.index_name = check_header(&head, path)?;
    Ok(head)
}

fn is_int(t: &ScalarType) -> bool {
    !matches!(t, ScalarType::Float | ScalarType::Double)
}

/// Checks the header for the elements and properties we need; returns the face list's name.
fn check_header(head: &PlyHeader, path: &Path) -> Result<&'static str> {
    let elements = &head.header.elements;
    let names = || {
        elements
            .keys()
            .map(|k| format!("'{k}'"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let vertex = elements.get("vertex").ok_or_else(|| {
        parse_error(
            path,
            head.end_line,
            format!(
                "no 'vertex' element in the PLY header (elements: {})",
                names()
            ),
        )
    })?;
    let vertex_line = head.element_line("vertex");
    for c in ["x", "y", "z"] {
        match vertex.properties.get(c) {
            Some(p) if matches!(p.data_type, PropertyType::Scalar(_)) => {}
            Some(_) => {
                return Err(parse_error(
                    path,
                    vertex_line,
                    format!("property '{c}' of element 'vertex' is a list; expected a number"),
                ));
            }
            None => {
                return Err(parse_error(
                    path,
                    vertex_line,
                    format!("element 'vertex' has no property '{c}'"),
                ));
            }
        }
    }
    let face = elements.get("face").ok_or_else(|| {
        parse_error(
            path,
            head.end_line,
            format!(
                "no 'face' element in the PLY header (elements: {}); a point cloud is not a polygon mesh",
                names()
            ),
        )
    })?;
    let face_line = head.element_line("face");
    for name in INDEX_NAMES {
        if let Some(p) = face.properties.get(name) {
            return match &p.data_type {
                PropertyType::List(_, t) if is_int(t) => Ok(name),
                other => Err(parse_error(
                    path,
                    face_line,
                    format!(
                        "property '{name}' of element 'face' has type {other:?}; expected a list of integers"
                    ),
                )),
            };
        }
    }
    Err(parse_error(
        path,
        face_line,
        "element 'face' has neither a 'vertex_indices' nor a 'vertex_index' list property",
    ))
}
