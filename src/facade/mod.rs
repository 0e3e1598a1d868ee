//! The curated library API: the entry points a Rust program (and the Python package) needs,
//! with typed values in and out, re-exported at the crate root.
//!
//! Every function runs the command line's own code path (`fairsub subdivide`, `analyze`,
//! `check`, `measure`, ...): the same loading, the same checks against the scheme's
//! descriptor, the same limits and the same error messages, with typed [`Options`] in place of
//! command-line words and the results handed back instead of written. Nothing here is a
//! second copy of a rule.

mod analyze;
mod picture;
mod refine;
mod surface;

pub use analyze::{Analysis, SchemeRow, analyze, schemes};
pub use picture::{Drawn, render};
pub use refine::{Refined, level_stencils, refine};
pub use surface::{Surface, surface};

use crate::cli::subdivide::{AlphaRuleArg, Args, FeatureArgs, SchemeArgs};
use crate::error::Result;
use crate::geom::Point;
use crate::mesh::PolyMesh;
use std::path::{Path, PathBuf};

pub use crate::host::Fallback;
pub use crate::mesh::tags::{BoundaryInterpolation, CreaseMethod, FvarInterpolation};
pub use crate::render::{
    BadOption, Image, LookOption, Mode, Overlays, RenderOptions, ShadeOptions, View,
};
pub use crate::schemes::bi2::ternary::AlphaRule;
pub use crate::schemes::descriptor::RulesChoice;
pub use crate::schemes::prepare::Mode as Prepare;

/// Where a control net comes from: a file or `gallery:NAME` (read the way the command line
/// reads it for the scheme: OBJ tags, FCVs and texture coordinates kept; tolerantly where the
/// scheme takes OpenSubdiv's features), or a net in memory.
#[derive(Debug, Clone)]
pub enum Source {
    /// A path (`.obj`, `.off`, `.ply`) or `gallery:NAME`.
    Path(String),
    /// A net in memory (its own tags and texture coordinates are kept).
    Net(Box<PolyMesh>),
}

impl Source {
    /// The name messages give the net, and the net when it is in memory.
    fn split(&self) -> (String, Option<PolyMesh>) {
        match self {
            Source::Path(p) => (p.clone(), None),
            Source::Net(m) => ("<net>".to_string(), Some(PolyMesh::clone(m))),
        }
    }
}

impl From<&str> for Source {
    fn from(p: &str) -> Self {
        Source::Path(p.to_string())
    }
}

impl From<&Path> for Source {
    fn from(p: &Path) -> Self {
        Source::Path(p.display().to_string())
    }
}

impl From<PolyMesh> for Source {
    fn from(m: PolyMesh) -> Self {
        Source::Net(Box::new(m))
    }
}

impl From<&PolyMesh> for Source {
    fn from(m: &PolyMesh) -> Self {
        Source::Net(Box::new(m.clone()))
    }
}

/// A scheme's options, typed: each is the command-line option of the same name (`split_ratio`
/// is `--split-ratio`), checked against the scheme's descriptor the same way (an option the
/// scheme does not take is an error naming the schemes that do). The defaults are the
/// command line's.
///
/// ```
/// use fairsub::{Options, BoundaryInterpolation};
/// let o = Options {
///     boundary: Some(BoundaryInterpolation::EdgeOnly),
///     ..Options::default()
/// };
/// let m = fairsub::refine("gallery:cube", "catmull-clark", 1, false, &o)?.into_net();
/// assert_eq!(m.num_faces(), 24);
/// # Ok::<(), fairsub::Error>(())
/// ```
#[derive(Debug, Clone, Default)]
pub struct Options {
    /// Guided schemes: the contraction (0.5; `None`: Catmull-Clark's lambda).
    pub lambda: Option<f64>,
    /// Non-box schemes: the FCVs are this multiple of the face barycentres.
    pub fcv_scale: Option<f64>,
    /// Non-box schemes: an FCV side file.
    pub fcv_file: Option<PathBuf>,
    /// EG, QAS+, guided: what to do at valences without rules (default: Catmull-Clark).
    pub fallback: Fallback,
    /// QAS+: a file of quadratic expansions per vertex.
    pub q_file: Option<PathBuf>,
    /// tps-adjustable: the split ratio e, 0 < e < 1/2.
    pub split_ratio: Option<f64>,
    /// tps-adjustable: how rule (18)'s alphas are chosen.
    pub alpha_rule: Option<AlphaRule>,
    /// polar-bi2: the pole of an n-gon cap, per input face.
    pub poles: Vec<(usize, Point)>,
    /// EG and QAS+: printed or derived rules.
    pub rules: Option<RulesChoice>,
    /// Every scheme: prepare a net the rules do not take, or refuse it.
    pub prepare: Prepare,
    /// Catmull-Clark, Loop and the dual schemes: how boundaries are interpolated.
    pub boundary: Option<BoundaryInterpolation>,
    /// Catmull-Clark, Loop: how semi-sharp creases decay.
    pub crease_method: Option<CreaseMethod>,
    /// Catmull-Clark: OpenSubdiv's smooth triangles.
    pub smooth_triangles: bool,
    /// Catmull-Clark, Loop: how texture coordinates are interpolated.
    pub fvar: Option<FvarInterpolation>,
    /// A side file of OpenSubdiv tag lines (creases, corners, holes).
    pub creases: Option<PathBuf>,
}

