//! Shading: one colour per sample for each [`Mode`], overlays, and the box filter to pixels.
//!
//! All lights are placed relative to the camera and the framed region ([`Lights::new`]), so a
//! panel whose cells share a camera also shares its lights.
//!
//! - *Highlight lines* (Beier and Chen 1994): a family of parallel light lines `a + c e + t d`
//!   lies in a plane between the camera and the surface (normal toward the camera, at
//!   [`ShadeOptions::light_height`] region radii in front of the centre); `d` is the camera's
//!   right vector turned by [`ShadeOptions::light_angle_deg`] in the image plane, `e` is
//!   orthogonal to it in the plane. The normal line `p + s n` of a surface point meets the line
//!   of the family with parameter `c = (p - a) . (n x d) / (n . (d x e))` (the distance between
//!   the two lines vanishes there); the light lines are `c = k delta`, so the highlight lines of
//!   the paper are the curves where `c / delta` is an integer, and a band is drawn where
//!   `frac(c / delta) < stripe_width`. A discontinuity of the normal shows as a break of the
//!   lines, one of the curvature as a kink.
//! - *Reflection lines*: the view ray is reflected about the normal; the light lines (direction
//!   `d`) are at infinity, all around the surface, so the reflected direction `r` sees the line
//!   at angle `atan2(r . e, r . (d x e))` about `d`. Unlike a finite plane this is defined for
//!   every normal, and a planar mirror shows straight lines.
//! - *Isophotes*: bands of equal angle between the normal (turned toward the eye) and the key
//!   light.
//!
//! The period of each stripe mode (the light-line spacing `delta`, or an angle) is fitted to
//! what is visible ([`Lights::fit_period`]): [`ShadeOptions::stripes`] periods over the spread
//! (2nd to 98th percentile) of the raw parameter over the covered samples, taken over all cells
//! of a panel together. Stripes are filtered analytically: each sample takes the dark fraction
//! of its footprint in the stripe parameter (from the differences to its neighbours), so dense
//! stripes fade to grey instead of aliasing.
//! - *Curvature*: a diverging map (blue negative, white 0, red positive) of `K` or `H` over a
//!   symmetric range, lightly shaded; undefined values are grey.
//! - *Provenance*: regular patches green, rings alternating orange and blue by ring index, cap
//!   red, unknown grey, shaded.

use super::raster::{Frame, NONE};
use super::{BACKGROUND, Camera, Image, Mode, Overlays, Region, Scene};
use crate::error::{Error, Result};
use crate::geom::{Point, add, cross, dot, normalize, scale, sub};
use crate::surface::Provenance;
use rayon::prelude::*;

mod overlay;

#[cfg(feature = "unit-tests")]
use overlay::clip_segment;
use overlay::{draw_net, patch_lines};

/// Stripes, light placement and curvature range.
#[derive(Debug, Clone, PartialEq)]
pub struct ShadeOptions {
    /// Stripe periods across the visible spread of the stripe parameter (see
    /// [`Lights::fit_period`]).
    pub stripes: f64,
    /// Fraction of each period drawn dark, in `(0, 1)`.
    pub stripe_width: f64,
    /// Direction of the light lines in the image plane, degrees from the image's horizontal.
    pub light_angle_deg: f64,
    /// Distance of the light plane in front of the region's centre, in region radii.
    pub light_height: f64,
    /// Fixed symmetric curvature range `[-r, r]`; automatic when `None`.
    pub range: Option<f64>,
    /// Percentile of `|curvature|` over the visible samples that sets the automatic range.
    pub percentile: f64,
}

impl Default for ShadeOptions {
    fn default() -> Self {
        ShadeOptions {
            stripes: 12.0,
            stripe_width: 0.5,
            light_angle_deg: 0.0,
            light_height: 3.0,
            range: None,
            percentile: 0.98,
        }
    }
}

