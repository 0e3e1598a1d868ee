//! Closest points on the exact surface and the inverse of evaluation: for a point `q` in
//! space, the nearest point of a [`Surface`] with its input-face parameters `(face, u, v)`
//! (those [`Surface::evaluate`] takes), distance and normal (`fairsub project`,
//! `fairsub check --against`).
//!
//! # The search
//!
//! The surface is cut into charts, one per cell of the evaluation index (`eval::charts`),
//! each with a box that holds it (its patches' control points: the convex hull property) and
//! a grid of sample points. An R*-tree (the `rstar` crate) over the boxes yields the charts in
//! increasing box distance from `q`; that distance is a lower bound of the chart's, so the
//! search stops at the first box farther than the best point found (branch and bound). Within
//! the charts it reaches, the samples give an upper bound; a chart whose samples come within
//! its sample spacing of the best distance is bounded more tightly by the triangles of its
//! sample grid less the surface's measured deviation from them (`linear`), and the charts
//! whose bound is below the best distance found get, nearest first, a Newton search
//! (`newton`) from the closest point of those triangles, minimising `|S(x) - q|^2` over the
//! local coordinates of the chart's face (it may leave the cell, not the face), with the
//! face's domain as a box or triangle constraint. The result is the evaluation at the parameters found, so
//! `evaluate(face, u, v)` returns exactly the point reported.
//!
//! At an interior minimum the residual `q - S` is orthogonal to the surface (to rounding,
//! `1e-12` relative here); at a point of the surface's boundary it is orthogonal to the
//! boundary curve only (`on_boundary`).

mod linear;
mod newton;

use super::eval::Surface;
use super::eval::charts::{Chart, Local};
use crate::bezier::domain::Shape;
use crate::error::Result;
use crate::geom::{Point, dist};
use rayon::prelude::*;
use rstar::RTree;
use rstar::primitives::{GeomWithData, Rectangle};
use serde::Serialize;

/// Samples per side of a quad chart's grid (and of a triangle chart's).
const GRID: usize = 5;

/// The nearest point of the surface to a query point.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct Closest {
    /// The input face.
    pub face: u32,
    /// The face parameter `u` (as [`Surface::evaluate`] takes it).
    pub u: f64,
    /// The face parameter `v`.
    pub v: f64,
    /// The point of the surface.
    pub point: Point,
    /// Its distance to the query point.
    pub distance: f64,
    /// The unit normal there.
    pub normal: Point,
    /// Whether the point lies on the boundary of the face's domain with the residual not
    /// orthogonal to the surface (the surface's own boundary, or a point no patch reaches).
    pub on_boundary: bool,
}

type Boxed = GeomWithData<Rectangle<[f64; 3]>, u32>;

/// A sample: its local point and position.
type Sample = ([f64; 2], Point);

/// The charts, their boxes in an R*-tree and their sample grids: what
/// [`Surface::closest_point`] searches (built once per surface).
#[derive(Debug, Clone)]
pub struct ProjectionIndex {
    charts: Vec<Chart>,
    tree: RTree<Boxed>,
    /// Samples of chart `c`: `samples[start[c] .. start[c + 1]]`, local point and position.
    samples: Vec<([f64; 2], Point)>,
    start: Vec<u32>,
    /// The largest distance between neighbouring samples of each chart (diagonals included).
    spacing: Vec<f64>,
    /// How far each chart's surface strays from the triangles of its sample grid (twice the
    /// largest deviation measured, [`linear`]); NaN where a sample is missing.
    deviation: Vec<f64>,
    /// The triangles of a quad chart's grid and of a triangle chart's ([`linear::triangles`]).
    triangles: [Vec<[usize; 3]>; 2],
}

/// The sample grid of a cell in its own coordinates, with each sample's grid indices.
fn grid(shape: crate::bezier::domain::Shape) -> Vec<(usize, usize, [f64; 2])> {
    let n = (GRID - 1) as f64;
    let mut out = Vec::new();
    for i in 0..GRID {
        for j in 0..GRID {
            if shape == crate::bezier::domain::Shape::Quad || i + j < GRID {
                out.push((i, j, [i as f64 / n, j as f64 / n]));
            }
        }
    }
    out
}

