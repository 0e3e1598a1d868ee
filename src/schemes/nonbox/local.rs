//! Analysis of non-box subdivision at an extraordinary vertex: the local matrix on the paper's
//! invariant neighbourhood, the published blocks `B(0)`, `B(m)` and numbers of Section 4, and the
//! characteristic ring.
//!
//! # The local net (the labelling of the lost Fig. 5)
//!
//! The invariant neighbourhood of a vertex `V0` of valence `k` has `10 k + 1` points: `V0`, then
//! per sector (counter-clockwise; sector `j` spans the edges `j` and `j + 1`, with chart `x`
//! along edge `j` and `y` towards edge `j + 1`, vertices at integer and FCVs at half-integer chart
//! points)
//!
//! | label | V1 | V2 | V3 | V4 | V5 | V6 | V7 | V8 | V9 | V10 |
//! | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |
//! | point | (1, 0) | (1/2, 1/2) | (2, 0) | (3/2, 1/2) | (1, 1) | (1/2, 3/2) | (2, 1) | (3/2, 3/2) | (1, 2) | (2, 2) |
//! | kind | vertex | FCV | vertex | FCV | vertex | FCV | vertex | FCV | vertex | vertex |
//!
//! This is the only labelling under which the paper's `B(0)` is the `m = 0` block (every row
//! identifies one rule: row 1 the E-vertex of the edge `V0 V1`, row 2 the NFCV at `V0`, row 3 the
//! V-vertex of `V1`, ...), and with it fairsub's blocks equal the printed `B(0)` and `B(m)`
//! entry by entry ([`published_b0`], [`published_bm`]). The printed `B(m)` has twelve rows: its
//! rows 10 and 11 repeat rows 8 and 9 (an extraction artefact); the ten distinct rows are the
//! block. The Fourier convention is that of [`crate::analysis::FourierBlock`]: a point of sector
//! `j + 1` enters with the factor `omega = exp(2 pi i m / k)`.
//!
//! The matrix is read off the scheme's own refinement stencils
//! ([`crate::schemes::nonbox::NonBox::step`], or [`crate::schemes::nonbox::NonBox4Dir::step`]
//! for the four-directional variant) applied to the c-net of valence `k` with FCVs.
//!
//! # The characteristic ring
//!
//! The local net determines the limit surface over the `k` cells around `V0`. After one step
//! the three cells `(1, 0)`, `(1, 1)`, `(0, 1)` of each sector of the child (in the child's chart)
//! are regular and lie between the level-1 and level-0 one-rings: they are the ring. Their Bezier
//! triangles ([`crate::schemes::nonbox::bezier`]) are computed from child points whose stencils
//! are checked to involve the local net only, applied to the characteristic map's control points,
//! and each triangle is stored as three non-degenerate bi-3 patches, so that
//! [`crate::analysis::certify::certify_ring`] certifies the map exactly as for Catmull-Clark.

use crate::bezier::BezierPatch;
use crate::error::{Error, Result};
use crate::linalg::C64;
use crate::mesh::PolyMesh;
use crate::mesh::nets::{self, CnetShape};
use crate::schemes::circulant::SparseLocal;
use crate::schemes::local::{LocalMatrix, LocalOperator};
use crate::schemes::nonbox::bezier::{cell_stencils, triangle_to_quads};
use crate::schemes::nonbox::fourdir::{NonBox4Dir, triangulate};
use crate::schemes::nonbox::{FcvNet, NonBox, a_k, subdominant_eigenvalue};
use crate::schemes::options::ids;
use crate::stencil::{Stencil, StencilTable};
use nalgebra::DMatrix;
use std::f64::consts::PI;

pub(crate) mod dart;

/// Points per sector of the local net.
pub const SECTOR: usize = 10;

fn check_valence(k: usize) -> Result<()> {
    if k < 3 {
        return Err(Error::InvalidArgument(format!(
            "valence {k}: non-box analysis needs k >= 3"
        )));
    }
    Ok(())
}

/// The c-net of valence `k` with `rings` rings of quads and barycentric FCVs.
pub fn local_fcv_net(k: usize, rings: usize) -> FcvNet {
    FcvNet::barycentric(nets::cnet(k, CnetShape::Convex, rings))
}