/// The light set of a picture (see the module notes).
#[derive(Debug, Clone, PartialEq)]
pub struct Lights {
    /// The eye.
    pub eye: Point,
    /// Unit vector toward the key light.
    pub key: Point,
    /// Unit vector toward the fill light.
    pub fill: Point,
    /// A point of the light plane (origin of the light-line parameter).
    pub plane_point: Point,
    /// Unit normal of the light plane, toward the camera (`d x e`).
    pub plane_normal: Point,
    /// Direction `d` of the light lines.
    pub line_dir: Point,
    /// Direction `e` across the light lines, in the plane.
    pub across: Point,
    /// Period of each stripe mode: highlight-line spacing (length), reflection-line and
    /// isophote periods (radians).
    pub periods: StripePeriods,
    /// Stripe periods across the visible spread (see [`Lights::fit_period`]).
    pub stripes: f64,
    /// Fraction of a period drawn dark.
    pub stripe_width: f64,
}

/// The period of each stripe mode.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct StripePeriods {
    /// Spacing of the highlight light lines (model units).
    pub highlight: f64,
    /// Angle between neighbouring reflected light lines (radians).
    pub reflection: f64,
    /// Angle between isophotes (radians).
    pub isophote: f64,
}

impl Lights {
    /// The lights for a camera and region; stripe periods before fitting: `2 radius / stripes`
    /// for highlight lines, `pi / stripes` for the angles.
    pub fn new(cam: &Camera, region: &Region, opts: &ShadeOptions) -> Lights {
        let [r, u, f] = cam.basis();
        let a = opts.light_angle_deg.to_radians();
        let d = add(scale(r, a.cos()), scale(u, a.sin()));
        let e = add(scale(r, -a.sin()), scale(u, a.cos()));
        let toward_cam = scale(f, -1.0);
        let comb = |x: f64, y: f64, z: f64| {
            normalize(add(add(scale(r, x), scale(u, y)), scale(toward_cam, z)))
        };
        let angle = std::f64::consts::PI / opts.stripes;
        Lights {
            eye: cam.eye,
            key: comb(-0.45, 0.6, 0.66),
            fill: comb(0.6, -0.25, 0.76),
            plane_point: add(
                region.centre,
                scale(toward_cam, opts.light_height * region.radius),
            ),
            plane_normal: cross(d, e),
            line_dir: d,
            across: e,
            periods: StripePeriods {
                highlight: 2.0 * region.radius / opts.stripes,
                reflection: angle,
                isophote: angle,
            },
            stripes: opts.stripes,
            stripe_width: opts.stripe_width,
        }
    }

    /// The light-line parameter `c` (a length along `e`) of the line that the normal line
    /// `p + s n` meets; `None` when the normal is parallel to the light plane.
    pub fn highlight_value(&self, p: Point, n: Point) -> Option<f64> {
        let m = cross(n, self.line_dir);
        let den = dot(n, self.plane_normal);
        if den.abs() < 1e-9 {
            return None;
        }
        Some(dot(sub(p, self.plane_point), m) / den)
    }

    /// The angle (radians) about the light-line direction of the reflected view ray; `None` when
    /// the reflected ray runs along the light lines.
    pub fn reflection_value(&self, p: Point, n: Point) -> Option<f64> {
        let v = super::view_dir(self.eye, p);
        let r = sub(v, scale(n, 2.0 * dot(v, n)));
        let (a, b) = (dot(r, self.across), dot(r, self.plane_normal));
        if a.hypot(b) < 1e-9 {
            return None;
        }
        Some(a.atan2(b))
    }

    /// The angle (radians) between the eye-facing normal and the key light.
    pub fn isophote_value(&self, n_front: Point) -> f64 {
        dot(n_front, self.key).clamp(-1.0, 1.0).acos()
    }

    /// The raw stripe value of a stripe mode at a point with normal `n` (eye-facing `n_front`);
    /// `None` where undefined or for other modes.
    pub fn value(&self, mode: Mode, p: Point, n: Point, n_front: Point) -> Option<f64> {
        match mode {
            Mode::Highlight => self.highlight_value(p, n),
            Mode::Reflection => self.reflection_value(p, n),
            Mode::Isophote => Some(self.isophote_value(n_front)),
            _ => None,
        }
    }

