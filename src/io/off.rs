//! Geomview OFF: reader and writer (ascii).
//!
//! The reader accepts the header keywords `OFF`, `COFF`, `NOFF`, `CNOFF`, `STOFF` and the like
//! (per-vertex colours, normals and texture coordinates after x y z are ignored, as is per-face
//! colour after the indices), `#` comments, blank lines, counts on the header line or the next
//! one, and a file without header keyword that starts with the counts. It reads line by line (one
//! vertex or face per line, as every OFF writer does), so errors name the line. `4OFF`, `nOFF`
//! (other dimensions) and `OFF BINARY` are rejected as unsupported. Text follows the rule of
//! every reader: invalid UTF-8 only inside comments.

use super::text::{Lines, io_error, parse_error, read_all};
use super::textout::ChunkedText;
use super::{ListedMesh, LoadedMesh, Polygons, finish_listed};
use crate::error::{Error, Result};
use std::io::{Read, Write};
use std::path::Path;

/// Reads an OFF file.
pub fn read_off(path: &Path) -> Result<LoadedMesh> {
    let file = std::fs::File::open(path).map_err(|e| io_error(path, e))?;
    read_off_from(std::io::BufReader::with_capacity(1 << 16, file), path)
}

/// Reads OFF from any reader; `path` is used in messages only.
pub fn read_off_from<R: Read>(reader: R, path: &Path) -> Result<LoadedMesh> {
    read_off_with(reader, path, false)
}

/// [`read_off_from`], tolerantly with `tolerant` (see [`super::read_mesh_as`]).
pub fn read_off_with<R: Read>(reader: R, path: &Path, tolerant: bool) -> Result<LoadedMesh> {
    let bytes = read_all(reader, path)?;
    // Non-empty content lines (comments stripped, trimmed) with their 1-based numbers.
    let mut lines = Lines::new(&bytes, path);
    let mut warnings = Vec::new();
    let (counts_line, toks) = read_header(&mut lines, path, &mut warnings)?;
    let (nv, nf) = parse_counts(&toks, counts_line, path)?;
    // Counts come from the file: never reserve more than its size can hold (a vertex or face
    // line has at least 6 bytes), so a garbage count cannot trigger a huge allocation.
    let cap = |n: usize| n.min(bytes.len() / 6 + 1);
    let mut listed = ListedMesh {
        positions: Vec::with_capacity(cap(nv)),
        vertex_line: Vec::with_capacity(cap(nv)),
        face_start: Vec::with_capacity(cap(nf) + 1),
        corners: Vec::with_capacity(3 * cap(nf)),
        face_line: Vec::with_capacity(cap(nf)),
    };
    read_vertices(&mut lines, path, nv, &mut listed)?;
    read_faces(&mut lines, path, (nf, nv), &mut listed)?;
    if let Some((l, _)) = lines.next_content()? {
        warnings.push(format!(
            "ignored content after the last face, from line {l} on"
        ));
    }
    if listed.face_line.is_empty() {
        return Err(parse_error(
            path,
            counts_line,
            format!("no faces ({nv} vertices); fairsub needs a polygon mesh"),
        ));
    }
    let mesh = finish_listed(
        path,
        listed,
        " (faces and vertices counted from 0 in file order)",
        &mut warnings,
        tolerant,
    )?;
    Ok(LoadedMesh { mesh, warnings })
}

/// The header: the keyword (`OFF`, `COFF`, ...; refused: other dimensions and binary OFF) and
/// the counts line's tokens with its number (on the keyword's line or the next one; the first
/// line itself, with a warning, when the file has no keyword).
fn read_header<'a>(
    lines: &mut Lines<'a>,
    path: &Path,
    warnings: &mut Vec<String>,
) -> Result<(usize, Vec<&'a str>)> {
    let (first_line, first) =
        lines.require(|| "empty file: expected an 'OFF' header".to_string())?;
    let mut toks: Vec<&str> = first.split_whitespace().collect();
    let mut counts_line = first_line;
    if toks[0].parse::<u64>().is_err() {
        let kw = toks[0];
        let Some(prefix) = kw.strip_suffix("OFF") else {
            return Err(parse_error(
                path,
                first_line,
                format!("expected the header keyword 'OFF' (or COFF, NOFF, ...), found '{kw}'"),
            ));
        };
        if prefix.contains('4') || prefix.contains('n') {
            return Err(Error::Unsupported(format!(
                "{}:{first_line}: '{kw}' files (points of other dimension than 3) are not supported",
                path.display()
            )));
        }
        if let Some(bad) = prefix.chars().find(|c| !matches!(c, 'S' | 'T' | 'C' | 'N')) {
            return Err(parse_error(
                path,
                first_line,
                format!("unknown OFF header keyword '{kw}' (unexpected '{bad}')"),
            ));
        }
        toks.remove(0);
        if toks
            .first()
            .is_some_and(|t| t.eq_ignore_ascii_case("BINARY"))
        {
            return Err(Error::Unsupported(format!(
                "{}:{first_line}: binary OFF is not supported; convert it to ascii OFF, OBJ or PLY",
                path.display()
            )));
        }
        if toks.is_empty() {
            let (l, t) = lines.require(|| {
                "file ends after the header: expected the counts line 'vertices faces edges'"
                    .to_string()
            })?;
            counts_line = l;
            toks = t.split_whitespace().collect();
        }
    } else {
        warnings.push("no 'OFF' header keyword; the first line was read as the counts".to_string());
    }
    Ok((counts_line, toks))
}

