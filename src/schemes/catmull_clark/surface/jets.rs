//! The limit point and edge derivatives of the Hermite-Coons fill, computed once per vertex.
//!
//! At an interior vertex of valence `n` whose faces are all quads, the derivative along edge `j`
//! is Halstead et al.'s eigen tangent `t_j = sum_i a_n cos(theta (i - j)) e_i + (cos(theta (i -
//! j)) + cos(theta (i + 1 - j))) f_i` (`theta = 2 pi / n`), a stencil of `2 n` entries. The fill
//! asks for it along every edge of the vertex, which would cost `n^2` at a vertex of high valence
//! (a minute at valence 20,000). Since `cos(theta (i - j)) = cos(theta i) cos(theta j) +
//! sin(theta i) sin(theta j)`, `t_j = cos(theta j) A + sin(theta j) B` with the two Fourier sums
//! `A`, `B` of the applied points, computed once per vertex: linear time in the valence. Other
//! vertices (boundary, next to non-quads) use [`limit_and_derivative`] directly.

use crate::geom::{self, Point};
use crate::mesh::PolyMesh;
use crate::schemes::catmull_clark::{CatmullClark, LimitStencils};
use std::collections::HashMap;
use std::f64::consts::PI;

/// One interior all-quad vertex: its limit point, the Fourier sums `A`, `B` and the index of
/// each neighbour among its outgoing half-edges.
struct Jet {
    limit: Point,
    a: Point,
    b: Point,
    n: usize,
    index: HashMap<u32, usize>,
}

/// The vertices' jets of one level, computed on first use.
pub(super) struct Jets<'m> {
    /// The level's limit stencils, its sharp level built once.
    limits: LimitStencils<'m>,
    cache: HashMap<usize, Option<Jet>>,
    /// With sharp features: the vertices whose derivatives are the chords of the limit points
    /// ([`crate::schemes::sdc::crease::adaptive::chord_vertices`]).
    chord: Option<Vec<bool>>,
}

impl<'m> Jets<'m> {
    /// No jet computed yet.
    pub(super) fn new(mesh: &'m PolyMesh) -> Self {
        Jets {
            limits: LimitStencils::new(mesh),
            cache: HashMap::new(),
            chord: crate::schemes::sdc::crease::adaptive::chord_vertices(mesh),
        }
    }

    /// The limit point of vertex `v` and the derivative of the limit curve of edge `v -> w`
    /// at `v`, in the edge's unit parameter (as [`limit_and_derivative`]).
    pub(super) fn limit_and_derivative(&mut self, v: usize, w: usize) -> (Point, Point) {
        if self.chord.as_ref().is_some_and(|c| c[v]) {
            let lim = self.limits.limit(v);
            return (lim, geom::sub(self.limits.limit(w), lim));
        }
        let limits = &self.limits;
        let jet = self.cache.entry(v).or_insert_with(|| jet(limits, v));
        match jet {
            Some(j) => {
                let n = j.n;
                let k = j.index.get(&(w as u32)).copied().unwrap_or(0);
                let t = 2.0 * PI * k as f64 / n as f64;
                let d = geom::add(geom::scale(j.a, t.cos()), geom::scale(j.b, t.sin()));
                (j.limit, geom::scale(d, 1.0 / (3.0 * n as f64)))
            }
            None => limit_and_derivative(&self.limits, v, w),
        }
    }
}

/// The jet of `v`, `None` when `v` is a boundary vertex or touches a face that is not a quad.
fn jet(limits: &LimitStencils<'_>, v: usize) -> Option<Jet> {
    let m = limits.mesh();
    if m.is_boundary_vertex(v)
        || m.vertex_faces(v)
            .iter()
            .any(|&f| m.face_size(f as usize) != 4)
    {
        return None;
    }
    let pos = m.positions();
    let hs = m.outgoing_halfedges(v);
    let n = hs.len();
    let nf = n as f64;
    let c = (2.0 * PI / nf).cos();
    let a_n = 1.0 + c + (PI / nf).cos() * (2.0 * (9.0 + c)).sqrt();
    let diag = |h: u32| m.he_from(m.he_next(m.he_next(h))) as usize;
    let (mut a, mut b) = ([0.0; 3], [0.0; 3]);
    let mut index = HashMap::with_capacity(n);
    for (i, &h) in hs.iter().enumerate() {
        let (t0, t1) = (2.0 * PI * i as f64 / nf, 2.0 * PI * (i + 1) as f64 / nf);
        let (e, f) = (pos[m.he_to(h) as usize], pos[diag(h)]);
        a = geom::axpy(geom::axpy(a, a_n * t0.cos(), e), t0.cos() + t1.cos(), f);
        b = geom::axpy(geom::axpy(b, a_n * t0.sin(), e), t0.sin() + t1.sin(), f);
        index.entry(m.he_to(h)).or_insert(i);
    }
    Some(Jet {
        limit: limits.limit(v),
        a,
        b,
        n,
        index,
    })
}

/// Limit position and derivative along edge `a -> b` (unit edge parameter) at vertex `a`.
fn limit_and_derivative(ls: &LimitStencils<'_>, a: usize, b: usize) -> (Point, Point) {
    let m = ls.mesh();
    let pos = m.positions();
    let lim = ls.limit(a);
    let hs = m.outgoing_halfedges(a);
    let quads = m
        .vertex_faces(a)
        .iter()
        .all(|&f| m.face_size(f as usize) == 4);
    if m.is_boundary_vertex(a) {
        let nb = m.vertex_neighbors(a);
        let (first, last) = (nb[0] as usize, *nb.last().expect("neighbours") as usize);
        let along_boundary = b == first || b == last;
        if along_boundary {
            let other = if b == first { last } else { first };
            let d = if nb.len() == 2 {
                geom::sub(pos[b], pos[a])
            } else {
                geom::scale(geom::sub(pos[b], pos[other]), 0.5)
            };
            return (lim, d);
        }
        if nb.len() == 3 && quads {
            // Regular boundary vertex, interior edge: derivative of the ghost-extended patch.
            let s = CatmullClark::boundary_cross_stencil(m, a, &hs, &nb);
            return (lim, geom::scale(s.apply(pos), 1.0 / 6.0));
        }
        return (lim, geom::sub(ls.limit(b), lim));
    }
    if !quads {
        return (lim, geom::sub(ls.limit(b), lim));
    }
    let j = hs
        .iter()
        .position(|&h| m.he_to(h) as usize == b)
        .unwrap_or(0);
    let t = CatmullClark::eigen_tangent(m, &hs, j);
    (
        lim,
        geom::scale(t.apply(pos), 1.0 / (3.0 * hs.len() as f64)),
    )
}
