//! Canonical nets built by functions: the local nets the schemes and analysis are defined on
//! (extended c-nets of any valence in four shapes, prisms with n-gon caps, triangle fans) and
//! the closed and open solids of the gallery. Every net is reproducible (no randomness), so
//! tests, analysis and the gallery agree on the same numbering.

use super::PolyMesh;
use std::f64::consts::PI;

/// Shape of a c-net's heights.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CnetShape {
    /// A dome: `z = -0.15 r^2` (convex, elliptic limit point).
    Convex,
    /// A saddle: `z = 0.15 r^2 cos(2 theta)` (hyperbolic).
    Saddle,
    /// Planar sectors: each sector lies in its own plane, rays alternately raised
    /// (`z = 0.5 i` on even rays) as in the papers' sector-blending tests.
    PlanarSectors,
    /// A flat net with one node off the centre raised by 0.5 (chart point (1, 1) of sector 0).
    RaisedNode,
}

impl CnetShape {
    /// All shapes.
    pub const ALL: [CnetShape; 4] = [
        CnetShape::Convex,
        CnetShape::Saddle,
        CnetShape::PlanarSectors,
        CnetShape::RaisedNode,
    ];

    /// File-name fragment.
    pub fn name(self) -> &'static str {
        match self {
            CnetShape::Convex => "convex",
            CnetShape::Saddle => "saddle",
            CnetShape::PlanarSectors => "planar",
            CnetShape::RaisedNode => "raised",
        }
    }
}

/// An extended c-net: one vertex of valence `n` surrounded by `rings` rings of quads (3 for the
/// papers' extended c-net: the c-net's two rings plus one ring that defines the surrounding bi-3
/// surface). Sector `s` holds the chart points `(i, j)`, `i = 1..=rings`, `j = 0..=rings`, at
/// `i e_s + j e_(s+1)` with `e_s = (cos 2 pi s / n, sin 2 pi s / n)`; the centre is vertex 0 and
/// chart point `(i, j)` of sector `s` is vertex `1 + s rings (rings + 1) + (i - 1)(rings + 1) + j`.
///
/// # Panics
/// Panics for `n < 3` or `rings < 1` (programming errors: the gallery's own parameters).
pub fn cnet(n: usize, shape: CnetShape, rings: usize) -> PolyMesh {
    assert!(n >= 3 && rings >= 1);
    let r = rings;
    let per = r * (r + 1);
    let idx = |s: usize, i: usize, j: usize| -> usize {
        if i == 0 && j == 0 {
            0
        } else if i == 0 {
            1 + ((s + 1) % n) * per + (j - 1) * (r + 1)
        } else {
            1 + s * per + (i - 1) * (r + 1) + j
        }
    };
    let e = |s: usize| {
        let a = 2.0 * PI * (s % n) as f64 / n as f64;
        [a.cos(), a.sin()]
    };
    let mut pos = vec![[0.0; 3]; 1 + n * per];
    for s in 0..n {
        let (es, et) = (e(s), e(s + 1));
        for i in 1..=r {
            for j in 0..=r {
                let (fi, fj) = (i as f64, j as f64);
                let x = fi * es[0] + fj * et[0];
                let y = fi * es[1] + fj * et[1];
                let r2 = x * x + y * y;
                let z = match shape {
                    CnetShape::Convex => -0.15 * r2,
                    CnetShape::Saddle => 0.15 * r2 * (2.0 * y.atan2(x)).cos(),
                    CnetShape::PlanarSectors => {
                        let h = |k: usize| if (k % n).is_multiple_of(2) { 0.5 } else { 0.0 };
                        fi * h(s) + fj * h(s + 1)
                    }
                    CnetShape::RaisedNode => {
                        if s == 0 && i == 1 && j == 1 {
                            0.5
                        } else {
                            0.0
                        }
                    }
                };
                pos[idx(s, i, j)] = [x, y, z];
            }
        }
    }
    let mut faces = Vec::new();
    for s in 0..n {
        for i in 0..r {
            for j in 0..r {
                faces.push(vec![
                    idx(s, i, j),
                    idx(s, i + 1, j),
                    idx(s, i + 1, j + 1),
                    idx(s, i, j + 1),
                ]);
            }
        }
    }
    PolyMesh::new(pos, &faces).expect("gallery c-net is valid")
}

