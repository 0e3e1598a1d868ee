//! The viewer's surface buffer of a refined net, for the schemes without exact patches (sqrt(3),
//! modified butterfly): the net `--levels N` makes (its points at their limit positions where
//! the scheme has limit masks), its faces fanned into triangles, with discrete per-vertex
//! normals and curvatures so that every shading mode of the page works on it.
//!
//! The discrete quantities are the standard ones of a triangle mesh (M. Meyer, M. Desbrun,
//! P. Schroeder, A. Barr, *Discrete differential-geometry operators for triangulated
//! 2-manifolds*, 2003, with the barycentric area instead of the mixed Voronoi area):
//! the normal is the area-weighted mean of the triangle normals; the Gauss curvature of an
//! interior vertex is its angle deficit `2 pi - sum of angles` over its area (a third of its
//! triangles' areas), so the sum of `K A` over a closed net is `2 pi` times its Euler
//! characteristic (Gauss-Bonnet, exact); the mean curvature is half the cotangent Laplacian of
//! the position along the normal, `H = (Delta x . n) / 2`, signed as the exact patches' (a
//! sphere with outward faces has `H = -1/r`). A boundary vertex has no closed fan, so it takes
//! the mean of its interior neighbours' values (0 without any).

use super::api::{Shape, encode, net_edges};
use crate::geom::{Point, add, cross, dot, norm, scale, sub};
use crate::mesh::PolyMesh;
use std::collections::HashMap;
use std::f64::consts::PI;

/// The surface buffer of the refined net `mesh`, with the edges of the control net `net`.
pub(super) fn mesh_buffer(mesh: &PolyMesh, net: Option<&PolyMesh>) -> Vec<u8> {
    let positions = mesh.positions();
    let triangles = fan_triangles(mesh);
    let (normals, curvature) = discrete_geometry(positions, &triangles);
    let curvature: Vec<[f32; 2]> = curvature
        .iter()
        .map(|&[k, h]| [k as f32, h as f32])
        .collect();
    encode(&Shape {
        positions,
        normals: &normals,
        curvature: &curvature,
        provenance: &vec![-1.0; positions.len()],
        triangles: &triangles,
        // the refined net's edges stand for the patch boundaries
        boundary: &net_edges(Some(mesh)),
        edges: &net_edges(net),
        patches: mesh.num_faces(),
    })
}

/// The faces of `mesh` fanned from their first corner.
fn fan_triangles(mesh: &PolyMesh) -> Vec<[u32; 3]> {
    mesh.faces()
        .flat_map(|f| (1..f.len().saturating_sub(1)).map(move |i| [f[0], f[i], f[i + 1]]))
        .collect()
}

