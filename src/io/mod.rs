//! Readers and writers: OBJ, OFF, PLY meshes in and out; BezierView `.bv` and IGES patch output.
//!
//! Every reader reports bad input as an [`Error`] that names the file, the line (where the format
//! has lines) and the element, and never panics. Every writer is atomic: it writes a temporary
//! file beside the target and renames it into place only when everything was written, so a
//! failure never leaves a half-written output (see [`write_atomically`]).
//!
//! | module | holds |
//! | --- | --- |
//! | [`obj`] | Wavefront OBJ reader (hand-written, for line numbers) and writer |
//! | [`off`] | OFF / COFF / NOFF reader and writer |
//! | [`ply`] | PLY reader (ascii, binary little and big endian, via `ply-rs-bw`) and writer |
//! | [`bv`] | BezierView `.bv` writer and reader (tensor, triangular patches, polyhedra, groups) |
//! | [`iges`] | IGES 5.3 writer (entity 128 per patch) and a validating reader |
//!
//! Mesh formats are chosen by [`read_mesh`] from the file extension; output formats by
//! [`OutputFormat::choose`] from a `--format` name or the extension.

pub mod bv;
pub mod iges;
pub mod obj;
pub mod off;
pub mod ply;

use crate::error::{Error, MeshError, Result};
use crate::geom::Point;
use crate::mesh::PolyMesh;
use std::fs::File;
use std::io::{BufWriter, Read, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

pub use bv::{
    BvFile, BvGroup, BvPolyhedron, TriPatch, bv_to_string, parse_bv, read_bv, write_bv,
    write_bv_mesh,
};
pub use iges::{iges_to_string, parse_iges, read_iges, write_iges};

/// A mesh read from a file, with the notes a user should see (nothing in them is an error).
#[derive(Debug, Clone)]
pub struct LoadedMesh {
    /// The validated mesh.
    pub mesh: PolyMesh,
    /// Human-readable notes: dropped unused vertices, ignored statements, and the like.
    pub warnings: Vec<String>,
}

/// The mesh file formats fairsub writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MeshFormat {
    /// Wavefront OBJ (`v` and `f` lines, 1-based indices).
    Obj,
    /// Geomview OFF (ascii).
    Off,
    /// PLY, ascii encoding.
    PlyAscii,
    /// PLY, binary little endian (double coordinates, `list uchar int` faces).
    PlyBinary,
}

impl MeshFormat {
    /// The usual file extension (without the dot).
    pub fn extension(self) -> &'static str {
        match self {
            MeshFormat::Obj => "obj",
            MeshFormat::Off => "off",
            MeshFormat::PlyAscii | MeshFormat::PlyBinary => "ply",
        }
    }
}

/// What an output file holds: a mesh (tessellation, refined net) or exact patches.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OutputFormat {
    /// A polygon mesh in one of the [`MeshFormat`]s.
    Mesh(MeshFormat),
    /// BezierView `.bv` patches.
    Bv,
    /// IGES 5.3, one entity 128 per patch.
    Iges,
}

/// The `--format` names [`OutputFormat::choose`] accepts, for help texts and errors.
pub const FORMAT_NAMES: &str = "obj, off, ply (binary), ply-ascii, ply-binary, bv, igs / iges";

impl OutputFormat {
    /// Chooses the output format: by `format` (a `--format` name, case-insensitive) when given,
    /// else by the extension of `path` (`.obj .off .ply .bv .igs .iges`). PLY is binary unless
    /// `ply-ascii` is asked for. Unknown names or extensions give an error listing the choices.
    pub fn choose(path: &Path, format: Option<&str>) -> Result<OutputFormat> {
        if let Some(name) = format {
            return match name.trim().to_ascii_lowercase().as_str() {
                "obj" => Ok(OutputFormat::Mesh(MeshFormat::Obj)),
                "off" => Ok(OutputFormat::Mesh(MeshFormat::Off)),
                "ply" | "ply-binary" | "ply_binary" => {
                    Ok(OutputFormat::Mesh(MeshFormat::PlyBinary))
                }
                "ply-ascii" | "ply_ascii" => Ok(OutputFormat::Mesh(MeshFormat::PlyAscii)),
                "bv" => Ok(OutputFormat::Bv),
                "igs" | "iges" => Ok(OutputFormat::Iges),
                _ => Err(Error::InvalidArgument(format!(
                    "unknown output format '{name}' (choose one of: {FORMAT_NAMES})"
                ))),
            };
        }
        match extension_lowercase(path).as_deref() {
            Some("obj") => Ok(OutputFormat::Mesh(MeshFormat::Obj)),
            Some("off") => Ok(OutputFormat::Mesh(MeshFormat::Off)),
            Some("ply") => Ok(OutputFormat::Mesh(MeshFormat::PlyBinary)),
            Some("bv") => Ok(OutputFormat::Bv),
            Some("igs") | Some("iges") => Ok(OutputFormat::Iges),
            Some(ext) => Err(Error::InvalidArgument(format!(
                "cannot tell the output format of '{}' from its extension '.{ext}': use .obj, .off, \
                 .ply, .bv, .igs or .iges, or give --format ({FORMAT_NAMES})",
                path.display()
            ))),
            None => Err(Error::InvalidArgument(format!(
                "'{}' has no extension to tell the output format: use .obj, .off, .ply, .bv, .igs \
                 or .iges, or give --format ({FORMAT_NAMES})",
                path.display()
            ))),
        }
    }
}