/// The `10 k + 1` point indices (vertices, then FCVs, as in [`FcvNet::points`]) of the local net
/// around the start vertex of half-edge `h`, sector 0 starting at `h`, in the labelling of the
/// [module](self) documentation. `None` when the two rings of quads around it are not regular.
pub fn labelled_points(m: &PolyMesh, h: u32) -> Option<Vec<usize>> {
    let mut out = vec![m.he_from(h) as usize];
    for g in m.interior_ring_from(h)? {
        out.extend_from_slice(&sector_labels(m, g)?.0);
    }
    Some(out)
}

/// The labels `V1 .. V10` of the sector that starts at the outgoing half-edge `g` (point
/// indices as in [`labelled_points`]), and its vertices `(0, 1)`, `(0, 2)` on the sector's
/// second edge; `None` when its 2 x 2 cells are not regular quads.
pub(crate) fn sector_labels(m: &PolyMesh, g: u32) -> Option<([usize; SECTOR], [usize; 2])> {
    let nv = m.num_vertices();
    let grid = m.sector_grid(g, 2)?;
    let cells = m.sector_cells(g, 2)?;
    let v = |i: usize, j: usize| grid[i][j] as usize;
    let f = |i: usize, j: usize| nv + m.he_face(cells[i][j]) as usize;
    Some((
        [
            v(1, 0),
            f(0, 0),
            v(2, 0),
            f(1, 0),
            v(1, 1),
            f(0, 1),
            v(2, 1),
            f(1, 1),
            v(1, 2),
            v(2, 2),
        ],
        [v(0, 1), v(0, 2)],
    ))
}

/// Rows `rows` of a step table restricted to the sources `cols`: the local matrix's table.
fn restrict(st: &StencilTable, rows: &[usize], cols: &[usize]) -> Result<StencilTable> {
    st.select_rows(rows).restrict_sources(cols).ok_or_else(|| {
        Error::Unsupported("the non-box local net is not invariant under refinement".into())
    })
}

/// The local subdivision table `S_k` (`(10 k + 1)^2`) of the quad variant with FCVs (or of the
/// four-directional variant), from [`NonBox::step`] ([`NonBox4Dir::step`]).
pub fn local_sparse(k: usize, four_dir: bool) -> Result<SparseLocal> {
    check_valence(k)?;
    let net = local_fcv_net(k, 2);
    let h0 = net.mesh.vertex_halfedge(0);
    let cols = labelled_points(&net.mesh, h0)
        .ok_or_else(|| Error::Unsupported("c-net is not regular".into()))?;
    let step = NonBox::step(&net)?;
    // Child face h is the quad of parent corner h; its first half-edge leaves the V-vertex
    // along the child of the parent's edge h. The triangulated child's vertices are the quad
    // child's points in the same order.
    let rows = labelled_points(&step.net.mesh, 4 * h0)
        .ok_or_else(|| Error::Unsupported("refined c-net is not regular".into()))?;
    let (id, t) = if four_dir {
        let (_, st) = NonBox4Dir::step(&triangulate(&net))?;
        (ids::NONBOX_4DIR, restrict(&st, &rows, &cols)?)
    } else {
        (ids::NONBOX, restrict(&step.stencils, &rows, &cols)?)
    };
    Ok(SparseLocal::from_table(id.name(), (1, SECTOR, k), &t))
}

/// The local subdivision matrix `S_k` (`(10 k + 1)^2`) of the quad variant with FCVs, from
/// [`NonBox::step`].
pub fn local_matrix(k: usize) -> Result<LocalMatrix> {
    Ok(local_sparse(k, false)?.to_matrix())
}

/// The local matrix of the four-directional variant, from [`NonBox4Dir::step`] on the
/// triangulated local net (same labelling; the triangle mesh's vertices are the net's points).
pub fn local_matrix_4dir(k: usize) -> Result<LocalMatrix> {
    Ok(local_sparse(k, true)?.to_matrix())
}

/// The local matrix as the analysis decomposes it: dense within
/// [`crate::linalg::MAX_DENSE_EIGEN_ROWS`] rows, its Fourier blocks above.
pub fn operator(k: usize, four_dir: bool) -> Result<Box<dyn LocalOperator>> {
    local_sparse(k, four_dir)?.operator()
}

