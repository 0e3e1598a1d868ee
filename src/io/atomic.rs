//! Atomic output: every writer fills a temporary file beside its target and renames it into
//! place only when everything was written, so a failure never leaves a half-written file.
//!
//! A front end that writes many files (`fairsub batch`) can *stage* the writes instead
//! ([`staged`]): the writers fill their temporary files as always, but the sync and the rename
//! wait for [`commit`], which syncs a whole group of files at once (one `syncfs` on Linux
//! instead of one `fsync` per file) before renaming each into place. The guarantee is the same
//! (a target is the complete file or untouched), the cost of durability is shared.

use super::text::io_error;
use crate::error::{Error, Result};
use std::cell::RefCell;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

static TEMP_COUNTER: AtomicU64 = AtomicU64::new(0);

thread_local! {
    /// The files written under [`staged`] on this thread, waiting for [`commit`].
    static STAGING: RefCell<Option<Vec<Staged>>> = const { RefCell::new(None) };
}

/// A complete file under its temporary name, waiting to be moved over its target.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Staged {
    /// The temporary file beside the target (a hidden name: `.NAME.tmp-PID-N`).
    pub temp: PathBuf,
    /// The file it becomes.
    pub target: PathBuf,
}

/// How [`commit`] makes the staged files durable before renaming them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Durability {
    /// `fsync` each file (what a single write does).
    EachFile,
    /// One `syncfs` of the file system of the first file (Linux; elsewhere each file): for
    /// many small files at once.
    FileSystem,
}

/// Runs `f` with this thread's atomic writes staged: each writer fills its temporary file
/// but neither syncs nor renames it; the files are returned for [`commit`] (or [`discard`],
/// when `f` failed). Nested calls stage into the outermost list.
pub fn staged<T>(f: impl FnOnce() -> T) -> (T, Vec<Staged>) {
    let outer = STAGING.with(|s| s.borrow().is_some());
    if outer {
        return (f(), Vec::new());
    }
    STAGING.with(|s| *s.borrow_mut() = Some(Vec::new()));
    // taken back also when `f` panics, so a caught panic leaves the thread unstaged
    struct Reset;
    impl Drop for Reset {
        fn drop(&mut self) {
            STAGING.with(|s| s.borrow_mut().take());
        }
    }
    let reset = Reset;
    let r = f();
    let files = STAGING.with(|s| s.borrow_mut().take()).unwrap_or_default();
    drop(reset);
    (r, files)
}

/// Makes the staged files durable (`how`) and renames each over its target; stops at the
/// first failure with the error naming that target (the files not renamed stay staged:
/// [`discard`] them).
pub fn commit(files: &[Staged], how: Durability) -> Result<()> {
    let sync_each = |files: &[Staged]| -> Result<()> {
        for f in files {
            let file = std::fs::File::open(&f.temp).map_err(|e| io_error(&f.target, e))?;
            file.sync_all().map_err(|e| io_error(&f.target, e))?;
        }
        Ok(())
    };
    match (how, files.first()) {
        (_, None) => return Ok(()),
        #[cfg(target_os = "linux")]
        (Durability::FileSystem, Some(first)) => {
            use std::os::fd::AsRawFd;
            let file = std::fs::File::open(&first.temp).map_err(|e| io_error(&first.target, e))?;
            // SAFETY: syncfs takes an open descriptor, which `file` owns while it runs.
            if unsafe { libc::syncfs(file.as_raw_fd()) } != 0 {
                return Err(io_error(&first.target, std::io::Error::last_os_error()));
            }
            // a file on another file system than the first is synced alone
            let dev = |p: &Path| {
                use std::os::unix::fs::MetadataExt;
                std::fs::metadata(p).map(|m| m.dev()).ok()
            };
            let d0 = dev(&first.temp);
            let others: Vec<Staged> = files
                .iter()
                .filter(|f| dev(&f.temp) != d0)
                .cloned()
                .collect();
            sync_each(&others)?;
        }
        _ => sync_each(files)?,
    }
    for f in files {
        std::fs::rename(&f.temp, &f.target).map_err(|e| io_error(&f.target, e))?;
    }
    Ok(())
}

/// Removes staged files that will not be committed (their targets stay as they were).
pub fn discard(files: &[Staged]) {
    for f in files {
        let _ = std::fs::remove_file(&f.temp);
    }
}

/// Removes the temporary files that writes of `target` left behind when their process was
/// stopped before it could clean up (`.NAME.tmp-*` beside it); returns how many. Only for a
/// caller that knows no write of `target` is under way.
pub fn remove_stale_temps(target: &Path) -> usize {
    let (Some(name), dir) = (target.file_name(), target.parent()) else {
        return 0;
    };
    let dir = match dir {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let prefix = format!(".{}.tmp-", name.to_string_lossy());
    let Ok(entries) = std::fs::read_dir(dir) else {
        return 0;
    };
    entries
        .flatten()
        .filter(|e| e.file_name().to_string_lossy().starts_with(&prefix))
        .filter(|e| std::fs::remove_file(e.path()).is_ok())
        .count()
}

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
/// which is flushed, synced and renamed over `path` only when `write` succeeded (under
/// [`staged`]: flushed and handed to the caller, who commits it). On any error
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
    let staging = STAGING.with(|s| s.borrow().is_some());
    if staging {
        drop(file);
        STAGING.with(|s| {
            if let Some(list) = s.borrow_mut().as_mut() {
                list.push(Staged {
                    temp: tmp.clone(),
                    target: path.to_path_buf(),
                });
            }
        });
        guard.armed = false;
        return Ok(());
    }
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

#[cfg(feature = "unit-tests")]
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

    #[crate::unit::test]
    fn atomic_write_commits_on_success() {
        let dir = tmpdir("ok");
        let p = dir.join("a.txt");
        write_bytes_atomically(&p, b"hello").unwrap();
        assert_eq!(std::fs::read(&p).unwrap(), b"hello");
        assert_eq!(entries_then_remove(&dir), ["a.txt"]);
    }

    #[crate::unit::test]
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

    #[crate::unit::test]
    fn staged_writes_wait_for_commit_or_discard() {
        let dir = tmpdir("staged");
        let (a, b) = (dir.join("a.obj"), dir.join("b.bv"));
        std::fs::write(&b, b"old").unwrap();
        let (r, files) = staged(|| {
            write_bytes_atomically(&a, b"new a")?;
            write_bytes_atomically(&b, b"new b")
        });
        r.unwrap();
        assert_eq!(files.len(), 2);
        assert!(!a.exists(), "nothing in place before the commit");
        assert_eq!(std::fs::read(&b).unwrap(), b"old");
        commit(&files, Durability::FileSystem).unwrap();
        assert_eq!(std::fs::read(&a).unwrap(), b"new a");
        assert_eq!(std::fs::read(&b).unwrap(), b"new b");
        let (_, files) = staged(|| write_bytes_atomically(&a, b"newer"));
        discard(&files);
        assert_eq!(std::fs::read(&a).unwrap(), b"new a");
        // a temporary file left by a stopped process is found by its target's name
        std::fs::write(dir.join(".a.obj.tmp-1-2"), b"half").unwrap();
        assert_eq!(remove_stale_temps(&a), 1);
        assert_eq!(entries_then_remove(&dir), ["a.obj", "b.bv"]);
    }

    #[crate::unit::test]
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
