//! Local subdivision matrices assembled from each scheme's own refinement stencils.
//!
//! For each scheme the local net of valence `n` is built as a small mesh (the gallery's c-net
//! layout), refined once by the scheme's ordinary refinement code, and the rows of the refined
//! local net are read off the resulting stencil table, in the same canonical order as the old
//! local net (sector 0 of the child starts on the child of the parent's sector-0 edge).

use super::LocalMatrix;
use crate::error::{Error, Result};
use crate::mesh::PolyMesh;
use crate::mesh::nets::{self, CnetShape};
use crate::schemes::{CatmullClark, DooSabin, Loop, Scheme};
use crate::stencil::StencilTable;
use nalgebra::DMatrix;

fn dense(t: &StencilTable) -> DMatrix<f64> {
    DMatrix::from_row_slice(t.num_rows(), t.num_sources(), &t.to_dense())
}

fn check_valence(n: usize) -> Result<()> {
    if n < 3 {
        return Err(Error::InvalidArgument(format!(
            "valence {n}: a valence is at least 3"
        )));
    }
    Ok(())
}

/// Catmull-Clark on the c-net of valence `n` (`6n + 1` points: centre, then 6 per sector at
/// chart points `(i, j)`, `i = 1, 2`, `j = 0, 1, 2`).
pub fn catmull_clark(n: usize) -> Result<LocalMatrix> {
    check_valence(n)?;
    let net = nets::cnet(n, CnetShape::Convex, 2);
    let st = CatmullClark::stencils(&net);
    let (fs, cn) = CatmullClark::child_topology(&net);
    let child = PolyMesh::from_refinement(st.apply(net.positions()), fs, cn)?;
    // Child face h is the quad of parent corner h; its first half-edge leaves the vertex point
    // along the child of the parent's edge.
    let h0 = net.vertex_halfedge(0);
    let rows = child
        .cnet_indices_from(4 * h0, 2)
        .ok_or_else(|| Error::Unsupported("refined c-net is not regular".into()))?;
    let rows: Vec<usize> = rows.iter().map(|&r| r as usize).collect();
    let t = st.select_rows(&rows);
    Ok(LocalMatrix {
        scheme: "catmull-clark".into(),
        n,
        centre: 1,
        sector: 6,
        matrix: dense(&t),
    })
}

/// A triangle fan of valence `n` with `rings` rings of regular triangles: centre 0, then per
/// sector the chart points `(i, j)`, `i >= 1`, `j >= 0`, `i + j <= rings`.
pub fn loop_net(n: usize, rings: usize) -> PolyMesh {
    let per = rings * (rings + 1) / 2;
    let local = |i: usize, j: usize| -> usize {
        // Position of (i, j) within a sector, rows by i.
        let mut k = 0;
        for a in 1..i {
            k += rings + 1 - a;
        }
        k + j
    };
    let idx = |s: usize, i: usize, j: usize| -> usize {
        if i == 0 && j == 0 {
            0
        } else if i == 0 {
            1 + ((s + 1) % n) * per + local(j, 0)
        } else {
            1 + (s % n) * per + local(i, j)
        }
    };
    let mut pos = vec![[0.0; 3]; 1 + n * per];
    for s in 0..n {
        let (a0, a1) = (
            2.0 * std::f64::consts::PI * s as f64 / n as f64,
            2.0 * std::f64::consts::PI * (s + 1) as f64 / n as f64,
        );
        for i in 1..=rings {
            for j in 0..=rings - i {
                let (fi, fj) = (i as f64, j as f64);
                pos[idx(s, i, j)] = [
                    fi * a0.cos() + fj * a1.cos(),
                    fi * a0.sin() + fj * a1.sin(),
                    0.0,
                ];
            }
        }
    }
    let mut faces = Vec::new();
    for s in 0..n {
        for i in 0..rings {
            for j in 0..rings - i {
                faces.push([idx(s, i, j), idx(s, i + 1, j), idx(s, i, j + 1)]);
                if i + j + 2 <= rings {
                    faces.push([idx(s, i + 1, j), idx(s, i + 1, j + 1), idx(s, i, j + 1)]);
                }
            }
        }
    }
    PolyMesh::new(pos, &faces).expect("triangle fan is valid")
}

