//! Readers and writers: OBJ, OFF, PLY meshes in and out; BezierView `.bv` and IGES patch output;
//! the FCV side file and OBJ layouts of the non-box schemes.
//!
//! Every reader reports bad input as an [`Error`] that names the file, the line (where the format
//! has lines) and the element, and never panics; every text reader decodes by one rule (the
//! `text` module: invalid UTF-8 only inside comments), which [`read_text`] offers to side files
//! parsed elsewhere. Every writer is atomic: it writes a temporary file beside the target and
//! renames it into place only when everything was written, so a failure never leaves a
//! half-written output (see [`write_atomically`]).
//!
//! | module | holds |
//! | --- | --- |
//! | [`obj`] | Wavefront OBJ reader (hand-written, for line numbers) and writer |
//! | [`off`] | OFF / COFF / NOFF reader and writer |
//! | [`ply`] | PLY reader (ascii, binary little and big endian; header and binary data via `ply-rs-bw`) and writers |
//! | [`bv`] | BezierView `.bv` writer and reader (tensor, triangular patches, polyhedra, groups) |
//! | [`iges`] | IGES 5.3 writer (entity 128 per patch or per CAD face) and a validating reader |
//! | [`step`] | STEP AP214 writer: B-spline faces with B-rep topology (solid or open shell) |
//! | [`usd`] | USD (`.usda`, `.usdc`, `.usdz`) `UsdGeomMesh` reader and writer (via `openusd`) |
//! | [`gltf`] | glTF 2.0 writer (`.glb`, `.gltf`; JSON via `gltf-json`) |
//! | [`scene`] | [`SceneMesh`]: what the USD and glTF writers write of a mesh (normals, texture coordinates, curvature, colours, tags) |
//! | [`table`] | the patch stencil table file (`subdivide --stencils`): writer and validating reader |
//! | [`fcv`] | FCV side files, OBJ nets with FCVs and OBJ limit meshes with normals (non-box schemes) |
//! | `format` | [`MeshFormat`], [`OutputFormat`] and the choice by name or extension |
//! | `text`, `textout` | the text rule and errors of the readers; number formatting and line sinks of the writers |
//! | `atomic`, `polygons`, `groups` | atomic file output (and staged output, committed in groups); checked polygon arrays; numbering names by first appearance |
//!
//! Mesh formats are chosen by [`read_mesh`] from the file extension; output formats by
//! [`OutputFormat::choose`] from a `--format` name or the extension.

mod atomic;
pub mod bv;
pub mod fcv;
mod format;
pub mod gltf;
mod groups;
pub mod iges;
pub mod obj;
pub mod off;
pub mod ply;
mod polygons;
pub mod scene;
pub mod step;
pub mod table;
#[cfg(feature = "unit-tests")]
mod testutil;
mod text;
mod textout;
pub mod usd;

use crate::error::{Error, MeshError, Result};
use crate::geom::Point;
use crate::mesh::PolyMesh;
use std::fs::File;
use std::io::Write;
use std::path::Path;

pub use atomic::{
    Durability, Staged, commit, discard, remove_stale_temps, staged, write_atomically,
};
pub use bv::{
    BvCounts, BvFile, BvGroup, BvPatches, BvPolyhedron, TriPatch, bv_to_string, parse_bv, read_bv,
    write_bv, write_bv_mesh,
};
pub use format::{FORMAT_NAMES, MeshFormat, OutputFormat, SceneFormat};
pub use iges::{iges_to_string, parse_iges, read_iges, write_iges};
pub use scene::SceneMesh;
pub use step::{step_to_string, write_step};
pub use text::read_text;

pub(crate) use atomic::write_bytes_atomically;
pub(crate) use polygons::Polygons;
pub(crate) use text::{io_error, parse_error};

/// A mesh read from a file, with the notes a user should see (nothing in them is an error).
#[derive(Debug, Clone)]
pub struct LoadedMesh {
    /// The validated mesh.
    pub mesh: PolyMesh,
    /// Human-readable notes: dropped unused vertices, ignored statements, and the like.
    pub warnings: Vec<String>,
}

