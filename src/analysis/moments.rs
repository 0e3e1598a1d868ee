//! Exact moments of a patch complex: area, enclosed volume, centroids and inertia tensors,
//! integrated patch by patch from the Bezier coefficients (`fairsub measure`).
//!
//! # What is integrated, and why it is exact
//!
//! With `X(u, v)` a patch of bi-degree `(m, n)` and `N = X_u x X_v` (bi-degree
//! `(2m - 1, 2n - 1)`), the divergence theorem turns the volume integrals of a closed,
//! consistently oriented surface into surface integrals of polynomials:
//!
//! * volume `V = 1/3 int X . N` (bi-degree `3m - 1`),
//! * first moments `int_V x = 1/2 int x^2 N_x` (and `y`, `z` alike; `4m - 1`),
//! * second moments `int_V x^2 = 1/3 int x^3 N_x`, `int_V x y = 1/2 int x^2 y N_x`,
//!   `int_V x z = 1/2 int x^2 z N_x`, `int_V y z = 1/2 int y^2 z N_y` (`5m - 1`),
//!
//! so the tensor Gauss-Legendre rule of `ceil(5m / 2) x ceil(5n / 2)` points integrates every
//! one of them exactly (a `q`-point rule is exact to degree `2q - 1`): the only error is
//! floating-point rounding. Triangular patches are integrated as the collapsed tensor patches
//! `T(u (1 - v), v)` fairsub stores them as (Loop, non-box; a `.bv` file's type 3 patches are
//! converted so): the same rule on the collapsed square is Stroud's conical product rule on
//! the triangle, exact for the same reason.
//!
//! A rational patch (a `.bv` file's type 8 with unequal weights) has rational integrands: no
//! finite rule is exact for them either, so its terms are integrated like the area below,
//! split until two rules agree to the tolerance (relative to the patch's area times the
//! coordinates' scale to each term's degree); [`Measurement::rational`] counts such patches.
//!
//! The area element `|N|` is the square root of a polynomial, not a polynomial: no finite
//! rule integrates it exactly. It is analytic wherever `N != 0`, so Gauss-Legendre converges
//! geometrically; each patch (or part of one) is integrated with the rule above and with the
//! same rule on its four quarters, and split further until the two agree to `tolerance`
//! (relative, `1e-14` by default; at most [`MAX_DEPTH`] levels, which only degenerate corners
//! where `N` vanishes need). "Exact" for the area, the area centroid and the shell's inertia
//! thus means: to the stated tolerance, with the estimated error (the sum of the differences
//! at the accepted parts) reported as `area_error`. Its convergence is measured in this
//! module's tests and in `docs/guide/src/measure-and-project.md`.
//!
//! # Closed and open surfaces
//!
//! The volume needs a closed, consistently oriented surface: every non-collapsed patch side
//! shared with another patch ([`adjacency::open_sides`] empty; T-junctions count as shared) and
//! no shared piece along which two patches' orientations disagree
//! ([`adjacency::orientation_conflicts`]). Otherwise `volume` is `None` and only the surface
//! quantities (area, area centroid, shell inertia) are reported. A closed surface oriented
//! inward gives a negative `1/3 int X . N`; its volume moments are reported with the sign
//! turned (and `outward: false`). `closure` (`|int N| / area`, zero on a closed surface up to
//! rounding) is reported in either case: it measures how watertight the complex is.
//!
//! Moments are taken about the centre of the control points' bounding box (shifted back at the
//! end) to keep the second moments free of cancellation; patches are integrated in parallel
//! and summed in patch order (the result does not depend on the number of threads).

mod faces;
pub mod quadrature;

pub use faces::{FaceAreas, face_areas, fan_face_areas};

use crate::bezier::BezierPatch;
use crate::geom::{Point, dot, norm};
use crate::surface::PatchComplex;
use crate::surface::adjacency;
use quadrature::{Columns, Sample, for_each_sample};
use rayon::prelude::*;
use serde::Serialize;

/// Levels an area integral splits a patch into quarters at most.
pub const MAX_DEPTH: usize = 24;

