//! `fairsub check`: continuity defects per kind of join and curvature per ring, of a BezierView
//! file or of a net's surface under a scheme.

use super::spec::{self, SchemeOptions};
use crate::analysis::{continuity, curvature, scaled};
use crate::error::{Error, Result};
use crate::schemes::Spec;
use crate::surface::PatchComplex;
use serde::Serialize;
use std::path::Path;

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
    /// EG and QAS+ only: the printed rules where they exist (default) or the derived ones.
    #[arg(long, value_enum)]
    pub rules: Option<spec::RulesArg>,
    /// With --scheme: prepare a net the scheme's rules do not take (auto, the default) or
    /// refuse it (none), as `subdivide --prepare`.
    #[arg(long, value_enum, default_value_t = spec::PrepareArg::Auto)]
    pub prepare: spec::PrepareArg,
    /// A mesh (a scan, another scheme's result; .obj, .off, .ply): report how far its
    /// vertices lie from the surface (max, mean, RMS, where the max is). Needs a net and a
    /// --scheme that evaluates (see `fairsub eval --help`).
    #[arg(long, requires = "scheme")]
    pub against: Option<String>,
}

/// The `check` report.
#[derive(Debug, Serialize)]
struct CheckReport {
    source: String,
    /// What a `.bv` file held, by kind (every kind is checked; polyhedron faces as flat
    /// patches whose joins are sharp).
    #[serde(skip_serializing_if = "Option::is_none")]
    kinds: Option<crate::io::BvCounts>,
    continuity: continuity::ContinuityReport,
    curvature: Vec<curvature::ElementCurvature>,
    /// C^1 up to a per-piece affine reparametrisation (bi-2 schemes, whose polar and
    /// adjustable rings shrink differently along and across their sides; `.bv` input).
    #[serde(skip_serializing_if = "Option::is_none")]
    c1_up_to_scaling: Option<scaled::ScaledContinuity>,
    /// The scheme's notes: elements that fell back, caps with derived or borrowed rules.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    notes: Vec<String>,
    /// `--against`: the mesh's vertices' distances from the surface.
    #[serde(skip_serializing_if = "Option::is_none")]
    deviation: Option<crate::surface::closest::Deviation>,
}

/// The report of `complex` (read from `source`, built by `spec` with `notes`, or a `.bv` file
/// without a spec).
fn build_report(
    source: &str,
    complex: &PatchComplex,
    spec: Option<&Spec>,
    notes: Vec<String>,
) -> CheckReport {
    // The bi-2 schemes (whose polar and adjustable rings shrink differently along and across
    // their sides) and .bv input get the certificate up to per-piece scaling.
    let scaled = match spec {
        None => true,
        Some(s) => crate::schemes::registry()
            .descriptor(s.id)
            .joins_up_to_scaling(),
    };
    CheckReport {
        source: source.to_string(),
        kinds: None,
        continuity: continuity::check(complex),
        curvature: curvature::ring_curvature(complex),
        c1_up_to_scaling: scaled.then(|| scaled::continuity_up_to_scaling(complex)),
        notes,
        deviation: None,
    }
}

/// `fairsub check --json`'s report of a complex built by `spec` (or read from a `.bv` file,
/// `None`), for front ends that hold the complex already.
pub fn report_json(
    source: &str,
    complex: &PatchComplex,
    spec: Option<&Spec>,
    notes: Vec<String>,
) -> String {
    let r = build_report(source, complex, spec, notes);
    serde_json::to_string_pretty(&r).expect("serialisable")
}

/// A patch complex a command reads: a net's surface under a scheme, or a `.bv` file's patches.
pub(super) struct LoadedComplex {
    pub complex: PatchComplex,
    /// The scheme's notes.
    pub notes: Vec<String>,
    /// The net (`None` for a `.bv` file).
    pub net: Option<crate::mesh::PolyMesh>,
    /// The scheme with the net's features (creases, corners) set.
    pub spec: Option<Spec>,
    /// The kinds of patches of a `.bv` file (`None` for a net).
    pub kinds: Option<crate::io::BvCounts>,
}

