//! The architecture, checked: layers only point down, scheme names are spelled in the registry
//! only, and no source file is too long (ARCHITECTURE.md explains the layers).
//!
//! The checks read the sources as text. Code under `#[cfg(test)]` (unit tests) is left out:
//! a test may use any layer to build its fixtures.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The layers, lowest first, and the top-level modules of `src/` in each.
const LAYERS: &[(&str, &[&str])] = &[
    ("core", &["geom", "error", "stencil", "linalg", "buffers"]),
    ("topology", &["mesh"]),
    ("bezier", &["bezier"]),
    ("host", &["host"]),
    ("schemes", &["schemes"]),
    ("surface", &["surface"]),
    ("analysis", &["analysis"]),
    ("io", &["io", "gallery"]),
    ("render", &["render"]),
    ("front ends", &["cli", "facade", "lib", "main"]),
];

fn layer_of(module: &str) -> Option<usize> {
    LAYERS.iter().position(|(_, ms)| ms.contains(&module))
}

fn sources() -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![Path::new(env!("CARGO_MANIFEST_DIR")).join("src")];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|e| e == "rs") {
                out.push(p);
            }
        }
    }
    out.sort();
    out
}

/// The top-level module a source file belongs to (`src/schemes/eg/mod.rs` -> `schemes`).
fn module_of(p: &Path) -> String {
    let rel = p
        .strip_prefix(Path::new(env!("CARGO_MANIFEST_DIR")).join("src"))
        .unwrap();
    let first = rel
        .components()
        .next()
        .unwrap()
        .as_os_str()
        .to_string_lossy();
    first.trim_end_matches(".rs").to_string()
}

/// Whether a file holds unit tests only (`tests.rs`, `testing.rs`, or under a `tests/` folder).
fn is_test_file(p: &Path) -> bool {
    p.file_stem()
        .is_some_and(|s| s == "tests" || s == "testing")
        || p.components().any(|c| c.as_os_str() == "tests")
}

/// The source without comments, string and char literal contents (a literal becomes `"$k"`,
/// `k` its index in `strings`), and without items marked `#[cfg(test)]`; `strings` receives the
/// string literals of the code that is left.
fn code_only(src: &str, strings: &mut Vec<String>) -> String {
    let b: Vec<char> = src.chars().collect();
    let mut out = String::with_capacity(src.len());
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        let next = b.get(i + 1).copied();
        if c == '/' && next == Some('/') {
            while i < b.len() && b[i] != '\n' {
                i += 1;
            }
        } else if c == '/' && next == Some('*') {
            let mut depth = 0;
            while i < b.len() {
                if b[i] == '/' && b.get(i + 1) == Some(&'*') {
                    depth += 1;
                    i += 2;
                } else if b[i] == '*' && b.get(i + 1) == Some(&'/') {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    i += 1;
                }
            }
        } else if c == 'r'
            && (next == Some('"') || (next == Some('#') && b.get(i + 2) == Some(&'"')))
            && (i == 0 || !(b[i - 1].is_alphanumeric() || b[i - 1] == '_'))
        {
            // Raw string r"..." or r#"..."#.
            let mut hashes = 0;
            i += 1;
            while b[i] == '#' {
                hashes += 1;
                i += 1;
            }
            i += 1;
            let start = i;
            loop {
                if b[i] == '"' && (0..hashes).all(|k| b.get(i + 1 + k) == Some(&'#')) {
                    break;
                }
                i += 1;
            }
            out.push_str(&format!("\"${}\"", strings.len()));
            strings.push(b[start..i].iter().collect());
            i += 1 + hashes;
        } else if c == '"' {
            i += 1;
            let start = i;
            while b[i] != '"' {
                if b[i] == '\\' {
                    i += 1;
                }
                i += 1;
            }
            out.push_str(&format!("\"${}\"", strings.len()));
            strings.push(b[start..i].iter().collect());
            i += 1;
        } else if c == '\''
            && (next == Some('\\') && b.get(i + 3) == Some(&'\'') || b.get(i + 2) == Some(&'\''))
        {
            // A char literal ('a', '\n'); lifetimes ('a) pass through.
            i += if next == Some('\\') { 4 } else { 3 };
            out.push_str("' '");
        } else {
            out.push(c);
            i += 1;
        }
    }
    let kept = strip_cfg_test(&out);
    // Keep the literals of the code that is left.
    let mut left = Vec::new();
    let mut rest = kept.as_str();
    while let Some(k) = rest.find("\"$") {
        let tail = &rest[k + 2..];
        let end = tail.find('"').unwrap_or(tail.len());
        if let Ok(idx) = tail[..end].parse::<usize>() {
            left.push(std::mem::take(&mut strings[idx]));
        }
        rest = &tail[end..];
    }
    *strings = left;
    kept
}

