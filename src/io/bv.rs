//! BezierView `.bv`: the patch format of SurfLab's viewers (writer and reader).
//!
//! # The format, as BezierView reads it
//!
//! Sources: SurfLab's format page (<https://www.cise.ufl.edu/research/SurfLab/bview/#file-format>),
//! `FORMAT.txt` of the BezierView repository (github.com/SurfLab/BezierView, Xiaobin Wu, 2003),
//! and its loader (`src/load.c`: `define_scene`, `get_kind`; `src/QuadBezier.cpp`: `loadFile`,
//! `DeCastel2`, `BBcopy4`; `src/TriBezier.cpp`: `loadFile`, `b2i_i`). The file is read with
//! `fscanf`, so only the order of whitespace-separated tokens matters, not the line breaks.
//!
//! * A file is a sequence of segments; each starts with its type number.
//! * `group <id> <name>` (or `Group`) before a segment makes `<name>` the current group of the
//!   segments that follow. Groups are identified by *name*; `<id>` is the group's colour index.
//!   The rest of the group line is read with `fgets`; ` #k` there sets the group's subdivision
//!   depth. Names are single tokens.
//! * Type `1`, polyhedron: `V F`, then `V` points `x y z`, then `F` faces `n i1 .. in` with
//!   0-based vertex indices (any `n`).
//! * Type `4`, tensor-product patch of equal degrees: `deg`, then `(deg+1)^2` points.
//! * Type `5`, general tensor-product patch: `degu degv`, then `(degu+1)(degv+1)` points in
//!   row-major order of the `(degu+1) x (degv+1)` matrix `p[i][j]`: rows `i` run along `u`,
//!   columns `j` along `v` (`DeCastel2` contracts `j` with `v`, then `i` with `u`). This is
//!   exactly fairsub's [`BezierPatch`] layout `cps[i * (deg_v + 1) + j]`, `i` along u, so
//!   coefficients are written and read in storage order with no transposition.
//! * Type `8`, rational tensor-product patch: `degu degv`, points `x y z w` in homogeneous form
//!   (BezierView divides by `w`). Read when all weights are equal (a polynomial patch); else
//!   rejected.
//! * Type `3`, triangular (total-degree) patch: `deg`, then `(deg+1)(deg+2)/2` points in
//!   "row-ascending" order: for `deg = 3` the indices are laid out as
//!   ```text
//!         9
//!        7 8
//!       4 5 6
//!      0 1 2 3
//!   ```
//!   i.e. coefficient `b[i][j][k]` (`i + j + k = deg`, barycentric weights `u, v, w`) is point
//!   number `sum_{kk<k} (deg + 1 - kk) + j` (`b2i_i`): rows by `k`, within a row by `j`. See
//!   [`TriPatch::index`].
//! * Types `9` (PN triangle: `deg ndeg`, points, then normal coefficients) and `10` (PN quad:
//!   `degu degv ndegu ndegv`, points, normals) are read as plain patches; the normals are
//!   dropped with a warning.
//!
//! The writer emits `group <id> <name>` whenever the group changes (ids numbered 1.. in order
//! of first appearance, names from [`Provenance::group_name`]), patches as `4 deg` when
//! `deg_u == deg_v` and `5 degu degv` otherwise, one point per line with round-trip precision.
//! The reader is lenient about whitespace and also skips `#` comments (which drops a group's
//! `#k` depth hint, which fairsub does not use).

use super::{ChunkedText, io_error, parse_error, push_point, write_atomically};
use crate::bezier::BezierPatch;
use crate::error::{Error, Result};
use crate::geom::Point;
use crate::mesh::PolyMesh;
use crate::surface::{PatchComplex, Provenance};
use std::io::Write;
use std::path::Path;

/// Degrees above this are rejected as implausible (protects against garbage input).
const MAX_DEGREE: usize = 64;

/// A triangular (total-degree) Bezier patch in BezierView's coefficient order.
#[derive(Debug, Clone, PartialEq)]
pub struct TriPatch {
    /// Total degree.
    pub deg: usize,
    /// `(deg + 1)(deg + 2) / 2` coefficients; `b[i][j][k]` is at [`TriPatch::index`]`(deg, j, k)`.
    pub cps: Vec<Point>,
}

