//! The public API stays small: rustdoc's all-items page lists at most 300 items.
//!
//! Building the documentation inside a test would take minutes, so this test reads what
//! decides the page instead: `src/lib.rs`. Every top-level module there is either private or
//! `#[doc(hidden)]` (its items are then not on the page), there are no glob re-exports (which
//! would put a whole module on it), and so the page lists exactly the names `lib.rs`
//! re-exports or defines, which are counted here. `.ci/run` checks the built page itself (it
//! runs `cargo doc` anyway) with the same bound.

use std::fs;

/// The bound of issue 48.
const MAX_ITEMS: usize = 300;

/// `src/lib.rs` without comments and attributes other than `#[doc(hidden)]`, as statements.
fn statements() -> Vec<String> {
    let src = fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/src/lib.rs")).unwrap();
    let code: String = src
        .lines()
        .map(str::trim)
        .filter(|l| !l.starts_with("//"))
        .filter(|l| !l.starts_with("#!["))
        .collect::<Vec<_>>()
        .join(" ");
    code.split(';')
        .map(|s| s.split_whitespace().collect::<Vec<_>>().join(" "))
        .filter(|s| !s.is_empty())
        .collect()
}

/// The names a `pub use` statement brings to the crate root (`a::b::{C, d as E}` -> C, E).
fn used_names(stmt: &str) -> Vec<String> {
    let path = stmt.trim_start_matches("pub use").trim();
    let list = match (path.find('{'), path.rfind('}')) {
        (Some(a), Some(b)) => path[a + 1..b].to_string(),
        _ => path.rsplit("::").next().unwrap().to_string(),
    };
    list.split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(|s| s.rsplit(" as ").next().unwrap().trim().to_string())
        .collect()
}

#[test]
fn all_items_page_stays_small() {
    let mut names = Vec::new();
    let mut undocumented_modules = Vec::new();
    for s in statements() {
        let hidden = s.contains("#[doc(hidden)]");
        let s = s.replace("#[doc(hidden)]", "");
        let s = s.trim();
        if let Some(m) = s.strip_prefix("pub mod ") {
            assert!(
                hidden,
                "`pub mod {m}` in src/lib.rs is documented: make it pub(crate) or \
                 #[doc(hidden)], and re-export what users need at the root"
            );
            undocumented_modules.push(m.to_string());
        } else if s.starts_with("pub use") {
            assert!(
                !s.contains('*'),
                "glob re-export in src/lib.rs ({s}) would list a whole module"
            );
            names.extend(used_names(s));
        } else if s.starts_with("pub ") && !s.starts_with("pub(") {
            panic!("src/lib.rs defines a public item directly ({s}): define it in a module");
        }
    }
    assert!(
        undocumented_modules.len() >= 10,
        "the statements were not read: {undocumented_modules:?}"
    );
    let mut unique = names.clone();
    unique.sort();
    unique.dedup();
    assert_eq!(unique.len(), names.len(), "a name re-exported twice");
    assert!(
        names.len() <= MAX_ITEMS,
        "{} items at the crate root, more than {MAX_ITEMS}: {names:?}",
        names.len()
    );
    // the entry points of issue 48 are there
    for want in [
        "PolyMesh", "Spec", "Surface", "refine", "surface", "analyze", "read_net",
    ] {
        assert!(names.iter().any(|n| n == want), "{want} is not re-exported");
    }
}

#[test]
fn the_reexports_are_read() {
    assert_eq!(used_names("pub use a::b::{C, d as E}"), ["C", "E"]);
    assert_eq!(used_names("pub use a::B"), ["B"]);
}