/// Removes every item that follows a `#[cfg(test)]` attribute (up to its matching brace or
/// semicolon).
fn strip_cfg_test(code: &str) -> String {
    let mut out = String::with_capacity(code.len());
    let mut rest = code;
    while let Some(k) = rest.find("#[cfg(test)]") {
        out.push_str(&rest[..k]);
        let after = &rest[k..];
        let mut depth = 0;
        let mut end = after.len();
        for (j, ch) in after.char_indices() {
            match ch {
                '{' => depth += 1,
                '}' => {
                    depth -= 1;
                    if depth == 0 {
                        end = j + 1;
                        break;
                    }
                }
                ';' if depth == 0 => {
                    end = j + 1;
                    break;
                }
                _ => {}
            }
        }
        rest = &after[end..];
    }
    out.push_str(rest);
    out
}

/// The top-level modules named by `crate::X` paths in a piece of code (also inside `use
/// crate::{a, b::c}` groups).
fn crate_paths(code: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = code;
    while let Some(k) = rest.find("crate::") {
        let before = rest[..k].chars().last();
        rest = &rest[k + 7..];
        if before.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == '$') {
            continue;
        }
        if let Some(group) = rest.strip_prefix('{') {
            let end = group.find('}').unwrap_or(group.len());
            for item in group[..end].split(',') {
                let name: String = item
                    .trim()
                    .chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_')
                    .collect();
                if !name.is_empty() {
                    out.push(name);
                }
            }
        } else {
            let name: String = rest
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            out.push(name);
        }
    }
    out
}

#[test]
fn layers_only_point_down() {
    let mut violations = Vec::new();
    for p in sources() {
        if is_test_file(&p) {
            continue;
        }
        let module = module_of(&p);
        let Some(own) = layer_of(&module) else {
            violations.push(format!("{}: module '{module}' is in no layer", p.display()));
            continue;
        };
        let code = code_only(&std::fs::read_to_string(&p).unwrap(), &mut Vec::new());
        for target in crate_paths(&code) {
            match layer_of(&target) {
                Some(l) if l > own => violations.push(format!(
                    "{}: {} ({}) uses crate::{target} ({})",
                    p.display(),
                    module,
                    LAYERS[own].0,
                    LAYERS[l].0
                )),
                Some(_) => {}
                None if ["Error", "Result", "Point", "PolyMesh", "MeshError"]
                    .contains(&target.as_str()) => {}
                None => violations.push(format!("{}: crate::{target} is in no layer", p.display())),
            }
        }
    }
    assert!(
        violations.is_empty(),
        "{} imports of a higher layer:\n{}",
        violations.len(),
        violations.join("\n")
    );
}

/// The registry's names and aliases, read from the registry source.
fn scheme_names() -> Vec<String> {
    fairsub::schemes::registry()
        .entries()
        .iter()
        .flat_map(|e| std::iter::once(e.name).chain(e.aliases.iter().copied()))
        .map(str::to_string)
        .collect()
}

#[test]
fn scheme_names_are_spelled_in_the_registry_only() {
    let names = scheme_names();
    let mut found = Vec::new();
    for p in sources() {
        if is_test_file(&p) || p.ends_with("schemes/registry.rs") {
            continue;
        }
        let mut strings = Vec::new();
        code_only(&std::fs::read_to_string(&p).unwrap(), &mut strings);
        for s in strings {
            // A literal that is a name, or that spells one as a word ("scheme 'eg' has ...");
            // names that are also English words ("loop", "non-box") only as a whole literal.
            let words: Vec<&str> = s
                .split(|c: char| !(c.is_ascii_alphanumeric() || c == '-' || c == '.'))
                .map(|w| w.trim_end_matches('.'))
                .collect();
            for n in &names {
                let prose = ["loop", "non-box"].contains(&n.as_str());
                if s == *n || (!prose && words.contains(&n.as_str())) {
                    found.push(format!("{}: \"{s}\" spells '{n}'", p.display()));
                }
            }
        }
    }
    assert!(
        found.is_empty(),
        "{} scheme names outside the registry:\n{}",
        found.len(),
        found.join("\n")
    );
}

#[test]
fn no_source_file_is_too_long() {
    let mut long = BTreeMap::new();
    for p in sources() {
        if is_test_file(&p) {
            continue;
        }
        let text = std::fs::read_to_string(&p).unwrap();
        let code = strip_cfg_test(&text);
        let lines = code.lines().count();
        if lines > 700 {
            long.insert(p.display().to_string(), lines);
        }
    }
    assert!(long.is_empty(), "files over 700 lines: {long:?}");
}
