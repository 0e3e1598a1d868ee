//! Evaluation at `(face, u, v)` of polar bi-2 subdivision (`polar-bi2`, PolBS): a pole's fan
//! triangle is a collapsed quad (`(0, 0)` at the corner after the pole, `v = 1` the pole), an
//! `n`-gon cap turned into a pole the strip of its fan triangles, and the radial rings lie in
//! halves of them (`fairsub::bezier::domain`). Tests as for the other schemes: agreement with
//! the patches `subdivide --rings` writes at random points of every face and on every ring and
//! cap, continuity across the lines of a dyadic grid of every face (the ring lines
//! `v = 1 - 2^-k` among them) and across every edge, convergence to the pole's limit point (16)
//! at `analyze`'s `lambda` per ring; `bi2-mixed` evaluates its poles the same way.

use fairsub::bezier::complex::{PatchComplex, Provenance};
use fairsub::cli::run_words;
use fairsub::geom::{Point, dist};
use fairsub::mesh::PolyMesh;
use fairsub::schemes::bi2::polar::{find_poles, to_polar_layout};
use fairsub::schemes::registry::{ids, registry};
use fairsub::surface::ComplexOptions;
use fairsub::surface::eval::Surface;
use std::collections::BTreeSet;

// the shared helpers, of which this file uses some
use crate::eval_helpers::cli;
use crate::eval_helpers::faces;
use crate::eval_helpers::ratios;
use crate::eval_helpers::support;
use cli::eval_words;
use faces::{agrees_at, face_points, jump_across, largest_jump, surface_of};
use ratios::{converges, lambda};
use support::{gallery, tmp, via_obj, written_from};

const POLAR: &str = "polar-bi2";
/// The pole given for face 0 (the bottom cap, centroid `(0, 0, -1)`) of prism-5.
const GIVEN: (usize, Point) = (0, [0.1, -0.05, -1.4]);

/// The polar layout of prism-`n` (its caps turned into poles with fans of input triangles:
/// quads mixed with pole triangles) as a net of its own.
fn layout(n: usize) -> (PolyMesh, String) {
    let net = to_polar_layout(&gallery(&format!("prism-{n}")), &[]).expect("polar layout");
    via_obj(&net.mesh, &format!("layout-{n}"))
}

/// Whether face `f` is a triangle at a pole of `mesh` (one collapsed quad `[0, 1]^2`).
fn pole_triangle(mesh: &PolyMesh, f: usize) -> bool {
    let poles = find_poles(mesh);
    mesh.face_size(f) == 3 && mesh.face(f).iter().any(|v| poles.contains(v))
}

/// Whether a face point lies in its face's domain (pole triangles are `[0, 1]^2`, not the
/// strip of a 3-gon; the grid helpers step past the last sub-face).
fn in_domain(mesh: &PolyMesh, (f, u, v): (u32, f64, f64)) -> bool {
    let width = match mesh.face_size(f as usize) {
        4 => 1.0,
        _ if pole_triangle(mesh, f as usize) => 1.0,
        n => n as f64,
    };
    (0.0..=width).contains(&u) && (0.0..=1.0).contains(&v)
}

/// The sub-faces of every face around a pole: `(face, first u)` of each fan triangle.
fn fan_triangles(mesh: &PolyMesh) -> Vec<(u32, f64)> {
    (0..mesh.num_faces())
        .flat_map(|f| {
            let subs = match mesh.face_size(f) {
                4 => 0,
                _ if pole_triangle(mesh, f) => 1,
                n => n,
            };
            (0..subs).map(move |s| (f as u32, s as f64))
        })
        .collect()
}

/// Random face points in the domains (`face_points`, those of pole triangles inside
/// `[0, 1]^2`) and, in every fan triangle, points on each ring `2 ..= rings` (`1 - v` in the
/// middle of `[2^(1-k), 2^(2-k)]`) and on the cap.
fn polar_points(mesh: &PolyMesh, rings: usize) -> Vec<(u32, f64, f64)> {
    let mut pts: Vec<_> = face_points(mesh, 60, 31)
        .into_iter()
        .filter(|&p| in_domain(mesh, p))
        .collect();
    for (f, base) in fan_triangles(mesh) {
        for u in [0.2, 0.7] {
            for k in 2..=rings {
                pts.push((f, base + u, 1.0 - 1.5 * 0.5f64.powi(k as i32 - 1)));
            }
            pts.push((f, base + u, 1.0 - 0.5f64.powi(rings as i32)));
        }
    }
    pts
}

/// The patches `subdivide --rings` writes for `src` with the extra options `extra`.
fn written_with(src: &str, name: &str, rings: usize, extra: &[&str]) -> PatchComplex {
    if extra.is_empty() {
        return written_from(src, name, POLAR, rings);
    }
    let out = tmp("fairsub-eval-polar", &format!("{name}-{rings}.bv"));
    let rings = rings.to_string();
    let mut words = vec!["fairsub", "subdivide", src, "--scheme", POLAR];
    words.extend_from_slice(&["--rings", &rings, "-o", out.to_str().expect("utf-8")]);
    words.extend_from_slice(extra);
    run_words(words).expect("subdivide writes the patches");
    fairsub::render::complex_from_bv(&fairsub::io::read_bv(&out).expect("read back"))
}

