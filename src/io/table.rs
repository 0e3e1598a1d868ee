//! The patch stencil table file (`subdivide --rings K --stencils OUT`): a text format, one
//! record per line, numbers in shortest round-trip form (they read back bit for bit).
//!
//! ```text
//! fairsub-patch-table 2
//! sources N          control points the rows read (the net's vertices as the scheme reads it)
//! patches P
//! rows R             P patches' coefficient rows, then the caps' data rows
//! entries E          non-zero weights in all rows
//! caps C
//! capmaps M
//! constants 0|1      1: a constant line per row follows the rows
//! p DU DV FIRST KIND GROUP        P lines: bi-degree, first row, linear|cap, provenance group
//! c FIRST COUNT ROW MAP DEGREE CENTRE FAN SECTORS SEGMENTS B C ... [kept S ...]   C lines
//! m ID VALENCE ROWS COLS          M blocks, each followed by ROWS lines of COLS numbers
//! r K I1 W1 ... IK WK             R lines: row r is sum_k Wk * point[Ik]
//! k X Y Z                         R lines when constants is 1
//! end
//! ```
//!
//! Patch `p` has `(DU + 1) (DV + 1)` coefficients at rows `FIRST ..`, `b[i][j]` at
//! `FIRST + i (DV + 1) + j` (i along u). A `cap` patch has empty rows: it is one of the
//! `COUNT` patches `FIRST ..` of a G^1 cap line `c`, computed from the cap's data rows `ROW ..`:
//! the centre `C`, two vectors `A`, `B` spanning the limit tangent plane, then per sector (of
//! `SECTORS`) and per segment (`SEGMENTS` numbers per sector, each segment given as its
//! `B C` coefficient counts) the boundary coefficients, then the cross-derivative coefficients.
//! The cap's patches are `matrix MAP x (C, T0, T1, data after A, B)`, bi-`DEGREE` per sector,
//! rows `s (DEGREE + 1)^2 + i (DEGREE + 1) + j`, where `T0, T1` are the spoke tangents fitted in
//! the plane with normal `A x B` ([`crate::bezier::g1::ring::chart_tangents`]; the one step that
//! is not linear in the points). `CENTRE` is `tangent-plane` or `quadratic-jet`. `FAN` is
//! `closed` (a hole around an interior vertex, spoke `s` at the angle `2 pi s / SECTORS`) or
//! `open` (a fan at a boundary vertex, `SECTORS + 1` spokes at the angles `pi s / SECTORS`, the
//! first and last on the boundary; [`crate::bezier::g1::Layout::OpenQuad`]) or `crease` (an
//! open fan beside an infinitely sharp crease, [`crate::bezier::g1::Fan::Crease`]: `T0` is
//! `A` itself, the crease's derivative, and only `T1` is fitted,
//! [`crate::bezier::g1::ring::crease_tangents`]) or `dart` (a fan around a dart,
//! [`crate::bezier::g1::Fan::Dart`]: `SECTORS + 1` spokes at the angles `2 pi s / SECTORS`,
//! the first and last the one sharp edge) or `wedge/M` (the `SECTORS` of the `M` sectors
//! around an interior vertex that are not OpenSubdiv hole faces,
//! [`crate::bezier::g1::Fan::Wedge`]: spokes at the angles `2 pi s / M`, the first and last
//! on the hole's border) or `corner` (a sector between two sharp edges at a corner,
//! [`crate::bezier::g1::Fan::Corner`]: spokes over a quarter-turn, `T0, T1` are `A, B`
//! themselves; `corner/reflex`: over three quarters, the last spoke along `-B`) or `cone` (a
//! hole closed around a cone point, [`crate::bezier::g1::Fan::Cone`]: `T0 = T1 = 0`, `A, B`
//! are zero rows, `w(0) = 2 cos(pi / SECTORS)`) or `cone/dart` (a dart's fan around a cone
//! point, the same). A line may end in `kept S1 .. S_COUNT`: the complex keeps the patches of
//! those sectors only (in this order), the cap being built whole (non-box beside OpenSubdiv's
//! hole faces). Version 2 added `FAN`; version 1 files are refused.

use super::atomic::write_atomically;
use super::text::{io_error, parse_error};
use super::textout::{ChunkedText, push_f64, push_point};
use crate::bezier::g1::{Centre, CornerAngle, Fan, hole_cap_map};
use crate::error::{Error, Result};
use crate::geom::Point;
use crate::stencil::StencilTable;
use crate::surface::table::{PatchTable, TableCap};
use std::collections::HashMap;
use std::fmt::Write as _;
use std::path::Path;

