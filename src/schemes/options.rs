//! Scheme identity and options: the bottom of `schemes/`, imported by every family, by the
//! descriptors and by the registry, importing none of them.
//!
//! A scheme is named by a [`SchemeId`] (its canonical command-line name; each family spells its
//! own ids in its `entry.rs`) and configured by typed [`Params`]; the two together are a
//! [`Spec`]. The option types of single schemes live here too ([`GuideDegree`], [`ChiKind`],
//! [`AlphaRule`], [`QSpec`]), so that [`Params`] can name them without pointing into a family;
//! each family re-exports its own and keeps their behaviour (`impl` blocks) beside its rules.

use crate::error::Error;
use crate::geom::Point;
pub use crate::host::Fallback;
use serde::Serialize;

/// The ids of the built-in schemes (their names are spelled here and in the families'
/// `entry.rs` catalogue rows only).
pub mod ids {
    use crate::schemes::options::SchemeId;

    /// Catmull-Clark.
    pub const CATMULL_CLARK: SchemeId = SchemeId::new("catmull-clark");
    /// Doo-Sabin.
    pub const DOO_SABIN: SchemeId = SchemeId::new("doo-sabin");
    /// DS^CC.
    pub const DOO_SABIN_CC: SchemeId = SchemeId::new("doo-sabin-cc");
    /// Loop.
    pub const LOOP: SchemeId = SchemeId::new("loop");
    /// Non-box subdivision, quad variant with FCVs.
    pub const NONBOX: SchemeId = SchemeId::new("nonbox");
    /// Non-box subdivision, four-directional triangle variant.
    pub const NONBOX_4DIR: SchemeId = SchemeId::new("nonbox-4dir");
    /// Evolving Guide subdivision.
    pub const EG: SchemeId = SchemeId::new("eg");
    /// QAS+ of degree bi-4.
    pub const QAS_PLUS: SchemeId = SchemeId::new("qas-plus");
    /// QAS+ of degree bi-3.
    pub const QAS_PLUS_BI3: SchemeId = SchemeId::new("qas-plus-bi3");
    /// QAS+^4 with lambda 0.4.
    pub const QAS_04: SchemeId = SchemeId::new("qas-0.4");
    /// QAS+^4 with the gradual schedule 0.5 .. 0.4.
    pub const QAS_05_04: SchemeId = SchemeId::new("qas-0.5-0.4");
    /// Point-augmented bi-2 subdivision.
    pub const PGS: SchemeId = SchemeId::new("pgs");
    /// PGS after two DS^CC steps.
    pub const PGS_DSCC: SchemeId = SchemeId::new("pgs-dscc");
    /// Polar bi-2 subdivision.
    pub const POLAR_BI2: SchemeId = SchemeId::new("polar-bi2");
    /// Primal ternary bi-2 subdivision.
    pub const TPS: SchemeId = SchemeId::new("tps");
    /// Adjustable TPS.
    pub const TPS_ADJUSTABLE: SchemeId = SchemeId::new("tps-adjustable");
    /// The bi-2 family in one mesh.
    pub const BI2_MIXED: SchemeId = SchemeId::new("bi2-mixed");
    /// Guided subdivision, bi-5 rings.
    pub const GUIDED_BI5: SchemeId = SchemeId::new("guided-bi5");
    /// Guided subdivision, bi-6 rings.
    pub const GUIDED_BI6: SchemeId = SchemeId::new("guided-bi6");
    /// Guided subdivision, bi-4 macro-patch rings.
    pub const GUIDED_BI4_MACRO: SchemeId = SchemeId::new("guided-bi4-macro");
    /// Guided subdivision, bi-3 macro-patch rings.
    pub const GUIDED_BI3_MACRO: SchemeId = SchemeId::new("guided-bi3-macro");
    /// Kobbelt's sqrt(3) subdivision.
    pub const SQRT3: SchemeId = SchemeId::new("sqrt3");
    /// The modified butterfly scheme.
    pub const BUTTERFLY: SchemeId = SchemeId::new("butterfly");
}

/// A scheme's identity: its canonical command-line name. The built-in ids are the constants of
/// [`crate::schemes::options::ids`] (each family's own `ID`s); a scheme defined outside fairsub makes its own with
/// [`SchemeId::new`] and adds a registry row.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct SchemeId(&'static str);

impl SchemeId {
    /// The id of the scheme with this canonical name.
    pub const fn new(name: &'static str) -> SchemeId {
        SchemeId(name)
    }

