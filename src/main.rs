//! The `fairsub` command-line tool.
//!
//! Exit codes: 0 success, 1 bad input (message on stderr), 2 usage error. Outputs are written
//! atomically: on any error no output file is created or left half-written.

mod cli;

use clap::Parser;
use std::process::ExitCode;

fn main() -> ExitCode {
    let args = cli::Cli::parse();
    match cli::run(args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(1)
        }
    }
}
