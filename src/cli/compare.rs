//! `fairsub compare`: a labelled grid of schemes x modes with one camera, one light set and one
//! curvature range per mode (and the demo's comparison picture). The arguments, the shared
//! scene builders and `render` itself are in `render.rs`; this file holds the grid (split from
//! it by topic).

use super::render::{CompareArgs, RangeReport, complex_scene, group_curvature, is_bv};
use super::spec::{self, SchemeOptions};
use crate::error::{Error, Result};
use crate::mesh::PolyMesh;
use crate::render::{self, Mode, RenderOptions, Scene, View, stats};
use crate::schemes::Spec;
use serde::Serialize;
use std::path::Path;

#[derive(Serialize)]
struct SchemeReport {
    scheme: String,
    patches: usize,
    frame: render::FrameStats,
    groups: Vec<stats::GroupCurvature>,
}

#[derive(Serialize)]
struct CompareReport<'a> {
    input: &'a str,
    rings: usize,
    modes: Vec<Mode>,
    output: String,
    cell_width: usize,
    cell_height: usize,
    supersample: usize,
    camera: &'a render::Camera,
    region: &'a render::Region,
    ranges: Vec<RangeReport>,
    stripe_periods: Vec<(Mode, f64)>,
    schemes: Vec<SchemeReport>,
}

/// Builds and renders a comparison panel; returns it with the scenes (for the report).
fn compare_panel(
    net: &PolyMesh,
    schemes: &[String],
    modes: &[Mode],
    rings: usize,
    fill: bool,
    opts: &RenderOptions,
) -> Result<(render::Panel, Vec<(String, Scene)>)> {
    let mut scenes = Vec::new();
    for s in schemes {
        let spec = spec::resolve(s, &SchemeOptions::default())?;
        let caps = crate::schemes::registry().entry(spec.id).capabilities();
        let scene = if caps.refine && !caps.patches {
            refined_scene(&spec, net)?
        } else {
            complex_scene(&spec, net, rings, fill)?
        };
        scenes.push((s.clone(), scene));
    }
    let panel = render::compare(&scenes, modes, opts)?;
    Ok((panel, scenes))
}

/// Levels of refinement `compare` draws for a scheme without exact patches.
const COMPARE_LEVELS: usize = 4;

/// A scheme without exact patches as `compare` draws it: its net refined [`COMPARE_LEVELS`]
/// times (as `render --scheme S --levels 4`), with the control net for the net overlay.
fn refined_scene(scheme: &Spec, net: &PolyMesh) -> Result<Scene> {
    let rules = super::subdivide::mesh_rules(scheme)?;
    super::limits::check_levels(rules.as_ref(), net, COMPARE_LEVELS)?;
    let fine = super::subdivide::refine_with(rules.as_ref(), net, COMPARE_LEVELS, false)?;
    let mut scene = Scene::mesh(&fine);
    scene.net = Some(net.clone());
    Ok(scene)
}

/// The schemes with patch output that take this net (Loop only takes triangle nets).
fn patch_schemes(net: &PolyMesh) -> Vec<String> {
    crate::schemes::registry()
        .entries()
        .iter()
        .filter(|e| e.capabilities().patches && e.descriptor.check_input(net).is_ok())
        .map(|e| e.name.to_string())
        .collect()
}

/// Runs `fairsub compare`.
pub fn run_compare(a: CompareArgs) -> Result<()> {
    if is_bv(&a.net) {
        return Err(Error::InvalidArgument(
            "compare builds each scheme's surface from a control net; a .bv file holds finished patches (use `fairsub render` on it)".into(),
        ));
    }
    let modes: Vec<Mode> = a.modes.iter().map(|m| m.parse()).collect::<Result<_>>()?;
    let net = super::load_net(&a.net)?.mesh;
    let schemes: Vec<String> = if a.schemes.is_empty() {
        patch_schemes(&net)
    } else {
        a.schemes.iter().map(|s| s.trim().to_string()).collect()
    };
    // With --lambda, the guided schemes among them take the contraction; the others keep theirs.
    let schemes: Vec<String> = schemes
        .into_iter()
        .map(|s| {
            let plain = spec::resolve(&s, &SchemeOptions::default())?;
            let takes = |kind| {
                crate::schemes::registry()
                    .descriptor(plain.id)
                    .params()
                    .contains(&kind)
            };
            use crate::schemes::descriptor::ParamKind;
            let lambda = a.lambda.filter(|_| takes(ParamKind::Contraction));
            let rules = a.rules.filter(|_| takes(ParamKind::Rules));
            let spec = spec::resolve(
                &s,
                &SchemeOptions {
                    lambda,
                    rules: rules.map(Into::into),
                    ..SchemeOptions::default()
                },
            )?;
            Ok(spec::label(&s, &spec))
        })
        .collect::<Result<_>>()?;
    let opts = a
        .look
        .options((400, 400), modes.first().copied().unwrap_or(Mode::Shaded))?;
    super::limits::check_render(
        opts.width,
        opts.height,
        opts.supersample,
        schemes.len() * modes.len(),
    )?;
    let (panel, scenes) = compare_panel(&net, &schemes, &modes, a.rings, !a.no_fill, &opts)?;
    panel.image.write_png(&a.output)?;
    if a.json {
        let report = CompareReport {
            input: &a.net,
            rings: a.rings,
            modes: modes.clone(),
            output: a.output.display().to_string(),
            cell_width: opts.width,
            cell_height: opts.height,
            supersample: opts.supersample,
            camera: &panel.camera,
            region: &panel.region,
            ranges: panel
                .ranges
                .iter()
                .map(|&(mode, value)| RangeReport {
                    mode,
                    value,
                    automatic: opts.shade.range.is_none(),
                })
                .collect(),
            stripe_periods: panel.periods.clone(),
            schemes: scenes
                .iter()
                .zip(&panel.stats)
                .map(|((name, scene), st)| SchemeReport {
                    scheme: name.clone(),
                    patches: scene.complex().map_or(0, |c| c.len()),
                    frame: st.clone(),
                    groups: group_curvature(scene),
                })
                .collect(),
        };
        super::say_json(&report);
    }
    let detail = format!(": {} schemes x {} modes", schemes.len(), modes.len());
    super::render::say_wrote(&a.output, &panel.image, &detail);
    Ok(())
}

/// The panel of `fairsub demo`: every scheme with patch output x highlight lines, mean
/// curvature and provenance, 320x320 cells, 6 rings, zoomed on the rings and cap of the net's
/// extraordinary element as in the papers (the same as `fairsub compare NET --modes
/// highlight,mean,provenance --size 320x320 --zoom-rings 1..7 --elevation 55`).
pub fn demo_compare(net: &PolyMesh, path: &Path) -> Result<()> {
    let modes = [Mode::Highlight, Mode::Mean, Mode::Provenance];
    let opts = RenderOptions {
        width: 320,
        height: 320,
        view: View {
            elevation_deg: 55.0,
            zoom_rings: Some((1, 7)),
            ..View::default()
        },
        ..RenderOptions::default()
    };
    let (panel, _) = compare_panel(net, &patch_schemes(net), &modes, 6, true, &opts)?;
    panel.image.write_png(path)
}
