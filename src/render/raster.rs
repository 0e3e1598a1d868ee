//! The z-buffer: which patch, at which `(u, v)`, every sample of the image sees, and the exact
//! surface there.
//!
//! Patches are tessellated for the camera: each patch gets a grid dense enough for triangles of
//! about [`TARGET_EDGE`] samples on screen (more for patches crossing the near plane, none for
//! patches outside the view), and every side also receives the grid samples of the sides it
//! shares (from [`crate::surface::adjacency::shared_boundaries`], T-junctions included) so
//! neighbouring tessellations meet vertex to vertex and leave no cracks. Boundary quads with
//! extra points are fanned around their centre. Every vertex keeps its patch's `(u, v)`.
//!
//! Triangles are clipped against the near plane and rasterised band by band (rows in parallel,
//! each band visiting its triangles in input order, so the result never depends on threads),
//! interpolating `(u, v)` perspective-correctly. The coverage test is inclusive with a tiny
//! tolerance, so pixel centres on shared edges are never lost; equal depths keep the first
//! triangle.
//!
//! Each covered sample is then *resolved*: Newton's method on `S(u, v) - eye` projected onto two
//! directions orthogonal to the pixel ray moves the interpolated `(u, v)` to the exact
//! intersection of the ray with the Bezier patch (the tessellation only supplies the start), and
//! the exact position, unit normal ([`crate::bezier::BezierPatch::normal_from`]) and Gauss and
//! mean curvature are stored in a [`Sample`]. Plain meshes are resolved by interpolating their
//! vertex normals.

use super::{Camera, MeshSurface, Scene, Surface};
use crate::bezier::{BezierPatch, Derivatives, Side};
use crate::error::{Error, Result};
use crate::geom::{Point, add, cross, dot, norm, normalize, scale, sub};
use crate::surface::PatchComplex;
use crate::surface::adjacency::{default_tolerance, shared_boundaries};
use rayon::prelude::*;

mod resolve;

pub use resolve::ray_patch;
use resolve::{RayGen, resolve_mesh, resolve_patch};

/// `prim` of a sample that sees no surface.
pub const NONE: u32 = u32::MAX;

/// Target length of a tessellation edge on screen, in samples.
pub const TARGET_EDGE: f64 = 6.0;

/// Largest number of intervals per patch edge.
pub const MAX_INTERVALS: usize = 64;

/// Rows of samples per raster band (the unit of parallel work).
const BAND: usize = 16;

/// Barycentric tolerance of the inclusive coverage test.
const COVER_EPS: f64 = 1e-9;

/// What one sample of the image sees.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// The patch (for a plain mesh: the polygon), [`NONE`] for background.
    pub prim: u32,
    /// Domain point in the patch (for a mesh: barycentric coordinates `(b1, b2)` in its
    /// triangle).
    pub uv: [f32; 2],
    /// Surface point relative to [`Frame::origin`].
    pub p: [f32; 3],
    /// Unit normal: the patch normal `du x dv` (not flipped toward the eye); for a mesh the
    /// interpolated vertex normal.
    pub n: [f32; 3],
    /// Gauss curvature (NaN where undefined and for meshes).
    pub gauss: f32,
    /// Mean curvature, signed relative to `n` (NaN where undefined and for meshes).
    pub mean: f32,
}

impl Sample {
    /// A background sample.
    pub const EMPTY: Sample = Sample {
        prim: NONE,
        uv: [0.0; 2],
        p: [0.0; 3],
        n: [0.0; 3],
        gauss: f32::NAN,
        mean: f32::NAN,
    };

    /// Whether the sample sees the surface.
    pub fn is_covered(&self) -> bool {
        self.prim != NONE
    }

    /// The normal as `f64`.
    pub fn normal(&self) -> Point {
        self.n.map(f64::from)
    }
}

/// The samples of one picture (`width x height` samples: the image size times the
/// supersampling factor).
#[derive(Debug, Clone, PartialEq)]
pub struct Frame {
    /// Samples per row.
    pub width: usize,
    /// Rows.
    pub height: usize,
    /// Samples per pixel along each axis.
    pub supersample: usize,
    /// Positions are stored relative to this point (the camera target), so `f32` keeps them
    /// precise.
    pub origin: Point,
    /// Row-major samples, top row first.
    pub samples: Vec<Sample>,
    /// Covered samples whose `(u, v)` Newton's method moved to the exact ray intersection (the
    /// rest, at silhouettes and degenerate points, keep the interpolated `(u, v)`).
    pub exact: usize,
}

