//! What the sharp-feature patch tests of Catmull-Clark and Loop share: the OpenSubdiv test nets,
//! the limit points of uniform refinement, the check that every regular and ring patch is exact
//! against them, and running the binary.

#![allow(dead_code)]

use fairsub::bezier::complex::{PatchComplex, Provenance};
use fairsub::geom::Point;
use fairsub::mesh::tags::SubdOptions;
use fairsub::mesh::{Extras, PolyMesh, SharpEdges};
use fairsub::schemes::Scheme;

/// The path of the net `tests/data/osd/NAME.obj`.
pub fn osd_path(name: &str) -> String {
    format!("{}/tests/data/osd/{name}.obj", env!("CARGO_MANIFEST_DIR"))
}

/// The net `tests/data/osd/NAME.obj` with its tags.
pub fn osd(name: &str) -> PolyMesh {
    fairsub::cli::load_net(&osd_path(name))
        .expect("net loads")
        .mesh
}

/// The option tags of a net.
pub fn file_options(m: &PolyMesh) -> SubdOptions {
    m.extras().map(|e| e.options).unwrap_or_default()
}

/// Whether the net tags an infinitely sharp edge.
pub fn has_infinite_crease(m: &PolyMesh) -> bool {
    m.extras().is_some_and(|e| match &e.sharp_edges {
        SharpEdges::ById(v) => v.iter().any(|p| p.1 >= 10.0),
        SharpEdges::ByPair(v) => v.iter().any(|p| p.1 >= 10.0),
    })
}

/// The limit points of `mesh` refined `levels` times by `scheme`, sorted by x.
pub fn limit_points(scheme: &dyn Scheme, mesh: &PolyMesh, levels: usize) -> Vec<Point> {
    let m = fairsub::schemes::refine_levels(scheme, mesh, levels, |_| {}).unwrap();
    let mut pts = scheme.limit_stencils(&m).unwrap().apply(m.positions());
    pts.sort_by(|a, b| a[0].total_cmp(&b[0]));
    pts
}

/// Distance from `p` to the nearest of the sorted points `pts` (searched in an x window).
pub fn nearest(pts: &[Point], p: Point) -> f64 {
    let w = 1e-6;
    let lo = pts.partition_point(|q| q[0] < p[0] - w);
    pts[lo..]
        .iter()
        .take_while(|q| q[0] <= p[0] + w)
        .map(|&q| fairsub::geom::dist(p, q))
        .fold(f64::INFINITY, f64::min)
}

/// The refinement level of a regular (0) or ring patch; `None` for caps and fills.
pub fn level_of(p: &Provenance) -> Option<usize> {
    match p {
        Provenance::Regular { .. } => Some(0),
        Provenance::Ring { ring, .. } => Some(*ring as usize),
        _ => None,
    }
}

/// The parameters of a quad patch where a net refined `k` more times has vertices.
pub fn quad_samples(k: usize) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    for i in 0..=k {
        for j in 0..=k {
            out.push((i as f64 / k as f64, j as f64 / k as f64));
        }
    }
    out
}

/// The same for a triangle stored as Loop stores it (`X(u, v) = T(u (1 - v), v)`): the lattice
/// points `(s, t) = (i, j) / k`, `i + j <= k`, at `u = i / (k - j)`, `v = j / k`.
pub fn triangle_samples(k: usize) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    for j in 0..=k {
        for i in 0..=k - j {
            let u = if j == k {
                0.0
            } else {
                i as f64 / (k - j) as f64
            };
            out.push((u, j as f64 / k as f64));
        }
    }
    out
}

/// Checks that every regular and ring patch of `c` is exact against `levels` uniform levels:
/// its samples (`samples(2^(levels - l))`) are limit points (distance < 1e-9). Returns
/// (patches checked, samples checked, largest distance).
pub fn check_exact(
    c: &PatchComplex,
    pts: &[Point],
    levels: usize,
    samples: fn(usize) -> Vec<(f64, f64)>,
) -> (usize, usize, f64) {
    let (mut patches, mut count, mut worst) = (0, 0, 0f64);
    for (p, prov) in c.patches.iter().zip(&c.provenance) {
        let Some(l) = level_of(prov) else { continue };
        assert!(l <= levels, "ring {l} beyond {levels} levels");
        let k = 1usize << (levels - l);
        patches += 1;
        for (u, v) in samples(k) {
            let x = p.eval(u, v);
            let d = nearest(pts, x);
            worst = worst.max(d);
            count += 1;
            assert!(
                d < 1e-9,
                "{prov:?} sample ({u}, {v}) at {x:?}: {d:e} from the limit"
            );
        }
    }
    (patches, count, worst)
}

