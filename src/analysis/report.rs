//! The analysis of one scheme at one valence, as `fairsub analyze` reports it: the local
//! matrix from the scheme's own stencils, its spectrum and Fourier blocks, the limit and
//! tangent stencils, the certificate of the characteristic map, the published numbers beside
//! the computed ones and the scheme's extra facts. Every scheme-specific part comes from the
//! scheme's [`LocalRules`]; nothing here knows a scheme by name.

use super::certify::{self, InjectivityCertificate};
use crate::error::{Error, Result};
use crate::linalg::C64;
use crate::schemes::descriptor::{Computed, LocalRules, Published, ValenceRules};
use crate::schemes::local::{LocalOperator, Spectrum};
use crate::schemes::{Spec, registry};
use serde::Serialize;
use std::collections::BTreeMap;

/// One Fourier block in the report.
#[derive(Debug, Clone, Serialize)]
pub struct BlockReport {
    /// Frequency.
    pub frequency: usize,
    /// Size of the block.
    pub size: usize,
    /// Its eigenvalues as (re, im).
    pub eigenvalues: Vec<[f64; 2]>,
    /// Coefficients of det(x I - B), highest degree first, as (re, im).
    pub characteristic_polynomial: Vec<[f64; 2]>,
}

/// The `analyze` report.
#[derive(Debug, Clone, Serialize)]
pub struct AnalyzeReport {
    /// The matrix's label (scheme name, with the form analysed).
    pub scheme: String,
    /// Valence.
    pub valence: usize,
    /// Rows of the local matrix.
    pub matrix_size: usize,
    /// Central points of the local net.
    pub centre_points: usize,
    /// Points per sector.
    pub points_per_sector: usize,
    /// Largest deviation from rotational symmetry.
    pub rotation_defect: f64,
    /// The spectrum.
    pub spectrum: Spectrum,
    /// The discrete Fourier blocks (empty without rotational symmetry).
    pub fourier_blocks: Vec<BlockReport>,
    /// Limit-point stencil: weights of the local-net points (centre first, then sector 0).
    pub limit_stencil: Vec<f64>,
    /// Tangent stencils: left eigenvectors of lambda (orthonormal basis).
    pub tangent_stencils: Vec<Vec<f64>>,
    /// The injectivity certificate of the characteristic map, if the scheme has one.
    pub characteristic_map: Option<InjectivityCertificate>,
    /// Which rules were analysed (printed, derived, regular, another scheme's), for schemes
    /// whose rules differ in origin by valence.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rules: Option<ValenceRules>,
    /// The paper's numbers beside the computed ones.
    pub published: Vec<Published>,
    /// The scheme's extra facts (for example QAS+'s `M_d` and `M_q`), by key.
    #[serde(flatten)]
    pub extra: BTreeMap<&'static str, serde_json::Value>,
    /// The text report's lines of the extra facts.
    #[serde(skip)]
    pub extra_lines: Vec<String>,
}

fn c2(z: C64) -> [f64; 2] {
    [z.re, if z.im.abs() < 1e-13 { 0.0 } else { z.im }]
}

/// The local rules of a scheme, or the error listing the schemes with analysis.
pub fn local_rules(spec: &Spec) -> Result<Box<dyn LocalRules>> {
    let r = registry();
    r.descriptor(spec.id).local_rules(spec)?.ok_or_else(|| {
        let names: Vec<&str> = r
            .entries()
            .iter()
            .filter(|e| {
                e.descriptor
                    .local_rules(&Spec::new(e.id))
                    .ok()
                    .flatten()
                    .is_some()
            })
            .map(|e| e.name)
            .collect();
        Error::InvalidArgument(format!(
            "no analysis for scheme '{}' (available: {})",
            spec.name(),
            names.join(", ")
        ))
    })
}

/// Analyses a scheme at valence `n`; with `replicated_centre` the local matrix is taken in the
/// form with the central points replicated once per sector.
pub fn analyze(spec: &Spec, n: usize, replicated_centre: bool) -> Result<AnalyzeReport> {
    let rules = local_rules(spec)?;
    let lm = rules.operator(n, replicated_centre)?;
    let mut r = report(rules.as_ref(), n, lm.as_ref())?;
    r.rules = registry().descriptor(spec.id).valence_rules(spec, n);
    Ok(r)
}

fn report(rules: &dyn LocalRules, n: usize, lm: &dyn LocalOperator) -> Result<AnalyzeReport> {
    let spectrum = lm.spectrum();
    let blocks = lm.fourier_blocks().unwrap_or_default();
    let fourier_blocks = blocks
        .iter()
        .map(|b| BlockReport {
            frequency: b.frequency,
            size: b.matrix.nrows(),
            eigenvalues: b.eigenvalues().into_iter().map(c2).collect(),
            characteristic_polynomial: b.characteristic_polynomial().into_iter().map(c2).collect(),
        })
        .collect();
    let limit_stencil = rules.limit_stencil(n, lm)?;
    let tangent_stencils = lm
        .left_eigenvectors(spectrum.lambda)
        .into_iter()
        .map(|v| v.iter().copied().collect())
        .collect();
    let characteristic_map = rules
        .characteristic_ring(n)
        .ok()
        .map(|(ring, lambda)| certify::certify_ring(&ring, lambda));
    let published = rules.published(
        n,
        &Computed {
            matrix: lm,
            spectrum: &spectrum,
            limit_stencil: &limit_stencil,
        },
    )?;
    let mut extra = BTreeMap::new();
    let mut extra_lines = Vec::new();
    for x in rules.extras(n)? {
        extra.insert(x.key, x.value);
        extra_lines.extend(x.lines);
    }
    Ok(AnalyzeReport {
        scheme: lm.scheme().to_string(),
        valence: lm.n(),
        matrix_size: lm.size(),
        centre_points: lm.centre(),
        points_per_sector: lm.sector(),
        rotation_defect: lm.rotation_defect(),
        spectrum,
        fourier_blocks,
        limit_stencil,
        tangent_stencils,
        characteristic_map,
        rules: None,
        published,
        extra,
        extra_lines,
    })
}

/// The characteristic ring of a scheme at valence `n`, with lambda.
pub fn characteristic_ring(
    spec: &Spec,
    n: usize,
) -> Result<(Vec<crate::bezier::BezierPatch>, f64)> {
    local_rules(spec)?.characteristic_ring(n)
}
