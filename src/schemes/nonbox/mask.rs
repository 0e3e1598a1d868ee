//! The matrix refinement mask (3) of the four-directional S_3^1 splines and vector subdivision.
//!
//! The paper's regular scheme is the vector subdivision `(S Lambda)_a = sum_b A_(a - 2b)^T
//! Lambda_b` of eq. (2) with the 2 x 2 matrix mask `A` of eq. (3) (from Conti and Jetter).
//! [`PRINTED_MASK`] holds (3) exactly as printed, block by block, in eighths. fairsub's
//! refinement on a regular grid is checked against the mask in [`derived_block`] (test
//! `regular_refinement_is_vector_subdivision_of_mask_3`).
//!
//! # Coordinates and components
//!
//! The printed array's block in row `r` (1..4 from the top of the non-zero window) and column
//! `c` (2..5 counted from its first, all-zero column) is `A_(c - 4, 2 - r)`: the text's
//! `A_(0,0) = [1/2 1/8; 0 1/8]` sits in row 2, column 4. In these coordinates the first
//! component of `Lambda` is the FCV (type-2) coefficient and the second the vertex (type-1)
//! coefficient: the first diagonal entries (1/2 on a 2 x 2 block, 1/8 around it) are the
//! refinement of the diamond pyramid, which the text calls `phi_2`, the second ones the tensor
//! `(1, 2, 1) / 8` of the square pyramid, `phi_1`. With vertex `Lambda^2_b` at the point `b`
//! and FCV `Lambda^1_b` at the cell centre `b - (1/2, 1/2)` (the same after refinement, in units
//! of the finer grid), the mask's rows are the paper's four stencils (Fig. 2).
//!
//! # The two corrected blocks
//!
//! Derived from the generators (the refinement of the two pyramids on the four-directional grid,
//! convolved with the unit box; see [`derived_block`]) the mask agrees with the printed array in
//! every block but two: the second rows of `A_(0,0)` and `A_(0,1)` are printed `(0, 1/8)` (in the
//! array and in the text's `A_(0,0)`) where the generators give `(1/4, 1/2)` and `(1/4, 1/4)`.
//! As printed, the mask is not affine (`sum_a A_a = [3 2; 1/2 3/2]` has no eigenvalue 4, so no
//! refinable pair of integrable generators satisfies it, and subdivision does not keep the
//! constant `(1, 1)`), and its FCV rows lack the vertex weight 1/4 of the paper's own type-2
//! E-vertex rule in two of the four cosets. With the corrected blocks every rule of the paper
//! follows and the refinement reproduces the mask exactly; fairsub uses the derived mask.

use crate::geom::{self, Point};

/// A 2 x 2 block of the mask in eighths: `[[a11, a12], [a21, a22]]`.
pub type Block = [[i32; 2]; 2];

/// The matrix mask (3) as printed: `PRINTED_MASK[r - 1][c - 2]` is the block in row `r` = 1..4
/// and column `c` = 2..5 of the printed array's non-zero window, in eighths; it is
/// `A_(c - 4, 2 - r)`. All other blocks are zero.
pub const PRINTED_MASK: [[Block; 4]; 4] = [
    [
        [[0, 0], [0, 0]],
        [[1, 0], [0, 1]],
        [[1, 0], [0, 1]],
        [[0, 0], [2, 1]],
    ],
    [
        [[1, 1], [0, 0]],
        [[4, 2], [0, 2]],
        [[4, 1], [0, 1]],
        [[1, 0], [2, 2]],
    ],
    [
        [[1, 2], [0, 0]],
        [[4, 4], [0, 1]],
        [[4, 2], [0, 2]],
        [[1, 0], [0, 1]],
    ],
    [
        [[0, 1], [0, 0]],
        [[1, 2], [0, 0]],
        [[1, 1], [0, 0]],
        [[0, 0], [0, 0]],
    ],
];

/// The printed block `A_alpha` (eighths; zero outside the window).
pub fn printed_block(alpha: [i32; 2]) -> Block {
    let c = alpha[0] + 4;
    let r = 2 - alpha[1];
    if (2..=5).contains(&c) && (1..=4).contains(&r) {
        PRINTED_MASK[(r - 1) as usize][(c - 2) as usize]
    } else {
        [[0, 0], [0, 0]]
    }
}

