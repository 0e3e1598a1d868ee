//! OpenSubdiv's sharp features on the command line of `fairsub subdivide`: the options
//! (`--boundary`, `--crease-method`, `--smooth-triangles`, `--fvar`, named as OpenSubdiv names
//! them), the `--creases` side file, and loading a net for a scheme that takes them
//! (Catmull-Clark, Loop): tolerantly (non-manifold nets, unused vertices kept), with the file's
//! tags, a command-line option overriding a tag.

use crate::error::{Error, Result};
use crate::mesh::PolyMesh;
use crate::mesh::tags::{
    BoundaryInterpolation, CreaseMethod, FvarInterpolation, Named, SubdOptions, TriangleSubdivision,
};
use crate::schemes::Spec;
use crate::schemes::descriptor::ParamKind;
use clap::builder::{PossibleValuesParser, TypedValueParser};
use std::path::PathBuf;

/// A parser of one of OpenSubdiv's option names (the possible values are listed by `--help`).
fn named<T: Named + Clone + Send + Sync>() -> impl TypedValueParser<Value = T> {
    PossibleValuesParser::new(T::ALL.iter().map(|v| v.name()))
        .map(|s| T::parse(&s).expect("a possible value"))
}

/// OpenSubdiv's options of `fairsub subdivide` (Catmull-Clark and Loop).
#[derive(Debug, Clone, Default, clap::Args)]
pub struct FeatureArgs {
    /// Catmull-Clark, Loop: how boundaries are interpolated (OpenSubdiv's
    /// VtxBoundaryInterpolation): edge-and-corner (the default: boundary edges are infinitely
    /// sharp creases, a vertex with one face is a corner and stays), edge-only (such a vertex
    /// follows the boundary crease), none (the faces at the boundary become holes, refined for
    /// support but not written). Overrides the net's `interpolateboundary` tag.
    #[arg(long, value_parser = named::<BoundaryInterpolation>())]
    pub boundary: Option<BoundaryInterpolation>,
    /// Catmull-Clark, Loop: how semi-sharp creases decay (OpenSubdiv's CreasingMethod):
    /// uniform (the default; the OBJ tag calls it normal) or chaikin. Overrides the
    /// `creasemethod` tag.
    #[arg(long, value_parser = named::<CreaseMethod>())]
    pub crease_method: Option<CreaseMethod>,
    /// Catmull-Clark: OpenSubdiv's smooth triangle option (TRI_SUB_SMOOTH: edge points next to
    /// triangles weigh the triangle's face point 0.47). Overrides the `smoothtriangles` tag.
    #[arg(long)]
    pub smooth_triangles: bool,
    /// Catmull-Clark, Loop: how texture coordinates (OBJ `vt`) are interpolated (OpenSubdiv's
    /// FVarLinearInterpolation): none, corners-only, corners-plus1, corners-plus2, boundaries,
    /// all (the default: linear). Overrides the `facevaryinginterpolateboundary` tag. The
    /// refined values are written as `vt` with `f v/vt` (OBJ output; with `--limit` the
    /// refined, not the limit, values).
    #[arg(long, value_parser = named::<FvarInterpolation>())]
    pub fvar: Option<FvarInterpolation>,
    /// Catmull-Clark, Loop: a side file of OpenSubdiv tag lines for OFF and PLY nets (or in
    /// addition to an OBJ net's own): `t crease 2/1/0 A B SHARPNESS`, `t corner 1/1/0 V
    /// SHARPNESS`, `t hole 1/0/0 F`, `t interpolateboundary 1/0/0 N`, ... (vertices and faces
    /// counted from 0; see the README).
    #[arg(long, value_name = "FILE")]
    pub creases: Option<PathBuf>,
}

impl FeatureArgs {
    /// The options as given on the command line.
    pub fn options(&self) -> SubdOptions {
        SubdOptions {
            boundary: self.boundary,
            crease_method: self.crease_method,
            triangles: self.smooth_triangles.then_some(TriangleSubdivision::Smooth),
            fvar: self.fvar,
        }
    }
}

/// Whether the scheme takes OpenSubdiv's sharp features.
pub fn takes_features(spec: &Spec) -> bool {
    crate::schemes::registry()
        .descriptor(spec.id)
        .params()
        .contains(&ParamKind::SharpFeatures)
}

/// Loads `arg` for a scheme that takes sharp features: tolerantly when `tolerant` (refinement:
/// non-manifold nets are accepted, unused vertices kept), with the `--creases` file's tags on
/// top of the net's own; the file's options fill the ones the command line leaves unset. With
/// `given`, that mesh (with its own tags) stands for the net `arg` names and no file is read.
pub fn load_net(
    spec: &mut Spec,
    a: &FeatureArgs,
    arg: &str,
    tolerant: bool,
    given: Option<PolyMesh>,
) -> Result<PolyMesh> {
    let mut mesh = match given {
        Some(m) => m,
        None => super::super::load_net_as(arg, tolerant)?.mesh,
    };
    if !tolerant && mesh.extras().is_some_and(|ex| ex.uv.is_some()) {
        eprintln!("warning: {arg}: texture coordinates are not carried into patch output");
    }
    if let Some(file) = &a.creases {
        let (tags, warnings) = crate::io::obj::read_tag_file(file)?;
        for w in warnings {
            eprintln!("warning: {}: {w}", file.display());
        }
        mesh = mesh.with_tags(&tags, file)?;
    }
    let mut file_opts = mesh.extras().map(|e| e.options).unwrap_or_default();
    if file_opts.triangles.is_some() && !takes(spec, ParamKind::SmoothTriangles) {
        eprintln!(
            "warning: {arg}: the smoothtriangles tag applies to Catmull-Clark only; ignored by {}",
            spec.name()
        );
        file_opts.triangles = None;
    }
    spec.params.subd = spec.params.subd.or(file_opts);
    Ok(mesh)
}