/// The first line of the format.
pub const MAGIC: &str = "fairsub-patch-table 2";

fn centre_name(c: Centre) -> &'static str {
    match c {
        Centre::QuadraticJet => "quadratic-jet",
        _ => "tangent-plane",
    }
}

/// Writes `table` to `path` atomically (checked first: finite weights and constants).
pub fn write_table(path: &Path, table: &PatchTable) -> Result<()> {
    let rows = table.rows();
    check_finite(table)?;
    let (maps, cap_map_ids) = distinct_cap_maps(table)?;
    write_atomically(path, |w| {
        let mut out = ChunkedText::new(w);
        let io = |e| io_error(path, e);
        let s = &mut out.buf;
        let _ = writeln!(s, "{MAGIC}");
        let _ = writeln!(s, "sources {}", table.num_sources());
        let _ = writeln!(s, "patches {}", table.num_patches());
        let _ = writeln!(s, "rows {}", rows.num_rows());
        let _ = writeln!(s, "entries {}", rows.num_entries());
        let _ = writeln!(s, "caps {}", table.caps().len());
        let _ = writeln!(s, "capmaps {}", maps.len());
        let _ = writeln!(s, "constants {}", u8::from(!table.constants().is_empty()));
        for (p, &(du, dv)) in table.shapes().iter().enumerate() {
            let kind = if table.is_cap_patch(p) {
                "cap"
            } else {
                "linear"
            };
            let group = table.provenance()[p].group_name();
            let _ = writeln!(out.buf, "p {du} {dv} {} {kind} {group}", table.first_row(p));
            out.maybe_flush().map_err(io)?;
        }
        for (cap, id) in table.caps().iter().zip(&cap_map_ids) {
            push_cap_line(&mut out.buf, cap, *id);
        }
        write_cap_maps(&mut out, &maps).map_err(io)?;
        write_rows(&mut out, table).map_err(io)?;
        out.buf.push_str("end\n");
        out.finish().map_err(io)
    })
}

/// Refuses a table with a weight or a constant that is not finite.
fn check_finite(table: &PatchTable) -> Result<()> {
    let rows = table.rows();
    if let Some(r) = (0..rows.num_rows()).find(|&r| rows.row(r).1.iter().any(|w| !w.is_finite())) {
        return Err(Error::InvalidArgument(format!(
            "row {r} of the patch table has a weight that is not finite; nothing written"
        )));
    }
    if table.constants().iter().flatten().any(|x| !x.is_finite()) {
        return Err(Error::InvalidArgument(
            "the patch table has constants that are not finite; nothing written".into(),
        ));
    }
    Ok(())
}

/// One matrix per distinct cap map (valence, layout, degrees, centre and fan), and per cap the
/// number of its map.
fn distinct_cap_maps(
    table: &PatchTable,
) -> Result<(Vec<std::sync::Arc<crate::bezier::g1::CapMap>>, Vec<usize>)> {
    let mut maps: Vec<std::sync::Arc<crate::bezier::g1::CapMap>> = Vec::new();
    let mut map_of: HashMap<(usize, String), usize> = HashMap::new();
    let mut cap_map_ids = Vec::new();
    for cap in table.caps() {
        let hole = &cap.step.hole;
        let (layout, degrees) = hole.layout()?;
        let key = (
            hole.valence(),
            format!(
                "{layout:?}{degrees:?}{}{:?}{:?}",
                cap.degree,
                cap.centre,
                hole.fan()
            ),
        );
        let id = match map_of.get(&key) {
            Some(&id) => id,
            None => {
                maps.push(hole_cap_map(hole, cap.degree, cap.centre)?);
                map_of.insert(key, maps.len() - 1);
                maps.len() - 1
            }
        };
        cap_map_ids.push(id);
    }
    Ok((maps, cap_map_ids))
}

/// The `FAN` word of a cap line.
fn fan_word(fan: Fan) -> String {
    match fan {
        Fan::Closed => "closed".to_string(),
        Fan::Open => "open".to_string(),
        Fan::Crease => "crease".to_string(),
        Fan::Dart => "dart".to_string(),
        Fan::Wedge(m) => format!("wedge/{m}"),
        Fan::Corner(CornerAngle::Convex) => "corner".to_string(),
        Fan::Corner(CornerAngle::Reflex) => "corner/reflex".to_string(),
        Fan::Cone => "cone".to_string(),
        Fan::DartCone => "cone/dart".to_string(),
    }
}

