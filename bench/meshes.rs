//! Generated benchmark meshes, shared by the criterion benches (`benches/`) and the peer
//! comparison tool (`bench/fairsub_bench.rs`).
//!
//! Closed tori are used so that boundary rules play no part in comparisons with OpenSubdiv
//! (fairsub's corner rule equals OpenSubdiv's `VTX_BOUNDARY_EDGE_AND_CORNER`, but a closed mesh
//! needs no such care).

#![allow(dead_code)]

use fairsub::PolyMesh;
use fairsub::geom::Point;

/// Points of an `m x n` torus grid (major radius 3, minor radius 1), row `i` around the major
/// circle, column `j` around the minor one.
fn torus_points(m: usize, n: usize) -> Vec<Point> {
    let (big, small) = (3.0, 1.0);
    let mut pos = Vec::with_capacity(m * n);
    for i in 0..m {
        let u = std::f64::consts::TAU * i as f64 / m as f64;
        for j in 0..n {
            let v = std::f64::consts::TAU * j as f64 / n as f64;
            let rr = big + small * v.cos();
            pos.push([rr * u.cos(), rr * u.sin(), small * v.sin()]);
        }
    }
    pos
}

/// Flat arrays `(positions, face_start, corners)` of an `m x n` quad torus (`m, n >= 3`).
pub fn quad_torus_arrays(m: usize, n: usize) -> (Vec<Point>, Vec<u32>, Vec<u32>) {
    let id = |i: usize, j: usize| ((i % m) * n + (j % n)) as u32;
    let mut corners = Vec::with_capacity(4 * m * n);
    for i in 0..m {
        for j in 0..n {
            corners.extend_from_slice(&[id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    let face_start = (0..=(m * n) as u32).map(|f| 4 * f).collect();
    (torus_points(m, n), face_start, corners)
}

/// Flat arrays of an `m x n` torus with every quad split along the same diagonal: a regular
/// triangle mesh (every vertex of valence 6) with `2 m n` triangles.
pub fn tri_torus_arrays(m: usize, n: usize) -> (Vec<Point>, Vec<u32>, Vec<u32>) {
    let id = |i: usize, j: usize| ((i % m) * n + (j % n)) as u32;
    let mut corners = Vec::with_capacity(6 * m * n);
    for i in 0..m {
        for j in 0..n {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            corners.extend_from_slice(&[a, b, c, a, c, d]);
        }
    }
    let face_start = (0..=(2 * m * n) as u32).map(|f| 3 * f).collect();
    (torus_points(m, n), face_start, corners)
}

/// OpenSubdiv tag lines that crease an `m x n` quad torus (of [`quad_torus_arrays`]): every
/// 8th ring of edges around the minor circle and every 8th ring around the major one, with
/// sharpness cycling through infinitely sharp (10) and the semi-sharp 0.5, 1, 2.5 and 4; and a
/// semi-sharp corner (2) at every 16th vertex off the creases. About an eighth of the edges
/// and a quarter of the faces touch a crease, so every sharp rule (crease, corner, dart where a
/// semi-sharp ring meets a smooth vertex after it is spent, the transition blend) is exercised.
pub fn torus_crease_tags(m: usize, n: usize) -> String {
    use std::fmt::Write;
    const SHARPNESS: [f64; 5] = [10.0, 0.5, 1.0, 2.5, 4.0];
    let id = |i: usize, j: usize| (i % m) * n + (j % n);
    let mut out = String::new();
    for i in (0..m).step_by(8) {
        let s = SHARPNESS[(i / 8) % SHARPNESS.len()];
        for j in 0..n {
            let _ = writeln!(out, "t crease 2/1/0 {} {} {s}", id(i, j), id(i, j + 1));
        }
    }
    for j in (0..n).step_by(8) {
        let s = SHARPNESS[(j / 8 + 2) % SHARPNESS.len()];
        for i in 0..m {
            let _ = writeln!(out, "t crease 2/1/0 {} {} {s}", id(i, j), id(i + 1, j));
        }
    }
    for i in (4..m).step_by(16) {
        for j in (4..n).step_by(16) {
            let _ = writeln!(out, "t corner 1/1/0 {} 2", id(i, j));
        }
    }
    out
}

/// Grid dimensions `(m, n)` with `m * n` close to `cells`, `m` about `1.6 n` (so a 100k-cell
/// torus is 400 x 250).
pub fn torus_dims(cells: usize) -> (usize, usize) {
    let n = ((cells as f64 / 1.6).sqrt().round() as usize).max(3);
    let m = (cells as f64 / n as f64).round().max(3.0) as usize;
    (m, n)
}

/// A quad torus of about `faces` quads.
pub fn quad_torus(faces: usize) -> PolyMesh {
    let (m, n) = torus_dims(faces);
    let (p, fs, c) = quad_torus_arrays(m, n);
    PolyMesh::from_flat(p, fs, c).expect("a torus is a valid mesh")
}

/// A triangle torus of about `faces` triangles.
pub fn tri_torus(faces: usize) -> PolyMesh {
    let (m, n) = torus_dims(faces / 2);
    let (p, fs, c) = tri_torus_arrays(m, n);
    PolyMesh::from_flat(p, fs, c).expect("a torus is a valid mesh")
}

/// Parses a face count such as `100k`, `1M` or `2500`.
pub fn parse_count(s: &str) -> Option<usize> {
    let s = s.trim();
    let (num, mul) = match s.chars().last()? {
        'k' | 'K' => (&s[..s.len() - 1], 1_000.0),
        'm' | 'M' => (&s[..s.len() - 1], 1_000_000.0),
        _ => (s, 1.0),
    };
    num.parse::<f64>().ok().map(|x| (x * mul).round() as usize)
}
