//! `fairsub render` and `fairsub compare`: shape-interrogation pictures as PNG files.
//!
//! `render` draws one surface (a scheme's patch complex, a refined or plain mesh, or the
//! patches of a `.bv` file) in one mode; `compare` draws a labelled grid of schemes x modes with
//! one camera, one light set and one curvature range per mode. Both can print the numbers
//! behind the picture as JSON (camera, range used, per-ring curvature ranges).

use super::spec::{self, SchemeOptions};
use crate::error::{Error, Result};
use crate::io::{BvCounts, BvFile};
use crate::mesh::PolyMesh;
use crate::render::{
    self, Mode, Overlays, RenderOptions, Scene, ShadeOptions, View, camera, stats,
};
use crate::schemes::Spec;
use crate::schemes::options::ids;
use serde::Serialize;
use std::path::{Path, PathBuf};

/// A default of the library's [`RenderOptions::default`], for clap's `default_value_t`: the
/// command's defaults are the library's, written once.
fn default<T>(f: impl FnOnce(&RenderOptions) -> T) -> T {
    f(&RenderOptions::default())
}

/// Camera, lights, stripes and range: the options `render` and `compare` share, parsed into
/// the library's [`RenderOptions`] ([`LookArgs::options`]) whose defaults and checks they use.
#[derive(Debug, clap::Args)]
pub struct LookArgs {
    /// Image size WIDTHxHEIGHT in pixels (per cell for compare) [default: 800x800 for
    /// render, 400x400 for compare].
    #[arg(long)]
    pub size: Option<String>,
    /// Supersampling: AA x AA samples per pixel (1 = none).
    #[arg(long, default_value_t = default(|d| d.supersample))]
    pub aa: usize,
    /// Eye angle around the z axis, degrees from +x (-90 puts +x to the right).
    #[arg(long, default_value_t = default(|d| d.view.azimuth_deg), allow_negative_numbers = true)]
    pub azimuth: f64,
    /// Eye angle above the xy plane, degrees (90 looks straight down).
    #[arg(long, default_value_t = default(|d| d.view.elevation_deg), allow_negative_numbers = true)]
    pub elevation: f64,
    /// Eye distance from the centre in model units [default: fit the view].
    #[arg(long)]
    pub distance: Option<f64>,
    /// Vertical field of view in degrees.
    #[arg(long, default_value_t = default(|d| d.view.fov_deg))]
    pub fov: f64,
    /// Centre on the limit point of this input vertex (V, vertex:V or face:F).
    #[arg(long, value_name = "V")]
    pub focus: Option<String>,
    /// Frame rings K..L (1 = outermost) of the focused (or only) extraordinary element; the cap
    /// counts as the ring after the last.
    #[arg(long, value_name = "K..L")]
    pub zoom_rings: Option<String>,
    /// Fixed symmetric curvature range [-R, R] [default: automatic, the 98th percentile of
    /// |value| over the visible surface].
    #[arg(long, value_name = "R")]
    pub range: Option<f64>,
    /// Overlays: net (control net), patches (patch boundaries); repeat or comma-separate.
    #[arg(long, value_delimiter = ',')]
    pub overlay: Vec<String>,
    /// Stripe periods across the visible surface (highlight, reflection lines, isophotes).
    #[arg(long, default_value_t = default(|d| d.shade.stripes))]
    pub stripes: f64,
    /// Dark fraction of each stripe period, in (0, 1).
    #[arg(long, default_value_t = default(|d| d.shade.stripe_width))]
    pub stripe_width: f64,
    /// Direction of the light lines in the image, degrees from horizontal.
    #[arg(long, default_value_t = default(|d| d.shade.light_angle_deg), allow_negative_numbers = true)]
    pub light_angle: f64,
    /// No legend strip under curvature pictures.
    #[arg(long)]
    pub no_legend: bool,
}

impl LookArgs {
    /// The typed options these arguments give for `mode`, with `default_size` when `--size` is
    /// not given; checked by [`RenderOptions::validate`] (the error names the option).
    pub(crate) fn options(
        &self,
        default_size: (usize, usize),
        mode: Mode,
    ) -> Result<RenderOptions> {
        let (width, height) = match &self.size {
            Some(s) => render::parse_size(s)?,
            None => default_size,
        };
        let opts = RenderOptions {
            width,
            height,
            supersample: self.aa,
            mode,
            view: View {
                azimuth_deg: self.azimuth,
                elevation_deg: self.elevation,
                distance: self.distance,
                fov_deg: self.fov,
                focus: self
                    .focus
                    .as_deref()
                    .map(camera::parse_element)
                    .transpose()?,
                zoom_rings: self
                    .zoom_rings
                    .as_deref()
                    .map(camera::parse_rings)
                    .transpose()?,
            },
            shade: ShadeOptions {
                stripes: self.stripes,
                stripe_width: self.stripe_width,
                light_angle_deg: self.light_angle,
                range: self.range,
                ..ShadeOptions::default()
            },
            overlays: Overlays::parse(&self.overlay)?,
            legend: !self.no_legend,
        };
        opts.validate()?;
        Ok(opts)
    }
}

