//! `fairsub analyze` and `fairsub charmap`: a scheme's local analysis at one valence, and its
//! characteristic ring with the injectivity certificate.

use super::spec::{self, SchemeOptions};
use crate::analysis::{certify, report};
use crate::error::{Error, Result};
use crate::io::OutputFormat;
use crate::surface::{PatchComplex, Provenance};
use std::path::{Path, PathBuf};

/// Arguments of `fairsub analyze`.
#[derive(Debug, clap::Args)]
pub struct AnalyzeArgs {
    /// The scheme.
    #[arg(long, short)]
    pub scheme: String,
    /// Valence of the extraordinary vertex (or size of the extraordinary facet).
    #[arg(long, short = 'n')]
    pub valence: usize,
    /// Contraction of a guided scheme (0.5; default Catmull-Clark's lambda).
    #[arg(long)]
    pub lambda: Option<f64>,
    /// Print the report as JSON.
    #[arg(long)]
    pub json: bool,
    /// Analyse the form with the central points replicated once per sector (as the bi-2 paper
    /// writes its matrices): same non-zero spectrum, equal-size Fourier blocks.
    #[arg(long)]
    pub replicated_centre: bool,
    /// tps-adjustable only: the split ratio e, 0 < e < 1/2 (default 0.2).
    #[arg(long)]
    pub split_ratio: Option<f64>,
    /// tps-adjustable only: how rule (18)'s alphas are chosen.
    #[arg(long, value_enum)]
    pub alpha_rule: Option<super::subdivide::AlphaRuleArg>,
    /// EG and QAS+ only: analyse the printed rules where they exist (default) or the derived
    /// ones.
    #[arg(long, value_enum)]
    pub rules: Option<spec::RulesArg>,
}

/// Runs `fairsub analyze`.
pub fn analyze(a: AnalyzeArgs) -> Result<()> {
    let spec = spec::resolve(
        &a.scheme,
        &SchemeOptions {
            lambda: a.lambda,
            split_ratio: a.split_ratio,
            alpha_rule: a.alpha_rule.map(Into::into),
            rules: a.rules.map(Into::into),
            ..SchemeOptions::default()
        },
    )?;
    super::limits::check_analysis(&spec, a.valence, a.replicated_centre)?;
    let r = report::analyze(&spec, a.valence, a.replicated_centre)?;
    if a.json {
        super::say_json(&r);
        return Ok(());
    }
    if let Some(v) = &r.rules {
        say!("rules at valence {}: {}", v.valence, v.rules);
    }
    say!(
        "{} at valence {}: {}x{} local matrix ({} centre + {} x {} points), rotation defect {:.1e}",
        r.scheme,
        r.valence,
        r.matrix_size,
        r.matrix_size,
        r.centre_points,
        r.valence,
        r.points_per_sector,
        r.rotation_defect
    );
    say!("eigenvalues (modulus-sorted, multiplicity):");
    for e in r.spectrum.eigenvalues.iter().take(12) {
        if e.im == 0.0 {
            say!("  {:.10} x{}", e.re, e.multiplicity);
        } else {
            say!("  {:.10} {:+.10}i x{}", e.re, e.im, e.multiplicity);
        }
    }
    if r.spectrum.eigenvalues.len() > 12 {
        say!("  ... ({} distinct in all)", r.spectrum.eigenvalues.len());
    }
    say!(
        "dominant {:.12}, lambda {:.12} (x{}), mu {:.12}, mu/lambda^2 {:.6}",
        r.spectrum.dominant,
        r.spectrum.lambda,
        r.spectrum.lambda_multiplicity,
        r.spectrum.mu,
        r.spectrum.mu_over_lambda_squared
    );
    let shown: Vec<String> = r
        .limit_stencil
        .iter()
        .take(1 + r.points_per_sector)
        .map(|w| format!("{w:.6}"))
        .collect();
    say!("limit stencil (centre, sector 0): {}", shown.join(" "));
    if let Some(c) = &r.characteristic_map {
        say!(
            "characteristic map: {} ({} patches, Jacobian min coefficient {:.3e} over {} pieces, windings {:?}, boundaries simple: {}, scaled copy inside: {})",
            if c.injective {
                "injective (certified)"
            } else {
                "NOT certified injective"
            },
            c.patches,
            c.jacobian_min_coefficient,
            c.pieces,
            c.windings,
            c.boundaries_simple,
            c.scaled_copy_inside
        );
    }
    for line in &r.extra_lines {
        say!("{line}");
    }
    for p in &r.published {
        say!(
            "published {}: {:.12}, computed {:.12} (difference {:.1e})",
            p.quantity,
            p.published,
            p.computed,
            p.difference
        );
    }
    Ok(())
}

/// Arguments of `fairsub charmap`.
#[derive(Debug, clap::Args)]
pub struct CharmapArgs {
    /// The scheme.
    #[arg(long, short)]
    pub scheme: String,
    /// Valence.
    #[arg(long, short = 'n')]
    pub valence: usize,
    /// Output: .bv (the ring and its lambda-scaled copy as patches) or .svg (control nets and
    /// patch boundaries of both).
    #[arg(long, short)]
    pub output: PathBuf,
    /// Print the certificate as JSON.
    #[arg(long)]
    pub json: bool,
    /// EG and QAS+ only: the printed rules where they exist (default) or the derived ones.
    #[arg(long, value_enum)]
    pub rules: Option<spec::RulesArg>,
}

