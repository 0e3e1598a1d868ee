//! From command-line words to a scheme with typed parameters: the registry looks the name up,
//! and every scheme option given is checked against the [`ParamKind`]s the scheme's descriptor
//! takes, so an option for another scheme is an error naming the schemes it applies to.

use crate::error::{Error, Result};
use crate::geom::Point;
use crate::schemes::descriptor::{AlphaRule, ChiKind, Fallback, ParamKind, RulesChoice};
use crate::schemes::prepare::Mode;
use crate::schemes::{Spec, registry};
use std::path::Path;

/// The scheme options of a command line, before they are checked against the scheme.
#[derive(Debug, Default, Clone, Copy)]
pub struct SchemeOptions<'a> {
    /// `--lambda`.
    pub lambda: Option<f64>,
    /// `--fallback`.
    pub fallback: Option<Fallback>,
    /// `--split-ratio`.
    pub split_ratio: Option<f64>,
    /// `--alpha-rule`.
    pub alpha_rule: Option<AlphaRule>,
    /// `--pole` values.
    pub poles: &'a [String],
    /// `--q-file`.
    pub q_file: Option<&'a Path>,
    /// Whether `--fcv-scale` or `--fcv-file` was given.
    pub fcv: bool,
    /// `--rules`.
    pub rules: Option<RulesChoice>,
    /// `--boundary`, `--crease-method`, `--smooth-triangles`, `--fvar`.
    pub subd: crate::mesh::tags::SubdOptions,
    /// Whether `--creases` was given.
    pub creases: bool,
    /// `--prepare` (every scheme).
    pub prepare: Mode,
}

/// The names of the schemes that take `kind`, in catalogue order.
fn takers(kind: ParamKind) -> Vec<&'static str> {
    registry()
        .entries()
        .iter()
        .filter(|e| e.descriptor.params().contains(&kind))
        .map(|e| e.name)
        .collect()
}

/// `a, b and c`.
fn and_list(names: &[&str]) -> String {
    match names {
        [] => String::new(),
        [one] => one.to_string(),
        [rest @ .., last] => format!("{} and {last}", rest.join(", ")),
    }
}

/// Whether the scheme takes `kind`.
fn takes(spec: &Spec, kind: ParamKind) -> bool {
    registry().descriptor(spec.id).params().contains(&kind)
}

/// The scheme `name` with the options `o`. Errors: an unknown name ([`Error::UnknownScheme`]),
/// an option the scheme does not take, a value out of range, an unreadable q file.
pub fn resolve(name: &str, o: &SchemeOptions<'_>) -> Result<Spec> {
    let mut spec = registry().lookup(name)?;
    if let Some(l) = o.lambda {
        set_contraction(&mut spec, name, l)?;
    }
    if o.split_ratio.is_some() || o.alpha_rule.is_some() {
        if !takes(&spec, ParamKind::SplitRatio) {
            return Err(Error::InvalidArgument(format!(
                "--split-ratio and --alpha-rule apply to {}, not to '{name}'",
                and_list(&takers(ParamKind::SplitRatio))
            )));
        }
        spec.params.split_ratio = o.split_ratio;
        spec.params.alpha_rule = o.alpha_rule;
        // The range of e is checked here, before any net is read.
        crate::schemes::bi2::descriptor::Bi2Descriptor::ternary_rules(&spec)?;
    }
    if !o.poles.is_empty() {
        if !takes(&spec, ParamKind::Poles) {
            return Err(Error::InvalidArgument(format!(
                "--pole applies to {}, not to '{name}'",
                and_list(&takers(ParamKind::Poles))
            )));
        }
        spec.params.poles = o
            .poles
            .iter()
            .map(|s| parse_pole(s))
            .collect::<Result<_>>()?;
    }
    if o.fcv && !takes(&spec, ParamKind::Fcv) {
        return Err(Error::InvalidArgument(format!(
            "--fcv-scale and --fcv-file set face control vertices, which only the non-box \
             schemes ({}) have, not '{name}'",
            takers(ParamKind::Fcv).join(", ")
        )));
    }
    if let Some(path) = o.q_file {
        if !takes(&spec, ParamKind::QFile) {
            return Err(Error::InvalidArgument(format!(
                "--q-file applies to {}, not to '{name}'",
                and_list(&takers(ParamKind::QFile))
            )));
        }
        let text = crate::io::read_text(path)?;
        spec.params.q_overrides = crate::schemes::qas::parse_q_file(&text, path)?;
    }
    if let Some(r) = o.rules {
        if !takes(&spec, ParamKind::Rules) {
            return Err(Error::InvalidArgument(format!(
                "--rules chooses between printed and derived rules, which only {} have, not '{name}'",
                and_list(&takers(ParamKind::Rules))
            )));
        }
        spec.params.rules = r;
    }
    let s = o.subd;
    check_sharp_features(&spec, name, o)?;
    spec.params.subd = s;
    if let Some(f) = o.fallback {
        spec.params.fallback = f;
    }
    spec.params.prepare = o.prepare;
    Ok(spec)
}