/// The extension of `path`, lower-cased, when it has one that is valid UTF-8.
fn extension_lowercase(path: &Path) -> Option<String> {
    path.extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase())
}

/// Reads a mesh, choosing the format by extension (`.obj`, `.off`, `.ply`, case-insensitive).
pub fn read_mesh(path: &Path) -> Result<LoadedMesh> {
    let ext = extension_lowercase(path);
    let reader = match ext.as_deref() {
        Some("obj") => obj::read_obj_from,
        Some("off") => off::read_off_from,
        Some("ply") => ply::read_ply_from,
        other => {
            let what = match other {
                Some(e) => format!("unknown mesh extension '.{e}'"),
                None => "no extension".to_string(),
            };
            return Err(Error::Unsupported(format!(
                "cannot read '{}': {what}; supported mesh formats are .obj, .off and .ply",
                path.display()
            )));
        }
    };
    let file = File::open(path).map_err(|e| io_error(path, e))?;
    reader(std::io::BufReader::with_capacity(1 << 16, file), path)
}

/// Writes a mesh in the given format (atomically).
pub fn write_mesh(path: &Path, mesh: &PolyMesh, format: MeshFormat) -> Result<()> {
    let polys = match mesh.uniform_face_size() {
        // A refined net: faces of one size, no offsets needed (nor built).
        Some(k) => Polygons::uniform(mesh.positions(), k, mesh.corners())?,
        None => Polygons::new(mesh.positions(), mesh.face_starts(), mesh.corners())?,
    };
    write_polygons_checked(path, &polys, format)
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
    write_polygons_checked(path, &polys, format)
}

