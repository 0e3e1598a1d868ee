//! `fairsub measure --per-face` where the input faces are fan triangles of the polygons the
//! complex is built on (`nonbox-4dir` on quasi-four-directional triangle meshes): each
//! triangle's area equals a composite quadrature of `|S_u x S_v|` over its own barycentric
//! domain through `Surface::evaluate`, the areas add up to the surface's, and on the cube's
//! triangulation (24 triangles, congruent under the cube's symmetries) they are equal.

use fairsub::geom::{cross, norm};
use fairsub::mesh::PolyMesh;
use fairsub::schemes::nonbox::FcvNet;
use fairsub::surface::ComplexOptions;
use fairsub::surface::eval::Surface;

/// The quasi-four-directional triangle mesh of gallery net `name`, and an OBJ file of it.
fn four_dir(name: &str) -> (PolyMesh, String) {
    let net = fairsub::gallery::all()
        .into_iter()
        .find(|(n, _)| n == name)
        .expect("gallery net")
        .1;
    let tri = fairsub::schemes::nonbox::fourdir::triangulate(&FcvNet::from_mesh(&net));
    let dir = std::env::temp_dir().join(format!("fairsub-measure-faces-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join(format!("{name}-4dir.obj"));
    fairsub::io::write_mesh(&path, &tri.mesh, fairsub::io::MeshFormat::Obj).expect("write");
    let back = fairsub::io::read_mesh(&path).expect("read back").mesh;
    (back, path.to_str().expect("utf-8").to_string())
}

/// `fairsub measure FILE --scheme nonbox-4dir --rings 2 --json --per-face`: the total area,
/// the per-face areas and the unassigned area.
fn measured(path: &str) -> (f64, Vec<f64>, f64) {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_fairsub"))
        .args([
            "measure",
            path,
            "--scheme",
            "nonbox-4dir",
            "--rings",
            "2",
            "--json",
            "--per-face",
        ])
        .output()
        .expect("runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let j: serde_json::Value = serde_json::from_slice(&out.stdout).expect("json");
    let areas = j["faces"]["areas"]
        .as_array()
        .expect("areas")
        .iter()
        .map(|a| a.as_f64().expect("number"))
        .collect();
    (
        j["area"].as_f64().expect("area"),
        areas,
        j["faces"]["unassigned"].as_f64().expect("unassigned"),
    )
}

/// The area of input triangle `face` by the composite 3-point (edge midpoint) rule on its
/// `m^2` sub-triangles, through `evaluate`'s derivatives by the triangle's own `(u, v)`.
fn quadrature_area(s: &Surface, face: u32, m: usize) -> f64 {
    let h = 1.0 / m as f64;
    let element = |u: f64, v: f64| {
        let e = s.evaluate(face, u, v).expect("in the domain");
        norm(cross(e.du, e.dv))
    };
    let tri = |a: [f64; 2], b: [f64; 2], c: [f64; 2]| {
        let mid = |p: [f64; 2], q: [f64; 2]| [(p[0] + q[0]) / 2.0, (p[1] + q[1]) / 2.0];
        let pts = [mid(a, b), mid(b, c), mid(c, a)];
        pts.iter().map(|p| element(p[0], p[1])).sum::<f64>() / 3.0 * (h * h / 2.0)
    };
    let mut total = 0.0;
    for i in 0..m {
        for j in 0..m - i {
            let (u, v) = (i as f64 * h, j as f64 * h);
            total += tri([u, v], [u + h, v], [u, v + h]);
            if i + j + 1 < m {
                total += tri([u + h, v], [u + h, v + h], [u, v + h]);
            }
        }
    }
    total
}

#[test]
fn fan_triangles_get_the_area_over_them() {
    for name in ["cube", "prism-5"] {
        let (mesh, path) = four_dir(name);
        let (area, faces, unassigned) = measured(&path);
        assert_eq!(faces.len(), mesh.num_faces(), "{name}");
        let sum: f64 = faces.iter().sum();
        assert!(
            (sum - area).abs() <= 1e-12 * area,
            "{name}: {sum} vs {area}"
        );
        assert!(unassigned <= 1e-14 * area, "{name}: {unassigned}");
        let spec = fairsub::schemes::registry::registry()
            .lookup("nonbox-4dir")
            .expect("scheme");
        let s = Surface::build(
            &spec,
            &mesh,
            ComplexOptions {
                rings: 2,
                fill: true,
            },
        )
        .expect("surface");
        // the area element is only C^0 across patches: the rule converges like h^2, to well
        // within the area of any one patch
        for (f, a) in faces.iter().enumerate() {
            let q = quadrature_area(&s, f as u32, 96);
            assert!(
                (q - a).abs() <= 1e-4 * a,
                "{name} face {f}: measured {a}, quadrature {q}"
            );
        }
        if name == "cube" {
            let (lo, hi) = faces
                .iter()
                .fold((f64::INFINITY, 0.0f64), |(l, h), &x| (l.min(x), h.max(x)));
            assert!(hi - lo <= 1e-12 * hi, "{lo} .. {hi}");
            assert!((hi - area / 24.0).abs() <= 1e-12 * area);
        }
    }
}