/// Reads a mesh, choosing the format by extension (`.obj`, `.off`, `.ply`, `.usd`, `.usda`,
/// `.usdc`, `.usdz`; case-insensitive).
pub fn read_mesh(path: &Path) -> Result<LoadedMesh> {
    read_mesh_as(path, false)
}

/// Reads a mesh like [`read_mesh`]; with `tolerant` it accepts every net OpenSubdiv accepts
/// (non-manifold edges and vertices, faces that repeat a vertex, unused vertices kept: see
/// [`PolyMesh::from_flat_general`]), for the schemes that refine them (Catmull-Clark, Loop).
/// OBJ tags and texture coordinates and PLY vertex properties are read in both modes.
pub fn read_mesh_as(path: &Path, tolerant: bool) -> Result<LoadedMesh> {
    let ext = format::extension_lowercase(path);
    if let Some("usd" | "usda" | "usdc" | "usdz") = ext.as_deref() {
        return usd::read_usd_with(path, tolerant);
    }
    let reader = match ext.as_deref() {
        Some("obj") => obj::read_obj_with,
        Some("off") => off::read_off_with,
        Some("ply") => ply::read_ply_with,
        other => {
            let what = match other {
                Some(e) => format!("unknown mesh extension '.{e}'"),
                None => "no extension".to_string(),
            };
            return Err(Error::Unsupported(format!(
                "cannot read '{}': {what}; supported mesh formats are .obj, .off, .ply and USD \
                 (.usd, .usda, .usdc, .usdz)",
                path.display()
            )));
        }
    };
    let file = File::open(path).map_err(|e| io_error(path, e))?;
    reader(
        std::io::BufReader::with_capacity(1 << 16, file),
        path,
        tolerant,
    )
}

/// Writes a mesh in the given format (atomically).
pub fn write_mesh(path: &Path, mesh: &PolyMesh, format: MeshFormat) -> Result<()> {
    let polys = match mesh.uniform_face_size() {
        // A refined net: faces of one size, no offsets needed (nor built).
        Some(k) => Polygons::uniform(mesh.positions(), k, mesh.corners())?,
        None => Polygons::new(mesh.positions(), mesh.face_starts(), mesh.corners())?,
    };
    let uv = mesh
        .extras()
        .and_then(|e| e.uv.as_ref())
        .filter(|_| format != MeshFormat::Off);
    let data = mesh
        .extras()
        .and_then(|e| e.vertex_data.as_ref())
        .filter(|_| matches!(format, MeshFormat::PlyAscii | MeshFormat::PlyBinary));
    if let Some(uv) = uv {
        check_uv(uv, mesh.corners().len())?;
    }
    if let Some(d) = data {
        check_vertex_data(d, mesh.num_vertices())?;
    }
    if uv.is_some() || data.is_some() {
        return write_atomically(path, |w| {
            match (format, uv) {
                (MeshFormat::Obj, Some(uv)) => obj::write_obj_uv_to(w, &polys, uv),
                _ => ply::write_ply_extras_to(w, &polys, uv, data, format == MeshFormat::PlyBinary),
            }
            .map_err(|e| io_error(path, e))
        });
    }
    write_checked(path, &polys, format)
}

/// What [`write_mesh`] cannot keep of `mesh` in `format`, as notes for the user (a warning, as
/// for the other lossy outputs: the geometry is written, the data named here is not): texture
/// coordinates in OFF, per-vertex data (PLY properties) in OBJ and OFF.
pub fn lost_in(mesh: &PolyMesh, format: MeshFormat) -> Vec<String> {
    let mut notes = Vec::new();
    let data = mesh.extras().and_then(|e| e.vertex_data.as_ref());
    if let (MeshFormat::Obj | MeshFormat::Off, Some(d)) = (format, data) {
        notes.push(format!(
            "{} cannot hold the per-vertex properties ({}): they are dropped (write .ply to keep \
             them)",
            if format == MeshFormat::Obj {
                "OBJ"
            } else {
                "OFF"
            },
            d.names.join(", ")
        ));
    }
    if let (MeshFormat::Off, Some(uv)) = (format, mesh.extras().and_then(|e| e.uv.as_ref())) {
        notes.push(format!(
            "OFF cannot hold texture coordinates: the net's {} face-varying values are dropped \
             (write .obj or .ply to keep them)",
            uv.values.len()
        ));
    }
    notes
}

