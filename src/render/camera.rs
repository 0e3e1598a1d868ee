//! The camera: a perspective look-at camera placed by azimuth, elevation and distance around a
//! framed region.
//!
//! Shape is judged on the inner rings of an extraordinary point, so besides fitting the whole
//! surface the camera can centre on the limit point of one element ([`View::focus`]) and frame
//! its rings `K..L` ([`View::zoom_rings`]). What must be seen is sampled as surface points
//! ([`framing`]); the camera looks from the direction given by azimuth and elevation (z is up)
//! and, unless a distance is given, is moved until those points fill the image ([`fit`]).
//! Several scenes (a comparison panel) are framed together and share one camera.

use super::{BV_ELEMENT, Scene, Surface, element_name};
use crate::error::{Error, Result};
use crate::geom::{Point, add, cross, dist, dot, normalize, scale, sub};
use crate::surface::{Element, PatchComplex, Provenance};
use serde::Serialize;

/// Where the camera looks from and what it frames.
#[derive(Debug, Clone, PartialEq)]
pub struct View {
    /// Angle of the eye around the z axis, in degrees from the x axis (counter-clockwise seen
    /// from above). At `-90` the eye is on the `-y` side and the image's right is `+x`.
    pub azimuth_deg: f64,
    /// Angle of the eye above the xy plane, in degrees (90 looks straight down).
    pub elevation_deg: f64,
    /// Distance from the eye to the region's centre in model units; automatic (the region just
    /// fills the view) when `None`.
    pub distance: Option<f64>,
    /// Vertical field of view in degrees.
    pub fov_deg: f64,
    /// Centre on the limit point of this extraordinary element.
    pub focus: Option<Element>,
    /// Frame rings `K..=L` (1 = outermost) of the focused element (or of the only element); the
    /// cap counts as the ring after the last one.
    pub zoom_rings: Option<(u32, u32)>,
}

impl Default for View {
    fn default() -> Self {
        View {
            azimuth_deg: -60.0,
            elevation_deg: 40.0,
            distance: None,
            fov_deg: 30.0,
            focus: None,
            zoom_rings: None,
        }
    }
}

/// Parses `K..L`, `K..=L` or `K` (a single ring).
pub fn parse_rings(s: &str) -> Result<(u32, u32)> {
    let bad = || {
        Error::InvalidArgument(format!(
            "bad ring range '{s}': expected K..L with 1 <= K <= L (ring 1 is the outermost)"
        ))
    };
    let t = s.trim();
    let (k, l) = match t.split_once("..") {
        Some((k, l)) => (k.trim(), l.trim().trim_start_matches('=').trim()),
        None => (t, t),
    };
    let k: u32 = k.parse().map_err(|_| bad())?;
    let l: u32 = l.parse().map_err(|_| bad())?;
    if k == 0 || l < k {
        return Err(bad());
    }
    Ok((k, l))
}

/// Parses a focus element: `V` or `vertex:V` for a vertex, `face:F` for a face.
pub fn parse_element(s: &str) -> Result<Element> {
    let t = s.trim().to_ascii_lowercase();
    let (kind, num) = match t.split_once(':') {
        Some((k, n)) => (k.trim().to_string(), n.trim().to_string()),
        None => ("vertex".to_string(), t.clone()),
    };
    let n: u32 = num.parse().map_err(|_| {
        Error::InvalidArgument(format!(
            "bad element '{s}': expected a vertex index V, vertex:V or face:F"
        ))
    })?;
    match kind.as_str() {
        "v" | "vertex" => Ok(Element::Vertex(n)),
        "f" | "face" => Ok(Element::Face(n)),
        _ => Err(Error::InvalidArgument(format!(
            "bad element '{s}': expected a vertex index V, vertex:V or face:F"
        ))),
    }
}

/// The framed region: the camera target and the radius of the disc the view shows there (the
/// length scale of the light plane's distance and of the curvature floors).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Region {
    /// Centre (the camera looks at it).
    pub centre: Point,
    /// Radius of the visible disc at the centre's depth.
    pub radius: f64,
}

