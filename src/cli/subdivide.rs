//! `fairsub subdivide`: refined nets, exact patch complexes and their tessellations.

use fairsub::io::OutputFormat;
use fairsub::surface::{ComplexOptions, PatchComplex};
use fairsub::{Error, PolyMesh, Result};
use std::path::PathBuf;

mod nonbox;

/// Arguments of `fairsub subdivide`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The control net (file or gallery:NAME).
    pub net: String,
    /// The scheme (see `fairsub schemes`).
    #[arg(long, short)]
    pub scheme: String,
    /// Refinement steps for net output.
    #[arg(long, short)]
    pub levels: Option<usize>,
    /// Rings per extraordinary element for patch output.
    #[arg(long, short)]
    pub rings: Option<usize>,
    /// Project the refined net's points to their limit positions.
    #[arg(long)]
    pub limit: bool,
    /// Leave the hole inside the last ring open instead of filling it.
    #[arg(long, conflicts_with = "cap")]
    pub no_fill: bool,
    /// Close the hole inside the last ring with the scheme's cap (the default; guided schemes:
    /// the G^1 bi-6 cap of Appendix B).
    #[arg(long)]
    pub cap: bool,
    /// Contraction of a guided scheme: 0.5 samples through QAS+'s characteristic map (valences
    /// 5..10); without it, Catmull-Clark's chi and lambda.
    #[arg(long)]
    pub lambda: Option<f64>,
    /// Samples per patch edge when a patch complex is written as a mesh.
    #[arg(long, default_value_t = 8)]
    pub tess: usize,
    /// Face control vertices (non-box schemes).
    #[command(flatten)]
    pub fcv: nonbox::FcvArgs,
    /// Output file.
    #[arg(long, short)]
    pub output: PathBuf,
    /// Output format (obj, off, ply, ply-ascii, bv, igs), instead of the extension.
    #[arg(long)]
    pub format: Option<String>,
    /// At vertices whose valence has no rules (EG: all but 3, 4, 5): use Catmull-Clark there,
    /// or stop with an error.
    #[arg(long, value_enum, default_value_t = FallbackArg::CatmullClark)]
    pub fallback: FallbackArg,
    /// QAS+ only: quadratic expansions per vertex (lines `vertex V`, `kind c2|c1|c1-c0`,
    /// `p X Y Z`, `q SECTOR K X Y Z`); they replace fairsub's qas-fit where given.
    #[arg(long)]
    pub q_file: Option<PathBuf>,
    /// tps-adjustable only: the split ratio e, 0 < e < 1/2 (default 0.2; 1/3 is TPS).
    #[arg(long)]
    pub split_ratio: Option<f64>,
    /// tps-adjustable only: how rule (18)'s alphas are chosen.
    #[arg(long, value_enum)]
    pub alpha_rule: Option<AlphaRuleArg>,
    /// polar-bi2 only: the pole of an n-gon cap, `FACE:X,Y,Z` (input face index; repeatable).
    /// Caps without one get their centroid.
    #[arg(long)]
    pub pole: Vec<String>,
}

/// `--fallback` values.
#[derive(Debug, Clone, Copy, clap::ValueEnum)]
pub enum FallbackArg {
    /// Catmull-Clark rings and fill at vertices without rules.
    CatmullClark,
    /// Stop with an error naming the vertex.
    Error,
}

impl From<FallbackArg> for fairsub::surface::Fallback {
    fn from(f: FallbackArg) -> Self {
        match f {
            FallbackArg::CatmullClark => fairsub::surface::Fallback::CatmullClark,
            FallbackArg::Error => fairsub::surface::Fallback::Error,
        }
    }
}

/// `--alpha-rule` values.
#[derive(Debug, Clone, Copy, clap::ValueEnum)]
pub enum AlphaRuleArg {
    /// The paper's: the stationary limit point is TPS's (21) (default).
    TpsLimitPoint,
    /// fairsub's alternative: stationary frequency-0 eigenvalues lambda^2, lambda^4 (bounded
    /// curvature, mu / lambda^2 = 1); the limit point is still TPS's (21).
    RegularSpectrum,
}

