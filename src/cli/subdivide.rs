//! `fairsub subdivide`: refined nets, exact patch complexes and their tessellations.

use super::spec::{self, SchemeOptions};
use crate::error::{Error, Result};
use crate::io::OutputFormat;
use crate::mesh::PolyMesh;
use crate::schemes::{Scheme, Spec, registry};
use crate::surface::cad::FaceMode;
use crate::surface::{ComplexOptions, PatchComplex};
use std::path::PathBuf;

pub(crate) mod features;
mod nonbox;
mod options;
pub mod scene;

pub use features::FeatureArgs;
pub use nonbox::FcvArgs;
pub use options::{AlphaRuleArg, SchemeArgs};

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
    /// Samples per patch edge when a patch complex is written as a mesh.
    #[arg(long, default_value_t = 8)]
    pub tess: usize,
    /// The scheme's options (lambda, FCVs, fallback, q file, split ratio, alpha rule, poles,
    /// rules).
    #[command(flatten)]
    pub options: SchemeArgs,
    /// OpenSubdiv's sharp features and options (Catmull-Clark, Loop).
    #[command(flatten)]
    pub features: FeatureArgs,
    /// Output file.
    #[arg(long, short)]
    pub output: PathBuf,
    /// With --rings: also write the patch stencil table (the weights from the net's points to
    /// every Bezier coefficient of the written complex; format in the README, `fairsub::io::table`).
    #[arg(long, value_name = "FILE")]
    pub stencils: Option<PathBuf>,
    /// Output format (obj, off, ply, ply-ascii, bv, igs, step, usda, usdc, usdz, glb, gltf),
    /// instead of the extension.
    #[arg(long)]
    pub format: Option<String>,
    /// USD and glTF tessellations (--rings): colour the vertices by mean or Gaussian curvature
    /// or by the patches' provenance (glTF COLOR_0, USD primvars:displayColor).
    #[arg(long, value_enum, value_name = "BY")]
    pub vertex_colors: Option<scene::VertexColors>,
    /// CAD faces of STEP and IGES output: one per input face (default; per quad sub-face of
    /// an n-gon), packed into rectangles of the quad layout, or one per Bezier patch.
    #[arg(long, value_enum, default_value_t)]
    pub faces: FaceMode,
}

impl Args {
    /// The scheme with its options, checked against it.
    fn spec(&self) -> Result<Spec> {
        let o = &self.options;
        spec::resolve(
            &self.scheme,
            &SchemeOptions {
                lambda: o.lambda,
                fallback: Some(o.fallback.into()),
                split_ratio: o.split_ratio,
                alpha_rule: o.alpha_rule.map(Into::into),
                poles: &o.pole,
                q_file: o.q_file.as_deref(),
                fcv: o.fcv.fcv_scale.is_some() || o.fcv.fcv_file.is_some(),
                rules: o.rules.map(Into::into),
                subd: self.features.options(),
                creases: self.features.creases.is_some(),
                prepare: o.prepare.into(),
            },
        )
    }
}

/// Default rings of patch output when none are given.
pub const DEFAULT_RINGS: usize = 6;

/// What `fairsub subdivide` computes, before anything is written (the command writes it; the
/// library's other front ends, the Python package, hand it back).
#[derive(Debug, Clone)]
pub enum Computed {
    /// A refined net (`--levels N [--limit]`), hole faces removed.
    Net(PolyMesh),
    /// A non-box limit mesh (`--levels N --limit` under a non-box scheme that makes one): the
    /// refined quads split around their FCVs, every point at its limit, with the exact limit
    /// normals per vertex.
    LimitMesh(PolyMesh, Vec<crate::geom::Point>),
    /// A refined net of a non-box scheme in its FCV layout (`crate::schemes::nonbox::FcvNet`):
    /// OBJ output lists the FCVs as the last `v` lines.
    FcvNet(PolyMesh),
    /// An exact patch complex (`--rings K`) and the notes of its construction (fallbacks,
    /// derived rules).
    Complex(PatchComplex, Vec<String>),
}

