//! `fairsub measure`: area, enclosed volume, centroids and inertia tensors of a net's exact
//! surface or of a `.bv` file's patches, integrated exactly from the Bezier patches
//! ([`crate::analysis::moments`]).

use super::check::{load_complex, optional_spec};
use super::spec;
use crate::analysis::moments::{self, FaceAreas, MeasureOptions, Measurement};
use crate::error::{Error, Result};
use serde::Serialize;

/// Arguments of `fairsub measure`.
#[derive(Debug, clap::Args)]
pub struct MeasureArgs {
    /// A control net (file or gallery:NAME) with --scheme, or a BezierView file (.bv).
    pub input: String,
    /// Build the surface of a net with this scheme.
    #[arg(long, short)]
    pub scheme: Option<String>,
    /// Rings around extraordinary elements (the complex `subdivide --rings K` writes).
    #[arg(long, short, default_value_t = 6)]
    pub rings: usize,
    /// Leave the hole inside the last ring open (the surface is then open: no volume).
    #[arg(long)]
    pub no_fill: bool,
    /// Print the report as JSON.
    #[arg(long)]
    pub json: bool,
    /// With --json: the area over each input face (needs a scheme that evaluates, see
    /// `fairsub eval --help`).
    #[arg(long, requires = "json")]
    pub per_face: bool,
    /// Relative tolerance of the area integrals (the polynomial moments are exact).
    #[arg(long, default_value_t = moments::AREA_TOLERANCE)]
    pub tolerance: f64,
    /// EG and QAS+ only: the printed rules where they exist (default) or the derived ones.
    #[arg(long, value_enum)]
    pub rules: Option<spec::RulesArg>,
}

/// The JSON report.
#[derive(Serialize)]
struct Report<'a> {
    source: &'a str,
    #[serde(flatten)]
    measurement: &'a Measurement,
    #[serde(skip_serializing_if = "Option::is_none")]
    faces: Option<FaceAreas>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    notes: Vec<String>,
}

/// Runs `fairsub measure`.
pub fn run(a: MeasureArgs) -> Result<()> {
    if !(a.tolerance > 0.0 && a.tolerance < 1.0) {
        return Err(Error::InvalidArgument(format!(
            "--tolerance {} must lie between 0 and 1 (relative)",
            a.tolerance
        )));
    }
    let spec = optional_spec(a.scheme.as_deref(), a.rules, spec::PrepareArg::Auto)?;
    let loaded = load_complex(&a.input, spec.as_ref(), (a.rings, !a.no_fill))?;
    let opts = MeasureOptions {
        area_tolerance: a.tolerance,
    };
    for n in &loaded.notes {
        eprintln!("note: {n}");
    }
    if a.json {
        let per = if a.per_face {
            match (&loaded.spec, &loaded.net) {
                (Some(s), Some(n)) => Some((s, n)),
                _ => {
                    return Err(Error::InvalidArgument(
                        "--per-face needs a net and its --scheme (a .bv file's patches carry \
                         no input faces)"
                            .into(),
                    ));
                }
            }
        } else {
            None
        };
        let text = json_report(&a.input, &loaded.complex, per, opts, loaded.notes)?;
        say!("{text}");
        return Ok(());
    }
    let m = moments::measure(&loaded.complex, &opts);
    print_text(&a.input, &m);
    Ok(())
}

/// `fairsub measure --json`'s report of `complex` (from `source`), with the area per input
/// face of the net under the scheme `per_face` gives.
///
/// # Errors
/// `per_face` with a scheme that does not evaluate.
pub(super) fn json_report(
    source: &str,
    complex: &crate::surface::PatchComplex,
    per_face: Option<(&crate::schemes::Spec, &crate::mesh::PolyMesh)>,
    opts: MeasureOptions,
    notes: Vec<String>,
) -> Result<String> {
    let faces = match per_face {
        Some((spec, net)) => Some(face_areas(complex, spec, net, opts.area_tolerance)?),
        None => None,
    };
    let m = moments::measure(complex, &opts);
    let r = Report {
        source,
        measurement: &m,
        faces,
        notes,
    };
    Ok(serde_json::to_string_pretty(&r).expect("serialisable"))
}

/// The area per input face of a net's surface.
fn face_areas(
    complex: &crate::surface::PatchComplex,
    spec: &crate::schemes::Spec,
    net: &crate::mesh::PolyMesh,
    tol: f64,
) -> Result<FaceAreas> {
    crate::surface::eval::supported(spec).map_err(|e| {
        Error::InvalidArgument(format!("--per-face needs the input faces' domains: {e}"))
    })?;
    let d = crate::schemes::registry().descriptor(spec.id);
    match d.eval_faces(spec, net)? {
        // fan triangles of the polygons the surface is built on (nonbox-4dir's triangles)
        Some(fans) => moments::fan_face_areas(complex, &fans, tol)
            .map_err(|e| Error::InvalidArgument(format!("--per-face: {e}"))),
        None => Ok(moments::face_areas(complex, net.num_faces(), tol)),
    }
}

fn matrix_lines(name: &str, m: &[[f64; 3]; 3]) {
    say!("  {name}");
    for row in m {
        say!("    {:+.15e} {:+.15e} {:+.15e}", row[0], row[1], row[2]);
    }
}

fn print_text(source: &str, m: &Measurement) {
    let rules: Vec<String> = m
        .rules
        .iter()
        .map(|r| format!("{}x{} ({}x{} points)", r[0], r[1], r[2], r[3]))
        .collect();
    say!(
        "{source}: {} patches of bi-degree {}",
        m.patches,
        rules.join(", ")
    );
    if m.rational > 0 {
        say!(
            "  {} rational patches: their volume moments integrated to the area's tolerance, \
             not exactly",
            m.rational
        );
    }
    if m.closed {
        say!(
            "  closed surface (closure |int n dA| / area = {:.2e})",
            m.closure
        );
    } else {
        say!(
            "  open surface: {} open sides, {} joins of opposite orientation; no volume \
             (closure {:.2e})",
            m.open_sides,
            m.orientation_conflicts,
            m.closure
        );
    }
    say!(
        "  area             {:.17e} (estimated quadrature error {:.1e})",
        m.area,
        m.area_error
    );
    let [x, y, z] = m.area_centroid;
    say!("  area centroid    {x:+.17e} {y:+.17e} {z:+.17e}");
    if let Some(v) = &m.volume {
        say!(
            "  volume           {:.17e} ({} normals)",
            v.volume,
            if v.outward { "outward" } else { "inward" }
        );
        let [x, y, z] = v.centroid;
        say!("  centroid         {x:+.17e} {y:+.17e} {z:+.17e}");
        matrix_lines("inertia about the centroid (unit density):", &v.inertia);
        let [a, b, c] = v.principal_moments;
        say!("  principal moments {a:.15e} {b:.15e} {c:.15e}");
    }
    matrix_lines(
        "shell inertia about the area centroid (unit area density):",
        &m.area_inertia,
    );
}
