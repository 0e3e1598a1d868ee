//! File formats of the non-box schemes' nets with face control vertices (FCVs): the FCV side
//! file, the OBJ layout of a net with FCVs, and the OBJ limit mesh with normals. The net itself,
//! [`FcvNet`], and its logic live with the scheme in [`crate::schemes::nonbox`]; this module
//! only reads and writes files.
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
//! The text rule of [`crate::io`] applies (invalid UTF-8 is allowed only in comments).
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
//! [`write_limit_obj`] writes a [limit mesh](crate::schemes::NonBox::limit_mesh_with_normals) with one
//! `vn` line per `v` line (the exact limit normal of that point) and faces `f a//a b//b c//c`.
//!
//! [`read_fcv_obj`] reads it back: the vertices no face uses become the FCVs when they are the
//! last `v` lines and there is exactly one per face (or a `# fcv N` line says so). The same
//! layout in memory is [`FcvNet::to_layout_mesh`].

use super::text::{Lines, parse_error, read_file};
use super::{LoadedMesh, MeshFormat, obj, write_bytes_atomically};
use crate::error::{Error, Result};
use crate::geom::Point;
use crate::mesh::PolyMesh;
use crate::schemes::nonbox::FcvNet;
use std::path::Path;

/// The entries of an FCV side file (see [`parse_fcv_file`]) and its number of lines.
type Entries = (Vec<(usize, Option<Point>)>, usize);

/// Parses an FCV side file: one entry per FCV line (`None` for `*`, the default), with the
/// 1-based line number of each. Errors name the line.
pub fn parse_fcv_file(text: &str, path: &Path) -> Result<Vec<(usize, Option<Point>)>> {
    Ok(parse_entries(text.as_bytes(), path)?.0)
}

/// The entries of an FCV side file, and its number of lines (for messages at its end).
fn parse_entries(bytes: &[u8], path: &Path) -> Result<Entries> {
    let mut out = Vec::new();
    let mut lines = Lines::new(bytes, path);
    while let Some((line, content)) = lines.next_content()? {
        if content == "*" {
            out.push((line, None));
            continue;
        }
        let toks: Vec<&str> = content
            .split(|c: char| c.is_whitespace() || c == ',')
            .filter(|t| !t.is_empty())
            .collect();
        if toks.len() != 3 {
            return Err(parse_error(
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
                parse_error(
                    path,
                    line,
                    format!("'{t}' is not a number (coordinate {} of the FCV)", k + 1),
                )
            })?;
            if !x.is_finite() {
                return Err(parse_error(
                    path,
                    line,
                    format!("coordinate {} of the FCV is not finite ('{t}')", k + 1),
                ));
            }
            p[k] = x;
        }
        out.push((line, Some(p)));
    }
    Ok((out, lines.end_line()))
}

/// The net of `mesh` with the FCVs of an FCV side file (`text`, read from `path`); faces marked
/// `*` get `scale` times their barycentre. Errors name the file line, or say how many lines are
/// missing.
pub fn fcv_net_from_file(mesh: PolyMesh, text: &str, path: &Path, scale: f64) -> Result<FcvNet> {
    fcv_net_from_bytes(mesh, text.as_bytes(), path, scale)
}