/// A perspective camera. View coordinates: `x` right, `y` up, `z` forward (depth); pixel
/// coordinates: `x` from the left edge, `y` from the top edge, pixel `(i, j)` centred at
/// `(i + 0.5, j + 0.5)`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Camera {
    /// Eye point.
    pub eye: Point,
    /// The point looked at (centre of the image).
    pub target: Point,
    /// A vector pointing up in the image (orthogonal to the viewing direction).
    pub up: Point,
    /// Vertical field of view in degrees.
    pub fov_deg: f64,
    /// Image width in pixels.
    pub width: usize,
    /// Image height in pixels.
    pub height: usize,
    /// Depth of the near clipping plane.
    pub near: f64,
}

impl Camera {
    /// A look-at camera; the near plane at `1e-3` times the eye-target distance.
    pub fn look_at(
        eye: Point,
        target: Point,
        up: Point,
        fov_deg: f64,
        width: usize,
        height: usize,
    ) -> Camera {
        let near = 1e-3 * dist(eye, target).max(f64::MIN_POSITIVE);
        Camera {
            eye,
            target,
            up,
            fov_deg,
            width,
            height,
            near,
        }
    }

    /// The orthonormal basis `(right, up, forward)`.
    pub fn basis(&self) -> [Point; 3] {
        let f = normalize(sub(self.target, self.eye));
        let r = normalize(cross(f, self.up));
        let u = cross(r, f);
        [r, u, f]
    }

    /// Focal length in pixels.
    pub fn focal(&self) -> f64 {
        0.5 * self.height as f64 / (0.5 * self.fov_deg.to_radians()).tan()
    }

    /// The same view with `k` times as many pixels along each axis (the sample grid of `k x k`
    /// supersampling).
    pub fn scaled(&self, k: usize) -> Camera {
        Camera {
            width: self.width * k,
            height: self.height * k,
            ..self.clone()
        }
    }

    /// View coordinates of a point.
    pub fn to_view(&self, p: Point) -> Point {
        let [r, u, f] = self.basis();
        let d = sub(p, self.eye);
        [dot(d, r), dot(d, u), dot(d, f)]
    }

    /// Pixel coordinates `(x, y)` and depth of a point; `None` when it is not in front of the
    /// near plane.
    pub fn project(&self, p: Point) -> Option<[f64; 3]> {
        let v = self.to_view(p);
        if v[2] <= self.near {
            return None;
        }
        let s = self.focal() / v[2];
        Some([
            0.5 * self.width as f64 + s * v[0],
            0.5 * self.height as f64 - s * v[1],
            v[2],
        ])
    }

    /// The unit direction of the ray from the eye through pixel coordinates `(x, y)`.
    pub fn ray(&self, x: f64, y: f64) -> Point {
        let [r, u, f] = self.basis();
        let fl = self.focal();
        let a = (x - 0.5 * self.width as f64) / fl;
        let b = (0.5 * self.height as f64 - y) / fl;
        normalize(add(add(f, scale(r, a)), scale(u, b)))
    }
}

/// Unit vector from the region's centre to the eye for azimuth / elevation (degrees) and the
/// camera's up vector (the derivative of that direction in elevation, defined even at the
/// poles).
pub fn direction(azimuth_deg: f64, elevation_deg: f64) -> (Point, Point) {
    let (az, el) = (azimuth_deg.to_radians(), elevation_deg.to_radians());
    let d = [el.cos() * az.cos(), el.cos() * az.sin(), el.sin()];
    let up = [-el.sin() * az.cos(), -el.sin() * az.sin(), el.cos()];
    (d, up)
}

