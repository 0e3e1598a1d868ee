//! Unit tests of the Doo-Sabin family's adaptive surfaces and centroid fill.

use super::*;
use crate::schemes::{DooSabin, Scheme};

fn opts(rings: usize) -> ComplexOptions {
    ComplexOptions { rings, fill: true }
}

/// A regular quad grid: every vertex gives one patch (boundary and corner vertices
/// included), and the points `(a / 2, b / 2)` of every patch are limit points of the once
/// refined net: face centroids, or on the boundary the midpoints of boundary edges (knots of
/// the Chaikin limit curve).
#[crate::unit::test]
fn regular_grid_patches_are_limit_points() {
    let m = crate::mesh::nets::open_grid();
    let c = doo_sabin_complex(&m, opts(3), |_| {}).unwrap();
    assert_eq!(c.len(), m.num_vertices());
    let fine = DooSabin.refine(&m).unwrap().mesh;
    let mut lim = crate::schemes::doo_sabin::face_limit_stencils(&fine).apply(fine.positions());
    lim.extend(
        DooSabin
            .limit_stencils(&fine)
            .unwrap()
            .apply(fine.positions()),
    );
    for e in 0..fine.num_edges() {
        if fine.is_boundary_edge(e) {
            let [a, b] = fine.edge(e);
            lim.push(crate::geom::lerp(
                fine.position(a as usize),
                fine.position(b as usize),
                0.5,
            ));
        }
    }
    for p in &c.patches {
        for a in 0..3 {
            for b in 0..3 {
                let q = p.eval(a as f64 / 2.0, b as f64 / 2.0);
                let best = lim
                    .iter()
                    .map(|l| crate::geom::dist(*l, q))
                    .fold(f64::INFINITY, f64::min);
                assert!(best < 1e-13, "({a}, {b}): {best}");
            }
        }
    }
}

#[crate::unit::test]
fn cube_rings_and_fill() {
    let m = crate::mesh::nets::cube();
    // Every vertex has valence 3: ring 1 is empty, ring 2 has 3 * 3 patches per vertex.
    let c = doo_sabin_complex(&m, opts(2), |_| {}).unwrap();
    let rings = |r: u32| {
        c.provenance
            .iter()
            .filter(|p| matches!(p, Provenance::Ring { ring, .. } if *ring == r))
            .count()
    };
    assert_eq!(rings(1), 0);
    assert_eq!(rings(2), 8 * 9);
    let caps = c
        .provenance
        .iter()
        .filter(|p| matches!(p, Provenance::Cap { .. }))
        .count();
    assert_eq!(caps, 8 * 3);
    // No regular patches: every input vertex is extraordinary.
    assert_eq!(c.len(), 8 * 9 + 8 * 3);
}

#[crate::unit::test]
fn rings_zero_names_the_vertex() {
    let m = crate::mesh::nets::cube();
    let e = doo_sabin_complex(&m, opts(0), |_| {})
        .unwrap_err()
        .to_string();
    assert!(e.contains("vertex 0 has 3 faces"), "{e}");
    assert!(e.contains("--rings 1"), "{e}");
    // Without fill the same request is fine (and empty).
    let c = doo_sabin_complex(
        &m,
        ComplexOptions {
            rings: 0,
            fill: false,
        },
        |_| {},
    )
    .unwrap();
    assert!(c.is_empty());
}