/// Runs `fairsub subdivide`.
pub fn run(a: Args) -> Result<()> {
    run_keeping(&a).map(|_| ())
}

/// Runs `fairsub subdivide` and hands back the prepared job and what it wrote (`fairsub
/// batch` measures the same surface).
pub(crate) fn run_keeping(a: &Args) -> Result<(Prepared, Computed)> {
    let fmt = OutputFormat::choose(&a.output, a.format.as_deref())?;
    let p = prepare(a, None)?;
    if let (OutputFormat::Scene(sf), Some(0)) = (fmt, a.levels) {
        // the control net itself, with its scheme and tags
        scene::write_net(&a.output, &p.mesh, Some(&p.spec), sf)?;
        wrote(&p.mesh, 0, &p.label, &a.output);
        let net = p.mesh.clone();
        return Ok((p, Computed::Net(net)));
    }
    let (computed, label) = finish(a, &p)?;
    match &computed {
        Computed::Complex(complex, _) if matches!(fmt, OutputFormat::Scene(_)) => {
            let OutputFormat::Scene(sf) = fmt else {
                unreachable!("matched above")
            };
            crate::surface::validate::check_finite(complex)?;
            scene::write_complex(&a.output, complex, a.tess, a.vertex_colors, sf)?;
            eprintln!(
                "wrote the tessellation of {} patches ({} rings, {}, {} samples per edge) to {}",
                complex.len(),
                a.rings.unwrap_or(DEFAULT_RINGS),
                label,
                a.tess,
                a.output.display()
            );
        }
        Computed::Complex(complex, _) => {
            let table = match &a.stencils {
                Some(_) => Some(patch_table(a, &p, complex)?),
                None => None,
            };
            write_complex_as(complex, fmt, &a.output, a.tess, Some(a.faces))?;
            if let (Some(path), Some(t)) = (&a.stencils, &table) {
                crate::io::table::write_table(path, t)?;
                eprintln!(
                    "wrote the patch table ({} rows, {} weights over {} points) to {}",
                    t.rows().num_rows(),
                    t.rows().num_entries(),
                    t.num_sources(),
                    path.display()
                );
            }
            eprintln!(
                "wrote {} patches ({} rings, {}) to {}",
                complex.len(),
                a.rings.unwrap_or(DEFAULT_RINGS),
                label,
                a.output.display()
            );
        }
        Computed::LimitMesh(m, normals) => {
            nonbox::write_limit(m, normals, fmt, &a.output)?;
            wrote(m, a.levels.unwrap_or(1), &label, &a.output);
        }
        Computed::FcvNet(m) => {
            nonbox::write_refined(m, fmt, &a.output)?;
            wrote(m, a.levels.unwrap_or(1), &label, &a.output);
        }
        Computed::Net(refined) => {
            match fmt {
                OutputFormat::Mesh(mf) => {
                    for note in crate::io::lost_in(refined, mf) {
                        eprintln!("warning: {}: {note}", a.output.display());
                    }
                    crate::io::write_mesh(&a.output, refined, mf)?
                }
                OutputFormat::Bv => crate::io::write_bv_mesh(&a.output, refined)?,
                OutputFormat::Scene(sf) => scene::write_net(&a.output, refined, None, sf)?,
                OutputFormat::Iges | OutputFormat::Step => {
                    unreachable!("CAD net output was rejected above")
                }
            }
            wrote(refined, a.levels.unwrap_or(1), &label, &a.output);
        }
    }
    Ok((p, computed))
}