/// Loop on the one-ring of a vertex of valence `n` (`n + 1` points: centre, then its neighbours
/// in counter-clockwise order).
pub fn loop_one_ring(n: usize) -> Result<LocalMatrix> {
    check_valence(n)?;
    let net = loop_net(n, 2);
    let r = Loop.refine(&net)?;
    // Child of the centre is vertex 0; its neighbours are the edge points of the centre's edges.
    let nv = net.num_vertices();
    let mut rows = vec![0usize];
    for h in net.outgoing_halfedges(0) {
        rows.push(nv + net.he_edge(h) as usize);
    }
    let mut cols = vec![0usize];
    cols.extend(net.vertex_neighbors(0).iter().map(|&v| v as usize));
    let t = r
        .stencils
        .select_rows(&rows)
        .restrict_sources(&cols)
        .ok_or_else(|| Error::Unsupported("Loop one-ring is not invariant".into()))?;
    Ok(LocalMatrix {
        scheme: "loop".into(),
        n,
        centre: 1,
        sector: 1,
        matrix: dense(&t),
    })
}

/// Doo-Sabin's `n x n` block of an `n`-gon facet: the child points of the facet's corners in
/// terms of its corners (the facet of a prism cap).
pub fn doo_sabin_facet(n: usize) -> Result<LocalMatrix> {
    check_valence(n)?;
    let net = nets::prism(n);
    let f = (0..net.num_faces())
        .find(|&f| net.face_size(f) == n && n != 4 || (n == 4 && f == 0))
        .unwrap_or(0);
    let r = DooSabin.refine(&net)?;
    // Child point h is the point of parent corner (half-edge) h.
    let h0 = net.face_halfedge(f) as usize;
    let rows: Vec<usize> = (h0..h0 + n).collect();
    let cols: Vec<usize> = net.face(f).iter().map(|&v| v as usize).collect();
    let t = r
        .stencils
        .select_rows(&rows)
        .restrict_sources(&cols)
        .ok_or_else(|| Error::Unsupported("Doo-Sabin facet block is not invariant".into()))?;
    Ok(LocalMatrix {
        scheme: "doo-sabin".into(),
        n,
        centre: 0,
        sector: 1,
        matrix: dense(&t),
    })
}

/// EG subdivision's matrix `A_n` on the local vector `(c0, d-net)` (`12 n + 1` points).
pub fn eg(n: usize) -> Result<LocalMatrix> {
    check_valence(n)?;
    let st = crate::schemes::eg::Eg::new(n)?.step()?;
    Ok(LocalMatrix {
        scheme: "eg".into(),
        n,
        centre: 1,
        sector: 12,
        matrix: dense(&st.step),
    })
}

/// The local matrix of a scheme by name.
pub fn local_matrix(scheme: &str, n: usize) -> Result<LocalMatrix> {
    match scheme {
        "catmull-clark" | "cc" => catmull_clark(n),
        "loop" => loop_one_ring(n),
        "doo-sabin" | "ds" => doo_sabin_facet(n),
        "eg" => eg(n),
        "qas-plus" => qas(n, 0.5),
        "qas-0.4" => qas(n, 0.4),
        "qas-plus-bi3" => qas_bi3(n, 0.5),
        "pgs" | "polar-bi2" | "tps" | "tps-adjustable" => super::bi2::local_matrix(scheme, n),
        "polbs" => super::bi2::local_matrix("polar-bi2", n),
        "nonbox" | "non-box" => super::nonbox::local_matrix(n),
        "nonbox-4dir" | "non-box-4dir" => super::nonbox::local_matrix_4dir(n),
        name if crate::surface::guided::parse_scheme(name).is_some() => {
            let o = crate::surface::guided::parse_scheme(name).expect("checked");
            guided(n, o.guide, guided_lambda(n, o.chi))
        }
        other => Err(Error::InvalidArgument(format!(
            "no analysis for scheme '{other}' (available: catmull-clark, loop, doo-sabin, eg, \
             qas-plus, qas-0.4, pgs, polar-bi2, tps, tps-adjustable, nonbox, nonbox-4dir, guided-bi5, \
             guided-bi6, guided-bi5-half, ...)"
        ))),
    }
}

