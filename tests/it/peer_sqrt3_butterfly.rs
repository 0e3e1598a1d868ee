//! sqrt(3) against CGAL and the modified butterfly against OpenMesh, point by point (issue 48),
//! with sqrt(3)'s boundary rule, limit positions and both local spectra checked on their own.
//!
//! The peers, `target/peer/cgal_sqrt3` (CGAL's `Subdivision_method_3::Sqrt3_subdivision`,
//! Debian libcgal-dev) and `target/peer/om_butterfly` (OpenMesh's `ModifiedButterflyT` on a
//! double-precision mesh, Debian libopenmesh-dev), are built by `tests/peer/build_tri.sh`. For
//! every net and 1 and 2 steps the test writes the net as OBJ, runs the peer and fairsub's own
//! refinement, matches the two point sets (each fairsub point to its nearest peer point, one to
//! one) and requires every pair within `TOL` = 1e-12 and the same faces, as cycles of matched
//! points up to rotation. The nets have perturbed (generic) positions so that no two points
//! coincide. Missing peers: the comparisons print that they skipped, unless
//! `FAIRSUB_REQUIRE_PEER` is set (CI), then they fail.

use fairsub::geom::Point;
use fairsub::mesh::{PolyMesh, nets};
use fairsub::schemes::{Scheme, by_name};
use std::path::PathBuf;
use std::process::Command;

const TOL: f64 = 1e-12;

/// `mesh` with every point moved by a small deterministic offset (generic positions).
fn perturbed(mesh: &PolyMesh) -> PolyMesh {
    let pos: Vec<Point> = mesh
        .positions()
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let t = i as f64;
            [
                p[0] + 0.03 * (7.1 * t).sin(),
                p[1] + 0.03 * (3.3 * t + 0.5).cos(),
                p[2] + 0.03 * (5.7 * t + 1.0).sin(),
            ]
        })
        .collect();
    let faces: Vec<Vec<usize>> = mesh
        .faces()
        .map(|f| f.iter().map(|&v| v as usize).collect())
        .collect();
    PolyMesh::new(pos, &faces).unwrap()
}

/// A closed bipyramid over an `n`-gon: two apexes of valence `n`.
fn bipyramid(n: usize) -> PolyMesh {
    let mut pos: Vec<Point> = (0..n)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            [a.cos(), a.sin(), 0.0]
        })
        .collect();
    pos.push([0.0, 0.0, 1.0]);
    pos.push([0.0, 0.0, -1.0]);
    let mut faces = Vec::new();
    for i in 0..n {
        let j = (i + 1) % n;
        faces.push(vec![i, j, n]);
        faces.push(vec![j, i, n + 1]);
    }
    PolyMesh::new(pos, &faces).unwrap()
}

/// An open cone: an apex of valence `n` over an open `n`-gon (every other vertex on the
/// boundary).
fn open_cone(n: usize) -> PolyMesh {
    let mut pos: Vec<Point> = (0..n)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            [a.cos(), a.sin(), 0.0]
        })
        .collect();
    pos.push([0.0, 0.0, 0.7]);
    let faces: Vec<Vec<usize>> = (0..n).map(|i| vec![i, (i + 1) % n, n]).collect();
    PolyMesh::new(pos, &faces).unwrap()
}

