//! Evaluation at `(face, u, v)` (`fairsub eval`, `surface::eval::Surface`): agreement with the
//! patches `subdivide --rings` writes, with the bi-3 B-spline on regular faces, convergence to
//! the limit point at the rate of the subdominant eigenvalue, and the errors.

use fairsub::geom::{Point, dist, norm, sub};
use fairsub::mesh::PolyMesh;
use fairsub::schemes::catmull_clark::catmull_clark_lambda;
use fairsub::schemes::registry::{ids, registry};
use fairsub::surface::ComplexOptions;
use fairsub::surface::eval::Surface;

use crate::eval_helpers::cli;
use crate::eval_helpers::support;
use cli::eval_words;
use support::{Lcg, gallery, limit_along, tmp, toward_ev, written};

/// Random points of every face of `mesh` in its domain (quads `[0,1]^2`, n-gons `[0,n]x[0,1]`,
/// triangles barycentric), plus each face's corners.
fn face_points(mesh: &PolyMesh, per_face: usize, seed: u64) -> Vec<(u32, f64, f64)> {
    let mut r = Lcg(seed);
    let mut pts = Vec::new();
    for f in 0..mesh.num_faces() {
        let n = mesh.face_size(f);
        for _ in 0..per_face {
            let (mut u, mut v) = (r.next(), r.next());
            match n {
                3 if u + v > 1.0 => (u, v) = (1.0 - u, 1.0 - v),
                3 | 4 => {}
                _ => u *= n as f64,
            }
            pts.push((f as u32, u, v));
        }
        let corners: &[(f64, f64)] = if n == 3 {
            &[(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)]
        } else {
            &[(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]
        };
        pts.extend(corners.iter().map(|&(u, v)| (f as u32, u, v)));
    }
    pts
}

/// Writes `subdivide --rings` of `net`, evaluates random points of every face with the library
/// and checks each against the written patch it names; returns the largest difference.
fn agrees_with_written(net: &str, scheme: &str, rings: usize) -> f64 {
    let written = written(net.trim_start_matches("gallery:"), scheme, rings);
    let mesh = gallery(net.trim_start_matches("gallery:"));
    let spec = registry().lookup(scheme).expect("scheme");
    let s = Surface::build(&spec, &mesh, ComplexOptions { rings, fill: true }).expect("surface");
    assert_eq!(s.complex().len(), written.len(), "{net}: same patches");
    let mut worst: f64 = 0.0;
    for (f, u, v) in face_points(&mesh, 40, 17) {
        let e = s
            .evaluate(f, u, v)
            .unwrap_or_else(|err| panic!("{net} face {f} at ({u}, {v}): {err}"));
        let w = written.patches[e.patch].eval(e.patch_uv[0], e.patch_uv[1]);
        worst = worst.max(dist(w, e.point));
        assert!(
            e.point.iter().all(|x| x.is_finite()),
            "{net}: finite point at face {f}"
        );
    }
    worst
}

#[test]
fn eval_agrees_with_the_written_patches() {
    let cc = ids::CATMULL_CLARK.name();
    for (net, scheme, rings) in [
        ("gallery:cube", cc, 2),
        ("gallery:cnet-5-saddle", cc, 3),
        ("gallery:cnet-3-convex", cc, 2),
        ("gallery:prism-5", cc, 2),
        ("gallery:torus-evs", cc, 2),
        ("gallery:icosahedron", ids::LOOP.name(), 2),
        ("gallery:octahedron", ids::LOOP.name(), 3),
        ("gallery:tri-grid", ids::LOOP.name(), 1),
    ] {
        let worst = agrees_with_written(net, scheme, rings);
        eprintln!("{net} under {scheme}, {rings} rings: largest difference {worst:.3e}");
        assert!(worst <= 1e-12, "{net} under {scheme}: {worst:e}");
    }
}

/// Uniform cubic B-spline basis and its first derivative at `t`.
fn bspline(t: f64) -> ([f64; 4], [f64; 4]) {
    let s = 1.0 - t;
    (
        [
            s * s * s / 6.0,
            (3.0 * t * t * t - 6.0 * t * t + 4.0) / 6.0,
            (-3.0 * t * t * t + 3.0 * t * t + 3.0 * t + 1.0) / 6.0,
            t * t * t / 6.0,
        ],
        [
            -s * s / 2.0,
            (3.0 * t * t - 4.0 * t) / 2.0,
            (-3.0 * t * t + 2.0 * t + 1.0) / 2.0,
            t * t / 2.0,
        ],
    )
}

#[test]
fn regular_catmull_clark_faces_are_the_bicubic_bspline() {
    let m = 6;
    let mesh =
        fairsub::mesh::nets::quad_grid(m, |x, y| (1.3 * x).sin() + 0.4 * (0.7 * y * x).cos());
    let spec = registry().lookup(ids::CATMULL_CLARK.name()).expect("cc");
    let s = Surface::build(
        &spec,
        &mesh,
        ComplexOptions {
            rings: 2,
            fill: true,
        },
    )
    .expect("surface");
    let id = |i: usize, j: usize| j * (m + 1) + i;
    let mut r = Lcg(5);
    for (i0, j0) in [(2, 2), (1, 3), (3, 1), (4, 4)] {
        let f = (j0 * m + i0) as u32;
        for _ in 0..25 {
            let (u, v) = (r.next(), r.next());
            let (bu, du) = bspline(u);
            let (bv, dv) = bspline(v);
            let (mut p, mut pu, mut pv) = ([0.0; 3], [0.0; 3], [0.0; 3]);
            for a in 0..4 {
                for b in 0..4 {
                    let x = mesh.position(id(i0 - 1 + a, j0 - 1 + b));
                    for c in 0..3 {
                        p[c] += bu[a] * bv[b] * x[c];
                        pu[c] += du[a] * bv[b] * x[c];
                        pv[c] += bu[a] * dv[b] * x[c];
                    }
                }
            }
            let e = s.evaluate(f, u, v).expect("regular face");
            assert!(dist(e.point, p) < 1e-12, "face {f} ({u}, {v})");
            assert!(dist(e.du, pu) < 1e-11, "du at face {f}");
            assert!(dist(e.dv, pv) < 1e-11, "dv at face {f}");
        }
    }
}

/// The Catmull-Clark limit position of vertex `v` from the scheme's limit masks.
fn limit_point(scheme: &str, mesh: &PolyMesh, v: usize) -> Point {
    let spec = registry().lookup(scheme).expect("scheme");
    let rules = registry()
        .descriptor(spec.id)
        .mesh_rules(&spec)
        .expect("rules")
        .expect("refines");
    rules
        .limit_stencils(mesh)
        .expect("masks")
        .apply(mesh.positions())[v]
}

/// Catmull-Clark on the saddle c-nets of valences 3, 5, 7, and Loop on the tetrahedron,
/// octahedron and icosahedron (valences 3, 4, 5; its caps are kites, evaluated through their
/// bilinear charts): points at `2^-k` of the extraordinary vertex converge to its limit point
/// with ratio `lambda` per halving, and the vertex itself is the limit point.
#[test]
fn limit_evaluation_converges_to_the_limit_point_at_rate_lambda() {
    let cc = ids::CATMULL_CLARK.name();
    let lp = ids::LOOP.name();
    let loop_lambda = |n: usize| 0.375 + 0.25 * (std::f64::consts::TAU / n as f64).cos();
    let cases = [
        (cc, "cnet-3-saddle".to_string(), 3, catmull_clark_lambda(3)),
        (cc, "cnet-5-saddle".to_string(), 5, catmull_clark_lambda(5)),
        (cc, "cnet-7-saddle".to_string(), 7, catmull_clark_lambda(7)),
        (lp, "tetrahedron".to_string(), 3, loop_lambda(3)),
        (lp, "octahedron".to_string(), 4, loop_lambda(4)),
        (lp, "icosahedron".to_string(), 5, loop_lambda(5)),
    ];
    for (scheme, net, n, lambda) in cases {
        let mesh = gallery(&net);
        let (ev, at) = toward_ev(&mesh, n);
        let evals = limit_along(scheme, &mesh, &at, 12);
        let lim = limit_point(scheme, &mesh, ev);
        let centre = evals.last().expect("the centre");
        assert!(
            dist(centre.point, lim) < 1e-12,
            "{scheme} {net}: limit point"
        );
        let err: Vec<f64> = evals[..evals.len() - 1]
            .iter()
            .map(|e| norm(sub(e.point, lim)))
            .collect();
        let ratios: Vec<f64> = err.windows(2).map(|w| w[1] / w[0]).collect();
        eprintln!(
            "{scheme} {net} (valence {n}): lambda {lambda:.6}, error ratios \
             {ratios:.6?}"
        );
        for k in 4..err.len() - 1 {
            let ratio = err[k + 1] / err[k];
            assert!(
                (ratio / lambda - 1.0).abs() < 0.1,
                "{scheme} {net}: error ratio {ratio} at k = {}, lambda {lambda} (errors {err:?})",
                k + 2
            );
        }
    }
}

#[test]
fn cli_json_names_the_patch_and_matches_the_library() {
    let cc = ids::CATMULL_CLARK.name();
    let out = eval_words(&[
        "gallery:cube",
        "--scheme",
        cc,
        "--rings",
        "2",
        "--at",
        "0:0.25:0.5,3:1:1",
        "--at",
        "5:0.01:0.99",
        "--json",
    ])
    .expect("eval runs");
    let json: serde_json::Value = serde_json::from_str(&out).expect("JSON");
    let arr = json.as_array().expect("array");
    assert_eq!(arr.len(), 3);
    let mesh = gallery("cube");
    let spec = registry().lookup(cc).expect("cc");
    let s = Surface::build(
        &spec,
        &mesh,
        ComplexOptions {
            rings: 2,
            fill: true,
        },
    )
    .expect("surface");
    for (item, (f, u, v)) in arr
        .iter()
        .zip([(0, 0.25, 0.5), (3, 1.0, 1.0), (5, 0.01, 0.99)])
    {
        let e = s.evaluate(f, u, v).expect("point");
        assert_eq!(item["patch"].as_u64(), Some(e.patch as u64));
        for key in [
            "point", "du", "dv", "duu", "duv", "dvv", "normal", "patch_uv",
        ] {
            assert!(item[key].is_array(), "{key} in the JSON");
        }
        let p: Vec<f64> = item["point"]
            .as_array()
            .expect("point")
            .iter()
            .map(|x| x.as_f64().expect("number"))
            .collect();
        assert!(dist([p[0], p[1], p[2]], e.point) < 1e-15);
        assert!(item["gauss"].is_number() && item["mean"].is_number());
    }
    // text output: one line per point, and the limit surface without --rings
    let text = eval_words(&["gallery:cube", "--scheme", cc, "--at", "0:0.5:0.5,1:0:0"])
        .expect("limit eval");
    assert_eq!(text.lines().count(), 2);
    assert!(text.starts_with("0:0.5:0.5 patch "), "{text}");
}

#[test]
fn errors_name_the_face_the_domain_and_the_scheme() {
    let cc = ids::CATMULL_CLARK.name();
    let run = |at: &str, scheme: &str, net: &str| {
        eval_words(&[net, "--scheme", scheme, "--rings", "1", "--at", at]).expect_err("must fail")
    };
    let e = run("99:0.5:0.5", cc, "gallery:cube");
    assert!(e.contains("face 99") && e.contains("6 faces"), "{e}");
    let e = run("2:1.5:0.5", cc, "gallery:cube");
    assert!(
        e.contains("face 2") && e.contains("outside its domain"),
        "{e}"
    );
    let e = run("2:0.5:-0.1", cc, "gallery:cube");
    assert!(e.contains("outside its domain"), "{e}");
    // an n-gon's strip ends at u = n, a triangle's domain at u + v = 1
    let e = run("0:5.5:0.5", cc, "gallery:prism-5");
    assert!(e.contains("[0, 5]"), "{e}");
    let e = run("0:0.7:0.7", ids::LOOP.name(), "gallery:icosahedron");
    assert!(e.contains("u + v <= 1"), "{e}");
    // polar-bi2's TPS rings (a vertex that is not a pole) lie in thirds of their quarters,
    // as bi2-mixed's (an error before 2026-12-04)
    let at = [
        "gallery:cnet-5-saddle",
        "--rings",
        "1",
        "--at",
        "0:0.1:0.1,0:0.01:0.02",
    ];
    let with = |scheme: &str| {
        let mut words = vec!["--scheme", scheme];
        words.extend_from_slice(&at);
        eval_words(&words).expect("a TPS vertex's quarter evaluates")
    };
    assert_eq!(with(ids::POLAR_BI2.name()), with(ids::BI2_MIXED.name()));
    // pgs-dscc's quarters at boundary vertices evaluate (its first DS^CC step hands them to
    // the corner points; an error before 2026-12-04): a face of the c-net at a boundary vertex
    let net = "gallery:cnet-5-saddle";
    let mesh = gallery("cnet-5-saddle");
    let (f, k) = (0..mesh.num_faces())
        .find_map(|f| {
            let face = mesh.face(f);
            (face.len() == 4)
                .then(|| {
                    face.iter()
                        .position(|&x| mesh.is_boundary_vertex(x as usize))
                })
                .flatten()
                .map(|k| (f, k))
        })
        .expect("a face at the boundary");
    let corner = [[0.1, 0.1], [0.9, 0.1], [0.9, 0.9], [0.1, 0.9]][k];
    let at = format!("{f}:{}:{}", corner[0], corner[1]);
    let words = [
        net,
        "--scheme",
        ids::PGS_DSCC.name(),
        "--rings",
        "1",
        "--at",
        &at,
    ];
    let out = eval_words(&words).expect("a boundary quarter evaluates");
    assert!(out.starts_with(&format!("{at} patch ")), "{out}");
    let e = run("0:0.5", cc, "gallery:cube");
    assert!(
        e.contains("--at point 1") && e.contains("three fields"),
        "{e}"
    );
    let e = run("0:x:0.5", cc, "gallery:cube");
    assert!(e.contains("finite numbers"), "{e}");
    // a point in the open hole
    let e = eval_words(&[
        "gallery:cube",
        "--scheme",
        cc,
        "--rings",
        "1",
        "--no-fill",
        "--at",
        "0:0:0",
    ])
    .expect_err("open hole");
    assert!(e.contains("no patch") && e.contains("face 0"), "{e}");
    // a bad line of an --at-file names the file and line
    let file = tmp("fairsub-eval", "points.txt");
    std::fs::write(&file, "# points\n0 0.5 0.5\n1:0.2\n").expect("write");
    let e = eval_words(&[
        "gallery:cube",
        "--scheme",
        cc,
        "--at-file",
        file.to_str().expect("utf-8"),
    ])
    .expect_err("bad line");
    assert!(e.contains("points.txt:3"), "{e}");
}

/// The batch path (`Surface::evaluate_into`, which the CLI and the Python package use) gives
/// exactly `evaluate`'s results, in order, on every scheme family's faces (quads, n-gons,
/// Loop's triangles), and names the first point that fails.
#[test]
fn evaluate_into_is_evaluate() {
    for (net, scheme) in [
        ("torus-evs", "catmull-clark"),
        ("prism-5", "catmull-clark"),
        ("octahedron", "loop"),
        ("cube", "doo-sabin"),
    ] {
        let mesh = gallery(net);
        let spec = registry().lookup(scheme).expect("scheme");
        let s = Surface::build(
            &spec,
            &mesh,
            ComplexOptions {
                rings: 2,
                fill: true,
            },
        )
        .expect("surface");
        let pts = face_points(&mesh, 300, 5);
        let mut out = vec![Default::default(); pts.len()];
        s.evaluate_into(&pts, &mut out)
            .expect("every point evaluates");
        let many = s.evaluate_many(&pts);
        for ((&(f, u, v), got), want) in pts.iter().zip(&out).zip(many) {
            // compared as printed (shortest round trip: the same bits, NaN curvatures too)
            let want = want.expect("evaluates");
            assert_eq!(
                format!("{got:?}"),
                format!("{want:?}"),
                "{net} {scheme} face {f} ({u}, {v})"
            );
        }
        // the first failing point by index, whichever thread meets it first
        let mut bad = pts.clone();
        let n = bad.len();
        bad[n - 5].0 = mesh.num_faces() as u32;
        bad[n / 3].1 = -1.0;
        let (i, e) = s.evaluate_into(&bad, &mut out).expect_err("bad points");
        assert_eq!(i, n / 3, "{net}: {e}");
        assert!(e.to_string().contains("outside its domain"), "{e}");
    }
}

#[test]
fn cli_binary_records_equal_the_library_bit_for_bit() {
    let cc = ids::CATMULL_CLARK.name();
    let pts = [
        (0, 0.25, 0.5),
        (3, 1.0, 1.0),
        (5, 0.01, 0.99),
        (2, 0.7, 0.1),
    ];
    let at = "0:0.25:0.5,3:1:1,5:0.01:0.99,2:0.7:0.1";
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_fairsub"))
        .args(["eval", "gallery:cube", "--scheme", cc, "--rings", "2"])
        .args(["--at", at, "--binary"])
        .output()
        .expect("fairsub runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let x: Vec<f64> = out
        .stdout
        .chunks(8)
        .map(|b| f64::from_le_bytes(b.try_into().expect("8 bytes")))
        .collect();
    assert_eq!(x.len(), 29 * pts.len());
    let spec = registry().lookup(cc).expect("cc");
    let opts = ComplexOptions {
        rings: 2,
        fill: true,
    };
    let s = Surface::build(&spec, &gallery("cube"), opts).expect("surface");
    for (rec, &(f, u, v)) in x.chunks(29).zip(&pts) {
        let e = s.evaluate(f, u, v).expect("point");
        let mut want = vec![f64::from(e.face), e.u, e.v, e.patch as f64];
        want.extend(e.patch_uv);
        for p in [e.point, e.du, e.dv, e.duu, e.duv, e.dvv, e.normal] {
            want.extend(p);
        }
        want.extend([e.gauss, e.mean]);
        for (a, b) in rec.iter().zip(&want) {
            assert_eq!(a.to_bits(), b.to_bits(), "record {rec:?} against {want:?}");
        }
    }
    // --binary and --json exclude each other
    let both = eval_words(&[
        "gallery:cube",
        "--scheme",
        cc,
        "--at",
        at,
        "--json",
        "--binary",
    ]);
    assert!(both.is_err());
}

/// `eval --rings` on one worker thread (`RAYON_NUM_THREADS=1`, or a one-core machine) on a net
/// big enough for the regular patches to be computed in several blocks: the build runs inside
/// the pool while a block is pushed, which deadlocked when the next block was computed on a
/// thread that waited for the pool's only worker. The output equals the default run's.
#[test]
fn eval_on_one_worker_thread_finishes_and_agrees() {
    let fairsub = env!("CARGO_BIN_EXE_fairsub");
    let net = tmp("fairsub-eval-one-thread", "cube-l5.obj");
    let cc = ids::CATMULL_CLARK.name();
    let made = std::process::Command::new(fairsub)
        .args(["subdivide", "gallery:cube", "-s", cc, "-l", "5", "-o"])
        .arg(&net)
        .output()
        .expect("fairsub runs");
    assert!(made.status.success(), "{made:?}");
    let mesh = fairsub::io::read_mesh(&net)
        .expect("the refined cube reads back")
        .mesh;
    assert!(
        mesh.num_faces() > 4096,
        "{} faces: one block",
        mesh.num_faces()
    );
    let at = "0:0.25:0.5,6000:0.5:0.5,17:1:0";
    let run = |threads: Option<&str>| {
        let mut cmd = std::process::Command::new(fairsub);
        cmd.arg("eval")
            .arg(&net)
            .args(["--scheme", cc, "--rings", "2", "--at", at])
            .stdout(std::process::Stdio::piped());
        if let Some(t) = threads {
            cmd.env("RAYON_NUM_THREADS", t);
        }
        let mut child = cmd.spawn().expect("fairsub runs");
        let start = std::time::Instant::now();
        // a deadlock is a failure, not a hung test run
        while child.try_wait().expect("waits").is_none() {
            if start.elapsed() > std::time::Duration::from_secs(120) {
                let _ = child.kill();
                panic!("eval with RAYON_NUM_THREADS={threads:?} did not finish in 120 s");
            }
            std::thread::sleep(std::time::Duration::from_millis(50));
        }
        let out = child.wait_with_output().expect("output");
        assert!(out.status.success(), "{out:?}");
        String::from_utf8(out.stdout).expect("utf-8")
    };
    let one = run(Some("1"));
    assert_eq!(one.lines().count(), 3, "{one}");
    assert_eq!(one, run(None));
}
