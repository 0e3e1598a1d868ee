//! The `fairsub` command-line tool.
//!
//! Exit codes: 0 success, 1 bad input (message on stderr), 2 usage error. Outputs are written
//! atomically: on any error no output file is created or left half-written.

use std::process::ExitCode;

fn main() -> ExitCode {
    // Rust ignores SIGPIPE, so `fairsub ... | head` would panic on the closed pipe; restore the
    // default so the tool ends quietly like other Unix tools.
    #[cfg(unix)]
    // SAFETY: setting a signal disposition to its default before any thread starts.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    fairsub::cli::main()
}