/// The patch stencil table of the complex `finish` built for a prepared `--rings` job (the
/// construction run again on displaced points, [`crate::surface::table`]), within the memory
/// budget.
pub fn patch_table(
    a: &Args,
    p: &Prepared,
    complex: &PatchComplex,
) -> Result<crate::surface::table::PatchTable> {
    let opts = ComplexOptions {
        rings: a.rings.unwrap_or(DEFAULT_RINGS),
        fill: !a.no_fill,
    };
    super::limits::check_table(complex)?;
    let spec = &p.spec;
    // the tracked table belongs to the same complex: the construction is deterministic
    if let Some((c, table)) = crate::surface::table::PatchTable::tracked(spec, &p.mesh, opts)?
        && c.patches == complex.patches
    {
        return Ok(table);
    }
    crate::surface::table::probe::build_from(&p.mesh, complex, &|m| {
        crate::surface::build(spec, m, opts, &mut |_| {}).map(|o| o.complex)
    })
}

/// The report line of a written net.
fn wrote(m: &PolyMesh, levels: usize, label: &str, output: &std::path::Path) {
    eprintln!(
        "wrote {} vertices, {} faces ({} x {}) to {}",
        m.num_vertices(),
        m.num_faces(),
        levels,
        label,
        output.display()
    );
}

/// The refinement or the complex of a prepared job, and the scheme's label for its report.
pub fn finish(a: &Args, p: &Prepared) -> Result<(Computed, String)> {
    let (spec, mesh) = (&p.spec, &p.mesh);
    let label = p.label.clone();
    if p.patches {
        let rings = a.rings.unwrap_or(DEFAULT_RINGS);
        let (complex, notes) = build_complex_noted(spec, mesh, rings, !a.no_fill)?;
        return Ok((Computed::Complex(complex, notes), label));
    }
    let levels = a.levels.unwrap_or(1);
    let scheme = mesh_rules(spec)?;
    let prepared = crate::schemes::prepare::prepare(
        registry().descriptor(spec.id),
        spec,
        mesh,
        crate::schemes::prepare::Purpose::Refine,
    )?;
    for n in prepared.notes(spec.name()) {
        eprintln!("note: {n}");
    }
    let mesh = &prepared.mesh;
    super::limits::check_levels(scheme.as_ref(), mesh, levels)?;
    if scheme.fcv_layout() != crate::schemes::FcvLayout::None {
        // the non-box reports name the scheme's rules, and the limit
        let label = format!("{}{}", scheme.name(), if a.limit { ", limit" } else { "" });
        let net = nonbox::compute_net(scheme.as_ref(), mesh, levels, a.limit)?;
        let out = match &net {
            Computed::Net(m) | Computed::FcvNet(m) | Computed::LimitMesh(m, _) => m.extras(),
            Computed::Complex(..) => None,
        };
        let input = mesh.extras().and_then(|e| e.vertex_data.as_ref());
        if let (Some(d), None) = (input, out.and_then(|e| e.vertex_data.as_ref())) {
            // The FCV layout of given FCVs and the limit mesh around the FCVs are new points.
            eprintln!(
                "warning: {}: the per-vertex properties ({}) are not carried into {}'s {}; the \
                 output has positions only",
                a.net,
                d.names.join(", "),
                scheme.name(),
                if a.limit { "limit mesh" } else { "FCV layout" }
            );
        }
        return Ok((net, label));
    }
    let refined = refine_with(scheme.as_ref(), mesh, levels, a.limit)?.without_holes();
    Ok((Computed::Net(refined), label))
}

/// A `subdivide` job after its arguments are checked and its net is loaded.
#[derive(Debug)]
pub struct Prepared {
    /// The scheme with its options (and the net's option tags where the scheme takes them).
    pub spec: Spec,
    /// The scheme as reports name it.
    pub label: String,
    /// The net, as the scheme reads it (FCV layout, tags).
    pub mesh: PolyMesh,
    /// Whether the job writes patches (else a refined net).
    pub patches: bool,
}