impl Frame {
    /// The sample at column `x`, row `y`.
    pub fn get(&self, x: usize, y: usize) -> &Sample {
        &self.samples[y * self.width + x]
    }

    /// The world position of a sample.
    pub fn position(&self, s: &Sample) -> Point {
        add(self.origin, s.p.map(f64::from))
    }

    /// Number of covered samples.
    pub fn covered(&self) -> usize {
        self.samples.iter().filter(|s| s.is_covered()).count()
    }
}

/// A triangle in sample coordinates with `1/z` and the attribute (`(u, v)` or barycentric)
/// at its corners.
#[derive(Debug, Clone, Copy)]
struct Tri {
    x: [f64; 3],
    y: [f64; 3],
    iz: [f64; 3],
    a: [[f64; 2]; 3],
    id: u32,
}

/// Projection from view coordinates to samples.
#[derive(Debug, Clone, Copy)]
struct Proj {
    near: f64,
    focal: f64,
    cx: f64,
    cy: f64,
    /// `tan` of the half field of view, horizontally and vertically.
    tx: f64,
    ty: f64,
}

impl Proj {
    fn new(cam: &Camera) -> Proj {
        let focal = cam.focal();
        Proj {
            near: cam.near,
            focal,
            cx: 0.5 * cam.width as f64,
            cy: 0.5 * cam.height as f64,
            tx: 0.5 * cam.width as f64 / focal,
            ty: 0.5 * cam.height as f64 / focal,
        }
    }

    fn xy(&self, v: Point) -> [f64; 2] {
        let s = self.focal / v[2];
        [self.cx + s * v[0], self.cy - s * v[1]]
    }

    /// Whether all points lie outside one side plane of the view frustum.
    fn culled(&self, vs: &[Point]) -> bool {
        vs.iter().all(|v| v[2] <= self.near)
            || vs.iter().all(|v| v[0] > self.tx * v[2])
            || vs.iter().all(|v| v[0] < -self.tx * v[2])
            || vs.iter().all(|v| v[1] > self.ty * v[2])
            || vs.iter().all(|v| v[1] < -self.ty * v[2])
    }

    /// Clips a triangle (view coordinates and attributes) against the near plane and appends
    /// the projected pieces.
    fn emit(&self, v: [(Point, [f64; 2]); 3], id: u32, out: &mut Vec<Tri>) {
        let inside = v.map(|(p, _)| p[2] > self.near);
        if inside.iter().all(|&b| b) {
            out.push(self.tri(v, id));
            return;
        }
        if !inside.iter().any(|&b| b) {
            return;
        }
        let mut poly: Vec<(Point, [f64; 2])> = Vec::with_capacity(4);
        for k in 0..3 {
            let (a, b) = (v[k], v[(k + 1) % 3]);
            let (ia, ib) = (inside[k], inside[(k + 1) % 3]);
            if ia {
                poly.push(a);
            }
            if ia != ib {
                let t = (self.near - a.0[2]) / (b.0[2] - a.0[2]);
                let p = add(a.0, scale(sub(b.0, a.0), t));
                let at = [
                    a.1[0] + t * (b.1[0] - a.1[0]),
                    a.1[1] + t * (b.1[1] - a.1[1]),
                ];
                poly.push(([p[0], p[1], self.near], at));
            }
        }
        for k in 1..poly.len().saturating_sub(1) {
            out.push(self.tri([poly[0], poly[k], poly[k + 1]], id));
        }
    }

    fn tri(&self, v: [(Point, [f64; 2]); 3], id: u32) -> Tri {
        let xy = v.map(|(p, _)| self.xy(p));
        Tri {
            x: xy.map(|q| q[0]),
            y: xy.map(|q| q[1]),
            iz: v.map(|(p, _)| 1.0 / p[2]),
            a: v.map(|(_, a)| a),
            id,
        }
    }
}

/// View-coordinate transform of a camera.
#[derive(Debug, Clone, Copy)]
struct ViewXf {
    eye: Point,
    basis: [Point; 3],
}

impl ViewXf {
    fn new(cam: &Camera) -> ViewXf {
        ViewXf {
            eye: cam.eye,
            basis: cam.basis(),
        }
    }

    fn apply(&self, p: Point) -> Point {
        let d = sub(p, self.eye);
        [
            dot(d, self.basis[0]),
            dot(d, self.basis[1]),
            dot(d, self.basis[2]),
        ]
    }
}

