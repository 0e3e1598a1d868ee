//! sqrt(3) subdivision and the modified butterfly scheme on their own (issue 48): Kobbelt's
//! boundary rule, sqrt(3)'s limit positions, both local spectra against their closed forms,
//! interpolation, and the command line (`schemes`, `subdivide --levels / --limit`, `analyze`).
//! The point-by-point comparisons with CGAL and OpenMesh are in `tests/it/peer_sqrt3_butterfly.rs`.

use fairsub::error::Result;
use fairsub::geom::Point;
use fairsub::mesh::{PolyMesh, nets};
use fairsub::schemes::local::spectrum;
use fairsub::schemes::{Scheme, butterfly, by_name, sqrt3};

fn run(words: &[&str]) -> (Result<()>, String) {
    let mut all = vec!["fairsub"];
    all.extend_from_slice(words);
    fairsub::cli::capture(|| fairsub::cli::run_words(all))
}

fn dist(a: &Point, b: &Point) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

fn lerp3(a: &Point, wa: f64, b: &Point, wb: f64, c: &Point, wc: f64) -> Point {
    std::array::from_fn(|k| wa * a[k] + wb * b[k] + wc * c[k])
}

/// An open net with an extraordinary interior vertex and a bumpy boundary.
fn open_net() -> PolyMesh {
    let mut m = nets::loop_net(5, 2);
    let pos: Vec<Point> = m
        .positions()
        .iter()
        .enumerate()
        .map(|(i, p)| [p[0], p[1], p[2] + 0.1 * (i as f64 * 1.7).sin()])
        .collect();
    m.set_positions(pos);
    m
}

/// The boundary loop of `mesh` as points, walked from its first boundary vertex.
fn boundary_points(mesh: &PolyMesh) -> Vec<Point> {
    let loops = mesh.boundary_loops();
    assert_eq!(loops.len(), 1);
    loops[0]
        .iter()
        .map(|&v| mesh.position(v as usize))
        .collect()
}

/// Every point of `want` has a point of `have` within 1e-12 and the counts agree.
fn same_point_set(have: &[Point], want: &[Point], what: &str) {
    assert_eq!(have.len(), want.len(), "{what}: counts");
    for w in want {
        let d = have
            .iter()
            .map(|h| dist(h, w))
            .fold(f64::INFINITY, f64::min);
        assert!(d < 1e-12, "{what}: {w:?} missing (nearest {d:e})");
    }
}

#[test]
fn sqrt3_boundary_follows_kobbelts_rule() {
    let net = open_net();
    let s = sqrt3::Sqrt3;
    let b0 = boundary_points(&net);
    // Step 1 leaves the boundary polygon as it is.
    let one = s.refine_uniform(&net, 1, &mut |_| {}).unwrap();
    same_point_set(&boundary_points(&one), &b0, "after one step");
    // Step 2 is the ternary cubic B-spline step: (4, 19, 4) / 27 at the old points,
    // (1, 16, 10) / 27 and (10, 16, 1) / 27 on each edge.
    let two = s.refine_uniform(&net, 2, &mut |_| {}).unwrap();
    let n = b0.len();
    let mut want = Vec::new();
    for i in 0..n {
        let (r, p, q, t) = (
            &b0[(i + n - 1) % n],
            &b0[i],
            &b0[(i + 1) % n],
            &b0[(i + 2) % n],
        );
        want.push(lerp3(r, 4.0 / 27.0, p, 19.0 / 27.0, q, 4.0 / 27.0));
        want.push(lerp3(r, 1.0 / 27.0, p, 16.0 / 27.0, q, 10.0 / 27.0));
        want.push(lerp3(p, 10.0 / 27.0, q, 16.0 / 27.0, t, 1.0 / 27.0));
    }
    same_point_set(&boundary_points(&two), &want, "after two steps");
    // Three steps: odd again, the boundary of step 2 kept.
    let three = s.refine_uniform(&net, 3, &mut |_| {}).unwrap();
    same_point_set(&boundary_points(&three), &want, "after three steps");
    // Every triangle is cut in three at every step.
    assert_eq!(three.num_faces(), 27 * net.num_faces());
}