/// The cap patches that belong to no G^1 cap (the C^0 fill's).
pub fn fill_patches(c: &PatchComplex) -> usize {
    let capped = |i: usize| {
        c.caps
            .iter()
            .any(|s| (s.first as usize..(s.first + s.count) as usize).contains(&i))
    };
    (0..c.len())
        .filter(|&i| matches!(c.provenance[i], Provenance::Cap { .. }) && !capped(i))
        .count()
}

/// Runs the `fairsub` binary: (exit code, stdout, stderr).
pub fn run(args: &[&str]) -> (i32, String, String) {
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_fairsub"))
        .args(args)
        .output()
        .unwrap();
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

/// Checks the complex `c` of the test net `name` (`m`): every regular and ring patch exact
/// against the limit points of `scheme` after as many levels as its deepest ring, no crack
/// (every join C^0, the sharp ones too), no open side when `closed`, sharp joins when
/// `sharp` (an infinitely sharp crease inside the surface). Returns the continuity report.
pub fn check_net(
    name: &str,
    m: &PolyMesh,
    c: &PatchComplex,
    scheme: &dyn Scheme,
    samples: fn(usize) -> Vec<(f64, f64)>,
    closed: bool,
    sharp: bool,
) -> fairsub::analysis::continuity::ContinuityReport {
    let levels = c.provenance.iter().filter_map(level_of).max().unwrap_or(0);
    let pts = limit_points(scheme, m, levels);
    let (patches, count, worst) = check_exact(c, &pts, levels, samples);
    eprintln!(
        "{name}: {} patches, {patches} exact ({count} samples, worst {worst:.1e}), {levels} levels",
        c.len()
    );
    assert!(patches > 0, "{name}");
    assert!(worst < 1e-9, "{name}");
    let r = fairsub::analysis::continuity::check(c);
    eprintln!(
        "  joins {} (C0 {:.1e}, C2 {:.1e}, G1 {:.2}), sharp {} (C0 {:.1e}, G1 {:.2}), open {}",
        r.all.pieces,
        r.all.c0,
        r.all.c2,
        r.all.g1,
        r.sharp.pieces,
        r.sharp.c0,
        r.sharp.g1,
        r.open_sides
    );
    assert!(
        r.all.c0 < 1e-9 && r.sharp.c0 < 1e-9,
        "{name}: {} {}",
        r.all.c0,
        r.sharp.c0
    );
    if closed {
        assert_eq!(r.open_sides, 0, "{name}");
    }
    if sharp {
        assert!(r.sharp.pieces > 0, "{name}");
    }
    r
}

/// Runs `subdivide NET -s SCHEME --rings RINGS -o FILE` (in a temporary folder) and `check NET
/// -s SCHEME --rings RINGS --json` on the test net `name`, both of which must succeed, and
/// checks that the report has at least `sharp_pieces` sharp joins, C^0 with a crease angle, and
/// no open side: the first's stderr and the second's report.
pub fn rings_and_check(
    scheme: &str,
    name: &str,
    rings: &str,
    sharp_pieces: u64,
) -> (String, serde_json::Value) {
    let net = &osd_path(name);
    let dir = crate::common::scratch(&format!("sharp-{scheme}"));
    let out = dir.join("out.bv");
    let args = ["subdivide", net, "-s", scheme, "--rings", rings, "-o"];
    let (code, _, written) = run(&[&args[..], &[out.to_str().unwrap()]].concat());
    assert_eq!(code, 0, "{written}");
    std::fs::remove_dir_all(&dir).ok();
    let (code, json, err) = run(&["check", net, "-s", scheme, "--rings", rings, "--json"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    let sharp = &v["continuity"]["sharp"];
    assert!(sharp["pieces"].as_u64().unwrap() >= sharp_pieces, "{sharp}");
    assert!(sharp["c0"].as_f64().unwrap() < 1e-9);
    assert!(sharp["g1"].as_f64().unwrap() > 0.1);
    assert!(v["continuity"]["all"]["c0"].as_f64().unwrap() < 1e-9);
    assert_eq!(v["continuity"]["open_sides"].as_u64(), Some(0));
    (written, v)
}

/// The uniform cubic B-spline segment of the control points `d` at `t` in `[0, 1]`.
pub fn bspline(d: [Point; 4], t: f64) -> Point {
    let b = [
        (1.0 - t) * (1.0 - t) * (1.0 - t) / 6.0,
        (3.0 * t * t * t - 6.0 * t * t + 4.0) / 6.0,
        (-3.0 * t * t * t + 3.0 * t * t + 3.0 * t + 1.0) / 6.0,
        t * t * t / 6.0,
    ];
    let mut p = [0.0; 3];
    for (w, q) in b.iter().zip(d) {
        p = fairsub::geom::axpy(p, *w, q);
    }
    p
}

/// Builds `scheme`'s patch table of `mesh` (`name` for messages) at 2 rings, checks that it
/// re-applies to points moved by 5% of the net's size within 1e-12 of the recomputed complex,
/// and returns how many of its caps `kind` selects.
pub fn table_reapplies(
    scheme: &str,
    name: &str,
    mesh: &PolyMesh,
    kind: impl Fn(&fairsub::bezier::g1::Hole) -> bool,
) -> usize {
    let spec = fairsub::schemes::registry::registry()
        .lookup(scheme)
        .expect("registered");
    spec_table_reapplies(&spec, name, mesh, kind)
}

/// [`table_reapplies`] of a scheme with its options (`spec`).
pub fn spec_table_reapplies(
    spec: &fairsub::schemes::Spec,
    name: &str,
    mesh: &PolyMesh,
    kind: impl Fn(&fairsub::bezier::g1::Hole) -> bool,
) -> usize {
    use fairsub::surface::table::{PatchTable, probe};
    let spec = spec.clone();
    let opts = fairsub::host::ComplexOptions {
        rings: 2,
        fill: true,
    };
    let table = PatchTable::build(&spec, mesh, opts).expect(name);
    let count = table.caps().iter().filter(|c| kind(&c.step.hole)).count();
    let s = probe::net_size(mesh.positions());
    let moved = probe::moved_points(mesh.positions(), 0.05 * s, 11);
    let mut mm = mesh.clone();
    mm.set_positions(moved.clone());
    let truth = fairsub::surface::build(&spec, &mm, opts, &mut |_| {})
        .expect(name)
        .complex;
    let (d, _) = probe::max_deviation(&table.apply(&moved).expect(name), &truth);
    assert!(d <= 1e-12 * s, "{name}: moved points {d:.3e}");
    count
}

/// Infinitely sharp edge chains from vertex 0 of `m` along its spokes `spokes` (indices into
/// its outgoing half-edges), each continued straight across regular vertices (valence 4 for
/// quads, 6 for triangles) to the boundary, as vertex pairs with sharpness 10.
pub fn sharp_chains(m: &PolyMesh, spokes: &[usize]) -> Vec<([u32; 2], f32)> {
    let regular = if m.face_size(0) == 3 { 6 } else { 4 };
    let hs = m.outgoing_halfedges(0);
    let mut pairs = Vec::new();
    for &j in spokes {
        let mut h = hs[j];
        loop {
            let (a, b) = (m.he_from(h), m.he_to(h));
            pairs.push(([a, b], 10.0f32));
            let out = m.outgoing_halfedges(b as usize);
            if m.is_boundary_vertex(b as usize) || out.len() != regular {
                break;
            }
            // the edge opposite b -> a around the regular vertex b
            let back = out
                .iter()
                .position(|&g| m.he_to(g) == a)
                .expect("edge back");
            h = out[(back + regular / 2) % regular];
        }
    }
    pairs
}

/// The complex of `m` at `rings` rings (with the fill) under Loop (`loop_`) or Catmull-Clark,
/// with the net's own options.
pub fn complex_of(loop_: bool, m: &PolyMesh, rings: usize) -> PatchComplex {
    let subd = file_options(m);
    let opts = fairsub::host::ComplexOptions { rings, fill: true };
    if loop_ {
        fairsub::schemes::loop_subdivision::surface::loop_complex_with(m, opts, subd, |_| {})
    } else {
        fairsub::schemes::catmull_clark::surface::catmull_clark_complex_with(m, opts, subd, |_| {})
    }
    .expect("complex")
}

/// [`check_net`] of a complex whose holes are all capped: additionally no fill patch is left
/// and every join but the sharp ones is G^1 below 1e-8 rad.
pub fn check_capped(
    what: &str,
    m: &PolyMesh,
    c: &PatchComplex,
    scheme: &dyn Scheme,
    samples: fn(usize) -> Vec<(f64, f64)>,
    closed: bool,
    sharp: bool,
) -> fairsub::analysis::continuity::ContinuityReport {
    let r = check_net(what, m, c, scheme, samples, closed, sharp);
    assert_eq!(fill_patches(c), 0, "{what}: fill patches left");
    assert!(
        r.all.g1 < 1e-8,
        "{what}: G^1 {:e} at {:?}",
        r.all.g1,
        r.all.g1_at
    );
    r
}

/// A scheme's parameter samples of a patch (`k` per side).
pub type Samples = fn(usize) -> Vec<(f64, f64)>;

/// Loop (`loop_`) or Catmull-Clark with the net's own options, and its parameter samples.
pub fn scheme_of(loop_: bool, m: &PolyMesh) -> (Box<dyn Scheme>, Samples) {
    let options = file_options(m);
    if loop_ {
        (
            Box::new(fairsub::schemes::loop_subdivision::Configured { options }),
            triangle_samples,
        )
    } else {
        (
            Box::new(fairsub::schemes::catmull_clark::Configured { options }),
            quad_samples,
        )
    }
}

/// `subdivide` of OpenSubdiv's net `net` under `scheme` at 2 rings with `--stencils`: the number
/// of the file's cap lines whose `FAN` word is `word`. The file must read back with the cap
/// count and rows of the library's table of the same complex.
pub fn stencil_caps_named(net: &str, scheme: &str, word: &str) -> usize {
    use fairsub::surface::table::PatchTable;
    let dir = crate::common::scratch(&format!("tab-{}", word.replace('/', "-")));
    let (bv, tab) = (dir.join("c.bv"), dir.join("c.tab"));
    let path = osd_path(net);
    let args = ["subdivide", &path, "-s", scheme, "--rings", "2", "-o"];
    let (bv_s, tab_s) = (bv.to_str().unwrap(), tab.to_str().unwrap());
    let (code, _, err) = run(&[&args[..], &[bv_s, "--stencils", tab_s]].concat());
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(&tab).unwrap();
    let named = text
        .lines()
        .filter(|l| l.starts_with("c ") && l.split_whitespace().nth(7) == Some(word))
        .count();
    let file = fairsub::io::table::read_table(&tab).unwrap();
    let spec = fairsub::schemes::registry::registry()
        .lookup(scheme)
        .unwrap();
    let opts = fairsub::host::ComplexOptions {
        rings: 2,
        fill: true,
    };
    let table = PatchTable::build(&spec, &osd(net), opts).unwrap();
    assert_eq!(file.caps.len(), table.caps().len(), "{net}");
    assert_eq!(&file.rows, table.rows(), "{net}");
    std::fs::remove_dir_all(&dir).ok();
    named
}

/// The gallery cube refined twice by Catmull-Clark (96 quads, eight valence-3 vertices), with
/// the crease loop `z = 0` of sharpness `equator` (none for 0) and, when `top` is positive,
/// the loop of the eight edges around the centre of the face `z = 1` with that sharpness.
pub fn creased_cube(equator: f32, top: f32) -> PolyMesh {
    let cube = fairsub::gallery::all()
        .into_iter()
        .find(|(n, _)| n == "cube")
        .expect("gallery cube")
        .1;
    let cc = fairsub::schemes::by_name("catmull-clark").expect("catmull-clark");
    let m = fairsub::schemes::refine_levels(cc.as_ref(), &cube, 2, |_| {}).expect("refine");
    let p = m.positions();
    let zmax = p.iter().map(|x| x[2]).fold(f64::MIN, f64::max);
    let centre = (0..m.num_vertices())
        .find(|&v| (p[v][2] - zmax).abs() < 1e-12 && p[v][0].abs() < 1e-12 && p[v][1].abs() < 1e-12)
        .expect("the top face's centre");
    // the loop around the centre: the edges of its four faces that do not touch it (eight
    // edges; the centre's neighbours alone share no edge)
    let mut around = vec![false; m.num_edges()];
    for f in m.vertex_faces(centre) {
        let h0 = m.face_halfedge(f as usize);
        let mut h = h0;
        loop {
            if m.he_from(h) as usize != centre && m.he_to(h) as usize != centre {
                around[m.he_edge(h) as usize] = true;
            }
            h = m.he_next(h);
            if h == h0 {
                break;
            }
        }
    }
    let mut sharp = Vec::new();
    for (e, &on_top) in around.iter().enumerate() {
        let h = m.edge_halfedge(e);
        let (a, b) = (m.he_from(h), m.he_to(h));
        let on_equator = p[a as usize][2].abs() < 1e-12 && p[b as usize][2].abs() < 1e-12;
        if on_equator && equator > 0.0 {
            sharp.push((e as u32, equator));
        } else if on_top && top > 0.0 {
            sharp.push((e as u32, top));
        }
    }
    m.with_extras(Some(Extras {
        sharp_edges: SharpEdges::ById(sharp),
        ..Extras::default()
    }))
}
