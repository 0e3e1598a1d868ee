//! Loop's weights (`beta`, the limit weight `chi`) and its limit tangents and normals.

use super::{Loop, check_triangles};
use crate::error::Result;
use crate::geom::{Point, cross, normalize};
use crate::mesh::PolyMesh;
use crate::schemes::common::{RowBuf, cos_2pi, sin_2pi};
use crate::stencil::StencilTable;

/// Loop's interior tangent mask over the `n` neighbours of a vertex counted from neighbour `j`:
/// `(cos(2 pi (i - j) / n), sin(2 pi (i - j) / n))` for neighbour `i = 0 .. n-1` (exact where
/// [`cos_2pi`] is). The cosine row is the tangent towards neighbour `j` (up to the factor
/// `2 / n` of a unit-parameter derivative), the sine row the one across it; one source for
/// [`Loop::limit_tangent_stencils`] and the Hermite edges of the patch fill.
pub(crate) fn tangent_mask(n: usize, j: usize) -> impl Iterator<Item = (f64, f64)> {
    let (n, j) = (n as i64, j as i64);
    (0..n).map(move |i| (cos_2pi(i - j, n), sin_2pi(i - j, n)))
}

/// The weights `(a, b)` of the vertex and of its two boundary neighbours in Loop's tangent
/// across the boundary at a boundary vertex of `k` triangles (the interior neighbours `p_i`
/// take `sin(pi i / k)`; [`Loop::limit_tangent_stencils`]).
pub(crate) fn across_weights(k: usize) -> (f64, f64) {
    let k = k as i64;
    let sin_t = sin_2pi(1, 2 * k);
    let s: f64 = (1..k).map(|i| sin_2pi(i, 2 * k)).sum();
    let l = 0.375 + 0.25 * cos_2pi(1, 2 * k);
    let b = ((0.75 - l) * sin_t - 0.375 * s) / (8.0 * (0.75 - l) * (l - 0.5) + 1.0);
    let a = 8.0 * (l - 0.5) * b - sin_t;
    (a, b)
}

/// The rows of [`Loop::limit_tangent_stencils`] at vertex `v` (documented there), term by
/// term: `add(k, p, w)` adds weight `w` of point `p` to tangent `k` (0 or 1). The one source
/// of the masks for the stencil tables and for the tangent planes of the G^1 caps.
pub(crate) fn tangent_rows(mesh: &PolyMesh, v: usize, mut add: impl FnMut(usize, u32, f64)) {
    let vi = v as u32;
    if !mesh.is_boundary_vertex(v) {
        let n = mesh.outgoing(v).count();
        for (h, (c, s)) in mesh.outgoing(v).zip(tangent_mask(n, 0)) {
            let p = mesh.he_to(h);
            add(0, p, c);
            add(1, p, s);
        }
    } else if mesh.is_corner(v) {
        let (p0, p1) = mesh.boundary_neighbors(v);
        add(0, p0, 1.0);
        add(0, vi, -1.0);
        add(1, p1, 1.0);
        add(1, vi, -1.0);
    } else {
        let (p0, pk) = mesh.boundary_neighbors(v);
        add(0, p0, 1.0);
        add(0, pk, -1.0);
        let k = mesh.outgoing(v).count() as i64;
        let (a, b) = across_weights(k as usize);
        add(1, vi, a);
        add(1, p0, b);
        add(1, pk, b);
        // The interior neighbours p_1 .. p_{k-1} end the outgoing half-edges 1 .. k-1.
        for (i, h) in mesh.outgoing(v).enumerate().skip(1) {
            add(1, mesh.he_to(h), sin_2pi(i as i64, 2 * k));
        }
    }
}

impl Loop {
    /// Loop's weight `beta` of each edge neighbour of an interior vertex of valence `n >= 3`:
    /// `(5/8 - (3/8 + cos(2 pi / n) / 4)^2) / n`; `1/16` for the regular `n = 6`.
    pub fn vertex_beta(n: usize) -> f64 {
        let c = 0.375 + 0.25 * cos_2pi(1, n as i64);
        (0.625 - c * c) / n as f64
    }

    /// Weight `chi` of each edge neighbour in the limit-position mask of an interior vertex of
    /// valence `n`: `chi = 1 / (3 / (8 beta) + n)`, the vertex itself keeping `1 - n chi`;
    /// `1/12` (and `1/2` for the centre) for `n = 6`.
    pub fn limit_chi(n: usize) -> f64 {
        1.0 / (3.0 / (8.0 * Self::vertex_beta(n)) + n as f64)
    }