    /// The canonical command-line name.
    pub const fn name(self) -> &'static str {
        self.0
    }
}

impl std::fmt::Display for SchemeId {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.0)
    }
}

impl Serialize for SchemeId {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        s.serialize_str(self.0)
    }
}

/// The typed options that some schemes take (the front ends check that an option given applies
/// to the scheme chosen).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ParamKind {
    /// `--fallback`: what happens at valences without rules.
    Fallback,
    /// `--lambda` / the `-half` suffix: the contraction of guided subdivision.
    Contraction,
    /// `--split-ratio`: adjustable TPS's `e`.
    SplitRatio,
    /// `--alpha-rule`: how adjustable TPS's alphas are chosen.
    AlphaRule,
    /// `--pole FACE:X,Y,Z`: poles of polar bi-2 caps.
    Poles,
    /// `--q-file`: user-given quadratic expansions of QAS+.
    QFile,
    /// `--fcv-scale`, `--fcv-file`: the face control vertices of the non-box schemes.
    Fcv,
    /// `--rules printed|derived` (or the `-derived` name suffix): the paper's printed rules or
    /// fairsub's derived ones where both exist (EG, QAS+).
    Rules,
    /// OpenSubdiv's sharp features and options: `--boundary`, `--crease-method`, `--fvar`,
    /// `--creases`, the net's crease, corner and hole tags, non-manifold nets.
    SharpFeatures,
    /// `--smooth-triangles`: OpenSubdiv's smooth triangle option (Catmull-Clark).
    SmoothTriangles,
    /// `--boundary` alone (and the net's `interpolateboundary` tag): the boundary modes of the
    /// dual schemes (`crate::schemes::doo_sabin`), for schemes without the rest of
    /// [`ParamKind::SharpFeatures`].
    BoundaryMode,
    /// The net's crease and corner tags (OpenSubdiv's `t crease`, `t corner`), `--creases`
    /// and `--crease-method`, for schemes that refine them with a construction of their own
    /// (the bi-2 family, non-box: fairsub's crease constructions) without the rest of
    /// [`ParamKind::SharpFeatures`]; the options are put on the net.
    Creases,
    /// The net's hole tags (OpenSubdiv's `t hole`) under `--levels` too, for a scheme with
    /// [`ParamKind::Creases`] whose refinement carries them to the children of hole faces
    /// (non-box); its patch output takes them either way.
    Holes,
}

impl ParamKind {
    /// The command-line option that sets it (for [`ParamKind::Holes`], the net's tag).
    pub fn option(self) -> &'static str {
        match self {
            ParamKind::Fallback => "--fallback",
            ParamKind::Contraction => "--lambda",
            ParamKind::SplitRatio => "--split-ratio",
            ParamKind::AlphaRule => "--alpha-rule",
            ParamKind::Poles => "--pole",
            ParamKind::QFile => "--q-file",
            ParamKind::Fcv => "--fcv-scale / --fcv-file",
            ParamKind::Rules => "--rules",
            ParamKind::SharpFeatures => "--boundary / --crease-method / --fvar / --creases",
            ParamKind::SmoothTriangles => "--smooth-triangles",
            ParamKind::BoundaryMode => "--boundary",
            ParamKind::Creases => "--creases / --crease-method",
            ParamKind::Holes => "t hole",
        }
    }
}

/// Which rules a scheme with printed and derived rules uses where the paper prints them
/// (`--rules`); elsewhere it uses its derived rules either way.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum RulesChoice {
    /// The paper's printed rules where they exist (the default).
    #[default]
    Printed,
    /// fairsub's derived rules also where printed ones exist (to compare the two).
    Derived,
}

/// Whether nets are prepared (`--prepare`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum PrepareMode {
    /// Apply the smallest documented step a scheme's rules need (the default).
    #[default]
    Auto,
    /// Apply nothing: a scheme refuses a net its rules do not take, naming the element.
    None,
}

/// Degree of the guide (Section 6.1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum GuideDegree {
    /// Bi-5, the paper's main guide.
    #[default]
    Bi5,
    /// Bi-4 (Section 6.1).
    Bi4,
    /// Bi-3 (Section 6.1).
    Bi3,
}

/// Which characteristic map the rings are sampled through.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ChiKind {
    /// Catmull-Clark's characteristic ring and lambda (the paper's default).
    #[default]
    CatmullClark,
    /// The QAS+ characteristic map, lambda = 1/2 (`--lambda 0.5`, valences 5..10).
    Half,
}