#[test]
fn sqrt3_limit_positions_are_invariant_and_approached() {
    let s = sqrt3::Sqrt3;
    for net in [nets::icosahedron(), nets::tetrahedron(), open_net()] {
        let l0 = s.limit_stencils(&net).unwrap().apply(net.positions());
        // Two levels on: vertex v is still vertex v, with the same limit point.
        let two = s.refine_uniform(&net, 2, &mut |_| {}).unwrap();
        let l2 = s.limit_stencils(&two).unwrap().apply(two.positions());
        for v in 0..net.num_vertices() {
            assert!(
                dist(&l0[v], &l2[v]) < 1e-12,
                "vertex {v}: {:?} vs {:?}",
                l0[v],
                l2[v]
            );
        }
        // The vertices converge to them.
        let d = |levels: usize| {
            let m = s.refine_uniform(&net, levels, &mut |_| {}).unwrap();
            (0..net.num_vertices())
                .map(|v| dist(&m.position(v), &l0[v]))
                .fold(0.0, f64::max)
        };
        let (d2, d6) = (d(2), d(6));
        assert!(d6 < d2 / 20.0 && d6 < 1e-2, "{d2} -> {d6}");
    }
}

#[test]
fn sqrt3_spectrum_is_kobbelts() {
    for n in 3..=12 {
        let m = sqrt3::local::local_matrix(n).unwrap();
        let mut ev: Vec<f64> = fairsub::linalg::eigenvalues(&m.matrix)
            .iter()
            .map(|z| {
                assert!(z.im.abs() < 1e-9, "n = {n}: complex eigenvalue {z}");
                z.re
            })
            .collect();
        let a = sqrt3::alpha(n);
        let mut want = vec![1.0, (2.0 / 3.0 - a).powi(2)];
        for k in 1..n {
            want.push((2.0 + 2.0 * (std::f64::consts::TAU * k as f64 / n as f64).cos()) / 9.0);
        }
        ev.sort_by(f64::total_cmp);
        want.sort_by(f64::total_cmp);
        for (e, w) in ev.iter().zip(&want) {
            assert!((e - w).abs() < 1e-10, "n = {n}: {ev:?} vs {want:?}");
        }
        // alpha_n makes the centre's eigenvalue the square of the subdominant one.
        let sub = (2.0 + 2.0 * (std::f64::consts::TAU / n as f64).cos()) / 9.0;
        assert!(((2.0 / 3.0 - a).powi(2) - sub * sub).abs() < 1e-14);
        let sp = spectrum(&m.matrix);
        assert!(
            (sp.lambda - sub).abs() < 1e-10,
            "n = {n}: lambda {}",
            sp.lambda
        );
    }
}

#[test]
fn butterfly_spectrum_is_zss() {
    for n in [3, 4, 5, 7, 8, 12] {
        let m = butterfly::local::local_matrix(n).unwrap();
        let mut ev: Vec<f64> = fairsub::linalg::eigenvalues(&m.matrix)
            .iter()
            .map(|z| z.re)
            .collect();
        ev.sort_by(|a, b| b.total_cmp(a));
        // 1 (the centre), then the ring's Fourier symbols: 1/2 twice, 1/4 (k = 0) and for
        // n >= 4 the rest: 1/4 once (n = 4), 1/4 twice and zeros (n >= 5).
        let mut want = vec![1.0, 0.5, 0.5, 0.25];
        match n {
            3 => {}
            4 => want.push(0.25),
            _ => {
                want.extend([0.25, 0.25]);
                want.resize(n + 1, 0.0);
            }
        }
        for (e, w) in ev.iter().zip(&want) {
            assert!((e - w).abs() < 1e-12, "n = {n}: {ev:?} vs {want:?}");
        }
        assert_eq!(ev.len(), want.len());
    }
    assert!(butterfly::local::local_matrix(6).is_err());
}

#[test]
fn butterfly_interpolates_and_keeps_planes() {
    let s = butterfly::Butterfly;
    for net in [nets::icosahedron(), open_net(), nets::tri_grid()] {
        let r = s.refine_uniform(&net, 2, &mut |_| {}).unwrap();
        for v in 0..net.num_vertices() {
            assert_eq!(r.position(v), net.position(v));
        }
    }
    // A flat net stays flat (every rule's weights sum to 1 and are affine).
    let flat = nets::loop_net(5, 3);
    let r = s.refine_uniform(&flat, 2, &mut |_| {}).unwrap();
    assert!(r.positions().iter().all(|p| p[2].abs() < 1e-12));
}

