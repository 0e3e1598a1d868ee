//! Helpers shared by the evaluation tests (`tests/it/eval.rs`, `tests/it/eval_caps.rs`): gallery nets,
//! deterministic random numbers and a temporary directory per test process.

use fairsub::mesh::PolyMesh;
use fairsub::schemes::registry::registry;
use fairsub::surface::ComplexOptions;
use fairsub::surface::eval::{Evaluation, Surface, evaluate_limit};

/// The gallery net `name`.
pub fn gallery(name: &str) -> PolyMesh {
    fairsub::gallery::all()
        .into_iter()
        .find(|(n, _)| n == name)
        .unwrap_or_else(|| panic!("gallery net {name}"))
        .1
}

/// Deterministic points in `[0, 1)`.
pub struct Lcg(pub u64);
impl Lcg {
    /// The next number.
    pub fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A path `name` in a new scratch folder (`prefix` names the test; see `common::scratch`).
pub fn tmp(prefix: &str, name: &str) -> std::path::PathBuf {
    crate::common::scratch(prefix).join(name)
}

/// `mesh` written to an OBJ file and read back, with the file's path (the CLI reads the same
/// file as the library's surface).
#[allow(dead_code)]
pub fn via_obj(mesh: &PolyMesh, name: &str) -> (PolyMesh, String) {
    let path = tmp("fairsub-eval-nets", &format!("{name}.obj"));
    fairsub::io::write_mesh(&path, mesh, fairsub::io::MeshFormat::Obj).expect("write");
    let back = fairsub::io::read_mesh(&path).expect("read back").mesh;
    (back, path.to_str().expect("utf-8 path").to_string())
}

/// The interior vertex of valence `n` of a net (a c-net, or a triangle net for Loop), a face at it
/// (quad or triangle), and the face point at distance `h` from it (along a fixed direction into
/// the face).
pub fn toward_ev(mesh: &PolyMesh, n: usize) -> (usize, impl Fn(f64) -> (u32, f64, f64)) {
    let ev = (0..mesh.num_vertices())
        .find(|&v| mesh.valence(v) == n && !mesh.is_boundary_vertex(v))
        .expect("the extraordinary vertex");
    let (f, c) = (0..mesh.num_faces())
        .find_map(|f| {
            mesh.face(f)
                .iter()
                .position(|&w| w as usize == ev)
                .map(|c| (f, c))
        })
        .expect("a face at the vertex");
    let corners: &[[f64; 2]] = if mesh.face_size(f) == 3 {
        &[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]
    } else {
        &[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
    };
    let k = corners.len();
    let (o, a, b) = (corners[c], corners[(c + 1) % k], corners[(c + k - 1) % k]);
    let at = move |h: f64| {
        let x = o[0] + h * (0.6 * (a[0] - o[0]) + 0.3 * (b[0] - o[0]));
        let y = o[1] + h * (0.6 * (a[1] - o[1]) + 0.3 * (b[1] - o[1]));
        (f as u32, x, y)
    };
    (ev, at)
}

/// The limit surface of `scheme` on `mesh` ([`evaluate_limit`]) at `at(2^-k)` for `k = 2 ..=
/// 12` and, last, at `at(0)`; asserts that at least `min_rings` rings were computed (12, or
/// fewer for schemes whose complex starts after whole-net steps: `pgs-dscc`'s two).
pub fn limit_along(
    scheme: &str,
    mesh: &PolyMesh,
    at: &dyn Fn(f64) -> (u32, f64, f64),
    min_rings: usize,
) -> Vec<Evaluation> {
    let mut pts: Vec<(u32, f64, f64)> = (2..=12).map(|k| at(0.5f64.powi(k))).collect();
    pts.push(at(0.0));
    let spec = registry().lookup(scheme).expect("scheme");
    let (evals, rings) = evaluate_limit(&pts, &mut |k| {
        Surface::build(
            &spec,
            mesh,
            ComplexOptions {
                rings: k,
                fill: true,
            },
        )
    })
    .expect("limit evaluation");
    eprintln!("{scheme}: {rings} rings");
    assert!(
        rings >= min_rings,
        "{scheme}: {rings} rings for points at 2^-12"
    );
    evals
}

/// The patches `subdivide --rings` writes for gallery net `net` under `scheme`, read back from
/// the `.bv` file.
pub fn written(net: &str, scheme: &str, rings: usize) -> fairsub::bezier::complex::PatchComplex {
    written_from(&format!("gallery:{net}"), net, scheme, rings)
}

/// The patches `subdivide --rings` writes for the net `src` (a path or `gallery:NAME`), `name`
/// naming the output file.
pub fn written_from(
    src: &str,
    name: &str,
    scheme: &str,
    rings: usize,
) -> fairsub::bezier::complex::PatchComplex {
    let out = tmp(
        "fairsub-eval-written",
        &format!("{name}-{scheme}-{rings}.bv"),
    );
    let words = [
        "fairsub",
        "subdivide",
        src,
        "--scheme",
        scheme,
        "--rings",
        &rings.to_string(),
        "-o",
        out.to_str().expect("utf-8 path"),
    ];
    fairsub::cli::run_words(words).expect("subdivide writes the patches");
    let bv = fairsub::io::read_bv(&out).expect("read back");
    fairsub::render::complex_from_bv(&bv)
}

/// Nets with extraordinary boundary vertices (no gallery net has one): an L-shaped 4 x 4 grid
/// of curved quads whose concave corner is a boundary vertex of three quads, and
/// `cnet-5-saddle` without one face at its centre (a boundary vertex of four quads).
#[allow(dead_code)]
pub fn irregular_boundary_nets() -> Vec<(&'static str, PolyMesh)> {
    let mut pos = Vec::new();
    let mut faces = Vec::new();
    let at = |i: usize, j: usize| i * 5 + j;
    for i in 0..5 {
        for j in 0..5 {
            let (x, y) = (i as f64, j as f64);
            pos.push([x, y, 0.1 * x.sin() * (1.3 * y).cos()]);
        }
    }
    for i in 0..4 {
        for j in 0..4 {
            if i < 2 || j < 2 {
                faces.push(vec![at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]);
            }
        }
    }
    let l_shape = PolyMesh::new(pos, &faces).expect("the L-shaped net");
    let cnet = gallery("cnet-5-saddle");
    let centre = (0..cnet.num_vertices())
        .find(|&v| !cnet.is_boundary_vertex(v) && cnet.valence(v) == 5)
        .expect("the centre");
    let mut dropped = false;
    let kept: Vec<Vec<usize>> = (0..cnet.num_faces())
        .map(|f| cnet.face(f))
        .filter(|f| {
            let drop = !dropped && f.contains(&(centre as u32));
            dropped |= drop;
            !drop
        })
        .map(|f| f.iter().map(|&x| x as usize).collect())
        .collect();
    let notched = PolyMesh::new(cnet.positions().to_vec(), &kept).expect("the notched c-net");
    assert!(notched.is_boundary_vertex(centre) && notched.vertex_faces(centre).len() == 4);
    vec![("l-shape", l_shape), ("cnet-5-notched", notched)]
}