/// The characteristic ring of a scheme at valence `n`: the planar patches of one ring built from
/// the characteristic-map control points on the local net by the scheme's own patch code, and
/// lambda.
pub fn characteristic_ring(
    scheme: &str,
    n: usize,
) -> Result<(Vec<crate::bezier::BezierPatch>, f64)> {
    match scheme {
        "catmull-clark" | "cc" => {
            let lm = catmull_clark(n)?;
            let (pts, lambda) = lm.characteristic_points()?;
            let mut net = nets::cnet(n, CnetShape::Convex, 2);
            net.set_positions(pts);
            // One step with Catmull-Clark's stencils; the ring is the level-1 faces of the 2-ring
            // that do not touch the centre, each an exact bi-3 patch of its regular 4x4 net.
            let r = CatmullClark.refine(&net)?;
            let child = r.mesh;
            let start = 4 * net.vertex_halfedge(0);
            let mut ring = Vec::with_capacity(3 * n);
            let m3 = crate::bezier::convert::cubic_bspline_matrix();
            let mut h = start;
            for _ in 0..n {
                let cells = child
                    .sector_cells(h, 2)
                    .ok_or_else(|| Error::Unsupported("refined c-net is not regular".into()))?;
                for (i, j) in [(1, 0), (1, 1), (0, 1)] {
                    let f = child.he_face(cells[i][j]) as usize;
                    let netp = crate::surface::regular::bi3_net(&child, f)
                        .ok_or_else(|| Error::Unsupported("ring face is not regular".into()))?;
                    let pts: Vec<_> = netp.iter().map(|s| s.apply(child.positions())).collect();
                    ring.push(crate::bezier::convert::tensor_apply(m3, m3, &pts));
                }
                h = child
                    .he_twin(child.he_prev(h))
                    .ok_or_else(|| Error::Unsupported("centre on the boundary".into()))?;
            }
            Ok((ring, lambda))
        }
        "eg" => {
            let lm = eg(n)?;
            let (pts, lambda) = lm.characteristic_points()?;
            let ring = crate::schemes::eg::Eg::new(n)?.step()?.ring.apply(&pts);
            let patches = (0..3 * n)
                .map(|k| {
                    crate::bezier::BezierPatch::new(4, 4, ring[25 * k..25 * k + 25].to_vec())
                        .transposed()
                })
                .collect();
            Ok((patches, lambda))
        }
        name if crate::surface::guided::parse_scheme(name).is_some() => {
            let o = crate::surface::guided::parse_scheme(name).expect("checked");
            guided_characteristic_ring(n, o)
        }
        // The paper's chi of Section 3 (n = 5..10).
        "qas-plus" | "qas-plus-chi" => Ok((crate::schemes::qas::chi::chi_ring(n)?.0, 0.5)),
        // The characteristic map of the QAS+^4 rules (eigenvectors of the subdivision matrix).
        "qas-plus-rules" => {
            let [cx, cy] = crate::schemes::qas::characteristic_vectors(n)?;
            let pts: Vec<_> = cx.iter().zip(&cy).map(|(&x, &y)| [x, y, 0.0]).collect();
            let ring = crate::schemes::qas::Qas::new(n)?
                .step(0.5)?
                .ring
                .apply(&pts);
            let patches = (0..3 * n)
                .map(|k| {
                    crate::bezier::BezierPatch::new(4, 4, ring[25 * k..25 * k + 25].to_vec())
                        .transposed()
                })
                .collect();
            Ok((patches, 0.5))
        }
        "pgs" | "polar-bi2" | "tps" | "tps-adjustable" => {
            super::bi2::characteristic_ring(scheme, n)
        }
        "polbs" => super::bi2::characteristic_ring("polar-bi2", n),
        "nonbox" | "non-box" | "nonbox-4dir" | "non-box-4dir" => {
            super::nonbox::characteristic_ring(n)
        }
        other => Err(Error::InvalidArgument(format!(
            "no characteristic map for scheme '{other}' (available: catmull-clark, eg, qas-plus \
             (Section 3), qas-plus-rules, pgs, polar-bi2, tps, tps-adjustable, nonbox, nonbox-4dir)"
        ))),
    }
}

