//! `fairsub analyze`, `fairsub charmap` and `fairsub check`: the proofs beside the surfaces.

use fairsub::analysis::{self, certify, continuity, curvature, local};
use fairsub::io::OutputFormat;
use fairsub::surface::{PatchComplex, Provenance};
use fairsub::{Error, Result};
use serde::Serialize;
use std::path::{Path, PathBuf};

/// One Fourier block in the report.
#[derive(Debug, Serialize)]
struct BlockReport {
    frequency: usize,
    size: usize,
    eigenvalues: Vec<[f64; 2]>,
    /// Coefficients of det(x I - B), highest degree first, as (re, im).
    characteristic_polynomial: Vec<[f64; 2]>,
}

/// The `analyze` report.
#[derive(Debug, Serialize)]
struct AnalyzeReport {
    scheme: String,
    valence: usize,
    matrix_size: usize,
    centre_points: usize,
    points_per_sector: usize,
    rotation_defect: f64,
    spectrum: analysis::Spectrum,
    fourier_blocks: Vec<BlockReport>,
    /// Limit-point stencil: weights of the local-net points (centre first, then sector 0).
    limit_stencil: Vec<f64>,
    /// Tangent stencils: left eigenvectors of lambda (orthonormal basis).
    tangent_stencils: Vec<Vec<f64>>,
    characteristic_map: Option<certify::InjectivityCertificate>,
    published: Vec<Published>,
    /// QAS+: the spectral radius of M_d and the eigenvalues of M_q per kind of expansion.
    #[serde(skip_serializing_if = "Option::is_none")]
    qas: Option<local::QasFacts>,
}

/// A published value next to the computed one.
#[derive(Debug, Serialize)]
struct Published {
    quantity: String,
    published: f64,
    computed: f64,
    difference: f64,
}

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
}

fn c2(z: analysis::C64) -> [f64; 2] {
    [z.re, if z.im.abs() < 1e-13 { 0.0 } else { z.im }]
}