/// Intervals per edge for a patch: 0 when it is outside the view, [`MAX_INTERVALS`] when it
/// crosses the near plane, else enough for edges of [`TARGET_EDGE`] samples along the longest
/// projected row or column of its control net (which bounds the projected curve length).
fn intervals(patch: &BezierPatch, xf: &ViewXf, pr: &Proj) -> usize {
    let vs: Vec<Point> = patch.cps.iter().map(|&p| xf.apply(p)).collect();
    if pr.culled(&vs) {
        return 0;
    }
    if vs.iter().any(|v| v[2] <= pr.near) {
        return MAX_INTERVALS;
    }
    let xy: Vec<[f64; 2]> = vs.iter().map(|&v| pr.xy(v)).collect();
    let (nu, nv) = (patch.deg_u + 1, patch.deg_v + 1);
    let len = |a: [f64; 2], b: [f64; 2]| ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt();
    let mut longest: f64 = 0.0;
    for i in 0..nu {
        let l: f64 = (1..nv)
            .map(|j| len(xy[i * nv + j - 1], xy[i * nv + j]))
            .sum();
        longest = longest.max(l);
    }
    for j in 0..nv {
        let l: f64 = (1..nu)
            .map(|i| len(xy[(i - 1) * nv + j], xy[i * nv + j]))
            .sum();
        longest = longest.max(l);
    }
    if !longest.is_finite() {
        return MAX_INTERVALS;
    }
    ((longest / TARGET_EDGE).ceil() as usize).clamp(1, MAX_INTERVALS)
}

/// Parameters closer than this are one sample.
const PARAM_EPS: f64 = 1e-9;

/// The triangles of a patch complex for a camera (see the module notes).
fn patch_triangles(c: &PatchComplex, cam: &Camera) -> Vec<Tri> {
    let (xf, pr) = (ViewXf::new(cam), Proj::new(cam));
    let n: Vec<usize> = c
        .patches
        .par_iter()
        .map(|p| intervals(p, &xf, &pr))
        .collect();
    // extra samples of every side (index 4 p + side) from the sides it shares
    let mut extra: Vec<Vec<f64>> = vec![Vec::new(); 4 * c.len()];
    if n.iter().any(|&k| k > 0) {
        for r in shared_boundaries(c, default_tolerance(c)) {
            let (na, nb) = (n[r.a].max(1), n[r.b].max(1));
            let ka = 4 * r.a + r.side_a.index();
            let kb = 4 * r.b + r.side_b.index();
            for k in 0..=nb {
                extra[ka].push(r.map_to_a(k as f64 / nb as f64));
            }
            for k in 0..=na {
                let g = k as f64 / na as f64;
                if g >= r.t[0] - PARAM_EPS && g <= r.t[1] + PARAM_EPS {
                    extra[kb].push(r.map_to_b(g));
                }
            }
        }
    }
    let per_patch: Vec<Vec<Tri>> = (0..c.len())
        .into_par_iter()
        .map(|p| {
            if n[p] == 0 {
                return Vec::new();
            }
            let sides: [Vec<f64>; 4] =
                std::array::from_fn(|s| clean_extras(n[p], &extra[4 * p + s]));
            one_patch(&c.patches[p], p as u32, n[p], &sides, &xf, &pr)
        })
        .collect();
    per_patch.into_iter().flatten().collect()
}

/// Sorted extra parameters strictly inside `(0, 1)` that are not grid samples `k / n`.
fn clean_extras(n: usize, e: &[f64]) -> Vec<f64> {
    let mut v: Vec<f64> = e
        .iter()
        .copied()
        .filter(|&t| t > PARAM_EPS && t < 1.0 - PARAM_EPS)
        .filter(|&t| {
            let g = (t * n as f64).round() / n as f64;
            (t - g).abs() > PARAM_EPS
        })
        .collect();
    v.sort_by(f64::total_cmp);
    v.dedup_by(|a, b| (*a - *b).abs() <= PARAM_EPS);
    v
}

