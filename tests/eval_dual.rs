//! Evaluation of the dual bi-2 schemes (Doo-Sabin, DS^CC, PGS) at `(face, u, v)`: the patch of
//! an input vertex covers a quarter of each face around it (four pieces of one patch), every
//! later patch one dyadic cell of a face, the caps and fills the cells at the hole's centre
//! (corner `(0, 0)` of the quarters at an extraordinary vertex, the centre `(1, 1)` of an
//! n-gon's sub-faces). Tests: agreement with the patches `subdivide --rings` writes at random
//! points of every face (caps included; on nets with a boundary, the quarters at boundary
//! vertices are errors), continuity across every line of a dyadic grid of every face (a piece
//! in the wrong quarter, or turned, jumps there), and convergence to the limit point at the
//! rate of the scheme's subdominant eigenvalue. Also Catmull-Clark's triangles, which share the
//! dual schemes' 3-gon domain.

use fairsub::geom::dist;
use fairsub::mesh::PolyMesh;
use fairsub::schemes::registry::ids;

#[path = "eval/support.rs"]
mod support;
use support::{gallery, toward_ev};
#[path = "eval/faces.rs"]
mod faces;
use faces::{all_agree, all_continuous, at_interior_vertex};
#[path = "eval/ratios.rs"]
mod ratios;

fn dual_schemes() -> [&'static str; 3] {
    [
        ids::DOO_SABIN.name(),
        ids::DOO_SABIN_CC.name(),
        ids::PGS.name(),
    ]
}

#[test]
fn dual_schemes_eval_agrees_with_the_written_patches() {
    // closed nets (triangles, pentagons, valences 3 to 5) and a c-net with a boundary
    let nets = [
        "cube",
        "prism-5",
        "tetrahedron",
        "torus-evs",
        "octahedron",
        "cnet-5-saddle",
    ];
    all_agree(
        &dual_schemes(),
        &nets,
        &[1, 2, 3, 1, 2, 3],
        &at_interior_vertex,
    );
}

#[test]
fn dual_scheme_evaluation_is_continuous_across_patch_boundaries() {
    // cells go down to 2^-4 (3 rings, up to 2 more levels separating the holes, the
    // quarters of level 0)
    all_continuous(&dual_schemes(), &["cube", "prism-5", "tetrahedron"]);
}

/// The subdominant eigenvalue of `scheme` at an `n`-gon (the V-face of a vertex of valence
/// `n` after one step): `fairsub analyze`'s, or for DS^CC (which has no local analysis) that
/// of its corner rule's circulant, `1/2 + cos(2 pi / n) / 4` (mode 1 of `v_i / 2 + (v_(i-1) +
/// v_(i+1)) / 8 + c / 4`; it exceeds the rest of the matrix's 1/2 for n >= 5).
fn lambda(scheme: &str, n: usize) -> f64 {
    if scheme == ids::DOO_SABIN_CC.name() {
        return 0.5 + (2.0 * std::f64::consts::PI / n as f64).cos() / 4.0;
    }
    ratios::lambda(scheme, n)
}

/// The limit evaluation's centre along `at` after asserting the error ratios are `lambda`
/// ([`ratios::converges`] with 12 rings at least).
fn converges(
    scheme: &str,
    mesh: &PolyMesh,
    at: impl Fn(f64) -> (u32, f64, f64),
    lambda: f64,
    what: &str,
) -> fairsub::geom::Point {
    ratios::converges(scheme, mesh, at, lambda, 12, what).0
}

#[test]
fn dual_limit_evaluation_converges_at_rate_lambda() {
    for (scheme, n) in [
        (ids::DOO_SABIN.name(), 3),
        (ids::DOO_SABIN.name(), 5),
        (ids::DOO_SABIN_CC.name(), 5),
        (ids::PGS.name(), 5),
        (ids::PGS.name(), 6),
    ] {
        let mesh = gallery(&format!("cnet-{n}-saddle"));
        let (_, at) = toward_ev(&mesh, n);
        converges(
            scheme,
            &mesh,
            at,
            lambda(scheme, n),
            &format!("vertex n = {n}"),
        );
    }
    // toward the centre (1, 1) of the last sub-face of a pentagon (u = 5 on its strip; u = 1
    // would be sub-face 1's corner 0): Doo-Sabin's limit point of a facet is its centroid
    let mesh = gallery("prism-5");
    let f = (0..mesh.num_faces())
        .find(|&f| mesh.face_size(f) == 5)
        .expect("a pentagon");
    let at = |h: f64| (f as u32, 5.0 - 0.6 * h, 1.0 - 0.3 * h);
    let scheme = ids::DOO_SABIN.name();
    let centre = converges(scheme, &mesh, at, lambda(scheme, 5), "facet n = 5");
    let face = mesh.face(f);
    let mut c = [0.0; 3];
    for &x in face {
        c = fairsub::geom::axpy(c, 1.0 / face.len() as f64, mesh.position(x as usize));
    }
    assert!(
        dist(centre, c) < 1e-12,
        "Doo-Sabin facet limit {centre:?}, centroid {c:?}"
    );
}

/// Catmull-Clark splits a triangle into three quads, as the dual schemes' domains do: its
/// triangles are 3-gons on the strip `[0, 3] x [0, 1]` (they were once given Loop's
/// barycentric cells, and the evaluation jumped by 0.25 across `u = 1/4`).
#[test]
fn catmull_clark_triangles_are_three_quad_sub_faces() {
    let cc = [ids::CATMULL_CLARK.name()];
    all_agree(&cc, &["tetrahedron"], &[2], &|_, _| true);
    all_continuous(&cc, &["tetrahedron"]);
}
