//! The commands as library calls for front ends that hold command-line words (the viewer's
//! page builds `subdivide` words from its controls) and the writers the library API shares:
//! the same argument words, parsed by the same clap definitions, the same loading, limits,
//! construction and reports, with the results handed back instead of written. Typed calls
//! (the Python package's, a Rust program's) go through the crate root's API
//! (`crate::facade`). Nothing here is a second copy of a rule or of a command's logic: each
//! function is the command's own code path (`subdivide::prepare` and `finish`,
//! `check::report_json`, ...) with an in-memory net in place of a file where one is given.

use super::subdivide::{self, Computed};
use super::{Cli, Command, limits};
use crate::error::{Error, Result};
use crate::mesh::PolyMesh;
use crate::schemes::Spec;
use crate::schemes::descriptor::ParamKind;
use crate::surface::PatchComplex;
use clap::Parser;

/// What [`subdivide`](fn@subdivide) computed.
#[derive(Debug, Clone)]
pub struct Outcome {
    /// The refined net, the limit mesh or the patch complex.
    pub computed: Computed,
    /// The scheme as the command's report names it.
    pub label: String,
    /// The scheme with its typed options, as resolved from the words.
    pub spec: Spec,
    /// The net as the scheme read it (the domain of the surface's evaluation).
    pub net: PolyMesh,
}

/// Parses `fairsub WORDS...` (without the program name) like the command line does; usage
/// errors are [`Error::InvalidArgument`] with clap's message.
fn parse(words: &[String]) -> Result<Cli> {
    let all = std::iter::once("fairsub".to_string()).chain(words.iter().cloned());
    Cli::try_parse_from(all).map_err(|e| Error::InvalidArgument(e.to_string().trim().to_string()))
}

/// The memory budget of a parsed command line (`--max-memory`).
fn budget(cli: &Cli) -> Result<Option<u64>> {
    cli.max_memory
        .as_deref()
        .map(limits::parse_memory)
        .transpose()
}

/// One option of `subdivide` that sets a scheme parameter, described from the command's own
/// clap definition for a front end that offers it (the viewer builds its controls from these
/// and passes the values back as words).
#[derive(Debug, Clone, serde::Serialize)]
pub struct OptionWord {
    /// The option without its dashes (`split-ratio`).
    pub name: String,
    /// Its help text.
    pub help: String,
    /// The values it takes, when they are a fixed set (else empty).
    pub choices: Vec<String>,
    /// Whether its value names a file.
    pub file: bool,
    /// Whether it is a flag without a value.
    pub flag: bool,
    /// Whether it may be given more than once.
    pub repeated: bool,
}

/// The options of `subdivide` that set the parameters `kinds` (a scheme descriptor's
/// [`ParamKind`]s, named by [`ParamKind::option`]), in that order.
pub fn option_words(kinds: &[ParamKind]) -> Vec<OptionWord> {
    let cmd = <Cli as clap::CommandFactory>::command();
    let sub = cmd
        .find_subcommand("subdivide")
        .expect("subdivide is a command");
    kinds
        .iter()
        .flat_map(|k| k.option().split(" / "))
        .filter_map(|o| {
            let name = o.strip_prefix("--")?;
            let arg = sub.get_arguments().find(|a| a.get_long() == Some(name))?;
            let action = arg.get_action();
            Some(OptionWord {
                name: name.to_string(),
                help: arg.get_help().map(|h| h.to_string()).unwrap_or_default(),
                choices: arg
                    .get_possible_values()
                    .iter()
                    .map(|v| v.get_name().to_string())
                    .collect(),
                file: arg.get_value_parser().type_id()
                    == std::any::TypeId::of::<std::path::PathBuf>(),
                flag: matches!(action, clap::ArgAction::SetTrue),
                repeated: matches!(action, clap::ArgAction::Append),
            })
        })
        .collect()
}

/// `subdivide WORDS...` parsed (with a placeholder `-o` when none is given: a `.bv` for
/// `--rings`, else an `.obj`), and its memory budget (the running command's `--max-memory`
/// when the words give none).
fn subdivide_args(words: &[String]) -> Result<(subdivide::Args, Option<u64>)> {
    let mut all = vec!["subdivide".to_string()];
    all.extend(words.iter().cloned());
    if !words
        .iter()
        .any(|w| w == "-o" || w == "--output" || w.starts_with("--output="))
    {
        let rings = words
            .iter()
            .any(|w| w == "--rings" || w == "-r" || w.starts_with("--rings="));
        all.push("-o".into());
        all.push(if rings { "out.bv" } else { "out.obj" }.into());
    }
    let cli = parse(&all)?;
    let budget = budget(&cli)?.or_else(limits::max_memory);
    let Command::Subdivide(args) = cli.command else {
        unreachable!("the words start with subdivide")
    };
    Ok((args, budget))
}

