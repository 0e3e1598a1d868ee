//! Shape interrogation as images: highlight lines, reflection lines, isophotes, curvature maps,
//! provenance colours and comparison panels, rendered offscreen on the CPU.
//!
//! The papers judge a scheme by highlight lines and curvature on its inner rings; this module
//! draws the same pictures without a display or GPU. The pipeline is
//!
//! 1. [`camera`]: a perspective look-at camera from azimuth / elevation / distance, fitted to the
//!    whole surface, to the limit point of one extraordinary element ([`View::focus`]) or to its
//!    rings `K..L` ([`View::zoom_rings`]);
//! 2. [`raster`]: a z-buffer over a dense, crack-free tessellation that records per sample the
//!    patch and its domain point `(u, v)`, refined by Newton's method to the exact intersection
//!    of the pixel ray with the Bezier patch; then the exact position, normal and Gauss and mean
//!    curvature of the patch at that `(u, v)` ([`raster::Frame`]), so the pictures show the true
//!    surface, not its tessellation;
//! 3. [`shade`]: one colour per sample for a [`Mode`], averaged over the `aa x aa` samples of a
//!    pixel, plus optional overlays (patch boundaries, the control net);
//! 4. [`text`] and [`panel`]: legends with numbers and labelled grids (scheme x mode) that
//!    share one camera, one light set and, per mode, one curvature range or stripe period.
//!
//! Plain polygon meshes ([`MeshSurface`]) go through the same pipeline with interpolated vertex
//! normals (no curvature). Everything is deterministic: the same input gives the same bytes,
//! whatever the number of threads (work is split by image rows, never reduced in thread order).

pub mod camera;
mod image;
mod options;
pub mod panel;
pub mod raster;
pub mod shade;
pub mod stats;
pub mod text;

pub use camera::{Camera, Region, View};
pub use image::{BACKGROUND, Image};
pub use options::{BadOption, LookOption, MAX_SAMPLES, MAX_SIZE, RenderOptions, parse_size};
pub use raster::{Frame, Sample};
pub use shade::{Lights, ShadeOptions, StripePeriods};
pub use stats::{FrameStats, GroupCurvature};

use crate::error::{Error, Result};
use crate::geom::{Point, add, cross, norm, normalize, scale, sub};
use crate::io::BvFile;
use crate::mesh::PolyMesh;
use crate::surface::{Element, PatchComplex, Provenance};

/// What a picture shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Mode {
    /// Plain shading (two lights and a highlight), for the overall shape.
    Shaded,
    /// Beier-Chen highlight lines: stripes of a family of parallel light lines, seen along the
    /// surface normals ([`Lights::highlight_value`]).
    Highlight,
    /// Reflection lines: the reflection of a plane of parallel light lines in the surface, seen
    /// from the camera ([`Lights::reflection_value`]).
    Reflection,
    /// Isophotes: curves of equal light intensity `n . l` ([`Lights::isophote_value`]).
    Isophote,
    /// Gauss curvature `K` as a diverging colour map (blue negative, white 0, red positive).
    Gauss,
    /// Mean curvature `H` as a diverging colour map (sign relative to the patch normal `du x dv`,
    /// see [`crate::bezier::Curvature`]).
    Mean,
    /// Patch provenance: regular patches, rings (two alternating colours) and cap, as in the
    /// papers' figures.
    Provenance,
}

impl Mode {
    /// Every mode, in the order of [`Mode::name`]s in help texts.
    pub const ALL: [Mode; 7] = [
        Mode::Shaded,
        Mode::Highlight,
        Mode::Reflection,
        Mode::Isophote,
        Mode::Gauss,
        Mode::Mean,
        Mode::Provenance,
    ];

