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

use crate::eval_helpers::faces;
use crate::eval_helpers::ratios;
use crate::eval_helpers::support;
use faces::{
    Covered, agrees_with, all_agree, all_continuous, at_interior_vertex, face_points, largest_jump,
    surface_of,
};
use fairsub::mesh::Extras;
use fairsub::mesh::tags::{BoundaryInterpolation, SubdOptions};
use support::{gallery, irregular_boundary_nets, toward_ev, via_obj, written_from};

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
    all_agree(&dual_schemes(), &nets, &[1, 2, 3, 1, 2, 3], &|_, _| true);
}

/// Open nets: the c-nets (their boundary vertices regular: two quads, or a corner with one)
/// and the open grid. The patch of a regular boundary vertex spans half a face beyond the
/// boundary edges (the doubled boundary layer: the boundary curve is the line of knots
/// between the phantom row and the boundary row); its halves over the vertex's faces are the
/// quarters of those faces, as at an interior vertex, so every point of every face evaluates.
const OPEN: [&str; 3] = ["cnet-5-saddle", "cnet-3-convex", "open-grid"];

#[test]
fn dual_schemes_evaluate_the_quarters_at_boundary_vertices() {
    all_agree(&dual_schemes(), &OPEN[..2], &[2, 3], &|_, _| true);
    all_continuous(&dual_schemes(), &OPEN);
}

/// Every point of every face of nets with extraordinary boundary vertices evaluates (the
/// quarters at those vertices were not tracked before 2026-12-04): it agrees with the patches
/// `subdivide --rings` writes to 1e-12, points near the vertex lie on its fill, and the
/// evaluation is continuous across the lines `i 2^-6` of every face.
#[test]
fn dual_schemes_evaluate_next_to_extraordinary_boundary_vertices() {
    for (name, mesh) in irregular_boundary_nets() {
        let (mesh, src) = via_obj(&mesh, name);
        for scheme in dual_schemes().into_iter().chain([ids::PGS_DSCC.name()]) {
            let written = written_from(&src, name, scheme, 3);
            let (mesh, s) = surface_of(mesh.clone(), scheme, 3);
            let (worst, in_caps) = agrees_with(&written, &mesh, &s, &|_, _| true);
            let jump = largest_jump(&mesh, &s, 1 << 6, 1e-10, &|_, _| true);
            eprintln!(
                "{name} under {scheme}: largest difference {worst:.3e}, {in_caps} points on \
                 caps and fills, largest jump {jump:.3e}"
            );
            assert!(worst <= 1e-12, "{name} under {scheme}: {worst:e}");
            assert!(in_caps > 0, "{name} under {scheme}: no point on a fill");
            assert!(jump < 1e-7, "{name} under {scheme}: jump {jump:e}");
        }
    }
}

/// The same nets' complexes are G^1 at every join (fills included) under the dual schemes, as
/// `check` measures them (1e-14 rad on 2026-12-04). Catmull-Clark and the schemes that fall
/// back to it close them with open-fan G^1 caps (`tests/it/boundary_caps.rs`).
#[test]
fn dual_schemes_are_g1_at_extraordinary_boundary_vertices() {
    use fairsub::analysis::continuity::check;
    use fairsub::surface::{ComplexOptions, complex};
    for (name, mesh) in irregular_boundary_nets() {
        for scheme in dual_schemes().into_iter().chain([ids::PGS_DSCC.name()]) {
            let opts = ComplexOptions {
                rings: 3,
                fill: true,
            };
            let c = complex(scheme, &mesh, opts, |_| {})
                .unwrap_or_else(|e| panic!("{name} under {scheme}: {e}"));
            let r = check(&c);
            assert!(!r.by_kind.is_empty(), "{name} under {scheme}: no joins");
            for (kind, d) in &r.by_kind {
                assert!(
                    d.g1 < 1e-8,
                    "{name} under {scheme}, {kind}: G^1 {:e} at {:?}",
                    d.g1,
                    d.g1_at
                );
            }
        }
    }
}

/// `mesh` with the boundary mode `mode`.
fn with_mode(mesh: PolyMesh, mode: BoundaryInterpolation) -> PolyMesh {
    mesh.with_extras(Some(Extras {
        options: SubdOptions {
            boundary: Some(mode),
            ..SubdOptions::default()
        },
        ..Extras::default()
    }))
}

/// The boundary modes (`schemes::doo_sabin`): under `edge-only` a corner (one quad) is not
/// kept, so it is an extraordinary element (its V-face a triangle) refined next to the
/// boundary; its corner point carries the quarter of its face, so every point evaluates (until
/// 2026-12-04 the quarters at corners were errors). Under `none` the patches of boundary
/// vertices are not part of the surface, so there is no surface over the quarters at boundary
/// vertices: errors there.
#[test]
fn boundary_modes_decide_which_boundary_quarters_evaluate() {
    let modes: [(BoundaryInterpolation, &Covered); 2] = [
        (BoundaryInterpolation::EdgeOnly, &|_, _| true),
        (BoundaryInterpolation::None, &at_interior_vertex),
    ];
    for scheme in dual_schemes() {
        for (mode, covered) in modes {
            for net in OPEN {
                let mesh = with_mode(gallery(net), mode);
                let (mesh, s) = surface_of(mesh, scheme, 2);
                let pts = face_points(&mesh, 60, 29);
                let ok = pts.iter().filter(|&&p| covered(&mesh, p)).count();
                for &(f, u, v) in &pts {
                    let got = s.evaluate(f, u, v);
                    assert_eq!(
                        got.is_ok(),
                        covered(&mesh, (f, u, v)),
                        "{net} under {scheme}, {mode:?}: face {f} at ({u}, {v}): {:?}",
                        got.err()
                    );
                }
                eprintln!(
                    "{net} under {scheme}, {mode:?}: {ok} of {} points evaluate",
                    pts.len()
                );
            }
        }
    }
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