/// The surface of `mesh` under `polar-bi2` with `rings` rings, the poles `poles` given.
fn polar_surface(mesh: &PolyMesh, rings: usize, poles: &[(usize, Point)]) -> Surface {
    let mut spec = registry().lookup(POLAR).expect("scheme");
    spec.params.poles = poles.to_vec();
    let opts = ComplexOptions { rings, fill: true };
    Surface::build(&spec, mesh, opts).expect("surface")
}

/// A net of the tests: `(name, net, source for the CLI, poles given)`.
type Net = (String, PolyMesh, String, Vec<(usize, Point)>);

/// The nets of the tests.
fn nets() -> Vec<Net> {
    let mut out: Vec<_> = [3, 5, 8]
        .into_iter()
        .map(|n| {
            let name = format!("prism-{n}");
            (
                name.clone(),
                gallery(&name),
                format!("gallery:{name}"),
                vec![],
            )
        })
        .collect();
    out.push((
        "prism-5-pole".into(),
        gallery("prism-5"),
        "gallery:prism-5".into(),
        vec![GIVEN],
    ));
    let (mesh, src) = layout(6);
    out.push(("layout-6".into(), mesh, src, vec![]));
    out
}

#[test]
fn polar_eval_agrees_with_the_written_patches() {
    for ((name, mesh, src, poles), rings) in nets().into_iter().zip([0, 1, 3, 2, 3]) {
        let given = poles
            .iter()
            .map(|(f, p)| format!("{f}:{},{},{}", p[0], p[1], p[2]))
            .collect::<Vec<_>>();
        let extra: Vec<&str> = given.iter().flat_map(|g| ["--pole", g.as_str()]).collect();
        let written = written_with(&src, &name, rings, &extra);
        let s = polar_surface(&mesh, rings, &poles);
        let pts = polar_points(&mesh, rings);
        let (worst, in_caps) = agrees_at(&written, &mesh, &s, &pts, &|_, _| true);
        // every ring and the caps are hit
        let mut hit = BTreeSet::new();
        for &(f, u, v) in &pts {
            if let Provenance::Ring { ring, .. } =
                s.complex().provenance[s.evaluate(f, u, v).expect("point").patch]
            {
                hit.insert(ring as usize);
            }
        }
        eprintln!(
            "{name}, {rings} rings: {} points, largest difference {worst:.3e}, {in_caps} on caps, \
             rings hit {hit:?}",
            pts.len()
        );
        assert!(worst <= 1e-12, "{name}: {worst:e}");
        assert!(in_caps > 0, "{name}: no point on a cap");
        assert_eq!(hit, (1..=rings).collect(), "{name}");
    }
}

/// The largest jump of the evaluation across every interior edge of `mesh` (quads, pole
/// triangles, caps turned into poles): each edge point evaluated from both faces.
fn jump_across_edges(mesh: &PolyMesh, s: &Surface) -> f64 {
    let poles = find_poles(mesh);
    let quad = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    // the face parameters of the ends of face f's edge from corner k: a quad's corners; a
    // pole triangle's corner after the pole at (0, 0), the next at (1, 0), the pole at v = 1
    // above the edge's other end
    let ends = |f: usize, k: usize| -> [[f64; 2]; 2] {
        let c = mesh.face(f);
        let n = c.len();
        if n == 4 {
            return [quad[k], quad[(k + 1) % 4]];
        }
        if !pole_triangle(mesh, f) {
            // a cap's strip: its edge k is v = 0 of sub-face k
            return [[k as f64, 0.0], [k as f64 + 1.0, 0.0]];
        }
        let at = |j: usize| {
            [
                if poles.contains(&c[(j + 2) % 3]) {
                    0.0
                } else {
                    1.0
                },
                0.0,
            ]
        };
        let (a, b) = (k, (k + 1) % n);
        match (poles.contains(&c[a]), poles.contains(&c[b])) {
            (true, _) => [[at(b)[0], 1.0], at(b)],
            (_, true) => [at(a), [at(a)[0], 1.0]],
            _ => [at(a), at(b)],
        }
    };
    let lerp = |e: [[f64; 2]; 2], x: f64| {
        [
            e[0][0] + x * (e[1][0] - e[0][0]),
            e[0][1] + x * (e[1][1] - e[0][1]),
        ]
    };
    let mut worst: f64 = 0.0;
    for f in 0..mesh.num_faces() {
        let h0 = mesh.face_halfedge(f);
        for k in 0..mesh.face_size(f) {
            let Some(t) = mesh.he_twin(h0 + k as u32) else {
                continue;
            };
            let g = mesh.he_face(t) as usize;
            let j = (t - mesh.face_halfedge(g)) as usize;
            for i in 1..16 {
                // the point at x along the edge is at 1 - x along its twin
                let x = f64::from(i) / 16.0;
                let p = lerp(ends(f, k), x);
                let q = lerp(ends(g, j), 1.0 - x);
                let a = s.evaluate(f as u32, p[0], p[1]).expect("point");
                let b = s.evaluate(g as u32, q[0], q[1]).expect("point");
                worst = worst.max(dist(a.point, b.point));
            }
        }
    }
    worst
}