/// The default relative tolerance of the area integrals.
pub const AREA_TOLERANCE: f64 = 1e-14;

/// The volume moments of a closed surface (unit density).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct VolumeMoments {
    /// Enclosed volume.
    pub volume: f64,
    /// Centre of mass of the solid.
    pub centroid: Point,
    /// Inertia tensor about the centroid, `int (|r|^2 I - r r^T) dV`, `r = x - centroid`.
    pub inertia: [[f64; 3]; 3],
    /// Its eigenvalues (principal moments), ascending.
    pub principal_moments: [f64; 3],
    /// Whether the patches' normals (`du x dv`) point out of the solid.
    pub outward: bool,
}

/// The moments of a patch complex ([`measure`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Measurement {
    /// Number of patches.
    pub patches: usize,
    /// Whether the complex is a closed, consistently oriented surface (see the module doc).
    pub closed: bool,
    /// Non-collapsed patch sides no other patch shares (0 on a closed surface).
    pub open_sides: usize,
    /// Shared pieces along which two patches' orientations disagree.
    pub orientation_conflicts: usize,
    /// Surface area.
    pub area: f64,
    /// Estimated absolute error of the area quadrature.
    pub area_error: f64,
    /// Centroid of the surface (unit area density).
    pub area_centroid: Point,
    /// Inertia tensor of the surface as a shell of unit area density, about `area_centroid`.
    pub area_inertia: [[f64; 3]; 3],
    /// `|int N dA| / area`: zero (to rounding) on a closed surface.
    pub closure: f64,
    /// The volume moments, for a closed surface (`None` for an open one).
    pub volume: Option<VolumeMoments>,
    /// Gauss-Legendre points per direction used for each bi-degree `(m, n)` present:
    /// `[m, n, qu, qv]`.
    pub rules: Vec<[usize; 4]>,
    /// Rational patches: their volume moments are integrated to the area's tolerance, not
    /// exactly (see the module documentation).
    pub rational: usize,
}

/// Options of [`measure`].
#[derive(Debug, Clone, Copy)]
pub struct MeasureOptions {
    /// Relative tolerance of the area integrals ([`AREA_TOLERANCE`] by default).
    pub area_tolerance: f64,
}

impl Default for MeasureOptions {
    fn default() -> Self {
        MeasureOptions {
            area_tolerance: AREA_TOLERANCE,
        }
    }
}

/// Points per direction of the exact rule for degree `d`: the fifth moments have degree
/// `5 d - 1` along that direction, so `ceil(5 d / 2)` points.
pub fn exact_points(d: usize) -> usize {
    (5 * d).div_ceil(2).max(1)
}

/// The ten polynomial moments (volume, three first and six second moments, in the order
/// `1, x, y, z, xx, yy, zz, xy, xz, yz`) and the vector `N` of one sample.
fn exact_terms(s: &Sample) -> [f64; 13] {
    let ([x, y, z], n) = (s.p, s.n);
    [
        dot(s.p, n) / 3.0,
        0.5 * x * x * n[0],
        0.5 * y * y * n[1],
        0.5 * z * z * n[2],
        x * x * x * n[0] / 3.0,
        y * y * y * n[1] / 3.0,
        z * z * z * n[2] / 3.0,
        0.5 * x * x * y * n[0],
        0.5 * x * x * z * n[0],
        0.5 * y * y * z * n[1],
        n[0],
        n[1],
        n[2],
    ]
}

/// The ten area-weighted moments of one sample (order `1, x, y, z, xx, yy, zz, xy, xz, yz`).
fn area_terms(s: &Sample) -> [f64; 10] {
    let a = norm(s.n);
    let [x, y, z] = s.p;
    [
        a,
        a * x,
        a * y,
        a * z,
        a * x * x,
        a * y * y,
        a * z * z,
        a * x * y,
        a * x * z,
        a * y * z,
    ]
}