/// Triangulates one patch on an `n x n` grid with extra samples on its sides.
fn one_patch(
    patch: &BezierPatch,
    id: u32,
    n: usize,
    sides: &[Vec<f64>; 4],
    xf: &ViewXf,
    pr: &Proj,
) -> Vec<Tri> {
    let nf = n as f64;
    let vert = |u: f64, v: f64| (xf.apply(patch.eval(u, v)), [u, v]);
    let grid: Vec<(Point, [f64; 2])> = (0..=n)
        .flat_map(|i| (0..=n).map(move |j| (i, j)))
        .map(|(i, j)| vert(i as f64 / nf, j as f64 / nf))
        .collect();
    let g = |i: usize, j: usize| grid[i * (n + 1) + j];
    // extra points of a side between grid samples k and k + 1, increasing
    let between = |side: Side, k: usize| -> Vec<(Point, [f64; 2])> {
        let e = &sides[side.index()];
        let (lo, hi) = (k as f64 / nf, (k + 1) as f64 / nf);
        let a = e.partition_point(|&t| t <= lo);
        let b = e.partition_point(|&t| t < hi);
        e[a..b]
            .iter()
            .map(|&t| {
                let [u, v] = side.domain_point(t);
                vert(u, v)
            })
            .collect()
    };
    let mut out = Vec::with_capacity(2 * n * n + 8);
    for i in 0..n {
        for j in 0..n {
            let mut ring = vec![g(i, j)];
            if j == 0 {
                ring.extend(between(Side::V0, i));
            }
            ring.push(g(i + 1, j));
            if i + 1 == n {
                ring.extend(between(Side::U1, j));
            }
            ring.push(g(i + 1, j + 1));
            if j + 1 == n {
                ring.extend(between(Side::V1, i).into_iter().rev());
            }
            ring.push(g(i, j + 1));
            if i == 0 {
                ring.extend(between(Side::U0, j).into_iter().rev());
            }
            if ring.len() == 4 {
                pr.emit([ring[0], ring[1], ring[2]], id, &mut out);
                pr.emit([ring[0], ring[2], ring[3]], id, &mut out);
            } else {
                let centre = vert((i as f64 + 0.5) / nf, (j as f64 + 0.5) / nf);
                for k in 0..ring.len() {
                    pr.emit([ring[k], ring[(k + 1) % ring.len()], centre], id, &mut out);
                }
            }
        }
    }
    out
}

/// The triangles of a plain mesh; attributes are barycentric coordinates.
fn mesh_triangles(m: &MeshSurface, cam: &Camera) -> Vec<Tri> {
    let (xf, pr) = (ViewXf::new(cam), Proj::new(cam));
    let vs: Vec<Point> = m.positions.iter().map(|&p| xf.apply(p)).collect();
    let mut out = Vec::with_capacity(m.triangles.len());
    for (t, tri) in m.triangles.iter().enumerate() {
        let corners = tri.map(|k| vs[k as usize]);
        if pr.culled(&corners) {
            continue;
        }
        pr.emit(
            [
                (corners[0], [0.0, 0.0]),
                (corners[1], [1.0, 0.0]),
                (corners[2], [0.0, 1.0]),
            ],
            t as u32,
            &mut out,
        );
    }
    out
}

/// Rasterises and resolves a scene: `camera` is the picture's camera, `supersample` the samples
/// per pixel along each axis.
pub fn rasterize(scene: &Scene, camera: &Camera, supersample: usize) -> Result<Frame> {
    let ss = supersample.max(1);
    let cam = camera.scaled(ss);
    let (w, h) = (cam.width, cam.height);
    if w == 0 || h == 0 {
        return Err(Error::InvalidArgument(format!(
            "cannot render an image of {w}x{h} samples"
        )));
    }
    if let Surface::Mesh(m) = &scene.surface
        && let Some(&bad) = m
            .triangles
            .iter()
            .flatten()
            .find(|&&k| k as usize >= m.positions.len() || k as usize >= m.normals.len())
    {
        return Err(Error::InvalidArgument(format!(
            "mesh triangle refers to vertex {bad}, but the mesh has {} vertices",
            m.positions.len()
        )));
    }
    let tris = match &scene.surface {
        Surface::Patches(c) => patch_triangles(c, &cam),
        Surface::Mesh(m) => mesh_triangles(m, &cam),
    };
    // bin triangles into bands, in input order
    let nbands = h.div_ceil(BAND);
    let mut bins: Vec<Vec<u32>> = vec![Vec::new(); nbands];
    for (k, t) in tris.iter().enumerate() {
        let lo = t.y.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = t.y.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        if !(lo.is_finite() && hi.is_finite()) || hi < 0.5 || lo > h as f64 - 0.5 {
            continue;
        }
        let b0 = ((lo - 0.5).ceil().max(0.0) as usize) / BAND;
        let b1 = (((hi - 0.5).floor().max(0.0) as usize).min(h - 1)) / BAND;
        for bin in &mut bins[b0..=b1.min(nbands - 1)] {
            bin.push(k as u32);
        }
    }
    let rays = RayGen::new(&cam);
    let origin = camera.target;
    let mut samples = vec![Sample::EMPTY; w * h];
    let exact: usize = samples
        .par_chunks_mut(BAND * w)
        .enumerate()
        .map(|(b, chunk)| {
            let y0 = b * BAND;
            let rows = chunk.len() / w;
            let mut depth = vec![0.0f64; chunk.len()];
            let mut prim = vec![NONE; chunk.len()];
            let mut attr = vec![[0.0f64; 2]; chunk.len()];
            for &t in &bins[b] {
                raster_tri(
                    &tris[t as usize],
                    w,
                    y0,
                    rows,
                    &mut depth,
                    &mut prim,
                    &mut attr,
                );
            }
            let mut exact = 0;
            for k in 0..chunk.len() {
                if prim[k] == NONE {
                    continue;
                }
                let (x, y) = ((k % w) as f64 + 0.5, (y0 + k / w) as f64 + 0.5);
                let dir = rays.dir(x, y);
                let (s, ok) = match &scene.surface {
                    Surface::Patches(c) => resolve_patch(
                        &c.patches[prim[k] as usize],
                        prim[k],
                        &rays,
                        dir,
                        attr[k],
                        origin,
                    ),
                    Surface::Mesh(m) => (resolve_mesh(m, prim[k], attr[k], origin), true),
                };
                chunk[k] = s;
                exact += ok as usize;
            }
            exact
        })
        .sum();
    Ok(Frame {
        width: w,
        height: h,
        supersample: ss,
        origin,
        samples,
        exact,
    })
}

