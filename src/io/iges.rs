//! IGES 5.3 output: one rational B-spline surface entity (type 128) per Bezier patch, and a
//! validating reader for exactly such files.
//!
//! # What is written
//!
//! An IGES file is a sequence of 80-column ASCII records in five sections, each record ending
//! with its section letter (column 73) and its sequence number within the section (74-80):
//!
//! * **Start (S)**: free text (columns 1-72) saying what the file holds.
//! * **Global (G)**: 25 parameters, `,` as parameter and `;` as record delimiter, strings as
//!   Hollerith constants `nH...`: delimiters, product id (the file stem), file name, native system
//!   id `fairsub`, preprocessor version, 32 integer bits, single precision 38 / 6 and double
//!   precision 308 / 15 (max power of ten / significant digits), receiver product id, model
//!   scale 1.0, **unit flag 2 = millimetres** (`2HMM`; fairsub coordinates are unitless, and a
//!   CAD system needs *some* unit, so one model unit is one millimetre), 1 line-weight gradation,
//!   max line width 1.0, generation date `15HYYYYMMDD.HHNNSS` (UTC; `SOURCE_DATE_EPOCH` is
//!   honoured for reproducible output), minimum resolution `1e-6 * max(1, max |coordinate|)`,
//!   max coordinate, author and organisation left empty (their default), **version flag 11
//!   (IGES 5.3)**, drafting standard 0 (none), model date (= generation date). The optional 26th
//!   parameter (application protocol) is omitted. Strings are ASCII, at most 60 characters, and
//!   no parameter is split across records.
//! * **Directory entry (D)**: two records per entity, ten 8-column fields each: entity type
//!   128, pointer to the first parameter record, structure 0, line font 0, level 0, view 0,
//!   transformation 0, label display 0, status `00000000` (visible, independent, geometry,
//!   top-down); then 128, line weight 0, colour 0, parameter record count, form 0, two reserved
//!   blank fields, entity label (the provenance group name, at most 8 characters) and entity
//!   subscript (1-based number of the patch within its group).
//! * **Parameter data (P)**: the entity's free-format parameters in columns 1-64, column 65
//!   blank, the directory entry's sequence number in 66-72.
//! * **Terminate (T)**: one record with the record counts `S0000001G0000003D...P...`.
//!
//! Entity 128 (IGES 5.3 section 4.24) holds `K1, K2` (upper indices of the sums, here the
//! degrees), `M1, M2` (degrees), `PROP1..5` = `0, 0, 1, 0, 0` (open, polynomial, non-periodic),
//! the knots `S(-M1)..S(N1+M1)` and `T(-M2)..T(N2+M2)` (here `0` repeated `deg+1` times, then
//! `1` repeated `deg+1` times: a single Bezier span), the weights `W(0,0), W(1,0), ...` (all 1),
//! the control points `X(0,0), Y(0,0), Z(0,0), X(1,0), ...` and the parameter range `U(0),
//! U(1), V(0), V(1)` = `0, 1, 0, 1`. In both the weights and the control points the *first*
//! index (along u) varies fastest (as in OpenCASCADE's `IGESGeom_ToolBSplineSurface`), so
//! fairsub's `b[i][j]` (stored row-major, `j` fastest) is written in the order `j` outer,
//! `i` inner. Reals are written in shortest round-trip form with a `D` exponent
//! (`-1.25D-3`, `1.0D0`), so coefficients read back bit for bit. A patch of degree 0 in a
//! direction is written degree-raised to 1 (exactly), since CAD systems expect degree >= 1.

use super::bv::check_complex;
use super::{io_error, parse_error, write_atomically};
use crate::bezier::BezierPatch;
use crate::error::{Error, Result};
use crate::surface::{PatchComplex, Provenance};
use std::path::Path;

/// Keeps an ASCII string of safe characters for a Hollerith constant or label.
fn sanitize(s: &str, max: usize) -> String {
    s.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || matches!(c, '.' | '_' | '-') {
                c
            } else {
                '_'
            }
        })
        .take(max)
        .collect()
}

/// A Hollerith string constant `nH...`.
fn hollerith(s: &str) -> String {
    format!("{}H{s}", s.len())
}

/// An IGES real constant: shortest round-trip digits, always with a decimal point, `D`
/// exponent.
pub(crate) fn iges_real(x: f64) -> String {
    let s = format!("{x:E}");
    let (mant, exp) = s.split_once('E').unwrap_or((&s, "0"));
    if mant.contains('.') {
        format!("{mant}D{exp}")
    } else {
        format!("{mant}.0D{exp}")
    }
}

/// Days since 1970-01-01 to (year, month, day), proleptic Gregorian (H. Hinnant's algorithm).
fn civil_from_days(z: i64) -> (i64, u32, u32) {
    let z = z + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097);
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let y = yoe + era * 400;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = (doy - (153 * mp + 2) / 5 + 1) as u32;
    let m = if mp < 10 { mp + 3 } else { mp - 9 } as u32;
    (if m <= 2 { y + 1 } else { y }, m, d)
}

/// `YYYYMMDD.HHNNSS` (UTC) of a Unix time.
fn iges_date(unix_secs: i64) -> String {
    let (y, mo, d) = civil_from_days(unix_secs.div_euclid(86_400));
    let s = unix_secs.rem_euclid(86_400);
    format!(
        "{y:04}{mo:02}{d:02}.{:02}{:02}{:02}",
        s / 3600,
        s / 60 % 60,
        s % 60
    )
}