/// Checks `subdivide`'s arguments and loads the net (`net`, when given, stands for the file);
/// see [`compute`].
pub fn prepare(a: &Args, net: Option<PolyMesh>) -> Result<Prepared> {
    let fmt = OutputFormat::choose(&a.output, a.format.as_deref())?;
    let mut spec = match a.spec() {
        Ok(s) => s,
        // An unknown name: the error lists the schemes for what was asked.
        Err(Error::UnknownScheme { name, .. }) => {
            let wants_patches = a.rings.is_some()
                || (a.levels.is_none()
                    && matches!(
                        fmt,
                        OutputFormat::Bv | OutputFormat::Iges | OutputFormat::Step
                    ));
            return Err(if wants_patches {
                crate::surface::no_patch_output(&name)
            } else {
                registry()
                    .lookup_for(&name, " for refinement", |c| c.refine)
                    .err()
                    .unwrap_or(Error::InvalidArgument(name))
            });
        }
        Err(e) => return Err(e),
    };
    let label = spec::label(&a.scheme, &spec);
    if a.levels.is_some() && a.rings.is_some() {
        return Err(Error::InvalidArgument(
            "give either --levels (refined net) or --rings (patch complex), not both".into(),
        ));
    }
    let caps = registry().entry(spec.id).capabilities();
    if !caps.refine && caps.patches && a.levels.is_some() {
        return Err(Error::InvalidArgument(format!(
            "scheme '{}' has no control net of its own to refine: write its patches with --rings K \
             (.bv, .igs, or a tessellated .obj/.ply)",
            a.scheme
        )));
    }
    let patches = match (fmt, a.levels, a.rings) {
        (_, _, Some(_)) => true,
        (_, None, None) if !caps.refine && caps.patches => true,
        (OutputFormat::Iges | OutputFormat::Step, Some(_), None) => {
            return Err(Error::InvalidArgument(
                "IGES and STEP hold surfaces: use --rings K instead of --levels".into(),
            ));
        }
        (OutputFormat::Iges | OutputFormat::Step | OutputFormat::Bv, None, None) => true,
        (_, _, None) => false,
    };
    if a.stencils.is_some() && !patches {
        return Err(Error::InvalidArgument(
            "--stencils writes the patch table of a complex: give --rings K (for the stencils \
             of a refined net use the library's level_stencils)"
                .into(),
        ));
    }
    if a.tess == 0 {
        return Err(Error::InvalidArgument("--tess must be at least 1".into()));
    }
    if a.vertex_colors.is_some() && !(patches && matches!(fmt, OutputFormat::Scene(_))) {
        return Err(Error::InvalidArgument(
            "--vertex-colors colours the tessellation of the exact surface in USD or glTF \
             output: give --rings K and -o OUT.glb, .gltf, .usda, .usd or .usdz"
                .into(),
        ));
    }
    let mesh = if features::takes_features(&spec) {
        features::load_net(&mut spec, &a.features, &a.net, !patches, net)?
    } else {
        let m = nonbox::load_net(&spec, &a.net, &a.options.fcv, net)?;
        features::with_net_options(&spec, &a.features, m)?
    };
    if let Some(q) = &a.options.q_file {
        // the expansions name vertices of this net: check them against it, at their lines
        crate::schemes::qas::qfile::check_q_file(&crate::io::read_text(q)?, q, &mesh)?;
    }
    if patches {
        if let Some(d) = mesh.extras().and_then(|e| e.vertex_data.as_ref()) {
            eprintln!(
                "warning: {}: the per-vertex properties ({}) are not carried into patch output",
                a.net,
                d.names.join(", ")
            );
        }
        features::refuse_patch_features(&spec, &mesh, &a.net)?;
    } else if !features::takes_features(&spec) {
        features::refuse_features(&spec, &mesh, &a.net, &format!("{label} has no rules for"))?;
    }
    Ok(Prepared {
        spec,
        label,
        mesh,
        patches,
    })
}

/// The mesh rules of a scheme (the error lists the schemes that refine nets).
pub fn mesh_rules(spec: &Spec) -> Result<Box<dyn Scheme>> {
    registry()
        .descriptor(spec.id)
        .mesh_rules(spec)?
        .ok_or_else(|| {
            registry()
                .lookup_for(spec.name(), " for refinement", |c| c.refine)
                .err()
                .unwrap_or_else(|| Error::InvalidArgument(spec.name().into()))
        })
}

