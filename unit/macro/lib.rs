//! `#[test]` for the library's unit tests, compiled into the library itself.
//!
//! A unit test beside the code it tests is written
//!
//! ```ignore
//! #[crate::unit::test]
//! fn keeps_the_corner() { ... }
//! ```
//!
//! and this attribute leaves the function as it is and adds an entry for it to the library's
//! list of unit tests (`crate::unit::TESTS`, a `linkme` distributed slice), which the harness in
//! `unit/` runs. Why not `#[test]`: libtest's attribute exists only in a `--test` compilation,
//! and that is a second compilation of the whole library; this one works in the library's own
//! build (under its `unit-tests` feature), so `cargo test --release` compiles the library once.
//! `#[ignore]` or `#[ignore = "why"]` after it marks the test as ignored, as with libtest.

use proc_macro::{Delimiter, Spacing, TokenStream, TokenTree};

/// Registers the function that follows as a unit test (see the crate documentation).
#[proc_macro_attribute]
pub fn test(attr: TokenStream, item: TokenStream) -> TokenStream {
    if !attr.is_empty() {
        return error("#[unit::test] takes no arguments");
    }
    let tokens: Vec<TokenTree> = item.into_iter().collect();
    let mut kept: Vec<TokenTree> = Vec::with_capacity(tokens.len());
    let mut ignore = String::from("::core::option::Option::None");
    let mut name = None;
    let mut k = 0;
    while k < tokens.len() {
        // An outer attribute: `#` then a bracketed group.
        if let (TokenTree::Punct(p), Some(TokenTree::Group(g))) = (&tokens[k], tokens.get(k + 1))
            && p.as_char() == '#'
            && p.spacing() == Spacing::Alone
            && g.delimiter() == Delimiter::Bracket
            && name.is_none()
        {
            let inner: Vec<TokenTree> = g.stream().into_iter().collect();
            if let Some(TokenTree::Ident(id)) = inner.first()
                && id.to_string() == "ignore"
            {
                ignore = match inner.get(2) {
                    Some(TokenTree::Literal(reason)) => {
                        format!("::core::option::Option::Some({reason})")
                    }
                    _ => "::core::option::Option::Some(\"\")".to_string(),
                };
                k += 2;
                continue;
            }
        }
        if let TokenTree::Ident(id) = &tokens[k]
            && id.to_string() == "fn"
            && name.is_none()
        {
            match tokens.get(k + 1) {
                Some(TokenTree::Ident(n)) => name = Some(n.to_string()),
                _ => return error("#[unit::test] expects `fn name() { ... }`"),
            }
        }
        kept.push(tokens[k].clone());
        k += 1;
    }
    let Some(name) = name else {
        return error("#[unit::test] goes on a function");
    };
    let entry = format!(
        "#[::linkme::distributed_slice(crate::unit::TESTS)]
         #[linkme(crate = ::linkme)]
         static __UNIT_TEST_{upper}: crate::unit::Test = crate::unit::Test {{
             path: ::core::concat!(::core::module_path!(), \"::{name}\"),
             run: {name},
             ignore: {ignore},
         }};",
        upper = name.to_uppercase(),
    );
    let mut out: TokenStream = kept.into_iter().collect();
    match entry.parse::<TokenStream>() {
        Ok(entry) => out.extend(entry),
        Err(_) => return error("#[unit::test]: could not write the test's entry"),
    }
    out
}

/// A `compile_error!` with `message`.
fn error(message: &str) -> TokenStream {
    format!("::core::compile_error!({message:?});")
        .parse()
        .unwrap_or_default()
}
