//! Watertightness on closed complexes (a torus of bi-3 patches, with and without 2:1
//! T-junctions, and a sphere of lunes with collapsed sides): every edge is shared by exactly
//! two triangles in opposite directions, Euler characteristics are right, no two vertices
//! coincide, triangles face along the patch normals.

use super::*;
use crate::geom::{cross, dist, dot, sub};
use crate::surface::testing::{grid, lunes, refine_some, torus};
use std::collections::HashMap;

/// Checks closedness and orientation; returns (V, E, F).
fn check_closed(t: &Tessellation) -> (usize, usize, usize) {
    let mut directed: HashMap<(u32, u32), usize> = HashMap::new();
    for tri in &t.triangles {
        for k in 0..3 {
            *directed.entry((tri[k], tri[(k + 1) % 3])).or_insert(0) += 1;
        }
    }
    for (&(a, b), &cnt) in &directed {
        assert_eq!(cnt, 1, "directed edge {a}->{b} used {cnt} times");
        assert_eq!(
            directed.get(&(b, a)),
            Some(&1),
            "edge {a}-{b} has no opposite"
        );
    }
    // every vertex is used
    let mut used = vec![false; t.num_vertices()];
    for tri in &t.triangles {
        for &v in tri {
            used[v as usize] = true;
        }
    }
    assert!(used.iter().all(|&u| u), "unused vertices");
    (t.num_vertices(), directed.len() / 2, t.num_triangles())
}

/// Every edge used at most twice, once in each direction.
fn check_closed_or_open(t: &Tessellation) {
    let mut directed: HashMap<(u32, u32), usize> = HashMap::new();
    for tri in &t.triangles {
        for k in 0..3 {
            *directed.entry((tri[k], tri[(k + 1) % 3])).or_insert(0) += 1;
        }
    }
    assert!(directed.values().all(|&c| c == 1));
}

/// No two vertices within 1e-12, positions on their patches, triangles facing the normals.
fn check_geometry(c: &PatchComplex, t: &Tessellation) {
    let (_, distinct) = weld_points(&t.positions, 1e-12);
    assert_eq!(distinct, t.num_vertices(), "duplicate positions");
    for v in 0..t.num_vertices() {
        let [u, w] = t.uv[v];
        let p = c.patches[t.patch_of_vertex[v] as usize].eval(u, w);
        assert!(dist(p, t.positions[v]) < 1e-12);
        assert!((norm(t.normals[v]) - 1.0).abs() < 1e-12);
    }
    for (tri, &p) in t.triangles.iter().zip(&t.triangle_patch) {
        let [a, b, d] = tri.map(|v| t.positions[v as usize]);
        let tn = cross(sub(b, a), sub(d, a));
        let centroid_uv = {
            let uvs = tri.map(|v| t.uv[v as usize]);
            // vertices of another patch (shared) have another domain: use this patch's normal
            // at the triangle's first vertex owned by it, or at its centre otherwise
            uvs.iter()
                .zip(tri)
                .find(|(_, v)| t.patch_of_vertex[**v as usize] == p)
                .map(|(uv, _)| *uv)
                .unwrap_or([0.5, 0.5])
        };
        let pn = c.patches[p as usize].normal(centroid_uv[0], centroid_uv[1]);
        assert!(
            dot(tn, pn) > 0.0,
            "triangle {tri:?} faces against its patch"
        );
    }
}

#[crate::unit::test]
fn closed_torus() {
    let c = torus(6, 4);
    for n in [1usize, 2, 4] {
        let t = tessellate(&c, n);
        let (v, e, f) = check_closed(&t);
        assert_eq!(v as i64 - e as i64 + f as i64, 0);
        // a regular closed quad grid: n^2 vertices and 2 n^2 triangles per patch
        assert_eq!(v, 24 * n * n);
        assert_eq!(f, 2 * 24 * n * n);
        check_geometry(&c, &t);
    }
}

#[crate::unit::test]
fn torus_with_t_junctions() {
    // three patches split into quarters: their neighbours see 2:1 T-junctions
    let c = refine_some(&torus(6, 4), &[0, 7, 14]);
    for n in [1usize, 3, 4] {
        let t = tessellate(&c, n);
        let (v, e, f) = check_closed(&t);
        assert_eq!(v as i64 - e as i64 + f as i64, 0, "n = {n}");
        check_geometry(&c, &t);
        // the coarse neighbours carry the fine samples: vertex count of a uniform grid where
        // the split patches count four times, plus centre vertices of doubly refined quads
        assert!(v >= (21 + 12) * n * n);
    }
    // n = 2: the coarse side's grid point 1/2 is the fine sides' shared end; no extras needed
    // beyond the fine samples at 1/4 and 3/4
    let t = tessellate(&c, 2);
    check_closed(&t);
    let mesh = crate::mesh::PolyMesh::new(
        t.positions.clone(),
        &t.triangles
            .iter()
            .map(|x| x.map(|v| v as usize))
            .collect::<Vec<_>>(),
    );
    assert!(mesh.is_ok());
}