/// Refines `levels` times with a progress bar and optionally projects to the limit; per-vertex
/// data goes through the same stencils as the positions ([`crate::schemes::refine_levels`],
/// the limit stencils).
pub fn refine_with(
    s: &dyn Scheme,
    mesh: &PolyMesh,
    levels: usize,
    limit: bool,
) -> Result<PolyMesh> {
    let scheme = s.name();
    let pb = super::progress_bar(levels as u64, scheme);
    let mut m = crate::schemes::refine_levels(s, mesh, levels, |l| pb.set_position(l as u64))?;
    pb.finish_and_clear();
    if limit {
        // One table for the positions and the per-vertex data.
        let table = s.limit_stencils(&m)?;
        m.set_positions(table.apply(m.positions()));
        if let Some(mut ex) = m.take_extras() {
            ex.vertex_data = ex.vertex_data.map(|d| d.through(&table));
            m.set_extras(Some(ex));
        }
    }
    Ok(m)
}

/// Builds the patch complex with a progress bar; prints the notes (fallbacks, derived rules)
/// on stderr.
pub fn build_complex(
    spec: &Spec,
    mesh: &PolyMesh,
    rings: usize,
    fill: bool,
) -> Result<PatchComplex> {
    build_complex_noted(spec, mesh, rings, fill).map(|(c, _)| c)
}

/// Like [`build_complex`], also returning the notes.
pub fn build_complex_noted(
    spec: &Spec,
    mesh: &PolyMesh,
    rings: usize,
    fill: bool,
) -> Result<(PatchComplex, Vec<String>)> {
    let prepared = crate::surface::prepare(spec, mesh)?;
    super::limits::check_complex(spec, &prepared.mesh, rings, fill)?;
    let pb = super::progress_bar(rings as u64, &format!("{} rings", spec.name()));
    let opts = ComplexOptions { rings, fill };
    let o =
        crate::surface::build_prepared(spec, &prepared, opts, &mut |l| pb.set_position(l as u64))?;
    pb.finish_and_clear();
    for n in &o.notes {
        eprintln!("note: {n}");
    }
    Ok((o.complex, o.notes))
}

/// Writes a patch complex in the chosen format (meshes get a watertight tessellation), after
/// checking that the output will be valid: finite coefficients, a tessellation within the
/// budget that is a valid mesh. IGES gets one face per patch, STEP one per input face
/// ([`write_complex_as`] chooses).
pub fn write_complex(
    c: &PatchComplex,
    fmt: OutputFormat,
    path: &std::path::Path,
    tess: usize,
) -> Result<()> {
    write_complex_as(c, fmt, path, tess, None)
}

/// [`write_complex`] with the CAD faces of IGES and STEP output (`None`: IGES per patch, STEP
/// per input face).
pub fn write_complex_as(
    c: &PatchComplex,
    fmt: OutputFormat,
    path: &std::path::Path,
    tess: usize,
    faces: Option<FaceMode>,
) -> Result<()> {
    crate::surface::validate::check_finite(c)?;
    match fmt {
        OutputFormat::Bv => crate::io::write_bv(path, c),
        OutputFormat::Iges => match faces {
            Some(mode) if mode != FaceMode::Patches => {
                let f = crate::surface::cad::faces(c, mode)?;
                crate::io::iges::write_iges_faces(path, &f)
            }
            _ => crate::io::write_iges(path, c),
        },
        OutputFormat::Step => super::cad::write_step(c, faces.unwrap_or_default(), path),
        OutputFormat::Mesh(mf) => {
            super::limits::check_tessellation(c, tess)?;
            let t = crate::surface::tessellate::tessellate(c, tess);
            // Written only as the mesh a reader would read back (validated, or an error that
            // names the patch).
            let mesh = t.to_mesh(c)?;
            drop(t);
            crate::io::write_mesh(path, &mesh, mf)
        }
        OutputFormat::Scene(sf) => scene::write_complex(path, c, tess, None, sf),
    }
}