impl TriPatch {
    /// Position of coefficient `b[deg-j-k][j][k]` in BezierView order:
    /// `sum_{kk<k} (deg + 1 - kk) + j` (rows by `k`, within a row by `j`).
    pub fn index(deg: usize, j: usize, k: usize) -> usize {
        k * (deg + 1) - k * k.saturating_sub(1) / 2 + j
    }

    /// Coefficient `b[i][j][k]` (`i + j + k == deg`).
    pub fn cp(&self, i: usize, j: usize, k: usize) -> Point {
        debug_assert_eq!(i + j + k, self.deg);
        self.cps[Self::index(self.deg, j, k)]
    }

    /// Number of coefficients of a patch of total degree `deg`.
    pub fn count(deg: usize) -> usize {
        (deg + 1) * (deg + 2) / 2
    }
}

/// A group of a `.bv` file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct BvGroup {
    /// The number after `group` (BezierView uses it as the group's colour index).
    pub id: i64,
    /// The group name (identifies the group).
    pub name: String,
}

/// A polyhedron (type 1 segment): vertices and 0-based faces, as in the file.
#[derive(Debug, Clone, PartialEq)]
pub struct BvPolyhedron {
    /// Vertex positions.
    pub positions: Vec<Point>,
    /// Faces as vertex index lists.
    pub faces: Vec<Vec<usize>>,
    /// Index into [`BvFile::groups`] of the group the polyhedron belongs to.
    pub group: Option<usize>,
}

/// The contents of a `.bv` file.
#[derive(Debug, Clone, Default)]
pub struct BvFile {
    /// Groups in order of first appearance.
    pub groups: Vec<BvGroup>,
    /// Tensor-product patches (types 4, 5, polynomial 8, 10), with [`Provenance::Unknown`].
    pub patches: PatchComplex,
    /// Group of each tensor-product patch (index into `groups`).
    pub patch_groups: Vec<Option<usize>>,
    /// Triangular patches (types 3, 9).
    pub tri_patches: Vec<TriPatch>,
    /// Group of each triangular patch.
    pub tri_groups: Vec<Option<usize>>,
    /// Polyhedra (type 1).
    pub polyhedra: Vec<BvPolyhedron>,
    /// Notes about what was read but dropped (normals of PN patches).
    pub warnings: Vec<String>,
}

// ---------------------------------------------------------------------------------------------
// Writing

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
    names: Vec<String>,
    current: Option<usize>,
}

impl GroupTracker {
    fn new() -> Self {
        GroupTracker {
            names: Vec::new(),
            current: None,
        }
    }

    /// Switches to `name` (emitting a `group` line when it changes) with the given id, or the
    /// next free number when `id` is `None`.
    fn switch(&mut self, out: &mut String, name: &str, id: Option<i64>) {
        use std::fmt::Write as _;
        let name = token_name(name);
        let k = match self.names.iter().position(|n| *n == name) {
            Some(k) => k,
            None => {
                self.names.push(name.clone());
                self.names.len() - 1
            }
        };
        if self.current != Some(k) {
            let id = id.unwrap_or(k as i64 + 1);
            let _ = writeln!(out, "group {id} {name}");
            self.current = Some(k);
        }
    }
}

fn emit_patch(out: &mut String, p: &BezierPatch) {
    use std::fmt::Write as _;
    if p.deg_u == p.deg_v {
        let _ = writeln!(out, "4 {}", p.deg_u);
    } else {
        let _ = writeln!(out, "5 {} {}", p.deg_u, p.deg_v);
    }
    for &q in &p.cps {
        push_point(out, q);
        out.push('\n');
    }
}

fn emit_polyhedron(
    out: &mut String,
    positions: &[Point],
    faces: &mut dyn Iterator<Item = &[u32]>,
    nf: usize,
) {
    use std::fmt::Write as _;
    let _ = writeln!(out, "1\n{} {}", positions.len(), nf);
    for &q in positions {
        push_point(out, q);
        out.push('\n');
    }
    for f in faces {
        let _ = write!(out, "{}", f.len());
        for v in f {
            let _ = write!(out, " {v}");
        }
        out.push('\n');
    }
}