    /// The period of a stripe mode (1 for other modes).
    pub fn period(&self, mode: Mode) -> f64 {
        match mode {
            Mode::Highlight => self.periods.highlight,
            Mode::Reflection => self.periods.reflection,
            Mode::Isophote => self.periods.isophote,
            _ => 1.0,
        }
    }

    /// The stripe parameter (in periods) of a stripe mode.
    pub fn stripe_param(&self, mode: Mode, p: Point, n: Point, n_front: Point) -> Option<f64> {
        self.value(mode, p, n, n_front)
            .map(|c| c / self.period(mode))
    }

    /// Fits the period of a stripe mode to the frames: [`Lights::stripes`] periods over the
    /// spread between the 2nd and 98th percentiles of the raw value over all covered samples
    /// (the period is kept when the spread is zero or there are no samples). Returns the
    /// period.
    pub fn fit_period(&mut self, mode: Mode, frames: &[&Frame]) -> f64 {
        let mut vals: Vec<f64> = frames
            .iter()
            .flat_map(|f| f.samples.iter().map(move |s| (f, s)))
            .filter(|(_, s)| s.is_covered())
            .filter_map(|(f, s)| {
                let (p, n, nf) = geometry(f, self, s);
                self.value(mode, p, n, nf)
            })
            .filter(|v| v.is_finite())
            .collect();
        if vals.len() >= 2 {
            vals.sort_by(f64::total_cmp);
            let at = |q: f64| vals[((vals.len() - 1) as f64 * q).round() as usize];
            let spread = at(0.98) - at(0.02);
            if spread.is_finite() && spread > 0.0 {
                let period = spread / self.stripes;
                match mode {
                    Mode::Highlight => self.periods.highlight = period,
                    Mode::Reflection => self.periods.reflection = period,
                    Mode::Isophote => self.periods.isophote = period,
                    _ => {}
                }
            }
        }
        self.period(mode)
    }

    /// Whether a stripe parameter lies in a dark band.
    pub fn is_dark(&self, c: f64) -> bool {
        c.rem_euclid(1.0) < self.stripe_width
    }

    /// Diffuse light (key and fill, plus ambient) and specular highlight for an eye-facing
    /// normal at `p`.
    pub fn light(&self, p: Point, n_front: Point) -> (f64, f64) {
        let diffuse =
            0.22 + 0.63 * dot(n_front, self.key).max(0.0) + 0.25 * dot(n_front, self.fill).max(0.0);
        let v = scale(super::view_dir(self.eye, p), -1.0);
        let h = normalize(add(v, self.key));
        let spec = dot(n_front, h).max(0.0).powi(40);
        (diffuse.min(1.0), spec)
    }
}

/// The diverging colour map: `t` in `[-1, 1]` (clamped) from dark blue through white to dark
/// red.
pub fn diverging(t: f64) -> [f64; 3] {
    const STOPS: [(f64, [f64; 3]); 5] = [
        (-1.0, [0.12, 0.20, 0.55]),
        (-0.5, [0.35, 0.58, 0.90]),
        (0.0, [0.97, 0.97, 0.97]),
        (0.5, [0.93, 0.50, 0.32]),
        (1.0, [0.60, 0.08, 0.10]),
    ];
    let t = if t.is_nan() { 0.0 } else { t.clamp(-1.0, 1.0) };
    for k in 0..STOPS.len() - 1 {
        let (t0, c0) = STOPS[k];
        let (t1, c1) = STOPS[k + 1];
        if t <= t1 {
            let s = (t - t0) / (t1 - t0);
            return [0, 1, 2].map(|i| c0[i] + s * (c1[i] - c0[i]));
        }
    }
    STOPS[STOPS.len() - 1].1
}

/// The provenance palette: regular green, odd rings orange, even rings blue, cap red, unknown
/// grey.
pub fn provenance_colour(p: &Provenance) -> [f64; 3] {
    match p {
        Provenance::Regular { .. } => [0.55, 0.78, 0.52],
        Provenance::Ring { ring, .. } if ring % 2 == 1 => [0.96, 0.72, 0.35],
        Provenance::Ring { .. } => [0.45, 0.62, 0.92],
        Provenance::Cap { .. } => [0.90, 0.38, 0.38],
        Provenance::Unknown => [0.75, 0.75, 0.75],
    }
}

