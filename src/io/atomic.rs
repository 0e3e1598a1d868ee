//! Atomic output: every writer fills a temporary file beside its target and renames it into
//! place only when everything was written, so a failure never leaves a half-written file.

use super::text::io_error;
use crate::error::{Error, Result};
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

static TEMP_COUNTER: AtomicU64 = AtomicU64::new(0);

/// A number no other call in this process gets (for temporary names).
pub(crate) fn unique_number() -> u64 {
    TEMP_COUNTER.fetch_add(1, Ordering::Relaxed)
}

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
    tmp_name.push(format!(".tmp-{}-{}", std::process::id(), unique_number()));
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

/// Writes `bytes` to `path` atomically (the writers that build their text first).
pub(crate) fn write_bytes_atomically(path: &Path, bytes: &[u8]) -> Result<()> {
    write_atomically(path, |w| w.write_all(bytes).map_err(|e| io_error(path, e)))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tmpdir(tag: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!(
            "fairsub-io-{tag}-{}-{}",
            std::process::id(),
            unique_number()
        ));
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    /// The sorted file names in `dir`, which is then removed.
    fn entries_then_remove(dir: &Path) -> Vec<String> {
        let mut v: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        std::fs::remove_dir_all(dir).unwrap();
        v
    }

    #[test]
    fn atomic_write_commits_on_success() {
        let dir = tmpdir("ok");
        let p = dir.join("a.txt");
        write_bytes_atomically(&p, b"hello").unwrap();
        assert_eq!(std::fs::read(&p).unwrap(), b"hello");
        assert_eq!(entries_then_remove(&dir), ["a.txt"]);
    }

    #[test]
    fn atomic_write_leaves_nothing_on_error_and_keeps_the_old_file() {
        let dir = tmpdir("err");
        let p = dir.join("b.obj");
        let r = write_atomically(&p, |w| {
            w.write_all(&[b'x'; 3_000_000]).unwrap(); // more than the buffer: reaches the file
            Err(Error::InvalidArgument("failing closure".into()))
        });
        assert!(matches!(r, Err(Error::InvalidArgument(ref m)) if m == "failing closure"));
        let q = dir.join("c.off");
        std::fs::write(&q, b"old contents").unwrap();
        let r = write_atomically(&q, |w| {
            w.write_all(b"new").unwrap();
            Err(Error::Unsupported("no".into()))
        });
        assert!(r.is_err());
        assert_eq!(std::fs::read(&q).unwrap(), b"old contents");
        assert_eq!(entries_then_remove(&dir), ["c.off"]);
    }

    #[test]
    fn atomic_write_into_missing_directory_is_an_io_error() {
        let dir = tmpdir("missing");
        let p = dir.join("no/such/dir/d.ply");
        match write_atomically(&p, |_| Ok(())) {
            Err(Error::Io { path, .. }) => assert_eq!(path, p),
            other => panic!("expected Io error, got {other:?}"),
        }
        assert!(entries_then_remove(&dir).is_empty());
    }
}
