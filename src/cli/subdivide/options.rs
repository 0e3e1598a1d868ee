//! The scheme options of `fairsub subdivide`, one clap definition that `fairsub view` flattens
//! too: contraction, face control vertices, fallback, q file, split ratio, alpha rule, poles
//! and rules. [`SchemeArgs::words`] gives them back as the command's words, for front ends that
//! pass words on (the viewer's start URL, which `cli::api` parses again with this definition).

use super::nonbox::FcvArgs;
use crate::schemes::descriptor::{AlphaRule, Fallback};
use std::path::PathBuf;

/// The scheme options of `subdivide` and `view`.
#[derive(Debug, Clone, clap::Args)]
pub struct SchemeArgs {
    /// Contraction of a guided scheme: 0.5 samples through QAS+'s characteristic map (valences
    /// 5..10); without it, Catmull-Clark's chi and lambda.
    #[arg(long)]
    pub lambda: Option<f64>,
    /// Face control vertices (non-box schemes).
    #[command(flatten)]
    pub fcv: FcvArgs,
    /// At vertices whose valence no rules cover (EG, QAS+: above 16): use Catmull-Clark there,
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
    /// EG and QAS+ only: the paper's printed rules where they exist (default; derived rules at
    /// the other valences), or fairsub's derived rules everywhere (to compare).
    #[arg(long, value_enum)]
    pub rules: Option<super::spec::RulesArg>,
    /// Every scheme: prepare a net the scheme's rules do not take by the smallest documented
    /// step (auto: one Catmull-Clark step for TPS on triangles and n-gons, one step of the
    /// scheme itself for the dual schemes at interior vertices of valence 2, ...; each named
    /// in a note, see the user guide's preparation page), or refuse it naming the element
    /// (none). `--levels` refines, and `--rings` builds on, the prepared net.
    #[arg(long, value_enum, default_value_t = super::spec::PrepareArg::Auto)]
    pub prepare: super::spec::PrepareArg,
}

/// The name of a value of a clap value enum, as the command line spells it.
fn value_name(v: &impl clap::ValueEnum) -> String {
    v.to_possible_value()
        .expect("no skipped values")
        .get_name()
        .to_string()
}

impl SchemeArgs {
    /// The options given, as the command line's words (`--split-ratio 0.3`, `--pole F:X,Y,Z`
    /// once per pole; the default fallback is left out), parsed back into the same options.
    pub fn words(&self) -> Vec<String> {
        let mut w: Vec<(&str, String)> = Vec::new();
        if let Some(l) = self.lambda {
            w.push(("lambda", l.to_string()));
        }
        if let Some(s) = self.fcv.fcv_scale {
            w.push(("fcv-scale", s.to_string()));
        }
        if let Some(f) = &self.fcv.fcv_file {
            w.push(("fcv-file", f.display().to_string()));
        }
        if !matches!(self.fallback, FallbackArg::CatmullClark) {
            w.push(("fallback", value_name(&self.fallback)));
        }
        if let Some(f) = &self.q_file {
            w.push(("q-file", f.display().to_string()));
        }
        if let Some(e) = self.split_ratio {
            w.push(("split-ratio", e.to_string()));
        }
        if let Some(a) = &self.alpha_rule {
            w.push(("alpha-rule", value_name(a)));
        }
        for p in &self.pole {
            w.push(("pole", p.clone()));
        }
        if let Some(r) = &self.rules {
            w.push(("rules", value_name(r)));
        }
        if self.prepare != super::spec::PrepareArg::Auto {
            w.push(("prepare", value_name(&self.prepare)));
        }
        w.into_iter()
            .flat_map(|(k, v)| [format!("--{k}"), v])
            .collect()
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

impl From<FallbackArg> for Fallback {
    fn from(f: FallbackArg) -> Self {
        match f {
            FallbackArg::CatmullClark => Fallback::CatmullClark,
            FallbackArg::Error => Fallback::Error,
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

impl From<Fallback> for FallbackArg {
    fn from(f: Fallback) -> Self {
        match f {
            Fallback::CatmullClark => FallbackArg::CatmullClark,
            Fallback::Error => FallbackArg::Error,
        }
    }
}

impl AlphaRuleArg {
    /// The option value of a rule, `None` for TPS's published alphas (the `tps` scheme's own,
    /// not an option of tps-adjustable).
    pub fn of(a: AlphaRule) -> Option<Self> {
        match a {
            AlphaRule::Published => None,
            AlphaRule::TpsLimitPoint => Some(AlphaRuleArg::TpsLimitPoint),
            AlphaRule::RegularSpectrum => Some(AlphaRuleArg::RegularSpectrum),
        }
    }
}

impl From<AlphaRuleArg> for AlphaRule {
    fn from(a: AlphaRuleArg) -> Self {
        match a {
            AlphaRuleArg::TpsLimitPoint => AlphaRule::TpsLimitPoint,
            AlphaRuleArg::RegularSpectrum => AlphaRule::RegularSpectrum,
        }
    }
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::super::super::{Cli, Command};
    use clap::Parser;

    /// The options of `subdivide NET --scheme S WORDS -o x.obj`.
    fn parse(words: &[&str]) -> super::SchemeArgs {
        let all = [
            "fairsub",
            "subdivide",
            "net.obj",
            "--scheme",
            "s",
            "-o",
            "x.obj",
        ];
        let cli = Cli::try_parse_from(all.iter().chain(words)).unwrap();
        match cli.command {
            Command::Subdivide(a) => a.options,
            _ => unreachable!(),
        }
    }

    #[crate::unit::test]
    fn words_parse_back_into_the_same_options() {
        let given = [
            "--lambda",
            "0.5",
            "--fcv-scale",
            "1.5",
            "--fcv-file",
            "f.txt",
            "--fallback",
            "error",
            "--q-file",
            "q.txt",
            "--split-ratio",
            "0.3",
            "--alpha-rule",
            "regular-spectrum",
            "--pole",
            "0:1,2,3",
            "--pole",
            "4:0,0,1",
            "--rules",
            "derived",
        ];
        let words = parse(&given).words();
        assert_eq!(words, given);
        let back: Vec<&str> = words.iter().map(String::as_str).collect();
        assert_eq!(parse(&back).words(), words);
        assert!(parse(&[]).words().is_empty(), "defaults give no words");
    }
}
