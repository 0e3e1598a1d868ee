//! Packed CAD faces (`subdivide --faces packed`): rectangles of regular input faces merged into
//! one B-spline each. They are the input faces, exactly (every Bezier piece of a packed face is
//! one input face, up to a rotation of its parameters, to `1e-12` of the model's size); they
//! are fewer on nets with regular regions; Catmull-Clark's regular rectangles have simple
//! interior knots (C^2); and the B-rep of the packed faces is closed (T-points where a
//! rectangle's side meets several faces are split).

use crate::cad_common;

use cad_common::{complex, net};
use fairsub::bezier::BezierPatch;
use fairsub::geom::dist;
use fairsub::surface::cad::{self, FaceMode, FaceSource, brep};

/// The largest distance between `a` and `b` at a grid of points, the least over the four
/// rotations of `b`'s parameter square.
fn distance_up_to_rotation(a: impl Fn(f64, f64) -> fairsub::geom::Point, b: &BezierPatch) -> f64 {
    let rotations = [
        b.clone(),
        b.transposed().reversed_u(),
        b.reversed_u().reversed_v(),
        b.transposed().reversed_v(),
    ];
    rotations
        .iter()
        .map(|r| {
            let mut worst: f64 = 0.0;
            for i in 0..=6 {
                for j in 0..=6 {
                    let (u, v) = (i as f64 / 6.0, j as f64 / 6.0);
                    worst = worst.max(dist(a(u, v), r.eval(u, v)));
                }
            }
            worst
        })
        .fold(f64::INFINITY, f64::min)
}

/// Packed and input faces of `scheme` on `name`, with every packed rectangle's pieces checked
/// against the input face with the same corners; returns (input faces, packed faces,
/// rectangles of more than one face).
fn packed_against_input(scheme: &str, name: &str) -> (usize, usize, usize) {
    let mesh = net(name);
    let c = complex(scheme, &mesh, 3);
    let size = fairsub::surface::adjacency::default_tolerance(&c) * 1e9;
    let input = cad::faces(&c, FaceMode::Input).unwrap();
    let packed = cad::faces(&c, FaceMode::Packed).unwrap();
    let centres: Vec<_> = input.surfaces.iter().map(|s| s.eval(0.5, 0.5)).collect();
    let mut rects = 0;
    let mut held = 0;
    for (s, src) in packed.surfaces.iter().zip(&packed.sources) {
        let FaceSource::Packed { size: [w, h], .. } = *src else {
            held += 1;
            continue;
        };
        rects += 1;
        assert!(
            w * h > 1,
            "{scheme} on {name}: a packed face of one input face"
        );
        held += (w * h) as usize;
        // cell (i, j) of the rectangle is one input face (knot lines where the faces join
        // as one polynomial are dropped, so cells are not the spline's pieces)
        for (i, j) in (0..w).flat_map(|i| (0..h).map(move |j| (i, j))) {
            let (w, h) = (f64::from(w), f64::from(h));
            let cell = |x: f64, y: f64| s.eval((f64::from(i) + x) / w, (f64::from(j) + y) / h);
            let m = cell(0.5, 0.5);
            let nearest = (0..centres.len())
                .min_by(|&x, &y| dist(centres[x], m).total_cmp(&dist(centres[y], m)))
                .unwrap();
            let want = &input.surfaces[nearest];
            let (_, wb) = want.bezier_pieces().pop().unwrap();
            let d = distance_up_to_rotation(cell, &wb);
            assert!(
                d <= 1e-12 * size,
                "{scheme} on {name}: packed cell off its input face by {d:e}"
            );
        }
    }
    assert_eq!(
        held,
        input.len(),
        "{scheme} on {name}: every input face held once"
    );
    (input.len(), packed.len(), rects)
}

#[test]
fn packed_faces_are_the_input_faces() {
    // measured counts: (input faces, packed faces, rectangles)
    for (scheme, name, want) in [
        ("catmull-clark", "open-grid", (36, 1, 1)),
        ("catmull-clark", "torus-evs", (48, 27, 5)),
        ("catmull-clark", "open-pipe", (32, 1, 1)),
        ("guided-bi6", "torus-evs", (48, 27, 5)),
        ("eg", "torus-evs", (48, 27, 5)),
    ] {
        let got = packed_against_input(scheme, name);
        assert_eq!(got, want, "{scheme} on {name}");
        assert!(got.1 < got.0, "{scheme} on {name}: packing saves no face");
    }
    // no regular face on the cube: packed is input
    let (i, p, r) = packed_against_input("catmull-clark", "cube");
    assert_eq!((i, p, r), (6, 6, 0));
}

#[test]
fn catmull_clark_rectangles_have_simple_knots() {
    let mesh = net("torus-evs");
    let c = complex("catmull-clark", &mesh, 3);
    let packed = cad::faces(&c, FaceMode::Packed).unwrap();
    let mut rects = 0;
    for (s, src) in packed.surfaces.iter().zip(&packed.sources) {
        if let FaceSource::Packed { size, .. } = *src {
            rects += 1;
            assert_eq!(s.deg, [3, 3]);
            for (knots, n) in s.knots.iter().zip(size) {
                let (vals, mult) = cad::spline::distinct(knots);
                assert_eq!(vals.len() as u32, n + 1);
                assert!(mult[1..mult.len() - 1].iter().all(|&m| m == 1), "{mult:?}");
            }
        }
    }
    assert!(rects > 0);
}

#[test]
fn packed_topology_is_closed() {
    for (scheme, name, chi) in [("catmull-clark", "torus-evs", 0), ("eg", "prism-5", 2)] {
        let mesh = net(name);
        let c = complex(scheme, &mesh, 3);
        let weld = fairsub::surface::adjacency::default_tolerance(&c);
        let mut f = cad::faces(&c, FaceMode::Packed).unwrap();
        let b = brep::build(&mut f.surfaces, weld);
        assert!(
            b.is_closed(),
            "{scheme} on {name}: {} free edges",
            b.free_edges
        );
        assert_eq!(b.misoriented, 0);
        assert_eq!(b.nonmanifold, 0);
        let euler = b.vertices.len() as i64 - b.edges.len() as i64 + f.len() as i64;
        assert_eq!(euler, chi, "{scheme} on {name}");
        let mut input = cad::faces(&c, FaceMode::Input).unwrap();
        brep::build(&mut input.surfaces, weld);
        let (a, v) = (
            brep::signed_volume(&f.surfaces),
            brep::signed_volume(&input.surfaces),
        );
        assert!(a > 0.0 && (a - v).abs() <= 1e-12 * v, "{a} vs {v}");
    }
}
