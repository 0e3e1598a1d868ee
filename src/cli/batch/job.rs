//! One job of `fairsub batch`, run in-process: the words of `fairsub subdivide` parsed by the
//! command line's own parser and run by its own code (`subdivide::run_keeping`), so the files
//! are the single-file command's bytes; the writes staged (`io::staged`) for the caller to
//! commit, the metrics of `"measure": true` from `check`'s report of the same surface.

use super::results::OutputFile;
use crate::cli::subdivide::{self, Computed};
use crate::cli::{Cli, Command};
use crate::error::{Error, Result};
use crate::surface::PatchComplex;
use clap::Parser;
use serde::{Deserialize, Serialize};
use serde_json::{Map, Value};
use std::path::{Path, PathBuf};

/// Rings of the surface that `"measure": true` measures when the job gives none (`fairsub
/// check`'s default).
pub const MEASURE_RINGS: usize = 4;

/// A job as a worker runs it: the command line's words, nothing left to resolve.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Task {
    /// The manifest line (for messages).
    pub line: usize,
    /// The words of `fairsub subdivide` that write the output (`None`: metrics only).
    pub write: Option<Vec<String>>,
    /// The words of `fairsub subdivide --rings K` whose surface is measured (`None`: no
    /// metrics).
    pub measure: Option<Vec<String>>,
    /// The input as the manifest wrote it (the `source` of the metrics).
    pub input: String,
    /// The output file (absolute or relative to the working folder), if any.
    pub output: Option<PathBuf>,
    /// `--out`: the outputs are reported relative to it.
    pub out: PathBuf,
    /// The memory budget of the job (bytes; the `--max-memory` of its commands).
    pub budget: u64,
}

/// What a job did, before its files are committed.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
pub struct Outcome {
    /// Why it failed (the command line's message).
    pub error: Option<String>,
    /// Wall-clock seconds.
    pub seconds: f64,
    /// Vertices and faces, or patches.
    pub counts: Map<String, Value>,
    /// The metrics (with `measure`).
    pub metrics: Option<Value>,
    /// The construction's notes.
    pub notes: Vec<String>,
    /// The staged files: (temporary, target).
    pub staged: Vec<(PathBuf, PathBuf)>,
    /// The files with their sizes and hashes (of the staged bytes).
    pub outputs: Vec<OutputFile>,
}

/// Runs a task in this thread: the files are staged, not committed (on failure they are
/// removed and `staged` is empty). A panic (a bug) becomes an error outcome.
pub fn run(t: &Task) -> Outcome {
    let start = std::time::Instant::now();
    let (r, staged) = crate::io::staged(|| {
        crate::cli::capture(|| {
            std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                crate::cli::limits::with_budget(Some(t.budget), || execute(t))
            }))
        })
        .0
    });
    let r = r.unwrap_or_else(|p| {
        let what = p
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| p.downcast_ref::<String>().cloned())
            .unwrap_or_default();
        Err(Error::InvalidArgument(format!(
            "internal error (a bug in fairsub, please report it): {what}"
        )))
    });
    let hashed = r.and_then(|done| {
        let outputs = staged
            .iter()
            .map(|s| output_file(&s.temp, &s.target, &t.out))
            .collect::<Result<Vec<_>>>()?;
        Ok((done, outputs))
    });
    let seconds = start.elapsed().as_secs_f64();
    match hashed {
        Ok(((counts, metrics, notes), outputs)) => Outcome {
            error: None,
            seconds,
            counts,
            metrics,
            notes,
            staged: staged.into_iter().map(|s| (s.temp, s.target)).collect(),
            outputs,
        },
        Err(e) => {
            crate::io::discard(&staged);
            Outcome {
                error: Some(e.to_string()),
                seconds,
                ..Outcome::default()
            }
        }
    }
}

/// The size and hash of a staged file, named by its target relative to `out`.
fn output_file(temp: &Path, target: &Path, out: &Path) -> Result<OutputFile> {
    let (bytes, sha256) = super::results::file_hash(temp).map_err(|source| Error::Io {
        path: target.to_path_buf(),
        source,
    })?;
    let rel = target.strip_prefix(out).unwrap_or(target);
    Ok(OutputFile {
        path: rel.to_string_lossy().replace('\\', "/"),
        bytes,
        sha256,
    })
}

