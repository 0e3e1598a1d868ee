//! CAD faces (`subdivide --faces`, `fairsub::surface::cad`): the merged faces are the patch
//! complex, exactly; their counts; their continuity as `check` reports it; and the B-rep
//! topology of the STEP file (closed solids, shared edges, T-points split).

use crate::cad_common;

use cad_common::{complex, net};
use fairsub::analysis::continuity;
use fairsub::bezier::complex::PatchComplex;
use fairsub::schemes::registry;
use fairsub::surface::cad::{self, FaceMode, FaceSource, brep};
use fairsub::surface::eval::Surface;

/// A small deterministic generator of points in `[0, 1)`.
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The schemes that evaluate at `(face, u, v)` and take quad nets.
const EVAL_SCHEMES: &[&str] = &[
    "catmull-clark",
    "doo-sabin",
    "doo-sabin-cc",
    "pgs",
    "pgs-dscc",
    "tps",
    "tps-adjustable",
    "eg",
    "qas-plus",
    "qas-plus-bi3",
    "guided-bi5",
    "guided-bi6",
];

#[test]
fn input_faces_evaluate_to_the_patch_complex() {
    for scheme in EVAL_SCHEMES {
        for name in ["cube", "prism-5", "torus-evs", "open-grid"] {
            if scheme.starts_with("tps") && name == "prism-5" {
                continue; // TPS takes quad nets only
            }
            let mesh = net(name);
            let spec = registry().lookup(scheme).unwrap();
            let c = complex(scheme, &mesh, 3);
            let faces = cad::faces(&c, FaceMode::Input).unwrap();
            let surface = Surface::of_scheme(&spec, &mesh, c.clone()).unwrap();
            let mut rng = Lcg(7);
            let mut worst: f64 = 0.0;
            let mut merged = 0;
            for (s, src) in faces.surfaces.iter().zip(&faces.sources) {
                let FaceSource::Input { face, sub } = *src else {
                    continue;
                };
                merged += 1;
                for _ in 0..20 {
                    let (u, v) = (rng.next(), rng.next());
                    let want = surface.evaluate(face, u + f64::from(sub), v).unwrap().point;
                    worst = worst.max(fairsub::geom::dist(s.eval(u, v), want));
                }
            }
            assert!(merged > 0, "{scheme} on {name}: no merged face");
            // relative to the model's size (TPS's cells in thirds round their maps once per
            // level, in the complex's evaluation and in the merge alike)
            let size = fairsub::surface::adjacency::default_tolerance(&c) * 1e9;
            assert!(
                worst <= 1e-12 * size,
                "{scheme} on {name}: merged faces off the complex by {worst:e} (size {size})"
            );
        }
    }
}

#[test]
fn one_face_per_input_quad_on_closed_nets() {
    for (scheme, name, want) in [
        ("catmull-clark", "cube", 6),
        ("catmull-clark", "torus-evs", 48),
        ("guided-bi6", "cube", 6),
        ("eg", "icosahedron", 60), // triangles: three quad sub-faces each
        ("pgs", "cube", 6),
        ("tps", "cube", 6),
    ] {
        let mesh = net(name);
        let c = complex(scheme, &mesh, 3);
        let f = cad::faces(&c, FaceMode::Input).unwrap();
        assert_eq!(f.len(), want, "{scheme} on {name}");
        assert_eq!(f.unmerged, 0, "{scheme} on {name}");
        assert_eq!(f.c0_faces, 0, "{scheme} on {name}");
        let patches = cad::faces(&c, FaceMode::Patches).unwrap();
        assert_eq!(patches.len(), c.len());
    }
}

#[test]
fn knot_multiplicities_state_the_continuity() {
    // Catmull-Clark on the cube: bi-4 faces (the cap's degree), rings C^2 (multiplicity 2),
    // the cap C^1 to the last ring (3), the face's own regular patch C^2 to the rings.
    let mesh = net("cube");
    let c = complex("catmull-clark", &mesh, 3);
    let f = cad::faces(&c, FaceMode::Input).unwrap();
    for s in &f.surfaces {
        assert_eq!(s.deg, [4, 4]);
        let (vals, mult) = cad::spline::distinct(&s.knots[0]);
        assert_eq!(vals, [0.0, 0.125, 0.25, 0.5, 0.75, 0.875, 1.0]);
        assert_eq!(mult, [5, 3, 2, 2, 2, 3, 5]);
    }
}

/// The merged faces cut back into Bezier patches, as a complex `check` can read.
fn as_complex(faces: &cad::CadFaces) -> PatchComplex {
    let mut c = PatchComplex::new();
    for s in &faces.surfaces {
        for (_, b) in s.bezier_pieces() {
            c.push(b, fairsub::surface::Provenance::Unknown);
        }
    }
    c
}