/// The block `A_alpha` derived from the generators (eighths).
///
/// Derivation: the diamond pyramid `phi` (peak at a lattice point) is, on the grid of half the
/// spacing, its own copy at the peak, plus 1/2 of the copies at the four axis neighbours, plus
/// 1/2 of the four square pyramids around the peak; the square pyramid is the diamond copy at
/// its centre plus 1/2 of the four square pyramids inside it. Convolving with the unit box turns
/// each half-spacing copy `g(2x - a)` into `1/4 sum_(d in {0,1}^2) g_bar(2x - a - d)`. With the
/// vertex generator centred at the origin (the printed `A_(0,0)` label) this gives:
///
/// - `a11` (FCV from FCV): 1/2 on `{-1, 0}^2`, 1/8 on its eight edge neighbours;
/// - `a12` (FCV into vertex rows): `b(a1 + 1) b(a2 + 1) / 8` on `{-2, -1, 0}^2`;
/// - `a21` (vertex into FCV rows): 1/4 on `{0, 1}^2`;
/// - `a22` (vertex from vertex): `b(a1) b(a2) / 8` on `{-1, 0, 1}^2`,
///
/// with `b(-1) = b(1) = 1`, `b(0) = 2`.
pub fn derived_block(alpha: [i32; 2]) -> Block {
    let b = |x: i32| match x {
        -1 | 1 => 1,
        0 => 2,
        _ => 0,
    };
    let [x, y] = alpha;
    let inner = |v: i32| (-1..=0).contains(&v);
    let a11 = if inner(x) && inner(y) {
        4
    } else if (inner(y) && (x == -2 || x == 1)) || (inner(x) && (y == -2 || y == 1)) {
        1
    } else {
        0
    };
    let a12 = b(x + 1) * b(y + 1);
    let a21 = if (0..=1).contains(&x) && (0..=1).contains(&y) {
        2
    } else {
        0
    };
    let a22 = b(x) * b(y);
    [[a11, a12], [a21, a22]]
}

/// Control data on a periodic `n x n` grid: `vertex[j n + i]` is `Lambda^2_(i, j)` (at the point
/// `(i, j)`), `fcv[j n + i]` is `Lambda^1_(i, j)` (at the cell centre `(i - 1/2, j - 1/2)`).
#[derive(Debug, Clone, PartialEq)]
pub struct PeriodicGrid {
    /// Grid size (indices modulo `n`).
    pub n: usize,
    /// Type-2 (FCV) coefficients.
    pub fcv: Vec<Point>,
    /// Type-1 (vertex) coefficients.
    pub vertex: Vec<Point>,
}

/// One step of vector subdivision `(S Lambda)_a = sum_b A_(a - 2b)^T Lambda_b` with the mask
/// `mask` (blocks in eighths, support within `[-2, 1]^2`) on periodic data (`n >= 4`): the
/// result lives on the `2n x 2n` grid.
///
/// # Panics
/// Panics for `n < 4` (the mask would wrap around).
pub fn vector_subdivide(mask: impl Fn([i32; 2]) -> Block, data: &PeriodicGrid) -> PeriodicGrid {
    let n = data.n as i32;
    assert!(n >= 4, "periodic grid too small for the mask");
    let m = 2 * n;
    let wrap = |v: i32| {
        let r = v.rem_euclid(m);
        if r > n { r - m } else { r }
    };
    let mut fcv = vec![[0.0; 3]; (m * m) as usize];
    let mut vertex = vec![[0.0; 3]; (m * m) as usize];
    for ay in 0..m {
        for ax in 0..m {
            let (mut p1, mut p2) = ([0.0; 3], [0.0; 3]);
            for by in 0..n {
                for bx in 0..n {
                    let g = [wrap(ax - 2 * bx), wrap(ay - 2 * by)];
                    let a = mask(g);
                    let k = (by * n + bx) as usize;
                    let (l1, l2) = (data.fcv[k], data.vertex[k]);
                    // Row i of A^T is column i of A.
                    p1 = geom::axpy(p1, a[0][0] as f64 / 8.0, l1);
                    p1 = geom::axpy(p1, a[1][0] as f64 / 8.0, l2);
                    p2 = geom::axpy(p2, a[0][1] as f64 / 8.0, l1);
                    p2 = geom::axpy(p2, a[1][1] as f64 / 8.0, l2);
                }
            }
            let k = (ay * m + ax) as usize;
            fcv[k] = p1;
            vertex[k] = p2;
        }
    }
    PeriodicGrid {
        n: m as usize,
        fcv,
        vertex,
    }
}