/// What a job reports besides its files.
type Report = (Map<String, Value>, Option<Value>, Vec<String>);

/// The `subdivide` arguments of a job's words.
fn subdivide_args(words: &[String]) -> Result<subdivide::Args> {
    let cli = Cli::try_parse_from(words).map_err(|e| Error::InvalidArgument(e.to_string()))?;
    match cli.command {
        Command::Subdivide(a) => Ok(a),
        _ => Err(Error::InvalidArgument(
            "a batch job runs `fairsub subdivide`".into(),
        )),
    }
}

/// Writes the output (if any), then measures.
fn execute(t: &Task) -> Result<Report> {
    let mut counts = Map::new();
    let mut notes = Vec::new();
    let mut built: Option<(PatchComplex, crate::schemes::Spec)> = None;
    if let Some(words) = &t.write {
        let a = subdivide_args(words)?;
        let (p, computed) = subdivide::run_keeping(&a)?;
        match computed {
            Computed::Net(m) | Computed::FcvNet(m) | Computed::LimitMesh(m, _) => {
                counts.insert("vertices".into(), m.num_vertices().into());
                counts.insert("faces".into(), m.num_faces().into());
            }
            Computed::Complex(c, n) => {
                counts.insert("patches".into(), c.len().into());
                notes = n;
                // the written surface is the measured one when the rings agree
                let measured_rings = t
                    .measure
                    .as_ref()
                    .and_then(|m| subdivide_args(m).ok())
                    .and_then(|m| m.rings);
                if measured_rings == Some(a.rings.unwrap_or(subdivide::DEFAULT_RINGS)) {
                    built = Some((c, p.spec));
                }
            }
        }
    }
    let Some(words) = &t.measure else {
        return Ok((counts, None, notes));
    };
    let (complex, spec) = match built {
        Some(b) => b,
        None => {
            let a = subdivide_args(words)?;
            let p = subdivide::prepare(&a, None)?;
            match subdivide::finish(&a, &p)?.0 {
                Computed::Complex(c, n) => {
                    if notes.is_empty() {
                        notes = n;
                    }
                    (c, p.spec)
                }
                _ => {
                    return Err(Error::InvalidArgument(
                        "\"measure\" needs the scheme's exact surface, which it has none of".into(),
                    ));
                }
            }
        }
    };
    if t.write.is_none() {
        counts.insert("patches".into(), complex.len().into());
    }
    let metrics = metrics(&t.input, &complex, &spec, notes.clone());
    Ok((counts, Some(metrics), notes))
}

/// The metrics of a surface: `check --json`'s report of it and a curvature summary (the
/// extremes of the Gauss and mean curvature over the rings and caps of all elements, read
/// off the report).
fn metrics(
    source: &str,
    complex: &PatchComplex,
    spec: &crate::schemes::Spec,
    notes: Vec<String>,
) -> Value {
    let report = crate::cli::check::report_json(source, complex, Some(spec), notes);
    let report: Value = serde_json::from_str(&report).expect("check writes JSON");
    let mut k = (f64::INFINITY, f64::NEG_INFINITY);
    let mut h = (f64::INFINITY, f64::NEG_INFINITY);
    let rings = report["curvature"].as_array().into_iter().flatten();
    for ring in rings.flat_map(|e| e["rings"].as_array().into_iter().flatten()) {
        let x = |name: &str| ring[name].as_f64().unwrap_or(f64::NAN);
        k = (k.0.min(x("gauss_min")), k.1.max(x("gauss_max")));
        h = (h.0.min(x("mean_min")), h.1.max(x("mean_max")));
    }
    let range = |(lo, hi): (f64, f64)| {
        if lo <= hi {
            serde_json::json!([lo, hi])
        } else {
            Value::Null
        }
    };
    serde_json::json!({
        "check": report,
        "curvature": {"gauss": range(k), "mean": range(h)},
    })
}