/// QAS+^4's matrix on the local vector `(p, d-net, q)` reordered sector by sector: centre `p`,
/// then per sector its 12 d-net nodes and its 5 expansion coefficients `q_2 .. q_6` (17 points),
/// so that the Fourier blocks apply. `lambda` is the contraction of `S` (1/2 for QAS+).
pub fn qas(n: usize, lambda: f64) -> Result<LocalMatrix> {
    use crate::schemes::qas::Qas;
    check_valence(n)?;
    qas_from_step(n, Qas::new(n)?.step(lambda)?.step, "qas-plus")
}

/// QAS+^3's matrix (bi-3 d-net through `T_3^4`), ordered like [`qas`].
pub fn qas_bi3(n: usize, lambda: f64) -> Result<LocalMatrix> {
    check_valence(n)?;
    qas_from_step(
        n,
        crate::schemes::qas::bi3::QasBi3::new(n)?.step(lambda)?.step,
        "qas-plus-bi3",
    )
}

fn qas_from_step(n: usize, st: StencilTable, name: &str) -> Result<LocalMatrix> {
    use crate::schemes::qas::{num_sources, q_index};
    let m = num_sources(n);
    let perm: Vec<usize> = std::iter::once(0)
        .chain((0..n).flat_map(|s| {
            (0..12)
                .map(move |e| 1 + 12 * s + e)
                .chain((2..=6).map(move |k| q_index(n, s, k)))
        }))
        .collect();
    let a = dense(&st);
    let b = DMatrix::from_fn(m, m, |i, j| a[(perm[i], perm[j])]);
    Ok(LocalMatrix {
        scheme: name.into(),
        n,
        centre: 1,
        sector: 17,
        matrix: b,
    })
}

/// Facts of QAS+ beyond the spectrum of the whole matrix: the spectral radius of `M_d` (the
/// d-net block, independent of `q`) and the eigenvalues of `M_q` restricted to each kind of
/// quadratic expansion (C^2: 6 coordinates, C^1: `3 + n`, C^1-C^0: `3 + 2n`).
#[derive(Debug, Clone, serde::Serialize)]
pub struct QasFacts {
    /// Largest modulus of the eigenvalues of `M_d`.
    pub m_d_spectral_radius: f64,
    /// Eigenvalues (real parts, sorted decreasing) of `M_q` on C^2 expansions.
    pub m_q_c2: Vec<f64>,
    /// Eigenvalues of `M_q` on C^1 expansions.
    pub m_q_c1: Vec<f64>,
    /// Eigenvalues of `M_q` on C^1-C^0 expansions.
    pub m_q_c1c0: Vec<f64>,
    /// Largest residual of the invariance of each kind's subspace under `M_q` (0 = invariant).
    pub invariance_defect: f64,
}

/// Computes [`QasFacts`] at valence `n` with contraction `lambda`.
pub fn qas_facts(n: usize, lambda: f64) -> Result<QasFacts> {
    qas_facts_of(n, crate::schemes::qas::Qas::new(n)?.step(lambda)?.step)
}

/// [`QasFacts`] of QAS+^3.
pub fn qas_bi3_facts(n: usize, lambda: f64) -> Result<QasFacts> {
    qas_facts_of(
        n,
        crate::schemes::qas::bi3::QasBi3::new(n)?.step(lambda)?.step,
    )
}

