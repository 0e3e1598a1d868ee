//! sqrt(3)'s local analysis: the two-step subdivision matrix on the one-ring of an interior
//! vertex of valence `n`, read off the scheme's own refinement of a triangle fan.
//!
//! One step rotates the ring by `pi / n` (the new neighbours are the face points), so the
//! matrix of one step maps the ring onto a rotated copy; two steps bring the ring back over the
//! old neighbours (the point over `p_i` is `(5 v + p_i-1 + 2 p_i + p_i+1) / 9` plus the
//! centre's share), which is the matrix Kobbelt analyses. Its eigenvalues: 1,
//! `(2/3 - alpha_n)^2` (centre against ring mean) and `(2 + 2 cos(2 pi k / n)) / 9` per
//! Fourier index `k` of the ring; `alpha_n` makes the centre's equal to the square of the
//! subdominant `(2 + 2 cos(2 pi / n)) / 9`.

use super::Sqrt3;
use crate::error::{Error, Result};
use crate::mesh::nets;
use crate::schemes::local::{LocalMatrix, check_valence};
use crate::stencil::StencilTable;

/// The two-step matrix on the one-ring of valence `n` (`n + 1` points: centre, then its
/// neighbours counter-clockwise).
pub fn local_matrix(n: usize) -> Result<LocalMatrix> {
    check_valence(n)?;
    let net = nets::loop_net(n, 2);
    let s = Sqrt3;
    let one = s.step(&net, false)?;
    let two = s.step(&one.mesh, true)?;
    let table: StencilTable = two.stencils.compose(&one.stencils);
    let mut cols = vec![0usize];
    cols.extend(net.vertex_neighbors(0).iter().map(|&v| v as usize));
    let ring: Vec<usize> = two
        .mesh
        .vertex_neighbors(0)
        .iter()
        .map(|&v| v as usize)
        .collect();
    if ring.len() != n || cols.len() != n + 1 {
        return Err(Error::Unsupported(format!(
            "valence {n}: the sqrt(3) ring after two steps has {} points",
            ring.len()
        )));
    }
    // The child ring point over parent neighbour 0 carries the largest weight on it.
    let weight_on = |row: usize, src: usize| -> f64 {
        let (i, w) = table.row(row);
        i.iter()
            .zip(w)
            .find(|(i, _)| **i as usize == src)
            .map_or(0.0, |(_, w)| *w)
    };
    let shift = (0..n)
        .max_by(|&a, &b| weight_on(ring[a], cols[1]).total_cmp(&weight_on(ring[b], cols[1])))
        .unwrap_or(0);
    let mut rows = vec![0usize];
    rows.extend((0..n).map(|k| ring[(k + shift) % n]));
    let t = table
        .select_rows(&rows)
        .restrict_sources(&cols)
        .ok_or_else(|| Error::Unsupported("the sqrt(3) one-ring is not invariant".into()))?;
    let data: Vec<f64> = (0..=n)
        .flat_map(|r| {
            let (i, w) = t.row(r);
            let mut dense = vec![0.0; n + 1];
            for (&i, &w) in i.iter().zip(w) {
                dense[i as usize] += w;
            }
            dense
        })
        .collect();
    Ok(LocalMatrix {
        scheme: crate::schemes::options::ids::SQRT3.name().into(),
        n,
        centre: 1,
        sector: 1,
        matrix: nalgebra::DMatrix::from_row_slice(n + 1, n + 1, &data),
    })
}