    /// The command-line name.
    pub fn name(self) -> &'static str {
        match self {
            Mode::Shaded => "shaded",
            Mode::Highlight => "highlight",
            Mode::Reflection => "reflection",
            Mode::Isophote => "isophote",
            Mode::Gauss => "gauss",
            Mode::Mean => "mean",
            Mode::Provenance => "provenance",
        }
    }

    /// Whether the mode draws stripes (highlight, reflection lines, isophotes).
    pub fn is_striped(self) -> bool {
        matches!(self, Mode::Highlight | Mode::Reflection | Mode::Isophote)
    }

    /// Whether the mode shows a curvature (and so has a range and a legend).
    pub fn is_curvature(self) -> bool {
        matches!(self, Mode::Gauss | Mode::Mean)
    }

    /// The label of the mode's legend or panel column.
    pub fn title(self) -> &'static str {
        match self {
            Mode::Shaded => "shaded",
            Mode::Highlight => "highlight lines",
            Mode::Reflection => "reflection lines",
            Mode::Isophote => "isophotes",
            Mode::Gauss => "Gauss curvature K",
            Mode::Mean => "mean curvature H",
            Mode::Provenance => "provenance",
        }
    }
}

impl std::str::FromStr for Mode {
    type Err = Error;

    fn from_str(s: &str) -> Result<Mode> {
        let m = match s.trim().to_ascii_lowercase().as_str() {
            "shaded" | "shade" => Mode::Shaded,
            "highlight" | "highlights" | "highlight-lines" => Mode::Highlight,
            "reflection" | "reflections" | "reflection-lines" => Mode::Reflection,
            "isophote" | "isophotes" => Mode::Isophote,
            "gauss" | "gaussian" => Mode::Gauss,
            "mean" => Mode::Mean,
            "provenance" | "rings" => Mode::Provenance,
            _ => {
                let names: Vec<&str> = Mode::ALL.iter().map(|m| m.name()).collect();
                return Err(Error::InvalidArgument(format!(
                    "unknown mode '{s}' (modes: {})",
                    names.join(", ")
                )));
            }
        };
        Ok(m)
    }
}

/// Lines drawn over the shaded surface.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Overlays {
    /// The control net (its edges and vertices, drawn on top).
    pub net: bool,
    /// Patch boundaries (face boundaries for a plain mesh).
    pub patches: bool,
}

impl Overlays {
    /// Parses overlay names (`net`, `patches`), each given once or as a comma list.
    pub fn parse<S: AsRef<str>>(names: &[S]) -> Result<Overlays> {
        let mut o = Overlays::default();
        for name in names.iter().flat_map(|s| s.as_ref().split(',')) {
            match name.trim() {
                "net" | "control-net" => o.net = true,
                "patches" | "patch" | "boundaries" => o.patches = true,
                "" => {}
                other => {
                    return Err(Error::InvalidArgument(format!(
                        "unknown overlay '{other}' (overlays: net, patches)"
                    )));
                }
            }
        }
        Ok(o)
    }
}

/// A triangle mesh with vertex normals: how a plain polygon mesh is rendered (no curvature).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct MeshSurface {
    /// Vertex positions.
    pub positions: Vec<Point>,
    /// Unit vertex normals (area-weighted means of the face normals around each vertex).
    pub normals: Vec<Point>,
    /// Triangles (fans of the polygons).
    pub triangles: Vec<[u32; 3]>,
    /// The polygon each triangle comes from.
    pub triangle_face: Vec<u32>,
}

impl MeshSurface {
    /// The polygons of `mesh` as fans of triangles, with area-weighted vertex normals (Newell
    /// normals of the polygons, so non-planar polygons count with their vector area).
    pub fn from_polymesh(mesh: &PolyMesh) -> MeshSurface {
        let pos = mesh.positions();
        let mut normals = vec![[0.0; 3]; pos.len()];
        let mut triangles = Vec::new();
        let mut triangle_face = Vec::new();
        for (f, face) in mesh.faces().enumerate() {
            let mut area = [0.0; 3];
            for k in 0..face.len() {
                let a = pos[face[k] as usize];
                let b = pos[face[(k + 1) % face.len()] as usize];
                area = add(area, scale(cross(a, b), 0.5));
            }
            for &v in face {
                normals[v as usize] = add(normals[v as usize], area);
            }
            for k in 1..face.len().saturating_sub(1) {
                triangles.push([face[0], face[k], face[k + 1]]);
                triangle_face.push(f as u32);
            }
        }
        for n in &mut normals {
            *n = normalize(*n);
        }
        MeshSurface {
            positions: pos.to_vec(),
            normals,
            triangles,
            triangle_face,
        }
    }
}