/// Writes checked polygons (atomically).
fn write_polygons_checked(path: &Path, polys: &Polygons<'_>, format: MeshFormat) -> Result<()> {
    write_atomically(path, |w| {
        let r = match format {
            MeshFormat::Obj => obj::write_obj_to(w, polys),
            MeshFormat::Off => off::write_off_to(w, polys),
            MeshFormat::PlyAscii => ply::write_ply_ascii_to(w, polys),
            MeshFormat::PlyBinary => ply::write_ply_binary_to(w, polys),
        };
        r.map_err(|e| io_error(path, e))
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
    let r = match format {
        MeshFormat::Obj => obj::write_obj_to(w, &polys),
        MeshFormat::Off => off::write_off_to(w, &polys),
        MeshFormat::PlyAscii => ply::write_ply_ascii_to(w, &polys),
        MeshFormat::PlyBinary => ply::write_ply_binary_to(w, &polys),
    };
    r.map_err(|e| io_error(Path::new("<output>"), e))
}

/// Checked flat polygon arrays, the common input of the mesh writers.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Polygons<'a> {
    pub positions: &'a [Point],
    /// `num_faces + 1` offsets (or empty for no faces, or when `uniform != 0`).
    pub face_start: &'a [u32],
    pub corners: &'a [u32],
    /// The common face size when the offsets are implicit, else 0.
    pub uniform: usize,
    /// Largest face size.
    pub max_face: usize,
}

impl<'a> Polygons<'a> {
    /// Faces of `size` corners each (implicit offsets), from a mesh whose connectivity is
    /// valid by construction; only the coordinates are checked.
    pub fn uniform(positions: &'a [Point], size: usize, corners: &'a [u32]) -> Result<Self> {
        Self::check_finite(positions)?;
        debug_assert!(size >= 3 && corners.len().is_multiple_of(size));
        Ok(Polygons {
            positions,
            face_start: &[],
            corners,
            uniform: size,
            max_face: size,
        })
    }

    /// Fails when a coordinate is not finite, naming the first such vertex.
    fn check_finite(positions: &[Point]) -> Result<()> {
        // Checked in parallel: a refined net has millions of points.
        match first_index(positions.len(), |v| {
            !positions[v].iter().all(|c| c.is_finite())
        }) {
            Some(v) => Err(Error::InvalidArgument(format!(
                "cannot write vertex {v}: its coordinates {:?} are not all finite",
                positions[v]
            ))),
            None => Ok(()),
        }
    }

    /// Checks offsets, indices and coordinates; errors name the face or vertex.
    pub fn new(
        positions: &'a [Point],
        face_start: &'a [u32],
        corners: &'a [u32],
    ) -> Result<Polygons<'a>> {
        use rayon::prelude::*;
        Self::check_finite(positions)?;
        let mut max_face = 0;
        if !face_start.is_empty() {
            if face_start[0] != 0 {
                return Err(Error::InvalidArgument(format!(
                    "face offsets must start at 0, not {}",
                    face_start[0]
                )));
            }
            let last = face_start[face_start.len() - 1] as usize;
            if last != corners.len() {
                return Err(Error::InvalidArgument(format!(
                    "face offsets end at {last} but there are {} corners",
                    corners.len()
                )));
            }
            let nf = face_start.len() - 1;
            if let Some(f) = first_index(nf, |f| {
                face_start[f + 1] < face_start[f] || face_start[f + 1] - face_start[f] < 3
            }) {
                let pair = &face_start[f..f + 2];
                if pair[1] < pair[0] {
                    return Err(Error::InvalidArgument(format!(
                        "face offsets decrease at face {f} ({} then {})",
                        pair[0], pair[1]
                    )));
                }
                let n = pair[1] - pair[0];
                return Err(Error::InvalidArgument(format!(
                    "face {f} has {n} corners; a face needs at least 3"
                )));
            }
            max_face = (0..nf)
                .into_par_iter()
                .with_min_len(CHECK_CHUNK)
                .map(|f| (face_start[f + 1] - face_start[f]) as usize)
                .max()
                .unwrap_or(0);
        } else if !corners.is_empty() {
            return Err(Error::InvalidArgument(
                "corners given without face offsets".to_string(),
            ));
        }
        if let Some(c) = first_index(corners.len(), |c| corners[c] as usize >= positions.len()) {
            let f = face_start.partition_point(|&s| s as usize <= c) - 1;
            return Err(Error::InvalidArgument(format!(
                "face {f} refers to vertex {}, but there are only {} vertices",
                corners[c],
                positions.len()
            )));
        }
        Ok(Polygons {
            positions,
            face_start,
            corners,
            uniform: 0,
            max_face,
        })
    }

    /// Number of faces.
    pub fn num_faces(&self) -> usize {
        self.corners
            .len()
            .checked_div(self.uniform)
            .unwrap_or_else(|| self.face_start.len().saturating_sub(1))
    }

    /// Offset of face `f`'s first corner (`f = num_faces` gives the end).
    pub fn face_offset(&self, f: usize) -> usize {
        if self.uniform != 0 {
            self.uniform * f
        } else {
            self.face_start[f] as usize
        }
    }

    /// Corners of face `f`.
    pub fn face(&self, f: usize) -> &'a [u32] {
        &self.corners[self.face_offset(f)..self.face_offset(f + 1)]
    }
}

/// Indices per parallel task in [`first_index`].
const CHECK_CHUNK: usize = 1 << 16;

/// The first index in `0..n` for which `bad` holds: blocks of indices are scanned in parallel,
/// each sequentially (rayon's per-item `position_first` is far slower on tens of millions).
fn first_index(n: usize, bad: impl Fn(usize) -> bool + Sync) -> Option<usize> {
    use rayon::prelude::*;
    (0..n.div_ceil(CHECK_CHUNK))
        .into_par_iter()
        .find_map_first(|c| (c * CHECK_CHUNK..((c + 1) * CHECK_CHUNK).min(n)).find(|&i| bad(i)))
}

static TEMP_COUNTER: AtomicU64 = AtomicU64::new(0);