/// A cap's `c` line, with map number `id`.
fn push_cap_line(buf: &mut String, cap: &TableCap, id: usize) {
    let st = &cap.step;
    let shape = cap.shape();
    let _ = write!(
        buf,
        "c {} {} {} {id} {} {} {} {} {}",
        st.first,
        st.count,
        cap.data_row,
        cap.degree,
        centre_name(cap.centre),
        fan_word(st.hole.fan()),
        shape.len(),
        shape.first().map_or(0, Vec::len)
    );
    for (b, c) in shape.iter().flatten() {
        let _ = write!(buf, " {b} {c}");
    }
    if let Some(kept) = &st.kept {
        buf.push_str(" kept");
        for s in kept {
            let _ = write!(buf, " {s}");
        }
    }
    buf.push('\n');
}

/// The cap maps' `m` blocks: a head line, then the matrix row by row.
fn write_cap_maps(
    out: &mut ChunkedText<'_>,
    maps: &[std::sync::Arc<crate::bezier::g1::CapMap>],
) -> std::io::Result<()> {
    for (id, map) in maps.iter().enumerate() {
        let m = map.matrix();
        let _ = writeln!(out.buf, "m {id} {} {} {}", map.n, m.nrows(), m.ncols());
        for i in 0..m.nrows() {
            for j in 0..m.ncols() {
                if j > 0 {
                    out.buf.push(' ');
                }
                push_f64(&mut out.buf, m[(i, j)]);
            }
            out.buf.push('\n');
            out.maybe_flush()?;
        }
    }
    Ok(())
}

/// The table's `r` lines (index-weight pairs) and its `k` lines (constants, when it has them).
fn write_rows(out: &mut ChunkedText<'_>, table: &PatchTable) -> std::io::Result<()> {
    let rows = table.rows();
    for r in 0..rows.num_rows() {
        let (idx, w) = rows.row(r);
        let _ = write!(out.buf, "r {}", idx.len());
        for (&i, &x) in idx.iter().zip(w) {
            let _ = write!(out.buf, " {i} ");
            push_f64(&mut out.buf, x);
        }
        out.buf.push('\n');
        out.maybe_flush()?;
    }
    for &c in table.constants() {
        out.buf.push_str("k ");
        push_point(&mut out.buf, c);
        out.buf.push('\n');
        out.maybe_flush()?;
    }
    Ok(())
}

/// A patch table file as read back: what every line holds, checked for consistency.
#[derive(Debug, Clone, PartialEq)]
pub struct TableFile {
    /// Per patch `(deg_u, deg_v, first_row, is_cap)`.
    pub patches: Vec<(u32, u32, u32, bool)>,
    /// The rows.
    pub rows: StencilTable,
    /// Per cap `(first_patch, count, data_row, map, degree)`.
    pub caps: Vec<(u32, u32, u32, u32, u32)>,
    /// Per cap, the sectors its `count` patches are when the complex keeps only some
    /// (`kept S1 .. S_COUNT` at the end of its line; `None`: all).
    pub cap_sectors: Vec<Option<Vec<u32>>>,
    /// The cap maps' matrices, row major, with `(rows, cols)`.
    pub maps: Vec<((usize, usize), Vec<f64>)>,
    /// The constants (empty when the file has none).
    pub constants: Vec<Point>,
}

/// The lines of a patch table file, numbered from 1, each asked for by what it should hold.
struct TableLines<'a> {
    path: &'a Path,
    text: &'a str,
    lines: std::str::Lines<'a>,
    number: usize,
}

impl<'a> TableLines<'a> {
    /// The next line and its number; at the end of the file an error saying `what` is missing.
    fn next(&mut self, what: &str) -> Result<(usize, &'a str)> {
        match self.lines.next() {
            Some(line) => {
                self.number += 1;
                Ok((self.number, line))
            }
            None => Err(parse_error(
                self.path,
                self.text.lines().count().max(1),
                format!("missing {what}"),
            )),
        }
    }

    /// A header line `key COUNT`.
    fn header(&mut self, key: &str) -> Result<usize> {
        let (l, line) = self.next(key)?;
        let mut w = line.split_whitespace();
        match (
            w.next(),
            w.next().and_then(|x| x.parse::<usize>().ok()),
            w.next(),
        ) {
            (Some(k), Some(v), None) if k == key => Ok(v),
            _ => Err(parse_error(self.path, l, format!("expected '{key} COUNT'"))),
        }
    }