impl ProjectionIndex {
    /// The index of `s`.
    pub fn new(s: &Surface) -> ProjectionIndex {
        let charts = s.charts();
        let per: Vec<(Vec<Sample>, f64, f64)> = charts
            .par_iter()
            .map(|c| {
                let grid: Vec<(usize, usize, Option<Sample>)> = grid(c.shape)
                    .into_iter()
                    .map(|(i, j, g)| {
                        let p = clamp_local(c.local, c.cell.apply(g));
                        let e = s.derivatives_local(c.face, c.sub, p).ok();
                        (i, j, e.map(|e| (p, e.p)))
                    })
                    .collect();
                // the largest distance between grid neighbours (diagonals included): every
                // point over a grid cell lies about that close to one of its corners
                let mut r: f64 = 0.0;
                for (i, j, a) in &grid {
                    for (k, l, b) in &grid {
                        if let (Some(a), Some(b)) = (a, b)
                            && i.abs_diff(*k) <= 1
                            && j.abs_diff(*l) <= 1
                        {
                            r = r.max(dist(a.1, b.1));
                        }
                    }
                }
                let complete = grid.iter().all(|x| x.2.is_some());
                let samples: Vec<Sample> = grid.into_iter().filter_map(|x| x.2).collect();
                let dev = if complete {
                    linear_deviation(s, c, &samples, &linear::triangles(c.shape, GRID))
                } else {
                    f64::NAN
                };
                (samples, r, dev)
            })
            .collect();
        let spacing = per.iter().map(|x| x.1).collect();
        let deviation = per.iter().map(|x| x.2).collect();
        let mut start = Vec::with_capacity(per.len() + 1);
        let mut samples = Vec::new();
        for (p, ..) in per {
            start.push(samples.len() as u32);
            samples.extend(p);
        }
        start.push(samples.len() as u32);
        let boxes = charts
            .iter()
            .enumerate()
            .map(|(i, c)| GeomWithData::new(Rectangle::from_corners(c.bbox.0, c.bbox.1), i as u32))
            .collect();
        ProjectionIndex {
            charts,
            tree: RTree::bulk_load(boxes),
            samples,
            start,
            spacing,
            deviation,
            triangles: [
                linear::triangles(Shape::Quad, GRID),
                linear::triangles(Shape::Triangle, GRID),
            ],
        }
    }

    /// The lower bound of chart `c`'s distance to `q` by its triangles (see [`linear`]) and
    /// the local point of the closest point on them; `None` for a chart without them.
    fn linear_bound(&self, c: usize, q: Point) -> Option<(f64, [f64; 2])> {
        let dev = self.deviation[c];
        if !dev.is_finite() {
            return None;
        }
        let samples = self.samples_of(c);
        let tris = &self.triangles[usize::from(self.charts[c].shape == Shape::Triangle)];
        let mut best = (f64::INFINITY, [0.0; 2]);
        for t in tris {
            let pos = t.map(|i| samples[i].1);
            let w = linear::closest_on_triangle(q, pos);
            let d2 = dist2(linear::combine(w, pos), q);
            if d2 < best.0 {
                best = (d2, linear::combine_local(w, t.map(|i| samples[i].0)));
            }
        }
        Some((best.0.sqrt() - dev, best.1))
    }

    fn samples_of(&self, c: usize) -> &[([f64; 2], Point)] {
        &self.samples[self.start[c] as usize..self.start[c + 1] as usize]
    }

    /// The nearest point of `s` (whose index this is) to `q`; `None` for a surface without
    /// charts or a query that is not finite.
    pub fn closest(&self, s: &Surface, q: Point) -> Option<Closest> {
        if !q.iter().all(|x| x.is_finite()) {
            return None;
        }
        // the charts within reach, with their best sample, until the boxes are farther than
        // the best sample found (the true distance is at most that)
        let mut upper = f64::INFINITY;
        let mut cands: Vec<(f64, usize, usize)> = Vec::new();
        for (b, d2) in self.tree.nearest_neighbor_iter_with_distance_2(q) {
            if d2 > upper * upper {
                break;
            }
            let c = b.data as usize;
            let best = self
                .samples_of(c)
                .iter()
                .enumerate()
                .map(|(k, (_, p))| (dist2(*p, q), k))
                .min_by(|a, b| a.0.total_cmp(&b.0));
            if let Some((d2s, k)) = best {
                let d = d2s.sqrt();
                upper = upper.min(d);
                cands.push((d - self.spacing[c], c, k));
            }
        }
        // the charts that may come closer than the best sample, bounded by their triangles
        // where they have them, started from the closest point of those
        let mut cands: Vec<(f64, usize, [f64; 2])> = cands
            .into_iter()
            .filter(|&(lower, ..)| lower <= upper)
            .map(|(lower, c, k)| match self.linear_bound(c, q) {
                Some((l, start)) => (l.max(lower), c, start),
                None => (lower, c, self.samples_of(c)[k].0),
            })
            .collect();
        cands.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut best: Option<(f64, newton::Found)> = None;
        for &(lower, c, start) in &cands {
            if best.as_ref().is_some_and(|(d, _)| lower >= *d) {
                break;
            }
            let chart = &self.charts[c];
            if let Some(found) = newton::minimise(s, c, chart, start, q) {
                let d = dist(found.point, q);
                if best.as_ref().is_none_or(|(bd, _)| d < *bd) {
                    best = Some((d, found));
                }
            }
        }
        let (_, f) = best?;
        let chart = &self.charts[f.chart];
        let [u, v] = s.face_params(chart.face, chart.sub, f.local);
        let e = s.evaluate(chart.face, u, v).ok()?;
        Some(Closest {
            face: chart.face,
            u,
            v,
            point: e.point,
            distance: dist(e.point, q),
            normal: e.normal,
            on_boundary: f.on_boundary,
        })
    }
}