/// The file date: `SOURCE_DATE_EPOCH` when set (reproducible builds), else now.
fn now_date() -> String {
    let secs = std::env::var("SOURCE_DATE_EPOCH")
        .ok()
        .and_then(|v| v.trim().parse::<i64>().ok())
        .unwrap_or_else(|| {
            std::time::SystemTime::now()
                .duration_since(std::time::UNIX_EPOCH)
                .map(|d| d.as_secs() as i64)
                .unwrap_or(0)
        });
    iges_date(secs)
}

/// Accumulates the records of one section.
struct Section {
    letter: char,
    lines: Vec<String>,
}

impl Section {
    fn new(letter: char) -> Self {
        Section {
            letter,
            lines: Vec::new(),
        }
    }

    /// Adds a record: `body` (at most 72 columns) padded, then letter and sequence number.
    fn push(&mut self, body: &str) {
        debug_assert!(body.len() <= 72 && body.is_ascii());
        let seq = self.lines.len() + 1;
        self.lines
            .push(format!("{body:<72}{}{seq:>7}", self.letter));
    }

    /// Adds free-format parameters, wrapped at `width` columns without splitting one; each
    /// record gets `suffix` (the DE pointer for P records) before column 73.
    fn push_params(&mut self, params: &[String], width: usize, suffix: &str) -> usize {
        let start = self.lines.len();
        let mut cur = String::new();
        for p in params {
            if !cur.is_empty() && cur.len() + p.len() > width {
                self.push(&format!("{cur:<width$}{suffix}"));
                cur.clear();
            }
            cur.push_str(p);
        }
        if !cur.is_empty() {
            self.push(&format!("{cur:<width$}{suffix}"));
        }
        self.lines.len() - start
    }
}

/// Appends `,` to every parameter but the last, which gets `;`.
fn delimited(mut params: Vec<String>) -> Vec<String> {
    let n = params.len();
    for (k, p) in params.iter_mut().enumerate() {
        p.push(if k + 1 == n { ';' } else { ',' });
    }
    params
}

/// Raises a degree-0 direction to degree 1 (exact: the coefficient is repeated).
fn at_least_linear(p: &BezierPatch) -> BezierPatch {
    let (du, dv) = (p.deg_u.max(1), p.deg_v.max(1));
    let mut cps = Vec::with_capacity((du + 1) * (dv + 1));
    for i in 0..=du {
        for j in 0..=dv {
            cps.push(p.cp(i.min(p.deg_u), j.min(p.deg_v)));
        }
    }
    BezierPatch {
        deg_u: du,
        deg_v: dv,
        cps,
    }
}

