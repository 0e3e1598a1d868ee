//! Local subdivision matrices assembled from each scheme's own refinement stencils.
//!
//! For each scheme the local net of valence `n` is built as a small mesh (the gallery's c-net
//! layout), refined once by the scheme's ordinary refinement code, and the rows of the refined
//! local net are read off the resulting stencil table, in the same canonical order as the old
//! local net (sector 0 of the child starts on the child of the parent's sector-0 edge).

use super::LocalMatrix;
use crate::error::{Error, Result};
use crate::gallery::{self, CnetShape};
use crate::mesh::PolyMesh;
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
    let net = gallery::cnet(n, CnetShape::Convex, 2);
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
    let net = gallery::prism(n);
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
        "nonbox" | "non-box" => super::nonbox::local_matrix(n),
        "nonbox-4dir" | "non-box-4dir" => super::nonbox::local_matrix_4dir(n),
        other => Err(Error::InvalidArgument(format!(
            "no analysis for scheme '{other}' (available: catmull-clark, loop, doo-sabin, eg, \
             nonbox, nonbox-4dir)"
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
            let mut net = gallery::cnet(n, CnetShape::Convex, 2);
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
        "nonbox" | "non-box" | "nonbox-4dir" | "non-box-4dir" => {
            super::nonbox::characteristic_ring(n)
        }
        other => Err(Error::InvalidArgument(format!(
            "no characteristic map for scheme '{other}' (available: catmull-clark, eg, nonbox, \
             nonbox-4dir)"
        ))),
    }
}
