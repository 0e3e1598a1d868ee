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
    #[arg(long)]
    pub no_fill: bool,
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
    /// Non-box schemes: the FCVs are S times the face barycentres, scaled about the origin (the
    /// paper's Fig. 10 takes 0.5, 1, 1.5 on a cube). Default 1; ignored when an OBJ net lists
    /// its FCVs.
    #[arg(long, value_name = "S")]
    pub fcv_scale: Option<f64>,
    /// Non-box schemes: an FCV side file, one `x y z` line (or `*` for the default) per face in
    /// face order; replaces the FCVs of the net.
    #[arg(long, value_name = "FILE")]
    pub fcv_file: Option<PathBuf>,
}

/// Whether `scheme` names a non-box scheme (nets with face control vertices).
fn is_nonbox(scheme: &str) -> bool {
    matches!(
        scheme,
        "nonbox" | "non-box" | "nonbox-4dir" | "non-box-4dir"
    )
}

/// Loads the net of a non-box scheme: an OBJ file keeps the FCVs it lists (the layout of
/// `fairsub::schemes::nonbox::fcv`), `--fcv-file` and `--fcv-scale` set them otherwise. Returns
/// a layout mesh when FCVs were given, else the plain mesh (whose FCVs are its barycentres).
fn load_nonbox_net(a: &Args) -> Result<PolyMesh> {
    use fairsub::schemes::nonbox::{FcvNet, fcv};
    let path = std::path::Path::new(&a.net);
    let is_obj = !a.net.starts_with("gallery:")
        && path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("obj"));
    let (mesh, fcvs) = if is_obj {
        let (mesh, fcvs, warnings) = fcv::read_obj_fcvs(path)?;
        for w in warnings {
            eprintln!("warning: {}: {w}", a.net);
        }
        (mesh, fcvs)
    } else {
        (super::load_net(&a.net)?.mesh, None)
    };
    let scale = a.fcv_scale.unwrap_or(1.0);
    match fcvs {
        Some(fcvs) => {
            let net = FcvNet::new(mesh, fcvs)?;
            if a.fcv_scale.is_some() && a.fcv_file.is_none() {
                eprintln!("note: --fcv-scale is ignored: {} lists its own FCVs", a.net);
            }
            let net = match &a.fcv_file {
                Some(file) => fcv::load_fcv_file(net.mesh, file, scale)?,
                None => net,
            };
            Ok(net.to_layout_mesh())
        }
        None if a.fcv_scale.is_some() || a.fcv_file.is_some() => {
            Ok(FcvNet::choose(&mesh, scale, a.fcv_file.as_deref())?.to_layout_mesh())
        }
        None => Ok(mesh),
    }
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
pub fn run(a: Args) -> Result<()> {
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
        .any(|s| s.name == a.scheme && s.rings);
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
    let nonbox = is_nonbox(&a.scheme);
    if !nonbox && (a.fcv_scale.is_some() || a.fcv_file.is_some()) {
        return Err(Error::InvalidArgument(format!(
            "--fcv-scale and --fcv-file set face control vertices, which only the non-box \
             schemes (nonbox, nonbox-4dir) have, not '{}'",
            a.scheme
        )));
    }
    let mesh = if nonbox {
        load_nonbox_net(&a)?
    } else {
        super::load_net(&a.net)?.mesh
    };
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
        if nonbox {
            for n in fairsub::schemes::nonbox::input_notes(&a.scheme, &mesh) {
                eprintln!("note: {n}");
            }
        }
        let quad_nonbox = matches!(a.scheme.as_str(), "nonbox" | "non-box");
        let mut limit_normals = None;
        let refined = if quad_nonbox && a.limit {
            // The limit mesh: the refined net's quads split into four triangles around their
            // FCVs, every point at its limit (vertices, then face centres); OBJ gets normals.
            let net = fairsub::schemes::nonbox::FcvNet::from_mesh(&mesh);
            let (m, n) = fairsub::schemes::NonBox::limit_mesh_with_normals(&net, levels)?;
            limit_normals = Some(n);
            m
        } else {
            refine(&a.scheme, &mesh, levels, a.limit)?
        };
        let fcv_net = match (quad_nonbox && !a.limit, fmt) {
            (true, OutputFormat::Mesh(fairsub::io::MeshFormat::Obj)) => {
                fairsub::schemes::nonbox::FcvNet::from_layout_mesh(&refined)
            }
            _ => None,
        };
        match fmt {
            OutputFormat::Mesh(fairsub::io::MeshFormat::Obj) if limit_normals.is_some() => {
                fairsub::schemes::nonbox::fcv::write_limit_obj(
                    &a.output,
                    &refined,
                    limit_normals.as_deref().expect("checked"),
                )?
            }
            _ if fcv_net.is_some() => fairsub::schemes::nonbox::write_fcv_obj(
                &a.output,
                fcv_net.as_ref().expect("checked"),
            )?,
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