/// Grey for samples where a mode is undefined.
const UNDEFINED: [f64; 3] = [0.6, 0.6, 0.6];

fn to_u8(c: [f64; 3]) -> [u8; 3] {
    c.map(|x| (x.clamp(0.0, 1.0) * 255.0).round() as u8)
}

/// Position, normal and eye-facing normal of a covered sample.
fn geometry(frame: &Frame, lights: &Lights, s: &super::Sample) -> (Point, Point, Point) {
    let p = frame.position(s);
    let n = s.normal();
    let v = super::view_dir(lights.eye, p);
    let nf = if dot(n, v) > 0.0 { scale(n, -1.0) } else { n };
    (p, n, nf)
}

/// Light at a covered sample: diffuse and specular.
fn lit(frame: &Frame, lights: &Lights, s: &super::Sample) -> (f64, f64) {
    let (p, _, nf) = geometry(frame, lights, s);
    lights.light(p, nf)
}

/// The stripe parameter of a covered sample (NaN where undefined) for a stripe mode.
fn stripe_param(frame: &Frame, lights: &Lights, mode: Mode, s: &super::Sample) -> f64 {
    let (p, n, nf) = geometry(frame, lights, s);
    lights.stripe_param(mode, p, n, nf).unwrap_or(f64::NAN)
}

/// The dark fraction of the stripe parameter interval `[c - w/2, c + w/2]` (box filter of the
/// periodic indicator of `frac(x) < width`).
pub fn dark_fraction(c: f64, w: f64, width: f64) -> f64 {
    let f = |x: f64| x.floor() * width + (x - x.floor()).min(width);
    if w.is_nan() || w <= 1e-12 {
        return if c.rem_euclid(1.0) < width { 1.0 } else { 0.0 };
    }
    if w > 1e6 {
        return width;
    }
    ((f(c + 0.5 * w) - f(c - 0.5 * w)) / w).clamp(0.0, 1.0)
}

/// Footprint of a sample in the stripe parameter: per axis the smaller difference to a
/// neighbour (so a jump across a crease does not blur), the larger over the two axes.
fn footprint(params: &[f64], w: usize, h: usize, x: usize, y: usize) -> f64 {
    let c = params[y * w + x];
    let diff = |k: Option<usize>| k.map(|k| (params[k] - c).abs()).filter(|d| d.is_finite());
    let axis = |a: Option<f64>, b: Option<f64>| match (a, b) {
        (Some(a), Some(b)) => a.min(b),
        (Some(a), None) | (None, Some(a)) => a,
        (None, None) => 0.0,
    };
    let fx = axis(
        diff((x + 1 < w).then(|| y * w + x + 1)),
        diff((x > 0).then(|| y * w + x - 1)),
    );
    let fy = axis(
        diff((y + 1 < h).then(|| (y + 1) * w + x)),
        diff((y > 0).then(|| (y - 1) * w + x)),
    );
    fx.max(fy)
}