/// The vertex and face counts of the counts line (number `counts_line`).
fn parse_counts(toks: &[&str], counts_line: usize, path: &Path) -> Result<(usize, usize)> {
    if toks.len() < 2 {
        return Err(parse_error(
            path,
            counts_line,
            "expected the counts 'vertices faces [edges]'",
        ));
    }
    let count = |k: usize, what: &str| -> Result<usize> {
        toks[k].parse::<usize>().map_err(|_| {
            parse_error(
                path,
                counts_line,
                format!(
                    "bad {what} count '{}' (expected a non-negative integer)",
                    toks[k]
                ),
            )
        })
    };
    let nv = count(0, "vertex")?;
    if nv > u32::MAX as usize {
        return Err(parse_error(
            path,
            counts_line,
            format!("{nv} vertices are more than fairsub's limit of 2^32 - 1"),
        ));
    }
    let nf = count(1, "face")?;
    Ok((nv, nf))
}

/// The `nv` vertex lines: x y z each (anything after them is ignored).
fn read_vertices(
    lines: &mut Lines<'_>,
    path: &Path,
    nv: usize,
    listed: &mut ListedMesh,
) -> Result<()> {
    for k in 0..nv {
        let (l, t) = lines.require(|| format!("file ends after {k} of {nv} vertices"))?;
        let mut it = t.split_whitespace();
        let mut p = [0.0; 3];
        for (c, slot) in p.iter_mut().enumerate() {
            let tok = it.next().ok_or_else(|| {
                parse_error(
                    path,
                    l,
                    format!("vertex {k} has {c} coordinates; expected x y z"),
                )
            })?;
            *slot = tok.parse().map_err(|_| {
                parse_error(
                    path,
                    l,
                    format!(
                        "bad number '{tok}' for the {} coordinate of vertex {k}",
                        ["x", "y", "z"][c]
                    ),
                )
            })?;
        }
        listed.positions.push(p);
        listed.vertex_line.push(l as u32);
    }
    Ok(())
}

/// The `nf` face lines: a corner count, then that many indices below `nv` (anything after
/// them is ignored).
fn read_faces(
    lines: &mut Lines<'_>,
    path: &Path,
    (nf, nv): (usize, usize),
    listed: &mut ListedMesh,
) -> Result<()> {
    let corners = &mut listed.corners;
    listed.face_start.push(0);
    for k in 0..nf {
        let (l, t) = lines.require(|| format!("file ends after {k} of {nf} faces"))?;
        let mut it = t.split_whitespace();
        let n_tok = it.next().unwrap_or("");
        let n: usize = n_tok
            .parse()
            .map_err(|_| parse_error(path, l, format!("bad corner count '{n_tok}' of face {k}")))?;
        if n < 3 {
            return Err(parse_error(
                path,
                l,
                format!("face {k} has {n} corners; a face needs at least 3"),
            ));
        }
        for c in 0..n {
            let tok = it.next().ok_or_else(|| {
                parse_error(
                    path,
                    l,
                    format!("face {k} announces {n} corners but lists {c}"),
                )
            })?;
            let v: usize = tok.parse().map_err(|_| {
                parse_error(path, l, format!("bad vertex index '{tok}' in face {k}"))
            })?;
            if v >= nv {
                return Err(parse_error(
                    path,
                    l,
                    format!(
                        "face {k} refers to vertex {v}, but the file has {nv} vertices (indices 0..{})",
                        nv.saturating_sub(1)
                    ),
                ));
            }
            corners.push(v as u32);
        }
        if corners.len() > u32::MAX as usize {
            return Err(parse_error(path, l, "more than 2^32 - 1 face corners"));
        }
        listed.face_start.push(corners.len() as u32);
        listed.face_line.push(l as u32);
    }
    Ok(())
}

/// Writes polygons as ascii OFF with round-trip precision.
pub(crate) fn write_off_to(w: &mut dyn Write, p: &Polygons<'_>) -> std::io::Result<()> {
    use std::fmt::Write as _;
    let mut out = ChunkedText::new(w);
    let _ = writeln!(out.buf, "OFF\n{} {} 0", p.positions.len(), p.num_faces());
    out.point_lines("", p.positions)?;
    out.counted_face_lines(p.faces())?;
    out.finish()
}

#[cfg(feature = "unit-tests")]
mod tests;