/// What is drawn: an exact patch complex or a plain mesh.
#[derive(Debug, Clone)]
pub enum Surface {
    /// Bezier patches, shaded with their exact normals and curvatures.
    Patches(PatchComplex),
    /// A polygon mesh with interpolated vertex normals.
    Mesh(MeshSurface),
}

/// A surface and, optionally, the control net it comes from (for the net overlay).
#[derive(Debug, Clone)]
pub struct Scene {
    /// The surface.
    pub surface: Surface,
    /// The control net, drawn by [`Overlays::net`].
    pub net: Option<PolyMesh>,
}

impl Scene {
    /// A scene of a patch complex and its control net.
    pub fn patches(complex: PatchComplex, net: Option<PolyMesh>) -> Scene {
        Scene {
            surface: Surface::Patches(complex),
            net,
        }
    }

    /// A scene of a plain polygon mesh (the mesh is also its own net).
    pub fn mesh(mesh: &PolyMesh) -> Scene {
        Scene {
            surface: Surface::Mesh(MeshSurface::from_polymesh(mesh)),
            net: Some(mesh.clone()),
        }
    }

    /// The patch complex, when the surface is one.
    pub fn complex(&self) -> Option<&PatchComplex> {
        match &self.surface {
            Surface::Patches(c) => Some(c),
            Surface::Mesh(_) => None,
        }
    }
}

/// The element that stands for the rings and cap of a `.bv` file, whose groups do not record
/// which extraordinary element they belong to.
pub const BV_ELEMENT: Element = Element::Vertex(u32::MAX);

/// The patch complex of a `.bv` file with provenance recovered from its group names: `regular`
/// gives [`Provenance::Regular`] (face unknown: `u32::MAX`), `ringK` gives ring `K` and `cap`
/// the cap, both of the unrecorded element [`BV_ELEMENT`] (sector 0); other groups stay
/// [`Provenance::Unknown`]. Triangular patches are included as exact tensor-product patches
/// ([`BvFile::all_patches`]), polyhedra are not (see [`complex_from_bv_with`]).
pub fn complex_from_bv(file: &BvFile) -> PatchComplex {
    complex_from_bv_with(file, false)
}

/// [`complex_from_bv`], with the faces of the file's polyhedra as flat patches when
/// `polyhedra` is true.
pub fn complex_from_bv_with(file: &BvFile, polyhedra: bool) -> PatchComplex {
    let all = file.all_patches(polyhedra);
    let mut c = all.complex;
    for (k, prov) in c.provenance.iter_mut().enumerate() {
        let Some(Some(g)) = all.groups.get(k) else {
            continue;
        };
        let Some(group) = file.groups.get(*g) else {
            continue;
        };
        let name = group.name.as_str();
        *prov = if name == "regular" {
            Provenance::Regular { face: u32::MAX }
        } else if name == "cap" {
            Provenance::Cap {
                element: BV_ELEMENT,
                sector: 0,
            }
        } else if let Some(ring) = name
            .strip_prefix("ring")
            .and_then(|r| r.parse::<u32>().ok())
        {
            Provenance::Ring {
                element: BV_ELEMENT,
                ring,
                sector: 0,
            }
        } else {
            Provenance::Unknown
        };
    }
    c
}

/// A human-readable name of an element (`vertex 3`, `face 7`, or the unrecorded `.bv` element).
pub fn element_name(e: Element) -> String {
    match e {
        BV_ELEMENT => "the extraordinary element of the .bv file".to_string(),
        Element::Vertex(v) => format!("vertex {v}"),
        Element::Face(f) => format!("face {f}"),
    }
}