#[test]
fn both_run_from_the_command_line() {
    let dir = std::env::temp_dir().join(format!("fairsub-sqrt3-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (r, out) = run(&["schemes", "--json"]);
    r.unwrap();
    let cat: serde_json::Value = serde_json::from_str(&out).unwrap();
    for name in ["sqrt3", "butterfly"] {
        let row = cat
            .as_array()
            .unwrap()
            .iter()
            .find(|r| r["name"] == name)
            .unwrap_or_else(|| panic!("{name} missing from the catalogue"));
        assert_eq!(row["refine"], true);
        assert_eq!(row["rings"], false);
    }
    let obj = dir.join("s.obj");
    let (r, _) = run(&[
        "subdivide",
        "gallery:icosahedron",
        "--scheme",
        "sqrt3",
        "--levels",
        "2",
        "--limit",
        "-o",
        obj.to_str().unwrap(),
    ]);
    r.unwrap();
    let text = std::fs::read_to_string(&obj).unwrap();
    assert_eq!(text.lines().filter(|l| l.starts_with("f ")).count(), 20 * 9);
    let (r, _) = run(&[
        "subdivide",
        "gallery:tri-grid",
        "--scheme",
        "butterfly",
        "--levels",
        "2",
        "-o",
        obj.to_str().unwrap(),
    ]);
    r.unwrap();
    // Quads are refused with the face named.
    let (r, _) = run(&[
        "subdivide",
        "gallery:cube",
        "--scheme",
        "sqrt3",
        "--levels",
        "1",
        "-o",
        obj.to_str().unwrap(),
    ]);
    let e = r.unwrap_err().to_string();
    assert!(e.contains("face 0"), "{e}");
    // No exact patches.
    let (r, _) = run(&[
        "subdivide",
        "gallery:icosahedron",
        "--scheme",
        "butterfly",
        "--rings",
        "2",
        "-o",
        obj.to_str().unwrap(),
    ]);
    assert!(r.is_err());
    // The spectrum from the command line.
    let (r, out) = run(&["analyze", "--scheme", "sqrt3", "--valence", "5", "--json"]);
    r.unwrap();
    let a: serde_json::Value = serde_json::from_str(&out).unwrap();
    let lambda = a["spectrum"]["lambda"]
        .as_f64()
        .unwrap_or_else(|| panic!("{a}"));
    let want = (2.0 + 2.0 * (std::f64::consts::TAU / 5.0).cos()) / 9.0;
    assert!((lambda - want).abs() < 1e-10, "{lambda}");
    let (r, _) = run(&[
        "analyze",
        "--scheme",
        "butterfly",
        "--valence",
        "7",
        "--json",
    ]);
    r.unwrap();
    let _ = by_name("sqrt-3").unwrap();
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn step_sizes_bound_the_real_steps() {
    use fairsub::schemes::growth::NetSize;
    for name in ["sqrt3", "butterfly"] {
        let s = by_name(name).unwrap();
        for net in [nets::icosahedron(), open_net(), nets::tri_grid()] {
            let mut m = net.clone();
            for level in 0..3 {
                let bound = s.step_size(&NetSize::of(&m));
                let r = match name {
                    "sqrt3" => sqrt3::Sqrt3.step(&m, level % 2 == 1).unwrap(),
                    _ => s.refine(&m).unwrap(),
                };
                let real = NetSize::of(&r.mesh);
                let what = format!("{name} level {level}");
                assert!(real.vertices <= bound.vertices, "{what}: vertices");
                assert!(real.faces <= bound.faces, "{what}: faces");
                assert!(real.edges <= bound.edges, "{what}: edges");
                assert!(real.corners <= bound.corners, "{what}: corners");
                assert!(
                    real.valence_squares <= bound.valence_squares,
                    "{what}: valences"
                );
                assert!(
                    r.stencils.num_entries() as f64 <= bound.stencil,
                    "{what}: stencil"
                );
                m = r.mesh;
            }
        }
    }
}