fn qas_facts_of(n: usize, st: StencilTable) -> Result<QasFacts> {
    use crate::schemes::qas::{num_sources, q_index, quadratic_bb};
    let m = num_sources(n);
    let a = dense(&st);
    let nd = 12 * n;
    let md = a.view((1, 1), (nd, nd)).into_owned();
    let rho = super::eigenvalues(&md)
        .iter()
        .map(|z| z.norm())
        .fold(0.0, f64::max);
    // q-space: coordinates p (source 0) and all q_k^s.
    let qsrc: Vec<usize> = std::iter::once(0)
        .chain((0..n).flat_map(|s| (2..=6).map(move |k| q_index(n, s, k))))
        .collect();
    let mq = DMatrix::from_fn(qsrc.len(), qsrc.len(), |i, j| a[(qsrc[i], qsrc[j])]);
    let c = (2.0 * std::f64::consts::PI / n as f64).cos();
    let col = |p: f64, f: &dyn Fn(usize, usize) -> f64| -> Vec<f64> {
        let mut v = vec![p];
        for s in 0..n {
            for k in 2..=6 {
                v.push(f(s, k));
            }
        }
        v
    };
    let poly = |p: f64, lin: [f64; 2], quad: [f64; 3]| {
        col(p, &|s, k| quadratic_bb(n, s, p, lin, quad)[k - 1])
    };
    let mut c2 = vec![
        poly(1.0, [0.0; 2], [0.0; 3]),
        poly(0.0, [1.0, 0.0], [0.0; 3]),
        poly(0.0, [0.0, 1.0], [0.0; 3]),
    ];
    let mut c1 = c2.clone();
    let mut c1c0 = c2.clone();
    for quad in [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]] {
        c2.push(poly(0.0, [0.0; 2], quad));
    }
    for t in 0..n {
        // C^1: q_5^t = 1; q_6^s = q_3^(s+1) = (q_5^s + q_5^(s+1)) / (2c).
        c1.push(col(0.0, &|s, k| match k {
            5 if s == t => 1.0,
            6 if s == t || (s + 1) % n == t => 0.5 / c,
            3 if s == t || s == (t + 1) % n => 0.5 / c,
            _ => 0.0,
        }));
        // C^1-C^0: q_3^t free (and q_6^(t-1) = q_3^t), q_5^t free.
        c1c0.push(col(0.0, &|s, k| match k {
            3 if s == t => 1.0,
            6 if (s + 1) % n == t => 1.0,
            _ => 0.0,
        }));
        c1c0.push(col(0.0, &|s, k| if k == 5 && s == t { 1.0 } else { 0.0 }));
    }
    let mut defect: f64 = 0.0;
    let mut restricted = |cols: &[Vec<f64>]| -> Vec<f64> {
        let b = DMatrix::from_fn(qsrc.len(), cols.len(), |i, j| cols[j][i]);
        let mb = &mq * &b;
        let pinv = b.clone().pseudo_inverse(1e-12).expect("pseudo-inverse");
        let r = &pinv * &mb;
        defect = defect.max((&b * &r - &mb).abs().max());
        let mut ev: Vec<f64> = super::eigenvalues(&r).iter().map(|z| z.re).collect();
        ev.sort_by(|x, y| y.total_cmp(x));
        ev
    };
    let m_q_c2 = restricted(&c2);
    let m_q_c1 = restricted(&c1);
    let m_q_c1c0 = restricted(&c1c0);
    let _ = m;
    Ok(QasFacts {
        m_d_spectral_radius: rho,
        m_q_c2,
        m_q_c1,
        m_q_c1c0,
        invariance_defect: defect,
    })
}

/// The contraction of guided subdivision: Catmull-Clark's lambda, or 1/2.
pub fn guided_lambda(n: usize, chi: crate::schemes::guided::chi::ChiKind) -> f64 {
    match chi {
        crate::schemes::guided::chi::ChiKind::CatmullClark => super::catmull_clark_lambda(n),
        crate::schemes::guided::chi::ChiKind::Half => 0.5,
    }
}