/// Sums `terms` over `rule` on `patch`.
fn integrate<const K: usize>(
    patch: &BezierPatch,
    rule: &Columns,
    terms: impl Fn(&Sample) -> [f64; K],
) -> [f64; K] {
    let mut acc = [0.0; K];
    for_each_sample(patch, rule, |s, w| {
        for (a, t) in acc.iter_mut().zip(terms(&s)) {
            *a += w * t;
        }
    });
    acc
}

/// A part of a patch's domain an area integral covers: a rectangle, or the triangle below the
/// diagonal of a square (`v - lo[1] <= u - lo[0]`).
#[derive(Debug, Clone, Copy)]
pub(crate) enum Region {
    Rect([f64; 2], [f64; 2]),
    Lower([f64; 2], f64),
}

impl Region {
    /// The whole domain.
    pub(crate) const WHOLE: Region = Region::Rect([0.0, 0.0], [1.0, 1.0]);

    /// The rule with `q` points per direction (per collapsed direction: `q + n` along the
    /// triangle's `u`, where its Jacobian and `v = u t` raise the degree).
    fn rule(&self, qu: usize, qv: usize) -> Columns {
        match *self {
            Region::Rect(lo, hi) => quadrature::rectangle(lo, hi, qu, qv),
            Region::Lower(lo, s) => quadrature::lower_triangle(qu + qv, qv)
                .into_iter()
                .map(|(x, col)| {
                    let col = col
                        .into_iter()
                        .map(|(y, w)| (lo[1] + s * y, w * s * s))
                        .collect();
                    (lo[0] + s * x, col)
                })
                .collect(),
        }
    }

    /// The parts it splits into: four quarters of a rectangle; a triangle's two half-size
    /// triangles and the square between them.
    fn split(&self) -> Vec<Region> {
        match *self {
            Region::Rect(lo, hi) => {
                let m = [(lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0];
                vec![
                    Region::Rect(lo, m),
                    Region::Rect([m[0], lo[1]], [hi[0], m[1]]),
                    Region::Rect(m, hi),
                    Region::Rect([lo[0], m[1]], [m[0], hi[1]]),
                ]
            }
            Region::Lower(lo, s) => {
                let h = s / 2.0;
                vec![
                    Region::Lower(lo, h),
                    Region::Rect([lo[0] + h, lo[1]], [lo[0] + s, lo[1] + h]),
                    Region::Lower([lo[0] + h, lo[1] + h], h),
                ]
            }
        }
    }
}

/// The area-weighted moments of `region` of `patch` to relative tolerance `tol` (of the
/// region's area; with `scale`, the patch's coordinates' size, for the weighted terms), and
/// the estimated error of the area.
pub(crate) fn area_moments(
    patch: &BezierPatch,
    region: Region,
    tol: f64,
    scale: f64,
) -> ([f64; 10], f64) {
    let (qu, qv) = (exact_points(patch.deg_u), exact_points(patch.deg_v));
    let coarse = integrate(patch, &region.rule(qu, qv), area_terms);
    let mut budget = MAX_PARTS;
    let goal = Goal {
        q: (qu, qv),
        tol: tol * coarse[0].abs().max(f64::MIN_POSITIVE),
        scale,
    };
    // each term against the tolerance of the area times the scale to its degree
    let terms = Terms {
        f: area_terms,
        degree: &[0, 1, 1, 1, 2, 2, 2, 2, 2, 2],
    };
    refine(patch, region, coarse, &goal, &terms, 0, &mut budget)
}

/// Parts one area integral splits into at most (beyond, the parts left are accepted as they
/// are: only a patch whose area element is singular along a curve could need more).
const MAX_PARTS: usize = 1 << 14;

/// What [`refine`] aims at: the rule's points, the absolute tolerance of the area (the
/// relative tolerance times the whole region's area: a part near a singular corner need not
/// be accurate relative to its own tiny area) and the coordinates' scale.
struct Goal {
    q: (usize, usize),
    tol: f64,
    scale: f64,
}

/// The integrand of [`refine`]: the terms of one sample, and each term's degree in the
/// coordinates beyond the area's (its tolerance is the area's times the scale to it).
struct Terms<'a, const K: usize, F: Fn(&Sample) -> [f64; K]> {
    f: F,
    degree: &'a [i32; K],
}