/// `--lambda l` on the scheme `name`: only the guided schemes take a contraction, and they
/// offer 0.5 (or, without the option, Catmull-Clark's lambda).
fn set_contraction(spec: &mut Spec, name: &str, l: f64) -> Result<()> {
    if !takes(spec, ParamKind::Contraction) {
        return Err(Error::InvalidArgument(format!(
            "--lambda {l}: only the guided schemes ({}) take a contraction; '{name}' has its own",
            takers(ParamKind::Contraction).join(", ")
        )));
    }
    if (l - 0.5).abs() > 1e-12 {
        return Err(Error::InvalidArgument(format!(
            "--lambda {l}: guided subdivision offers lambda = 0.5 (QAS+'s characteristic map, valences 5..10) or, without --lambda, Catmull-Clark's lambda"
        )));
    }
    spec.params.chi = Some(ChiKind::Half);
    Ok(())
}

/// Checks OpenSubdiv's sharp features and options (`--boundary`, `--crease-method`, `--fvar`,
/// `--creases`, `--smooth-triangles`) against the scheme `name`: the dual schemes' boundary
/// modes and the schemes with a crease construction of their own take some of them on the net.
fn check_sharp_features(spec: &Spec, name: &str, o: &SchemeOptions<'_>) -> Result<()> {
    let s = o.subd;
    let boundary_only = s.crease_method.is_none() && s.fvar.is_none() && !o.creases;
    let crease_only =
        s.fvar.is_none() && (s.boundary.is_none() || takes(spec, ParamKind::BoundaryMode));
    if s.boundary.is_some() && boundary_only && takes(spec, ParamKind::BoundaryMode) {
        // the dual schemes' boundary modes: the front end puts the option on the net
    } else if crease_only && takes(spec, ParamKind::Creases) {
        // crease tags and the crease method of the schemes with a crease construction of
        // their own: the front end puts them on the net
    } else if (s.boundary.is_some() || s.crease_method.is_some() || s.fvar.is_some() || o.creases)
        && !takes(spec, ParamKind::SharpFeatures)
    {
        return Err(Error::InvalidArgument(format!(
            "{} set OpenSubdiv's sharp features and options, which {} take, not '{name}'",
            ParamKind::SharpFeatures.option(),
            and_list(&takers(ParamKind::SharpFeatures))
        )));
    }
    if s.triangles.is_some() && !takes(spec, ParamKind::SmoothTriangles) {
        return Err(Error::InvalidArgument(format!(
            "--smooth-triangles is OpenSubdiv's Catmark option, which {} take{}, not '{name}'",
            and_list(&takers(ParamKind::SmoothTriangles)),
            if takers(ParamKind::SmoothTriangles).len() == 1 {
                "s"
            } else {
                ""
            }
        )));
    }
    Ok(())
}

/// The name a report shows for `spec` given as `name`: with `--lambda 0.5` a guided scheme is
/// shown with the `-half` suffix, with `--rules derived` an EG or QAS+ scheme with the
/// `-derived` suffix, each naming the same scheme.
pub fn label(name: &str, spec: &Spec) -> String {
    let mut out = name.to_string();
    if spec.params.chi == Some(ChiKind::Half) && !out.ends_with("-half") {
        out.push_str("-half");
    }
    if spec.params.rules == RulesChoice::Derived && !out.ends_with("-derived") {
        out.push_str("-derived");
    }
    out
}

/// `--rules` values.
#[derive(Debug, Clone, Copy, clap::ValueEnum)]
pub enum RulesArg {
    /// The paper's printed rules where they exist (EG: 3, 5; QAS+: 5, 6, 7), derived elsewhere.
    Printed,
    /// fairsub's derived rules wherever they exist (EG and QAS+: 3..16; QAS+ uses EG's at 3).
    Derived,
}

impl From<RulesArg> for RulesChoice {
    fn from(r: RulesArg) -> Self {
        match r {
            RulesArg::Printed => RulesChoice::Printed,
            RulesArg::Derived => RulesChoice::Derived,
        }
    }
}

impl From<RulesChoice> for RulesArg {
    fn from(r: RulesChoice) -> Self {
        match r {
            RulesChoice::Printed => RulesArg::Printed,
            RulesChoice::Derived => RulesArg::Derived,
        }
    }
}

/// `--prepare` values.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum PrepareArg {
    /// Apply the smallest documented step a scheme's rules need (one Catmull-Clark step for
    /// TPS on a net with triangles, ...; named in a note).
    #[default]
    Auto,
    /// Apply nothing: a scheme refuses a net its rules do not take, naming the element.
    None,
}

impl From<PrepareArg> for Mode {
    fn from(p: PrepareArg) -> Self {
        match p {
            PrepareArg::Auto => Mode::Auto,
            PrepareArg::None => Mode::None,
        }
    }
}

impl From<Mode> for PrepareArg {
    fn from(p: Mode) -> Self {
        match p {
            Mode::Auto => PrepareArg::Auto,
            Mode::None => PrepareArg::None,
        }
    }
}

/// Parses `FACE:X,Y,Z`.
fn parse_pole(s: &str) -> Result<(usize, Point)> {
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