/// Guided subdivision's subdivision matrix `M` on the free set `P` of the guide (Section 5 and
/// Appendix C of the paper): the guide restricted to `[0, lambda]^2` by de Casteljau, in the
/// guide's coordinates. For the bi-5 guide these are the paper's coordinates (6 central ones, one
/// more for n = 3, 6, then 18 per sector); the central quadratic expansion is not
/// rotation-invariant, so the matrix has no discrete Fourier blocks. Its eigenvalues are
/// `lambda^s`, `s = 0..10`, with the multiplicities of the paper's table (5). The matrix does not
/// depend on the ring degree (bi-5 or bi-6) or on chi, only on `lambda`.
pub fn guided(
    n: usize,
    degree: crate::schemes::guided::guide::GuideDegree,
    lambda: f64,
) -> Result<LocalMatrix> {
    check_valence(n)?;
    let space = crate::schemes::guided::guide::GuideSpace::new(n, degree)?;
    let m = space.step_matrix(lambda);
    let (centre, sector) = if space.centre + 18 * n == space.dim() {
        (space.centre, 18)
    } else {
        (space.dim(), 0)
    };
    Ok(LocalMatrix {
        scheme: format!("guided (bi-{} guide)", space.degree),
        n,
        centre,
        sector,
        matrix: m,
    })
}

/// The characteristic ring of guided subdivision: the ring sampled from the planar guide `L`
/// (the subdominant eigenfunctions), i.e. chi re-expressed in bi-5 or bi-6 form by the scheme's
/// own ring table, and lambda.
fn guided_characteristic_ring(
    n: usize,
    o: crate::schemes::guided::rings::GuidedOptions,
) -> Result<(Vec<crate::bezier::BezierPatch>, f64)> {
    let g = crate::schemes::guided::rings::Guided::new(n, o)?;
    let d = g.degree();
    let dg = g.space.degree;
    let mg = (dg + 1) * (dg + 1);
    let l = crate::schemes::guided::guide::shear_coeffs(n, dg);
    let lambda = g.chi.lambda;
    let m = (d + 1) * (d + 1);
    let mut out = Vec::with_capacity(3 * n);
    for s in 0..n {
        let ring = &g.ring_table * l.rows(s * mg, mg);
        for x in 0..3 {
            let cps: Vec<[f64; 3]> = (0..m)
                .map(|r| {
                    let r = x * m + r;
                    [ring[(r, 0)] / lambda, ring[(r, 1)] / lambda, 0.0]
                })
                .collect();
            match o.ring.macro_kind() {
                None => out.push(crate::bezier::BezierPatch::new(d, d, cps)),
                // The macro variants: the pieces of the macro patch.
                Some(k) => out.extend(
                    k.pieces_of(&cps)
                        .into_iter()
                        .map(|p| crate::bezier::BezierPatch::new(k.degree(), k.degree(), p)),
                ),
            }
        }
    }
    Ok((out, lambda))
}

/// Table (5) of the guided paper against a computed matrix: for `s = 0..=10`, the published
/// multiplicity of `lambda^s` (1, 2, 3, n*, 2n, 3n, 3n, 3n, 3n, 2n, n) and the number of
/// eigenvalues of `m` within `1e-6` (relative) of `lambda^s`.
pub fn guided_table5(
    n: usize,
    lambda: f64,
    m: &nalgebra::DMatrix<f64>,
) -> Vec<(usize, usize, usize)> {
    let ns = crate::schemes::guided::guide::n_star(n);
    let published = [1, 2, 3, ns, 2 * n, 3 * n, 3 * n, 3 * n, 3 * n, 2 * n, n];
    let ev = super::eigenvalues(m);
    (0..=10)
        .map(|s| {
            let t = lambda.powi(s as i32);
            let count = ev
                .iter()
                .filter(|z| (z.re - t).abs() < 1e-6 * t.max(1e-4) + 1e-9 && z.im.abs() < 1e-7)
                .count();
            (s, published[s], count)
        })
        .collect()
}