impl From<AlphaRuleArg> for fairsub::schemes::bi2::AlphaRule {
    fn from(a: AlphaRuleArg) -> Self {
        match a {
            AlphaRuleArg::TpsLimitPoint => fairsub::schemes::bi2::AlphaRule::TpsLimitPoint,
            AlphaRuleArg::RegularSpectrum => fairsub::schemes::bi2::AlphaRule::RegularSpectrum,
        }
    }
}

/// The rules of `tps-adjustable` from `--split-ratio` and `--alpha-rule` (`None` when neither
/// is given); an error when they are given for another scheme.
pub fn adjustable_rules(
    scheme: &str,
    split_ratio: Option<f64>,
    alpha_rule: Option<AlphaRuleArg>,
) -> Result<Option<fairsub::schemes::bi2::ternary::TernaryRules>> {
    if split_ratio.is_none() && alpha_rule.is_none() {
        return Ok(None);
    }
    if scheme != "tps-adjustable" {
        return Err(Error::InvalidArgument(format!(
            "--split-ratio and --alpha-rule apply to tps-adjustable, not to '{scheme}'"
        )));
    }
    let e = split_ratio.unwrap_or(fairsub::analysis::bi2::DEFAULT_E);
    let rule = alpha_rule.map(Into::into).unwrap_or_default();
    fairsub::schemes::bi2::ternary::TernaryRules::adjustable_with(e, rule).map(Some)
}

/// Default rings of patch output when none are given.
pub const DEFAULT_RINGS: usize = 6;

/// Runs `fairsub subdivide`.
pub fn run(mut a: Args) -> Result<()> {
    a.scheme = fairsub::surface::guided::scheme_with_lambda(&a.scheme, a.lambda)?;
    let fmt = OutputFormat::choose(&a.output, a.format.as_deref())?;
    if a.levels.is_some() && a.rings.is_some() {
        return Err(Error::InvalidArgument(
            "give either --levels (refined net) or --rings (patch complex), not both".into(),
        ));
    }
    let refinable = fairsub::schemes::catalog()
        .iter()
        .any(|s| s.name == a.scheme && s.refine)
        || fairsub::schemes::by_name(&a.scheme).is_ok();
    let has_patches = fairsub::schemes::catalog()
        .iter()
        .any(|s| s.name == a.scheme && s.rings)
        || fairsub::surface::guided::parse_scheme(&a.scheme).is_some();
    if !refinable && has_patches && a.levels.is_some() {
        return Err(Error::InvalidArgument(format!(
            "scheme '{}' has no control net of its own to refine: write its patches with --rings K \
             (.bv, .igs, or a tessellated .obj/.ply)",
            a.scheme
        )));
    }
    let patches = match (fmt, a.levels, a.rings) {
        (_, _, Some(_)) => true,
        (_, None, None) if !refinable && has_patches => true,
        (OutputFormat::Iges, Some(_), None) => {
            return Err(Error::InvalidArgument(
                "IGES holds patches: use --rings K instead of --levels".into(),
            ));
        }
        (OutputFormat::Iges, None, None) | (OutputFormat::Bv, None, None) => true,
        (_, _, None) => false,
    };
    if a.tess == 0 {
        return Err(Error::InvalidArgument("--tess must be at least 1".into()));
    }
    let bi2 = Bi2Options::from_args(&a)?;
    let mesh = nonbox::load_net(&a.scheme, &a.net, &a.fcv)?;
    if patches {
        let rings = a.rings.unwrap_or(DEFAULT_RINGS);
        let complex = match (&a.q_file, &bi2) {
            (Some(qf), _) => {
                build_qas_with_file(&a.scheme, &mesh, rings, !a.no_fill, a.fallback.into(), qf)?
            }
            (None, Some(b)) => b.complex(&mesh, rings, !a.no_fill)?,
            (None, None) => {
                build_complex_with(&a.scheme, &mesh, rings, !a.no_fill, a.fallback.into())?
            }
        };
        write_complex(&complex, fmt, &a.output, a.tess)?;
        eprintln!(
            "wrote {} patches ({} rings, {}) to {}",
            complex.len(),
            rings,
            a.scheme,
            a.output.display()
        );
    } else {
        let levels = a.levels.unwrap_or(1);
        if nonbox::is_nonbox(&a.scheme) {
            return nonbox::write_net(&a.scheme, &mesh, levels, a.limit, fmt, &a.output);
        }
        let refined = match &bi2 {
            Some(b) => refine_with(b.scheme(), &mesh, levels, a.limit)?,
            None => refine(&a.scheme, &mesh, levels, a.limit)?,
        };
        match fmt {
            OutputFormat::Mesh(mf) => fairsub::io::write_mesh(&a.output, &refined, mf)?,
            OutputFormat::Bv => fairsub::io::write_bv_mesh(&a.output, &refined)?,
            OutputFormat::Iges => unreachable!("IGES net output was rejected above"),
        }
        eprintln!(
            "wrote {} vertices, {} faces ({} x {}) to {}",
            refined.num_vertices(),
            refined.num_faces(),
            levels,
            a.scheme,
            a.output.display()
        );
    }
    Ok(())
}