fn write_complex_to(w: &mut dyn Write, c: &PatchComplex) -> std::io::Result<()> {
    let mut out = ChunkedText::new(w);
    let mut groups = GroupTracker::new();
    for (p, prov) in c.patches.iter().zip(&c.provenance) {
        groups.switch(&mut out.buf, &prov.group_name(), None);
        emit_patch(&mut out.buf, p);
        out.maybe_flush()?;
    }
    out.finish()
}

/// The `.bv` text of a patch complex (groups from the provenance, see the module doc).
pub fn bv_to_string(complex: &PatchComplex) -> Result<String> {
    check_complex(complex)?;
    let mut buf = Vec::new();
    write_complex_to(&mut buf, complex).map_err(|e| io_error(Path::new("<string>"), e))?;
    Ok(String::from_utf8(buf).unwrap_or_default())
}

/// Writes a patch complex as a `.bv` file (atomically).
pub fn write_bv(path: &Path, complex: &PatchComplex) -> Result<()> {
    check_complex(complex)?;
    write_atomically(path, |w| {
        write_complex_to(w, complex).map_err(|e| io_error(path, e))
    })
}

/// The `.bv` text of a mesh as one polyhedron (type 1) segment.
pub fn bv_mesh_to_string(mesh: &PolyMesh) -> String {
    let mut s = String::new();
    emit_polyhedron(
        &mut s,
        mesh.positions(),
        &mut mesh.faces(),
        mesh.num_faces(),
    );
    s
}

/// Writes a mesh as a `.bv` polyhedron (type 1), e.g. to show a control net beside its
/// patches (atomically).
pub fn write_bv_mesh(path: &Path, mesh: &PolyMesh) -> Result<()> {
    write_atomically(path, |w| {
        w.write_all(bv_mesh_to_string(mesh).as_bytes())
            .map_err(|e| io_error(path, e))
    })
}

impl BvFile {
    /// The `.bv` text of everything in this file: polyhedra, then tensor-product patches, then
    /// triangular patches, each preceded by its group line when the group changes (group ids
    /// and names as stored).
    pub fn to_bv_string(&self) -> Result<String> {
        check_complex(&self.patches)?;
        let mut out = String::new();
        let mut tracker = GroupTracker::new();
        let mut switch = |out: &mut String, g: Option<usize>| -> Result<()> {
            if let Some(g) = g {
                let grp = self.groups.get(g).ok_or_else(|| {
                    Error::InvalidArgument(format!(
                        "group index {g} out of range ({} groups)",
                        self.groups.len()
                    ))
                })?;
                tracker.switch(out, &grp.name, Some(grp.id));
            }
            Ok(())
        };
        for (k, p) in self.polyhedra.iter().enumerate() {
            switch(&mut out, p.group)?;
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
            let faces: Vec<Vec<u32>> = p
                .faces
                .iter()
                .map(|f| f.iter().map(|&v| v as u32).collect())
                .collect();
            emit_polyhedron(
                &mut out,
                &p.positions,
                &mut faces.iter().map(|f| &f[..]),
                faces.len(),
            );
        }
        for (k, p) in self.patches.patches.iter().enumerate() {
            switch(&mut out, self.patch_groups.get(k).copied().flatten())?;
            emit_patch(&mut out, p);
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
            switch(&mut out, self.tri_groups.get(k).copied().flatten())?;
            use std::fmt::Write as _;
            let _ = writeln!(out, "3 {}", t.deg);
            for &q in &t.cps {
                push_point(&mut out, q);
                out.push('\n');
            }
        }
        Ok(out)
    }
}

/// Writes a [`BvFile`] (atomically).
pub fn write_bv_file(path: &Path, file: &BvFile) -> Result<()> {
    let text = file.to_bv_string()?;
    write_atomically(path, |w| {
        w.write_all(text.as_bytes()).map_err(|e| io_error(path, e))
    })
}

// ---------------------------------------------------------------------------------------------
// Reading