/// The integral of `terms` over `region` from its `coarse` estimate, `depth` splits down,
/// with `budget` parts left to split into; and the estimated error of its first term.
fn refine<const K: usize, F: Fn(&Sample) -> [f64; K]>(
    patch: &BezierPatch,
    region: Region,
    coarse: [f64; K],
    goal: &Goal,
    terms: &Terms<'_, K, F>,
    depth: usize,
    budget: &mut usize,
) -> ([f64; K], f64) {
    let parts: Vec<(Region, [f64; K])> = region
        .split()
        .into_iter()
        .map(|r| (r, integrate(patch, &r.rule(goal.q.0, goal.q.1), &terms.f)))
        .collect();
    let mut fine = [0.0; K];
    for (_, p) in &parts {
        for (f, x) in fine.iter_mut().zip(p) {
            *f += x;
        }
    }
    let converged = fine
        .iter()
        .zip(&coarse)
        .zip(terms.degree)
        .all(|((f, c), &d)| (f - c).abs() <= goal.tol * goal.scale.powi(d) + 1e-300);
    *budget = budget.saturating_sub(parts.len());
    if converged || depth >= MAX_DEPTH || *budget == 0 {
        return (fine, (fine[0] - coarse[0]).abs());
    }
    let mut out = [0.0; K];
    let mut err = 0.0;
    for (r, c) in parts {
        let (m, e) = refine(patch, r, c, goal, terms, depth + 1, budget);
        for (o, x) in out.iter_mut().zip(m) {
            *o += x;
        }
        err += e;
    }
    (out, err)
}

/// What one patch contributes.
struct PatchSums {
    exact: [f64; 13],
    area: [f64; 10],
    area_error: f64,
}

/// The patch translated by `-origin` (moments about `origin`).
fn shifted(p: &BezierPatch, origin: Point) -> BezierPatch {
    p.map_points(|q| crate::geom::sub(q, origin))
}

/// The scale of a patch's coordinates for the area tolerance: its control points' largest
/// distance from the origin the moments are taken about (the weighted terms `a x^2` are
/// rounded relative to that), at least its size.
fn size(p: &BezierPatch) -> f64 {
    let (lo, hi) = p.control_bbox();
    let far = p.cps.iter().map(|q| norm(*q)).fold(0.0, f64::max);
    crate::geom::dist(lo, hi).max(far).max(f64::MIN_POSITIVE)
}

fn patch_sums(p: &BezierPatch, origin: Point, tol: f64) -> PatchSums {
    let p = shifted(p, origin);
    let (qu, qv) = (exact_points(p.deg_u), exact_points(p.deg_v));
    let rule = Region::WHOLE.rule(qu, qv);
    let exact = integrate(&p, &rule, exact_terms);
    let scale = size(&p);
    let (area, area_error) = area_moments(&p, Region::WHOLE, tol, scale);
    let exact = if p.weights.is_some() {
        // the terms scale as the area times length to the degrees below
        let goal = Goal {
            q: (qu, qv),
            tol: tol * area[0].abs().max(f64::MIN_POSITIVE),
            scale,
        };
        let degree = [1, 2, 2, 2, 3, 3, 3, 3, 3, 3, 0, 0, 0];
        let mut budget = MAX_PARTS;
        let terms = Terms {
            f: exact_terms,
            degree: &degree,
        };
        refine(&p, Region::WHOLE, exact, &goal, &terms, 0, &mut budget).0
    } else {
        exact
    };
    PatchSums {
        exact,
        area,
        area_error,
    }
}

/// Neumaier's compensated sum of `xs` in order.
fn compensated(xs: impl Iterator<Item = f64>) -> f64 {
    let (mut s, mut c) = (0.0f64, 0.0f64);
    for x in xs {
        let t = s + x;
        c += if s.abs() >= x.abs() {
            (s - t) + x
        } else {
            (x - t) + s
        };
        s = t;
    }
    s + c
}

