//! `DIR/results.jsonl`: one row per job and run, appended as jobs finish (a crash leaves at
//! most one torn last line, which the next run ignores), the content hashes that make a row
//! evidence for resuming, and the check that a job's outputs are still intact.

use super::manifest::{Input, Job};
use crate::error::Result;
use serde::{Deserialize, Serialize};
use serde_json::{Map, Value};
use sha2::{Digest, Sha256};
use std::collections::HashMap;
use std::io::{Read, Write};
use std::path::{Path, PathBuf};

/// The file name of the results in `--out`.
pub const RESULTS: &str = "results.jsonl";

/// fairsub's version, part of every job's key.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// What became of a job.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Status {
    /// Done in this run; its outputs are in place.
    Ok,
    /// Failed; `error` says why (naming the file and the element).
    Error,
    /// Done in an earlier run with the same key, outputs intact: not redone.
    Skipped,
}

/// A written output with its size and SHA-256 (what "intact" means on resuming).
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct OutputFile {
    /// Relative to `--out`.
    pub path: String,
    /// Bytes.
    pub bytes: u64,
    /// SHA-256, lower-case hex (as `sha256sum` prints it).
    pub sha256: String,
}

/// One row of `results.jsonl`.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Row {
    /// The manifest line of the job.
    pub line: usize,
    /// The input as the manifest wrote it.
    pub input: Option<String>,
    /// The output as the manifest wrote it (relative to `--out`).
    pub output: Option<String>,
    /// ok, error or skipped.
    pub status: Status,
    /// Why the job failed (error rows).
    pub error: Option<String>,
    /// Wall-clock seconds of the job (0 when skipped).
    pub seconds: f64,
    /// The job's content hash: fairsub's version, the job's fields and options, the bytes of
    /// its input and side files (SHA-256, hex).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub key: Option<String>,
    /// The files written, with their hashes.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub outputs: Vec<OutputFile>,
    /// Counts of the result: vertices and faces of a net, patches of a complex.
    #[serde(default, skip_serializing_if = "Map::is_empty")]
    pub counts: Map<String, Value>,
    /// With `"measure": true`: the metrics (see the guide's batch page).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub metrics: Option<Value>,
    /// The construction's notes (fallbacks, derived rules).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub notes: Vec<String>,
    /// fairsub's version.
    pub version: String,
}

impl Row {
    /// An error row of a job (or a manifest line).
    pub fn error(
        line: usize,
        input: Option<String>,
        output: Option<String>,
        message: String,
    ) -> Row {
        Row {
            line,
            input,
            output,
            status: Status::Error,
            error: Some(message),
            seconds: 0.0,
            key: None,
            outputs: Vec::new(),
            counts: Map::new(),
            metrics: None,
            notes: Vec::new(),
            version: VERSION.into(),
        }
    }
}

/// Lower-case hex of bytes.
fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

/// Feeds a file's bytes to `h`.
fn feed_file(h: &mut Sha256, path: &Path) -> std::io::Result<u64> {
    let mut f = std::fs::File::open(path)?;
    let mut buf = vec![0u8; 1 << 16];
    let mut n = 0u64;
    loop {
        let k = f.read(&mut buf)?;
        if k == 0 {
            return Ok(n);
        }
        h.update(&buf[..k]);
        n += k as u64;
    }
}

/// A file's size and SHA-256.
pub fn file_hash(path: &Path) -> std::io::Result<(u64, String)> {
    let mut h = Sha256::new();
    let n = feed_file(&mut h, path)?;
    Ok((n, hex(&h.finalize())))
}

/// The job's key: SHA-256 over fairsub's version, the job's canonical fields and the bytes of
/// its input and side files; `None` when a file cannot be read (the job then runs and reports
/// it).
pub fn job_key(job: &Job) -> Option<String> {
    let mut h = Sha256::new();
    h.update(format!("fairsub {VERSION}\n{}\n", job.canonical()).as_bytes());
    let mut files: Vec<&PathBuf> = job.side_files.iter().map(|(_, p)| p).collect();
    if let Input::File(p) = &job.source {
        files.insert(0, p);
    }
    for p in files {
        // the length closes each file's bytes, so no two file lists hash alike
        let n = feed_file(&mut h, p).ok()?;
        h.update(format!("\n{n}\n").as_bytes());
    }
    Some(hex(&h.finalize()))
}

/// The rows of earlier runs that let a job be skipped: by key, the last ok row.
#[derive(Debug, Default)]
pub struct Done {
    by_key: HashMap<String, Row>,
    /// Lines of `results.jsonl` that are not rows (a torn last line, an edited row).
    pub unreadable: Vec<usize>,
}

impl Done {
    /// Reads `DIR/results.jsonl` (nothing when it does not exist).
    pub fn read(out: &Path) -> Result<Done> {
        let path = out.join(RESULTS);
        let text = match std::fs::read(&path) {
            Ok(b) => String::from_utf8_lossy(&b).into_owned(),
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Done::default()),
            Err(source) => return Err(crate::Error::Io { path, source }),
        };
        let mut done = Done::default();
        for (i, l) in text.lines().enumerate() {
            if l.trim().is_empty() {
                continue;
            }
            match serde_json::from_str::<Row>(l) {
                Ok(r) => {
                    if let (Status::Ok, Some(k)) = (r.status, &r.key) {
                        done.by_key.insert(k.clone(), r);
                    }
                }
                Err(_) => done.unreadable.push(i + 1),
            }
        }
        Ok(done)
    }

    /// The ok row of an earlier run with this key whose outputs are all still in `out` with
    /// their sizes and hashes.
    pub fn intact(&self, key: &str, out: &Path) -> Option<&Row> {
        let row = self.by_key.get(key)?;
        let all = row.outputs.iter().all(|o| {
            file_hash(&out.join(&o.path)).is_ok_and(|(n, h)| n == o.bytes && h == o.sha256)
        });
        all.then_some(row)
    }
}

/// `results.jsonl` open for appending.
pub struct Log {
    file: std::fs::File,
    path: PathBuf,
}

impl Log {
    /// Opens (creates) `DIR/results.jsonl` for appending; a torn last line of a crashed run
    /// gets its newline first, so the next row starts a line of its own.
    pub fn open(out: &Path) -> Result<Log> {
        let path = out.join(RESULTS);
        let io = |source| crate::Error::Io {
            path: path.clone(),
            source,
        };
        let mut file = std::fs::OpenOptions::new()
            .create(true)
            .append(true)
            .read(true)
            .open(&path)
            .map_err(io)?;
        let len = file.metadata().map_err(io)?.len();
        if len > 0 {
            use std::io::{Seek, SeekFrom};
            let mut last = [0u8; 1];
            file.seek(SeekFrom::Start(len - 1)).map_err(io)?;
            file.read_exact(&mut last).map_err(io)?;
            if last[0] != b'\n' {
                file.write_all(b"\n").map_err(io)?;
            }
        }
        Ok(Log { file, path })
    }

    /// Appends rows (one write each, whole lines) and syncs the file.
    pub fn append(&mut self, rows: &[Row]) -> Result<()> {
        let io = |source| crate::Error::Io {
            path: self.path.clone(),
            source,
        };
        for r in rows {
            let mut line = serde_json::to_string(r).expect("serialisable");
            line.push('\n');
            self.file.write_all(line.as_bytes()).map_err(io)?;
        }
        self.file.sync_data().map_err(io)
    }
}