/// The complex of `input`: the surface of the net `input` under `spec` with `rings` (and the
/// fill), or the patches of the `.bv` file `input` without a spec: every kind it holds, its
/// polyhedra's faces as flat patches ([`crate::render::complex_from_bv_with`]).
pub(super) fn load_complex(
    input: &str,
    spec: Option<&Spec>,
    (rings, fill): (usize, bool),
) -> Result<LoadedComplex> {
    if let Some(s) = spec {
        let net = super::load_net(input)?.mesh;
        let mut s = s.clone();
        super::subdivide::features::patch_features(&mut s, &net, input)?;
        let (complex, notes) = super::subdivide::build_complex_noted(&s, &net, rings, fill)?;
        return Ok(LoadedComplex {
            complex,
            notes,
            net: Some(net),
            spec: Some(s),
            kinds: None,
        });
    }
    let path = Path::new(input);
    let is_bv = path
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("bv"));
    if !is_bv {
        return Err(Error::InvalidArgument(format!(
            "'{input}' is not a .bv file: give a BezierView file, or a net with --scheme"
        )));
    }
    let f = crate::io::read_bv(path)?;
    for w in &f.warnings {
        eprintln!("warning: {input}: {w}");
    }
    let n = f.counts();
    if n.tensor + n.rational + n.triangular + n.polyhedron_faces == 0 {
        return Err(Error::InvalidArgument(format!(
            "{input}: no patches or polyhedron faces to check"
        )));
    }
    Ok(LoadedComplex {
        complex: crate::render::complex_from_bv_with(&f, true),
        notes: Vec::new(),
        net: None,
        spec: None,
        kinds: Some(n),
    })
}

/// The deviation of the vertices of the mesh file `mesh` from the surface of `loaded`.
fn deviation_of(loaded: &LoadedComplex, mesh: &str) -> Result<crate::surface::closest::Deviation> {
    let (Some(net), Some(spec)) = (&loaded.net, &loaded.spec) else {
        return Err(Error::InvalidArgument(
            "--against needs a net and its --scheme (a .bv file has no input faces)".into(),
        ));
    };
    crate::surface::eval::supported(spec)?;
    let s = crate::surface::eval::Surface::of_scheme(spec, net, loaded.complex.clone())?;
    let other = super::load_net_as(mesh, true)?.mesh;
    crate::surface::closest::deviation(&s, other.positions())
}

/// The scheme of `--scheme` with `--rules`, if one is given (`--rules` alone is an error: a
/// `.bv` file holds its patches already).
pub(super) fn optional_spec(
    scheme: Option<&str>,
    rules: Option<spec::RulesArg>,
    prepare: spec::PrepareArg,
) -> Result<Option<Spec>> {
    match scheme {
        Some(s) => Ok(Some(spec::resolve(
            s,
            &SchemeOptions {
                rules: rules.map(Into::into),
                prepare: prepare.into(),
                ..SchemeOptions::default()
            },
        )?)),
        None if rules.is_some() => Err(Error::InvalidArgument(
            "--rules chooses the rules of a --scheme; a .bv file holds its patches already".into(),
        )),
        None => Ok(None),
    }
}

/// Runs `fairsub check`.
pub fn check(a: CheckArgs) -> Result<()> {
    let spec = optional_spec(a.scheme.as_deref(), a.rules, a.prepare)?;
    let loaded = load_complex(&a.input, spec.as_ref(), (a.rings, !a.no_fill))?;
    let deviation = match &a.against {
        Some(mesh) => Some(deviation_of(&loaded, mesh)?),
        None => None,
    };
    let mut r = build_report(&a.input, &loaded.complex, spec.as_ref(), loaded.notes);
    r.kinds = loaded.kinds;
    r.deviation = deviation;
    if a.json {
        super::say_json(&r);
        return Ok(());
    }
    say_joins(&r);
    say_extremes(&r.continuity);
    if let Some(sc) = &r.c1_up_to_scaling {
        say_scaled(sc);
    }
    if let (Some(d), Some(m)) = (&r.deviation, &a.against) {
        say_deviation(d, m);
    }
    say_curvature(&r.curvature);
    Ok(())
}