/// For a scheme that reads its options from the net (the dual schemes' boundary modes, the
/// crease constructions of the bi-2 family and non-box): the net with `--boundary` (when the
/// scheme takes the boundary modes) and `--crease-method` (when it takes creases) as its
/// options, overriding the net's tags, and with the `--creases` file's tags (when it takes
/// creases); the scheme reads them from there
/// ([`crate::schemes::doo_sabin::boundary_mode`], [`crate::schemes::doo_sabin::sharp`]).
///
/// # Errors
/// Those of reading the `--creases` file and applying its tags.
pub fn with_net_options(spec: &Spec, a: &FeatureArgs, mesh: PolyMesh) -> Result<PolyMesh> {
    let creases = takes(spec, ParamKind::Creases);
    let mut mesh = mesh;
    if let (Some(file), true) = (&a.creases, creases) {
        let (tags, warnings) = crate::io::obj::read_tag_file(file)?;
        for w in warnings {
            eprintln!("warning: {}: {w}", file.display());
        }
        mesh = mesh.with_tags(&tags, file)?;
    }
    let boundary = spec
        .params
        .subd
        .boundary
        .filter(|_| takes(spec, ParamKind::BoundaryMode));
    let method = spec.params.subd.crease_method.filter(|_| creases);
    if boundary.is_none() && method.is_none() {
        return Ok(mesh);
    }
    let mut ex = mesh.extras().cloned().unwrap_or_default();
    if boundary.is_some() {
        ex.options.boundary = boundary;
    }
    if method.is_some() {
        ex.options.crease_method = method;
    }
    Ok(mesh.with_extras(Some(ex)))
}

/// Whether the scheme refines the net's crease and corner tags with a construction of its own
/// ([`ParamKind::Creases`]).
pub fn takes_creases(spec: &Spec) -> bool {
    takes(spec, ParamKind::Creases)
}

fn takes(spec: &Spec, kind: ParamKind) -> bool {
    crate::schemes::registry()
        .descriptor(spec.id)
        .params()
        .contains(&kind)
}

/// For a scheme without OpenSubdiv's sharp features (or for patch output, which does not take
/// them yet): fails when the net tags sharp features, warns about option tags.
pub fn refuse_features(spec: &Spec, mesh: &PolyMesh, arg: &str, what: &str) -> Result<()> {
    let Some(ex) = mesh.extras() else {
        return Ok(());
    };
    if takes_creases(spec) && (ex.holes.is_empty() || takes(spec, ParamKind::Holes)) {
        // creases and corners are the scheme's own; the crease method is read off the net
    } else if ex.has_features() {
        return Err(Error::Unsupported(format!(
            "{arg} tags sharp features ({} sharp edges, {} sharp vertices, {} holes), which {what}; \
             refine it with --levels and a scheme with OpenSubdiv's rules (Catmull-Clark, Loop), or remove \
             the tags",
            ex.sharp_edges.len(),
            ex.sharp_vertices.len(),
            ex.holes.len()
        )));
    }
    let boundary_only = SubdOptions {
        boundary: None,
        ..ex.options
    }
    .is_empty();
    let creases_only = SubdOptions {
        boundary: None,
        crease_method: None,
        ..ex.options
    }
    .is_empty();
    if !ex.options.is_empty()
        && !takes_features(spec)
        && (!boundary_only || !takes(spec, ParamKind::BoundaryMode))
        && (!creases_only || !takes_creases(spec))
    {
        eprintln!(
            "warning: {arg}: OpenSubdiv option tags (interpolateboundary, creasemethod, ...) are \
             ignored by {}",
            spec.name()
        );
    }
    Ok(())
}

/// For patch output: fails when the net tags sharp features and the scheme's patches do not
/// take them (see [`refuse_features`]).
pub fn refuse_patch_features(spec: &Spec, mesh: &PolyMesh, arg: &str) -> Result<()> {
    if crate::schemes::registry()
        .descriptor(spec.id)
        .patches_take_features()
    {
        return Ok(());
    }
    let what = format!(
        "the patch output (--rings) of {} does not take yet",
        spec.name()
    );
    refuse_features(spec, mesh, arg, &what)
}

/// For `check --scheme` on a net: the net's option tags fill the options left unset, and a
/// scheme whose patches do not take sharp features refuses a net that tags them.
pub fn patch_features(spec: &mut Spec, mesh: &PolyMesh, arg: &str) -> Result<()> {
    refuse_patch_features(spec, mesh, arg)?;
    if takes_features(spec) {
        let file_opts = mesh.extras().map(|e| e.options).unwrap_or_default();
        spec.params.subd = spec.params.subd.or(file_opts);
    }
    Ok(())
}