    /// The numbers of line `l`, which starts with `tag`.
    fn nums(&self, l: usize, line: &str, tag: &str) -> Result<Vec<f64>> {
        let path = self.path;
        let mut w = line.split_whitespace();
        if w.next() != Some(tag) {
            return Err(parse_error(path, l, format!("expected a '{tag}' line")));
        }
        w.map(|x| {
            x.parse::<f64>()
                .map_err(|_| parse_error(path, l, format!("'{x}' is not a number")))
        })
        .collect()
    }
}

/// Reads a patch table file, naming the line of any error.
pub fn read_table(path: &Path) -> Result<TableFile> {
    let text = super::read_text(path)?;
    let mut lines = TableLines {
        path,
        text: &text,
        lines: text.lines(),
        number: 0,
    };
    let (l, first) = lines.next("the first line")?;
    if first.trim() != MAGIC {
        return Err(parse_error(path, l, format!("expected '{MAGIC}'")));
    }
    let sources = lines.header("sources")?;
    let npatches = lines.header("patches")?;
    let nrows = lines.header("rows")?;
    let nentries = lines.header("entries")?;
    let ncaps = lines.header("caps")?;
    let nmaps = lines.header("capmaps")?;
    let has_constants = lines.header("constants")?;
    if sources > u32::MAX as usize || nrows > u32::MAX as usize || has_constants > 1 {
        return Err(parse_error(path, 2, "counts out of range"));
    }
    let patches = read_patch_lines(&mut lines, npatches, nrows)?;
    let (mut caps, mut cap_sectors) = (Vec::new(), Vec::new());
    for _ in 0..ncaps {
        let (cap, kept) = read_cap_line(&mut lines, nmaps)?;
        caps.push(cap);
        cap_sectors.push(kept);
    }
    let mut maps = Vec::new();
    for _ in 0..nmaps {
        maps.push(read_cap_map(&mut lines)?);
    }
    let rows = read_rows(&mut lines, sources, nrows)?;
    if rows.num_entries() != nentries {
        return Err(parse_error(
            path,
            5,
            format!("{} entries, not {nentries}", rows.num_entries()),
        ));
    }
    let mut constants = Vec::new();
    if has_constants == 1 {
        for _ in 0..nrows {
            let (l, line) = lines.next("a constant")?;
            let v = lines.nums(l, line, "k")?;
            if v.len() != 3 {
                return Err(parse_error(path, l, "expected 'k X Y Z'"));
            }
            constants.push([v[0], v[1], v[2]]);
        }
    }
    let (l, end) = lines.next("'end'")?;
    if end.trim() != "end" {
        return Err(parse_error(path, l, "expected 'end'"));
    }
    Ok(TableFile {
        patches,
        rows,
        caps,
        cap_sectors,
        maps,
        constants,
    })
}

/// The `p` lines of `npatches` patches, each with its rows inside the table's `nrows`.
fn read_patch_lines(
    lines: &mut TableLines<'_>,
    npatches: usize,
    nrows: usize,
) -> Result<Vec<(u32, u32, u32, bool)>> {
    let path = lines.path;
    let mut patches = Vec::with_capacity(npatches.min(1 << 24));
    for _ in 0..npatches {
        let (l, line) = lines.next("a patch line")?;
        let w: Vec<&str> = line.split_whitespace().collect();
        let parse = |x: &str| x.parse::<u32>().ok();
        match w.as_slice() {
            ["p", du, dv, first, kind, _group] => {
                let (Some(du), Some(dv), Some(first)) = (parse(du), parse(dv), parse(first)) else {
                    return Err(parse_error(path, l, "bad patch line"));
                };
                let end = first as u64 + (du as u64 + 1) * (dv as u64 + 1);
                if end > nrows as u64 || !matches!(*kind, "linear" | "cap") {
                    return Err(parse_error(path, l, "patch rows out of range or bad kind"));
                }
                patches.push((du, dv, first, *kind == "cap"));
            }
            _ => return Err(parse_error(path, l, "expected 'p DU DV FIRST KIND GROUP'")),
        }
    }
    Ok(patches)
}

/// A cap line's `(first_patch, count, data_row, map, degree)`.
type CapNumbers = (u32, u32, u32, u32, u32);