/// The colour of one covered sample; `stripe` is the dark fraction for stripe modes.
fn sample_colour(
    scene: &Scene,
    frame: &Frame,
    lights: &Lights,
    mode: Mode,
    range: f64,
    s: &super::Sample,
    stripe: Option<f64>,
) -> [f64; 3] {
    let (diff, spec) = lit(frame, lights, s);
    let light = [0.98; 3].map(|x| x * (0.62 + 0.38 * diff) + 0.15 * spec);
    let stripes = |dark: [f64; 3]| match stripe {
        Some(k) if k.is_finite() => {
            let d = dark.map(|x| x * (0.7 + 0.3 * diff));
            [0, 1, 2].map(|i| k * d[i] + (1.0 - k) * light[i])
        }
        _ => UNDEFINED,
    };
    match mode {
        Mode::Shaded => [0.80, 0.82, 0.86].map(|x| x * diff + 0.35 * spec),
        Mode::Highlight => stripes([0.06, 0.06, 0.09]),
        Mode::Reflection => stripes([0.05, 0.12, 0.35]),
        Mode::Isophote => stripes([0.25, 0.10, 0.05]),
        Mode::Gauss | Mode::Mean => {
            let k = if mode == Mode::Gauss { s.gauss } else { s.mean } as f64;
            if k.is_finite() {
                diverging(k / range).map(|x| x * (0.8 + 0.2 * diff))
            } else {
                UNDEFINED
            }
        }
        Mode::Provenance => {
            let prov = scene
                .complex()
                .and_then(|c| c.provenance.get(s.prim as usize))
                .copied()
                .unwrap_or(Provenance::Unknown);
            provenance_colour(&prov).map(|x| x * (0.3 + 0.7 * diff) + 0.2 * spec)
        }
    }
}

/// Shades a frame into an image of the camera's size: colours per sample for `mode`
/// (curvature modes need `range`), overlays, then the box filter over each pixel's samples.
pub fn shade(
    scene: &Scene,
    frame: &Frame,
    camera: &Camera,
    lights: &Lights,
    mode: Mode,
    range: Option<f64>,
    overlays: Overlays,
) -> Result<Image> {
    let range = match (mode.is_curvature(), range) {
        (true, Some(r)) if r.is_finite() && r > 0.0 => r,
        (true, _) => {
            return Err(Error::InvalidArgument(format!(
                "mode '{}' needs a positive curvature range",
                mode.name()
            )));
        }
        (false, _) => 1.0,
    };
    if overlays.net && scene.net.is_none() {
        return Err(Error::InvalidArgument(
            "--overlay net needs a control net, and this input has none (a .bv file without polyhedra)"
                .into(),
        ));
    }
    let (w, h) = (frame.width, frame.height);
    let striped = mode.is_striped();
    let params: Vec<f64> = if striped {
        frame
            .samples
            .par_iter()
            .map(|s| {
                if s.is_covered() {
                    stripe_param(frame, lights, mode, s)
                } else {
                    f64::NAN
                }
            })
            .collect()
    } else {
        Vec::new()
    };
    let mut cols = vec![BACKGROUND; w * h];
    cols.par_chunks_mut(w).enumerate().for_each(|(y, row)| {
        for (x, c) in row.iter_mut().enumerate() {
            let s = frame.get(x, y);
            if s.is_covered() {
                let stripe = striped.then(|| {
                    let p = params[y * w + x];
                    dark_fraction(p, footprint(&params, w, h, x, y), lights.stripe_width)
                });
                *c = to_u8(sample_colour(scene, frame, lights, mode, range, s, stripe));
            }
        }
    });
    if overlays.patches {
        patch_lines(frame, &mut cols);
    }
    if overlays.net
        && let Some(net) = &scene.net
    {
        draw_net(
            net,
            &camera.scaled(frame.supersample),
            frame.supersample,
            &mut cols,
            w,
            h,
        );
    }
    Ok(downsample(&cols, w, h, frame.supersample))
}

/// Box filter of `ss x ss` samples per pixel (integer mean, rounded).
fn downsample(cols: &[[u8; 3]], w: usize, h: usize, ss: usize) -> Image {
    let (pw, ph) = (w / ss, h / ss);
    let n = (ss * ss) as u32;
    let mut img = Image::filled(pw, ph, BACKGROUND);
    img.data
        .par_chunks_mut(3 * pw)
        .enumerate()
        .for_each(|(py, row)| {
            for px in 0..pw {
                let mut sum = [0u32; 3];
                for sy in 0..ss {
                    for sx in 0..ss {
                        let c = cols[(py * ss + sy) * w + px * ss + sx];
                        for k in 0..3 {
                            sum[k] += c[k] as u32;
                        }
                    }
                }
                for k in 0..3 {
                    row[3 * px + k] = ((sum[k] + n / 2) / n) as u8;
                }
            }
        });
    img
}

#[cfg(feature = "unit-tests")]
mod tests;