/// A regular `m x m` quad grid over the lattice points `(i, j)`, `0 <= i, j <= m` (vertex
/// `j (m + 1) + i`), with heights `z(i, j)`: the basic regular net of tests and examples.
pub fn quad_grid(m: usize, z: impl Fn(f64, f64) -> f64) -> PolyMesh {
    let id = |i: usize, j: usize| j * (m + 1) + i;
    let mut pos = Vec::new();
    for j in 0..=m {
        for i in 0..=m {
            pos.push([i as f64, j as f64, z(i as f64, j as f64)]);
        }
    }
    let mut faces = Vec::new();
    for j in 0..m {
        for i in 0..m {
            faces.push(vec![id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    PolyMesh::new(pos, &faces).expect("grid is valid")
}

/// The cube `[0, 1]^3` (vertex `k` at `(k & 1, k >> 1 & 1, k >> 2 & 1)`), for hand-checked
/// refinement values.
pub fn unit_cube() -> PolyMesh {
    let pos: Vec<[f64; 3]> = (0..8)
        .map(|k| [(k & 1) as f64, ((k >> 1) & 1) as f64, ((k >> 2) & 1) as f64])
        .collect();
    let faces = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    PolyMesh::new(pos, &faces).expect("cube is valid")
}

/// The corners of [`cube`] (`[-1, 1]^3`, the bottom square counter-clockwise, then the top)
/// and its six quads, outward: the one definition the split cubes start from too.
fn cube_corners_and_quads() -> (Vec<[f64; 3]>, [[usize; 4]; 6]) {
    let mut p = Vec::with_capacity(8);
    for z in [-1.0, 1.0] {
        for (x, y) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
            p.push([x, y, z]);
        }
    }
    let f = [
        [0, 3, 2, 1],
        [4, 5, 6, 7],
        [0, 1, 5, 4],
        [1, 2, 6, 5],
        [2, 3, 7, 6],
        [3, 0, 4, 7],
    ];
    (p, f)
}

/// The unit cube (8 vertices of valence 3).
pub fn cube() -> PolyMesh {
    let (p, f) = cube_corners_and_quads();
    PolyMesh::new(p, &f).expect("cube")
}

/// The regular tetrahedron (4 triangles).
pub fn tetrahedron() -> PolyMesh {
    let p = vec![
        [1.0, 1.0, 1.0],
        [1.0, -1.0, -1.0],
        [-1.0, 1.0, -1.0],
        [-1.0, -1.0, 1.0],
    ];
    let f = [[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]];
    PolyMesh::new(p, &f).expect("tetrahedron")
}

/// The cube with one top edge split by a vertex pushed outwards to `(0, -1.3, 1.3)`: two
/// pentagons, whose first Catmull-Clark step leaves that vertex with valence 2, the quad
/// schemes' valence-2 case (a half-plane G^1 cap, [`crate::bezier::g1`], "Two sectors"). Not
/// in the gallery's [`crate::gallery::all`]: the dual schemes refuse an interior vertex of
/// valence 2 (refine once first), and the gallery is every scheme's test bed.
pub fn split_edge_cube() -> PolyMesh {
    let (mut p, _) = cube_corners_and_quads();
    p.push([0.0, -1.3, 1.3]);
    // the cube's top and front quads with vertex 8 on their common edge 4 -> 5
    let f: [&[usize]; 6] = [
        &[0, 3, 2, 1],
        &[4, 8, 5, 6, 7],
        &[0, 1, 5, 8, 4],
        &[1, 2, 6, 5],
        &[2, 3, 7, 6],
        &[3, 0, 4, 7],
    ];
    PolyMesh::new(p, &f).expect("split-edge cube")
}

/// The cube with every edge split at its midpoint pushed outwards by 1.2: six octagons, whose
/// first Catmull-Clark step leaves twelve vertices of valence 2 (each on a ridge, the two
/// sectors mirror images). Not in [`crate::gallery::all`], as [`split_edge_cube`].
pub fn all_edges_split_cube() -> PolyMesh {
    let (mut p, quads) = cube_corners_and_quads();
    let mut mid = std::collections::HashMap::new();
    let faces: Vec<Vec<usize>> = quads
        .iter()
        .map(|q| {
            let mut f = Vec::with_capacity(8);
            for k in 0..4 {
                let (a, b) = (q[k], q[(k + 1) % 4]);
                f.push(a);
                let m = *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
                    p.push(std::array::from_fn(|i| 0.6 * (p[a][i] + p[b][i])));
                    p.len() - 1
                });
                f.push(m);
            }
            f
        })
        .collect();
    PolyMesh::new(p, &faces).expect("all-edges-split cube")
}

/// The regular octahedron (8 triangles, valence 4).
pub fn octahedron() -> PolyMesh {
    let p = vec![
        [1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
    ];
    let f = [
        [0, 2, 4],
        [2, 1, 4],
        [1, 3, 4],
        [3, 0, 4],
        [2, 0, 5],
        [1, 2, 5],
        [3, 1, 5],
        [0, 3, 5],
    ];
    PolyMesh::new(p, &f).expect("octahedron")
}

/// The regular icosahedron (20 triangles, valence 5).
pub fn icosahedron() -> PolyMesh {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let p = vec![
        [-1.0, t, 0.0],
        [1.0, t, 0.0],
        [-1.0, -t, 0.0],
        [1.0, -t, 0.0],
        [0.0, -1.0, t],
        [0.0, 1.0, t],
        [0.0, -1.0, -t],
        [0.0, 1.0, -t],
        [t, 0.0, -1.0],
        [t, 0.0, 1.0],
        [-t, 0.0, -1.0],
        [-t, 0.0, 1.0],
    ];
    let f = [
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    PolyMesh::new(p, &f).expect("icosahedron")
}

/// Grid points and quads of a torus (`m` around the axis, `k` around the tube), before edits.
fn torus_grid(m: usize, k: usize) -> (Vec<[f64; 3]>, Vec<Vec<usize>>) {
    let (big, small) = (2.0, 0.75);
    let mut pos = Vec::new();
    for i in 0..m {
        for j in 0..k {
            let (a, b) = (
                2.0 * PI * i as f64 / m as f64,
                2.0 * PI * j as f64 / k as f64,
            );
            let rr = big + small * b.cos();
            pos.push([rr * a.cos(), rr * a.sin(), small * b.sin()]);
        }
    }
    let id = |i: usize, j: usize| (i % m) * k + (j % k);
    let mut faces = Vec::new();
    for i in 0..m {
        for j in 0..k {
            faces.push(vec![id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    (pos, faces)
}

/// Rotates the edge shared by quads `f1` and `f2`: the hexagon they form is split the other way,
/// which lowers the valence of the edge's end points to 3 and raises two others to 5.
fn rotate_edge(faces: &mut [Vec<usize>], f1: usize, f2: usize) {
    let q1 = faces[f1].clone();
    let q2 = faces[f2].clone();
    // Find the shared edge (a, b) as it runs in q1; in q2 it runs (b, a).
    for k in 0..4 {
        let (a, b) = (q1[k], q1[(k + 1) % 4]);
        if let Some(l) = (0..4).find(|&l| q2[l] == b && q2[(l + 1) % 4] == a) {
            // Hexagon, counter-clockwise: b, c, d, a (from q1), e, f (from q2).
            let (c, d) = (q1[(k + 2) % 4], q1[(k + 3) % 4]);
            let (e, f) = (q2[(l + 2) % 4], q2[(l + 3) % 4]);
            faces[f1] = vec![c, d, a, e];
            faces[f2] = vec![e, f, b, c];
            return;
        }
    }
    panic!("faces {f1} and {f2} share no edge");
}

/// A torus of 8 x 6 quads with two rotated edges: four vertices of valence 3 and four of
/// valence 5, in two clusters of adjacent extraordinary vertices (a test for schemes that need
/// extraordinary vertices separated by a regular one).
pub fn torus_with_evs() -> PolyMesh {
    let (m, k) = (8, 6);
    let (pos, mut faces) = torus_grid(m, k);
    // Quads (i, j) and (i + 1, j) share the edge at ring i + 1.
    rotate_edge(&mut faces, k, 2 * k);
    rotate_edge(&mut faces, 5 * k + 3, 6 * k + 3);
    PolyMesh::new(pos, &faces).expect("torus")
}

/// A prism with regular `n`-gon caps and three bands of quads on its side.
pub fn prism(n: usize) -> PolyMesh {
    assert!(n >= 3);
    let zs = [-1.0, -1.0 / 3.0, 1.0 / 3.0, 1.0];
    let mut pos = Vec::new();
    for &z in &zs {
        for i in 0..n {
            let a = 2.0 * PI * i as f64 / n as f64;
            pos.push([a.cos(), a.sin(), z]);
        }
    }
    let id = |r: usize, i: usize| r * n + (i % n);
    let mut faces = Vec::new();
    faces.push((0..n).rev().map(|i| id(0, i)).collect::<Vec<_>>());
    faces.push((0..n).map(|i| id(3, i)).collect());
    for r in 0..3 {
        for i in 0..n {
            faces.push(vec![id(r, i), id(r, i + 1), id(r + 1, i + 1), id(r + 1, i)]);
        }
    }
    PolyMesh::new(pos, &faces).expect("prism")
}

/// An open 6 x 6 quad grid with a smooth bump (one boundary loop).
pub fn open_grid() -> PolyMesh {
    let mut m = quad_grid(6, |_, _| 0.0);
    let pos = m
        .positions()
        .iter()
        .map(|p| {
            let (x, y) = (p[0] - 3.0, p[1] - 3.0);
            [x, y, 1.2 * (-(x * x + y * y) / 4.0).exp()]
        })
        .collect();
    m.set_positions(pos);
    m
}

/// An open pipe: a cylinder of 8 x 4 quads with two boundary loops.
pub fn open_pipe() -> PolyMesh {
    let (m, k) = (8, 4);
    let mut pos = Vec::new();
    for j in 0..=k {
        for i in 0..m {
            let a = 2.0 * PI * i as f64 / m as f64;
            pos.push([a.cos(), a.sin(), j as f64 * 0.6]);
        }
    }
    let id = |i: usize, j: usize| j * m + (i % m);
    let mut faces = Vec::new();
    for j in 0..k {
        for i in 0..m {
            faces.push(vec![id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    PolyMesh::new(pos, &faces).expect("pipe")
}

/// An open triangulated 5 x 5 grid with a bump: interior vertices of valence 6.
pub fn tri_grid() -> PolyMesh {
    let n = 5;
    let mut pos = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (i as f64 - 2.5, j as f64 - 2.5);
            pos.push([x, y, (-(x * x + y * y) / 3.0).exp()]);
        }
    }
    let mut faces = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let a = j * (n + 1) + i;
            faces.push(vec![a, a + 1, a + n + 2]);
            faces.push(vec![a, a + n + 2, a + n + 1]);
        }
    }
    PolyMesh::new(pos, &faces).expect("tri grid")
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
