//! The IGES writer: the five sections of 80-column records, the global parameters, and one
//! entity 128 with its directory entry per patch (layout in the [module doc](super)).

use crate::bezier::BezierPatch;
use crate::error::Result;
use crate::io::bv::check_complex;
use crate::io::groups::FirstSeen;
use crate::io::write_bytes_atomically;
use crate::surface::PatchComplex;
use crate::surface::cad::spline::SplineSurface;
use crate::surface::cad::{CadFaces, FaceSource};
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
pub(super) fn iges_real(x: f64) -> String {
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
pub(super) fn iges_date(unix_secs: i64) -> String {
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
pub(crate) fn now_date() -> String {
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
    let mut weights = Vec::with_capacity((du + 1) * (dv + 1));
    for i in 0..=du {
        for j in 0..=dv {
            let k = i.min(p.deg_u) * (p.deg_v + 1) + j.min(p.deg_v);
            cps.push(p.cps[k]);
            weights.push(p.weights.as_ref().map_or(1.0, |w| w[k]));
        }
    }
    BezierPatch {
        deg_u: du,
        deg_v: dv,
        cps,
        weights: p.weights.as_ref().map(|_| weights),
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
        // PROP3: 1 polynomial, 0 rational
        if p.is_rational() { "0" } else { "1" },
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
    for j in 0..=dv {
        for i in 0..=du {
            let w = p.weights.as_ref().map_or(1.0, |w| w[i * (dv + 1) + j]);
            v.push(if p.is_rational() {
                iges_real(w)
            } else {
                "1.0".to_string()
            });
        }
    }
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

/// [`iges_to_string`] with a given date (`YYYYMMDD.HHNNSS`).
pub(super) fn iges_text(complex: &PatchComplex, file_name: &str, date: &str) -> Result<String> {
    check_complex(complex)?;
    let n = complex.len();
    let start = [
        format!(
            "fairsub {}: {n} Bezier patches as IGES 5.3 entity 128 surfaces",
            env!("CARGO_PKG_VERSION")
        ),
        "(polynomial B-splines with one span each). Model units: millimetres.".to_string(),
    ];
    let entities = complex
        .patches
        .iter()
        .zip(&complex.provenance)
        .map(|(patch, prov)| (entity_128(patch), prov.group_name()));
    let points = complex.patches.iter().flat_map(|p| p.cps.iter());
    Ok(sections(&start, entities, points, file_name, date))
}

/// The IGES text for CAD faces ([`crate::surface::cad`]): one entity 128 per face, labelled
/// `face` (an input face) or `patch`.
pub fn iges_faces_to_string(faces: &CadFaces, file_name: &str) -> Result<String> {
    iges_faces_text(faces, file_name, &now_date())
}

fn iges_faces_text(faces: &CadFaces, file_name: &str, date: &str) -> Result<String> {
    let start = [
        format!(
            "fairsub {}: {} B-spline faces as IGES 5.3 entity 128 surfaces",
            env!("CARGO_PKG_VERSION"),
            faces.len()
        ),
        "(polynomial, knots as merged). Model units: millimetres.".to_string(),
    ];
    let entities = faces.surfaces.iter().zip(&faces.sources).map(|(s, src)| {
        let label = match src {
            FaceSource::Input { .. } => "face",
            FaceSource::Patch { .. } => "patch",
            FaceSource::Packed { .. } => "packed",
        };
        (spline_128(s), label.to_string())
    });
    let points = faces.surfaces.iter().flat_map(|s| s.cps.iter());
    Ok(sections(&start, entities, points, file_name, date))
}

/// The parameters of entity 128 for a polynomial B-spline surface.
fn spline_128(s: &SplineSurface) -> Vec<String> {
    let [nu, nv] = s.counts();
    let [du, dv] = s.deg;
    let mut v: Vec<String> = vec![
        "128".into(),
        (nu - 1).to_string(),
        (nv - 1).to_string(),
        du.to_string(),
        dv.to_string(),
        "0".into(),
        "0".into(),
        "1".into(),
        "0".into(),
        "0".into(),
    ];
    for k in &s.knots {
        v.extend(k.iter().map(|&x| iges_real(x)));
    }
    v.extend(std::iter::repeat_n("1.0".to_string(), nu * nv));
    for j in 0..nv {
        for i in 0..nu {
            for c in s.cp(i, j) {
                v.push(iges_real(c));
            }
        }
    }
    let r = s.range();
    for x in [r[0][0], r[0][1], r[1][0], r[1][1]] {
        v.push(iges_real(x));
    }
    v
}

/// The five sections: start text, the global section, and one entity 128 per `(parameters,
/// group name)`.
fn sections<'a>(
    start: &[String],
    entities: impl Iterator<Item = (Vec<String>, String)>,
    points: impl Iterator<Item = &'a crate::geom::Point>,
    file_name: &str,
    date: &str,
) -> String {
    let mut s = Section::new('S');
    for l in start {
        s.push(l);
    }
    let max_coord = points
        .flat_map(|q| q.iter())
        .fold(0.0f64, |m, x| m.max(x.abs()));
    let g = global_section(max_coord, file_name, date);
    let (d, p) = entity_sections(entities);
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
    out
}

/// The global section: delimiters, product and file names (from `file_name`), the writer,
/// number formats, millimetres, the `date`, the resolution and size from the largest
/// coordinate `max_coord`, and the IGES version.
fn global_section(max_coord: f64, file_name: &str, date: &str) -> Section {
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
    g
}

/// The directory and parameter sections of one entity 128 per `(parameters, group name)`,
/// each labelled with its group and numbered within it.
fn entity_sections(entities: impl Iterator<Item = (Vec<String>, String)>) -> (Section, Section) {
    let mut d = Section::new('D');
    let mut p = Section::new('P');
    // The entity subscript: the number of the patch within its group.
    let mut group_numbers = FirstSeen::default();
    let mut group_counts: Vec<usize> = Vec::new();
    for (params, gname) in entities {
        let (gk, new) = group_numbers.number(&gname);
        if new {
            group_counts.push(0);
        }
        group_counts[gk] += 1;
        let label = sanitize(&gname, 8);
        let de_seq = d.lines.len() + 1;
        let p_start = p.lines.len() + 1;
        let count = p.push_params(&delimited(params), 64, &format!(" {de_seq:>7}"));
        d.push(&format!(
            "{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}",
            128, p_start, 0, 0, 0, 0, 0, 0, "00000000"
        ));
        d.push(&format!(
            "{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}",
            128, 0, 0, count, 0, "", "", label, group_counts[gk]
        ));
    }
    (d, p)
}

/// Writes CAD faces as an IGES 5.3 file (atomically).
pub fn write_iges_faces(path: &Path, faces: &CadFaces) -> Result<()> {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    write_bytes_atomically(path, iges_faces_to_string(faces, &name)?.as_bytes())
}

/// Writes a patch complex as an IGES 5.3 file (atomically).
pub fn write_iges(path: &Path, complex: &PatchComplex) -> Result<()> {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    write_bytes_atomically(path, iges_to_string(complex, &name)?.as_bytes())
}
