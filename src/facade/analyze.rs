//! The catalogue of schemes (`fairsub schemes`) and a scheme's local analysis at one valence
//! (`fairsub analyze`).

use super::Options;
use crate::cli::spec::{self, SchemeOptions};
use crate::error::Result;

pub use crate::analysis::report::AnalyzeReport as Analysis;
pub use crate::cli::CatalogueRow as SchemeRow;

/// The catalogue, one row per scheme of the registry in its order (`fairsub schemes
/// --json`): name, family, input, patches, smoothness, status, rules by valence.
///
/// ```
/// let names: Vec<&str> = fairsub::schemes().iter().map(|r| r.info.name).collect();
/// assert!(names.contains(&"catmull-clark") && names.contains(&"butterfly"));
/// ```
pub fn schemes() -> Vec<SchemeRow> {
    crate::cli::catalogue()
}

/// The local analysis of `scheme` at valence `valence` (`fairsub analyze`): the local
/// matrix's spectrum, limit stencil, characteristic-map certificate and the published numbers
/// with their differences. With `replicated_centre`, the form with the central points
/// replicated once per sector. Of the options, `lambda`, `split_ratio`, `alpha_rule` and
/// `rules` apply (as on the command line).
///
/// ```
/// use fairsub::{Options, analyze};
/// let a = analyze("catmull-clark", 5, false, &Options::default())?;
/// assert!((a.spectrum.dominant - 1.0).abs() < 1e-12);
/// assert!(a.spectrum.lambda > 0.5 && a.spectrum.lambda < 0.6);
/// # Ok::<(), fairsub::Error>(())
/// ```
pub fn analyze(
    scheme: &str,
    valence: usize,
    replicated_centre: bool,
    options: &Options,
) -> Result<Analysis> {
    let o = options;
    let net_only = [
        (o.fcv_scale.is_some(), "fcv_scale"),
        (o.fcv_file.is_some(), "fcv_file"),
        (o.fallback != Default::default(), "fallback"),
        (o.q_file.is_some(), "q_file"),
        (!o.poles.is_empty(), "poles"),
        (o.prepare != Default::default(), "prepare"),
        (o.boundary.is_some(), "boundary"),
        (o.crease_method.is_some(), "crease_method"),
        (o.smooth_triangles, "smooth_triangles"),
        (o.fvar.is_some(), "fvar"),
        (o.creases.is_some(), "creases"),
    ];
    if let Some((_, name)) = net_only.iter().find(|(set, _)| *set) {
        return Err(crate::Error::InvalidArgument(format!(
            "analyze takes the options lambda, split_ratio, alpha_rule and rules; {name} \
             applies to nets"
        )));
    }
    let s = spec::resolve(
        scheme,
        &SchemeOptions {
            lambda: options.lambda,
            split_ratio: options.split_ratio,
            alpha_rule: options.alpha_rule,
            rules: options.rules,
            ..SchemeOptions::default()
        },
    )?;
    crate::cli::limits::check_analysis(&s, valence, replicated_centre)?;
    crate::analysis::report::analyze(&s, valence, replicated_centre)
}