/// The bi-2 options of `subdivide` (`--split-ratio`, `--pole`), checked against the scheme.
enum Bi2Options {
    /// `tps-adjustable` with the given rules.
    Adjustable(fairsub::schemes::bi2::ternary::TernaryRules),
    /// `polar-bi2` with user-given poles.
    Poles(Vec<(usize, fairsub::geom::Point)>),
}

impl Bi2Options {
    /// `None` when neither option is given.
    fn from_args(a: &Args) -> Result<Option<Bi2Options>> {
        if let Some(r) = adjustable_rules(&a.scheme, a.split_ratio, a.alpha_rule)? {
            return Ok(Some(Bi2Options::Adjustable(r)));
        }
        if a.pole.is_empty() {
            return Ok(None);
        }
        if !matches!(a.scheme.as_str(), "polar-bi2" | "polbs") {
            return Err(Error::InvalidArgument(format!(
                "--pole applies to polar-bi2, not to '{}'",
                a.scheme
            )));
        }
        a.pole
            .iter()
            .map(|s| parse_pole(s))
            .collect::<Result<Vec<_>>>()
            .map(|p| Some(Bi2Options::Poles(p)))
    }

    /// The scheme for refined-net output.
    fn scheme(&self) -> Box<dyn fairsub::schemes::Scheme> {
        use fairsub::schemes::bi2::{AdjustableTps, PolarBi2};
        match self {
            Bi2Options::Adjustable(r) => Box::new(AdjustableTps {
                e: r.e,
                alphas: r.alphas,
            }),
            Bi2Options::Poles(p) => Box::new(PolarBi2 { poles: p.clone() }),
        }
    }

    /// The patch complex, with a progress bar; notes on stderr.
    fn complex(&self, mesh: &PolyMesh, rings: usize, fill: bool) -> Result<PatchComplex> {
        use fairsub::surface::bi2;
        let opts = ComplexOptions { rings, fill };
        let pb = super::progress_bar(rings as u64, "bi-2 rings");
        let progress = |l: usize| pb.set_position(l as u64);
        let (c, notes) = match self {
            Bi2Options::Adjustable(r) => bi2::tps_complex(mesh, opts, *r, progress)?,
            Bi2Options::Poles(p) => bi2::polar_complex(mesh, opts, p, progress)?,
        };
        pb.finish_and_clear();
        for n in notes {
            eprintln!("note: {n}");
        }
        Ok(c)
    }
}

/// Parses `FACE:X,Y,Z`.
fn parse_pole(s: &str) -> Result<(usize, fairsub::geom::Point)> {
    let bad = || {
        Error::InvalidArgument(format!(
            "--pole '{s}': expected FACE:X,Y,Z (input face index, then the pole's coordinates)"
        ))
    };
    let (f, xyz) = s.split_once(':').ok_or_else(bad)?;
    let f = f.trim().parse::<usize>().map_err(|_| bad())?;
    let c = xyz
        .split(',')
        .map(|t| t.trim().parse::<f64>())
        .collect::<std::result::Result<Vec<_>, _>>()
        .map_err(|_| bad())?;
    if c.len() != 3 || c.iter().any(|x| !x.is_finite()) {
        return Err(bad());
    }
    Ok((f, [c[0], c[1], c[2]]))
}