/// Runs `fairsub charmap`.
pub fn charmap(a: CharmapArgs) -> Result<()> {
    let spec = spec::resolve(
        &a.scheme,
        &SchemeOptions {
            rules: a.rules.map(Into::into),
            ..SchemeOptions::default()
        },
    )?;
    super::limits::check_analysis(&spec, a.valence, false)?;
    let (ring, lambda) = report::characteristic_ring(&spec, a.valence)?;
    let cert = certify::certify_ring(&ring, lambda);
    let mut c = PatchComplex::new();
    for (k, p) in ring.iter().enumerate() {
        let prov = Provenance::Ring {
            element: crate::surface::Element::Vertex(0),
            ring: 1,
            sector: (k / 3) as u32,
        };
        c.push(p.clone(), prov);
    }
    for (k, p) in ring.iter().enumerate() {
        let prov = Provenance::Ring {
            element: crate::surface::Element::Vertex(0),
            ring: 2,
            sector: (k / 3) as u32,
        };
        c.push(p.map_points(|q| [lambda * q[0], lambda * q[1], 0.0]), prov);
    }
    let ext = a
        .output
        .extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase());
    match ext.as_deref() {
        Some("svg") => write_svg(&a.output, &c)?,
        _ => match OutputFormat::choose(&a.output, None)? {
            OutputFormat::Bv => crate::io::write_bv(&a.output, &c)?,
            OutputFormat::Iges => crate::io::write_iges(&a.output, &c)?,
            OutputFormat::Mesh(_) | OutputFormat::Scene(_) | OutputFormat::Step => {
                return Err(Error::InvalidArgument(
                    "charmap writes .bv, .igs or .svg".into(),
                ));
            }
        },
    }
    if a.json {
        super::say_json(&cert);
    } else {
        say!(
            "{} valence {}: lambda {:.12}; {}; Jacobian min coefficient {:.3e}; wrote {}",
            a.scheme,
            a.valence,
            lambda,
            if cert.injective {
                "injective (certified)"
            } else {
                "NOT certified injective"
            },
            cert.jacobian_min_coefficient,
            a.output.display()
        );
    }
    Ok(())
}

/// Writes the planar patches' control nets and boundaries as SVG.
fn write_svg(path: &Path, c: &PatchComplex) -> Result<()> {
    let (lo, hi) = crate::geom::bounding_box(c.patches.iter().flat_map(|p| p.cps.iter().copied()))
        .unwrap_or(([0.0; 3], [1.0; 3]));
    let size = 800.0;
    let span = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(1e-12);
    let tx = |p: [f64; 3]| -> (f64, f64) {
        (
            20.0 + (p[0] - lo[0]) / span * (size - 40.0),
            size - 20.0 - (p[1] - lo[1]) / span * (size - 40.0),
        )
    };
    let mut s = String::new();
    s.push_str(&format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{size}\" height=\"{size}\" viewBox=\"0 0 {size} {size}\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    ));
    for (p, prov) in c.patches.iter().zip(&c.provenance) {
        let colour = match prov {
            Provenance::Ring { ring: 1, .. } => "#c0392b",
            _ => "#2c6fbb",
        };
        // Control net.
        for i in 0..=p.deg_u {
            for j in 0..=p.deg_v {
                let (x, y) = tx(p.cp(i, j));
                if i < p.deg_u {
                    let (x2, y2) = tx(p.cp(i + 1, j));
                    s.push_str(&format!("<line x1=\"{x:.2}\" y1=\"{y:.2}\" x2=\"{x2:.2}\" y2=\"{y2:.2}\" stroke=\"#bbbbbb\" stroke-width=\"0.5\"/>\n"));
                }
                if j < p.deg_v {
                    let (x2, y2) = tx(p.cp(i, j + 1));
                    s.push_str(&format!("<line x1=\"{x:.2}\" y1=\"{y:.2}\" x2=\"{x2:.2}\" y2=\"{y2:.2}\" stroke=\"#bbbbbb\" stroke-width=\"0.5\"/>\n"));
                }
            }
        }
        // Patch boundary.
        let mut d = String::new();
        let k = 16;
        for (step, &(u0, v0, du, dv)) in [
            (0.0, 0.0, 1.0, 0.0),
            (1.0, 0.0, 0.0, 1.0),
            (1.0, 1.0, -1.0, 0.0),
            (0.0, 1.0, 0.0, -1.0),
        ]
        .iter()
        .enumerate()
        {
            for t in 0..k {
                let f = t as f64 / k as f64;
                let (x, y) = tx(p.eval(u0 + du * f, v0 + dv * f));
                d.push_str(&format!(
                    "{}{x:.2},{y:.2} ",
                    if step == 0 && t == 0 { "M" } else { "L" }
                ));
            }
        }
        d.push('Z');
        s.push_str(&format!(
            "<path d=\"{d}\" fill=\"none\" stroke=\"{colour}\" stroke-width=\"1\"/>\n"
        ));
    }
    s.push_str("</svg>\n");
    crate::io::write_atomically(path, |w| {
        w.write_all(s.as_bytes()).map_err(|source| Error::Io {
            path: path.to_path_buf(),
            source,
        })
    })
}
