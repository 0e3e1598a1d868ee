//! The linear map from a hole's data vector to the canonical quad data the cap's system is
//! written in ([`Conversion`]), and the Bernstein helpers it is built from.

use super::hole::{Degrees, Layout};
use crate::geom::{Point, axpy};
use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

/// The linear map from a hole's data vector ([`Hole::data`](super::hole::Hole::data)) to the canonical quad data: centre,
/// `T0`, `T1`, then per quad sector `a.boundary, a.cross, b.boundary, b.cross`, each with
/// `degree + 1` coefficients (a split sector: the `m` pieces of `a`, each boundary then cross,
/// then those of `b`).
#[derive(Debug, Clone)]
pub(crate) struct Conversion {
    /// Degree of the canonical curves.
    pub degree: usize,
    /// Spoke-end twist of the layout.
    pub kappa: f64,
    /// Spoke-end value `w(1)` of the layout's weight.
    pub w1: f64,
    /// `rows x cols` weights, row-major.
    pub rows: usize,
    pub cols: usize,
    pub w: Vec<f64>,
}

/// Bernstein polynomial values `B_i^d(t)`, `i = 0..=d`.
pub(crate) fn bern(d: usize, t: f64) -> Vec<f64> {
    let mut out = vec![0.0; d + 1];
    crate::bezier::curve::bernstein(d, t, &mut out);
    out
}

/// Bernstein first derivatives `d/dt B_i^d(t)`.
pub(crate) fn bern_d1(d: usize, t: f64) -> Vec<f64> {
    let (mut b0, mut b1, mut b2) = (vec![0.0; d + 1], vec![0.0; d + 1], vec![0.0; d + 1]);
    crate::bezier::curve::bernstein_derivs(d, t, &mut b0, &mut b1, &mut b2);
    b1
}

/// The `(d + 1) x (d + 1)` inverse of the Bernstein collocation matrix at the points
/// `(k + 1/2) / (d + 1)`: maps values at those points to the coefficients of the interpolant.
pub(crate) fn collocation_inverse(d: usize) -> nalgebra::DMatrix<f64> {
    let m = nalgebra::DMatrix::from_fn(d + 1, d + 1, |k, i| {
        bern(d, (k as f64 + 0.5) / (d as f64 + 1.0))[i]
    });
    m.try_inverse()
        .expect("Bernstein collocation at distinct points is invertible")
}

impl Conversion {
    /// [`Conversion::new`], built once per process and shape and shared (it depends on the
    /// shape only; every cap of a complex at one valence uses the same).
    pub(crate) fn cached(n: usize, layout: Layout, deg: Degrees) -> Arc<Conversion> {
        type Cache = Mutex<HashMap<(usize, Layout, Degrees), Arc<Conversion>>>;
        static CACHE: OnceLock<Cache> = OnceLock::new();
        let cache = CACHE.get_or_init(|| Mutex::new(HashMap::new()));
        let key = (n, layout, deg);
        if let Some(c) = cache.lock().ok().and_then(|m| m.get(&key).cloned()) {
            return c;
        }
        let c = Arc::new(Conversion::new(n, layout, deg));
        if let Ok(mut m) = cache.lock() {
            m.insert(key, c.clone());
        }
        c
    }

    /// The conversion for `n` sectors of `layout` whose segments have degrees `deg`.
    pub(crate) fn new(n: usize, layout: Layout, deg: Degrees) -> Conversion {
        let (db, dc) = (deg.boundary, deg.cross);
        let seg_len = db + dc + 2;
        let (degree, kappa, w1, nseg) = match layout {
            Layout::Quad | Layout::OpenQuad => (db.max(dc), 0.0, 0.0, 2),
            Layout::Split(m) => (db.max(dc), 0.0, 0.0, 2 * m),
            Layout::Triangle => (db.max(dc + 1), 1.0, 0.0, 1),
            Layout::OpenTriangle => (db.max(dc + 1), 1.5, -0.5, 1),
        };
        let cols = 3 + n * nseg * seg_len;
        let m = degree + 1;
        let rows = 3 + n * 4 * layout.pieces() * m;
        let mut c = Collocation {
            m,
            cols,
            inv: collocation_inverse(degree),
            w: vec![0.0; rows * cols],
        };
        for k in 0..3 {
            c.w[k * cols + k] = 1.0;
        }
        // Offsets of boundary / cross coefficients of input segment `k` of sector `s`.
        let off = |s: usize, k: usize| 3 + (s * nseg + k) * seg_len;
        for s in 0..n {
            let r = 3 + s * 4 * layout.pieces() * m;
            match layout {
                Layout::Quad | Layout::OpenQuad | Layout::Split(_) => {
                    for k in 0..nseg {
                        c.put_segment(r + 2 * k * m, off(s, k), deg);
                    }
                }
                Layout::OpenTriangle => c.put_straight_corner(r, off(s, 0), deg),
                Layout::Triangle => c.put_kite(r, off(s, 0), off((s + 1) % n, 0), deg),
            }
        }
        Conversion {
            degree,
            kappa,
            w1,
            rows,
            cols,
            w: c.w,
        }
    }

    /// Applies the conversion to a data vector.
    pub(crate) fn apply(&self, data: &[Point]) -> Vec<Point> {
        (0..self.rows)
            .map(|r| {
                let row = &self.w[r * self.cols..(r + 1) * self.cols];
                row.iter()
                    .zip(data)
                    .filter(|(w, _)| **w != 0.0)
                    .fold([0.0; 3], |acc, (&w, &p)| axpy(acc, w, p))
            })
            .collect()
    }
}