/// A rendered picture with the data behind it.
#[derive(Debug, Clone)]
pub struct Rendered {
    /// The picture (with the legend strip when asked for and the mode has one).
    pub image: Image,
    /// Per-sample surface data the picture was shaded from.
    pub frame: Frame,
    /// The camera.
    pub camera: Camera,
    /// The framed region (centre and radius) the camera and lights were fitted to.
    pub region: Region,
    /// The symmetric curvature range `[-r, r]` of the colour map (curvature modes only).
    pub range: Option<f64>,
    /// The fitted stripe period (stripe modes only; see [`Lights::fit_period`]).
    pub stripe_period: Option<f64>,
    /// Coverage and visible curvature ranges of the frame.
    pub stats: FrameStats,
}

/// Renders one picture of a scene.
pub fn render(scene: &Scene, opts: &RenderOptions) -> Result<Rendered> {
    opts.validate()?;
    check_mode(scene, opts.mode)?;
    let (camera, region) = camera::fit(&[scene], &opts.view, opts.width, opts.height)?;
    let frame = raster::rasterize(scene, &camera, opts.supersample)?;
    let range = if opts.mode.is_curvature() {
        Some(resolve_range(&[&frame], opts.mode, &opts.shade, &region))
    } else {
        None
    };
    let mut lights = Lights::new(&camera, &region, &opts.shade);
    let stripe_period = opts
        .mode
        .is_striped()
        .then(|| lights.fit_period(opts.mode, &[&frame]));
    let image = shade::shade(
        scene,
        &frame,
        &camera,
        &lights,
        opts.mode,
        range,
        opts.overlays,
    )?;
    let image = match (opts.legend, range) {
        (true, Some(r)) => image.stacked(&text::legend(opts.width, opts.mode, r)),
        _ => image,
    };
    let stats = FrameStats::of(&frame);
    Ok(Rendered {
        image,
        frame,
        camera,
        region,
        range,
        stripe_period,
        stats,
    })
}

/// Rejects modes a scene cannot show (curvature and provenance of a plain mesh).
pub fn check_mode(scene: &Scene, mode: Mode) -> Result<()> {
    if scene.complex().is_none() && (mode.is_curvature() || mode == Mode::Provenance) {
        return Err(Error::InvalidArgument(format!(
            "mode '{}' needs exact patches; a plain mesh has none (give --scheme with patch output, or a .bv file)",
            mode.name()
        )));
    }
    Ok(())
}

/// The curvature range of a mode: the fixed [`ShadeOptions::range`], or automatic (see
/// [`auto_range`]).
pub fn resolve_range(frames: &[&Frame], mode: Mode, opts: &ShadeOptions, region: &Region) -> f64 {
    match opts.range {
        Some(r) => r,
        None => auto_range(frames, mode, opts.percentile, region.radius),
    }
}

/// The automatic symmetric range of a curvature mode over several frames: the `percentile`
/// (e.g. 0.98) of `|value|` over all covered samples with a defined value, rounded up to two
/// significant digits. It is at least `1e-6 / radius` (mean) or `1e-6 / radius^2` (Gauss), so
/// a plane shows white rather than amplified rounding noise.
pub fn auto_range(frames: &[&Frame], mode: Mode, percentile: f64, radius: f64) -> f64 {
    let mut vals: Vec<f32> = frames
        .iter()
        .flat_map(|f| f.samples.iter())
        .filter(|s| s.is_covered())
        .map(|s| if mode == Mode::Gauss { s.gauss } else { s.mean })
        .filter(|v| v.is_finite())
        .map(f32::abs)
        .collect();
    let floor = if mode == Mode::Gauss {
        1e-6 / (radius * radius)
    } else {
        1e-6 / radius
    };
    let floor = if floor.is_finite() && floor > 0.0 {
        floor
    } else {
        1e-12
    };
    if vals.is_empty() {
        return nice_ceil(floor);
    }
    let k = ((vals.len() - 1) as f64 * percentile.clamp(0.0, 1.0)).round() as usize;
    let (_, v, _) = vals.select_nth_unstable_by(k, f32::total_cmp);
    nice_ceil((*v as f64).max(floor))
}

