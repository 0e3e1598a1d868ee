//! The limit surface's evaluation refines each extraordinary element only as far as its own
//! points need (`host::adaptive::RingTargets`, honoured by Catmull-Clark; on 10^6 random points
//! of a 10k-face net most vertices need 5 to 7 rings and a few 10): the result must evaluate
//! exactly like the complex with the most rings everywhere, and for quad meshes the estimate
//! from the points' distances to the corners (`quad_corner_targets`) must need no second
//! construction.

use fairsub::geom::dist;
use fairsub::mesh::PolyMesh;
use fairsub::schemes::registry::registry;
use fairsub::surface::ComplexOptions;
use fairsub::surface::eval::{Surface, limit_surface, limit_surface_from, quad_corner_targets};
use std::path::Path;

use crate::eval_helpers::support;
use support::{Lcg, gallery, irregular_boundary_nets};

/// Random points of every face (n-gons on their strip), half of them `2^-k` (`k = 1..=9`, a
/// random fraction of it) from a random corner: every element gets its own depth.
fn points(mesh: &PolyMesh, seed: u64) -> Vec<(u32, f64, f64)> {
    let mut r = Lcg(seed);
    let mut pts = Vec::new();
    for f in 0..mesh.num_faces() {
        let n = mesh.face_size(f);
        for k in 0..24 {
            let (mut u, mut v) = (r.next(), r.next());
            if k % 2 == 1 {
                let s = 0.5f64.powi(1 + (r.next() * 9.0) as i32);
                let c = (r.next() * 4.0) as usize;
                u = if c == 1 || c == 2 { 1.0 - s * u } else { s * u };
                v = if c >= 2 { 1.0 - s * v } else { s * v };
            }
            let sub = if n == 4 {
                0.0
            } else {
                (r.next() * n as f64).floor()
            };
            pts.push((f as u32, sub + u, v));
        }
    }
    pts
}

#[test]
fn per_element_rings_evaluate_as_the_most_rings_everywhere() {
    let spec = registry().lookup("catmull-clark").expect("registered");
    let osd = |name: &str| {
        let p = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/data/osd")
            .join(name);
        fairsub::io::read_mesh(&p).expect("osd net").mesh
    };
    // (net, one construction expected, several extraordinary elements)
    let mut nets: Vec<(String, PolyMesh, bool, bool)> = vec![
        (
            "cnet-5-saddle".into(),
            gallery("cnet-5-saddle"),
            true,
            false,
        ),
        (
            "cnet-3-convex".into(),
            gallery("cnet-3-convex"),
            true,
            false,
        ),
        // holes that touch (the cube's), n-gons (not estimated): more constructions
        ("cube".into(), gallery("cube"), false, true),
        (
            "cc_mixed_ngons".into(),
            osd("cc_mixed_ngons.obj"),
            false,
            true,
        ),
    ];
    for (name, m) in irregular_boundary_nets() {
        let several = name != "l-shape";
        nets.push((name.into(), m, true, several));
    }
    for (name, mesh, one_build, several) in nets {
        let pts = points(&mesh, 17);
        let build = |k: usize| {
            Surface::build(
                &spec,
                &mesh,
                ComplexOptions {
                    rings: k,
                    fill: true,
                },
            )
        };
        let mut builds = 0;
        let (s, rings) = limit_surface_from(&pts, quad_corner_targets(&mesh, &pts), &mut |k| {
            builds += 1;
            build(k)
        })
        .expect("limit surface");
        let all = build(rings).expect("uniform");
        // from 2 rings everywhere: its targets come from the 2-ring caps' cells, where the
        // nearest cell corner stands for the vertex (more rings, never fewer)
        let (plain, plain_rings) = limit_surface(&pts, &mut |k| build(k)).expect("from 2 rings");
        assert!(
            plain_rings >= rings,
            "{name}: {plain_rings} against {rings} rings"
        );
        assert!(rings >= 8, "{name}: {rings} rings");
        assert!(
            s.complex().len() < all.complex().len() || !several,
            "{name}: {} patches against {} with {rings} rings everywhere",
            s.complex().len(),
            all.complex().len()
        );
        if one_build {
            assert_eq!(builds, 1, "{name}: the estimate needed more constructions");
        }
        for &(f, u, v) in &pts {
            let (a, b, c) = (
                s.evaluate(f, u, v).expect("point"),
                all.evaluate(f, u, v).expect("point"),
                plain.evaluate(f, u, v).expect("point"),
            );
            for e in [&a, &c] {
                assert!(
                    dist(e.point, b.point) == 0.0 && dist(e.normal, b.normal) < 1e-15,
                    "{name}: face {f} ({u}, {v}): {:?} against {:?}",
                    e.point,
                    b.point
                );
                assert!(
                    (e.gauss - b.gauss).abs() <= 1e-12 * b.gauss.abs().max(1.0),
                    "{name}: face {f} ({u}, {v}): K {} against {}",
                    e.gauss,
                    b.gauss
                );
            }
        }
        eprintln!(
            "{name}: {rings} rings, {} patches against {} everywhere, {builds} construction(s)",
            s.complex().len(),
            all.complex().len()
        );
    }
}