/// The conversion's weights being filled: each canonical curve (degree `m - 1`) is given by its
/// values at the `m` collocation points as linear functionals of the data.
struct Collocation {
    /// Coefficients per canonical curve.
    m: usize,
    /// Length of the data vector.
    cols: usize,
    /// [`collocation_inverse`] of degree `m - 1`.
    inv: nalgebra::DMatrix<f64>,
    /// The conversion's weights, row-major.
    w: Vec<f64>,
}

impl Collocation {
    /// Sets the `m` rows from `row0` to the coefficients of the curve whose value at `t` the
    /// functional `f(t, out)` adds to `out` (one weight per data entry).
    fn put(&mut self, row0: usize, f: &dyn Fn(f64, &mut [f64])) {
        let (m, cols) = (self.m, self.cols);
        let mut vals = nalgebra::DMatrix::zeros(m, cols);
        let mut buf = vec![0.0; cols];
        for k in 0..m {
            buf.fill(0.0);
            f((k as f64 + 0.5) / m as f64, &mut buf);
            for (c, &x) in buf.iter().enumerate() {
                vals[(k, c)] = x;
            }
        }
        let coef = &self.inv * vals;
        for i in 0..m {
            for c in 0..cols {
                self.w[(row0 + i) * cols + c] = coef[(i, c)];
            }
        }
    }

    /// A quad-layout segment at data offset `o` as two canonical curves from row `r`: its
    /// boundary, then its cross derivative.
    fn put_segment(&mut self, r: usize, o: usize, deg: Degrees) {
        let (db, dc, m) = (deg.boundary, deg.cross, self.m);
        self.put(r, &|t, out| {
            for (i, b) in bern(db, t).into_iter().enumerate() {
                out[o + i] += b;
            }
        });
        self.put(r + m, &|t, out| {
            for (i, b) in bern(dc, t).into_iter().enumerate() {
                out[o + db + 1 + i] += b;
            }
        });
    }

    /// A quad sector of an open triangle fan from row `r`: fan triangle `s` (its segment at
    /// data offset `o`) with a straight corner at `M_s`: `a` = first half of segment `s`, `b` =
    /// second half, reversed (module documentation of `hole`).
    fn put_straight_corner(&mut self, r: usize, o: usize, deg: Degrees) {
        let (db, dc, m) = (deg.boundary, deg.cross, self.m);
        let add = |t: f64, wv: f64, wt: f64, wx: f64, out: &mut [f64]| {
            add_segment(db, dc, o, t, [wv, wt, wx], out);
        };
        self.put(r, &|v, out| add(0.5 * v, 1.0, 0.0, 0.0, out));
        // cross_a(v) = (1 - v) X + T / 2 at t = v / 2
        self.put(r + m, &|v, out| add(0.5 * v, 0.0, 0.5, 1.0 - v, out));
        self.put(r + 2 * m, &|u, out| add(1.0 - 0.5 * u, 1.0, 0.0, 0.0, out));
        // cross_b(u) = (1 - u) X - T / 2 at t = 1 - u / 2
        self.put(r + 3 * m, &|u, out| {
            add(1.0 - 0.5 * u, 0.0, -0.5, 1.0 - u, out)
        });
    }

    /// A quad sector of a closed triangle fan from row `r`: the kite at `E_(s+1)`, `a` = second
    /// half of segment `s` (data offset `oa`), `b` = first half of segment `s + 1` (offset
    /// `ob`), reversed.
    fn put_kite(&mut self, r: usize, oa: usize, ob: usize, deg: Degrees) {
        let (db, dc, m) = (deg.boundary, deg.cross, self.m);
        let add = |o: usize, t: f64, wv: f64, wt: f64, wx: f64, out: &mut [f64]| {
            add_segment(db, dc, o, t, [wv, wt, wx], out);
        };
        self.put(r, &|v, out| add(oa, 0.5 * (1.0 + v), 1.0, 0.0, 0.0, out));
        // cross_a(v) = (1 - v) X + v (T / 4 + X / 2) at t = (1 + v) / 2
        self.put(r + m, &|v, out| {
            add(oa, 0.5 * (1.0 + v), 0.0, v / 4.0, 1.0 - v / 2.0, out)
        });
        self.put(r + 2 * m, &|u, out| {
            add(ob, 0.5 * (1.0 - u), 1.0, 0.0, 0.0, out)
        });
        // cross_b(u) = (1 - u) X + u (-T / 4 + X / 2) at t = (1 - u) / 2
        self.put(r + 3 * m, &|u, out| {
            add(ob, 0.5 * (1.0 - u), 0.0, -u / 4.0, 1.0 - u / 2.0, out)
        });
    }
}

/// Adds to `out` the value, tangent `T = d/dt` and median derivative `X` at parameter `t` of
/// the triangle-layout segment whose boundary (degree `db`) and cross (degree `dc`)
/// coefficients start at offset `o` of the data vector, with weights `[wv, wt, wx]`.
fn add_segment(db: usize, dc: usize, o: usize, t: f64, w: [f64; 3], out: &mut [f64]) {
    let (b, b1) = (bern(db, t), bern_d1(db, t));
    for i in 0..=db {
        out[o + i] += w[0] * b[i] + w[1] * b1[i];
    }
    for (i, x) in bern(dc, t).into_iter().enumerate() {
        out[o + db + 1 + i] += w[2] * x;
    }
}