/// The camera and region for one or several scenes (a panel share both).
///
/// Each scene contributes the surface points of what must be seen ([`framing`]); the camera
/// looks from the view's direction at the first scene's centre. Unless [`View::distance`] is
/// given, the target is then moved so the projected points are centred (not with a focus or a
/// ring zoom: the limit point stays in the middle) and the distance is adjusted until they fill 92% of the
/// image's width or height. The returned region is the target with the radius of the view's
/// visible disc there, so the lights and curvature floors follow the view.
pub fn fit(
    scenes: &[&Scene],
    view: &View,
    width: usize,
    height: usize,
) -> Result<(Camera, Region)> {
    view.validate()?;
    let mut pts = Vec::new();
    let mut centre = None;
    for s in scenes {
        let (c, p) = framing(s, view)?;
        centre.get_or_insert(c);
        pts.extend(p);
    }
    let Some(mut target) = centre else {
        return Err(Error::InvalidArgument("nothing to render: no scene".into()));
    };
    let radius = pts.iter().map(|&p| dist(p, target)).fold(0.0, f64::max);
    let radius = if radius > 0.0 { radius } else { 1.0 };
    let half_y = 0.5 * view.fov_deg.to_radians();
    let half_x = (half_y.tan() * width as f64 / height as f64).atan();
    let half = half_y.min(half_x);
    let (d, up) = direction(view.azimuth_deg, view.elevation_deg);
    let make = |t: Point, dist: f64| {
        Camera::look_at(add(t, scale(d, dist)), t, up, view.fov_deg, width, height)
    };
    let mut distance = view.distance.unwrap_or(1.02 * radius / half.sin());
    if view.distance.is_none() {
        for _ in 0..6 {
            let cam = make(target, distance);
            let f = cam.focal();
            let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
            for &p in &pts {
                let v = cam.to_view(p);
                if v[2] > cam.near {
                    for k in 0..2 {
                        lo[k] = lo[k].min(f * v[k] / v[2]);
                        hi[k] = hi[k].max(f * v[k] / v[2]);
                    }
                }
            }
            if !(lo[0].is_finite() && lo[1].is_finite() && hi[0].is_finite() && hi[1].is_finite()) {
                break;
            }
            let (ext_x, ext_y) = if view.focus.is_some() || view.zoom_rings.is_some() {
                (lo[0].abs().max(hi[0].abs()), lo[1].abs().max(hi[1].abs()))
            } else {
                let [r, u, _] = cam.basis();
                let sx = 0.5 * (lo[0] + hi[0]) * distance / f;
                let sy = 0.5 * (lo[1] + hi[1]) * distance / f;
                target = add(target, add(scale(r, sx), scale(u, sy)));
                (0.5 * (hi[0] - lo[0]), 0.5 * (hi[1] - lo[1]))
            };
            let s = (ext_x / (0.46 * width as f64)).max(ext_y / (0.46 * height as f64));
            if !(s.is_finite() && s > 1e-6) {
                break;
            }
            distance *= s;
        }
    }
    let cam = make(target, distance);
    let reg = Region {
        centre: target,
        radius: distance * half.tan(),
    };
    Ok((cam, reg))
}

/// Points per patch edge sampled for framing.
const FRAME_SAMPLES: usize = 4;

/// What a scene must show under a view: a centre and surface points. Without focus or zoom,
/// the centre of the bounding box and all surface points (patches sampled on a 5 x 5 grid,
/// mesh vertices); with [`View::focus`] or [`View::zoom_rings`] the element's limit point
/// ([`focus_point`]) and all patches, or only those of rings `K..L`.
pub fn framing(scene: &Scene, view: &View) -> Result<(Point, Vec<Point>)> {
    let sample = |p: &crate::bezier::BezierPatch| {
        let n = FRAME_SAMPLES;
        (0..=n)
            .flat_map(move |i| (0..=n).map(move |j| (i, j)))
            .map(|(i, j)| p.eval(i as f64 / n as f64, j as f64 / n as f64))
            .collect::<Vec<_>>()
    };
    let pts_of = |c: &PatchComplex, sel: &mut dyn Iterator<Item = usize>| -> Vec<Point> {
        sel.flat_map(|k| sample(&c.patches[k])).collect()
    };
    let check = |centre: Point, pts: Vec<Point>| -> Result<(Point, Vec<Point>)> {
        if pts.is_empty() {
            return Err(Error::InvalidArgument(
                "nothing to render: the surface is empty".into(),
            ));
        }
        if !centre
            .iter()
            .chain(pts.iter().flatten())
            .all(|x| x.is_finite())
        {
            return Err(Error::InvalidArgument(
                "the surface has non-finite coordinates".into(),
            ));
        }
        Ok((centre, pts))
    };
    if view.focus.is_none() && view.zoom_rings.is_none() {
        let pts = match &scene.surface {
            Surface::Patches(c) => pts_of(c, &mut (0..c.len())),
            Surface::Mesh(m) => m.positions.clone(),
        };
        let Some((lo, hi)) = crate::geom::bounding_box(pts.iter().copied()) else {
            return check([0.0; 3], pts);
        };
        return check(scale(add(lo, hi), 0.5), pts);
    }
    let Surface::Patches(c) = &scene.surface else {
        return Err(Error::InvalidArgument(
            "--focus and --zoom-rings need a patch complex with provenance (give --scheme with patch output, or a .bv file)"
                .into(),
        ));
    };
    let element = match view.focus {
        Some(e) => {
            check_element(scene, e)?;
            e
        }
        None => sole_element(c)?,
    };
    let centre = focus_point(c, element)?;
    match view.zoom_rings {
        None => check(centre, pts_of(c, &mut (0..c.len()))),
        Some((k, l)) => {
            let last = last_ring(c, element);
            let sel: Vec<usize> = (0..c.len())
                .filter(|&p| match c.provenance[p] {
                    Provenance::Ring {
                        element: e, ring, ..
                    } => e == element && ring >= k && ring <= l,
                    Provenance::Cap { element: e, .. } => e == element && k <= last + 1 && l > last,
                    _ => false,
                })
                .collect();
            if sel.is_empty() {
                return Err(Error::InvalidArgument(format!(
                    "{} has no patches in rings {k}..{l} (it has rings 1..{last}{})",
                    element_name(element),
                    if has_cap(c, element) {
                        format!(", and its cap counts as ring {}", last + 1)
                    } else {
                        String::new()
                    }
                )));
            }
            let mut it = sel.into_iter();
            check(centre, pts_of(c, &mut it))
        }
    }
}

