//! File formats of nets with face control vertices: the FCV side file and the OBJ layout.
//!
//! # FCV side file (`.fcv`)
//!
//! Gives the FCVs of a control net read from any mesh file, one line per face, in the face
//! order of the mesh file:
//!
//! ```text
//! # fairsub FCV file: one line per face, in face order
//! 0.5 0.5 1.25      <- the FCV of face 0: three numbers x y z
//! *                 <- face 1 keeps its default FCV (barycentre times the FCV scale)
//! ```
//!
//! `#` starts a comment, blank lines are ignored, numbers may be separated by spaces, tabs or
//! commas. The number of FCV lines must equal the number of faces. Errors name the file line.
//!
//! # OBJ layout of a net with FCVs
//!
//! [`write_fcv_obj`] writes the mesh vertices as `v` lines, then the FCVs as further `v` lines
//! (one per face, in face order), then the faces over the mesh vertices only, so any OBJ viewer
//! shows the net with its FCVs as loose points. A comment line `# fcv N` states the count:
//!
//! ```text
//! # fairsub non-box net with face control vertices (FCVs)
//! # fcv 6: the last 6 v lines are the FCVs, one per face in face order; no face uses them
//! # fairsub: 14 vertices, 6 faces
//! v -1 -1 -1
//! ...
//! v 0 0 -1          <- FCV of face 0
//! ...
//! f 1 4 3 2
//! ```
//!
//! # OBJ limit mesh with normals
//!
//! [`write_limit_obj`] writes a [limit mesh](super::NonBox::limit_mesh_with_normals) with one
//! `vn` line per `v` line (the exact limit normal of that point) and faces `f a//a b//b c//c`.
//!
//! [`read_fcv_obj`] reads it back: the vertices no face uses become the FCVs when they are the
//! last `v` lines and there is exactly one per face (or a `# fcv N` line says so). The same
//! layout in memory is [`FcvNet::to_layout_mesh`].

use super::FcvNet;
use crate::error::{Error, Result};
use crate::geom::Point;
use crate::io::{LoadedMesh, MeshFormat};
use crate::mesh::PolyMesh;
use std::path::Path;

fn parse_err(path: &Path, line: usize, msg: String) -> Error {
    Error::Parse {
        path: path.to_path_buf(),
        line,
        msg,
    }
}

/// Parses an FCV side file: one entry per FCV line (`None` for `*`, the default), with the
/// 1-based line number of each. Errors name the line.
pub fn parse_fcv_file(text: &str, path: &Path) -> Result<Vec<(usize, Option<Point>)>> {
    let mut out = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let line = i + 1;
        let content = raw.split('#').next().unwrap_or("").trim();
        if content.is_empty() {
            continue;
        }
        if content == "*" {
            out.push((line, None));
            continue;
        }
        let toks: Vec<&str> = content
            .split(|c: char| c.is_whitespace() || c == ',')
            .filter(|t| !t.is_empty())
            .collect();
        if toks.len() != 3 {
            return Err(parse_err(
                path,
                line,
                format!(
                    "expected an FCV as three numbers 'x y z' or '*' for the default, found {} \
                     item(s) '{content}'",
                    toks.len()
                ),
            ));
        }
        let mut p = [0.0; 3];
        for (k, t) in toks.iter().enumerate() {
            let x: f64 = t.parse().map_err(|_| {
                parse_err(
                    path,
                    line,
                    format!("'{t}' is not a number (coordinate {} of the FCV)", k + 1),
                )
            })?;
            if !x.is_finite() {
                return Err(parse_err(
                    path,
                    line,
                    format!("coordinate {} of the FCV is not finite ('{t}')", k + 1),
                ));
            }
            p[k] = x;
        }
        out.push((line, Some(p)));
    }
    Ok(out)
}

/// The net of `mesh` with the FCVs of an FCV side file (`text`, read from `path`); faces marked
/// `*` get `scale` times their barycentre. Errors name the file line, or say how many lines are
/// missing.
pub fn fcv_net_from_file(mesh: PolyMesh, text: &str, path: &Path, scale: f64) -> Result<FcvNet> {
    let entries = parse_fcv_file(text, path)?;
    let nf = mesh.num_faces();
    if entries.len() > nf {
        return Err(parse_err(
            path,
            entries[nf].0,
            format!(
                "FCV line {} is one too many: the net has {nf} faces, so the file needs exactly \
                 {nf} FCV lines",
                nf + 1
            ),
        ));
    }
    if entries.len() < nf {
        let last = entries.last().map(|e| e.0).unwrap_or(0);
        return Err(parse_err(
            path,
            last,
            format!(
                "the file has {} FCV lines but the net has {nf} faces: add one line per missing \
                 face (three numbers, or '*' for the default)",
                entries.len()
            ),
        ));
    }
    let mut net = FcvNet::scaled(mesh, scale)?;
    for (f, (_, p)) in entries.into_iter().enumerate() {
        if let Some(p) = p {
            net.fcv[f] = p;
        }
    }
    Ok(net)
}