/// Checks per-vertex data before it is written: one row per vertex, finite values.
fn check_vertex_data(d: &crate::mesh::VertexData, vertices: usize) -> Result<()> {
    let bad = |what: String| Err(crate::error::Error::InvalidArgument(what));
    if d.kinds.len() != d.width() || d.values.len() != d.width() * vertices {
        return bad(format!(
            "per-vertex data: {} values of {} channels for {vertices} vertices",
            d.values.len(),
            d.width()
        ));
    }
    if let Some(i) = d.values.iter().position(|x| !x.is_finite()) {
        return bad(format!(
            "per-vertex property '{}' of vertex {} is not finite",
            d.names[i % d.width()],
            i / d.width()
        ));
    }
    Ok(())
}

/// Checks face-varying data before it is written: one value per corner, indices in range,
/// finite values.
fn check_uv(uv: &crate::mesh::FaceVarying, corners: usize) -> Result<()> {
    let bad = |what: String| Err(crate::error::Error::InvalidArgument(what));
    if uv.corners.len() != corners {
        return bad(format!(
            "texture coordinates: {} corner values for {corners} face corners",
            uv.corners.len()
        ));
    }
    if let Some(c) = uv
        .corners
        .iter()
        .position(|&i| i as usize >= uv.values.len())
    {
        return bad(format!(
            "texture coordinates: face corner {c} names a missing value"
        ));
    }
    if let Some(i) = uv
        .values
        .iter()
        .position(|t| !t[0].is_finite() || !t[1].is_finite())
    {
        return bad(format!("texture coordinate {} is not finite", i + 1));
    }
    Ok(())
}

/// Writes plain polygons (atomically): face `f` has corners
/// `corners[face_start[f]..face_start[f + 1]]`, indices into `positions`. Nothing is required of
/// the connectivity (a tessellation may be written without building a [`PolyMesh`]), but the
/// arrays must be consistent and coordinates finite; that is checked before any file is created.
pub fn write_polygons(
    path: &Path,
    positions: &[Point],
    face_start: &[u32],
    corners: &[u32],
    format: MeshFormat,
) -> Result<()> {
    let polys = Polygons::new(positions, face_start, corners)?;
    write_checked(path, &polys, format)
}

/// Writes checked polygons (atomically).
fn write_checked(path: &Path, polys: &Polygons<'_>, format: MeshFormat) -> Result<()> {
    write_atomically(path, |w| {
        encode_polygons(w, polys, format).map_err(|e| io_error(path, e))
    })
}

/// Writes plain polygons into any writer (no atomicity: the caller owns the sink). Same checks
/// as [`write_polygons`].
pub fn write_polygons_to(
    w: &mut dyn Write,
    positions: &[Point],
    face_start: &[u32],
    corners: &[u32],
    format: MeshFormat,
) -> Result<()> {
    let polys = Polygons::new(positions, face_start, corners)?;
    encode_polygons(w, &polys, format).map_err(|e| io_error(Path::new("<output>"), e))
}

/// Encodes checked polygons in `format`.
fn encode_polygons(w: &mut dyn Write, p: &Polygons<'_>, format: MeshFormat) -> std::io::Result<()> {
    match format {
        MeshFormat::Obj => obj::write_obj_to(w, p),
        MeshFormat::Off => off::write_off_to(w, p),
        MeshFormat::PlyAscii => ply::write_ply_ascii_to(w, p),
        MeshFormat::PlyBinary => ply::write_ply_binary_to(w, p),
    }
}