#[test]
fn check_reports_the_same_g1_figures_on_merged_faces() {
    for (scheme, name) in [
        ("catmull-clark", "cube"),
        ("catmull-clark", "prism-5"),
        ("guided-bi6", "torus-evs"),
        ("doo-sabin", "cube"),
        ("eg", "tetrahedron"),
    ] {
        let mesh = net(name);
        let c = complex(scheme, &mesh, 3);
        let f = cad::faces(&c, FaceMode::Input).unwrap();
        let a = continuity::check(&c);
        let b = continuity::check(&as_complex(&f));
        assert_eq!(b.open_sides, a.open_sides, "{scheme} on {name}");
        assert!(
            (a.all.g1 - b.all.g1).abs() <= 1e-9 && (a.all.c0 - b.all.c0).abs() <= 1e-9 * a.size,
            "{scheme} on {name}: G^1 {:e} vs {:e}, C^0 {:e} vs {:e}",
            a.all.g1,
            b.all.g1,
            a.all.c0,
            b.all.c0
        );
    }
}

#[test]
fn topology_is_closed_with_t_points_split() {
    // prism-5's n-gon caps are split into quad sub-faces, so each rim edge of a cap meets two
    // sub-faces on one side and one quad on the other: a T-point splits the quad's side.
    let mesh = net("prism-5");
    let c = complex("catmull-clark", &mesh, 3);
    let weld = fairsub::surface::adjacency::default_tolerance(&c);
    for mode in [FaceMode::Patches, FaceMode::Input] {
        let mut f = cad::faces(&c, mode).unwrap();
        let b = brep::build(&mut f.surfaces, weld);
        assert!(b.is_closed(), "{mode:?}: {} free edges", b.free_edges);
        assert_eq!(b.misoriented, 0, "{mode:?}");
        // Euler: V - E + F = 2 for a sphere
        let chi = b.vertices.len() as i64 - b.edges.len() as i64 + f.len() as i64;
        assert_eq!(chi, 2, "{mode:?}");
        assert!(brep::signed_volume(&f.surfaces) > 0.0);
    }
    // one face per quad, per quad sub-face of the caps
    let want: usize = (0..mesh.num_faces())
        .map(|f| match mesh.face_size(f) {
            4 => 1,
            n => n,
        })
        .sum();
    let f = cad::faces(&c, FaceMode::Input).unwrap();
    assert_eq!(f.len(), want);
}

/// A 6 x 6 grid of quads over a bump with semi-sharp creases of sharpness 6 (as on
/// OpenSubdiv's car): along the row `y = 3` and up the column `x = 3` from it, so faces have a
/// crease on one side, or on two sides meeting at a corner.
fn creased_grid() -> fairsub::mesh::PolyMesh {
    use std::fmt::Write as _;
    let mut obj = String::new();
    let id = |i: usize, j: usize| j * 7 + i;
    for j in 0..=6 {
        for i in 0..=6 {
            let (x, y) = (i as f64, j as f64);
            let z = 0.05 * ((x - 3.0).powi(2) + (y - 2.5).powi(2)) + 0.01 * x * y;
            writeln!(obj, "v {x} {y} {z}").unwrap();
        }
    }
    for j in 0..6 {
        for i in 0..6 {
            let c = [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)].map(|k| k + 1);
            writeln!(obj, "f {} {} {} {}", c[0], c[1], c[2], c[3]).unwrap();
        }
    }
    // OpenSubdiv's tag lines count vertices from 0
    for i in 0..6 {
        writeln!(obj, "t crease 2/1/0 {} {} 6.0", id(i, 3), id(i + 1, 3)).unwrap();
    }
    for j in 3..6 {
        writeln!(obj, "t crease 2/1/0 {} {} 6.0", id(3, j), id(3, j + 1)).unwrap();
    }
    let path = std::path::Path::new("creased-grid.obj");
    fairsub::io::obj::read_obj_from(obj.as_bytes(), path)
        .unwrap()
        .mesh
}

#[test]
fn semi_sharp_crease_faces_are_merged_at_their_continuity() {
    // Beside a crease of sharpness 6 a face holds the creases' refinement down to 2^-6 of the
    // face; Catmull-Clark's patches there are C^2 to each other, so every interior knot has
    // multiplicity 1 and the face costs fewer control points than its patches (at the C^0
    // multiplicity 3, a face with creases on two sides would need 37,249 instead of 4,489).
    let mesh = creased_grid();
    let c = complex("catmull-clark", &mesh, 3);
    let f = cad::faces(&c, FaceMode::Input).unwrap();
    assert_eq!(f.len(), 36);
    assert_eq!(f.unmerged, 0);
    assert_eq!(f.c0_faces, 0);
    let spec = registry().lookup("catmull-clark").unwrap();
    let surface = Surface::of_scheme(&spec, &mesh, c.clone()).unwrap();
    let mut rng = Lcg(11);
    let mut worst: f64 = 0.0;
    let mut finest = 0;
    for (s, src) in f.surfaces.iter().zip(&f.sources) {
        let FaceSource::Input { face, .. } = *src else {
            panic!("a face of its own: {src:?}");
        };
        assert_eq!(s.deg, [3, 3], "face {face}");
        for k in 0..2 {
            let (vals, mult) = cad::spline::distinct(&s.knots[k]);
            assert!(
                mult[1..mult.len() - 1].iter().all(|&m| m == 1),
                "face {face}: knots {vals:?} x {mult:?}"
            );
            finest = finest.max(vals.len() - 1);
        }
        for _ in 0..40 {
            let (u, v) = (rng.next(), rng.next());
            let want = surface.evaluate(face, u, v).unwrap().point;
            worst = worst.max(fairsub::geom::dist(s.eval(u, v), want));
        }
    }
    // the crease's refinement reaches 2^-6 of the face
    assert_eq!(finest, 64);
    let size = fairsub::surface::adjacency::default_tolerance(&c) * 1e9;
    assert!(worst <= 1e-12 * size, "off the complex by {worst:e}");
    let points: usize = f.surfaces.iter().map(|s| s.cps.len()).sum();
    let own: usize = c
        .patches
        .iter()
        .map(|p| (p.deg_u + 1) * (p.deg_v + 1))
        .sum();
    assert!(points < own, "{points} control points, the patches {own}");
}