/// The parameters of entity 128 for a Bezier patch.
fn entity_128(p: &BezierPatch) -> Vec<String> {
    let p = if p.deg_u == 0 || p.deg_v == 0 {
        at_least_linear(p)
    } else {
        p.clone()
    };
    let (du, dv) = (p.deg_u, p.deg_v);
    let mut v: Vec<String> = [
        "128",
        &du.to_string(),
        &dv.to_string(),
        &du.to_string(),
        &dv.to_string(),
        "0",
        "0",
        "1",
        "0",
        "0",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    for d in [du, dv] {
        v.extend(std::iter::repeat_n("0.0".to_string(), d + 1));
        v.extend(std::iter::repeat_n("1.0".to_string(), d + 1));
    }
    v.extend(std::iter::repeat_n("1.0".to_string(), (du + 1) * (dv + 1)));
    for j in 0..=dv {
        for i in 0..=du {
            for c in p.cp(i, j) {
                v.push(iges_real(c));
            }
        }
    }
    for x in ["0.0", "1.0", "0.0", "1.0"] {
        v.push(x.to_string());
    }
    v
}

/// The IGES text for a patch complex; `file_name` goes into the global section.
pub fn iges_to_string(complex: &PatchComplex, file_name: &str) -> Result<String> {
    iges_text(complex, file_name, &now_date())
}

fn iges_text(complex: &PatchComplex, file_name: &str, date: &str) -> Result<String> {
    check_complex(complex)?;
    let n = complex.len();

    let mut s = Section::new('S');
    s.push(&format!(
        "fairsub {}: {n} Bezier patches as IGES 5.3 entity 128 surfaces",
        env!("CARGO_PKG_VERSION")
    ));
    s.push("(polynomial B-splines with one span each). Model units: millimetres.");

    let max_coord = complex
        .patches
        .iter()
        .flat_map(|p| p.cps.iter())
        .flat_map(|q| q.iter())
        .fold(0.0f64, |m, x| m.max(x.abs()));
    let name = sanitize(file_name, 60);
    let stem = sanitize(
        Path::new(file_name)
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or("fairsub"),
        60,
    );
    let stem = if stem.is_empty() {
        "fairsub".to_string()
    } else {
        stem
    };
    let name = if name.is_empty() { stem.clone() } else { name };
    let global = vec![
        hollerith(","),
        hollerith(";"),
        hollerith(&stem),
        hollerith(&name),
        hollerith("fairsub"),
        hollerith(&format!("fairsub {}", env!("CARGO_PKG_VERSION"))),
        "32".into(),
        "38".into(),
        "6".into(),
        "308".into(),
        "15".into(),
        hollerith(&stem),
        "1.0".into(),
        "2".into(),
        hollerith("MM"),
        "1".into(),
        "1.0".into(),
        hollerith(date),
        iges_real(1e-6 * max_coord.max(1.0)),
        iges_real(max_coord),
        String::new(),
        String::new(),
        "11".into(),
        "0".into(),
        hollerith(date),
    ];
    let mut g = Section::new('G');
    g.push_params(&delimited(global), 72, "");

    let mut d = Section::new('D');
    let mut p = Section::new('P');
    let mut group_names: Vec<String> = Vec::new();
    let mut group_counts: Vec<usize> = Vec::new();
    for (patch, prov) in complex.patches.iter().zip(&complex.provenance) {
        let gname = prov.group_name();
        let gk = match group_names.iter().position(|x| *x == gname) {
            Some(k) => k,
            None => {
                group_names.push(gname.clone());
                group_counts.push(0);
                group_names.len() - 1
            }
        };
        group_counts[gk] += 1;
        let label = sanitize(&gname, 8);
        let de_seq = d.lines.len() + 1;
        let p_start = p.lines.len() + 1;
        let count = p.push_params(&delimited(entity_128(patch)), 64, &format!(" {de_seq:>7}"));
        d.push(&format!(
            "{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}",
            128, p_start, 0, 0, 0, 0, 0, 0, "00000000"
        ));
        d.push(&format!(
            "{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}",
            128, 0, 0, count, 0, "", "", label, group_counts[gk]
        ));
    }
    let mut t = Section::new('T');
    t.push(&format!(
        "S{:07}G{:07}D{:07}P{:07}",
        s.lines.len(),
        g.lines.len(),
        d.lines.len(),
        p.lines.len()
    ));
    let mut out = String::with_capacity(
        81 * (s.lines.len() + g.lines.len() + d.lines.len() + p.lines.len() + 1),
    );
    for sec in [&s, &g, &d, &p, &t] {
        for l in &sec.lines {
            out.push_str(l);
            out.push('\n');
        }
    }
    Ok(out)
}

/// Writes a patch complex as an IGES 5.3 file (atomically).
pub fn write_iges(path: &Path, complex: &PatchComplex) -> Result<()> {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let text = iges_to_string(complex, &name)?;
    write_atomically(path, |w| {
        w.write_all(text.as_bytes()).map_err(|e| io_error(path, e))
    })
}

// ---------------------------------------------------------------------------------------------
// Reading

/// Reads an IGES file of entity-128 Bezier surfaces (see [`parse_iges`]).
pub fn read_iges(path: &Path) -> Result<PatchComplex> {
    let bytes = std::fs::read(path).map_err(|e| io_error(path, e))?;
    let text = String::from_utf8_lossy(&bytes);
    parse_iges(&text, path)
}

/// Splits free-format IGES data into parameters, honouring Hollerith strings; stops at the
/// record delimiter. Returns `None` when the record delimiter is missing or a string is cut.
fn split_params(data: &str, pd: char, rd: char) -> std::result::Result<Vec<String>, String> {
    let b: Vec<char> = data.chars().collect();
    let mut params = Vec::new();
    let mut k = 0;
    loop {
        // One parameter: optional blanks, then a Hollerith string or plain text.
        while k < b.len() && b[k] == ' ' {
            k += 1;
        }
        let mut j = k;
        while j < b.len() && b[j].is_ascii_digit() {
            j += 1;
        }
        let value;
        if j > k && j < b.len() && b[j] == 'H' {
            let n: usize = b[k..j]
                .iter()
                .collect::<String>()
                .parse()
                .map_err(|_| "bad Hollerith count".to_string())?;
            let end = j + 1 + n;
            if end > b.len() {
                return Err(format!("Hollerith string {}H runs past the data", n));
            }
            value = b[j + 1..end].iter().collect::<String>();
            k = end;
            while k < b.len() && b[k] == ' ' {
                k += 1;
            }
        } else {
            let mut e = k;
            while e < b.len() && b[e] != pd && b[e] != rd {
                e += 1;
            }
            value = b[k..e].iter().collect::<String>().trim().to_string();
            k = e;
        }
        params.push(value);
        match b.get(k) {
            Some(&c) if c == pd => k += 1,
            Some(&c) if c == rd => return Ok(params),
            Some(&c) => return Err(format!("unexpected '{c}' after parameter {}", params.len())),
            None => return Err("the record delimiter is missing".to_string()),
        }
    }
}

fn parse_real(s: &str) -> Option<f64> {
    let t: String = s
        .trim()
        .chars()
        .map(|c| if c == 'D' || c == 'd' { 'E' } else { c })
        .collect();
    t.parse::<f64>().ok().filter(|x| x.is_finite())
}

/// One directory entry as read.
struct DirEntry {
    line: usize,
    seq: usize,
    entity: i64,
    p_start: usize,
    p_count: usize,
}

/// Parses IGES text holding entity-128 surfaces back into Bezier patches (with
/// [`Provenance::Unknown`]); `path` is used in messages only.
///
/// Checks the file structure strictly: every record has exactly 80 columns, sections come in the
/// order S, G, D, P, T with letters in column 73 and consecutive sequence numbers, the global
/// section parses, directory entries come in pairs whose two entity numbers agree, each entry's
/// parameter pointer and record count lie inside the P section, every P record carries the
/// sequence number of the entry that owns it and belongs to exactly one entry, and the T
/// record's counts match. Entity 128 surfaces must have a single span (`K = M`), clamped knots,
/// equal weights and the full parameter range; other entity types are rejected as unsupported.
pub fn parse_iges(text: &str, path: &Path) -> Result<PatchComplex> {
    let mut lines: Vec<&str> = text.split('\n').collect();
    if lines.last().is_some_and(|l| l.is_empty()) {
        lines.pop();
    }
    const ORDER: [char; 5] = ['S', 'G', 'D', 'P', 'T'];
    let mut sections: [Vec<usize>; 5] = Default::default(); // file line indices per section
    let mut current = 0usize;
    for (i, raw) in lines.iter().enumerate() {
        let line_no = i + 1;
        let l = raw.strip_suffix('\r').unwrap_or(raw);
        if !l.is_ascii() {
            return Err(parse_error(
                path,
                line_no,
                "non-ASCII character in an IGES record",
            ));
        }
        if l.len() != 80 {
            return Err(parse_error(
                path,
                line_no,
                format!(
                    "record has {} columns; IGES records have exactly 80",
                    l.len()
                ),
            ));
        }
        let letter = l.as_bytes()[72] as char;
        let Some(sec) = ORDER.iter().position(|&c| c == letter) else {
            return Err(match letter {
                'C' | 'B' => Error::Unsupported(format!(
                    "{}:{line_no}: compressed or binary IGES is not supported",
                    path.display()
                )),
                _ => parse_error(
                    path,
                    line_no,
                    format!("column 73 holds '{letter}', not a section letter (S, G, D, P, T)"),
                ),
            });
        };
        if sec < current {
            return Err(parse_error(
                path,
                line_no,
                format!(
                    "'{letter}' record after the {} section: sections must come in the order S, G, D, P, T",
                    ORDER[current]
                ),
            ));
        }
        current = sec;
        let seq_text = l[73..80].trim();
        let expected = sections[sec].len() + 1;
        match seq_text.parse::<usize>() {
            Ok(s) if s == expected => {}
            _ => {
                return Err(parse_error(
                    path,
                    line_no,
                    format!(
                        "sequence number '{seq_text}' in columns 74-80; expected {expected} ({letter} records are numbered 1, 2, ...)"
                    ),
                ));
            }
        }
        sections[sec].push(i);
    }
    let [s_lines, g_lines, d_lines, p_lines, t_lines] = &sections;
    let rec = |i: usize| lines[i].strip_suffix('\r').unwrap_or(lines[i]);
    if s_lines.is_empty() || g_lines.is_empty() {
        return Err(parse_error(
            path,
            1,
            "an IGES file starts with Start (S) and Global (G) records",
        ));
    }
    if t_lines.len() != 1 {
        return Err(parse_error(
            path,
            lines.len(),
            format!(
                "expected exactly one Terminate (T) record at the end, found {}",
                t_lines.len()
            ),
        ));
    }
    // Terminate counts.
    let t = rec(t_lines[0]);
    let t_line_no = t_lines[0] + 1;
    for (k, (letter, actual)) in [
        ('S', s_lines.len()),
        ('G', g_lines.len()),
        ('D', d_lines.len()),
        ('P', p_lines.len()),
    ]
    .into_iter()
    .enumerate()
    {
        let field = &t[8 * k..8 * k + 8];
        let ok =
            field.starts_with(letter) && field[1..].trim().parse::<usize>().ok() == Some(actual);
        if !ok {
            return Err(parse_error(
                path,
                t_line_no,
                format!(
                    "terminate record field {} is '{field}' but the file has {actual} {letter} records",
                    k + 1
                ),
            ));
        }
    }
    // Global section.
    let gtext: String = g_lines.iter().map(|&i| &rec(i)[..72]).collect();
    let g0 = g_lines[0] + 1;
    let (pd, rd) = global_delimiters(&gtext).map_err(|m| parse_error(path, g0, m))?;
    let global = split_params(&gtext, pd, rd)
        .map_err(|m| parse_error(path, g0, format!("global section: {m}")))?;
    if global.len() < 23 {
        return Err(parse_error(
            path,
            g0,
            format!(
                "global section has {} parameters; IGES 5.3 requires at least 23",
                global.len()
            ),
        ));
    }
    // Directory entries.
    if d_lines.len() % 2 != 0 {
        return Err(parse_error(
            path,
            d_lines[d_lines.len() - 1] + 1,
            format!(
                "the D section has {} records; directory entries are pairs of records",
                d_lines.len()
            ),
        ));
    }
    let np = p_lines.len();
    let p_owner: Vec<usize> = p_lines
        .iter()
        .map(|&i| rec(i)[65..72].trim().parse::<usize>().unwrap_or(0))
        .collect();
    let mut claimed = vec![false; np];
    let mut entries = Vec::with_capacity(d_lines.len() / 2);
    for e in 0..d_lines.len() / 2 {
        let (a, b) = (rec(d_lines[2 * e]), rec(d_lines[2 * e + 1]));
        let line = d_lines[2 * e] + 1;
        let seq = 2 * e + 1;
        let field = |r: &str, k: usize| r[8 * k..8 * k + 8].trim().to_string();
        let int = |r: &str, k: usize, l: usize| -> Result<i64> {
            let f = field(r, k);
            if f.is_empty() {
                return Ok(0);
            }
            f.parse::<i64>().map_err(|_| {
                parse_error(
                    path,
                    l,
                    format!(
                        "directory entry field {} is '{f}', not an integer",
                        k + 1 + if l == line { 0 } else { 10 }
                    ),
                )
            })
        };
        let entity = int(a, 0, line)?;
        let entity2 = int(b, 0, line + 1)?;
        if entity != entity2 {
            return Err(parse_error(
                path,
                line + 1,
                format!(
                    "directory entry {seq}: entity type {entity} in its first record but {entity2} in its second"
                ),
            ));
        }
        let p_start = int(a, 1, line)?;
        let p_count = int(b, 3, line + 1)?;
        if p_start < 1 || p_start as usize > np {
            return Err(parse_error(
                path,
                line,
                format!(
                    "directory entry {seq}: parameter data pointer {p_start} is outside the P section (1..={np})"
                ),
            ));
        }
        if p_count < 1 || (p_start + p_count - 1) as usize > np {
            return Err(parse_error(
                path,
                line + 1,
                format!(
                    "directory entry {seq}: parameter record count {p_count} from record {p_start} runs past the P section ({np} records)"
                ),
            ));
        }
        let (p_start, p_count) = (p_start as usize, p_count as usize);
        for q in p_start - 1..p_start - 1 + p_count {
            if p_owner[q] != seq {
                return Err(parse_error(
                    path,
                    p_lines[q] + 1,
                    format!(
                        "parameter record {} names directory entry {} in columns 66-72, but directory entry {seq} (line {line}) points to it",
                        q + 1,
                        p_owner[q]
                    ),
                ));
            }
            if claimed[q] {
                return Err(parse_error(
                    path,
                    p_lines[q] + 1,
                    format!(
                        "parameter record {} belongs to two directory entries",
                        q + 1
                    ),
                ));
            }
            claimed[q] = true;
        }
        entries.push(DirEntry {
            line,
            seq,
            entity,
            p_start,
            p_count,
        });
    }
    if let Some(q) = claimed.iter().position(|c| !c) {
        return Err(parse_error(
            path,
            p_lines[q] + 1,
            format!("parameter record {} belongs to no directory entry", q + 1),
        ));
    }
    // Entities.
    let mut out = PatchComplex::new();
    for e in &entries {
        let first = p_lines[e.p_start - 1] + 1;
        if e.entity != 128 {
            return Err(Error::Unsupported(format!(
                "{}:{}: entity type {} (directory entry {}) is not supported; only entity 128 (B-spline surface) is read",
                path.display(),
                e.line,
                e.entity,
                e.seq
            )));
        }
        let data: String = (e.p_start - 1..e.p_start - 1 + e.p_count)
            .map(|q| &rec(p_lines[q])[..64])
            .collect();
        let params = split_params(&data, pd, rd).map_err(|m| {
            parse_error(
                path,
                first,
                format!("entity 128 (directory entry {}): {m}", e.seq),
            )
        })?;
        let patch = surface_128(&params).map_err(|m| match m {
            Bad::Parse(m) => parse_error(
                path,
                first,
                format!("entity 128 (directory entry {}): {m}", e.seq),
            ),
            Bad::Unsupported(m) => Error::Unsupported(format!(
                "{}:{first}: entity 128 (directory entry {}): {m}",
                path.display(),
                e.seq
            )),
        })?;
        out.push(patch, Provenance::Unknown);
    }
    Ok(out)
}

/// The parameter and record delimiters declared at the start of the global section.
fn global_delimiters(g: &str) -> std::result::Result<(char, char), String> {
    let c: Vec<char> = g.chars().collect();
    let mut k = 0;
    let mut pd = ',';
    if c.len() >= 3 && c[0] == '1' && c[1] == 'H' {
        pd = c[2];
        k = 3;
    }
    match c.get(k) {
        Some(&x) if x == pd => k += 1,
        _ => {
            return Err(
                "global section must start with the parameter delimiter (e.g. '1H,,')".into(),
            );
        }
    }
    let mut rd = ';';
    if c.len() >= k + 3 && c[k] == '1' && c[k + 1] == 'H' {
        rd = c[k + 2];
    }
    if pd == rd {
        return Err("parameter and record delimiters are the same character".into());
    }
    Ok((pd, rd))
}

enum Bad {
    Parse(String),
    Unsupported(String),
}

/// Converts the parameters of entity 128 into a Bezier patch.
fn surface_128(params: &[String]) -> std::result::Result<BezierPatch, Bad> {
    let mut k = 0usize;
    let mut next = |what: &str| -> std::result::Result<&str, Bad> {
        let p = params.get(k).ok_or_else(|| {
            Bad::Parse(format!("parameters end at {k} where {what} was expected"))
        })?;
        k += 1;
        Ok(p.as_str())
    };
    let ty = next("the entity type")?;
    if ty.trim() != "128" {
        return Err(Bad::Parse(format!(
            "parameter data starts with '{ty}', not 128"
        )));
    }
    let mut int = |what: &str, max: i64| -> std::result::Result<usize, Bad> {
        let s = next(what)?;
        match s.trim().parse::<i64>() {
            Ok(v) if (0..=max).contains(&v) => Ok(v as usize),
            _ => Err(Bad::Parse(format!(
                "{what} is '{s}'; expected an integer in 0..={max}"
            ))),
        }
    };
    let k1 = int("K1", 10_000)?;
    let k2 = int("K2", 10_000)?;
    let m1 = int("M1", 64)?;
    let m2 = int("M2", 64)?;
    let mut props = [0usize; 5];
    for (n, p) in props.iter_mut().enumerate() {
        *p = int(&format!("PROP{}", n + 1), 1)?;
    }
    if k1 != m1 || k2 != m2 {
        return Err(Bad::Unsupported(format!(
            "B-spline surface with K1 = {k1}, M1 = {m1}, K2 = {k2}, M2 = {m2} has several spans; only single-span (Bezier) surfaces are read"
        )));
    }
    let mut real = |what: &str| -> std::result::Result<f64, Bad> {
        let s = next(what)?;
        parse_real(s).ok_or_else(|| Bad::Parse(format!("{what} is '{s}', not a real number")))
    };
    let mut knots = |m: usize, name: &str| -> std::result::Result<(f64, f64), Bad> {
        let v: Vec<f64> = (0..2 * m + 2)
            .map(|q| real(&format!("knot {name}({})", q as i64 - m as i64)))
            .collect::<std::result::Result<_, _>>()?;
        let (a, b) = (v[0], v[2 * m + 1]);
        let clamped = v[..=m].iter().all(|&x| x == a) && v[m + 1..].iter().all(|&x| x == b);
        if !clamped || a >= b {
            return Err(Bad::Unsupported(format!(
                "knots {name} = {v:?} are not those of one Bezier span (a repeated {} times, then b > a)",
                m + 1
            )));
        }
        Ok((a, b))
    };
    let (s0, s1) = knots(m1, "S")?;
    let (t0, t1) = knots(m2, "T")?;
    let n = (k1 + 1) * (k2 + 1);
    let mut w0 = None;
    for q in 0..n {
        let w = real(&format!("weight {q}"))?;
        let w0 = *w0.get_or_insert(w);
        if w <= 0.0 || (w - w0).abs() > 1e-12 * w0 {
            return Err(Bad::Unsupported(format!(
                "weights {w0} and {w} differ (or are not positive): rational surfaces are not read"
            )));
        }
    }
    let mut pts = vec![[0.0; 3]; n];
    for (q, pt) in pts.iter_mut().enumerate() {
        for (c, x) in pt.iter_mut().enumerate() {
            *x = real(&format!(
                "coordinate {} of control point {q}",
                ["X", "Y", "Z"][c]
            ))?;
        }
    }
    let range = [real("U(0)")?, real("U(1)")?, real("V(0)")?, real("V(1)")?];
    let close = |x: f64, y: f64| (x - y).abs() <= 1e-12 * (1.0 + x.abs().max(y.abs()));
    if !(close(range[0], s0) && close(range[1], s1) && close(range[2], t0) && close(range[3], t1)) {
        return Err(Bad::Unsupported(format!(
            "parameter range {range:?} is not the full knot range [{s0}, {s1}] x [{t0}, {t1}]"
        )));
    }
    // Control point (i, j) is number j * (K1 + 1) + i; fairsub stores b[i][j] at i * (K2+1) + j.
    let mut cps = vec![[0.0; 3]; n];
    for j in 0..=k2 {
        for i in 0..=k1 {
            cps[i * (k2 + 1) + j] = pts[j * (k1 + 1) + i];
        }
    }
    Ok(BezierPatch {
        deg_u: k1,
        deg_v: k2,
        cps,
    })
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
                    i as f64 + seed / 7.0,
                    -(j as f64) / 3.0 * 1e5,
                    (seed * (k as f64 + 1.0)).sin() * 1e-9,
                ]
            })
            .collect();
        BezierPatch::new(du, dv, cps)
    }

    fn complex() -> PatchComplex {
        let mut c = PatchComplex::new();
        c.push(patch(3, 3, 0.1), Provenance::Regular { face: 0 });
        c.push(patch(2, 5, 0.2), Provenance::Regular { face: 1 });
        let e = Element::Face(3);
        c.push(
            patch(4, 4, 0.3),
            Provenance::Ring {
                element: e,
                ring: 2,
                sector: 1,
            },
        );
        c.push(
            patch(3, 2, 0.4),
            Provenance::Cap {
                element: e,
                sector: 0,
            },
        );
        c
    }

    fn text() -> String {
        iges_text(&complex(), "out dir/model.igs", "20260102.030405").unwrap()
    }

    #[test]
    fn reals_and_dates() {
        assert_eq!(iges_real(1.0), "1.0D0");
        assert_eq!(iges_real(-1.25e-3), "-1.25D-3");
        assert_eq!(iges_real(0.0), "0.0D0");
        assert_eq!(iges_real(1e300), "1.0D300");
        for x in [1.0 / 3.0, -2.0e-308, 12345.678, f64::MAX, 5e-324] {
            assert_eq!(parse_real(&iges_real(x)), Some(x));
        }
        assert_eq!(parse_real("1."), Some(1.0));
        assert_eq!(parse_real(" -.5E1 "), Some(-5.0));
        assert_eq!(iges_date(0), "19700101.000000");
        assert_eq!(iges_date(951_782_400), "20000229.000000");
        assert_eq!(iges_date(1_767_323_045), "20260102.030405");
    }

    #[test]
    fn records_are_80_columns_with_sections_in_order() {
        let t = text();
        let lines: Vec<&str> = t.lines().collect();
        assert!(lines.iter().all(|l| l.len() == 80 && l.is_ascii()));
        let letters: String = lines.iter().map(|l| &l[72..73]).collect();
        let counts: Vec<usize> = "SGDPT"
            .chars()
            .map(|c| letters.matches(c).count())
            .collect();
        assert_eq!(counts[0], 2);
        assert_eq!(counts[2], 8); // two records per entity
        assert_eq!(counts[4], 1);
        let t_rec = lines.last().unwrap();
        assert_eq!(
            &t_rec[..32],
            format!("S{:07}G{:07}D{:07}P{:07}", 2, counts[1], 8, counts[3])
        );
        assert_eq!(&t_rec[72..], "T      1");
        // Global: delimiters, units, version 5.3, date, sanitized file name.
        let g: String = lines
            .iter()
            .filter(|l| &l[72..73] == "G")
            .map(|l| &l[..72])
            .collect();
        let params = split_params(&g, ',', ';').unwrap();
        assert_eq!(params.len(), 25);
        assert_eq!(params[0], ",");
        assert_eq!(params[1], ";");
        assert_eq!(params[2], "model");
        assert_eq!(params[3], "out_dir_model.igs");
        assert_eq!(params[13], "2");
        assert_eq!(params[14], "MM");
        assert_eq!(params[17], "20260102.030405");
        assert_eq!(params[22], "11");
        assert_eq!(params[23], "0");
        assert_eq!(parse_real(&params[19]), Some(5.0 / 3.0 * 1e5));
        // First directory entry: type 128, P pointer 1, status, label and subscript.
        let d1 = lines[2 + counts[1]];
        let d2 = lines[3 + counts[1]];
        assert_eq!(&d1[..16], "     128       1");
        assert_eq!(&d1[64..80], "00000000D      1");
        assert_eq!(&d2[..8], "     128");
        assert_eq!(&d2[56..72], " regular       1");
        let d4 = lines[5 + counts[1]];
        assert_eq!(&d4[56..72], " regular       2");
        let d6 = lines[7 + counts[1]];
        assert_eq!(&d6[56..72], "   ring2       1");
        // Parameter records: columns 65 blank, 66-72 DE pointer.
        let p1 = lines[2 + counts[1] + 8];
        assert!(
            p1.starts_with("128,3,3,3,3,0,0,1,0,0,0.0,0.0,0.0,0.0,1.0,1.0,1.0,1.0,"),
            "{p1}"
        );
        assert_eq!(&p1[64..80], "       1P      1");
    }

    #[test]
    fn roundtrip_is_exact() {
        let c = complex();
        let back = parse_iges(&text(), Path::new("m.igs")).unwrap();
        assert_eq!(back.patches, c.patches);
        assert!(back.provenance.iter().all(|p| *p == Provenance::Unknown));
        // Spot-check the u-fastest order of control points against the parameter records.
        let t = text();
        let p_data: String = t
            .lines()
            .filter(|l| &l[72..73] == "P")
            .take_while(|l| l[65..72].trim() == "1")
            .map(|l| &l[..64])
            .collect();
        let params = split_params(&p_data, ',', ';').unwrap();
        // 10 header values, 8 + 8 knots, 16 weights, then X(0,0) Y(0,0) Z(0,0) X(1,0)...
        let first_pt = 10 + 16 + 16;
        let b10 = c.patches[0].cp(1, 0);
        assert_eq!(parse_real(&params[first_pt + 3]), Some(b10[0]));
        assert_eq!(parse_real(&params[first_pt + 4]), Some(b10[1]));
        assert_eq!(params.len(), first_pt + 48 + 4);
    }

    #[test]
    fn degree_zero_is_raised_exactly() {
        let mut c = PatchComplex::new();
        c.push(
            BezierPatch::new(
                0,
                2,
                vec![[1.0, 2.0, 3.0], [4.0, 5.0, 6.0], [7.0, 8.0, 9.0]],
            ),
            Provenance::Unknown,
        );
        let back = parse_iges(
            &iges_text(&c, "z.igs", "20000101.000000").unwrap(),
            Path::new("z.igs"),
        )
        .unwrap();
        let p = &back.patches[0];
        assert_eq!((p.deg_u, p.deg_v), (1, 2));
        for j in 0..3 {
            assert_eq!(p.cp(0, j), c.patches[0].cp(0, j));
            assert_eq!(p.cp(1, j), c.patches[0].cp(0, j));
        }
    }

    #[test]
    fn empty_complex_is_a_valid_file() {
        let t = iges_text(&PatchComplex::new(), "e.igs", "20000101.000000").unwrap();
        assert!(parse_iges(&t, Path::new("e.igs")).unwrap().is_empty());
        assert!(
            t.lines()
                .last()
                .unwrap()
                .starts_with("S0000002G0000002D0000000P0000000"),
            "{t}"
        );
    }

    fn corrupt(f: impl Fn(&mut Vec<String>)) -> Error {
        let mut lines: Vec<String> = text().lines().map(String::from).collect();
        f(&mut lines);
        let s = lines.join("\n") + "\n";
        parse_iges(&s, Path::new("bad.igs")).unwrap_err()
    }

    fn d_index(lines: &[String], k: usize) -> usize {
        lines.iter().position(|l| &l[72..73] == "D").unwrap() + k
    }

    #[test]
    fn corrupted_files_are_rejected_with_clear_messages() {
        // 81 columns.
        let e = corrupt(|l| l[3].push(' ')).to_string();
        assert!(e.contains("bad.igs:4:") && e.contains("81 columns"), "{e}");
        // Bad parameter pointer in the second entry (records 3, 4 of D).
        let e = corrupt(|l| {
            let i = d_index(l, 2);
            l[i].replace_range(8..16, "     999");
        })
        .to_string();
        assert!(
            e.contains("directory entry 3") && e.contains("pointer 999"),
            "{e}"
        );
        // Pointer inside the P section but to another entity's records.
        let e = corrupt(|l| {
            let i = d_index(l, 2);
            l[i].replace_range(8..16, "       1");
        })
        .to_string();
        assert!(
            e.contains("names directory entry 1") && e.contains("directory entry 3"),
            "{e}"
        );
        // Wrong parameter record count.
        let e = corrupt(|l| {
            let i = d_index(l, 1);
            let n: usize = l[i][24..32].trim().parse().unwrap();
            l[i].replace_range(24..32, &format!("{:>8}", n + 1));
        })
        .to_string();
        assert!(
            e.contains("names directory entry 3") || e.contains("belongs to two"),
            "{e}"
        );
        let e = corrupt(|l| {
            let i = d_index(l, 1);
            let n: usize = l[i][24..32].trim().parse().unwrap();
            l[i].replace_range(24..32, &format!("{:>8}", n - 1));
        })
        .to_string();
        assert!(e.contains("belongs to no directory entry"), "{e}");
        // Wrong count in the terminate record.
        let e = corrupt(|l| {
            let last = l.len() - 1;
            l[last].replace_range(16..24, "D0000009");
        })
        .to_string();
        assert!(
            e.contains("terminate record field 3") && e.contains("8 D records"),
            "{e}"
        );
        // Sequence numbers must be consecutive.
        let e = corrupt(|l| {
            let i = d_index(l, 3);
            l[i].replace_range(73..80, "      7");
        })
        .to_string();
        assert!(
            e.contains("sequence number '7'") && e.contains("expected 4"),
            "{e}"
        );
        // Sections out of order.
        let e = corrupt(|l| l.swap(0, 2)).to_string();
        assert!(e.contains("order S, G, D, P, T"), "{e}");
        // Mismatched entity types in a directory entry pair.
        let e = corrupt(|l| {
            let i = d_index(l, 1);
            l[i].replace_range(0..8, "     126");
        })
        .to_string();
        assert!(e.contains("126"), "{e}");
        // A garbled number in the parameter data.
        let e = corrupt(|l| {
            let i = l.iter().position(|l| &l[72..73] == "P").unwrap();
            l[i].replace_range(0..4, "128,");
            l[i].replace_range(4..6, "x,");
        })
        .to_string();
        assert!(e.contains("K1 is 'x"), "{e}");
        // Missing terminate record.
        let e = corrupt(|l| {
            l.pop();
        })
        .to_string();
        assert!(e.contains("Terminate"), "{e}");
    }

    fn params(s: &str) -> Vec<String> {
        split_params(s, ',', ';').unwrap()
    }

    #[test]
    fn entity_128_conversion_rules() {
        // A bilinear patch: X(i,j) with i fastest.
        let ok = "128,1,1,1,1,0,0,1,0,0,0.,0.,1.,1.,0.,0.,1.,1.,1.,1.,1.,1.,\
                  0.,0.,0.,1.,0.,0.,0.,1.,0.,1.,1.,1.,0.,1.,0.,1.;";
        let p = match surface_128(&params(ok)) {
            Ok(p) => p,
            Err(_) => panic!("valid entity rejected"),
        };
        assert_eq!(p.cp(1, 0), [1.0, 0.0, 0.0]);
        assert_eq!(p.cp(0, 1), [0.0, 1.0, 0.0]);
        assert_eq!(p.cp(1, 1), [1.0, 1.0, 1.0]);
        // Equal weights other than 1 and knots on [2, 5] are fine.
        let ok2 = ok
            .replace("1.,1.,1.,1.,0.,0.,0.,1.", "3.,3.,3.,3.,0.,0.,0.,1.")
            .replace("0.,0.,1.,1.,0.,0.,1.,1.,", "2.,2.,5.,5.,0.,0.,1.,1.,")
            .replace("0.,1.,0.,1.;", "2.,5.,0.,1.;");
        assert!(surface_128(&params(&ok2)).is_ok());
        let unsupported = |s: &str| matches!(surface_128(&params(s)), Err(Bad::Unsupported(_)));
        // Rational weights.
        assert!(unsupported(
            &ok.replace("1.,1.,1.,1.,0.,0.,0.,1.", "2.,1.,1.,1.,0.,0.,0.,1.")
        ));
        // Partial parameter range.
        assert!(unsupported(&ok.replace("0.,1.,0.,1.;", "0.,0.5,0.,1.;")));
        // Several spans: K1 = 2, M1 = 1.
        assert!(unsupported(&ok.replacen("128,1,", "128,2,", 1)));
        // Unclamped knots.
        assert!(unsupported(&ok.replace(
            "0.,0.,1.,1.,0.,0.,1.,1.,",
            "0.,0.5,1.,1.,0.,0.,1.,1.,"
        )));
        // Too few parameters.
        assert!(matches!(
            surface_128(&params("128,1,1,1,1,0,0,1,0,0,0.;")),
            Err(Bad::Parse(_))
        ));
    }

    #[test]
    fn other_entity_types_are_unsupported() {
        let t = text().replace("     128", "     126");
        let e = parse_iges(&t, Path::new("o.igs")).unwrap_err();
        assert!(
            matches!(e, Error::Unsupported(_)) && e.to_string().contains("entity type 126"),
            "{e}"
        );
    }
}
