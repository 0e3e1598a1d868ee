//! The `.bv` reader: tokens with their lines (text rule of [`crate::io`]: invalid UTF-8 only in
//! `#` comments), then segments; groups are looked up by name in constant time, so the time is
//! linear in the size of the file.

use super::super::groups::FirstSeen;
use super::super::text::{Lines, parse_error, read_file};
use super::{BvFile, BvGroup, BvPolyhedron, MAX_DEGREE, TriPatch};
use crate::bezier::BezierPatch;
use crate::error::Result;
use crate::geom::Point;
use crate::surface::Provenance;
use std::path::Path;
use std::str::FromStr;

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
    fn new(bytes: &'a [u8], path: &'a Path) -> Result<Self> {
        let mut toks = Vec::new();
        let mut lines = Lines::new(bytes, path);
        for l in lines.by_ref() {
            let (line, content) = l?;
            for s in content.split_whitespace() {
                toks.push(Tok { s, line });
            }
        }
        Ok(Cursor {
            toks,
            pos: 0,
            path,
            last_line: lines.end_line(),
        })
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

    /// The line of the next token (the last line at the end of the file).
    fn line_ahead(&self) -> usize {
        self.peek().map_or(self.last_line, |t| t.line)
    }

    /// The next token as a `T`; `kind` says what that is in the error ("an integer").
    fn parsed<T: FromStr>(&mut self, what: &dyn Fn() -> String, kind: &str) -> Result<T> {
        let t = self.next(what)?;
        t.s.parse::<T>().map_err(|_| {
            parse_error(
                self.path,
                t.line,
                format!("expected {} ({kind}), found '{}'", what(), t.s),
            )
        })
    }

    fn int(&mut self, what: &dyn Fn() -> String) -> Result<i64> {
        self.parsed(what, "an integer")
    }

    fn real(&mut self, what: &dyn Fn() -> String) -> Result<f64> {
        self.parsed(what, "a number")
    }

    fn count(&mut self, what: &dyn Fn() -> String, max: usize) -> Result<usize> {
        let line = self.line_ahead();
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

    /// The `nf` faces of a polyhedron of `nv` vertices: `n i1 .. in` each, `n >= 3`, indices
    /// from 0.
    fn faces(
        &mut self,
        nv: usize,
        nf: usize,
        what: &dyn Fn(&str) -> String,
    ) -> Result<Vec<Vec<usize>>> {
        let mut faces = Vec::with_capacity(nf.min(self.remaining() / 4 + 1));
        for f in 0..nf {
            let line = self.line_ahead();
            let n = self.count(&|| what(&format!("the corner count of face {f}")), 1 << 20)?;
            if n < 3 {
                return Err(parse_error(
                    self.path,
                    line,
                    format!("face {f} of the polyhedron has {n} corners; a face needs at least 3"),
                ));
            }
            let mut face = Vec::with_capacity(n.min(self.remaining()));
            for c in 0..n {
                let line = self.line_ahead();
                let v = self.int(&|| what(&format!("corner {c} of face {f}")))?;
                if v < 0 || v as u64 >= nv as u64 {
                    return Err(parse_error(
                        self.path,
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
        Ok(faces)
    }

    /// `n` homogeneous points `x y z w` of a rational patch: the Euclidean points (divided by
    /// their weights) and the weights, which must be positive.
    fn rational_points(
        &mut self,
        n: usize,
        what: &dyn Fn(&str) -> String,
    ) -> Result<(Vec<Point>, Vec<f64>)> {
        let mut cps = Vec::with_capacity(n.min(self.remaining() / 4 + 1));
        let mut ws = Vec::with_capacity(n.min(self.remaining() / 4 + 1));
        for k in 0..n {
            let p = self.point(&|| what(&format!("control point {k}")))?;
            let line = self.line_ahead();
            let w = self.real(&|| what(&format!("the weight of control point {k}")))?;
            if !(w.is_finite() && w > 0.0) {
                return Err(parse_error(
                    self.path,
                    line,
                    format!(
                        "{} is {w}; weights must be positive",
                        what(&format!("the weight of control point {k}"))
                    ),
                ));
            }
            cps.push([p[0] / w, p[1] / w, p[2] / w]);
            ws.push(w);
        }
        Ok((cps, ws))
    }
}

/// Reads a `.bv` file.
pub fn read_bv(path: &Path) -> Result<BvFile> {
    parse_bv_bytes(&read_file(path)?, path)
}

/// Parses `.bv` text; `path` is used in messages only.
pub fn parse_bv(text: &str, path: &Path) -> Result<BvFile> {
    parse_bv_bytes(text.as_bytes(), path)
}

/// Parses the bytes of a `.bv` file (decoded by the text rule).
pub(super) fn parse_bv_bytes(bytes: &[u8], path: &Path) -> Result<BvFile> {
    let mut cur = Cursor::new(bytes, path)?;
    let mut file = BvFile::default();
    let mut group_numbers = FirstSeen::default();
    let mut group: Option<usize> = None;
    let mut seg = 0usize;
    let mut plain = PlainCounts::default();
    while let Some(t) = cur.peek() {
        cur.pos += 1;
        if t.s == "group" || t.s == "Group" {
            group = Some(read_group(&mut cur, t, &mut file, &mut group_numbers)?);
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
                let faces = cur.faces(nv, nf, &what)?;
                file.polyhedra.push(BvPolyhedron {
                    positions,
                    faces,
                    group,
                });
            }
            3 | 9 => {
                file.tri_patches
                    .push(read_triangular(&mut cur, kind, &what, &mut plain)?);
                file.tri_groups.push(group);
            }
            4 | 5 | 8 | 10 => {
                let patch = read_tensor(&mut cur, kind, &what, &mut plain)?;
                file.patches.push(patch, Provenance::Unknown);
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
    plain.warn(&mut file.warnings);
    Ok(file)
}

/// The patches read as plainer ones than their type: PN triangles and quads without their
/// normals, rational patches with equal weights as polynomial ones.
#[derive(Default)]
struct PlainCounts {
    pn_tri: usize,
    pn_quad: usize,
    rational: usize,
}

impl PlainCounts {
    /// A warning for each kind of patch read as a plainer one.
    fn warn(&self, warnings: &mut Vec<String>) {
        let PlainCounts {
            pn_tri,
            pn_quad,
            rational,
        } = *self;
        if pn_tri > 0 {
            warnings.push(format!(
                "{pn_tri} PN triangle patches (type 9) read as plain triangular patches; their normals were dropped"
            ));
        }
        if pn_quad > 0 {
            warnings.push(format!(
                "{pn_quad} PN quad patches (type 10) read as plain patches; their normals were dropped"
            ));
        }
        if rational > 0 {
            warnings.push(format!(
                "{rational} rational patches (type 8) with equal weights read as polynomial patches"
            ));
        }
    }
}

/// A `group ID NAME` line (`t` is its keyword): the rest of the line is skipped, as BezierView
/// does; a name seen before keeps its number and takes the new id. Returns the group's number.
fn read_group(
    cur: &mut Cursor<'_>,
    t: Tok<'_>,
    file: &mut BvFile,
    group_numbers: &mut FirstSeen,
) -> Result<usize> {
    let id = cur.int(&|| format!("the group id after 'group' on line {}", t.line))?;
    let name_tok = cur.next(&|| format!("the group name after 'group {id}'"))?;
    let name = name_tok.s.to_string();
    // BezierView reads the rest of the group line itself.
    while cur.peek().is_some_and(|n| n.line == name_tok.line) {
        cur.pos += 1;
    }
    let (k, new) = group_numbers.number(&name);
    if new {
        file.groups.push(BvGroup { id, name });
    } else {
        file.groups[k].id = id;
    }
    Ok(k)
}

/// A triangular patch (type 3) or PN triangle (type 9, whose normal coefficients are read and
/// dropped); `what` names a value in messages.
fn read_triangular(
    cur: &mut Cursor<'_>,
    kind: i64,
    what: &dyn Fn(&str) -> String,
    plain: &mut PlainCounts,
) -> Result<TriPatch> {
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
        plain.pn_tri += 1;
    }
    Ok(TriPatch { deg, cps })
}

/// A tensor-product patch: type 4 (one degree), 5 (two), 8 (rational; equal weights make a
/// polynomial patch) or 10 (PN quad, whose normal coefficients are read and dropped); `what`
/// names a value in messages.
fn read_tensor(
    cur: &mut Cursor<'_>,
    kind: i64,
    what: &dyn Fn(&str) -> String,
    plain: &mut PlainCounts,
) -> Result<BezierPatch> {
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
    let (cps, weights) = if kind == 8 {
        let (cps, ws) = cur.rational_points(n, what)?;
        // equal weights: a polynomial patch
        let equal = ws.iter().all(|&w| (w - ws[0]).abs() <= 1e-12 * ws[0]);
        plain.rational += usize::from(equal);
        (cps, (!equal).then_some(ws))
    } else {
        (
            cur.points(n, &|k| what(&format!("control point {k}")))?,
            None,
        )
    };
    if let Some((a, b)) = ndeg {
        cur.points((a + 1) * (b + 1), &|k| {
            what(&format!("normal coefficient {k}"))
        })?;
        plain.pn_quad += 1;
    }
    Ok(BezierPatch {
        deg_u: du,
        deg_v: dv,
        cps,
        weights,
    })
}