/// Mass, centroid and inertia about the centroid from the ten moments `1, x, y, z, xx, yy,
/// zz, xy, xz, yz` about `origin`.
fn mass_properties(m: &[f64], origin: Point) -> (f64, Point, [[f64; 3]; 3]) {
    let mass = m[0];
    let c = [m[1] / mass, m[2] / mass, m[3] / mass];
    // central second moments C = S - mass c c^T
    let s = [[m[4], m[7], m[8]], [m[7], m[5], m[9]], [m[8], m[9], m[6]]];
    let mut central = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            central[i][j] = s[i][j] - mass * c[i] * c[j];
        }
    }
    let trace = central[0][0] + central[1][1] + central[2][2];
    let mut inertia = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            inertia[i][j] = if i == j { trace } else { 0.0 } - central[i][j];
        }
    }
    let centroid = [c[0] + origin[0], c[1] + origin[1], c[2] + origin[2]];
    (mass, centroid, inertia)
}

/// The eigenvalues of a symmetric 3 x 3 matrix, ascending.
fn principal(m: &[[f64; 3]; 3]) -> [f64; 3] {
    let a = nalgebra::Matrix3::from_fn(|i, j| m[i][j]);
    let mut e: Vec<f64> = a.symmetric_eigen().eigenvalues.iter().copied().collect();
    e.sort_by(f64::total_cmp);
    [e[0], e[1], e[2]]
}

/// The moments of `c` (see the module documentation).
pub fn measure(c: &PatchComplex, opts: &MeasureOptions) -> Measurement {
    let tol = adjacency::default_tolerance(c);
    let shared = adjacency::shared_boundaries(c, tol);
    let open_sides = adjacency::open_sides(c, &shared, tol).len();
    let orientation_conflicts = adjacency::orientation_conflicts(&shared);
    let origin = crate::geom::bounding_box(c.patches.iter().flat_map(|p| p.cps.iter().copied()))
        .map(|(lo, hi)| crate::geom::lerp(lo, hi, 0.5))
        .unwrap_or([0.0; 3]);
    let sums: Vec<PatchSums> = c
        .patches
        .par_iter()
        .with_min_len(16)
        .map(|p| patch_sums(p, origin, opts.area_tolerance))
        .collect();
    let exact: Vec<f64> = (0..13)
        .map(|k| compensated(sums.iter().map(|s| s.exact[k])))
        .collect();
    let area: Vec<f64> = (0..10)
        .map(|k| compensated(sums.iter().map(|s| s.area[k])))
        .collect();
    let area_error = sums.iter().map(|s| s.area_error).sum();
    let (a, area_centroid, area_inertia) = mass_properties(&area, origin);
    let closure = norm([exact[10], exact[11], exact[12]]) / a;
    let closed = open_sides == 0 && orientation_conflicts == 0 && !c.is_empty();
    let volume = closed.then(|| {
        let outward = exact[0] >= 0.0;
        let sign = if outward { 1.0 } else { -1.0 };
        let m: Vec<f64> = exact[..10].iter().map(|x| sign * x).collect();
        let (volume, centroid, inertia) = mass_properties(&m, origin);
        VolumeMoments {
            volume,
            centroid,
            inertia,
            principal_moments: principal(&inertia),
            outward,
        }
    });
    let mut rules: Vec<[usize; 4]> = c
        .patches
        .iter()
        .map(|p| {
            let (m, n) = (p.deg_u, p.deg_v);
            [m, n, exact_points(m), exact_points(n)]
        })
        .collect();
    rules.sort_unstable();
    rules.dedup();
    Measurement {
        patches: c.len(),
        closed,
        open_sides,
        orientation_conflicts,
        area: a,
        area_error,
        area_centroid,
        area_inertia,
        closure,
        volume,
        rules,
        rational: c.patches.iter().filter(|p| p.weights.is_some()).count(),
    }
}

#[cfg(feature = "unit-tests")]
mod tests;