/// A cap's `c` line: `(first_patch, count, data_row, map, degree)` (the map one of `nmaps`)
/// and its `kept` sectors, if any.
fn read_cap_line(
    lines: &mut TableLines<'_>,
    nmaps: usize,
) -> Result<(CapNumbers, Option<Vec<u32>>)> {
    let path = lines.path;
    let (l, line) = lines.next("a cap line")?;
    let (line, kept) = match line.split_once(" kept") {
        Some((head, kept)) => {
            let kept: Vec<u32> = kept
                .split_whitespace()
                .map(str::parse)
                .collect::<std::result::Result<_, _>>()
                .map_err(|_| parse_error(path, l, "bad 'kept' sectors"))?;
            (head, Some(kept))
        }
        None => (line, None),
    };
    let w: Vec<&str> = line.split_whitespace().collect();
    let v: Vec<u32> = w
        .iter()
        .enumerate()
        .filter(|&(i, _)| i != 0 && i != 6 && i != 7)
        .map(|(_, x)| x.parse::<u32>())
        .collect::<std::result::Result<_, _>>()
        .map_err(|_| parse_error(path, l, "bad cap line"))?;
    if w.first() != Some(&"c")
        || v.len() < 7
        || v[3] as usize >= nmaps.max(1)
        || !w.get(7).is_some_and(|f| is_fan_word(f))
    {
        return Err(parse_error(
            path,
            l,
            "expected 'c FIRST COUNT ROW MAP DEGREE CENTRE FAN ...' (FAN: open, closed, \
             crease, dart, corner, corner/reflex, cone, cone/dart or wedge/M)",
        ));
    }
    if kept.as_ref().is_some_and(|k| k.len() != v[1] as usize) {
        return Err(parse_error(
            path,
            l,
            "expected one 'kept' sector per cap patch",
        ));
    }
    Ok(((v[0], v[1], v[2], v[3], v[4]), kept))
}

/// A cap map's `m` block: its `(rows, cols)` and its numbers, row major.
fn read_cap_map(lines: &mut TableLines<'_>) -> Result<((usize, usize), Vec<f64>)> {
    let path = lines.path;
    let (l, line) = lines.next("a cap map")?;
    let h = lines.nums(l, line, "m")?;
    if h.len() != 4 || h[2] * h[3] > 1e8 {
        return Err(parse_error(path, l, "expected 'm ID VALENCE ROWS COLS'"));
    }
    let (r, c) = (h[2] as usize, h[3] as usize);
    let mut data = Vec::with_capacity(r * c);
    for _ in 0..r {
        let (l, line) = lines.next("a cap map row")?;
        let row: Vec<f64> = line
            .split_whitespace()
            .map(|x| {
                x.parse::<f64>()
                    .map_err(|_| parse_error(path, l, "bad number"))
            })
            .collect::<Result<_>>()?;
        if row.len() != c {
            return Err(parse_error(path, l, format!("expected {c} numbers")));
        }
        data.extend(row);
    }
    Ok(((r, c), data))
}

/// The `nrows` `r` lines: index-weight pairs over `sources` control points.
fn read_rows(lines: &mut TableLines<'_>, sources: usize, nrows: usize) -> Result<StencilTable> {
    let path = lines.path;
    let mut rows = StencilTable::with_capacity(sources, nrows.min(1 << 24), 16);
    for _ in 0..nrows {
        let (l, line) = lines.next("a row")?;
        let v = lines.nums(l, line, "r")?;
        let k = v.first().copied().unwrap_or(-1.0);
        if k < 0.0 || v.len() != 1 + 2 * k as usize {
            return Err(parse_error(
                path,
                l,
                "expected 'r K' and K index-weight pairs",
            ));
        }
        let mut pairs = Vec::with_capacity(k as usize);
        for pair in v[1..].chunks(2) {
            let i = pair[0];
            if i < 0.0 || i >= sources as f64 || i.fract() != 0.0 || !pair[1].is_finite() {
                return Err(parse_error(path, l, format!("bad source {i} or weight")));
            }
            pairs.push((i as u32, pair[1]));
        }
        rows.push_pairs(&pairs);
    }
    Ok(rows)
}

/// Whether `w` is a `FAN` word of a cap line: `open`, `closed`, `crease`, `dart`, `corner`,
/// `corner/reflex`, `cone`, `cone/dart` or `wedge/M`
/// with a whole number `M >= 1`.
fn is_fan_word(w: &str) -> bool {
    match w.strip_prefix("wedge/") {
        Some(m) => m.parse::<usize>().is_ok_and(|m| m >= 1),
        None => matches!(
            w,
            "open"
                | "closed"
                | "crease"
                | "dart"
                | "corner"
                | "corner/reflex"
                | "cone"
                | "cone/dart"
        ),
    }
}