/// Removes the temporary file unless the write was committed (also on panic).
struct TempGuard {
    path: PathBuf,
    armed: bool,
}

impl Drop for TempGuard {
    fn drop(&mut self) {
        if self.armed {
            let _ = std::fs::remove_file(&self.path);
        }
    }
}

/// Writes `path` atomically: `write` fills a buffered temporary file in the same directory,
/// which is flushed, synced and renamed over `path` only when `write` succeeded. On any error
/// (from `write`, from flushing, or from the rename) the temporary file is removed and `path` is
/// left as it was, so no output is ever half-written.
pub fn write_atomically<F>(path: &Path, write: F) -> Result<()>
where
    F: FnOnce(&mut dyn Write) -> Result<()>,
{
    let name = path.file_name().ok_or_else(|| {
        Error::InvalidArgument(format!("'{}' does not name a file", path.display()))
    })?;
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let mut tmp_name = std::ffi::OsString::from(".");
    tmp_name.push(name);
    tmp_name.push(format!(
        ".tmp-{}-{}",
        std::process::id(),
        TEMP_COUNTER.fetch_add(1, Ordering::Relaxed)
    ));
    let tmp = dir.join(tmp_name);
    let file = std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&tmp)
        .map_err(|e| io_error(path, e))?;
    let mut guard = TempGuard {
        path: tmp.clone(),
        armed: true,
    };
    let mut w = BufWriter::with_capacity(1 << 20, file);
    write(&mut w)?;
    let file = w.into_inner().map_err(|e| io_error(path, e.into_error()))?;
    file.sync_all().map_err(|e| io_error(path, e))?;
    drop(file);
    std::fs::rename(&tmp, path).map_err(|e| io_error(path, e))?;
    guard.armed = false;
    Ok(())
}

/// `Error::Io` for `path`.
pub(crate) fn io_error(path: &Path, source: std::io::Error) -> Error {
    Error::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// `Error::Parse` for `path` at 1-based `line`.
pub(crate) fn parse_error(path: &Path, line: usize, msg: impl Into<String>) -> Error {
    Error::Parse {
        path: path.to_path_buf(),
        line,
        msg: msg.into(),
    }
}

/// Reads all of `reader` into a string; invalid UTF-8 is replaced (only numbers and keywords,
/// which are ASCII, are interpreted).
pub(crate) fn read_to_string_lossy<R: Read>(mut reader: R, path: &Path) -> Result<String> {
    let mut bytes = Vec::new();
    reader
        .read_to_end(&mut bytes)
        .map_err(|e| io_error(path, e))?;
    Ok(match String::from_utf8(bytes) {
        Ok(s) => s,
        Err(e) => String::from_utf8_lossy(e.as_bytes()).into_owned(),
    })
}

/// Turns a validation error of [`PolyMesh::new`] into a parse error at the file line of the face
/// or vertex it names, when those lines are known. `note` is appended (e.g. how the file numbers
/// vertices).
pub(crate) fn locate_mesh_error(
    path: &Path,
    err: Error,
    face_line: &dyn Fn(usize) -> Option<usize>,
    vertex_line: &dyn Fn(usize) -> Option<usize>,
    note: &str,
) -> Error {
    let Error::Mesh(me) = err else { return err };
    let line = match &me {
        MeshError::Empty => None,
        MeshError::FaceTooSmall { face, .. }
        | MeshError::RepeatedVertex { face, .. }
        | MeshError::IndexOutOfRange { face, .. } => face_line(*face),
        MeshError::NonFiniteCoordinate { vertex } | MeshError::NonManifoldVertex { vertex, .. } => {
            vertex_line(*vertex)
        }
        MeshError::NonManifoldEdge { faces, .. } => faces.last().and_then(|&f| face_line(f)),
        MeshError::InconsistentOrientation { faces, .. } => face_line(faces[1]),
    };
    match line {
        Some(line) => parse_error(path, line, format!("invalid mesh: {me}{note}")),
        None => Error::Mesh(me),
    }
}

/// The warning about vertices no face uses, or `None`.
pub(crate) fn dropped_warning(
    mesh: &PolyMesh,
    vertex_line: &dyn Fn(usize) -> Option<usize>,
    numbering: &str,
) -> Option<String> {
    let d = mesh.dropped_vertices();
    let first = *d.first()?;
    let at = vertex_line(first)
        .map(|l| format!(" on line {l}"))
        .unwrap_or_default();
    Some(format!(
        "{} vertices are used by no face and were dropped (first: vertex {first}{at}; {numbering})",
        d.len()
    ))
}

/// Appends `x` to `s` so that it reads back as exactly the same `f64` (shortest round-trip form;
/// exponent notation for very large or small magnitudes).
pub(crate) fn push_f64(s: &mut String, x: f64) {
    use std::fmt::Write as _;
    let a = x.abs();
    if a == 0.0 || (1e-5..1e16).contains(&a) {
        let _ = write!(s, "{x}");
    } else {
        let _ = write!(s, "{x:e}");
    }
}

/// Appends `x y z` of a point.
pub(crate) fn push_point(s: &mut String, p: Point) {
    push_f64(s, p[0]);
    s.push(' ');
    push_f64(s, p[1]);
    s.push(' ');
    push_f64(s, p[2]);
}

/// A text sink that formats into a string and hands it to the writer in large chunks, so that
/// many small lines cost no dynamic calls each.
pub(crate) struct ChunkedText<'w> {
    pub buf: String,
    w: &'w mut dyn Write,
}