/// prism-5 is a pentagonal prism with three bands of quads on its side: 15 quads and 2
/// pentagons, 17 faces (not the 7 of a prism without bands). Under every scheme with patch
/// output, `--faces input` (STEP and IGES, which write the same faces) gives one face per quad
/// and per quad sub-face of each pentagon, 15 + 2 x 5 = 25, each (face, sub-face) once (the
/// dual and ternary schemes included: their vertices' patches are cut at the faces' quarters,
/// and TPS's Catmull-Clark preparation step splits the pentagons the same way); non-box's
/// cubic triangles one face per patch; Loop refuses the pentagons. `measure --per-face` has
/// one entry per input face, 17 (a pentagon's sub-faces summed), adding up to the area.
/// `guided-bi3-macro` is left out (its complex alone takes 3 s to build on prism-5; the
/// command line gives it 25 and 17 as well).
#[test]
fn prism_5_face_counts_of_every_scheme() {
    let mesh = net("prism-5");
    assert_eq!((mesh.num_faces(), mesh.num_vertices()), (17, 20));
    let mut want = std::collections::BTreeSet::new();
    for f in 0..mesh.num_faces() {
        let n = mesh.face(f).len();
        let subs = if n == 4 { 1 } else { n };
        want.extend((0..subs as u32).map(|s| (f as u32, s)));
    }
    assert_eq!(want.len(), 25);
    let schemes = registry().names_with(|c| c.patches);
    assert_eq!(schemes.len(), 21, "{schemes:?}");
    for scheme in schemes {
        if scheme == "guided-bi3-macro" {
            continue;
        }
        let spec = registry().lookup(scheme).unwrap();
        let opts = fairsub::surface::ComplexOptions {
            rings: 1,
            fill: true,
        };
        let built = fairsub::surface::build(&spec, &mesh, opts, &mut |_| {});
        if scheme == "loop" {
            let Err(e) = built else {
                panic!("loop refuses pentagons")
            };
            let e = e.to_string();
            assert!(e.contains("triangle net"), "{e}");
            continue;
        }
        let c = built.unwrap().complex;
        let f = cad::faces(&c, FaceMode::Input).unwrap();
        if scheme.starts_with("nonbox") {
            assert_eq!(f.len(), c.len(), "{scheme}: one face per triangle patch");
            assert!(
                f.sources
                    .iter()
                    .all(|s| matches!(s, FaceSource::Patch { .. })),
                "{scheme}"
            );
        } else {
            let got: std::collections::BTreeSet<(u32, u32)> = f
                .sources
                .iter()
                .filter_map(|s| match *s {
                    FaceSource::Input { face, sub } => Some((face, sub)),
                    _ => None,
                })
                .collect();
            assert_eq!(f.len(), 25, "{scheme}: {} faces", f.len());
            assert_eq!(got, want, "{scheme}: the faces are the quads and sub-quads");
            assert_eq!(f.unmerged, 0, "{scheme}");
        }
        // measure --per-face: one area per input face
        let json =
            fairsub::cli::api::measure_json("gallery:prism-5", &c, &spec, &mesh, true, 1e-14)
                .unwrap();
        let v: serde_json::Value = serde_json::from_str(&json).unwrap();
        let areas: Vec<f64> = v["faces"]["areas"]
            .as_array()
            .unwrap()
            .iter()
            .map(|a| a.as_f64().unwrap())
            .collect();
        assert_eq!(areas.len(), 17, "{scheme}");
        assert!(areas.iter().all(|&a| a > 0.5), "{scheme}: {areas:?}");
        let total = v["area"].as_f64().unwrap();
        let sum = areas.iter().sum::<f64>() + v["faces"]["unassigned"].as_f64().unwrap();
        assert!(
            (sum - total).abs() <= 1e-12 * total,
            "{scheme}: {sum} vs {total}"
        );
    }
}
