//! The manifest of `fairsub batch`: JSON Lines (one job a line) or CSV with the same column
//! names, read into [`Job`]s whose inputs are resolved against the manifest's folder and whose
//! options become the words of `fairsub subdivide`'s command line. A bad line becomes an error
//! row of its own (it never stops the other jobs); only a manifest that cannot be read at all,
//! or a CSV header with an unknown column, stops the run.

use crate::error::{Error, Result};
use serde::Deserialize;
use serde_json::{Map, Value};
use std::path::{Path, PathBuf};

/// One line of a manifest as written: every field optional so that a `{"defaults": ...}` line
/// can supply what the rows leave out.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct Fields {
    input: Option<String>,
    scheme: Option<String>,
    levels: Option<usize>,
    rings: Option<usize>,
    output: Option<String>,
    options: Option<Map<String, Value>>,
    measure: Option<bool>,
}

impl Fields {
    /// These fields over `defaults` (options merged key by key, a row's own winning).
    fn over(self, defaults: &Fields) -> Fields {
        let mut options = defaults.options.clone().unwrap_or_default();
        for (k, v) in self.options.unwrap_or_default() {
            options.insert(k, v);
        }
        let (levels, rings) = match (self.levels, self.rings) {
            (None, None) => (defaults.levels, defaults.rings),
            given => given,
        };
        Fields {
            input: self.input.or_else(|| defaults.input.clone()),
            scheme: self.scheme.or_else(|| defaults.scheme.clone()),
            levels,
            rings,
            output: self.output.or_else(|| defaults.output.clone()),
            options: Some(options),
            measure: self.measure.or(defaults.measure),
        }
    }
}

/// Where a job's net comes from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Input {
    /// A net of the built-in gallery (`gallery:NAME`).
    Gallery(String),
    /// A file, resolved against the manifest's folder.
    File(PathBuf),
}

/// One job of a manifest, checked and resolved.
#[derive(Debug, Clone)]
pub struct Job {
    /// The manifest line (1-based; the CSV record's line).
    pub line: usize,
    /// The input as the manifest wrote it.
    pub input: String,
    /// The resolved input.
    pub source: Input,
    /// The scheme's name.
    pub scheme: String,
    /// Refinement steps (`--levels`).
    pub levels: Option<usize>,
    /// Rings (`--rings`).
    pub rings: Option<usize>,
    /// The output, relative to `--out` (none: only the metrics).
    pub output: Option<String>,
    /// The command line's options (names without `--`), in a stable order.
    pub options: Vec<(String, Value)>,
    /// Side files the options name (`q-file`, `fcv-file`, `creases`): the option and the file,
    /// resolved.
    pub side_files: Vec<(String, PathBuf)>,
    /// Whether the row gets the metrics.
    pub measure: bool,
}

/// A line of the manifest: a job, or the reason it is not one.
pub type Entry = std::result::Result<Job, LineError>;

/// A manifest line that is not a job: its line and the message (which names the manifest).
#[derive(Debug, Clone)]
pub struct LineError {
    /// The manifest line (1-based).
    pub line: usize,
    /// What is wrong, naming the manifest file and the line.
    pub message: String,
    /// The input, when the line named one.
    pub input: Option<String>,
    /// The output, when the line named one.
    pub output: Option<String>,
}

/// Options the manifest's own fields (or `fairsub batch` itself) set: not allowed in
/// `options`.
const RESERVED: [&str; 8] = [
    "net",
    "scheme",
    "levels",
    "rings",
    "output",
    "o",
    "max-memory",
    "stencils",
];

/// Options whose value is a file the job reads (resolved against the manifest's folder,
/// hashed with the input).
const SIDE_FILES: [&str; 3] = ["q-file", "fcv-file", "creases"];

/// Reads a manifest: CSV when its name ends in `.csv`, else JSON Lines.
///
/// # Errors
/// [`Error::Io`] when it cannot be read; [`Error::Parse`] for a CSV header with an unknown
/// column. Bad lines are entries of their own, not errors.
pub fn read(path: &Path) -> Result<Vec<Entry>> {
    let text = crate::io::read_text(path)?;
    let folder = path.parent().unwrap_or(Path::new("")).to_path_buf();
    let is_csv = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("csv"));
    let lines = if is_csv {
        csv_lines(&text, path)?
    } else {
        json_lines(&text)
    };
    let name = path.display().to_string();
    let mut defaults = Fields::default();
    let mut out = Vec::new();
    for (line, fields) in lines {
        match fields {
            Ok(Line::Defaults(d)) => defaults = d,
            Ok(Line::Job(f)) => out.push(resolve(f.over(&defaults), line, &folder, &name)),
            Err(message) => out.push(Err(LineError {
                line,
                message: format!("{name} line {line}: {message}"),
                input: None,
                output: None,
            })),
        }
    }
    Ok(out)
}