/// The help after `fairsub render --help`.
fn render_help() -> String {
    let cat = ids::CATMULL_CLARK;
    format!(
        "\
NET is a mesh file (.obj .off .ply), gallery:NAME, or a BezierView .bv file of patches (groups
named regular, ringK and cap give the provenance). With --scheme the net's exact patch complex is
drawn (--rings, default 6); with --scheme and --levels its refined net; without --scheme the net
itself. Curvature and provenance modes need patches.

Examples:
  fairsub render gallery:cnet-5-convex --scheme {cat} --mode highlight -o hl.png
  fairsub render net.obj -s {cat} -r 10 -m mean --zoom-rings 6..11 --json -o h.png
  fairsub render surface.bv --mode provenance --overlay patches -o rings.png"
    )
}

/// The help after `fairsub compare --help`.
fn compare_help() -> String {
    let cat = ids::CATMULL_CLARK;
    format!(
        "\
Rows are schemes, columns are modes. All cells share one camera (fitted to all surfaces), one
light set and, per mode, one curvature range or stripe period, so the schemes are compared
fairly.

Example:
  fairsub compare gallery:cnet-6-saddle --schemes {cat} --modes highlight,mean,provenance \\
      --zoom-rings 1..7 --size 320x320 -o panel.png"
    )
}

/// Arguments of `fairsub render`.
#[derive(Debug, clap::Args)]
#[command(after_help = render_help())]
pub struct RenderArgs {
    /// The control net (file or gallery:NAME) or a .bv file of patches.
    pub net: String,
    /// Scheme whose surface is drawn (see `fairsub schemes`); none: the net itself.
    #[arg(long, short)]
    pub scheme: Option<String>,
    /// Contraction of a guided scheme (0.5; default Catmull-Clark's lambda).
    #[arg(long)]
    pub lambda: Option<f64>,
    /// Rings per extraordinary element of the patch complex [default: 6].
    #[arg(long, short)]
    pub rings: Option<usize>,
    /// Leave the hole inside the last ring open.
    #[arg(long)]
    pub no_fill: bool,
    /// Draw the net refined this many times instead of the patches (interpolated normals).
    #[arg(long, short)]
    pub levels: Option<usize>,
    /// shaded, highlight, reflection, isophote, gauss, mean or provenance.
    #[arg(long, short, default_value = default(|d| d.mode.name()))]
    pub mode: String,
    #[command(flatten)]
    pub look: LookArgs,
    /// Print camera, range used and per-ring curvature ranges as JSON on stdout.
    #[arg(long)]
    pub json: bool,
    /// EG and QAS+ only: the printed rules where they exist (default) or the derived ones.
    #[arg(long, value_enum)]
    pub rules: Option<spec::RulesArg>,
    /// Output PNG file.
    #[arg(long, short)]
    pub output: PathBuf,
}

/// Arguments of `fairsub compare`.
#[derive(Debug, clap::Args)]
#[command(after_help = compare_help())]
pub struct CompareArgs {
    /// The control net (file or gallery:NAME).
    pub net: String,
    /// Schemes, comma-separated [default: all with patch output that take the net]. A scheme
    /// without exact patches is drawn as its net refined 4 times (no curvature or provenance
    /// modes).
    #[arg(long, value_delimiter = ',')]
    pub schemes: Vec<String>,
    /// Contraction of the guided schemes among them (0.5; default Catmull-Clark's lambda).
    #[arg(long)]
    pub lambda: Option<f64>,
    /// Modes, comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "highlight,mean")]
    pub modes: Vec<String>,
    /// Rings per extraordinary element.
    #[arg(long, short, default_value_t = 6)]
    pub rings: usize,
    /// Leave the hole inside the last ring open.
    #[arg(long)]
    pub no_fill: bool,
    #[command(flatten)]
    pub look: LookArgs,
    /// Print camera, ranges used and per-scheme per-ring curvature ranges as JSON on stdout.
    #[arg(long)]
    pub json: bool,
    /// The EG and QAS+ schemes among them: printed rules where they exist (default) or derived
    /// ones (a single scheme also by its `-derived` suffix, e.g. `eg,eg-derived`).
    #[arg(long, value_enum)]
    pub rules: Option<spec::RulesArg>,
    /// Output PNG file.
    #[arg(long, short)]
    pub output: PathBuf,
}

/// Samples per patch edge for the per-ring curvature numbers.
pub(super) const GROUP_SAMPLES: usize = 8;

pub(super) fn is_bv(path: &str) -> bool {
    Path::new(path)
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("bv"))
}