/// Errors for a focus element that is out of the net's range or has no patches.
fn check_element(scene: &Scene, e: Element) -> Result<()> {
    if let Some(net) = &scene.net {
        match e {
            Element::Vertex(v) if v as usize >= net.num_vertices() && e != BV_ELEMENT => {
                return Err(Error::InvalidArgument(format!(
                    "vertex {v} is out of range: the net has {} vertices (0..{})",
                    net.num_vertices(),
                    net.num_vertices().saturating_sub(1)
                )));
            }
            Element::Face(f) if f as usize >= net.num_faces() => {
                return Err(Error::InvalidArgument(format!(
                    "face {f} is out of range: the net has {} faces (0..{})",
                    net.num_faces(),
                    net.num_faces().saturating_sub(1)
                )));
            }
            _ => {}
        }
    }
    Ok(())
}

/// The extraordinary elements that have ring or cap patches, in order of first appearance.
pub fn elements(c: &PatchComplex) -> Vec<Element> {
    let mut out: Vec<Element> = Vec::new();
    for p in &c.provenance {
        if let Provenance::Ring { element, .. } | Provenance::Cap { element, .. } = *p
            && !out.contains(&element)
        {
            out.push(element);
        }
    }
    out
}

fn sole_element(c: &PatchComplex) -> Result<Element> {
    let els = elements(c);
    match els.as_slice() {
        [e] => Ok(*e),
        [] => Err(Error::InvalidArgument(
            "--zoom-rings: the surface has no rings of an extraordinary element".into(),
        )),
        _ => Err(Error::InvalidArgument(format!(
            "--zoom-rings: the surface has {} extraordinary elements; choose one with --focus ({})",
            els.len(),
            list_elements(&els)
        ))),
    }
}

fn list_elements(els: &[Element]) -> String {
    let names: Vec<String> = els.iter().take(12).map(|&e| element_name(e)).collect();
    let more = if els.len() > 12 { ", ..." } else { "" };
    format!("{}{more}", names.join(", "))
}

/// The last (innermost) ring number of an element (0 when it has no rings).
pub fn last_ring(c: &PatchComplex, e: Element) -> u32 {
    c.provenance
        .iter()
        .filter_map(|p| match *p {
            Provenance::Ring { element, ring, .. } if element == e => Some(ring),
            _ => None,
        })
        .max()
        .unwrap_or(0)
}

fn has_cap(c: &PatchComplex, e: Element) -> bool {
    c.provenance
        .iter()
        .any(|p| matches!(*p, Provenance::Cap { element, .. } if element == e))
}