#[crate::unit::test]
fn sphere_of_lunes_with_collapsed_sides() {
    let c = lunes(5);
    // (n = 1 would leave each lune a segment between its poles: no triangles)
    for n in [2usize, 3, 5] {
        let t = tessellate(&c, n);
        let (v, e, f) = check_closed(&t);
        assert_eq!(v as i64 - e as i64 + f as i64, 2, "n = {n}");
        check_geometry(&c, &t);
        // poles are single vertices: 5 lunes x (n - 1) inner rows x n columns + 2
        assert_eq!(v, 5 * (n - 1) * n + 2);
    }
}

#[crate::unit::test]
fn degenerate_input_does_not_panic() {
    let empty = PatchComplex::new();
    assert_eq!(tessellate(&empty, 4), Tessellation::default());
    assert!(shared_boundaries(&empty, 1e-9).is_empty());
    // a point patch, a curve patch and a flat square: only the square has area
    let mut c = PatchComplex::new();
    let prov = crate::surface::Provenance::Unknown;
    c.push(crate::bezier::BezierPatch::new(0, 0, vec![[5.0; 3]]), prov);
    c.push(
        crate::bezier::BezierPatch::new(1, 0, vec![[3.0, 0.0, 0.0], [4.0, 0.0, 0.0]]),
        prov,
    );
    c.push(
        crate::bezier::BezierPatch::new(
            1,
            1,
            vec![[0.0; 3], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0]],
        ),
        prov,
    );
    let t = tessellate(&c, 3);
    let area = |t: &Tessellation, patch: u32| -> f64 {
        t.triangles
            .iter()
            .zip(&t.triangle_patch)
            .filter(|(_, p)| **p == patch)
            .map(|(tri, _)| {
                let [a, b, d] = tri.map(|v| t.positions[v as usize]);
                0.5 * norm(cross(sub(b, a), sub(d, a)))
            })
            .sum()
    };
    // the point and curve patches are skipped: no vertices, no triangles
    assert!(t.triangle_patch.iter().all(|&p| p == 2));
    assert!(t.patch_of_vertex.iter().all(|&p| p == 2));
    assert_eq!(t.num_vertices(), 16);
    assert!((area(&t, 2) - 1.0).abs() < 1e-15);
    assert_eq!(t.num_triangles(), 18);
    check_closed_or_open(&t);
    let t = tessellate(&c, 0);
    assert_eq!(t.num_triangles(), 2);
}

#[crate::unit::test]
fn polygons_for_writers() {
    let c = refine_some(&grid(3), &[4]);
    let t = tessellate(&c, 2);
    let (pos, start, corners) = t.to_polygons();
    assert_eq!(pos.len(), t.num_vertices());
    assert_eq!(start.len(), t.num_triangles() + 1);
    assert_eq!(corners.len(), 3 * t.num_triangles());
    let mesh = crate::mesh::PolyMesh::from_flat(pos, start, corners);
    let Ok(mesh) = mesh else {
        panic!("tessellation is not a valid mesh: {:?}", mesh.err())
    };
    assert_eq!(mesh.num_faces(), t.num_triangles());
    // open 3x3 grid of unit patches: area ~ 9, and the T-junction side of the coarse patches
    // uses the fine samples (the quarter patches' grid is 4 x 4 per original patch)
    let area: f64 = t
        .triangles
        .iter()
        .map(|tri| {
            let [a, b, d] = tri.map(|v| t.positions[v as usize]);
            0.5 * norm(cross(sub(b, a), sub(d, a)))
        })
        .sum();
    assert!((area - 9.0).abs() < 0.05, "{area}");
    check_geometry(&c, &t);
    // boundary edges of the open grid: 4 sides x 3 patches x 2 segments
    let mut count: HashMap<(u32, u32), usize> = HashMap::new();
    for tri in &t.triangles {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            *count.entry((a.min(b), a.max(b))).or_insert(0) += 1;
        }
    }
    assert_eq!(count.values().filter(|&&x| x == 1).count(), 24);
    assert!(count.values().all(|&x| x <= 2));
}