/// A `.bv` file's patches of every kind, as BezierView draws them: tensor-product, rational and
/// triangular patches and the faces of its polyhedra (flat), with provenance from the group
/// names, and its first polyhedron, if any, as the net of the overlays. Also what it held, by
/// kind.
pub(super) fn bv_complex(
    path: &str,
) -> Result<(crate::surface::PatchComplex, Option<PolyMesh>, BvCounts)> {
    let file: BvFile = crate::io::read_bv(Path::new(path))?;
    for w in &file.warnings {
        eprintln!("warning: {path}: {w}");
    }
    let n = file.counts();
    if n.tensor + n.rational + n.triangular + n.polyhedron_faces == 0 {
        return Err(Error::InvalidArgument(format!(
            "{path}: no patches or polyhedron faces to draw"
        )));
    }
    let poly = file.polyhedra.first().and_then(|p| {
        PolyMesh::new(p.positions.clone(), &p.faces)
            .map_err(|e| eprintln!("warning: {path}: polyhedron not usable as a net: {e}"))
            .ok()
    });
    Ok((render::complex_from_bv_with(&file, true), poly, n))
}

/// A `.bv` file as a scene ([`bv_complex`]); a file of one polyhedron only: the polyhedron as
/// a mesh.
pub(super) fn bv_scene(path: &str) -> Result<Scene> {
    let (c, poly, n) = bv_complex(path)?;
    Ok(match poly {
        Some(m) if n.polyhedra == 1 && n.tensor + n.rational + n.triangular == 0 => Scene::mesh(&m),
        poly => Scene::patches(c, poly),
    })
}

/// The patch complex of a scheme as a scene with its net.
pub(super) fn complex_scene(
    scheme: &Spec,
    net: &PolyMesh,
    rings: usize,
    fill: bool,
) -> Result<Scene> {
    let c = super::subdivide::build_complex(scheme, net, rings, fill)?;
    if c.is_empty() {
        return Err(Error::InvalidArgument(format!(
            "scheme '{}' produced no patches for this net",
            scheme.name()
        )));
    }
    Ok(Scene::patches(c, Some(net.clone())))
}

#[derive(Serialize)]
pub(super) struct RangeReport {
    pub(super) mode: Mode,
    pub(super) value: f64,
    pub(super) automatic: bool,
}

#[derive(Serialize)]
struct RenderReport<'a> {
    input: &'a str,
    scheme: Option<&'a str>,
    rings: Option<usize>,
    mode: Mode,
    output: String,
    width: usize,
    height: usize,
    supersample: usize,
    camera: &'a render::Camera,
    region: &'a render::Region,
    range: Option<RangeReport>,
    stripe_period: Option<f64>,
    frame: &'a render::FrameStats,
    groups: Vec<stats::GroupCurvature>,
}

/// Runs `fairsub render`.
pub fn run_render(mut a: RenderArgs) -> Result<()> {
    let spec = render_spec(&mut a)?;
    let mode: Mode = a.mode.parse()?;
    let opts = a.look.options(default(|d| (d.width, d.height)), mode)?;
    let bv = is_bv(&a.net);
    check_render_sources(&a, bv)?;
    super::limits::check_render(opts.width, opts.height, opts.supersample, 1)?;
    let (scene, rings) = render_scene(&a, spec.as_ref(), bv)?;
    let out = render::render(&scene, &opts)?;
    out.image.write_png(&a.output)?;
    if a.json {
        let report = RenderReport {
            input: &a.net,
            scheme: a.scheme.as_deref(),
            rings,
            mode,
            output: a.output.display().to_string(),
            width: out.image.width,
            height: out.image.height,
            supersample: opts.supersample,
            camera: &out.camera,
            region: &out.region,
            range: out.range.map(|value| RangeReport {
                mode,
                value,
                automatic: opts.shade.range.is_none(),
            }),
            stripe_period: out.stripe_period,
            frame: &out.stats,
            groups: group_curvature(&scene),
        };
        super::say_json(&report);
    }
    let range = out
        .range
        .map(|r| format!(", range +-{}", render::text::format_number(r)));
    let detail = format!(", {}{}", mode.name(), range.unwrap_or_default());
    say_wrote(&a.output, &out.image, &detail);
    Ok(())
}

/// The scheme of `render --scheme` (its label replaces the name in `a`), or none; `--lambda`
/// and `--rules` without a scheme are errors.
fn render_spec(a: &mut RenderArgs) -> Result<Option<Spec>> {
    Ok(match &a.scheme {
        Some(s) => {
            let spec = spec::resolve(
                s,
                &SchemeOptions {
                    lambda: a.lambda,
                    rules: a.rules.map(Into::into),
                    ..SchemeOptions::default()
                },
            )?;
            a.scheme = Some(spec::label(s, &spec));
            Some(spec)
        }
        None if a.lambda.is_some() => {
            return Err(Error::InvalidArgument(
                "--lambda needs a guided --scheme".into(),
            ));
        }
        None if a.rules.is_some() => {
            return Err(Error::InvalidArgument(
                "--rules needs an EG or QAS+ --scheme".into(),
            ));
        }
        None => None,
    })
}