impl<'w> ChunkedText<'w> {
    const CHUNK: usize = 1 << 16;

    pub fn new(w: &'w mut dyn Write) -> Self {
        ChunkedText {
            buf: String::with_capacity(Self::CHUNK + 256),
            w,
        }
    }

    /// Flushes the buffer when it is full; call after each line.
    #[inline]
    pub fn maybe_flush(&mut self) -> std::io::Result<()> {
        if self.buf.len() >= Self::CHUNK {
            self.w.write_all(self.buf.as_bytes())?;
            self.buf.clear();
        }
        Ok(())
    }

    /// Writes what is left.
    pub fn finish(mut self) -> std::io::Result<()> {
        self.w.write_all(self.buf.as_bytes())?;
        self.buf.clear();
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tmpdir(tag: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!(
            "fairsub-io-{tag}-{}-{}",
            std::process::id(),
            TEMP_COUNTER.fetch_add(1, Ordering::Relaxed)
        ));
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    fn entries(dir: &Path) -> Vec<String> {
        let mut v: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }

    #[test]
    fn atomic_write_commits_on_success() {
        let dir = tmpdir("ok");
        let p = dir.join("a.txt");
        write_atomically(&p, |w| {
            w.write_all(b"hello")
                .map_err(|e| io_error(Path::new("x"), e))
        })
        .unwrap();
        assert_eq!(std::fs::read(&p).unwrap(), b"hello");
        assert_eq!(entries(&dir), vec!["a.txt".to_string()]);
        std::fs::remove_dir_all(dir).unwrap();
    }

    #[test]
    fn atomic_write_leaves_nothing_on_error() {
        let dir = tmpdir("err");
        let p = dir.join("b.obj");
        let r = write_atomically(&p, |w| {
            w.write_all(&[b'x'; 3_000_000]).unwrap(); // more than the buffer: reaches the file
            Err(Error::InvalidArgument("failing closure".into()))
        });
        assert!(matches!(r, Err(Error::InvalidArgument(ref m)) if m == "failing closure"));
        assert!(entries(&dir).is_empty(), "left: {:?}", entries(&dir));
        std::fs::remove_dir_all(dir).unwrap();
    }

    #[test]
    fn atomic_write_keeps_old_file_on_error() {
        let dir = tmpdir("keep");
        let p = dir.join("c.off");
        std::fs::write(&p, b"old contents").unwrap();
        let r = write_atomically(&p, |w| {
            w.write_all(b"new").unwrap();
            Err(Error::Unsupported("no".into()))
        });
        assert!(r.is_err());
        assert_eq!(std::fs::read(&p).unwrap(), b"old contents");
        assert_eq!(entries(&dir), vec!["c.off".to_string()]);
        std::fs::remove_dir_all(dir).unwrap();
    }

    #[test]
    fn atomic_write_into_missing_directory_is_an_io_error() {
        let dir = tmpdir("missing");
        let p = dir.join("no/such/dir/d.ply");
        let r = write_atomically(&p, |_| Ok(()));
        match r {
            Err(Error::Io { path, .. }) => assert_eq!(path, p),
            other => panic!("expected Io error, got {other:?}"),
        }
        std::fs::remove_dir_all(dir).unwrap();
    }

    #[test]
    fn invalid_polygons_create_no_file() {
        let dir = tmpdir("poly");
        let p = dir.join("bad.obj");
        let pos = [[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let e = write_polygons(&p, &pos, &[0, 3], &[0, 1, 7], MeshFormat::Obj).unwrap_err();
        assert!(e.to_string().contains("face 0 refers to vertex 7"), "{e}");
        let e = write_polygons(&p, &pos, &[0, 2], &[0, 1], MeshFormat::Obj).unwrap_err();
        assert!(e.to_string().contains("face 0 has 2 corners"), "{e}");
        let bad = [[0.0; 3], [f64::NAN, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let e = write_polygons(&p, &bad, &[0, 3], &[0, 1, 2], MeshFormat::PlyBinary).unwrap_err();
        assert!(e.to_string().contains("vertex 1"), "{e}");
        let e = write_polygons(&p, &pos, &[0, 3], &[0, 1], MeshFormat::Off).unwrap_err();
        assert!(e.to_string().contains("3 but there are 2 corners"), "{e}");
        assert!(entries(&dir).is_empty());
        std::fs::remove_dir_all(dir).unwrap();
    }

    #[test]
    fn output_format_by_name_and_extension() {
        use MeshFormat::*;
        let p = Path::new("out.PLY");
        assert_eq!(
            OutputFormat::choose(p, None).unwrap(),
            OutputFormat::Mesh(PlyBinary)
        );
        assert_eq!(
            OutputFormat::choose(p, Some("ply-ascii")).unwrap(),
            OutputFormat::Mesh(PlyAscii)
        );
        assert_eq!(
            OutputFormat::choose(Path::new("x.obj"), None).unwrap(),
            OutputFormat::Mesh(Obj)
        );
        assert_eq!(
            OutputFormat::choose(Path::new("x.Off"), None).unwrap(),
            OutputFormat::Mesh(Off)
        );
        assert_eq!(
            OutputFormat::choose(Path::new("x.bv"), None).unwrap(),
            OutputFormat::Bv
        );
        assert_eq!(
            OutputFormat::choose(Path::new("x.igs"), None).unwrap(),
            OutputFormat::Iges
        );
        assert_eq!(
            OutputFormat::choose(Path::new("x.IGES"), None).unwrap(),
            OutputFormat::Iges
        );
        assert_eq!(
            OutputFormat::choose(Path::new("x.txt"), Some("IGES")).unwrap(),
            OutputFormat::Iges
        );
        assert_eq!(
            OutputFormat::choose(Path::new("x"), Some("bv")).unwrap(),
            OutputFormat::Bv
        );
        let e = OutputFormat::choose(Path::new("x.stl"), None).unwrap_err();
        let m = e.to_string();
        assert!(
            m.contains(".stl") && m.contains(".iges") && m.contains("ply-ascii"),
            "{m}"
        );
        let e = OutputFormat::choose(Path::new("x.obj"), Some("stl")).unwrap_err();
        assert!(e.to_string().contains("'stl'"), "{e}");
        assert!(OutputFormat::choose(Path::new("noext"), None).is_err());
    }

    #[test]
    fn read_mesh_rejects_unknown_extension() {
        let e = read_mesh(Path::new("model.stl")).unwrap_err();
        let m = e.to_string();
        assert!(
            m.contains("'.stl'") && m.contains(".obj") && m.contains(".off") && m.contains(".ply"),
            "{m}"
        );
        assert!(matches!(e, Error::Unsupported(_)));
    }

    #[test]
    fn read_mesh_missing_file_names_it() {
        let e = read_mesh(Path::new("/nonexistent/dir/model.OBJ")).unwrap_err();
        match e {
            Error::Io { path, .. } => assert_eq!(path, Path::new("/nonexistent/dir/model.OBJ")),
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn push_f64_roundtrips() {
        for x in [
            0.0,
            -0.0,
            1.0,
            0.1,
            1.0 / 3.0,
            -2.5e-300,
            1.7976931348623157e308,
            123_456_789.123_456_79,
            1e-5,
            9.99e-6,
            1e16,
        ] {
            let mut s = String::new();
            push_f64(&mut s, x);
            let y: f64 = s.parse().unwrap();
            assert_eq!(x.to_bits(), y.to_bits(), "{x} -> {s}");
        }
        let mut s = String::new();
        push_f64(&mut s, 1e-7);
        assert_eq!(s, "1e-7");
    }
}