/// Refines `levels` times (with a progress bar) and optionally projects to the limit.
pub fn refine(scheme: &str, mesh: &PolyMesh, levels: usize, limit: bool) -> Result<PolyMesh> {
    refine_with(fairsub::schemes::by_name(scheme)?, mesh, levels, limit)
}

/// [`refine`] with a scheme value.
fn refine_with(
    s: Box<dyn fairsub::schemes::Scheme>,
    mesh: &PolyMesh,
    levels: usize,
    limit: bool,
) -> Result<PolyMesh> {
    let scheme = s.name();
    let pb = super::progress_bar(levels as u64, scheme);
    let mut m =
        fairsub::schemes::refine_levels(s.as_ref(), mesh, levels, |l| pb.set_position(l as u64))?;
    pb.finish_and_clear();
    if limit {
        let lim = s.limit_stencils(&m)?.apply(m.positions());
        m.set_positions(lim);
    }
    Ok(m)
}

/// Builds the patch complex with a progress bar.
pub fn build_complex(
    scheme: &str,
    mesh: &PolyMesh,
    rings: usize,
    fill: bool,
) -> Result<PatchComplex> {
    build_complex_with(
        scheme,
        mesh,
        rings,
        fill,
        fairsub::surface::Fallback::default(),
    )
}

/// Builds the patch complex with a progress bar; prints the notes (fallbacks) on stderr.
pub fn build_complex_with(
    scheme: &str,
    mesh: &PolyMesh,
    rings: usize,
    fill: bool,
    fallback: fairsub::surface::Fallback,
) -> Result<PatchComplex> {
    let pb = super::progress_bar(rings as u64, &format!("{scheme} rings"));
    let (c, notes) = fairsub::surface::complex_with_notes(
        scheme,
        mesh,
        ComplexOptions { rings, fill },
        fallback,
        |l| pb.set_position(l as u64),
    )?;
    pb.finish_and_clear();
    for n in notes {
        eprintln!("note: {n}");
    }
    Ok(c)
}

/// QAS+ with user-given quadratic expansions.
fn build_qas_with_file(
    scheme: &str,
    mesh: &PolyMesh,
    rings: usize,
    fill: bool,
    fallback: fairsub::surface::Fallback,
    path: &std::path::Path,
) -> Result<PatchComplex> {
    use fairsub::surface::qas::{Contraction, qas_complex_with};
    let contraction = match scheme {
        "qas-plus" => Contraction::Half,
        "qas-0.4" => Contraction::Fixed(0.4),
        "qas-0.5-0.4" => Contraction::Gradual,
        other => {
            return Err(Error::InvalidArgument(format!(
                "--q-file applies to qas-plus, qas-0.4 and qas-0.5-0.4, not to '{other}'"
            )));
        }
    };
    let text = std::fs::read_to_string(path).map_err(|source| Error::Io {
        path: path.to_path_buf(),
        source,
    })?;
    let overrides = fairsub::schemes::qas::parse_q_file(&text, path)?;
    let opts = fairsub::surface::eg::EgOptions {
        rings,
        fill,
        fallback,
    };
    let pb = super::progress_bar(rings as u64, &format!("{scheme} rings"));
    let out = qas_complex_with(mesh, opts, contraction, overrides, |l| {
        pb.set_position(l as u64)
    })?;
    pb.finish_and_clear();
    for n in out.notes {
        eprintln!("note: {n}");
    }
    Ok(out.complex)
}

/// Writes a patch complex in the chosen format (meshes get a watertight tessellation).
pub fn write_complex(
    c: &PatchComplex,
    fmt: OutputFormat,
    path: &std::path::Path,
    tess: usize,
) -> Result<()> {
    match fmt {
        OutputFormat::Bv => fairsub::io::write_bv(path, c),
        OutputFormat::Iges => fairsub::io::write_iges(path, c),
        OutputFormat::Mesh(mf) => {
            let t = fairsub::surface::tessellate::tessellate(c, tess);
            let (pos, fs, corners) = t.to_polygons();
            fairsub::io::write_polygons(path, &pos, &fs, &corners, mf)
        }
    }
}