/// Reads an FCV side file from disk for `mesh` (see [`fcv_net_from_file`]).
pub fn load_fcv_file(mesh: PolyMesh, path: &Path, scale: f64) -> Result<FcvNet> {
    let text = std::fs::read_to_string(path).map_err(|source| Error::Io {
        path: path.to_path_buf(),
        source,
    })?;
    fcv_net_from_file(mesh, &text, path, scale)
}

/// The FCV side file of a net (one `x y z` line per face).
pub fn fcv_file_string(net: &FcvNet) -> String {
    let mut s = format!(
        "# fairsub FCV file: one line per face, in face order ({} faces)\n",
        net.fcv.len()
    );
    for p in &net.fcv {
        s.push_str(&format!("{} {} {}\n", p[0], p[1], p[2]));
    }
    s
}

/// Writes the FCV side file of a net (atomically).
pub fn write_fcv_file(path: &Path, net: &FcvNet) -> Result<()> {
    let text = fcv_file_string(net);
    crate::io::write_atomically(path, |w| {
        w.write_all(text.as_bytes()).map_err(|source| Error::Io {
            path: path.to_path_buf(),
            source,
        })
    })
}

/// The OBJ text of a net with FCVs (layout in the [module](self) documentation).
pub fn fcv_obj_string(net: &FcvNet) -> Result<String> {
    let nf = net.fcv.len();
    let mut buf: Vec<u8> = format!(
        "# fairsub non-box net with face control vertices (FCVs)\n# fcv {nf}: the last {nf} v \
         lines are the FCVs, one per face in face order; no face uses them\n"
    )
    .into_bytes();
    crate::io::write_polygons_to(
        &mut buf,
        &net.points(),
        net.mesh.face_starts(),
        net.mesh.corners(),
        MeshFormat::Obj,
    )?;
    Ok(String::from_utf8(buf).expect("the OBJ writer writes UTF-8"))
}

/// Writes a net with FCVs as OBJ (atomically; layout in the [module](self) documentation).
pub fn write_fcv_obj(path: &Path, net: &FcvNet) -> Result<()> {
    let text = fcv_obj_string(net)?;
    crate::io::write_atomically(path, |w| {
        w.write_all(text.as_bytes()).map_err(|source| Error::Io {
            path: path.to_path_buf(),
            source,
        })
    })
}

/// Coordinates of every `v` line of an OBJ text, in file order (continued lines joined).
fn obj_vertex_lines(text: &str) -> Vec<(usize, Point)> {
    let mut out = Vec::new();
    let mut logical = String::new();
    let mut start = 0;
    for (i, raw) in text.lines().enumerate() {
        if logical.is_empty() {
            start = i + 1;
        }
        if let Some(head) = raw.strip_suffix('\\') {
            logical.push_str(head);
            logical.push(' ');
            continue;
        }
        logical.push_str(raw);
        let content = logical.split('#').next().unwrap_or("");
        let mut toks = content.split_whitespace();
        if toks.next() == Some("v") {
            let mut p = [f64::NAN; 3];
            for c in &mut p {
                *c = toks.next().and_then(|t| t.parse().ok()).unwrap_or(f64::NAN);
            }
            out.push((start, p));
        }
        logical.clear();
    }
    out
}

/// Parses OBJ text holding a net with FCVs (see [`read_fcv_obj`]); `path` names the file in
/// messages. Returns the net and notes for the user.
pub fn parse_fcv_obj(text: &str, path: &Path) -> Result<(FcvNet, Vec<String>)> {
    let (mesh, fcv, mut notes) = parse_obj_fcvs(text, path)?;
    match fcv {
        Some(fcv) => Ok((FcvNet::new(mesh, fcv)?, notes)),
        None => {
            notes.push("no FCVs in the file: the face barycentres are the FCVs".to_string());
            Ok((FcvNet::barycentric(mesh), notes))
        }
    }
}

