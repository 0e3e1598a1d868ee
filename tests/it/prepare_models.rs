//! The acceptance of the preparation stage on nets of fairsub's own that reproduce what real
//! models bring (the fetched models of `tests/it/acceptance_sweep.rs` are not in the repository):
//! equivalents of CGAL's `cross_quad` (a plus-shaped solid of five cubes), `P` (the letter P,
//! genus 1) and `torus_quad` (a quad torus of 16 cubes), the cube with one edge split (interior
//! valence 2, pentagons), the L-shaped grid (an extraordinary boundary vertex), a triangle
//! fan with a boundary, and gallery nets with triangles, n-gons and adjacent extraordinary
//! elements. Every scheme with patch output writes each one with G^1 below 1e-8 rad at every
//! join (`check` at 3 rings), or refuses it for a reason no preparation removes (Loop on nets
//! that are not all triangles).

use fairsub::mesh::PolyMesh;
use fairsub::schemes::registry::{ids, registry};
use fairsub::surface::ComplexOptions;

use crate::eval_helpers::support;

/// The boundary quads of a union of unit cubes (`cells`, integer corners), outward, with
/// shared corners, bent a little so that no two faces are coplanar.
fn voxels(cells: &[[i32; 3]]) -> PolyMesh {
    use std::collections::{HashMap, HashSet};
    let set: HashSet<[i32; 3]> = cells.iter().copied().collect();
    let mut index: HashMap<[i32; 3], usize> = HashMap::new();
    let mut pos = Vec::new();
    let mut faces = Vec::new();
    for &c in cells {
        for a in 0..3 {
            for s in [1, -1] {
                let mut n = c;
                n[a] += s;
                if set.contains(&n) {
                    continue;
                }
                let (b, d) = ((a + 1) % 3, (a + 2) % 3);
                let mut quad: Vec<[i32; 3]> = [(0, 0), (1, 0), (1, 1), (0, 1)]
                    .iter()
                    .map(|&(x, y)| {
                        let mut p = c;
                        p[a] += i32::from(s > 0);
                        p[b] += x;
                        p[d] += y;
                        p
                    })
                    .collect();
                if s < 0 {
                    quad.reverse();
                }
                faces.push(
                    quad.iter()
                        .map(|p| {
                            *index.entry(*p).or_insert_with(|| {
                                let [x, y, z] = p.map(f64::from);
                                pos.push([
                                    x + 0.05 * (0.7 * y + 0.3 * z).sin(),
                                    y + 0.05 * (0.9 * z).cos(),
                                    z + 0.04 * (1.1 * x + 0.5 * y).sin(),
                                ]);
                                pos.len() - 1
                            })
                        })
                        .collect::<Vec<usize>>(),
                );
            }
        }
    }
    PolyMesh::new(pos, &faces).expect("a closed quad net")
}

/// The nets of the acceptance (see the module documentation).
fn nets() -> Vec<(&'static str, PolyMesh)> {
    let cross = voxels(&[[0, 0, 0], [1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0]]);
    let p = voxels(&[
        [0, 0, 0],
        [0, 1, 0],
        [0, 2, 0],
        [0, 3, 0],
        [0, 4, 0],
        [1, 4, 0],
        [2, 4, 0],
        [2, 3, 0],
        [2, 2, 0],
        [1, 2, 0],
    ]);
    let ring: Vec<[i32; 3]> = (0..5)
        .flat_map(|i| (0..5).map(move |j| [i, j, 0]))
        .filter(|&[i, j, _]| !(1..4).contains(&i) || !(1..4).contains(&j))
        .collect();
    let torus = voxels(&ring);
    // a fan of 5 triangles around a boundary vertex (an extraordinary boundary vertex of
    // triangles) with a quad strip
    let fan = {
        let mut pos = vec![[0.0, 0.0, 0.1]];
        for k in 0..=5 {
            let t = std::f64::consts::PI * f64::from(k) / 5.0;
            pos.push([t.cos(), t.sin(), 0.0]);
            pos.push([2.0 * t.cos(), 2.0 * t.sin(), 0.2 * t.sin()]);
        }
        let mut faces = Vec::new();
        for k in 0..5 {
            let (a, b) = (1 + 2 * k, 3 + 2 * k);
            faces.push(vec![0, a, b]);
            faces.push(vec![a, a + 1, b + 1, b]);
        }
        PolyMesh::new(pos, &faces).expect("the fan")
    };
    let l_shape = support::irregular_boundary_nets()
        .into_iter()
        .find(|(n, _)| *n == "l-shape")
        .expect("the L-shape")
        .1;
    vec![
        ("cross", cross),
        ("p", p),
        ("torus-quad", torus),
        ("split-edge-cube", fairsub::mesh::nets::split_edge_cube()),
        ("l-shape", l_shape),
        ("fan", fan),
        ("octahedron", support::gallery("octahedron")),
        ("prism-5", support::gallery("prism-5")),
    ]
}

#[test]
fn every_scheme_writes_every_net_g1_or_refuses_for_a_reason() {
    let opts = ComplexOptions {
        rings: 3,
        fill: true,
    };
    let mut failures = Vec::new();
    let mut written = 0;
    for (name, mesh) in nets() {
        for e in registry().entries() {
            if !e.capabilities().patches {
                continue;
            }
            let spec = registry().lookup(e.name).expect("registered");
            let what = format!("{name} under {}", e.name);
            match fairsub::surface::build(&spec, &mesh, opts, &mut |_| {}) {
                Ok(out) => {
                    let c = fairsub::analysis::continuity::check(&out.complex);
                    let g1 = c.by_kind.values().map(|d| d.g1).fold(0.0f64, f64::max);
                    eprintln!("{what}: G^1 {g1:.1e}, {} open sides", c.open_sides);
                    written += 1;
                    if g1.is_nan() || g1 >= 1e-8 {
                        failures.push(format!("{what}: G^1 {g1:e}"));
                    }
                }
                Err(err) => {
                    let msg = err.to_string();
                    eprintln!("{what}: refused: {msg}");
                    let triangles = mesh.is_all_triangles();
                    if e.id != ids::LOOP || triangles {
                        failures.push(format!("{what}: {msg}"));
                    }
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    assert!(written > 150, "{written} surfaces written");
}