/// Where a mesh reader found each face and vertex (1-based file lines; `None` where the format
/// has no lines, as binary PLY), and how its file numbers them (appended to messages).
pub(crate) struct FileLines<'a> {
    pub face: &'a dyn Fn(usize) -> Option<usize>,
    pub vertex: &'a dyn Fn(usize) -> Option<usize>,
    pub note: &'a str,
}

/// The end of every mesh reader: validates the flat arrays as a [`PolyMesh`] and appends the
/// warning about vertices no face uses to `warnings`. A validation error is reported at the file
/// line of the face or vertex it names, or, where that line is not known, with the file name.
/// With `tolerant` the mesh is built by [`PolyMesh::from_flat_general`] (see [`read_mesh_as`])
/// and a note names its first non-manifold element.
pub(crate) fn finish_mesh(
    path: &Path,
    positions: Vec<Point>,
    face_start: Vec<u32>,
    corners: Vec<u32>,
    at: &FileLines<'_>,
    warnings: &mut Vec<String>,
    tolerant: bool,
) -> Result<PolyMesh> {
    if tolerant {
        let mesh = PolyMesh::from_flat_general(positions, face_start, corners)
            .map_err(|e| locate_mesh_error(path, e, at))?;
        if let Err(e) = mesh.require_manifold("fairsub's other schemes need") {
            let msg = e.to_string();
            let what = msg
                .split(", but ")
                .nth(1)
                .and_then(|r| r.split(';').next())
                .unwrap_or("");
            warnings.push(format!(
                "the net is not manifold ({what}); it is refined as OpenSubdiv refines such \
                 nets (non-manifold edges and vertices become infinitely sharp)"
            ));
        }
        return Ok(mesh);
    }
    let mesh = PolyMesh::from_flat(positions, face_start, corners)
        .map_err(|e| locate_mesh_error(path, e, at))?;
    let d = mesh.dropped_vertices();
    if let Some(&first) = d.first() {
        let on_line = (at.vertex)(first)
            .map(|l| format!(" on line {l}"))
            .unwrap_or_default();
        warnings.push(format!(
            "{} vertices are used by no face and were dropped (first: vertex {first}{on_line}; \
             counted from 0)",
            d.len()
        ));
    }
    Ok(mesh)
}

/// The flat arrays of a mesh as a reader collected them, with the file line of every vertex
/// and face (the text readers: OBJ, OFF).
pub(crate) struct ListedMesh {
    pub positions: Vec<Point>,
    pub face_start: Vec<u32>,
    pub corners: Vec<u32>,
    /// The 1-based line of each vertex.
    pub vertex_line: Vec<u32>,
    /// The 1-based line of each face.
    pub face_line: Vec<u32>,
}

/// [`finish_mesh`] for a text reader that knows the line of every vertex and face; `note` says
/// how the file numbers them (appended to messages).
pub(crate) fn finish_listed(
    path: &Path,
    listed: ListedMesh,
    note: &str,
    warnings: &mut Vec<String>,
    tolerant: bool,
) -> Result<PolyMesh> {
    let ListedMesh {
        positions,
        face_start,
        corners,
        vertex_line,
        face_line,
    } = listed;
    let fl = |f: usize| face_line.get(f).map(|&l| l as usize);
    let vl = |v: usize| vertex_line.get(v).map(|&l| l as usize);
    let at = FileLines {
        face: &fl,
        vertex: &vl,
        note,
    };
    finish_mesh(
        path, positions, face_start, corners, &at, warnings, tolerant,
    )
}