impl Options {
    /// The command's arguments for `scheme` on `net` with these options (typed, not parsed
    /// from words): what `fairsub subdivide NET --scheme SCHEME ...` would hold.
    ///
    /// # Errors
    /// [`AlphaRule::Published`], which is the `tps` scheme's own rule, not an option.
    pub(crate) fn args(&self, net: String, scheme: &str) -> Result<Args> {
        let alpha_rule = match self.alpha_rule {
            None => None,
            Some(a) => Some(AlphaRuleArg::of(a).ok_or_else(|| {
                crate::Error::InvalidArgument(
                    "the alpha rule Published is the TPS scheme's own rule, not an option: choose that scheme".into(),
                )
            })?),
        };
        Ok(Args {
            net,
            scheme: scheme.to_string(),
            levels: None,
            rings: None,
            limit: false,
            no_fill: false,
            cap: false,
            tess: 8,
            options: SchemeArgs {
                lambda: self.lambda,
                fcv: crate::cli::subdivide::FcvArgs {
                    fcv_scale: self.fcv_scale,
                    fcv_file: self.fcv_file.clone(),
                },
                fallback: self.fallback.into(),
                q_file: self.q_file.clone(),
                split_ratio: self.split_ratio,
                alpha_rule,
                // Rust's shortest round-trip decimals: the command's parser reads the same f64s
                pole: self
                    .poles
                    .iter()
                    .map(|(f, p)| format!("{f}:{},{},{}", p[0], p[1], p[2]))
                    .collect(),
                rules: self.rules.map(Into::into),
                prepare: self.prepare.into(),
            },
            features: FeatureArgs {
                boundary: self.boundary,
                crease_method: self.crease_method,
                smooth_triangles: self.smooth_triangles,
                fvar: self.fvar,
                creases: self.creases.clone(),
            },
            output: PathBuf::from("out.obj"),
            stencils: None,
            format: None,
            vertex_colors: None,
            faces: Default::default(),
        })
    }
}

/// Reads a control net (`.obj`, `.off`, `.ply` or `gallery:NAME`) strictly, as `fairsub info`
/// does; with `tolerant`, every net OpenSubdiv accepts (non-manifold, unused vertices kept).
/// Returns the net and the reader's warnings.
///
/// ```
/// let (net, warnings) = fairsub::read_net("gallery:cube", false)?;
/// assert_eq!((net.num_vertices(), net.num_faces()), (8, 6));
/// assert!(warnings.is_empty());
/// # Ok::<(), fairsub::Error>(())
/// ```
pub fn read_net(path: &str, tolerant: bool) -> Result<(PolyMesh, Vec<String>)> {
    let l = crate::cli::load_net_as(path, tolerant)?;
    Ok((l.mesh, l.warnings))
}

/// Writes a net as `subdivide --levels` does (format by extension: `.obj`, `.off`, `.ply`,
/// `.bv`, `.usda`, `.glb`, ...), validated, atomically.
///
/// ```
/// let (net, _) = fairsub::read_net("gallery:cube", false)?;
/// let path = std::env::temp_dir().join(format!("fairsub-doc-{}.off", std::process::id()));
/// fairsub::write_net(&net, &path)?;
/// assert_eq!(fairsub::read_net(path.to_str().unwrap(), false)?.0.num_faces(), 6);
/// # std::fs::remove_file(&path).ok();
/// # Ok::<(), fairsub::Error>(())
/// ```
pub fn write_net(net: &PolyMesh, path: &Path) -> Result<()> {
    crate::cli::api::write_net(net, path)
}
