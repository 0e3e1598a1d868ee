//! Catmull-Clark's local analysis: the subdivision matrix on the c-net of any valence, read off
//! the scheme's own refinement of the canonical c-net, and the characteristic ring.

use super::CatmullClark;
use crate::bezier::BezierPatch;
use crate::error::{Error, Result};
use crate::geom::Point;
use crate::mesh::PolyMesh;
use crate::mesh::nets::{self, CnetShape};
use crate::schemes::Scheme;
use crate::schemes::circulant::SparseLocal;
use crate::schemes::local::{LocalMatrix, check_valence};
use crate::schemes::options::ids;

/// Catmull-Clark on the c-net of valence `n` (`6n + 1` points: centre, then 6 per sector at
/// chart points `(i, j)`, `i = 1, 2`, `j = 0, 1, 2`).
pub fn local_matrix(n: usize) -> Result<LocalMatrix> {
    Ok(local_sparse(n)?.to_matrix())
}

/// [`local_matrix`]'s rows, sparse (for its Fourier blocks at large valences).
pub fn local_sparse(n: usize) -> Result<SparseLocal> {
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
    Ok(SparseLocal::from_table(
        ids::CATMULL_CLARK.name(),
        (1, 6, n),
        &t,
    ))
}

/// Catmull-Clark's characteristic ring at valence `n`: the planar patches of one ring of the
/// characteristic map (the subdominant frequency-1 eigenvector on the c-net, one Catmull-Clark
/// step, the exact bi-3 patches of the level-1 cells `(1, 0), (1, 1), (0, 1)` of every sector),
/// sector by sector, and lambda. Each patch is parameterised like its child face (Catmull-Clark's
/// child face `h` starts at the vertex point of parent corner `h`), i.e. the chart cells of
/// `characteristic_cells` turned by one, two and three quarter turns (exact permutations).
/// The one builder of this ring: analysis certifies it, guided subdivision samples through it.
pub fn characteristic_ring(n: usize) -> Result<(Vec<BezierPatch>, f64)> {
    let (cells, lambda) = characteristic_cells(n)?;
    let ring = cells
        .into_iter()
        .flat_map(|[a, b, c]| {
            [
                a.reversed_u().transposed(),
                b.reversed_u().reversed_v(),
                c.transposed().reversed_u(),
            ]
        })
        .collect();
    Ok((ring, lambda))
}

/// Sector 0's patches `A, B, C` of the characteristic ring in the c-net chart (`u` along the
/// sector's first edge, `v` along its second), with lambda.
pub fn characteristic_sector(n: usize) -> Result<([BezierPatch; 3], f64)> {
    let (mut cells, lambda) = characteristic_cells(n)?;
    Ok((cells.swap_remove(0), lambda))
}

/// The characteristic ring's patches over the level-1 cells `(1, 0), (1, 1), (0, 1)` of every
/// sector, in the sector's chart, from the level-1 grid points of the refined characteristic
/// net (3 rings), each the bi-3 patch of its 4 x 4 grid.
fn characteristic_cells(n: usize) -> Result<(Vec<[BezierPatch; 3]>, f64)> {
    let (pts, lambda) = local_sparse(n)?.operator()?.characteristic_points()?;
    let mut net = nets::cnet(n, CnetShape::Convex, 2);
    net.set_positions(pts);
    let child = CatmullClark.refine(&net)?.mesh;
    let idx = child
        .cnet_indices_from(4 * net.vertex_halfedge(0), 3)
        .ok_or_else(|| Error::Unsupported("refined characteristic net is not regular".into()))?;
    // Level-1 chart point (i, j) of sector s, normalised into its owning sector.
    let point = |s: usize, i: i32, j: i32| -> Point {
        let (mut s, mut i, mut j) = (s, i, j);
        for _ in 0..4 {
            if i == 0 && j == 0 {
                return child.position(idx[0] as usize);
            }
            if i >= 1 && j >= 0 {
                break;
            }
            if j < 0 {
                (s, i, j) = (s + n - 1, -j, i);
            } else if i == 0 {
                (s, i, j) = (s + 1, j, 0);
            } else {
                (s, i, j) = (s + 1, j, -i);
            }
        }
        let k = 1 + (s % n) * 12 + (i as usize - 1) * 4 + j as usize;
        child.position(idx[k] as usize)
    };
    let m3 = crate::bezier::convert::cubic_bspline_matrix();
    let cell = |s: usize, ci: i32, cj: i32| -> BezierPatch {
        let grid: Vec<Point> = (0..4)
            .flat_map(|p| (0..4).map(move |r| (p, r)))
            .map(|(p, r)| point(s, ci - 1 + p, cj - 1 + r))
            .collect();
        crate::bezier::convert::tensor_apply(m3, m3, &grid)
    };
    let cells = (0..n)
        .map(|s| [cell(s, 1, 0), cell(s, 1, 1), cell(s, 0, 1)])
        .collect();
    Ok((cells, lambda))
}