/// Twice the largest distance, at the centroids and edge midpoints of the grid's triangles
/// `tris`, between chart `c`'s surface and the linear interpolant of its `samples` (the full
/// grid, in grid order) at the same local point ([`linear`]).
fn linear_deviation(s: &Surface, c: &Chart, samples: &[Sample], tris: &[[usize; 3]]) -> f64 {
    let third = 1.0 / 3.0;
    let at = [
        [third, third, third],
        [0.5, 0.5, 0.0],
        [0.0, 0.5, 0.5],
        [0.5, 0.0, 0.5],
    ];
    let mut dev: f64 = 0.0;
    for t in tris {
        let (local, pos) = (t.map(|i| samples[i].0), t.map(|i| samples[i].1));
        for w in at {
            let x = clamp_local(c.local, linear::combine_local(w, local));
            match s.derivatives_local(c.face, c.sub, x) {
                Ok(e) => dev = dev.max(dist(e.p, linear::combine(w, pos))),
                Err(_) => return f64::NAN,
            }
        }
    }
    2.0 * dev
}

/// The squared distance of two points.
fn dist2(a: Point, b: Point) -> f64 {
    let d = crate::geom::sub(a, b);
    crate::geom::dot(d, d)
}

/// `p` moved into the local domain.
fn clamp_local(local: Local, p: [f64; 2]) -> [f64; 2] {
    newton::project(local, p)
}

impl Surface {
    /// The index [`Surface::closest_point`] searches (built on first use, in parallel).
    pub fn projection_index(&self) -> &ProjectionIndex {
        self.projection.get_or_init(|| ProjectionIndex::new(self))
    }

    /// The nearest point of the surface to `q`, with its input-face parameters (see the
    /// [module](self) documentation); `None` when the surface has no evaluable patch or `q`
    /// is not finite.
    pub fn closest_point(&self, q: Point) -> Option<Closest> {
        self.projection_index().closest(self, q)
    }

    /// [`Surface::closest_point`] of many points, in parallel, in the order of `points`.
    pub fn closest_points(&self, points: &[Point]) -> Vec<Option<Closest>> {
        let index = self.projection_index();
        points
            .par_iter()
            .with_min_len(256)
            .map(|&q| index.closest(self, q))
            .collect()
    }
}

/// Nothing to search: the error of a query on a surface without charts.
pub fn no_chart() -> crate::error::Error {
    crate::error::Error::InvalidArgument(
        "the surface has no patch that carries an input-face domain: nothing to project onto"
            .into(),
    )
}

/// [`Surface::closest_points`], failing with [`no_chart`] (or naming the point) where a
/// point has no closest point.
///
/// # Errors
/// A point that is not finite (named by its index), or a surface without charts.
pub fn closest_points(s: &Surface, points: &[Point]) -> Result<Vec<Closest>> {
    let out = s.closest_points(points);
    out.into_iter()
        .enumerate()
        .map(|(i, c)| {
            c.ok_or_else(|| {
                if points[i].iter().all(|x| x.is_finite()) {
                    no_chart()
                } else {
                    crate::error::Error::InvalidArgument(format!(
                        "point {}: {:?} is not a finite point",
                        i + 1,
                        points[i]
                    ))
                }
            })
        })
        .collect()
}

/// How far points (a scan's, another surface's vertices) lie from the surface
/// (`fairsub check --against`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Deviation {
    /// Number of points.
    pub points: usize,
    /// Largest distance.
    pub max: f64,
    /// Mean distance.
    pub mean: f64,
    /// Root mean square distance.
    pub rms: f64,
    /// The point farthest from the surface (its index among the points).
    pub max_index: usize,
    /// That point.
    pub max_point: Point,
    /// Its closest point on the surface.
    pub max_closest: Closest,
}

/// The [`Deviation`] of `points` from `s`.
///
/// # Errors
/// Those of [`closest_points`]; no points.
pub fn deviation(s: &Surface, points: &[Point]) -> Result<Deviation> {
    if points.is_empty() {
        return Err(crate::error::Error::InvalidArgument(
            "no points to measure the deviation of".into(),
        ));
    }
    let found = closest_points(s, points)?;
    let n = found.len() as f64;
    let (k, far) = found
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.distance.total_cmp(&b.1.distance))
        .expect("points");
    Ok(Deviation {
        points: found.len(),
        max: far.distance,
        mean: found.iter().map(|c| c.distance).sum::<f64>() / n,
        rms: (found.iter().map(|c| c.distance * c.distance).sum::<f64>() / n).sqrt(),
        max_index: k,
        max_point: points[k],
        max_closest: *far,
    })
}