/// A token and its 1-based line.
#[derive(Debug, Clone, Copy)]
struct Tok<'a> {
    s: &'a str,
    line: usize,
}

struct Cursor<'a> {
    toks: Vec<Tok<'a>>,
    pos: usize,
    path: &'a Path,
    last_line: usize,
}

impl<'a> Cursor<'a> {
    fn new(text: &'a str, path: &'a Path) -> Self {
        let mut toks = Vec::new();
        let mut last_line = 0;
        for (i, line) in text.lines().enumerate() {
            let line_content = match line.find('#') {
                Some(k) => &line[..k],
                None => line,
            };
            for s in line_content.split_whitespace() {
                toks.push(Tok { s, line: i + 1 });
            }
            last_line = i + 1;
        }
        Cursor {
            toks,
            pos: 0,
            path,
            last_line,
        }
    }

    fn remaining(&self) -> usize {
        self.toks.len() - self.pos
    }

    fn peek(&self) -> Option<Tok<'a>> {
        self.toks.get(self.pos).copied()
    }

    fn next(&mut self, what: &dyn Fn() -> String) -> Result<Tok<'a>> {
        match self.toks.get(self.pos) {
            Some(&t) => {
                self.pos += 1;
                Ok(t)
            }
            None => Err(parse_error(
                self.path,
                self.last_line,
                format!("file ends where {} was expected", what()),
            )),
        }
    }

    fn int(&mut self, what: &dyn Fn() -> String) -> Result<i64> {
        let t = self.next(what)?;
        t.s.parse::<i64>().map_err(|_| {
            parse_error(
                self.path,
                t.line,
                format!("expected {} (an integer), found '{}'", what(), t.s),
            )
        })
    }

    fn count(&mut self, what: &dyn Fn() -> String, max: usize) -> Result<usize> {
        let line = self.peek().map_or(self.last_line, |t| t.line);
        let v = self.int(what)?;
        if v < 0 || v as u64 > max as u64 {
            return Err(parse_error(
                self.path,
                line,
                format!("{} is {v}; expected 0..={max}", what()),
            ));
        }
        Ok(v as usize)
    }

    fn real(&mut self, what: &dyn Fn() -> String) -> Result<f64> {
        let t = self.next(what)?;
        t.s.parse::<f64>().map_err(|_| {
            parse_error(
                self.path,
                t.line,
                format!("expected {} (a number), found '{}'", what(), t.s),
            )
        })
    }

    fn point(&mut self, what: &dyn Fn() -> String) -> Result<Point> {
        let mut p = [0.0; 3];
        for (c, slot) in p.iter_mut().enumerate() {
            *slot =
                self.real(&|| format!("the {} coordinate of {}", ["x", "y", "z"][c], what()))?;
        }
        Ok(p)
    }

    fn points(&mut self, n: usize, what: &dyn Fn(usize) -> String) -> Result<Vec<Point>> {
        let mut v = Vec::with_capacity(n.min(self.remaining() / 3 + 1));
        for k in 0..n {
            v.push(self.point(&|| what(k))?);
        }
        Ok(v)
    }
}

/// Reads a `.bv` file.
pub fn read_bv(path: &Path) -> Result<BvFile> {
    let bytes = std::fs::read(path).map_err(|e| io_error(path, e))?;
    let text = String::from_utf8_lossy(&bytes);
    parse_bv(&text, path)
}

