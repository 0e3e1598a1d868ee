//! The `.bv` writer: patch complexes (groups from the provenance), meshes as polyhedra, and
//! whole [`BvFile`]s. Everything is checked before the first byte is written.

use super::super::groups::FirstSeen;
use super::super::textout::ChunkedText;
use super::super::{io_error, write_atomically, write_bytes_atomically};
use super::{BvFile, TriPatch};
use crate::bezier::BezierPatch;
use crate::error::{Error, Result};
use crate::mesh::PolyMesh;
use crate::surface::PatchComplex;
use std::io::Write;
use std::path::Path;

/// Checks a patch's coefficient count and that its coefficients are finite.
fn check_patch(k: usize, p: &BezierPatch) -> Result<()> {
    if p.cps.len() != (p.deg_u + 1) * (p.deg_v + 1) {
        return Err(Error::InvalidArgument(format!(
            "patch {k} of bi-degree ({}, {}) has {} coefficients, expected {}",
            p.deg_u,
            p.deg_v,
            p.cps.len(),
            (p.deg_u + 1) * (p.deg_v + 1)
        )));
    }
    if let Some(w) = &p.weights
        && (w.len() != p.cps.len() || w.iter().any(|x| !(x.is_finite() && *x > 0.0)))
    {
        return Err(Error::InvalidArgument(format!(
            "rational patch {k}: its weights must be one positive number per coefficient"
        )));
    }
    if let Some(c) = p.cps.iter().position(|q| !q.iter().all(|x| x.is_finite())) {
        return Err(Error::InvalidArgument(format!(
            "patch {k}: coefficient b[{}][{}] = {:?} is not finite",
            c / (p.deg_v + 1),
            c % (p.deg_v + 1),
            p.cps[c]
        )));
    }
    Ok(())
}

/// Checks a whole complex before anything is written.
pub(crate) fn check_complex(c: &PatchComplex) -> Result<()> {
    if c.provenance.len() != c.patches.len() {
        return Err(Error::InvalidArgument(format!(
            "patch complex has {} patches but {} provenance entries",
            c.patches.len(),
            c.provenance.len()
        )));
    }
    for (k, p) in c.patches.iter().enumerate() {
        check_patch(k, p)?;
    }
    Ok(())
}

/// A group name as a single token.
fn token_name(name: &str) -> String {
    let s: String = name
        .chars()
        .map(|c| {
            if c.is_whitespace() || c == '#' {
                '_'
            } else {
                c
            }
        })
        .collect();
    if s.is_empty() { "group".to_string() } else { s }
}

/// Emits `group` lines when the group changes, numbering groups by first appearance.
struct GroupTracker {
    numbers: FirstSeen,
    current: Option<usize>,
}

impl GroupTracker {
    fn new() -> Self {
        GroupTracker {
            numbers: FirstSeen::default(),
            current: None,
        }
    }

    /// Switches to `name` (emitting a `group` line when it changes) with the given id, or the
    /// next free number when `id` is `None`.
    fn switch(&mut self, out: &mut String, name: &str, id: Option<i64>) {
        use std::fmt::Write as _;
        let name = token_name(name);
        let (k, _) = self.numbers.number(&name);
        if self.current != Some(k) {
            let id = id.unwrap_or(k as i64 + 1);
            let _ = writeln!(out, "group {id} {name}");
            self.current = Some(k);
        }
    }
}

/// A tensor-product patch: `4 deg` or `5 degu degv`, then its coefficients in storage order; a
/// rational one `8 degu degv`, then its homogeneous coefficients `w x, w y, w z, w`.
fn emit_patch(out: &mut ChunkedText<'_>, p: &BezierPatch) -> std::io::Result<()> {
    use std::fmt::Write as _;
    if let Some(w) = &p.weights {
        let _ = writeln!(out.buf, "8 {} {}", p.deg_u, p.deg_v);
        for (c, &wi) in p.cps.iter().zip(w) {
            for x in [c[0] * wi, c[1] * wi, c[2] * wi] {
                super::super::textout::push_f64(&mut out.buf, x);
                out.buf.push(' ');
            }
            super::super::textout::push_f64(&mut out.buf, wi);
            out.buf.push('\n');
            out.maybe_flush()?;
        }
        return Ok(());
    }
    if p.deg_u == p.deg_v {
        let _ = writeln!(out.buf, "4 {}", p.deg_u);
    } else {
        let _ = writeln!(out.buf, "5 {} {}", p.deg_u, p.deg_v);
    }
    out.point_lines("", &p.cps)
}

/// A polyhedron: `1`, `V F`, the points, then the faces `n i1 .. in`.
fn emit_polyhedron<F: AsRef<[T]>, T: std::fmt::Display>(
    out: &mut ChunkedText<'_>,
    positions: &[crate::geom::Point],
    faces: &[F],
) -> std::io::Result<()> {
    use std::fmt::Write as _;
    let _ = writeln!(out.buf, "1\n{} {}", positions.len(), faces.len());
    out.point_lines("", positions)?;
    out.counted_face_lines(faces)
}

