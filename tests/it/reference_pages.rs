//! The guide's generated reference pages equal what the binary prints (`docs/make-reference.sh`
//! writes them), and every page with a Rust snippet is a doctest (the `doctests` module of
//! `src/lib.rs`).

use std::path::{Path, PathBuf};
use std::process::Command;

fn repo() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// What `fairsub ARGS` prints (it must succeed).
fn printed(args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_fairsub"))
        .args(args)
        .output()
        .expect("run fairsub");
    assert!(
        out.status.success(),
        "fairsub {args:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).expect("UTF-8 output")
}

/// Compares a checked-in page with the binary's output; the message names the first line that
/// differs.
fn assert_page(page: &str, args: &[&str]) {
    let path = repo().join(page);
    let checked_in = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("{}: {e} (run docs/make-reference.sh)", path.display()));
    let now = printed(args);
    if checked_in != now {
        let first = checked_in
            .lines()
            .zip(now.lines())
            .position(|(a, b)| a != b)
            .unwrap_or_else(|| checked_in.lines().count().min(now.lines().count()));
        panic!(
            "{page} differs from `fairsub {}` from line {} on ({} vs {} lines): run \
             docs/make-reference.sh and commit the page\n  page:   {:?}\n  binary: {:?}",
            args.join(" "),
            first + 1,
            checked_in.lines().count(),
            now.lines().count(),
            checked_in.lines().nth(first).unwrap_or(""),
            now.lines().nth(first).unwrap_or("")
        );
    }
}

#[test]
fn cli_reference_equals_the_binary() {
    assert_page("docs/guide/src/reference/cli.md", &["help-markdown"]);
}

#[test]
fn scheme_catalogue_equals_the_registry() {
    assert_page(
        "docs/guide/src/reference/schemes.md",
        &["schemes", "--markdown"],
    );
}

#[test]
fn cli_reference_covers_every_visible_command() {
    let page = printed(&["help-markdown"]);
    let help = printed(&["--help"]);
    // the command list of `fairsub --help`: two-space indented names up to the blank line
    let commands: Vec<&str> = help
        .split("Commands:\n")
        .nth(1)
        .expect("a command list")
        .lines()
        .take_while(|l| !l.trim().is_empty())
        .filter_map(|l| l.split_whitespace().next())
        .filter(|c| *c != "help")
        .collect();
    assert!(commands.len() >= 10, "{commands:?}");
    for c in commands {
        assert!(
            page.contains(&format!("\n## `fairsub {c}`\n")),
            "no section for fairsub {c}"
        );
        let sub = printed(&[c, "--help"]);
        // every long option of the command's help is in its section
        let section = page
            .split(&format!("\n## `fairsub {c}`\n"))
            .nth(1)
            .and_then(|s| s.split("\n## `").next())
            .unwrap_or("");
        for word in sub.split_whitespace() {
            let opt = word.trim_end_matches(',');
            if opt.starts_with("--")
                && opt.len() > 2
                && opt[2..]
                    .chars()
                    .all(|ch| ch.is_ascii_alphanumeric() || ch == '-')
                && sub.contains(&format!("  {opt}"))
                && !["--help", "--version", "--max-memory"].contains(&opt)
            {
                assert!(
                    section.contains(opt),
                    "fairsub {c}: {opt} is missing from its section"
                );
            }
        }
    }
}

#[test]
fn scheme_catalogue_has_every_scheme() {
    let page = printed(&["schemes", "--markdown"]);
    let json: serde_json::Value =
        serde_json::from_str(&printed(&["schemes", "--json"])).expect("JSON catalogue");
    let names: Vec<&str> = json
        .as_array()
        .expect("an array")
        .iter()
        .map(|r| r["name"].as_str().expect("a name"))
        .collect();
    assert!(names.len() >= 20, "{names:?}");
    for n in names {
        assert!(page.contains(&format!("\n## {n}\n")), "no section for {n}");
        assert!(
            page.contains(&format!("| [`{n}`](#")),
            "no table row for {n}"
        );
    }
}

/// README.md and the guide's pages.
fn pages() -> Vec<PathBuf> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        for e in std::fs::read_dir(dir).expect("read the guide").flatten() {
            let p = e.path();
            if p.is_dir() {
                walk(&p, out);
            } else if p.extension().is_some_and(|x| x == "md") {
                out.push(p);
            }
        }
    }
    let mut out = vec![repo().join("README.md")];
    walk(&repo().join("docs/guide/src"), &mut out);
    out.sort();
    out
}

#[test]
fn pages_with_rust_snippets_are_doctests() {
    let doctests = std::fs::read_to_string(repo().join("src/lib.rs")).expect("src/lib.rs");
    let mut missing = Vec::new();
    for page in pages() {
        let text = std::fs::read_to_string(&page).expect("read a page");
        let has_rust = text.lines().any(|l| {
            let t = l.trim_start();
            t.strip_prefix("```")
                .is_some_and(|info| info.trim().split(',').next() == Some("rust"))
        });
        let rel = page.strip_prefix(repo()).expect("in the repository");
        let listed = doctests.contains(&format!("include_str!(\"../{}\")", rel.display()));
        if has_rust && !listed {
            missing.push(rel.display().to_string());
        }
    }
    assert!(
        missing.is_empty(),
        "pages with ```rust blocks that the doctests module of src/lib.rs does not include \
         (add `#[doc = include_str!(\"../PAGE\")] pub struct Name;` per page): {missing:?}"
    );
}