/// [`fcv_net_from_file`] on the bytes of the file.
fn fcv_net_from_bytes(mesh: PolyMesh, bytes: &[u8], path: &Path, scale: f64) -> Result<FcvNet> {
    let (entries, end_line) = parse_entries(bytes, path)?;
    let nf = mesh.num_faces();
    if entries.len() > nf {
        return Err(parse_error(
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
        let last = entries.last().map_or(end_line, |e| e.0);
        return Err(parse_error(
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
    fcv_net_from_bytes(mesh, &read_file(path)?, path, scale)
}

/// The FCVs a user asked for: a [layout mesh](FcvNet::to_layout_mesh) keeps its own FCVs;
/// a plain mesh gets `scale` times its face barycentres, replaced face by face by the
/// positions of an FCV side file when `file` is given ([`load_fcv_file`]). This is the
/// library side of the CLI options `--fcv-scale S` and `--fcv-file F`.
pub fn choose_fcv_net(mesh: &PolyMesh, scale: f64, file: Option<&Path>) -> Result<FcvNet> {
    if let Some(net) = FcvNet::from_layout_mesh(mesh) {
        if let Some(path) = file {
            return load_fcv_file(net.mesh, path, scale);
        }
        return Ok(net);
    }
    match file {
        Some(path) => load_fcv_file(mesh.clone(), path, scale),
        None => FcvNet::scaled(mesh.clone(), scale),
    }
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
    write_bytes_atomically(path, fcv_file_string(net).as_bytes())
}

/// The OBJ text of a net with FCVs (layout in the [module](self) documentation).
pub fn fcv_obj_string(net: &FcvNet) -> Result<String> {
    let nf = net.fcv.len();
    let mut buf: Vec<u8> = format!(
        "# fairsub non-box net with face control vertices (FCVs)\n# fcv {nf}: the last {nf} v \
         lines are the FCVs, one per face in face order; no face uses them\n"
    )
    .into_bytes();
    super::write_polygons_to(
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
    write_bytes_atomically(path, fcv_obj_string(net)?.as_bytes())
}

/// Parses OBJ text holding a net with FCVs (see [`read_fcv_obj`]); `path` names the file in
/// messages. Returns the net and notes for the user.
pub fn parse_fcv_obj(text: &str, path: &Path) -> Result<(FcvNet, Vec<String>)> {
    let (mesh, fcv, notes) = parse_obj_fcvs(text, path)?;
    with_fcvs(mesh, fcv, notes)
}

/// The net of `mesh` with the FCVs read (or its face barycentres, with a note).
fn with_fcvs(
    mesh: PolyMesh,
    fcv: Option<Vec<Point>>,
    mut notes: Vec<String>,
) -> Result<(FcvNet, Vec<String>)> {
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
    obj_fcvs_from_bytes(text.as_bytes(), path)
}

/// [`parse_obj_fcvs`] on the bytes of the file.
fn obj_fcvs_from_bytes(
    bytes: &[u8],
    path: &Path,
) -> Result<(PolyMesh, Option<Vec<Point>>, Vec<String>)> {
    let data = obj::parse_obj(bytes, path)?;
    let nf = data.num_faces();
    let total = data.listed.positions.len();
    // The last nf `v` lines, candidates for the FCVs (the mesh drops them as unused).
    let tail: Vec<Point> = data.listed.positions[total.saturating_sub(nf)..].to_vec();
    let LoadedMesh { mesh, warnings } = data.into_mesh(path)?;
    let marker = fcv_marker(bytes);
    let dropped = mesh.dropped_vertices().to_vec();
    let trailing = dropped.len() == nf
        && total >= nf
        && dropped.iter().copied().eq(total - nf..total)
        && tail.iter().all(|p| p.iter().all(|c| c.is_finite()));
    if let Some((line, n)) = marker
        && (n != nf || !trailing)
    {
        return Err(parse_error(
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
        let notes = warnings
            .into_iter()
            .filter(|w| !w.contains("used by no face"))
            .collect();
        return Ok((mesh, Some(tail), notes));
    }
    Ok((mesh, None, warnings))
}

/// The first `# fcv N` comment of an OBJ file: its line and `N`.
fn fcv_marker(bytes: &[u8]) -> Option<(usize, usize)> {
    bytes.split(|&b| b == b'\n').enumerate().find_map(|(i, l)| {
        let rest = l.trim_ascii().strip_prefix(b"#")?.trim_ascii_start();
        let rest = rest.strip_prefix(b"fcv ")?;
        let digits = rest.iter().take_while(|b| b.is_ascii_digit()).count();
        let n = std::str::from_utf8(&rest[..digits]).ok()?.parse().ok()?;
        Some((i + 1, n))
    })
}

/// Reads an OBJ file that may hold a net with FCVs (see [`parse_obj_fcvs`]).
pub fn read_obj_fcvs(path: &Path) -> Result<(PolyMesh, Option<Vec<Point>>, Vec<String>)> {
    obj_fcvs_from_bytes(&read_file(path)?, path)
}

/// Reads an OBJ file holding a net with FCVs (layout in the [module](self) documentation); a
/// plain OBJ net gets its face barycentres as FCVs (with a note). Returns the net and notes.
pub fn read_fcv_obj(path: &Path) -> Result<(FcvNet, Vec<String>)> {
    let (mesh, fcv, notes) = read_obj_fcvs(path)?;
    with_fcvs(mesh, fcv, notes)
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
    write_bytes_atomically(path, limit_obj_string(mesh, normals)?.as_bytes())
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;
    use crate::io::testutil;

    #[crate::unit::test]
    fn side_file_follows_the_text_rule_and_names_lines() {
        let cube = crate::gallery::cube();
        let p = Path::new("c.fcv");
        let net = testutil::assert_text_rule(
            |b| fcv_net_from_bytes(cube.clone(), b, p, 1.0),
            b"# caf\xe9\n*\n*\n0 0 9 # \xff\n*\n*\n*\n",
            b"*\n*\n0 0 \xe99\n*\n*\n*\n",
            "c.fcv:3: invalid UTF-8 at column 5 (byte 0xE9)",
        );
        assert_eq!(net.fcv[2], [0.0, 0.0, 9.0]);
        // Too few lines: at the last line of the file, also when it has no FCV line at all.
        let e = fcv_net_from_bytes(cube.clone(), b"# nothing\n\n", p, 1.0).unwrap_err();
        assert_eq!(
            e.to_string(),
            "c.fcv:2: the file has 0 FCV lines but the net has 6 faces: add one line per missing \
             face (three numbers, or '*' for the default)"
        );
        let e = fcv_net_from_bytes(cube, b"", p, 1.0).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("c.fcv:1: the file has 0 FCV lines"),
            "{e}"
        );
    }

    #[crate::unit::test]
    fn obj_net_with_fcvs_tolerates_invalid_utf8_in_comments() {
        let net = FcvNet::barycentric(crate::gallery::cube());
        let mut text = fcv_obj_string(&net).unwrap().into_bytes();
        text.extend_from_slice(b"# written on a Latin-1 machine: caf\xe9\n");
        let (mesh, fcv, notes) = obj_fcvs_from_bytes(&text, Path::new("n.obj")).unwrap();
        assert_eq!(mesh.num_faces(), 6);
        assert_eq!(fcv.unwrap(), net.fcv);
        assert!(notes.is_empty(), "{notes:?}");
        // In a coordinate the byte is an error with its line (the first `v` line is line 4).
        let mut bad = fcv_obj_string(&net).unwrap().into_bytes();
        let k = bad.windows(3).position(|w| w == b"\nv ").unwrap();
        bad[k + 3] = 0xE9;
        let e = obj_fcvs_from_bytes(&bad, Path::new("n.obj")).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("n.obj:4: invalid UTF-8 at column 3"),
            "{e}"
        );
    }
}