/// How rule (18)'s `alpha_1, alpha_2` are chosen.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum AlphaRule {
    /// TPS's published values.
    Published,
    /// Adjustable TPS as the paper states it: the stationary limit point is TPS's (21) (with
    /// the valence-3 fallback of `bi2::ternary::TernaryRules::stationary_alphas`).
    #[default]
    TpsLimitPoint,
    /// fairsub's alternative for adjustable TPS: the stationary frequency-0 eigenvalues are
    /// `lambda^2, lambda^4` as in the regular case (`mu / lambda^2 = 1` in that block); the
    /// surface's limit point is still TPS's, through the first step's `alpha`s.
    RegularSpectrum,
}

/// Kinds of the quadratic expansion `q` (Section 4.2).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum QKind {
    /// C^2 between sectors: one quadratic polynomial (6 free coefficients).
    #[default]
    C2,
    /// C^1 between sectors: `p`, the tangent plane and `q_5^s` free (`3 + n`).
    C1,
    /// Tangent plane only, sectors C^0: `p`, the tangent plane, `q_3^s`, `q_5^s` free (`3 + 2n`).
    C1C0,
}

/// A user-given quadratic expansion for one extraordinary vertex (from a q file).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct QSpec {
    /// The kind the coefficients must satisfy.
    pub kind: QKind,
    /// The central point, if given.
    pub p: Option<[f64; 3]>,
    /// Given coefficients `(sector, k, value)`, `k = 2..6`.
    pub q: Vec<(usize, usize, [f64; 3])>,
    /// The q file's line of each entry of `q` (1-based), for errors found against the net.
    pub q_lines: Vec<usize>,
    /// The q file this section comes from (empty when built in code).
    pub path: std::path::PathBuf,
    /// The line of the section's `vertex V` statement (1-based; 0 when built in code).
    pub line: usize,
}

impl QSpec {
    /// An error about this section found against the net: a parse error at `line` of the q file
    /// when the section came from one, otherwise an invalid argument.
    pub fn error(&self, line: usize, msg: String) -> Error {
        if self.path.as_os_str().is_empty() || line == 0 {
            Error::InvalidArgument(msg)
        } else {
            Error::Parse {
                path: self.path.clone(),
                line,
                msg,
            }
        }
    }
}

/// Typed parameters of a scheme. Each field applies to the schemes whose descriptor lists its
/// [`ParamKind`]; `None` / empty means the scheme's default.
#[derive(Debug, Clone, Default)]
pub struct Params {
    /// Valences without rules.
    pub fallback: Fallback,
    /// Guided: degree of the guide.
    pub guide: Option<GuideDegree>,
    /// Guided: the characteristic map (and so the contraction).
    pub chi: Option<ChiKind>,
    /// Adjustable TPS: the split ratio `e`.
    pub split_ratio: Option<f64>,
    /// Adjustable TPS: the alpha rule.
    pub alpha_rule: Option<AlphaRule>,
    /// Polar bi-2: poles given by the user (input face, position).
    pub poles: Vec<(usize, Point)>,
    /// QAS+: quadratic expansions given by the user, per input vertex.
    pub q_overrides: std::collections::BTreeMap<u32, QSpec>,
    /// EG, QAS+: printed or derived rules where both exist.
    pub rules: RulesChoice,
    /// Catmull-Clark, Loop: OpenSubdiv's options (boundary interpolation, crease method,
    /// triangle subdivision, face-varying interpolation); unset ones fall to the net's tags,
    /// then to the defaults.
    pub subd: crate::mesh::tags::SubdOptions,
    /// Every scheme: whether a net the scheme's rules do not take is prepared by the smallest
    /// documented step (`--prepare`, [`crate::schemes::prepare`]).
    pub prepare: PrepareMode,
}

/// A scheme with its parameters: what a front end passes down.
#[derive(Debug, Clone)]
pub struct Spec {
    /// The scheme.
    pub id: SchemeId,
    /// Its parameters.
    pub params: Params,
}

impl Spec {
    /// The scheme with default parameters.
    pub fn new(id: SchemeId) -> Spec {
        Spec {
            id,
            params: Params::default(),
        }
    }

    /// The canonical name.
    pub fn name(&self) -> &'static str {
        self.id.name()
    }
}