/// Turns a validation error of [`PolyMesh::from_flat`] into an error of the file: at the line
/// of the face or vertex it names when known, else naming the file only.
fn locate_mesh_error(path: &Path, err: Error, at: &FileLines<'_>) -> Error {
    let Error::Mesh(me) = err else { return err };
    let line = match &me {
        MeshError::Empty => None,
        MeshError::FaceTooSmall { face, .. }
        | MeshError::RepeatedVertex { face, .. }
        | MeshError::IndexOutOfRange { face, .. } => (at.face)(*face),
        MeshError::NonFiniteCoordinate { vertex } | MeshError::NonManifoldVertex { vertex, .. } => {
            (at.vertex)(*vertex)
        }
        MeshError::NonManifoldEdge { faces, .. } => faces.last().and_then(|&f| (at.face)(f)),
        MeshError::InconsistentOrientation { faces, .. } => (at.face)(faces[1]),
    };
    // The general reader takes these nets: say which commands do (issue 20's contract).
    let hint = match &me {
        MeshError::RepeatedVertex { .. }
        | MeshError::NonManifoldEdge { .. }
        | MeshError::InconsistentOrientation { .. }
        | MeshError::NonManifoldVertex { .. } => {
            let names = crate::schemes::registry()
                .names_taking(crate::schemes::descriptor::ParamKind::SharpFeatures)
                .join(" and ");
            format!(
                "; this command needs a manifold net (only {names} refine such nets, with \
                 subdivide --levels; info reads them)"
            )
        }
        _ => String::new(),
    };
    let msg = format!("invalid mesh: {me}{hint}{}", at.note);
    match line {
        Some(line) => parse_error(path, line, msg),
        None => text::file_error(path, msg),
    }
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    #[crate::unit::test]
    fn invalid_polygons_create_no_file() {
        let dir = std::env::temp_dir().join(format!(
            "fairsub-io-poly-{}-{}",
            std::process::id(),
            atomic::unique_number()
        ));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join("bad.obj");
        let pos = [[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        for fmt in [MeshFormat::Obj, MeshFormat::PlyBinary] {
            let e = write_polygons(&p, &pos, &[0, 3], &[0, 1, 7], fmt).unwrap_err();
            assert!(e.to_string().contains("face 0 refers to vertex 7"), "{e}");
        }
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0);
        std::fs::remove_dir_all(dir).unwrap();
    }

    #[crate::unit::test]
    fn every_writer_roundtrips_exactly() {
        let p = testutil::polygons();
        let name = Path::new("w");
        for format in [
            MeshFormat::Obj,
            MeshFormat::Off,
            MeshFormat::PlyAscii,
            MeshFormat::PlyBinary,
        ] {
            let mut buf = Vec::new();
            encode_polygons(&mut buf, &p, format).unwrap();
            let m = match format {
                MeshFormat::Obj => obj::read_obj_from(&buf[..], name),
                MeshFormat::Off => off::read_off_from(&buf[..], name),
                MeshFormat::PlyAscii | MeshFormat::PlyBinary => ply::read_ply_from(&buf[..], name),
            };
            testutil::assert_is_fixture(&m.unwrap());
        }
    }

    #[crate::unit::test]
    fn read_mesh_rejects_unknown_extension() {
        let e = read_mesh(Path::new("model.stl")).unwrap_err();
        let m = e.to_string();
        assert!(
            m.contains("'.stl'") && m.contains(".obj") && m.contains(".off") && m.contains(".ply"),
            "{m}"
        );
        assert!(matches!(e, Error::Unsupported(_)));
    }

    #[crate::unit::test]
    fn read_mesh_missing_file_names_it() {
        let e = read_mesh(Path::new("/nonexistent/dir/model.OBJ")).unwrap_err();
        match e {
            Error::Io { path, .. } => assert_eq!(path, Path::new("/nonexistent/dir/model.OBJ")),
            other => panic!("{other:?}"),
        }
    }

    #[crate::unit::test]
    fn mesh_errors_without_a_line_name_the_file() {
        let none = |_: usize| None;
        let at = FileLines {
            face: &none,
            vertex: &none,
            note: " (counted from 0)",
        };
        let mut w = Vec::new();
        let e = finish_mesh(
            Path::new("b.ply"),
            vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
            vec![0, 3, 6],
            vec![0, 1, 2, 0, 1, 2],
            &at,
            &mut w,
            false,
        )
        .unwrap_err();
        assert!(
            e.to_string().starts_with("b.ply: invalid mesh: ")
                && e.to_string().ends_with(" (counted from 0)"),
            "{e}"
        );
    }
}