/// The paper's `B(0)` at valence `k` (11 x 11, rows and columns `V0, V1 .. V10`), as printed.
pub fn published_b0(k: usize) -> DMatrix<f64> {
    let a = a_k(k);
    let e = 0.125;
    #[rustfmt::skip]
    let rows: [[f64; 11]; 11] = [
        [1.0 - a, 0.0, a, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [2.0 * e, 2.0 * e, 4.0 * e, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [2.0 * e, 0.0, 6.0 * e, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [0.0, 4.0 * e, 2.0 * e, 0.0, e, 0.0, e, 0.0, 0.0, 0.0, 0.0],
        [0.0, 2.0 * e, 5.0 * e, 0.0, e, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [e, 2.0 * e, 4.0 * e, 0.0, 0.0, e, 0.0, 0.0, 0.0, 0.0, 0.0],
        [0.0, 2.0 * e, 5.0 * e, 0.0, 0.0, 0.0, e, 0.0, 0.0, 0.0, 0.0],
        [0.0, 2.0 * e, 2.0 * e, 0.0, 2.0 * e, 2.0 * e, 0.0, 0.0, 0.0, 0.0, 0.0],
        [0.0, 0.0, 4.0 * e, 0.0, e, 2.0 * e, e, 0.0, 0.0, 0.0, 0.0],
        [0.0, 2.0 * e, 2.0 * e, 0.0, 0.0, 2.0 * e, 2.0 * e, 0.0, 0.0, 0.0, 0.0],
        [0.0, 0.0, e, 0.0, e, 4.0 * e, e, 0.0, e, 0.0, 0.0],
    ];
    DMatrix::from_fn(11, 11, |i, j| rows[i][j])
}

/// The paper's `B(m)` at valence `k` (10 x 10, rows and columns `V1 .. V10`), as printed with
/// its repeated rows 10 and 11 removed (see the [module](self) documentation).
pub fn published_bm(k: usize, m: usize) -> DMatrix<C64> {
    let w = C64::from_polar(1.0, 2.0 * PI * m as f64 / k as f64);
    let wb = w.conj();
    let c = C64::new((2.0 * PI * m as f64 / k as f64).cos(), 0.0);
    let r = |x: f64| C64::new(x, 0.0);
    let (z, one) = (r(0.0), r(1.0));
    #[rustfmt::skip]
    let rows: [[C64; 10]; 10] = [
        [r(0.25), (one + wb) * 0.25, z, z, z, z, z, z, z, z],
        [z, r(0.5) + c * 0.25, z, z, z, z, z, z, z, z],
        [r(0.5), (one + wb) * 0.125, z, r(0.125), z, wb * 0.125, z, z, z, z],
        [r(0.25), r(0.5) + wb * 0.125, z, r(0.125), z, z, z, z, z, z],
        [(one + w) * 0.125, r(0.5), z, z, r(0.125), z, z, z, z, z],
        [w * 0.25, r(0.5) + w * 0.125, z, z, z, r(0.125), z, z, z, z],
        [r(0.25), r(0.25), z, r(0.25), r(0.25), z, z, z, z, z],
        [z, r(0.5), z, r(0.125), r(0.25), r(0.125), z, z, z, z],
        [w * 0.25, r(0.25), z, z, r(0.25), r(0.25), z, z, z, z],
        [z, r(0.125), z, r(0.125), r(0.5), r(0.125), z, r(0.125), z, z],
    ];
    DMatrix::from_fn(10, 10, |i, j| rows[i][j])
}

/// The eigenvalues of `B(0)` (`m = 0`) or `B(m)` as the paper prints them: `1, 3/4 - a_k, 1/4,
/// 1/8, 1/8, 0, 0, 0, 0` (9 values for the 11 x 11 block) and `1/2 + cos(2 pi m / k) / 4, 1/4,
/// 1/8, 1/8, 0, 0, 0, 0` (8 values for the 10 x 10 block).
pub fn printed_block_eigenvalues(k: usize, m: usize) -> Vec<f64> {
    let mut v = if m == 0 {
        vec![1.0, 0.75 - a_k(k), 0.25, 0.125, 0.125]
    } else {
        vec![
            0.5 + 0.25 * (2.0 * PI * m as f64 / k as f64).cos(),
            0.25,
            0.125,
            0.125,
        ]
    };
    v.extend([0.0; 4]);
    v
}

/// All eigenvalues of the printed `B(0)` (11) or `B(m)` (10). The printed blocks are block
/// triangular: rows `V0 .. V2` (`V1, V2` for `m > 0`) form a closed subsystem with the eigenvalues
/// `1, 3/4 - a_k, 1/4` (`1/2 + cos(2 pi m / k) / 4, 1/4`); rows `V4, V5, V6` add `1/8` each and
/// the rest `0`, so `det(x I - B(0)) = x^5 (x - 1) (x - 1/4) (x - 1/8)^3 (x - 3/4 + a_k)`. The
/// printed lists ([`printed_block_eigenvalues`]) miss one `1/8` and one `0`: their sum falls
/// `1/8` short of the blocks' traces.
pub fn block_eigenvalues(k: usize, m: usize) -> Vec<f64> {
    let mut v = printed_block_eigenvalues(k, m);
    v.insert(if m == 0 { 5 } else { 4 }, 0.125);
    v.push(0.0);
    v
}

/// Coefficients of `det(x I - B)` (highest degree first) by the Faddeev-LeVerrier recursion,
/// accurate for the small, well-scaled blocks here even where eigenvalues are defective.
pub fn characteristic_polynomial(b: &DMatrix<C64>) -> Vec<C64> {
    let n = b.nrows();
    let mut c = vec![C64::new(1.0, 0.0)];
    let mut m = DMatrix::<C64>::zeros(n, n);
    for k in 1..=n {
        m = b * &m + DMatrix::<C64>::identity(n, n) * c[k - 1];
        let am = b * &m;
        c.push(-am.trace() / C64::new(k as f64, 0.0));
    }
    c
}

/// The limit-point stencil of Section 4 on the local net: `1 / (1 + 4 a_k)` at `V0` and
/// `4 a_k / (k (1 + 4 a_k))` at each `V2^j`.
pub fn limit_point_formula(k: usize) -> Vec<f64> {
    let a = a_k(k);
    let mut l = vec![0.0; 1 + SECTOR * k];
    l[0] = 1.0 / (1.0 + 4.0 * a);
    for j in 0..k {
        l[1 + SECTOR * j + 1] = 4.0 * a / (k as f64 * (1.0 + 4.0 * a));
    }
    l
}

/// The tangent stencils `l1 = (.., cos(2 pi j / k) at V2^j, ..)` and `l2` (sines) of Section 4.
pub fn tangent_formulas(k: usize) -> (Vec<f64>, Vec<f64>) {
    let mut l1 = vec![0.0; 1 + SECTOR * k];
    let mut l2 = vec![0.0; 1 + SECTOR * k];
    for j in 0..k {
        let t = 2.0 * PI * j as f64 / k as f64;
        l1[1 + SECTOR * j + 1] = t.cos();
        l2[1 + SECTOR * j + 1] = t.sin();
    }
    (l1, l2)
}

/// A published value next to the computed one.
pub use crate::schemes::descriptor::Published as PublishedValue;

fn pv(quantity: impl Into<String>, published: f64, computed: f64) -> PublishedValue {
    PublishedValue::new(quantity, published, computed)
}

/// The paper's numbers at valence `k` beside fairsub's: `lambda`, `a_k`, the largest deviation
/// of the Fourier blocks from the printed `B(0)`, `B(m)`, of their characteristic polynomials
/// from the published eigenvalues, and of the limit-point and tangent formulas from the left
/// eigenvectors.
pub fn published_comparisons(k: usize) -> Result<Vec<PublishedValue>> {
    let lm = operator(k, false)?;
    let spec = lm.spectrum();
    let lambda = subdominant_eigenvalue(k);
    let mut out = vec![pv("lambda = 1/2 + cos(2 pi / k) / 4", lambda, spec.lambda)];
    out.push(pv(
        "a_k (Proposition 1) = 1 - (weight of V0 in the V-vertex rule)",
        a_k(k),
        1.0 - lm.entry(0, 0),
    ));
    let blocks = lm.fourier_blocks()?;
    let mut entry_dev: f64 = 0.0;
    let mut poly_dev: f64 = 0.0;
    for b in &blocks {
        let m = b.frequency;
        let printed: DMatrix<C64> = if m == 0 {
            published_b0(k).map(|x| C64::new(x, 0.0))
        } else {
            published_bm(k, m)
        };
        entry_dev = (&b.matrix - &printed)
            .iter()
            .fold(entry_dev, |d, z| d.max(z.norm()));
        let p = characteristic_polynomial(&b.matrix);
        let roots: Vec<C64> = block_eigenvalues(k, m)
            .into_iter()
            .map(|x| C64::new(x, 0.0))
            .collect();
        let q = crate::linalg::poly_from_roots(&roots);
        for (x, y) in p.iter().zip(&q) {
            poly_dev = poly_dev.max((x - y).norm());
        }
    }
    out.push(pv(
        "max |Fourier block - printed B(0), B(m)| over all entries",
        0.0,
        entry_dev,
    ));
    out.push(pv(
        "max |det(x I - B) - prod (x - eigenvalue)| over all coefficients, with the printed \
         eigenvalues completed by the missing 1/8 and 0",
        0.0,
        poly_dev,
    ));
    let b0 = published_b0(k);
    out.push(pv(
        "sum of the printed B(0) eigenvalues (9 of 11) vs the trace of B(0): one 1/8 is missing",
        printed_block_eigenvalues(k, 0).iter().sum(),
        b0.trace(),
    ));
    let limit = lm.limit_stencil()?;
    let formula = limit_point_formula(k);
    let dev = limit
        .iter()
        .zip(&formula)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    out.push(pv(
        "limit weight of V0 = 1 / (1 + 4 a_k) (left eigenvector of 1)",
        formula[0],
        limit[0],
    ));
    out.push(pv(
        "max |left eigenvector of 1 - limit formula (k V0 + 4 a_k sum V2^j) / (k (1 + 4 a_k))|",
        0.0,
        dev,
    ));
    out.push(pv(
        "distance of the tangent formulas l1, l2 from the left eigenvectors of lambda",
        0.0,
        tangent_deviation(lm.as_ref(), lambda),
    ));
    Ok(out)
}

/// How far the tangent formulas `l1`, `l2` are from the span of the left eigenvectors of
/// `lambda` (the largest residual after projection; 0 when they are left eigenvectors), or 1
/// when the span is not two-dimensional.
pub fn tangent_deviation(lm: &dyn LocalOperator, lambda: f64) -> f64 {
    let basis = lm.left_eigenvectors(lambda);
    if basis.len() != 2 {
        return 1.0;
    }
    let (l1, l2) = tangent_formulas(lm.n());
    let mut worst: f64 = 0.0;
    for l in [l1, l2] {
        let v = nalgebra::DVector::from_vec(l);
        let mut r = v.clone();
        for b in &basis {
            r -= b * b.dot(&v);
        }
        worst = worst.max(r.norm() / v.norm());
    }
    worst
}

/// The characteristic ring at valence `k` (three non-degenerate bi-3 patches per Bezier
/// triangle, 36 per sector) and `lambda`; see the [module](self) documentation.
pub fn characteristic_ring(k: usize) -> Result<(Vec<BezierPatch>, f64)> {
    let (pts, lambda) = operator(k, false)?.characteristic_points()?;
    // A larger net, so that the child points of the ring come from interior rules.
    let net = local_fcv_net(k, 3);
    let h0 = net.mesh.vertex_halfedge(0);
    let labels = labelled_points(&net.mesh, h0)
        .ok_or_else(|| Error::Unsupported("c-net is not regular".into()))?;
    let mut label_of = vec![usize::MAX; labels.iter().max().map_or(0, |&l| l + 1)];
    for (pos, &l) in labels.iter().enumerate() {
        label_of[l] = pos;
    }
    let step = NonBox::step(&net)?;
    let child = &step.net.mesh;
    let sectors = child
        .interior_ring_from(4 * h0)
        .ok_or_else(|| Error::Unsupported("centre on the boundary".into()))?;
    let pull = |s: &Stencil| -> Result<Stencil> {
        let mut parent = Stencil::new();
        for &(i, w) in s.entries() {
            parent.add_scaled(&step.stencils.stencil(i as usize), w);
        }
        let parent = parent.merged();
        let mut local = Stencil::new();
        for &(i, w) in parent.entries() {
            let pos = label_of
                .get(i as usize)
                .copied()
                .filter(|&p| p != usize::MAX)
                .ok_or_else(|| {
                    Error::Unsupported(
                        "a ring coefficient depends on points outside the local net".into(),
                    )
                })?;
            local.add(pos, w);
        }
        Ok(local.merged())
    };
    let mut ring = Vec::with_capacity(36 * k);
    for &hs in &sectors {
        let cells = child
            .sector_cells(hs, 2)
            .ok_or_else(|| Error::Unsupported("refined c-net is not regular".into()))?;
        for (i, j) in [(1, 0), (1, 1), (0, 1)] {
            let f = child.he_face(cells[i][j]) as usize;
            let st = cell_stencils(child, f)
                .ok_or_else(|| Error::Unsupported("ring cell is not regular".into()))?;
            for tri in st.iter() {
                let mut t = [[0.0; 3]; 10];
                for (c, s) in t.iter_mut().zip(tri) {
                    *c = pull(s)?.apply(&pts);
                }
                ring.extend(triangle_to_quads(&t));
            }
        }
    }
    Ok((ring, lambda))
}
