//! Small 3-vector helpers on `[f64; 3]`.
//!
//! Points are stored as plain `[f64; 3]` so that arrays of them can be viewed as flat `f64`
//! slices by the stencil kernel ([`crate::stencil`]) without copies.

/// A point or vector in 3-space.
pub type Point = [f64; 3];

/// `a + b`.
#[inline]
pub fn add(a: Point, b: Point) -> Point {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// `a - b`.
#[inline]
pub fn sub(a: Point, b: Point) -> Point {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `s * a`.
#[inline]
pub fn scale(a: Point, s: f64) -> Point {
    [a[0] * s, a[1] * s, a[2] * s]
}

/// `a + s * b`.
#[inline]
pub fn axpy(a: Point, s: f64, b: Point) -> Point {
    [a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2]]
}

/// Dot product.
#[inline]
pub fn dot(a: Point, b: Point) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Cross product.
#[inline]
pub fn cross(a: Point, b: Point) -> Point {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Euclidean length.
#[inline]
pub fn norm(a: Point) -> f64 {
    dot(a, a).sqrt()
}

/// Distance between two points.
#[inline]
pub fn dist(a: Point, b: Point) -> f64 {
    norm(sub(a, b))
}

/// `a / |a|`, or `a` itself when it is the zero vector.
#[inline]
pub fn normalize(a: Point) -> Point {
    let n = norm(a);
    if n > 0.0 { scale(a, 1.0 / n) } else { a }
}

/// Linear interpolation `(1 - t) a + t b`.
#[inline]
pub fn lerp(a: Point, b: Point, t: f64) -> Point {
    [
        a[0] + t * (b[0] - a[0]),
        a[1] + t * (b[1] - a[1]),
        a[2] + t * (b[2] - a[2]),
    ]
}

/// Centroid of a set of points (the origin for an empty set).
pub fn centroid(points: impl IntoIterator<Item = Point>) -> Point {
    let mut s = [0.0; 3];
    let mut k = 0usize;
    for p in points {
        s = add(s, p);
        k += 1;
    }
    if k == 0 { s } else { scale(s, 1.0 / k as f64) }
}

/// Axis-aligned bounding box `(min, max)` of a set of points; `None` when empty.
pub fn bounding_box(points: impl IntoIterator<Item = Point>) -> Option<(Point, Point)> {
    let mut it = points.into_iter();
    let first = it.next()?;
    let (mut lo, mut hi) = (first, first);
    for p in it {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    Some((lo, hi))
}