/// `x` rounded up to two significant digits (`0.01234 -> 0.013`).
pub fn nice_ceil(x: f64) -> f64 {
    if !(x.is_finite() && x > 0.0) {
        return x;
    }
    let e = x.log10().floor() as i32 - 1;
    let m = 10f64.powi(e);
    let r = (x / m).ceil() * m;
    // guard against 0.013000000000000001-style representation drift
    format!("{r:.3e}").parse().unwrap_or(r)
}

/// The unit direction from the eye to a point.
pub(crate) fn view_dir(eye: Point, p: Point) -> Point {
    let d = sub(p, eye);
    let l = norm(d);
    if l > 0.0 { scale(d, 1.0 / l) } else { d }
}

/// A panel of pictures: rows are schemes, columns are modes.
#[derive(Debug, Clone)]
pub struct Panel {
    /// The labelled grid.
    pub image: Image,
    /// The one camera of all cells.
    pub camera: Camera,
    /// The framed region.
    pub region: Region,
    /// The range used for each curvature mode (shared by its column).
    pub ranges: Vec<(Mode, f64)>,
    /// The stripe period used for each stripe mode (shared by its column).
    pub periods: Vec<(Mode, f64)>,
    /// Coverage and visible curvature ranges of each scheme's frame (rows in order).
    pub stats: Vec<FrameStats>,
}

/// Renders a comparison panel: one row per named scene (scheme), one column per mode, with one
/// camera (fitted to all scenes together), one light set and, per curvature mode, one range
/// over all scenes. `opts.width x opts.height` is the size of a cell; `opts.mode` is ignored.
pub fn compare(scenes: &[(String, Scene)], modes: &[Mode], opts: &RenderOptions) -> Result<Panel> {
    opts.validate()?;
    if scenes.is_empty() || modes.is_empty() {
        return Err(Error::InvalidArgument(
            "a comparison needs at least one scheme and one mode".into(),
        ));
    }
    for (name, s) in scenes {
        for &m in modes {
            check_mode(s, m).map_err(|e| Error::InvalidArgument(format!("{name}: {e}")))?;
        }
    }
    let refs: Vec<&Scene> = scenes.iter().map(|(_, s)| s).collect();
    let (camera, region) = camera::fit(&refs, &opts.view, opts.width, opts.height)?;
    let frames: Vec<Frame> = scenes
        .iter()
        .map(|(_, s)| raster::rasterize(s, &camera, opts.supersample))
        .collect::<Result<_>>()?;
    let frame_refs: Vec<&Frame> = frames.iter().collect();
    let base_lights = Lights::new(&camera, &region, &opts.shade);
    let mut ranges = Vec::new();
    let mut periods = Vec::new();
    let mut columns: Vec<Vec<Image>> = Vec::new();
    let mut legends = Vec::new();
    for &m in modes {
        let range = if m.is_curvature() {
            let r = resolve_range(&frame_refs, m, &opts.shade, &region);
            ranges.push((m, r));
            Some(r)
        } else {
            None
        };
        let mut lights = base_lights.clone();
        if m.is_striped() {
            periods.push((m, lights.fit_period(m, &frame_refs)));
        }
        let mut col = Vec::new();
        for ((_, s), f) in scenes.iter().zip(&frames) {
            col.push(shade::shade(
                s,
                f,
                &camera,
                &lights,
                m,
                range,
                opts.overlays,
            )?);
        }
        columns.push(col);
        legends.push(match (opts.legend, range) {
            (true, Some(r)) => Some(text::legend(opts.width, m, r)),
            _ => None,
        });
    }
    let row_labels: Vec<String> = scenes.iter().map(|(n, _)| n.clone()).collect();
    let col_labels: Vec<String> = modes.iter().map(|m| m.title().to_string()).collect();
    let image = panel::compose(&columns, &row_labels, &col_labels, &legends);
    Ok(Panel {
        image,
        camera,
        region,
        ranges,
        periods,
        stats: frames.iter().map(FrameStats::of).collect(),
    })
}

#[cfg(feature = "unit-tests")]
mod tests;