/// Per vertex of the triangle mesh `(positions, triangles)`: the unit normal, and the Gauss and
/// mean curvature (see the [module](self) documentation).
pub(super) fn discrete_geometry(
    positions: &[Point],
    triangles: &[[u32; 3]],
) -> (Vec<Point>, Vec<[f64; 2]>) {
    let nv = positions.len();
    let mut normal = vec![[0.0; 3]; nv];
    let mut area = vec![0.0; nv];
    let mut angles = vec![0.0; nv];
    let mut laplace = vec![[0.0; 3]; nv];
    // an edge in one triangle only is a boundary edge
    let mut uses: HashMap<(u32, u32), u32> = HashMap::new();
    for t in triangles {
        let p = t.map(|v| positions[v as usize]);
        let n = cross(sub(p[1], p[0]), sub(p[2], p[0]));
        let a = norm(n) / 2.0;
        for i in 0..3 {
            let (v, j, k) = (t[i] as usize, (i + 1) % 3, (i + 2) % 3);
            normal[v] = add(normal[v], n);
            area[v] += a / 3.0;
            let (e1, e2) = (sub(p[j], p[i]), sub(p[k], p[i]));
            let (c, s) = (dot(e1, e2), norm(cross(e1, e2)));
            angles[v] += s.atan2(c);
            // the cotangent of the angle at corner i weighs the opposite edge j-k
            if s > 0.0 {
                let w = c / s / 2.0;
                let d = sub(p[k], p[j]);
                let (vj, vk) = (t[j] as usize, t[k] as usize);
                laplace[vj] = add(laplace[vj], scale(d, w));
                laplace[vk] = add(laplace[vk], scale(d, -w));
            }
            let (a, b) = (t[j].min(t[k]), t[j].max(t[k]));
            *uses.entry((a, b)).or_default() += 1;
        }
    }
    let mut boundary = vec![false; nv];
    for (&(a, b), &n) in &uses {
        if n == 1 {
            boundary[a as usize] = true;
            boundary[b as usize] = true;
        }
    }
    let normals: Vec<Point> = normal
        .iter()
        .map(|&n| {
            let l = norm(n);
            if l > 0.0 { scale(n, 1.0 / l) } else { n }
        })
        .collect();
    let mut curv: Vec<[f64; 2]> = (0..nv)
        .map(|v| {
            if boundary[v] || area[v] <= 0.0 {
                return [0.0, 0.0];
            }
            [
                (2.0 * PI - angles[v]) / area[v],
                dot(laplace[v], normals[v]) / area[v] / 2.0,
            ]
        })
        .collect();
    // boundary vertices: the mean over their interior neighbours
    let mut sum = vec![([0.0, 0.0], 0u32); nv];
    for &(a, b) in uses.keys() {
        for (x, y) in [(a as usize, b as usize), (b as usize, a as usize)] {
            if boundary[x] && !boundary[y] && area[y] > 0.0 {
                sum[x].0[0] += curv[y][0];
                sum[x].0[1] += curv[y][1];
                sum[x].1 += 1;
            }
        }
    }
    for v in 0..nv {
        if boundary[v] && sum[v].1 > 0 {
            let n = sum[v].1 as f64;
            curv[v] = [sum[v].0[0] / n, sum[v].0[1] / n];
        }
    }
    (normals, curv)
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    /// The regular octahedron's points and (outward) triangles.
    fn octahedron() -> (Vec<Point>, Vec<[u32; 3]>) {
        let m = crate::mesh::nets::octahedron();
        (m.positions().to_vec(), fan_triangles(&m))
    }

    #[crate::unit::test]
    fn octahedron_curvature_is_its_angle_deficit_and_cotangent_laplacian() {
        let (p, t) = octahedron();
        let (n, c) = discrete_geometry(&p, &t);
        // every vertex: four angles of pi/3, area 4 * (sqrt(3)/2) / 3
        let area = 4.0 * 3f64.sqrt() / 2.0 / 3.0;
        for v in 0..6 {
            assert!((dot(n[v], p[v]) - 1.0).abs() < 1e-12, "outward unit normal");
            assert!((c[v][0] - (2.0 * PI - 4.0 * PI / 3.0) / area).abs() < 1e-12);
            // four edges of cotangent weight 2 * cot(pi/3) / 2 toward the neighbours: the
            // Laplacian is -(4 / sqrt(3)) x / area, so H = -(2 / sqrt(3)) / area
            let h = -(2.0 / 3f64.sqrt()) / area;
            assert!((c[v][1] - h).abs() < 1e-12, "{} vs {h}", c[v][1]);
        }
        // Gauss-Bonnet: sum K A = 4 pi
        let total: f64 = c.iter().map(|k| k[0] * area).sum();
        assert!((total - 4.0 * PI).abs() < 1e-12);
    }

    #[crate::unit::test]
    fn boundary_vertices_take_their_interior_neighbours_mean() {
        // the octahedron without its lower four faces: vertex 4 interior, the rest boundary
        let (p, t) = octahedron();
        let (_, c) = discrete_geometry(&p, &t[..4]);
        for v in 0..4 {
            assert_eq!(c[v], c[4], "vertex {v}");
        }
        assert!(c[4][0] > 0.0 && c[5] == [0.0, 0.0]);
    }
}
