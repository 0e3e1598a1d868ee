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

/// The pages whose measured tables must be generated (issue 51): every table with numbers on them
/// is an `{{#include tables/NAME.md}}` of a file a measuring script wrote.
const MEASURED_PAGES: [&str; 2] = [
    "docs/guide/src/performance.md",
    "docs/guide/src/performance-rust-peers.md",
];

/// The lines of a page outside fenced code blocks, numbered from 1.
fn lines_outside_code(text: &str) -> Vec<(usize, &str)> {
    let mut fence: Option<char> = None;
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let t = line.trim();
        let mark = ['`', '~']
            .into_iter()
            .find(|&c| t.starts_with(&String::from(c).repeat(3)));
        match (fence, mark) {
            (None, Some(c)) => fence = Some(c),
            (Some(f), Some(c)) if f == c && t.chars().all(|x| x == c) => fence = None,
            (None, None) => out.push((i + 1, line)),
            _ => {}
        }
    }
    out
}

/// The problems of the measured page `page` (its text `text`; `root` is the repository, whose
/// relative paths the headers use): a `| ... |` row with a digit outside an include, and for each
/// `{{#include FILE}}` the problems of FILE's generated header ([`generated_table_problems`]).
fn measured_page_problems(root: &Path, page: &str, text: &str) -> Vec<String> {
    let mut problems = Vec::new();
    let dir = Path::new(page).parent().expect("a page in a folder");
    for (number, line) in lines_outside_code(text) {
        let t = line.trim();
        if t.starts_with('|') && t.ends_with('|') && t.chars().any(|c| c.is_ascii_digit()) {
            problems.push(format!(
                "{page}:{number}: a table row with numbers written by hand (generate it with its \
                 script's TABLE=docs/guide/src/tables/NAME.md and include it): {t}"
            ));
        }
        if let Some(rest) = t.strip_prefix("{{#include ") {
            let target = rest.trim_end_matches("}}").trim();
            let file = dir.join(target.split(':').next().unwrap_or(target));
            let rel = normalize(&file);
            match std::fs::read_to_string(root.join(&rel)) {
                Ok(table) => problems.extend(
                    generated_table_problems(root, &rel, &table)
                        .into_iter()
                        .map(|p| format!("{page}:{number}: {p}")),
                ),
                Err(e) => problems.push(format!("{page}:{number}: {}: {e}", rel.display())),
            }
        }
    }
    problems
}

/// `a/b/../c` as `a/c` (the include's path relative to the page, as a repository path).
fn normalize(p: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for c in p.components() {
        match c {
            std::path::Component::ParentDir => {
                out.pop();
            }
            std::path::Component::CurDir => {}
            c => out.push(c),
        }
    }
    out
}

/// The problems of a generated table file `rel` (repository path) with the text `table`: its
/// first line must be bench/table.sh's header (`_Generated by `COMMAND` on DATE UTC at commit
/// HASH; machine: N cores, M GiB RAM (CPU); load average ... before and ... after._`), the command
/// must write this very file (`TABLE=rel`) by a script that exists, and that script must contain
/// the code that writes it (it sources bench/table.sh, calls `table_write` and names `rel`).
fn generated_table_problems(root: &Path, rel: &Path, table: &str) -> Vec<String> {
    let rel_s = rel.display().to_string();
    let header = table.lines().next().unwrap_or("");
    let Some(rest) = header.strip_prefix("_Generated by `") else {
        return vec![format!(
            "{rel_s}: the first line is not the generated header (`_Generated by `COMMAND` \
             ...`, bench/table.sh): {header:?}"
        )];
    };
    let Some((command, tail)) = rest.split_once('`') else {
        return vec![format!(
            "{rel_s}: the header's command is not closed by a backtick"
        )];
    };
    let mut problems = Vec::new();
    for part in [
        " on ",
        " UTC at commit ",
        "; machine: ",
        " cores, ",
        " GiB RAM",
        "; load average ",
        " before and ",
    ] {
        if !tail.contains(part) {
            problems.push(format!("{rel_s}: the header lacks {part:?}: {header:?}"));
        }
    }
    if !tail.ends_with(" after._") {
        problems.push(format!(
            "{rel_s}: the header does not end with the load after"
        ));
    }
    if !table.lines().any(|l| l.trim_start().starts_with('|')) {
        problems.push(format!("{rel_s}: no table below the header"));
    }
    if !command
        .split_whitespace()
        .any(|w| w == format!("TABLE={rel_s}"))
    {
        problems.push(format!(
            "{rel_s}: the header's command `{command}` does not write this file (TABLE={rel_s})"
        ));
    }
    let script = command.split_whitespace().last().unwrap_or("");
    match std::fs::read_to_string(root.join(script)) {
        Err(e) => problems.push(format!(
            "{rel_s}: the header names the script {script:?}, which cannot be read: {e}"
        )),
        Ok(code) => {
            for needle in ["table.sh", "table_write", rel_s.as_str()] {
                if !contains_word(&code, needle) {
                    problems.push(format!(
                        "{rel_s}: the script {script} does not contain {needle:?} (the code that \
                         writes this table)"
                    ));
                }
            }
        }
    }
    problems
}