/// Writes one triangle into a band's buffers (inclusive coverage, nearer `1/z` wins, first
/// triangle wins ties).
fn raster_tri(
    t: &Tri,
    w: usize,
    y0: usize,
    rows: usize,
    depth: &mut [f64],
    prim: &mut [u32],
    attr: &mut [[f64; 2]],
) {
    let [x0, x1, x2] = t.x;
    let [ya, yb, yc] = t.y;
    let area = (x1 - x0) * (yc - ya) - (x2 - x0) * (yb - ya);
    if area.is_nan() || area.abs() <= 1e-14 {
        return;
    }
    let inv = 1.0 / area;
    let min = |a: f64, b: f64, c: f64| a.min(b).min(c);
    let max = |a: f64, b: f64, c: f64| a.max(b).max(c);
    let (lx, hx) = (min(x0, x1, x2), max(x0, x1, x2));
    let (ly, hy) = (min(ya, yb, yc), max(ya, yb, yc));
    let px0 = (lx - 0.5).ceil().max(0.0);
    let px1 = (hx - 0.5).floor().min(w as f64 - 1.0);
    let py0 = (ly - 0.5).ceil().max(y0 as f64);
    let py1 = (hy - 0.5).floor().min((y0 + rows) as f64 - 1.0);
    if px0 > px1 || py0 > py1 {
        return;
    }
    let (px0, px1, py0, py1) = (px0 as usize, px1 as usize, py0 as usize, py1 as usize);
    let az = [
        [t.a[0][0] * t.iz[0], t.a[0][1] * t.iz[0]],
        [t.a[1][0] * t.iz[1], t.a[1][1] * t.iz[1]],
        [t.a[2][0] * t.iz[2], t.a[2][1] * t.iz[2]],
    ];
    for py in py0..=py1 {
        let cy = py as f64 + 0.5;
        let row = (py - y0) * w;
        for px in px0..=px1 {
            let cx = px as f64 + 0.5;
            let w0 = ((x2 - x1) * (cy - yb) - (yc - yb) * (cx - x1)) * inv;
            let w1 = ((x0 - x2) * (cy - yc) - (ya - yc) * (cx - x2)) * inv;
            let w2 = ((x1 - x0) * (cy - ya) - (yb - ya) * (cx - x0)) * inv;
            if w0 < -COVER_EPS || w1 < -COVER_EPS || w2 < -COVER_EPS {
                continue;
            }
            let iz = w0 * t.iz[0] + w1 * t.iz[1] + w2 * t.iz[2];
            let k = row + px;
            if iz > depth[k] {
                depth[k] = iz;
                prim[k] = t.id;
                attr[k] = [
                    (w0 * az[0][0] + w1 * az[1][0] + w2 * az[2][0]) / iz,
                    (w0 * az[0][1] + w1 * az[1][1] + w2 * az[2][1]) / iz,
                ];
            }
        }
    }
}