/// A line read: the defaults for the lines after it, or a job's fields.
enum Line {
    Defaults(Fields),
    Job(Fields),
}

/// The lines of a JSON Lines manifest (blank lines skipped).
fn json_lines(text: &str) -> Vec<(usize, std::result::Result<Line, String>)> {
    text.lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty())
        .map(|(i, l)| (i + 1, json_line(l)))
        .collect()
}

/// One JSON line: `{"defaults": {...}}` or a job.
fn json_line(l: &str) -> std::result::Result<Line, String> {
    let v: Value = serde_json::from_str(l).map_err(|e| format!("not a JSON object: {e}"))?;
    let Value::Object(mut o) = v else {
        return Err(
            "not a JSON object (one job per line: {\"input\": ..., \"scheme\": ...})".into(),
        );
    };
    if o.len() == 1
        && let Some(d) = o.remove("defaults")
    {
        return serde_json::from_value(d)
            .map(Line::Defaults)
            .map_err(|e| format!("bad defaults: {e}"));
    }
    serde_json::from_value(Value::Object(o))
        .map(Line::Job)
        .map_err(|e| e.to_string())
}

/// The records of a CSV manifest with its header's column names (the JSON fields; `options`
/// holds a JSON object).
fn csv_lines(text: &str, path: &Path) -> Result<Vec<(usize, std::result::Result<Line, String>)>> {
    let mut r = csv::ReaderBuilder::new()
        .flexible(true)
        .from_reader(text.as_bytes());
    let header: Vec<String> = r
        .headers()
        .map_err(|e| crate::io::parse_error(path, 1, e.to_string()))?
        .iter()
        .map(|h| h.trim().to_string())
        .collect();
    let known = [
        "input", "scheme", "levels", "rings", "output", "options", "measure",
    ];
    if let Some(h) = header.iter().find(|h| !known.contains(&h.as_str())) {
        return Err(crate::io::parse_error(
            path,
            1,
            format!(
                "unknown column '{h}' (the columns are the JSON fields: {})",
                known.join(", ")
            ),
        ));
    }
    let mut out = Vec::new();
    for rec in r.records() {
        let (line, fields) = match rec {
            Ok(rec) => {
                let line = rec.position().map_or(0, |p| p.line() as usize);
                (line, csv_record(&header, &rec))
            }
            Err(e) => {
                let line = e.position().map_or(0, |p| p.line() as usize);
                (line, Err(e.to_string()))
            }
        };
        out.push((line, fields.map(Line::Job)));
    }
    Ok(out)
}

/// One CSV record as fields (empty cells are absent).
fn csv_record(header: &[String], rec: &csv::StringRecord) -> std::result::Result<Fields, String> {
    if rec.len() > header.len() {
        return Err(format!(
            "{} cells, but the header has {} columns",
            rec.len(),
            header.len()
        ));
    }
    let mut o = Map::new();
    for (h, cell) in header.iter().zip(rec.iter()) {
        let cell = cell.trim();
        if cell.is_empty() {
            continue;
        }
        let v = match h.as_str() {
            "levels" | "rings" => Value::from(
                cell.parse::<u64>()
                    .map_err(|_| format!("{h} '{cell}' is not a whole number"))?,
            ),
            "measure" => Value::Bool(match cell.to_ascii_lowercase().as_str() {
                "true" | "1" | "yes" => true,
                "false" | "0" | "no" => false,
                _ => return Err(format!("measure '{cell}' is not true or false")),
            }),
            "options" => serde_json::from_str(cell)
                .map_err(|e| format!("options '{cell}' is not a JSON object: {e}"))?,
            _ => Value::String(cell.to_string()),
        };
        o.insert(h.clone(), v);
    }
    serde_json::from_value(Value::Object(o)).map_err(|e| e.to_string())
}