/// Whether `needle` occurs in `code` as a whole word (not followed or preceded by a letter,
/// digit or `_`: `table_writer` is not `table_write`).
fn contains_word(code: &str, needle: &str) -> bool {
    let word = |c: Option<char>| c.is_some_and(|c| c.is_alphanumeric() || c == '_');
    code.match_indices(needle).any(|(i, _)| {
        !word(code[..i].chars().next_back()) && !word(code[i + needle.len()..].chars().next())
    })
}

#[test]
fn measured_tables_are_generated_by_their_scripts() {
    let mut problems = Vec::new();
    for page in MEASURED_PAGES {
        let text = std::fs::read_to_string(repo().join(page)).expect("read a measured page");
        if !text.contains("{{#include tables/") {
            problems.push(format!("{page} includes no generated table"));
        }
        problems.extend(measured_page_problems(repo(), page, &text));
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

/// The check above finds each kind of problem (on pages and tables made up here, against the
/// repository's scripts).
#[test]
fn the_measured_table_check_can_fail() {
    let root = repo();
    let page = "docs/guide/src/performance.md";
    // a hand-written table with numbers; one without numbers and one in a code block pass
    let hand = "# P\n\n| a | b |\n| --- | --- |\n| x | 1.5 s |\n\n| a |\n| --- |\n| x |\n\n```text\n| 1 |\n```\n";
    let p = measured_page_problems(root, page, hand);
    assert_eq!(p.len(), 1, "{p:?}");
    assert!(p[0].contains(":5: a table row with numbers"), "{p:?}");
    // an include of a file that does not exist
    let p = measured_page_problems(root, page, "{{#include tables/no-such-table.md}}\n");
    assert_eq!(p.len(), 1, "{p:?}");
    assert!(
        p[0].contains("docs/guide/src/tables/no-such-table.md"),
        "{p:?}"
    );

    let rel = Path::new("docs/guide/src/tables/opensubdiv-refinement.md");
    let good = "_Generated by `REPS=1 TABLE=docs/guide/src/tables/opensubdiv-refinement.md \
                bench/run_peer.sh` on 2026-12-06 18:00 UTC at commit 0123456789; machine: 2 \
                cores, 23.5 GiB RAM (CPU); load average 1.0, 1.0, 1.0 before and 2.0, 1.0, 1.0 \
                after._\n\n| a | b |\n| --- | --- |\n| x | 1 |\n";
    assert_eq!(
        generated_table_problems(root, rel, good),
        Vec::<String>::new()
    );
    // no header
    let p = generated_table_problems(root, rel, "| a | b |\n| --- | --- |\n| x | 1 |\n");
    assert!(
        p.len() == 1 && p[0].contains("not the generated header"),
        "{p:?}"
    );
    // a header without the load after it
    let p = generated_table_problems(root, rel, &good.replace(" and 2.0, 1.0, 1.0 after", ""));
    assert!(p.iter().any(|m| m.contains("before and")), "{p:?}");
    // a script that does not exist
    let p = generated_table_problems(root, rel, &good.replace("run_peer.sh", "run_peers.sh"));
    assert!(
        p.len() == 1 && p[0].contains("bench/run_peers.sh") && p[0].contains("cannot be read"),
        "{p:?}"
    );
    // a script that exists but does not write this table (run_eval_cli.sh writes eval-cli.md)
    let p = generated_table_problems(root, rel, &good.replace("run_peer.sh", "run_eval_cli.sh"));
    assert!(
        p.len() == 1 && p[0].contains("does not contain") && p[0].contains("opensubdiv-refinement"),
        "{p:?}"
    );
    // a script with no table code at all
    let p = generated_table_problems(root, rel, &good.replace("bench/run_peer.sh", "Cargo.toml"));
    assert!(p.len() == 3, "{p:?}");
    // a script that calls another function than the writer
    assert!(contains_word("x | table_write\n", "table_write"));
    assert!(!contains_word("x | table_writer\n", "table_write"));
    assert!(!contains_word("my_table_write <f\n", "table_write"));
    // a table written for another file
    let other = Path::new("docs/guide/src/tables/eval-cli.md");
    let p = generated_table_problems(root, other, good);
    assert!(
        p.iter().any(|m| m.contains("does not write this file")),
        "{p:?}"
    );
}