/// Parses `.bv` text; `path` is used in messages only.
pub fn parse_bv(text: &str, path: &Path) -> Result<BvFile> {
    let mut cur = Cursor::new(text, path);
    let mut file = BvFile::default();
    let mut group: Option<usize> = None;
    let mut seg = 0usize;
    let (mut pn_tri, mut pn_quad, mut rational) = (0usize, 0usize, 0usize);
    while let Some(t) = cur.peek() {
        cur.pos += 1;
        if t.s == "group" || t.s == "Group" {
            let id = cur.int(&|| format!("the group id after 'group' on line {}", t.line))?;
            let name_tok = cur.next(&|| format!("the group name after 'group {id}'"))?;
            let name = name_tok.s.to_string();
            // BezierView reads the rest of the group line itself.
            while cur.peek().is_some_and(|n| n.line == name_tok.line) {
                cur.pos += 1;
            }
            group = Some(match file.groups.iter().position(|g| g.name == name) {
                Some(k) => {
                    file.groups[k].id = id;
                    k
                }
                None => {
                    file.groups.push(BvGroup { id, name });
                    file.groups.len() - 1
                }
            });
            continue;
        }
        seg += 1;
        let kind: i64 = t.s.parse().map_err(|_| {
            parse_error(
                path,
                t.line,
                format!(
                    "expected a patch type (1, 3, 4, 5, 8, 9, 10) or 'group', found '{}'",
                    t.s
                ),
            )
        })?;
        let at = t.line;
        let name = |k: i64| match k {
            1 => "polyhedron",
            3 => "triangular patch",
            4 | 5 => "tensor-product patch",
            8 => "rational patch",
            9 => "PN triangle",
            _ => "PN quad",
        };
        let what = |s: &str| format!("{s} of the {} (segment {seg}, line {at})", name(kind));
        match kind {
            1 => {
                let nv = cur.count(&|| what("the vertex count"), u32::MAX as usize)?;
                let nf = cur.count(&|| what("the face count"), u32::MAX as usize)?;
                let positions = cur.points(nv, &|k| what(&format!("vertex {k}")))?;
                let mut faces = Vec::with_capacity(nf.min(cur.remaining() / 4 + 1));
                for f in 0..nf {
                    let line = cur.peek().map_or(cur.last_line, |t| t.line);
                    let n =
                        cur.count(&|| what(&format!("the corner count of face {f}")), 1 << 20)?;
                    if n < 3 {
                        return Err(parse_error(
                            path,
                            line,
                            format!(
                                "face {f} of the polyhedron has {n} corners; a face needs at least 3"
                            ),
                        ));
                    }
                    let mut face = Vec::with_capacity(n.min(cur.remaining()));
                    for c in 0..n {
                        let line = cur.peek().map_or(cur.last_line, |t| t.line);
                        let v = cur.int(&|| what(&format!("corner {c} of face {f}")))?;
                        if v < 0 || v as u64 >= nv as u64 {
                            return Err(parse_error(
                                path,
                                line,
                                format!(
                                    "face {f} of the polyhedron refers to vertex {v}, but it has {nv} vertices (indices from 0)"
                                ),
                            ));
                        }
                        face.push(v as usize);
                    }
                    faces.push(face);
                }
                file.polyhedra.push(BvPolyhedron {
                    positions,
                    faces,
                    group,
                });
            }
            3 | 9 => {
                let deg = cur.count(&|| what("the degree"), MAX_DEGREE)?;
                let ndeg = if kind == 9 {
                    Some(cur.count(&|| what("the normal degree"), MAX_DEGREE)?)
                } else {
                    None
                };
                let cps = cur.points(TriPatch::count(deg), &|k| {
                    what(&format!("control point {k}"))
                })?;
                if let Some(nd) = ndeg {
                    cur.points(TriPatch::count(nd), &|k| {
                        what(&format!("normal coefficient {k}"))
                    })?;
                    pn_tri += 1;
                }
                file.tri_patches.push(TriPatch { deg, cps });
                file.tri_groups.push(group);
            }
            4 | 5 | 8 | 10 => {
                let du = cur.count(&|| what("the degree in u"), MAX_DEGREE)?;
                let dv = if kind == 4 {
                    du
                } else {
                    cur.count(&|| what("the degree in v"), MAX_DEGREE)?
                };
                let ndeg = if kind == 10 {
                    let a = cur.count(&|| what("the normal degree in u"), MAX_DEGREE)?;
                    let b = cur.count(&|| what("the normal degree in v"), MAX_DEGREE)?;
                    Some((a, b))
                } else {
                    None
                };
                let n = (du + 1) * (dv + 1);
                let cps = if kind == 8 {
                    let mut cps = Vec::with_capacity(n);
                    let mut w0 = None;
                    for k in 0..n {
                        let p = cur.point(&|| what(&format!("control point {k}")))?;
                        let line = cur.peek().map_or(cur.last_line, |t| t.line);
                        let w = cur.real(&|| what(&format!("the weight of control point {k}")))?;
                        let w0 = *w0.get_or_insert(w);
                        if w == 0.0 || (w - w0).abs() > 1e-12 * w0.abs() {
                            return Err(Error::Unsupported(format!(
                                "{}:{line}: rational patch (segment {seg}, line {at}) has weights {w0} and {w}; \
                                 only rational patches with equal weights (polynomial ones) can be read",
                                path.display()
                            )));
                        }
                        cps.push([p[0] / w, p[1] / w, p[2] / w]);
                    }
                    rational += 1;
                    cps
                } else {
                    cur.points(n, &|k| what(&format!("control point {k}")))?
                };
                if let Some((a, b)) = ndeg {
                    cur.points((a + 1) * (b + 1), &|k| {
                        what(&format!("normal coefficient {k}"))
                    })?;
                    pn_quad += 1;
                }
                file.patches.push(
                    BezierPatch {
                        deg_u: du,
                        deg_v: dv,
                        cps,
                    },
                    Provenance::Unknown,
                );
                file.patch_groups.push(group);
            }
            other => {
                return Err(parse_error(
                    path,
                    at,
                    format!("unknown patch type {other} (known: 1, 3, 4, 5, 8, 9, 10)"),
                ));
            }
        }
    }
    if pn_tri > 0 {
        file.warnings.push(format!(
            "{pn_tri} PN triangle patches (type 9) read as plain triangular patches; their normals were dropped"
        ));
    }
    if pn_quad > 0 {
        file.warnings.push(format!(
            "{pn_quad} PN quad patches (type 10) read as plain patches; their normals were dropped"
        ));
    }
    if rational > 0 {
        file.warnings.push(format!(
            "{rational} rational patches (type 8) with equal weights read as polynomial patches"
        ));
    }
    Ok(file)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::surface::Element;

    fn patch(du: usize, dv: usize, seed: f64) -> BezierPatch {
        let cps = (0..(du + 1) * (dv + 1))
            .map(|k| {
                let (i, j) = (k / (dv + 1), k % (dv + 1));
                [
                    i as f64 + seed,
                    j as f64 / 3.0,
                    (seed * (k as f64 + 1.0)).sin(),
                ]
            })
            .collect();
        BezierPatch::new(du, dv, cps)
    }

    fn complex() -> PatchComplex {
        let mut c = PatchComplex::new();
        c.push(patch(3, 3, 0.1), Provenance::Regular { face: 0 });
        c.push(patch(2, 3, 0.2), Provenance::Regular { face: 1 });
        let e = Element::Vertex(7);
        c.push(
            patch(3, 3, 0.3),
            Provenance::Ring {
                element: e,
                ring: 1,
                sector: 0,
            },
        );
        c.push(
            patch(3, 3, 0.4),
            Provenance::Cap {
                element: e,
                sector: 0,
            },
        );
        c.push(patch(1, 4, 0.5), Provenance::Regular { face: 2 });
        c
    }

    #[test]
    fn triangular_index_matches_bezierview_picture() {
        // 9 / 7 8 / 4 5 6 / 0 1 2 3 for degree 3: row k, position j.
        assert_eq!(TriPatch::index(3, 0, 0), 0);
        assert_eq!(TriPatch::index(3, 3, 0), 3);
        assert_eq!(TriPatch::index(3, 0, 1), 4);
        assert_eq!(TriPatch::index(3, 2, 1), 6);
        assert_eq!(TriPatch::index(3, 0, 2), 7);
        assert_eq!(TriPatch::index(3, 1, 2), 8);
        assert_eq!(TriPatch::index(3, 0, 3), 9);
        assert_eq!(TriPatch::count(3), 10);
        // Agrees with the loop of b2i_i for several degrees.
        for d in 0..8 {
            for k in 0..=d {
                let lk: usize = (0..k).map(|kk| d + 1 - kk).sum();
                for j in 0..=d - k {
                    assert_eq!(TriPatch::index(d, j, k), lk + j);
                }
            }
        }
    }

    #[test]
    fn writer_layout() {
        let s = bv_to_string(&complex()).unwrap();
        let lines: Vec<&str> = s.lines().collect();
        assert_eq!(lines[0], "group 1 regular");
        assert_eq!(lines[1], "4 3");
        assert_eq!(
            lines.len(),
            1 + 1 + 16 + 1 + 12 + 1 + 1 + 16 + 1 + 1 + 16 + 1 + 1 + 10
        );
        assert_eq!(lines[18], "5 2 3");
        assert_eq!(lines[31], "group 2 ring1");
        assert_eq!(lines[49], "group 3 cap");
        assert_eq!(lines[67], "group 1 regular");
        assert_eq!(lines[68], "5 1 4");
        // b[0][1] of the first patch is the second point: row-major, i along u.
        let p: Vec<f64> = lines[3].split(' ').map(|x| x.parse().unwrap()).collect();
        assert_eq!(p, complex().patches[0].cp(0, 1).to_vec());
    }

    #[test]
    fn roundtrip_is_exact_and_keeps_groups() {
        let c = complex();
        let s = bv_to_string(&c).unwrap();
        let f = parse_bv(&s, Path::new("r.bv")).unwrap();
        assert_eq!(f.patches.patches, c.patches);
        assert!(
            f.patches
                .provenance
                .iter()
                .all(|p| *p == Provenance::Unknown)
        );
        let names: Vec<&str> = f.groups.iter().map(|g| g.name.as_str()).collect();
        assert_eq!(names, ["regular", "ring1", "cap"]);
        assert_eq!(
            f.patch_groups,
            [Some(0), Some(0), Some(1), Some(2), Some(0)]
        );
        assert!(f.warnings.is_empty());
        // And the BvFile writes back to the same text.
        assert_eq!(f.to_bv_string().unwrap(), s);
    }

    #[test]
    fn reads_foreign_files_leniently() {
        // The tensor example of SurfLab's page, a triangle, a polyhedron with a quad,
        // comments and odd whitespace.
        let src = "# from another tool\nGroup 1 deg2x3\n5\n2 3\n-1.5 1.0 0.0\n-0.5 1.0 0.0\n0.5 1.0 0.0\n1.5 1.0 0.0\n\
                   -1.5 0.0 0.0\n-0.5 0.0 0.5\n0.5 0.0 0.5\n1.5 0.0 0.0\n-1.5 -1.0 0.0 -0.5 -1.0 0.0\n\
                   0.5\t-1.0 0.0\n1.5 -1.0 0.0\n\n\
                   group 4 tri #3\n3 1\n0 0 0\n1 0 0\n0 1 0\n\
                   1\n5 2\n0 0 0\n1 0 0\n1 1 0\n0 1 1\n0.5 2 0\n4 0 1 2 3\n3 3 2 4\n\
                   8 1 1\n0 0 0 2\n2 0 0 2\n0 2 0 2\n2 2 2 2\n\
                   10 1 1 0 0\n0 0 0\n1 0 0\n0 1 0\n1 1 1\n0 0 1\n";
        let f = parse_bv(src, Path::new("f.bv")).unwrap();
        assert_eq!(f.patches.len(), 3);
        let p = &f.patches.patches[0];
        assert_eq!((p.deg_u, p.deg_v), (2, 3));
        assert_eq!(p.cp(1, 1), [-0.5, 0.0, 0.5]);
        assert_eq!(p.cp(2, 0), [-1.5, -1.0, 0.0]);
        assert_eq!(p.cp(2, 1), [-0.5, -1.0, 0.0]);
        let r = &f.patches.patches[1];
        assert_eq!(
            r.cps,
            vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 1.0]]
        );
        assert_eq!(f.patches.patches[2].cp(1, 1), [1.0, 1.0, 1.0]);
        assert_eq!(f.tri_patches.len(), 1);
        assert_eq!(f.tri_patches[0].cp(0, 0, 1), [0.0, 1.0, 0.0]);
        assert_eq!(f.polyhedra.len(), 1);
        assert_eq!(f.polyhedra[0].faces, vec![vec![0, 1, 2, 3], vec![3, 2, 4]]);
        assert_eq!(f.polyhedra[0].positions[3], [0.0, 1.0, 1.0]);
        assert_eq!(
            f.groups,
            vec![
                BvGroup {
                    id: 1,
                    name: "deg2x3".into()
                },
                BvGroup {
                    id: 4,
                    name: "tri".into()
                }
            ]
        );
        assert_eq!(f.patch_groups, [Some(0), Some(1), Some(1)]);
        assert_eq!(f.tri_groups, [Some(1)]);
        assert_eq!(f.polyhedra[0].group, Some(1));
        assert_eq!(f.warnings.len(), 2, "{:?}", f.warnings);
        // A polyhedron read back becomes a valid mesh.
        let m = PolyMesh::new(f.polyhedra[0].positions.clone(), &f.polyhedra[0].faces).unwrap();
        assert_eq!(m.num_faces(), 2);
    }

    #[test]
    fn mesh_as_polyhedron_roundtrip() {
        let pos = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.1],
            [0.0, 1.0, 0.0],
            [0.5, 2.0, 0.0],
        ];
        let faces: Vec<Vec<usize>> = vec![vec![0, 1, 2, 3], vec![3, 2, 4]];
        let m = PolyMesh::new(pos.clone(), &faces).unwrap();
        let s = bv_mesh_to_string(&m);
        assert!(s.starts_with("1\n5 2\n"), "{s}");
        let f = parse_bv(&s, Path::new("m.bv")).unwrap();
        assert_eq!(f.polyhedra[0].positions, pos);
        assert_eq!(f.polyhedra[0].faces, faces);
        assert_eq!(f.polyhedra[0].group, None);
    }

    fn err(src: &str) -> (usize, String) {
        match parse_bv(src, Path::new("e.bv")) {
            Err(Error::Parse { line, msg, .. }) => (line, msg),
            other => panic!("expected parse error, got {other:?}"),
        }
    }

    #[test]
    fn errors_name_lines() {
        let (l, m) = err("4 1\n0 0 0\n1 0 0\n0 1 0\n1 1 q\n");
        assert_eq!(l, 5);
        assert!(
            m.contains("'q'") && m.contains("control point 3") && m.contains("line 1"),
            "{m}"
        );
        let (l, m) = err("4 1\n0 0 0\n1 0 0\n");
        assert_eq!(l, 3);
        assert!(
            m.contains("file ends") && m.contains("control point 2"),
            "{m}"
        );
        let (l, m) = err("\n\n7 1\n");
        assert_eq!(l, 3);
        assert!(m.contains("unknown patch type 7"), "{m}");
        let (l, m) = err("1\n3 1\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n3\n");
        assert_eq!(l, 7);
        assert!(m.contains("vertex 3"), "{m}");
        let (l, m) = err("5 2 -1\n");
        assert_eq!(l, 1);
        assert!(m.contains("degree in v") && m.contains("is -1"), "{m}");
        let (l, m) = err("hello\n");
        assert_eq!(l, 1);
        assert!(m.contains("'hello'"), "{m}");
        let (_, m) = err("1\n4000000000 1\n0 0 0\n");
        assert!(m.contains("file ends") && m.contains("vertex 1"), "{m}");
        let (l, m) = err("5 2 1000000\n");
        assert_eq!(l, 1);
        assert!(m.contains("1000000"), "{m}");
        let e = parse_bv(
            "8 1 1\n0 0 0 1\n1 0 0 2\n0 1 0 1\n1 1 0 1\n",
            Path::new("e.bv"),
        )
        .unwrap_err();
        assert!(
            matches!(e, Error::Unsupported(_)) && e.to_string().contains("e.bv:3"),
            "{e}"
        );
    }

    #[test]
    fn writer_rejects_bad_patches() {
        let mut c = complex();
        c.patches[1].cps[4][2] = f64::INFINITY;
        let e = bv_to_string(&c).unwrap_err().to_string();
        assert!(e.contains("patch 1") && e.contains("b[1][0]"), "{e}");
        let mut c = complex();
        c.patches[2].cps.pop();
        let e = bv_to_string(&c).unwrap_err().to_string();
        assert!(
            e.contains("patch 2") && e.contains("15 coefficients"),
            "{e}"
        );
    }
}