/// Checks a line's fields and resolves its paths.
fn resolve(f: Fields, line: usize, folder: &Path, manifest: &str) -> Entry {
    let fail = |message: String| LineError {
        line,
        message: format!("{manifest} line {line}: {message}"),
        input: f.input.clone(),
        output: f.output.clone(),
    };
    let input = f.input.clone().ok_or_else(|| fail("no \"input\"".into()))?;
    let scheme = f
        .scheme
        .clone()
        .ok_or_else(|| fail("no \"scheme\" (see `fairsub schemes`)".into()))?;
    if f.levels.is_some() && f.rings.is_some() {
        return Err(fail(
            "give either \"levels\" (refined net) or \"rings\" (patch complex), not both".into(),
        ));
    }
    let measure = f.measure.unwrap_or(false);
    if f.output.is_none() && !measure {
        return Err(fail(
            "no \"output\" (a path relative to --out) and no \"measure\": nothing to do".into(),
        ));
    }
    if let Some(o) = &f.output {
        check_output(o).map_err(&fail)?;
    }
    let source = match input.strip_prefix("gallery:") {
        Some(name) => Input::Gallery(name.to_string()),
        None => Input::File(folder.join(&input)),
    };
    let mut options = Vec::new();
    let mut side_files = Vec::new();
    let mut given = f.options.clone().unwrap_or_default();
    given.sort_keys();
    for (k, v) in given {
        let k = k.trim_start_matches("--").to_string();
        if RESERVED.contains(&k.as_str()) {
            return Err(fail(format!(
                "option \"{k}\" is not available in a manifest's options{}",
                if k == "stencils" {
                    ""
                } else {
                    " (it is a field of the job, or set by fairsub batch)"
                }
            )));
        }
        if k.is_empty() || !k.chars().all(|c| c.is_ascii_alphanumeric() || c == '-') {
            return Err(fail(format!("option \"{k}\" is not an option name")));
        }
        match &v {
            Value::String(s) if SIDE_FILES.contains(&k.as_str()) => {
                side_files.push((k.clone(), folder.join(s)));
            }
            Value::Object(_) => {
                return Err(fail(format!(
                    "option \"{k}\": a value is a string, number, true/false or a list"
                )));
            }
            _ => {}
        }
        options.push((k, v));
    }
    Ok(Job {
        line,
        input,
        source,
        scheme,
        levels: f.levels,
        rings: f.rings,
        output: f.output.clone(),
        options,
        side_files,
        measure,
    })
}

/// An output path must stay inside `--out`: relative, without `..`, naming a file.
fn check_output(o: &str) -> std::result::Result<(), String> {
    let p = Path::new(o);
    let inside = p.components().all(|c| {
        matches!(
            c,
            std::path::Component::Normal(_) | std::path::Component::CurDir
        )
    });
    if o.is_empty() || !inside || p.file_name().is_none() {
        return Err(format!(
            "output '{o}' must be a file path relative to --out, without '..'"
        ));
    }
    Ok(())
}

impl Job {
    /// The words of `fairsub subdivide` for this job, writing into `out` (a job without an
    /// output gets a `.bv` name that is never written: the format decides patch output).
    pub fn words(&self, out: &Path) -> Vec<String> {
        let input = match &self.source {
            Input::Gallery(_) => self.input.clone(),
            Input::File(p) => p.display().to_string(),
        };
        let mut w = vec![
            "fairsub".to_string(),
            "subdivide".into(),
            input,
            "--scheme".into(),
            self.scheme.clone(),
        ];
        if let Some(l) = self.levels {
            w.extend(["--levels".into(), l.to_string()]);
        }
        if let Some(r) = self.rings {
            w.extend(["--rings".into(), r.to_string()]);
        }
        let output = match &self.output {
            Some(o) => out.join(o),
            None => out.join(".measure-only.bv"),
        };
        w.extend(["-o".into(), output.display().to_string()]);
        for (k, v) in &self.options {
            let values = match v {
                Value::Array(a) => a.clone(),
                v => vec![v.clone()],
            };
            for v in values {
                match v {
                    Value::Bool(true) => w.push(format!("--{k}")),
                    Value::Bool(false) | Value::Null => {}
                    Value::String(s) => {
                        let side = self.side_files.iter().find(|(o, _)| o == k);
                        let s = side.map_or(s, |(_, p)| p.display().to_string());
                        w.extend([format!("--{k}"), s])
                    }
                    v => w.extend([format!("--{k}"), v.to_string()]),
                }
            }
        }
        w
    }

    /// The job as canonical JSON (for its content hash): the fields as written, options sorted.
    pub fn canonical(&self) -> String {
        let options: Map<String, Value> = self.options.iter().cloned().collect();
        serde_json::json!({
            "input": self.input,
            "scheme": self.scheme,
            "levels": self.levels,
            "rings": self.rings,
            "output": self.output,
            "options": options,
            "measure": self.measure,
        })
        .to_string()
    }
}

/// Reports a manifest that cannot be used at all (no jobs).
pub fn empty(path: &Path) -> Error {
    Error::InvalidArgument(format!("{}: the manifest lists no jobs", path.display()))
}