/// Parses OBJ text that may hold a net with FCVs: the mesh, its FCVs when the file has them
/// (layout in the [module](self) documentation), and notes for the user. Errors as
/// [`parse_fcv_obj`].
pub fn parse_obj_fcvs(
    text: &str,
    path: &Path,
) -> Result<(PolyMesh, Option<Vec<Point>>, Vec<String>)> {
    let LoadedMesh { mesh, warnings } = crate::io::obj::read_obj_from(text.as_bytes(), path)?;
    let marker = text.lines().enumerate().find_map(|(i, l)| {
        let rest = l.trim().strip_prefix('#')?.trim().strip_prefix("fcv ")?;
        let n: usize = rest
            .split(|c: char| !c.is_ascii_digit())
            .next()?
            .parse()
            .ok()?;
        Some((i + 1, n))
    });
    let nf = mesh.num_faces();
    let verts = obj_vertex_lines(text);
    let dropped = mesh.dropped_vertices().to_vec();
    let total = verts.len();
    let trailing = dropped.len() == nf
        && total >= nf
        && dropped.iter().copied().eq(total - nf..total)
        && verts[total - nf..]
            .iter()
            .all(|(_, p)| p.iter().all(|c| c.is_finite()));
    if let Some((line, n)) = marker
        && (n != nf || !trailing)
    {
        return Err(parse_err(
            path,
            line,
            format!(
                "'# fcv {n}' announces {n} FCVs as the last v lines, but the net has {nf} \
                     faces and {} vertices unused by faces{}: give one FCV per face after the \
                     mesh vertices, or remove the line",
                dropped.len(),
                if dropped.len() == nf && !trailing {
                    " (not the last v lines)"
                } else {
                    ""
                }
            ),
        ));
    }
    if trailing && nf > 0 {
        let fcv = verts[total - nf..].iter().map(|&(_, p)| p).collect();
        let notes = warnings
            .into_iter()
            .filter(|w| !w.contains("used by no face"))
            .collect();
        return Ok((mesh, Some(fcv), notes));
    }
    Ok((mesh, None, warnings))
}

/// Reads an OBJ file that may hold a net with FCVs (see [`parse_obj_fcvs`]).
pub fn read_obj_fcvs(path: &Path) -> Result<(PolyMesh, Option<Vec<Point>>, Vec<String>)> {
    let text = std::fs::read_to_string(path).map_err(|source| Error::Io {
        path: path.to_path_buf(),
        source,
    })?;
    parse_obj_fcvs(&text, path)
}

/// Reads an OBJ file holding a net with FCVs (layout in the [module](self) documentation); a
/// plain OBJ net gets its face barycentres as FCVs (with a note). Returns the net and notes.
pub fn read_fcv_obj(path: &Path) -> Result<(FcvNet, Vec<String>)> {
    let text = std::fs::read_to_string(path).map_err(|source| Error::Io {
        path: path.to_path_buf(),
        source,
    })?;
    parse_fcv_obj(&text, path)
}

/// The OBJ text of a limit mesh with one unit normal per vertex (`v`, then `vn` lines in the
/// same order, faces `f a//a ...`). Errors when the counts differ or a value is not finite.
pub fn limit_obj_string(mesh: &PolyMesh, normals: &[Point]) -> Result<String> {
    use std::fmt::Write;
    if normals.len() != mesh.num_vertices() {
        return Err(Error::InvalidArgument(format!(
            "{} normals given for a mesh of {} vertices",
            normals.len(),
            mesh.num_vertices()
        )));
    }
    let bad = |p: &Point| !p.iter().all(|c| c.is_finite());
    if let Some(v) = mesh.positions().iter().position(bad) {
        return Err(Error::InvalidArgument(format!(
            "vertex {v} of the limit mesh has a NaN or infinite coordinate"
        )));
    }
    if let Some(v) = normals.iter().position(bad) {
        return Err(Error::InvalidArgument(format!(
            "the limit normal of vertex {v} is undefined (degenerate tangents there)"
        )));
    }
    let mut s = format!(
        "# fairsub non-box limit mesh: {} vertices with their limit normals, {} faces\n",
        mesh.num_vertices(),
        mesh.num_faces()
    );
    for p in mesh.positions() {
        let _ = writeln!(s, "v {} {} {}", p[0], p[1], p[2]);
    }
    for n in normals {
        let _ = writeln!(s, "vn {} {} {}", n[0], n[1], n[2]);
    }
    for f in mesh.faces() {
        s.push('f');
        for &v in f {
            let _ = write!(s, " {0}//{0}", v + 1);
        }
        s.push('\n');
    }
    Ok(s)
}

/// Writes a limit mesh with normals as OBJ (atomically; see [`limit_obj_string`]).
pub fn write_limit_obj(path: &Path, mesh: &PolyMesh, normals: &[Point]) -> Result<()> {
    let text = limit_obj_string(mesh, normals)?;
    crate::io::write_atomically(path, |w| {
        w.write_all(text.as_bytes()).map_err(|source| Error::Io {
            path: path.to_path_buf(),
            source,
        })
    })
}
