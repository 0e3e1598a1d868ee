//! `fairsub subdivide`: refined nets, exact patch complexes and their tessellations.

use fairsub::io::OutputFormat;
use fairsub::surface::{ComplexOptions, PatchComplex};
use fairsub::{Error, PolyMesh, Result};
use std::path::PathBuf;

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
    let loaded = super::load_net(&a.net)?;
    let mesh = loaded.mesh;
    if patches {
        let rings = a.rings.unwrap_or(DEFAULT_RINGS);
        let complex = build_complex_with(&a.scheme, &mesh, rings, !a.no_fill, a.fallback.into())?;
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
        let refined = refine(&a.scheme, &mesh, levels, a.limit)?;
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

/// Refines `levels` times (with a progress bar) and optionally projects to the limit.
pub fn refine(scheme: &str, mesh: &PolyMesh, levels: usize, limit: bool) -> Result<PolyMesh> {
    let s = fairsub::schemes::by_name(scheme)?;
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