/// The text report's head: the counts, what a `.bv` file held, and the joins' defects by kind.
fn say_joins(r: &CheckReport) {
    let c = &r.continuity;
    say!(
        "{}: {} patches, {} shared pieces, {} open sides, size {:.4}",
        r.source,
        c.patches,
        c.all.pieces,
        c.open_sides,
        c.size
    );
    if let Some(n) = &r.kinds {
        say!(
            "  read: {} tensor-product, {} rational, {} triangular patches (as collapsed \
             tensor-product patches), {} polyhedra with {} faces (as flat patches, sharp joins)",
            n.tensor,
            n.rational,
            n.triangular,
            n.polyhedra,
            n.polyhedron_faces
        );
    }
    say!(
        "  {:<22} {:>7} {:>10} {:>10} {:>10} {:>10}",
        "join",
        "pieces",
        "C0",
        "C1",
        "C2",
        "G1 (rad)"
    );
    let sharp = (c.sharp.pieces > 0).then_some(("sharp (crease, C0)".to_string(), &c.sharp));
    for (k, d) in c.by_kind.iter().map(|(k, d)| (k.clone(), d)).chain(sharp) {
        say!(
            "  {:<22} {:>7} {:>10.2e} {:>10.2e} {:>10.2e} {:>10.2e}",
            k,
            d.pieces,
            d.c0,
            d.c1,
            d.c2,
            d.g1
        );
    }
}

/// The text report of the largest C0 gap and G1 defect and (up to 8 of) the open sides.
fn say_extremes(c: &continuity::ContinuityReport) {
    if let Some(l) = &c.all.c0_at {
        say!(
            "  largest C0 gap {:.3e} between patches {} and {} at {:?}",
            c.all.c0,
            l.patch_a,
            l.patch_b,
            l.point
        );
    }
    if let Some(l) = &c.all.g1_at {
        say!(
            "  largest G1 defect {:.3e} rad between patches {} and {} at {:?}; the normals' \
             rounding floor there (one unit in the last place of every coefficient) is {:.1e}; \
             the largest G1 defect above its place's floor is {:.1e}",
            c.all.g1,
            l.patch_a,
            l.patch_b,
            l.point,
            c.all.g1_rounding,
            c.all.g1_beyond_rounding
        );
    }
    for o in c.open.iter().take(8) {
        say!(
            "  open side {} of patch {} ({}) at {:?}",
            o.side,
            o.patch,
            o.provenance.group_name(),
            o.midpoint
        );
    }
    if c.open_sides > 8 {
        say!(
            "  ... {} open sides in all (the boundary of the surface, or cracks)",
            c.open_sides
        );
    }
}

/// The text report of C1 up to per-piece scaling, by kind of join.
fn say_scaled(sc: &scaled::ScaledContinuity) {
    say!("  C1 up to per-piece scaling (D_A + kappa D_B = 0 across each piece):");
    say!(
        "  {:<22} {:>7} {:>12} {:>10} {:>10} {:>10}",
        "join",
        "pieces",
        "C1 relative",
        "kappa min",
        "kappa max",
        "G1 (rad)"
    );
    for (k, d) in &sc.by_kind {
        say!(
            "  {:<22} {:>7} {:>12.2e} {:>10.4} {:>10.4} {:>10.2e}",
            k,
            d.pieces,
            d.c1_relative,
            d.kappa_min,
            d.kappa_max,
            d.g1
        );
    }
}

/// The text report of `--against`: the deviation of mesh `m`'s vertices from the surface.
fn say_deviation(d: &crate::surface::closest::Deviation, m: &str) {
    let c = &d.max_closest;
    say!(
        "  deviation of {m}'s {} vertices: max {:.6e}, mean {:.6e}, rms {:.6e}",
        d.points,
        d.max,
        d.mean,
        d.rms
    );
    say!(
        "    max at vertex {} {:?}, nearest surface point {:?} (face {} at ({}, {}))",
        d.max_index,
        d.max_point,
        c.point,
        c.face,
        c.u,
        c.v
    );
}

/// The text report of the curvature bounds, ring by ring, around each element.
fn say_curvature(elements: &[curvature::ElementCurvature]) {
    for e in elements {
        say!("  curvature around {:?}:", e.element);
        for ring in &e.rings {
            say!(
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
}
