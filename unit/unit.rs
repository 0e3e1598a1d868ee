//! Runs the library's unit tests (`fairsub::unit::TESTS`, see src/unit.rs) with libtest's
//! command line.
//!
//! Before running them it reads ../src and checks that the list holds every test written there:
//! the tests are gathered by the linker, so a test it dropped would otherwise pass unnoticed,
//! and a libtest `#[test]` left in src/ would never run.

use libtest_mimic::{Arguments, Trial};
use std::path::Path;

fn main() {
    let args = Arguments::from_args();
    let tests = &fairsub::unit::TESTS;
    if let Err(why) = check_list(tests.len()) {
        eprintln!("fairsub-unit: {why}");
        std::process::exit(101);
    }
    let mut trials: Vec<Trial> = tests
        .iter()
        .map(|t| {
            let run = t.run;
            let name = t.path.strip_prefix("fairsub::").unwrap_or(t.path);
            Trial::test(name, move || {
                run();
                Ok(())
            })
            .with_ignored_flag(t.ignore.is_some())
        })
        .collect();
    trials.sort_by(|a, b| a.name().cmp(b.name()));
    libtest_mimic::run(&args, trials).exit();
}

/// Counts `#[crate::unit::test]` in the library's sources and compares with `registered`;
/// refuses a plain `#[test]` there.
fn check_list(registered: usize) -> Result<(), String> {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("../src");
    let mut written = 0;
    let mut stack = vec![src];
    while let Some(dir) = stack.pop() {
        let entries = std::fs::read_dir(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
        for entry in entries {
            let path = entry.map_err(|e| format!("{}: {e}", dir.display()))?.path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                let text = std::fs::read_to_string(&path)
                    .map_err(|e| format!("{}: {e}", path.display()))?;
                for (k, line) in text.lines().enumerate() {
                    match line.trim() {
                        "#[crate::unit::test]" => written += 1,
                        "#[test]" => {
                            return Err(format!(
                                "{}:{}: `#[test]` does not run in the library; write \
                                 `#[crate::unit::test]` (src/unit.rs)",
                                path.display(),
                                k + 1
                            ));
                        }
                        _ => {}
                    }
                }
            }
        }
    }
    if written != registered {
        return Err(format!(
            "src/ marks {written} unit tests but the library registered {registered}"
        ));
    }
    Ok(())
}