fn write_complex_to(w: &mut dyn Write, c: &PatchComplex) -> std::io::Result<()> {
    let mut out = ChunkedText::new(w);
    let mut groups = GroupTracker::new();
    for (p, prov) in c.patches.iter().zip(&c.provenance) {
        groups.switch(&mut out.buf, &prov.group_name(), None);
        emit_patch(&mut out, p)?;
    }
    out.finish()
}

/// Text written into memory (the writers cannot fail there, and write UTF-8).
fn into_string(write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>) -> String {
    let mut buf = Vec::new();
    let _ = write(&mut buf);
    String::from_utf8(buf).unwrap_or_default()
}

/// The `.bv` text of a patch complex (groups from the provenance, see the module doc).
pub fn bv_to_string(complex: &PatchComplex) -> Result<String> {
    check_complex(complex)?;
    Ok(into_string(|w| write_complex_to(w, complex)))
}

/// Writes a patch complex as a `.bv` file (atomically).
pub fn write_bv(path: &Path, complex: &PatchComplex) -> Result<()> {
    check_complex(complex)?;
    write_atomically(path, |w| {
        write_complex_to(w, complex).map_err(|e| io_error(path, e))
    })
}

fn write_mesh_to(w: &mut dyn Write, mesh: &PolyMesh) -> std::io::Result<()> {
    let mut out = ChunkedText::new(w);
    let faces: Vec<&[u32]> = mesh.faces().collect();
    emit_polyhedron(&mut out, mesh.positions(), &faces)?;
    out.finish()
}

/// The `.bv` text of a mesh as one polyhedron (type 1) segment.
pub fn bv_mesh_to_string(mesh: &PolyMesh) -> String {
    into_string(|w| write_mesh_to(w, mesh))
}

/// Writes a mesh as a `.bv` polyhedron (type 1), e.g. to show a control net beside its
/// patches (atomically).
pub fn write_bv_mesh(path: &Path, mesh: &PolyMesh) -> Result<()> {
    write_atomically(path, |w| {
        write_mesh_to(w, mesh).map_err(|e| io_error(path, e))
    })
}

impl BvFile {
    /// The `.bv` text of everything in this file: polyhedra, then tensor-product patches, then
    /// triangular patches, each preceded by its group line when the group changes (group ids
    /// and names as stored).
    pub fn to_bv_string(&self) -> Result<String> {
        check_complex(&self.patches)?;
        for (k, p) in self.polyhedra.iter().enumerate() {
            if let Some(f) = p
                .faces
                .iter()
                .position(|f| f.iter().any(|&v| v >= p.positions.len()))
            {
                return Err(Error::InvalidArgument(format!(
                    "polyhedron {k}: face {f} refers to a vertex beyond its {} vertices",
                    p.positions.len()
                )));
            }
        }
        for (k, t) in self.tri_patches.iter().enumerate() {
            if t.cps.len() != TriPatch::count(t.deg) {
                return Err(Error::InvalidArgument(format!(
                    "triangular patch {k} of degree {} has {} coefficients, expected {}",
                    t.deg,
                    t.cps.len(),
                    TriPatch::count(t.deg)
                )));
            }
        }
        let groups = self
            .polyhedra
            .iter()
            .map(|p| p.group)
            .chain((0..self.patches.len()).map(|k| self.patch_groups.get(k).copied().flatten()))
            .chain((0..self.tri_patches.len()).map(|k| self.tri_groups.get(k).copied().flatten()));
        for g in groups.flatten() {
            if g >= self.groups.len() {
                return Err(Error::InvalidArgument(format!(
                    "group index {g} out of range ({} groups)",
                    self.groups.len()
                )));
            }
        }
        Ok(into_string(|w| self.write_to(w)))
    }

    /// Writes the checked file (see [`BvFile::to_bv_string`]).
    fn write_to(&self, w: &mut dyn Write) -> std::io::Result<()> {
        use std::fmt::Write as _;
        let mut out = ChunkedText::new(w);
        let mut tracker = GroupTracker::new();
        let mut switch = |out: &mut ChunkedText<'_>, g: Option<usize>| {
            if let Some(grp) = g.and_then(|g| self.groups.get(g)) {
                tracker.switch(&mut out.buf, &grp.name, Some(grp.id));
            }
        };
        for p in &self.polyhedra {
            switch(&mut out, p.group);
            emit_polyhedron(&mut out, &p.positions, &p.faces)?;
        }
        for (k, p) in self.patches.patches.iter().enumerate() {
            switch(&mut out, self.patch_groups.get(k).copied().flatten());
            emit_patch(&mut out, p)?;
        }
        for (k, t) in self.tri_patches.iter().enumerate() {
            switch(&mut out, self.tri_groups.get(k).copied().flatten());
            let _ = writeln!(out.buf, "3 {}", t.deg);
            out.point_lines("", &t.cps)?;
        }
        out.finish()
    }
}

/// Writes a [`BvFile`] (atomically).
pub fn write_bv_file(path: &Path, file: &BvFile) -> Result<()> {
    let text = file.to_bv_string()?;
    write_bytes_atomically(path, text.as_bytes())
}
