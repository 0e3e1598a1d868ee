//! The memory budget of the command line (`--max-memory`, or half of what the process may use)
//! and the shared checks that compare an estimate with it or with the 32-bit index bound, with
//! the messages that give the estimate and the way out. The per-command estimates live in
//! [`super`].

use super::MAX_ELEMENTS;
use crate::error::{Error, Result};
use std::cell::Cell;

thread_local! {
    /// The budget set by `--max-memory` for the command running on this thread.
    static BUDGET: Cell<Option<u64>> = const { Cell::new(None) };
}

/// A memory budget with where it comes from.
#[derive(Debug, Clone)]
pub struct Budget {
    /// Bytes.
    pub bytes: f64,
    /// How it was chosen (for messages).
    pub source: String,
}

/// Runs `f` with the budget `max` (bytes; `None`: the default) for the commands on this thread.
pub(crate) fn with_budget<T>(max: Option<u64>, f: impl FnOnce() -> T) -> T {
    let old = BUDGET.with(|b| b.replace(max));
    let r = f();
    BUDGET.with(|b| b.set(old));
    r
}

/// The `--max-memory` of the command running on this thread, if one was given.
pub(crate) fn max_memory() -> Option<u64> {
    BUDGET.with(Cell::get)
}

/// The budget of the command running on this thread.
pub fn budget() -> Budget {
    match BUDGET.with(Cell::get) {
        Some(b) => Budget {
            bytes: b as f64,
            source: "set by --max-memory".into(),
        },
        None => default_budget(),
    }
}

/// The default budget: half of the smallest memory limit of the process (see the module
/// documentation).
pub fn default_budget() -> Budget {
    let (limit, what) = process_memory_limit();
    Budget {
        bytes: limit / 2.0,
        source: format!("half of {what}, {}", human(limit)),
    }
}

/// The smallest memory limit that applies to this process, with its name.
pub(super) fn process_memory_limit() -> (f64, &'static str) {
    let mut best = (f64::INFINITY, "the memory of the machine");
    let mut take = |bytes: f64, what: &'static str| {
        if bytes > 0.0 && bytes < best.0 {
            best = (bytes, what);
        }
    };
    #[cfg(unix)]
    {
        // SAFETY: sysconf and getrlimit only read process and system parameters.
        let (pages, page) = unsafe {
            (
                libc::sysconf(libc::_SC_PHYS_PAGES),
                libc::sysconf(libc::_SC_PAGESIZE),
            )
        };
        if pages > 0 && page > 0 {
            take(pages as f64 * page as f64, "the physical memory");
        }
        for (res, what) in [
            (libc::RLIMIT_AS, "the address-space limit (ulimit -v)"),
            (libc::RLIMIT_DATA, "the data-segment limit (ulimit -d)"),
        ] {
            let mut r = libc::rlimit {
                rlim_cur: 0,
                rlim_max: 0,
            };
            // SAFETY: `r` is a valid rlimit to fill.
            if unsafe { libc::getrlimit(res, &mut r) } == 0 && r.rlim_cur != libc::RLIM_INFINITY {
                take(r.rlim_cur as f64, what);
            }
        }
    }
    if let Ok(s) = std::fs::read_to_string("/sys/fs/cgroup/memory.max")
        && let Ok(b) = s.trim().parse::<f64>()
    {
        take(b, "the cgroup memory limit");
    }
    if !best.0.is_finite() {
        // Nothing known: assume a small machine.
        best = (8.0 * GIB, "an assumed 8 GiB (no limit could be read)");
    }
    best
}

pub(super) const GIB: f64 = 1073741824.0;

/// Parses a memory size: a number with an optional binary unit (`K`, `M`, `G`, `T`, with or
/// without `B` / `iB`; case-insensitive).
pub fn parse_memory(s: &str) -> Result<u64> {
    let bad = || {
        Error::InvalidArgument(format!(
            "bad --max-memory '{s}': expected a size such as 4G, 512M or 2.5GiB (binary units)"
        ))
    };
    let t = s.trim().to_ascii_lowercase();
    let t = t
        .strip_suffix("ib")
        .or_else(|| t.strip_suffix('b'))
        .unwrap_or(&t);
    let (num, unit) = match t.char_indices().last() {
        Some((i, c)) if c.is_ascii_alphabetic() => (&t[..i], c),
        _ => (t, ' '),
    };
    let scale = match unit {
        ' ' => 1.0,
        'k' => 1024.0,
        'm' => 1024.0 * 1024.0,
        'g' => GIB,
        't' => 1024.0 * GIB,
        _ => return Err(bad()),
    };
    let x: f64 = num.trim().parse().map_err(|_| bad())?;
    let bytes = x * scale;
    if !bytes.is_finite() || !(1.0..=1.8e19).contains(&bytes) {
        return Err(bad());
    }
    Ok(bytes as u64)
}

/// A size in bytes for messages (`3.2 GiB`).
pub fn human(bytes: f64) -> String {
    let units = ["bytes", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"];
    let mut x = bytes;
    let mut u = 0;
    while x >= 1024.0 && u + 1 < units.len() {
        x /= 1024.0;
        u += 1;
    }
    if u + 1 == units.len() && x >= 1024.0 {
        return format!("{bytes:.1e} bytes");
    }
    if u == 0 {
        format!("{x:.0} bytes")
    } else {
        format!("{x:.1} {}", units[u])
    }
}

/// A count for messages: exact below a million, else `1.6e9`.
pub(super) fn count(x: f64) -> String {
    if x < 1e6 {
        format!("{x:.0}")
    } else {
        format!("{x:.2e}")
    }
}

/// The error for an estimate over the budget: `what` is what would be made, `lower` the
/// options that make it smaller.
pub(super) fn over_budget(what: &str, bytes: f64, b: &Budget, lower: &str) -> Error {
    let want = (bytes * 1.5).max(b.bytes * 2.0);
    let suggest = if want < GIB {
        format!("{}M", (want / 1048576.0).ceil())
    } else if want < 1e6 * GIB {
        format!("{}G", (want / GIB).ceil())
    } else {
        "SIZE".to_string()
    };
    Error::TooLarge(format!(
        "{what} would need about {}, more than the memory budget of {} ({}); {lower}, or \
         raise the budget with --max-memory SIZE (e.g. --max-memory {suggest})",
        human(bytes),
        human(b.bytes),
        b.source,
    ))
}

/// Checks `bytes` against the budget.
pub(super) fn within_budget(what: impl FnOnce() -> String, bytes: f64, lower: &str) -> Result<()> {
    let b = budget();
    if bytes.is_nan() || bytes > b.bytes {
        return Err(over_budget(&what(), bytes, &b, lower));
    }
    Ok(())
}

/// Checks that counts fit fairsub's 32-bit indices.
pub(super) fn within_indices(
    what: impl FnOnce() -> String,
    vertices: f64,
    corners: f64,
    lower: &str,
) -> Result<()> {
    if vertices >= MAX_ELEMENTS || corners >= MAX_ELEMENTS || vertices.is_nan() {
        return Err(Error::TooLarge(format!(
            "{} would have about {} vertices and {} corners; fairsub's meshes index with 32 \
             bits and take fewer than 2^31 of each: {lower}",
            what(),
            count(vertices),
            count(corners)
        )));
    }
    Ok(())
}