    /// Stencils of two limit tangents at every vertex, `[t1, t2]` (row `v` for vertex `v`; the
    /// weights of each row sum to 0). The limit normal is `t1 x t2`, pointing to the side from
    /// which the faces are counter-clockwise. Lengths carry no meaning, only directions do.
    ///
    /// Each mask is a left eigenvector of the subdivision matrix of the vertex's one-ring (which
    /// Loop's rules map to itself), so it gives the exact tangent direction of the limit surface:
    ///
    /// - interior vertex of valence `n`, neighbours `p_0 .. p_{n-1}` counter-clockwise:
    ///   `t1 = sum cos(2 pi i / n) p_i`, `t2 = sum sin(2 pi i / n) p_i` (eigenvalue
    ///   `3/8 + cos(2 pi / n) / 4`);
    /// - boundary vertex with `k >= 2` faces, neighbours `p_0 .. p_k` counter-clockwise (`p_0`
    ///   ends the outgoing boundary edge, `p_k` starts the incoming one): along the boundary
    ///   `t1 = p_0 - p_k` (eigenvalue `1/2`); across it, pointing into the surface,
    ///   `t2 = a v + b (p_0 + p_k) + sum_{i=1}^{k-1} sin(i theta) p_i` with `theta = pi / k`,
    ///   eigenvalue `l = 3/8 + cos(theta) / 4`, `b = ((3/4 - l) sin(theta) - 3/8 S) /
    ///   (8 (3/4 - l)(l - 1/2) + 1)`, `S = sum_{i=1}^{k-1} sin(i theta)`,
    ///   `a = 8 (l - 1/2) b - sin(theta)`. For `k = 3` (the regular boundary) this is
    ///   `(sqrt 3 / 4) (2 p_1 + 2 p_2 - 2 v - p_0 - p_3)`, for `k = 2` it is `p_1 - v`, both
    ///   multiples of OpenSubdiv's masks. For `k >= 4` OpenSubdiv uses the general formula of
    ///   Hoppe et al. (SIGGRAPH 1994), which belongs to their modified edge rule and is not an
    ///   eigenvector of the rules used here.
    /// - corner, neighbours `p_0` (outgoing boundary edge) and `p_1`: `t1 = p_0 - v`,
    ///   `t2 = p_1 - v`.
    ///
    /// The one-ring matrix of a boundary vertex has the eigenvalues `1, 1/2, 1/4` of the cubic
    /// B-spline curve and `3/8 + cos(m pi / k) / 4`, `m = 1 .. k-1`. The two tangent eigenvalues
    /// above are the subdominant pair for boundary vertices with up to 5 faces; from 6 faces on
    /// the mode `m = 2` reaches `1/2` (equal at 6, above from 7), a known weakness of these
    /// boundary rules, and the tangent plane there is not guaranteed.
    ///
    /// # Errors
    /// [`Error::Unsupported`](crate::error::Error::Unsupported) for a face that is not a triangle.
    pub fn limit_tangent_stencils(&self, mesh: &PolyMesh) -> Result<[StencilTable; 2]> {
        check_triangles(mesh)?;
        let nv = mesh.num_vertices();
        let mut t1 = StencilTable::with_capacity(nv, nv, 7);
        let mut t2 = StencilTable::with_capacity(nv, nv, 7);
        let (mut r1, mut r2) = (RowBuf::default(), RowBuf::default());
        for v in 0..nv {
            tangent_rows(
                mesh,
                v,
                |k, p, w| if k == 0 { r1.add(p, w) } else { r2.add(p, w) },
            );
            r1.flush_into(&mut t1);
            r2.flush_into(&mut t2);
        }
        Ok([t1, t2])
    }

    /// Unit limit normals at every vertex (`t1 x t2` of [`Loop::limit_tangent_stencils`],
    /// normalised; the zero vector where the net is degenerate).
    ///
    /// # Errors
    /// [`Error::Unsupported`](crate::error::Error::Unsupported) for a face that is not a triangle.
    pub fn limit_normals(&self, mesh: &PolyMesh) -> Result<Vec<Point>> {
        let [t1, t2] = self.limit_tangent_stencils(mesh)?;
        let (a, b) = (t1.apply(mesh.positions()), t2.apply(mesh.positions()));
        Ok(a.iter()
            .zip(&b)
            .map(|(&x, &y)| normalize(cross(x, y)))
            .collect())
    }
}