/// Runs `fairsub analyze`.
pub fn analyze(mut a: AnalyzeArgs) -> Result<()> {
    a.scheme = fairsub::surface::guided::scheme_with_lambda(&a.scheme, a.lambda)?;
    let adj = super::subdivide::adjustable_rules(&a.scheme, a.split_ratio, a.alpha_rule)?
        .unwrap_or(fairsub::schemes::bi2::ternary::TernaryRules::adjustable(
            analysis::bi2::DEFAULT_E,
        )?);
    let bi2_name = match a.scheme.as_str() {
        "pgs" | "polar-bi2" | "tps" | "tps-adjustable" => Some(a.scheme.as_str()),
        "polbs" => Some("polar-bi2"),
        _ => None,
    };
    let lm = match bi2_name {
        Some(s) => analysis::bi2::local_matrix_rules(s, a.valence, adj)?,
        None => local::local_matrix(&a.scheme, a.valence)?,
    };
    let lm = if a.replicated_centre {
        lm.replicated_centre()
    } else {
        lm
    };
    let spectrum = analysis::spectrum(&lm.matrix);
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
    let mut limit_stencil = lm.limit_stencil()?;
    // Guided: the matrix acts on the guide's free set P, whose first coordinate is the limit
    // point; its stencil on the c-net (centre, then sector by sector) is the fit's first row.
    if let Some(o) = fairsub::surface::guided::parse_scheme(&a.scheme)
        && let Ok(g) = fairsub::schemes::guided::rings::Guided::new(a.valence, o)
    {
        limit_stencil = g.fit.row(0).iter().copied().collect();
    }
    let tangent_stencils = lm
        .left_eigenvectors(spectrum.lambda)
        .into_iter()
        .map(|v| v.iter().copied().collect())
        .collect();
    let ring = match bi2_name {
        Some(s) => analysis::bi2::characteristic_ring_rules(s, a.valence, adj),
        None => local::characteristic_ring(&a.scheme, a.valence),
    };
    let characteristic_map = ring
        .ok()
        .map(|(ring, lambda)| certify::certify_ring(&ring, lambda));
    let mut published = Vec::new();
    if let Some(s) = bi2_name {
        // The bi-2 paper's polynomials, eigenvalues and limit points (its own matrix layout).
        for c in analysis::bi2::published_rules(s, a.valence, adj)? {
            published.push(Published {
                quantity: c.quantity,
                published: c.published,
                computed: c.computed,
                difference: c.difference,
            });
        }
    }
    if matches!(
        a.scheme.as_str(),
        "nonbox" | "non-box" | "nonbox-4dir" | "non-box-4dir"
    ) {
        for c in analysis::nonbox::published_comparisons(a.valence)? {
            published.push(Published {
                quantity: c.quantity,
                published: c.published,
                computed: c.computed,
                difference: c.difference,
            });
        }
    }
    if matches!(a.scheme.as_str(), "catmull-clark" | "cc") {
        let l = analysis::catmull_clark_lambda(a.valence);
        published.push(Published {
            quantity: "lambda = (c + 5 + sqrt((c+1)(c+9))) / 16".into(),
            published: l,
            computed: spectrum.lambda,
            difference: (spectrum.lambda - l).abs(),
        });
        let n = a.valence as f64;
        published.push(Published {
            quantity: "limit weight of the centre n / (n + 5)".into(),
            published: n / (n + 5.0),
            computed: limit_stencil[0],
            difference: (limit_stencil[0] - n / (n + 5.0)).abs(),
        });
    }
    if let Some(o) = fairsub::surface::guided::parse_scheme(&a.scheme) {
        let l = local::guided_lambda(a.valence, o.chi);
        published.push(Published {
            quantity: "lambda (Catmull-Clark's, or 1/2 with --lambda 0.5)".into(),
            published: l,
            computed: spectrum.lambda,
            difference: (spectrum.lambda - l).abs(),
        });
        // Table (5) is for extraordinary valences; at n = 4 (c = 0) the G^2 space is the larger
        // C^2 one (81 coordinates: lambda^3 x6, lambda^4 x9).
        let table = if a.valence == 4 {
            Vec::new()
        } else {
            local::guided_table5(a.valence, l, &lm.matrix)
        };
        for (s, p, c) in table {
            published.push(Published {
                quantity: format!("multiplicity of lambda^{s} (table (5))"),
                published: p as f64,
                computed: c as f64,
                difference: (p as f64 - c as f64).abs(),
            });
        }
    }
    let qas = match a.scheme.as_str() {
        "qas-plus" => Some(local::qas_facts(a.valence, 0.5)?),
        "qas-0.4" => Some(local::qas_facts(a.valence, 0.4)?),
        "qas-plus-bi3" => Some(local::qas_bi3_facts(a.valence, 0.5)?),
        _ => None,
    };
    if let Some(q) = &qas {
        let published_rho = match a.valence {
            5 => Some(0.136208),
            6 => Some(0.125485),
            7 => Some(0.124899),
            _ => None,
        };
        if let (Some(p), true) = (published_rho, a.scheme == "qas-plus") {
            published.push(Published {
                quantity:
                    "spectral radius of M_d (papers README, from the K layout; paper: < 0.13621)"
                        .into(),
                published: p,
                computed: q.m_d_spectral_radius,
                difference: (q.m_d_spectral_radius - p).abs(),
            });
        }
    }
    if a.scheme == "eg" {
        let ratio = match a.valence {
            3 => Some(1.00015),
            5 => Some(1.00016),
            _ => None,
        };
        if let Some(p) = ratio {
            published.push(Published {
                quantity: "mu / lambda^2 (printed to 5 decimals)".into(),
                published: p,
                computed: spectrum.mu_over_lambda_squared,
                difference: (spectrum.mu_over_lambda_squared - p).abs(),
            });
        }
    }
    let r = AnalyzeReport {
        scheme: lm.scheme.clone(),
        valence: lm.n,
        matrix_size: lm.matrix.nrows(),
        centre_points: lm.centre,
        points_per_sector: lm.sector,
        rotation_defect: lm.rotation_defect(),
        spectrum,
        fourier_blocks,
        limit_stencil,
        tangent_stencils,
        characteristic_map,
        published,
        qas,
    };
    if a.json {
        println!(
            "{}",
            serde_json::to_string_pretty(&r).expect("serialisable")
        );
        return Ok(());
    }
    println!(
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
    println!("eigenvalues (modulus-sorted, multiplicity):");
    for e in r.spectrum.eigenvalues.iter().take(12) {
        if e.im == 0.0 {
            println!("  {:.10} x{}", e.re, e.multiplicity);
        } else {
            println!("  {:.10} {:+.10}i x{}", e.re, e.im, e.multiplicity);
        }
    }
    if r.spectrum.eigenvalues.len() > 12 {
        println!("  ... ({} distinct in all)", r.spectrum.eigenvalues.len());
    }
    println!(
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
    println!("limit stencil (centre, sector 0): {}", shown.join(" "));
    if let Some(c) = &r.characteristic_map {
        println!(
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
    if let Some(q) = &r.qas {
        println!(
            "QAS+: spectral radius of M_d {:.6}; M_q eigenvalues: C^2 {:?}, C^1 {} values, C^1-C^0 {} values (all 1, 1/2 x2, then 1/4)",
            q.m_d_spectral_radius,
            q.m_q_c2
                .iter()
                .map(|x| format!("{x:.4}"))
                .collect::<Vec<_>>(),
            q.m_q_c1.len(),
            q.m_q_c1c0.len()
        );
    }
    for p in &r.published {
        println!(
            "published {}: {:.12}, computed {:.12} (difference {:.1e})",
            p.quantity, p.published, p.computed, p.difference
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
}

/// Runs `fairsub charmap`.
pub fn charmap(a: CharmapArgs) -> Result<()> {
    let (ring, lambda) = local::characteristic_ring(&a.scheme, a.valence)?;
    let cert = certify::certify_ring(&ring, lambda);
    let mut c = PatchComplex::new();
    for (k, p) in ring.iter().enumerate() {
        let prov = Provenance::Ring {
            element: fairsub::surface::Element::Vertex(0),
            ring: 1,
            sector: (k / 3) as u32,
        };
        c.push(p.clone(), prov);
    }
    for (k, p) in ring.iter().enumerate() {
        let prov = Provenance::Ring {
            element: fairsub::surface::Element::Vertex(0),
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
            OutputFormat::Bv => fairsub::io::write_bv(&a.output, &c)?,
            OutputFormat::Iges => fairsub::io::write_iges(&a.output, &c)?,
            OutputFormat::Mesh(_) => {
                return Err(Error::InvalidArgument(
                    "charmap writes .bv, .igs or .svg".into(),
                ));
            }
        },
    }
    if a.json {
        println!(
            "{}",
            serde_json::to_string_pretty(&cert).expect("serialisable")
        );
    } else {
        println!(
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
    let (lo, hi) =
        fairsub::geom::bounding_box(c.patches.iter().flat_map(|p| p.cps.iter().copied()))
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
    fairsub::io::write_atomically(path, |w| {
        w.write_all(s.as_bytes()).map_err(|source| Error::Io {
            path: path.to_path_buf(),
            source,
        })
    })
}

/// Arguments of `fairsub check`.
#[derive(Debug, clap::Args)]
pub struct CheckArgs {
    /// A BezierView file (any tool's), or a control net (file or gallery:NAME) with --scheme.
    pub input: String,
    /// Build the surface of a net with this scheme.
    #[arg(long, short)]
    pub scheme: Option<String>,
    /// Rings for --scheme.
    #[arg(long, short, default_value_t = 4)]
    pub rings: usize,
    /// Leave the centre open (check the rings only).
    #[arg(long)]
    pub no_fill: bool,
    /// Print the report as JSON.
    #[arg(long)]
    pub json: bool,
}

/// The `check` report.
#[derive(Debug, Serialize)]
struct CheckReport {
    source: String,
    continuity: continuity::ContinuityReport,
    curvature: Vec<curvature::ElementCurvature>,
    /// C^1 up to a per-piece affine reparametrisation (bi-2 schemes, whose polar and
    /// adjustable rings shrink differently along and across their sides; `.bv` input).
    #[serde(skip_serializing_if = "Option::is_none")]
    c1_up_to_scaling: Option<analysis::bi2::ScaledContinuity>,
}

/// Maps BezierView group names written by fairsub (`regular`, `ringK`, `cap`) back to provenance.
fn provenance_of_group(name: Option<&str>) -> Provenance {
    let e = fairsub::surface::Element::Vertex(0);
    match name {
        Some("regular") => Provenance::Regular { face: 0 },
        Some("cap") => Provenance::Cap {
            element: e,
            sector: 0,
        },
        Some(g) if g.starts_with("ring") => match g[4..].parse::<u32>() {
            Ok(ring) => Provenance::Ring {
                element: e,
                ring,
                sector: 0,
            },
            Err(_) => Provenance::Unknown,
        },
        _ => Provenance::Unknown,
    }
}

/// Runs `fairsub check`.
pub fn check(a: CheckArgs) -> Result<()> {
    let complex = match &a.scheme {
        Some(s) => {
            let net = super::load_net(&a.input)?.mesh;
            super::subdivide::build_complex(s, &net, a.rings, !a.no_fill)?
        }
        None => {
            let path = Path::new(&a.input);
            let is_bv = path
                .extension()
                .and_then(|e| e.to_str())
                .is_some_and(|e| e.eq_ignore_ascii_case("bv"));
            if !is_bv {
                return Err(Error::InvalidArgument(format!(
                    "'{}' is not a .bv file: give a BezierView file, or a net with --scheme",
                    a.input
                )));
            }
            let f = fairsub::io::read_bv(path)?;
            for w in &f.warnings {
                eprintln!("warning: {}: {w}", a.input);
            }
            let mut c = f.patches;
            for (k, g) in f.patch_groups.iter().enumerate() {
                let name = g.and_then(|g| f.groups.get(g)).map(|g| g.name.as_str());
                c.provenance[k] = provenance_of_group(name);
            }
            c
        }
    };
    let scaled = match a.scheme.as_deref() {
        None => true,
        Some(s) => matches!(
            s,
            "pgs" | "pgs-dscc" | "polar-bi2" | "polbs" | "tps" | "tps-adjustable" | "bi2-mixed"
        ),
    };
    let r = CheckReport {
        source: a.input.clone(),
        continuity: continuity::check(&complex),
        curvature: curvature::ring_curvature(&complex),
        c1_up_to_scaling: scaled.then(|| analysis::bi2::continuity_up_to_scaling(&complex)),
    };
    if a.json {
        println!(
            "{}",
            serde_json::to_string_pretty(&r).expect("serialisable")
        );
        return Ok(());
    }
    let c = &r.continuity;
    println!(
        "{}: {} patches, {} shared pieces, {} open sides, size {:.4}",
        r.source, c.patches, c.all.pieces, c.open_sides, c.size
    );
    println!(
        "  {:<22} {:>7} {:>10} {:>10} {:>10} {:>10}",
        "join", "pieces", "C0", "C1", "C2", "G1 (rad)"
    );
    for (k, d) in &c.by_kind {
        println!(
            "  {:<22} {:>7} {:>10.2e} {:>10.2e} {:>10.2e} {:>10.2e}",
            k, d.pieces, d.c0, d.c1, d.c2, d.g1
        );
    }
    if let Some(l) = &c.all.c0_at {
        println!(
            "  largest C0 gap {:.3e} between patches {} and {} at {:?}",
            c.all.c0, l.patch_a, l.patch_b, l.point
        );
    }
    for o in c.open.iter().take(8) {
        println!(
            "  open side {} of patch {} ({}) at {:?}",
            o.side,
            o.patch,
            o.provenance.group_name(),
            o.midpoint
        );
    }
    if c.open_sides > 8 {
        println!(
            "  ... {} open sides in all (the boundary of the surface, or cracks)",
            c.open_sides
        );
    }
    if let Some(sc) = &r.c1_up_to_scaling {
        println!("  C1 up to per-piece scaling (D_A + kappa D_B = 0 across each piece):");
        println!(
            "  {:<22} {:>7} {:>12} {:>10} {:>10} {:>10}",
            "join", "pieces", "C1 relative", "kappa min", "kappa max", "G1 (rad)"
        );
        for (k, d) in &sc.by_kind {
            println!(
                "  {:<22} {:>7} {:>12.2e} {:>10.4} {:>10.4} {:>10.2e}",
                k, d.pieces, d.c1_relative, d.kappa_min, d.kappa_max, d.g1
            );
        }
    }
    for e in &r.curvature {
        println!("  curvature around {:?}:", e.element);
        for ring in &e.rings {
            println!(
                "    {:<6} K [{:+.4e}, {:+.4e}]  H [{:+.4e}, {:+.4e}]",
                if ring.ring == 0 {
                    "cap".to_string()
                } else {
                    format!("ring{}", ring.ring)
                },
                ring.gauss_min,
                ring.gauss_max,
                ring.mean_min,
                ring.mean_max
            );
        }
    }
    Ok(())
}