/// The limit point of an element, found from its patches: with a cap, the corner shared by
/// the most cap patches (the centre of a fill of `n >= 3` sectors), or the centre of a single
/// cap patch; without a cap (`--no-fill`), the centroid of the corners of the innermost ring,
/// which approximates the limit point to the size of that ring. Errors when the element has no
/// patches, listing the elements that have.
pub fn focus_point(c: &PatchComplex, e: Element) -> Result<Point> {
    let cap: Vec<usize> = (0..c.len())
        .filter(|&p| matches!(c.provenance[p], Provenance::Cap { element, .. } if element == e))
        .collect();
    let corners = |p: usize| {
        let q = &c.patches[p];
        [
            q.corner(false, false),
            q.corner(true, false),
            q.corner(false, true),
            q.corner(true, true),
        ]
    };
    if cap.len() == 1 {
        return Ok(c.patches[cap[0]].eval(0.5, 0.5));
    }
    if !cap.is_empty() {
        let pts: Vec<Point> = cap.iter().flat_map(|&p| corners(p)).collect();
        let diag = crate::geom::bounding_box(pts.iter().copied())
            .map(|(lo, hi)| dist(lo, hi))
            .unwrap_or(0.0);
        let tol = 1e-9 * diag.max(f64::MIN_POSITIVE);
        let mut best = (0usize, pts[0]);
        for &q in &pts {
            let count = cap
                .iter()
                .filter(|&&p| corners(p).iter().any(|&r| dist(r, q) <= tol))
                .count();
            if count > best.0 {
                best = (count, q);
            }
        }
        if best.0 >= 3 {
            return Ok(best.1);
        }
        return Ok(crate::geom::centroid(pts));
    }
    let last = last_ring(c, e);
    let inner: Vec<Point> = (0..c.len())
        .filter(|&p| {
            matches!(c.provenance[p], Provenance::Ring { element, ring, .. } if element == e && ring == last)
        })
        .flat_map(corners)
        .collect();
    if inner.is_empty() {
        let els = elements(c);
        return Err(Error::InvalidArgument(format!(
            "no patches of {}: {}",
            element_name(e),
            if els.is_empty() {
                "the surface has no rings of any extraordinary element".to_string()
            } else if els == [BV_ELEMENT] {
                "a .bv file does not record which vertex its rings surround; use --zoom-rings without --focus".to_string()
            } else {
                format!("elements with rings: {}", list_elements(&els))
            }
        )));
    }
    Ok(crate::geom::centroid(inner))
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    #[crate::unit::test]
    fn azimuth_minus_90_puts_x_to_the_right() {
        let (d, up) = direction(-90.0, 30.0);
        let cam = Camera::look_at(scale(d, 5.0), [0.0; 3], up, 30.0, 100, 100);
        let [r, u, f] = cam.basis();
        assert!(dist(r, [1.0, 0.0, 0.0]) < 1e-12);
        assert!(u[2] > 0.0);
        assert!(dot(f, d) < -0.999_999);
        // straight down still has a basis
        let (d, up) = direction(0.0, 90.0);
        let cam = Camera::look_at(d, [0.0; 3], up, 30.0, 10, 10);
        let [r, _, _] = cam.basis();
        assert!((crate::geom::norm(r) - 1.0).abs() < 1e-12);
    }

    #[crate::unit::test]
    fn projection_and_rays_agree() {
        let (d, up) = direction(20.0, 35.0);
        let cam = Camera::look_at(scale(d, 4.0), [0.1, 0.2, 0.3], up, 40.0, 320, 200);
        let p = [0.5, -0.3, 0.2];
        let [x, y, z] = cam.project(p).unwrap();
        let dir = cam.ray(x, y);
        let q = add(cam.eye, scale(dir, dist(p, cam.eye)));
        assert!(dist(p, q) < 1e-12, "{p:?} {q:?}");
        assert!(z > 0.0);
        // the target projects to the image centre
        let [cx, cy, _] = cam.project(cam.target).unwrap();
        assert!((cx - 160.0).abs() < 1e-9 && (cy - 100.0).abs() < 1e-9);
    }

    #[crate::unit::test]
    fn parses_ring_ranges_and_elements() {
        assert_eq!(parse_rings("3..5").unwrap(), (3, 5));
        assert_eq!(parse_rings("3..=5").unwrap(), (3, 5));
        assert_eq!(parse_rings("4").unwrap(), (4, 4));
        assert!(parse_rings("0..2").is_err());
        assert!(parse_rings("5..3").is_err());
        assert!(parse_rings("a..b").is_err());
        assert_eq!(parse_element("7").unwrap(), Element::Vertex(7));
        assert_eq!(parse_element("face:2").unwrap(), Element::Face(2));
        assert!(parse_element("edge:2").is_err());
    }
}