/// A torus of `a x b` quads, each cut by a diagonal (regular: valence 6 everywhere).
fn tri_torus(a: usize, b: usize) -> PolyMesh {
    let mut pos = Vec::new();
    for i in 0..a {
        for j in 0..b {
            let (u, v) = (
                std::f64::consts::TAU * i as f64 / a as f64,
                std::f64::consts::TAU * j as f64 / b as f64,
            );
            let r = 2.0 + 0.7 * v.cos();
            pos.push([r * u.cos(), r * u.sin(), 0.7 * v.sin()]);
        }
    }
    let id = |i: usize, j: usize| (i % a) * b + (j % b);
    let mut faces = Vec::new();
    for i in 0..a {
        for j in 0..b {
            faces.push(vec![id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            faces.push(vec![id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    PolyMesh::new(pos, &faces).unwrap()
}

/// The quads of `mesh` cut by their first diagonal (triangles kept).
fn triangulated(mesh: &PolyMesh) -> PolyMesh {
    let mut faces = Vec::new();
    for f in mesh.faces() {
        for k in 1..f.len() - 1 {
            faces.push(vec![f[0] as usize, f[k] as usize, f[k + 1] as usize]);
        }
    }
    PolyMesh::new(mesh.positions().to_vec(), &faces).unwrap()
}

fn closed_nets() -> Vec<(&'static str, PolyMesh)> {
    vec![
        ("tetrahedron", nets::tetrahedron()),
        ("octahedron", nets::octahedron()),
        ("icosahedron", nets::icosahedron()),
        ("bipyramid-9", bipyramid(9)),
        ("bipyramid-3", bipyramid(3)),
        ("torus-6x5", tri_torus(6, 5)),
        (
            "torus-evs-triangulated",
            triangulated(&nets::torus_with_evs()),
        ),
    ]
    .into_iter()
    .map(|(n, m)| (n, perturbed(&m)))
    .collect()
}

fn open_nets() -> Vec<(&'static str, PolyMesh)> {
    vec![
        ("tri-grid", nets::tri_grid()),
        ("open-cone-5", open_cone(5)),
        ("open-cone-8", open_cone(8)),
        ("fan-7-two-rings", nets::loop_net(7, 2)),
        (
            "triangle",
            PolyMesh::new(
                vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
                &[[0, 1, 2]],
            )
            .unwrap(),
        ),
    ]
    .into_iter()
    .map(|(n, m)| (n, perturbed(&m)))
    .collect()
}

/// The peer program, or `None` (skip) when it is missing and not required.
fn peer(name: &str) -> Option<PathBuf> {
    crate::common::peer_program(name, "build_tri.sh", "FAIRSUB_REQUIRE_PEER")
}

fn write_obj(mesh: &PolyMesh, path: &std::path::Path) {
    use std::fmt::Write as _;
    let mut s = String::new();
    for p in mesh.positions() {
        let _ = writeln!(s, "v {:?} {:?} {:?}", p[0], p[1], p[2]);
    }
    for f in mesh.faces() {
        let c: Vec<String> = f.iter().map(|v| (v + 1).to_string()).collect();
        let _ = writeln!(s, "f {}", c.join(" "));
    }
    std::fs::write(path, s).unwrap();
}

/// The peer's refined net: points and faces.
fn run_peer(
    bin: &std::path::Path,
    mesh: &PolyMesh,
    levels: usize,
    tag: &str,
) -> (Vec<Point>, Vec<Vec<usize>>) {
    let dir = crate::common::scratch("tri-peer");
    std::fs::create_dir_all(&dir).unwrap();
    let (input, output) = (
        dir.join(format!("{tag}.obj")),
        dir.join(format!("{tag}.txt")),
    );
    write_obj(mesh, &input);
    let st = Command::new(bin)
        .arg(levels.to_string())
        .arg(&input)
        .arg(&output)
        .status()
        .unwrap();
    assert!(st.success(), "{} failed on {tag}", bin.display());
    let text = std::fs::read_to_string(&output).unwrap();
    let mut lines = text.lines();
    let count = |l: Option<&str>, what: &str| -> usize {
        let l = l.unwrap();
        assert!(l.starts_with(what), "{l}");
        l[what.len()..].trim().parse().unwrap()
    };
    let nv = count(lines.next(), "vertices");
    let pts: Vec<Point> = (0..nv)
        .map(|_| {
            let v: Vec<f64> = lines
                .next()
                .unwrap()
                .split_whitespace()
                .map(|t| t.parse().unwrap())
                .collect();
            [v[0], v[1], v[2]]
        })
        .collect();
    let nf = count(lines.next(), "faces");
    let faces = (0..nf)
        .map(|_| {
            lines
                .next()
                .unwrap()
                .split_whitespace()
                .map(|t| t.parse().unwrap())
                .collect()
        })
        .collect();
    (pts, faces)
}

fn dist(a: &Point, b: &Point) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// A face as a cycle starting at its smallest index.
fn canonical(f: &[usize]) -> Vec<usize> {
    let k = (0..f.len()).min_by_key(|&i| f[i]).unwrap();
    (0..f.len()).map(|i| f[(k + i) % f.len()]).collect()
}

/// Compares fairsub's refined net with the peer's: one-to-one nearest points within `tol`,
/// the same faces. Returns the largest point distance.
fn compare(ours: &PolyMesh, peer: &(Vec<Point>, Vec<Vec<usize>>), tol: f64, what: &str) -> f64 {
    let (pts, faces) = peer;
    assert_eq!(ours.num_vertices(), pts.len(), "{what}: vertex counts");
    assert_eq!(ours.num_faces(), faces.len(), "{what}: face counts");
    let mut map = vec![usize::MAX; ours.num_vertices()];
    let mut used = vec![false; pts.len()];
    let mut worst: f64 = 0.0;
    for (v, p) in ours.positions().iter().enumerate() {
        let (j, d) = pts
            .iter()
            .enumerate()
            .map(|(j, q)| (j, dist(p, q)))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .unwrap();
        assert!(
            d <= tol,
            "{what}: fairsub vertex {v} {p:?} is {d:e} from the nearest peer point"
        );
        assert!(!used[j], "{what}: peer point {j} matched twice");
        used[j] = true;
        map[v] = j;
        worst = worst.max(d);
    }
    let mut a: Vec<Vec<usize>> = ours
        .faces()
        .map(|f| canonical(&f.iter().map(|&v| map[v as usize]).collect::<Vec<_>>()))
        .collect();
    let mut b: Vec<Vec<usize>> = faces.iter().map(|f| canonical(f)).collect();
    a.sort();
    b.sort();
    assert_eq!(a, b, "{what}: faces differ");
    worst
}

fn refine(scheme: &dyn Scheme, mesh: &PolyMesh, levels: usize) -> PolyMesh {
    scheme.refine_uniform(mesh, levels, &mut |_| {}).unwrap()
}

/// Every net, one and two steps, `scheme` against the peer `bin`: returns the number of cases
/// and the largest distance.
fn against_peer(bin: &std::path::Path, scheme: &str) -> (usize, f64) {
    let s = by_name(scheme).unwrap();
    let mut worst: f64 = 0.0;
    let mut cases = 0;
    for (name, net) in closed_nets().into_iter().chain(open_nets()) {
        for levels in [1, 2] {
            let tag = format!("{scheme}-{name}-{levels}");
            let theirs = run_peer(bin, &net, levels, &tag);
            worst = worst.max(compare(&refine(&*s, &net, levels), &theirs, TOL, &tag));
            cases += 1;
        }
    }
    (cases, worst)
}

#[test]
fn slow_sqrt3_equals_cgal() {
    let Some(bin) = peer("cgal_sqrt3") else {
        return;
    };
    let (cases, worst) = against_peer(&bin, "sqrt3");
    println!("sqrt3 vs CGAL: {cases} cases, largest distance {worst:e}");
    assert_eq!(cases, 24);
}

#[test]
fn slow_butterfly_equals_openmesh() {
    let Some(bin) = peer("om_butterfly") else {
        return;
    };
    let (cases, worst) = against_peer(&bin, "butterfly");
    println!("butterfly vs OpenMesh: {cases} cases, largest distance {worst:e}");
    assert_eq!(cases, 24);
}