#[test]
fn polar_evaluation_is_continuous() {
    for (name, mesh, _, poles) in nets() {
        let s = polar_surface(&mesh, 3, &poles);
        let covered = |m: &PolyMesh, p: (u32, f64, f64)| in_domain(m, p);
        // the lines i 2^-6 hold the ring lines v = 1 - 2^-k; u = 1 is the spoke between
        // sub-faces of a cap's strip
        let grid = largest_jump(&mesh, &s, 1 << 6, 1e-10, &covered);
        let spokes = jump_across(&mesh, &s, &[1.0], 1e-10, &covered);
        let edges = jump_across_edges(&mesh, &s);
        eprintln!(
            "{name}: largest jump {grid:.3e} across i 2^-6, {spokes:.3e} across spokes, \
             {edges:.3e} across edges"
        );
        assert!(grid < 1e-8 && spokes < 1e-8 && edges < 1e-12, "{name}");
    }
}

#[test]
fn polar_limit_evaluation_converges_at_rate_lambda() {
    for n in [3, 5, 6, 8] {
        let mesh = gallery(&format!("prism-{n}"));
        // toward the pole of the top cap (face 1, centroid (0, 0, 1)), across sub-face 1
        let at = |h: f64| (1u32, 1.3, 1.0 - h);
        let what = format!("prism-{n}'s pole");
        let (centre, _) = converges(POLAR, &mesh, at, lambda(POLAR, n), 10, &what);
        // the limit point (16) of a pole at the centroid of its ring is the centroid
        assert!(
            dist(centre, mesh.face_centroid(1)) < 1e-12,
            "{what}: {centre:?}"
        );
    }
    // a given pole p: (16) is 2/3 p + 1/3 of the ring's centroid
    let mesh = gallery("prism-5");
    let c = mesh.face_centroid(GIVEN.0);
    let want: Point = std::array::from_fn(|i| (2.0 * GIVEN.1[i] + c[i]) / 3.0);
    let s = polar_surface(&mesh, 3, &[GIVEN]);
    for u in [0.0, 2.5, 5.0] {
        let got = s.evaluate(GIVEN.0 as u32, u, 1.0).expect("the pole").point;
        assert!(dist(got, want) < 1e-12, "given pole at u = {u}: {got:?}");
    }
}

#[test]
fn bi2_mixed_evaluates_its_poles_as_polar_bi2() {
    let (mesh, _) = layout(5);
    let (_, mixed) = surface_of(mesh.clone(), ids::BI2_MIXED.name(), 2);
    let polar = polar_surface(&mesh, 2, &[]);
    let mut worst: f64 = 0.0;
    for (f, u, v) in polar_points(&mesh, 2) {
        let (a, b) = (mixed.evaluate(f, u, v), polar.evaluate(f, u, v));
        let (a, b) = (a.expect("bi2-mixed point"), b.expect("polar point"));
        worst = worst.max(dist(a.point, b.point)).max(dist(a.du, b.du));
    }
    eprintln!("layout-5: bi2-mixed against polar-bi2, largest difference {worst:.3e}");
    assert_eq!(worst, 0.0);
}

#[test]
fn cli_evaluates_poles_and_names_what_it_cannot() {
    let out = eval_words(&[
        "gallery:prism-5",
        "--scheme",
        POLAR,
        "--rings",
        "2",
        "--at",
        "0:2.5:0.9,1:4.5:1,7:0.5:0.5",
    ])
    .expect("eval of polar-bi2");
    assert_eq!(out.lines().count(), 3, "{out}");
    // a pole triangle's domain is [0, 1]^2
    let (_, src) = layout(5);
    let e = eval_words(&[&src, "--scheme", POLAR, "--at", "0:1.5:0.5"]).expect_err("outside");
    assert!(e.contains("face 0") && e.contains("pole"), "{e}");
    // vertices that are not poles get TPS rings, in thirds of their quarters as under `tps`
    // (an error before 2026-12-04)
    let out = eval_words(&[
        "gallery:cnet-5-saddle",
        "--scheme",
        POLAR,
        "--rings",
        "2",
        "--at",
        "0:0.1:0.1",
    ])
    .expect("TPS vertex");
    assert!(out.starts_with("0:0.1:0.1 patch "), "{out}");
}
