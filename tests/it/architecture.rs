//! The architecture, checked: layers only point down, scheme names are spelled in the ids and
//! the families' catalogue rows only, no scheme family reaches up to the registry, the folders
//! of `src/schemes/` import each other without a circle, and no source file is too long
//! (ARCHITECTURE.md explains the layers).
//!
//! The checks read the sources as text. Code under `#[cfg(feature = "unit-tests")]` (unit
//! tests, src/unit.rs) is left out: a test may use any layer to build its fixtures.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The layers, lowest first, and the top-level modules of `src/` in each.
const LAYERS: &[(&str, &[&str])] = &[
    // `unit`: the unit tests' list and attribute (src/unit.rs), which tests at every layer use.
    (
        "core",
        &["geom", "error", "stencil", "linalg", "buffers", "unit"],
    ),
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

/// Whether a file holds unit tests only (`tests.rs`, `NAME_tests.rs`, `testing.rs`, or under a
/// `tests/` folder).
fn is_test_file(p: &Path) -> bool {
    p.file_stem()
        .and_then(|s| s.to_str())
        .is_some_and(|s| s == "tests" || s == "testing" || s.ends_with("_tests"))
        || p.components().any(|c| c.as_os_str() == "tests")
}

/// The source read once as Rust's lexer would for comments and literals. Without
/// `keep_lines`, comments go and each string literal becomes `"$k"`, `k` its index in the
/// returned literals; with it, comments and literal contents become spaces (newlines kept),
/// so that braces are the code's and line numbers the file's. A char literal becomes `' '`;
/// lifetimes (`'a`, no closing quote) pass through.
fn lex(src: &str, keep_lines: bool) -> (String, Vec<String>) {
    let b: Vec<char> = src.chars().collect();
    let mut out = String::with_capacity(src.len());
    let mut strings = Vec::new();
    // What is skipped (a comment, a literal's contents): kept as blanks with `keep_lines`.
    let skip = |out: &mut String, part: &[char]| {
        if keep_lines {
            out.extend(part.iter().map(|&c| if c == '\n' { '\n' } else { ' ' }));
        }
    };
    let mut literal = |out: &mut String, part: &[char]| {
        if keep_lines {
            out.push('"');
            skip(out, part);
            out.push('"');
        } else {
            out.push_str(&format!("\"${}\"", strings.len()));
            strings.push(part.iter().collect::<String>());
        }
    };
    let mut i = 0;
    while i < b.len() {
        let (c, next) = (b[i], b.get(i + 1).copied());
        let start = i;
        if c == '/' && next == Some('/') {
            while i < b.len() && b[i] != '\n' {
                i += 1;
            }
            skip(&mut out, &b[start..i]);
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
            skip(&mut out, &b[start..i.min(b.len())]);
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
            let from = i;
            while !(b[i] == '"' && (0..hashes).all(|k| b.get(i + 1 + k) == Some(&'#'))) {
                i += 1;
            }
            literal(&mut out, &b[from..i]);
            i += 1 + hashes;
        } else if c == '"' {
            i += 1;
            let from = i;
            while b[i] != '"' {
                if b[i] == '\\' {
                    i += 1;
                }
                i += 1;
            }
            literal(&mut out, &b[from..i]);
            i += 1;
        } else if c == '\'' && (next == Some('\\') || b.get(i + 2) == Some(&'\'')) {
            // A char literal ('a', '\n', '\u{..}').
            i += 1;
            while b[i] != '\'' {
                if b[i] == '\\' {
                    i += 1;
                }
                i += 1;
            }
            i += 1;
            out.push_str("' '");
        } else {
            out.push(c);
            i += 1;
        }
    }
    (out, strings)
}

/// The source without comments, string and char literal contents (a literal becomes `"$k"`,
/// `k` its index in `strings`), and without the unit tests' items ([`UNIT_CFG`]); `strings` receives the
/// string literals of the code that is left.
fn code_only(src: &str, strings: &mut Vec<String>) -> String {
    // The attribute's string literal would become `"$k"` below: mark it without one first.
    let src = src.replace(UNIT_CFG, UNIT_CFG_CODE);
    let (out, all) = lex(&src, false);
    *strings = all;
    let kept = strip_unit_tests(&out, UNIT_CFG_CODE);
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

/// The attribute of the library's unit tests (src/unit.rs).
const UNIT_CFG: &str = "#[cfg(feature = \"unit-tests\")]";
/// [`UNIT_CFG`] as [`code_only`] writes it, without a string literal.
const UNIT_CFG_CODE: &str = "#[cfg(unit_tests)]";

/// Removes every item that follows the attribute `marker` (up to its matching brace or
/// semicolon).
fn strip_unit_tests(code: &str, marker: &str) -> String {
    let mut out = String::with_capacity(code.len());
    let mut rest = code;
    while let Some(k) = rest.find(marker) {
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

/// The files that may spell scheme names: the ids (`schemes/options.rs`) and each family's
/// catalogue rows (`schemes/FAMILY/entry.rs`, whose text may refer to a sibling scheme).
fn spells_names(p: &Path) -> bool {
    let schemes = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/schemes");
    p == schemes.join("options.rs")
        || (p.file_name().is_some_and(|f| f == "entry.rs")
            && p.parent().and_then(|d| d.parent()) == Some(schemes.as_path()))
}

#[test]
fn scheme_names_are_spelled_in_the_ids_and_catalogue_rows_only() {
    let names = scheme_names();
    let mut found = Vec::new();
    for p in sources() {
        if is_test_file(&p) || spells_names(&p) {
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

/// The longest a non-test source file may be (lines, the unit tests' items left out).
const MAX_LINES: usize = 600;

#[test]
fn no_source_file_is_too_long() {
    let mut long = BTreeMap::new();
    for p in sources() {
        if is_test_file(&p) {
            continue;
        }
        let text = std::fs::read_to_string(&p).unwrap();
        let code = strip_unit_tests(&text, UNIT_CFG);
        let lines = code.lines().count();
        if lines > MAX_LINES {
            long.insert(p.display().to_string(), lines);
        }
    }
    assert!(long.is_empty(), "files over {MAX_LINES} lines: {long:?}");
}

/// The folders (and single-file modules) directly under `src/schemes/`, and the file of each
/// non-test source below it: `src/schemes/eg/surface/g1.rs` is in `eg`.
fn scheme_folders() -> (PathBuf, Vec<(String, PathBuf)>) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/schemes");
    let files = sources()
        .into_iter()
        .filter(|p| p.starts_with(&root) && !is_test_file(p))
        .filter_map(|p| {
            let rel = p.strip_prefix(&root).unwrap().to_path_buf();
            let first = rel.components().next()?.as_os_str().to_string_lossy();
            let node = first.trim_end_matches(".rs").to_string();
            Some((node, p))
        })
        .collect();
    (root, files)
}

/// The names a path names after `prefix` (`prefix` then `a` or `{a, b::c}`), first segments.
fn names_after(code: &str, prefix: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = code;
    while let Some(k) = rest.find(prefix) {
        let before = rest[..k].chars().last();
        rest = &rest[k + prefix.len()..];
        if before.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == '$' || c == ':') {
            continue;
        }
        let ident = |s: &str| -> String {
            s.trim()
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect()
        };
        if let Some(group) = rest.strip_prefix('{') {
            let mut depth = 0;
            let mut item = String::new();
            for ch in group.chars() {
                match ch {
                    '{' => depth += 1,
                    '}' if depth == 0 => break,
                    '}' => depth -= 1,
                    ',' if depth == 0 => {
                        out.push(ident(&item));
                        item.clear();
                        continue;
                    }
                    _ => {}
                }
                item.push(ch);
            }
            out.push(ident(&item));
        } else {
            out.push(ident(rest));
        }
    }
    out.retain(|n| !n.is_empty());
    out
}

/// The import graph of the folders of `src/schemes/`: for each folder, the folders its files
/// name (`crate::schemes::X`, or `super::` paths that climb to `schemes`), with one file per
/// arrow. A name that `schemes/mod.rs` re-exports counts as its module; `mod.rs` itself only
/// declares and re-exports.
fn scheme_graph() -> BTreeMap<String, BTreeMap<String, String>> {
    let (root, files) = scheme_folders();
    let nodes: BTreeSet<String> = files.iter().map(|(n, _)| n.clone()).collect();
    // Re-exports of schemes/mod.rs: item -> module.
    let mut reexports = BTreeMap::new();
    let root_code = code_only(
        &std::fs::read_to_string(root.join("mod.rs")).unwrap(),
        &mut Vec::new(),
    );
    for stmt in root_code.split(';') {
        let t = stmt.trim();
        let Some(path) = t
            .strip_prefix("pub use ")
            .or_else(|| t.strip_prefix("pub(crate) use "))
        else {
            continue;
        };
        let module: String = path.chars().take_while(|c| *c != ':').collect();
        let tail = path[module.len()..].trim_start_matches("::");
        for item in tail.trim_matches(|c| c == '{' || c == '}').split(',') {
            reexports.insert(item.trim().to_string(), module.trim().to_string());
        }
    }
    let mut graph: BTreeMap<String, BTreeMap<String, String>> = BTreeMap::new();
    for (node, p) in &files {
        if node == "mod" {
            continue;
        }
        let code = code_only(&std::fs::read_to_string(p).unwrap(), &mut Vec::new());
        let mut targets = names_after(&code, "crate::schemes::");
        // `super::` chains that climb to `schemes`: the file's depth below it.
        let rel = p.strip_prefix(&root).unwrap();
        let mut depth = rel.components().count();
        if p.file_name().is_some_and(|f| f == "mod.rs") {
            depth -= 1;
        }
        if depth >= 1 {
            targets.extend(names_after(&code, &"super::".repeat(depth)));
        }
        for t in targets {
            let target = if nodes.contains(&t) && t != "mod" {
                t
            } else if let Some(m) = reexports.get(&t) {
                m.clone()
            } else {
                "mod".to_string()
            };
            if target != *node {
                graph
                    .entry(node.clone())
                    .or_default()
                    .entry(target)
                    .or_insert_with(|| p.strip_prefix(&root).unwrap().display().to_string());
            }
        }
    }
    graph
}

#[test]
fn no_scheme_family_imports_the_registry() {
    let (root, files) = scheme_folders();
    let mut found = Vec::new();
    for (node, p) in files {
        if node == "registry" || node == "mod" {
            continue;
        }
        let code = code_only(&std::fs::read_to_string(&p).unwrap(), &mut Vec::new());
        let mentions = code.match_indices("registry").any(|(k, _)| {
            let before = code[..k].chars().last();
            let after = code[k + 8..].chars().next();
            !before.is_some_and(|c| c.is_alphanumeric() || c == '_')
                && !after.is_some_and(|c| c.is_alphanumeric() || c == '_')
        });
        if mentions {
            found.push(p.strip_prefix(&root).unwrap().display().to_string());
        }
    }
    assert!(
        found.is_empty(),
        "{} files under src/schemes/ reach up to the registry (a family exports its own \
         rows in entry.rs; its ids are in options::ids): {found:?}",
        found.len()
    );
}

#[test]
fn scheme_folders_import_without_a_circle() {
    let graph = scheme_graph();
    // Tarjan's strongly connected components.
    struct State<'a> {
        graph: &'a BTreeMap<String, BTreeMap<String, String>>,
        index: BTreeMap<&'a str, usize>,
        low: BTreeMap<&'a str, usize>,
        stack: Vec<&'a str>,
        circles: Vec<Vec<&'a str>>,
    }
    fn visit<'a>(s: &mut State<'a>, v: &'a str) {
        let k = s.index.len();
        s.index.insert(v, k);
        s.low.insert(v, k);
        s.stack.push(v);
        let graph = s.graph;
        for w in graph.get(v).into_iter().flat_map(|e| e.keys()) {
            let w = w.as_str();
            if !s.index.contains_key(w) {
                visit(s, w);
                let lw = s.low[w];
                let lv = s.low.get_mut(v).unwrap();
                *lv = (*lv).min(lw);
            } else if s.stack.contains(&w) {
                let iw = s.index[w];
                let lv = s.low.get_mut(v).unwrap();
                *lv = (*lv).min(iw);
            }
        }
        if s.low[v] == s.index[v] {
            let mut scc = Vec::new();
            while let Some(w) = s.stack.pop() {
                scc.push(w);
                if w == v {
                    break;
                }
            }
            if scc.len() > 1 {
                s.circles.push(scc);
            }
        }
    }
    let mut s = State {
        graph: &graph,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        circles: Vec::new(),
    };
    for v in graph.keys() {
        if !s.index.contains_key(v.as_str()) {
            visit(&mut s, v);
        }
    }
    let report: Vec<String> = s
        .circles
        .iter()
        .map(|scc| {
            let arrows: Vec<String> = scc
                .iter()
                .flat_map(|a| {
                    graph[*a]
                        .iter()
                        .filter(|(b, _)| scc.contains(&b.as_str()))
                        .map(move |(b, file)| format!("{a} -> {b} ({file})"))
                })
                .collect();
            arrows.join("; ")
        })
        .collect();
    assert!(
        report.is_empty(),
        "import circles among the folders of src/schemes/:\n{}",
        report.join("\n")
    );
    // The bottom stays the bottom: the ids and options import no other folder of schemes/.
    assert!(
        graph.get("options").is_none_or(|e| e.is_empty()),
        "schemes/options.rs imports {:?}",
        graph.get("options")
    );
}

/// The source with comments and the contents of string and char literals blanked (newlines
/// kept), so that its braces are the code's and its line numbers the file's.
fn blanked(src: &str) -> String {
    lex(src, true).0
}

/// The name of the function whose signature starts on `line`, if one does (`fn`, after any
/// visibility and `const` / `unsafe`).
fn fn_name(line: &str) -> Option<&str> {
    let mut rest = line.trim_start();
    if let Some(r) = rest.strip_prefix("pub") {
        rest = match r.strip_prefix('(') {
            Some(r) => r.split_once(')')?.1,
            None => r,
        }
        .trim_start();
    }
    for kw in ["const ", "unsafe "] {
        rest = rest.strip_prefix(kw).unwrap_or(rest);
    }
    let name = rest.strip_prefix("fn ")?;
    let end = name.find(|c: char| !(c.is_alphanumeric() || c == '_'))?;
    Some(&name[..end])
}

/// The longest a function of a non-test source file may be (lines from its `fn` line to its
/// closing brace). ARCHITECTURE.md would name any exception (a table or a match whose clearest
/// form is one function); there is none.
const MAX_FN_LINES: usize = 100;

#[test]
fn no_function_is_too_long() {
    let mut long = Vec::new();
    for p in sources() {
        if is_test_file(&p) {
            continue;
        }
        let text = std::fs::read_to_string(&p).unwrap();
        let code = blanked(&strip_unit_tests(&text, UNIT_CFG));
        let lines: Vec<&str> = code.lines().collect();
        for (i, line) in lines.iter().enumerate() {
            let Some(name) = fn_name(line) else { continue };
            let (mut depth, mut opened) = (0i64, false);
            let mut end = None;
            'body: for (j, l) in lines.iter().enumerate().skip(i) {
                for ch in l.chars() {
                    match ch {
                        '{' => {
                            depth += 1;
                            opened = true;
                        }
                        '}' => depth -= 1,
                        // a declaration without a body (a trait's method)
                        ';' if !opened => break 'body,
                        _ => {}
                    }
                    if opened && depth == 0 {
                        end = Some(j);
                        break 'body;
                    }
                }
            }
            if let Some(j) = end
                && j - i + 1 > MAX_FN_LINES
            {
                long.push(format!(
                    "{}:{} {name} ({} lines)",
                    p.display(),
                    i + 1,
                    j - i + 1
                ));
            }
        }
    }
    assert!(
        long.is_empty(),
        "functions over {MAX_FN_LINES} lines: {long:?}"
    );
}