/// Checks that the options fit what is drawn: a `.bv` file's patches, the refined net
/// (`--levels`) or the patch complex (`--rings`) of a scheme.
fn check_render_sources(a: &RenderArgs, bv: bool) -> Result<()> {
    if bv && (a.scheme.is_some() || a.levels.is_some() || a.rings.is_some()) {
        return Err(Error::InvalidArgument(
            "a .bv file holds its patches already: drop --scheme, --levels and --rings".into(),
        ));
    }
    if a.levels.is_some() && a.rings.is_some() {
        return Err(Error::InvalidArgument(
            "give either --levels (refined net) or --rings (patch complex), not both".into(),
        ));
    }
    if a.scheme.is_none() && (a.levels.is_some() || a.rings.is_some()) {
        return Err(Error::InvalidArgument(
            "--levels and --rings need --scheme".into(),
        ));
    }
    Ok(())
}

/// The scene `render` draws: a `.bv` file's patches, the net, the net refined `--levels`
/// times (with the net drawn over it), or the scheme's patch complex (and its rings).
fn render_scene(a: &RenderArgs, spec: Option<&Spec>, bv: bool) -> Result<(Scene, Option<usize>)> {
    if bv {
        return Ok((bv_scene(&a.net)?, None));
    }
    let net = super::load_net(&a.net)?.mesh;
    Ok(match (spec, a.levels) {
        (None, _) => (Scene::mesh(&net), None),
        (Some(s), Some(levels)) => {
            let rules = super::subdivide::mesh_rules(s)?;
            super::limits::check_levels(rules.as_ref(), &net, levels)?;
            let fine = super::subdivide::refine_with(rules.as_ref(), &net, levels, false)?;
            let mut scene = Scene::mesh(&fine);
            scene.net = Some(net);
            (scene, None)
        }
        (Some(s), None) => {
            let r = a.rings.unwrap_or(super::subdivide::DEFAULT_RINGS);
            (complex_scene(s, &net, r, !a.no_fill)?, Some(r))
        }
    })
}

/// Tells on standard error that the image `output` was written: its size, then `detail`.
pub(super) fn say_wrote(output: &Path, image: &render::Image, detail: &str) {
    eprintln!(
        "wrote {} ({}x{}{detail})",
        output.display(),
        image.width,
        image.height
    );
}

/// The per-ring curvature numbers of a scene's patches (none for a net).
pub(super) fn group_curvature(scene: &Scene) -> Vec<stats::GroupCurvature> {
    scene
        .complex()
        .map(|c| stats::curvature_by_group(c, GROUP_SAMPLES))
        .unwrap_or_default()
}

pub use super::compare::{demo_compare, run_compare};

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;
    use crate::cli::{Cli, Command};
    use clap::Parser;

    /// `fairsub render NET WORDS... -o x.png`'s typed options.
    fn parsed(words: &[&str]) -> Result<RenderOptions> {
        let mut all = vec!["fairsub", "render", "gallery:cube", "-o", "x.png"];
        all.extend_from_slice(words);
        let Command::Render(a) = Cli::try_parse_from(all).unwrap().command else {
            panic!("not render")
        };
        let mode: Mode = a.mode.parse()?;
        a.look.options(default(|d| (d.width, d.height)), mode)
    }

    #[crate::unit::test]
    fn the_commands_defaults_are_the_librarys() {
        assert_eq!(parsed(&[]).unwrap(), RenderOptions::default());
        let o = parsed(&["--stripes", "7", "--azimuth", "-30", "--no-legend"]).unwrap();
        let mut want = RenderOptions::default();
        want.shade.stripes = 7.0;
        want.view.azimuth_deg = -30.0;
        want.legend = false;
        assert_eq!(o, want);
    }

    #[crate::unit::test]
    fn the_command_checks_by_the_librarys_rule() {
        let e = parsed(&["--stripe-width", "1.5"]).unwrap_err().to_string();
        let mut o = RenderOptions::default();
        o.shade.stripe_width = 1.5;
        assert_eq!(
            e,
            format!("invalid argument: {}", o.check().unwrap_err().cli_message())
        );
        assert_eq!(
            e,
            "invalid argument: bad --stripe-width 1.5: must lie strictly between 0 and 1"
        );
        let e = parsed(&["--fov", "200"]).unwrap_err().to_string();
        assert_eq!(
            e,
            "invalid argument: bad --fov 200: the field of view must be between 1 and 170 degrees"
        );
    }
}