/// Runs `fairsub subdivide WORDS...` (the words after `subdivide`, with `--max-memory` allowed
/// among them) and returns what it would write. `-o` may be omitted (a `.obj` for `--levels`, a
/// `.bv` for `--rings`; nothing is written). With `given`, that mesh is the net and the NET word
/// only names it in messages.
pub fn subdivide(words: &[String], given: Option<PolyMesh>) -> Result<Outcome> {
    let (args, budget) = subdivide_args(words)?;
    limits::with_budget(budget, || {
        let p = subdivide::prepare(&args, given)?;
        let (computed, label) = subdivide::finish(&args, &p)?;
        Ok(Outcome {
            computed,
            label,
            spec: p.spec,
            net: p.mesh,
        })
    })
}

/// `fairsub measure --json`'s report of a complex built by `spec` on `net` (with the area
/// per input face when `per_face`), areas to the relative `tolerance`.
///
/// # Errors
/// `per_face` with a scheme whose input faces carry no domains.
pub fn measure_json(
    source: &str,
    complex: &PatchComplex,
    spec: &Spec,
    net: &PolyMesh,
    per_face: bool,
    tolerance: f64,
) -> Result<String> {
    let opts = crate::analysis::moments::MeasureOptions {
        area_tolerance: tolerance,
    };
    super::measure::json_report(
        source,
        complex,
        per_face.then_some((spec, net)),
        opts,
        Vec::new(),
    )
}

/// `fairsub info --json`'s report of a net.
pub fn info_json(source: &str, mesh: &PolyMesh) -> String {
    serde_json::to_string_pretty(&super::info::report(source, mesh)).expect("serialisable")
}

/// Writes a patch stencil table as `subdivide --stencils` does (validated, atomic).
pub fn write_patch_table(
    t: &crate::surface::table::PatchTable,
    path: &std::path::Path,
) -> Result<()> {
    crate::io::table::write_table(path, t)
}

/// Writes a complex as `subdivide --rings` does (`.bv`, `.igs`, or a tessellated mesh with
/// `tess` samples per patch edge), validated before the atomic rename.
pub fn write_complex(c: &PatchComplex, path: &std::path::Path, tess: usize) -> Result<()> {
    let fmt = crate::io::OutputFormat::choose(path, None)?;
    subdivide::write_complex(c, fmt, path, tess)
}

/// Writes a net as `subdivide --levels` does (format by extension).
pub fn write_net(m: &PolyMesh, path: &std::path::Path) -> Result<()> {
    match crate::io::OutputFormat::choose(path, None)? {
        crate::io::OutputFormat::Mesh(mf) => crate::io::write_mesh(path, m, mf),
        crate::io::OutputFormat::Bv => crate::io::write_bv_mesh(path, m),
        crate::io::OutputFormat::Scene(sf) => subdivide::scene::write_net(path, m, None, sf),
        crate::io::OutputFormat::Iges | crate::io::OutputFormat::Step => {
            Err(Error::InvalidArgument(
                "IGES and STEP hold surfaces: write a surface, not a net".into(),
            ))
        }
    }
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    #[crate::unit::test]
    fn option_words_come_from_the_command() {
        let w = option_words(&[
            ParamKind::AlphaRule,
            ParamKind::QFile,
            ParamKind::Poles,
            ParamKind::SmoothTriangles,
            ParamKind::Fcv,
        ]);
        let names: Vec<&str> = w.iter().map(|o| o.name.as_str()).collect();
        assert_eq!(
            names,
            [
                "alpha-rule",
                "q-file",
                "pole",
                "smooth-triangles",
                "fcv-scale",
                "fcv-file"
            ]
        );
        assert_eq!(w[0].choices, ["tps-limit-point", "regular-spectrum"]);
        assert!(w[1].file && !w[1].flag && !w[1].repeated);
        assert!(w[2].repeated && !w[2].file);
        assert!(w[3].flag);
        assert!(!w[4].file && w[5].file);
        assert!(w[0].help.contains("alphas"));
    }
}
