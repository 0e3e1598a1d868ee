//! Per-vertex PLY data through `subdivide --levels L [--limit]` (issue 16: "per-vertex colours
//! and other per-point data through the same stencils").
//!
//! The nets are the OpenSubdiv peer's nets (`tests/data/osd/`), written here as PLY files with
//! per-vertex properties of every kind (`uchar` colours, `float` alpha and normal, `double`
//! quality, `short` and `char` channels) in ascii, binary little endian and binary big endian;
//! their crease and corner tags go in a `--creases` side file. Checks:
//!
//! - values: every output channel equals the test's own values pushed through the stencil table
//!   of `schemes::level_stencils` on the same net (and the limit stencils of the refined net
//!   with `--limit`), multiplied out here row by row; integer channels rounded to the nearest
//!   integer and clamped to their type's range (within half a unit plus 1e-9 of the exact
//!   value), `float` within single-precision rounding, `double` within 1e-12;
//! - names and types: the output header lists the input's properties in their order with their
//!   types; ascii and binary outputs hold the same values;
//! - positions: equal (to 1e-12) to those of the run on the same net without properties;
//! - creased nets: the same check (the data takes the sharp rules' weights);
//! - OpenSubdiv: where the peer (`target/peer/osd_refine`, `tests/peer/build.sh`) is built, the
//!   float channels are refined by OpenSubdiv as a vertex primvar (the peer refines the points
//!   of an OBJ net; the data is given as the points of the same net) and compared point by
//!   point (1e-6), vertices matched through the peer's refined positions;
//! - bad input: a list-typed vertex property is skipped with a warning naming it, a NaN is an
//!   error naming the vertex and the property; OBJ output warns that it drops the data.

#[path = "ply_data/support.rs"]
mod support;

use crate::common::scratch;
use fairsub::mesh::PolyMesh;
use fairsub::schemes::{CatmullClark, Loop, Scheme};
use std::path::{Path, PathBuf};
use std::process::Command;
use support::{
    CHANNELS, Enc, Out, multiply, read_net, read_out, root, type_range, value, write_ply,
};

/// `fairsub ARGS`: (success, stderr).
fn fairsub(args: &[&str]) -> (bool, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_fairsub"))
        .args(args)
        .output()
        .unwrap();
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// What the run must write for the net in `ply` (with the tags of `creases`): the stencils of
/// `schemes::level_stencils` (and the limit stencils) applied to the test's values.
fn expected(
    scheme: &dyn Scheme,
    ply: &Path,
    creases: Option<&Path>,
    levels: usize,
    limit: bool,
) -> Vec<Vec<f64>> {
    let mut mesh: PolyMesh = fairsub::io::read_mesh_as(ply, true).unwrap().mesh;
    if let Some(c) = creases {
        let (tags, _) = fairsub::io::obj::read_tag_file(c).unwrap();
        mesh = mesh.with_tags(&tags, c).unwrap();
    }
    let (fine, table) = fairsub::schemes::level_stencils(scheme, &mesh, levels).unwrap();
    let src: Vec<Vec<f64>> = (0..mesh.num_vertices())
        .map(|v| (0..CHANNELS.len()).map(|c| value(v, c)).collect())
        .collect();
    let refined = multiply(&table, &src);
    if limit {
        multiply(&scheme.limit_stencils(&fine).unwrap(), &refined)
    } else {
        refined
    }
}

/// Checks an output against the expected values; returns the largest deviation of the
/// floating channels.
fn check_values(out: &Out, want: &[Vec<f64>], what: &str) -> f64 {
    assert_eq!(out.rows.len(), want.len(), "{what}: vertex count");
    // Names and types, in the input's order (alpha and nx came before z there; fairsub writes
    // x y z first, then the data in its own order).
    let names: Vec<(&str, &str)> = out
        .props
        .iter()
        .map(|(n, t)| (n.as_str(), t.as_str()))
        .collect();
    let order = [3, 4, 0, 1, 2, 5, 6, 7];
    let mut expect_names = vec![("x", "double"), ("y", "double"), ("z", "double")];
    expect_names.extend(order.iter().map(|&c| CHANNELS[c]));
    assert_eq!(names, expect_names, "{what}: properties");
    let mut worst: f64 = 0.0;
    for (c, (name, ty)) in CHANNELS.iter().enumerate() {
        let col = out.column(name).unwrap();
        let (lo, hi) = type_range(ty);
        for (v, (row, w)) in out.rows.iter().zip(want).enumerate() {
            let (got, exact) = (row[col], w[c]);
            match *ty {
                "float" => {
                    let d = (got - exact).abs();
                    assert!(
                        d <= 1e-6 * exact.abs().max(1.0),
                        "{what}: vertex {v} {name}: {got} vs {exact}"
                    );
                    worst = worst.max(d);
                }
                "double" => {
                    let d = (got - exact).abs();
                    assert!(
                        d <= 1e-12 * exact.abs().max(1.0),
                        "{what}: vertex {v} {name}: {got} vs {exact}"
                    );
                    worst = worst.max(d);
                }
                _ => {
                    assert_eq!(got, got.round(), "{what}: vertex {v} {name} not an integer");
                    let clamped = exact.clamp(lo, hi);
                    assert!(
                        (got - clamped).abs() <= 0.5 + 1e-9,
                        "{what}: vertex {v} {name}: {got}, exact {exact}"
                    );
                }
            }
        }
    }
    worst
}

fn positions(out: &Out) -> Vec<[f64; 3]> {
    let (x, y, z) = (
        out.column("x").unwrap(),
        out.column("y").unwrap(),
        out.column("z").unwrap(),
    );
    out.rows.iter().map(|r| [r[x], r[y], r[z]]).collect()
}

/// One net through one scheme, every encoding, `--levels 2` with and without `--limit`.
fn run_net(name: &str, scheme: &dyn Scheme, cli: &str, creased: bool) {
    let net = read_net(name);
    let dir = scratch(&format!("{cli}-{name}"));
    let creases = dir.join("tags.txt");
    std::fs::write(&creases, &net.tags).unwrap();
    let plain = dir.join("plain.ply");
    write_ply(&plain, &net, Enc::Little, false, false);
    for enc in [Enc::Ascii, Enc::Little, Enc::Big] {
        let ply = dir.join("net.ply");
        write_ply(&ply, &net, enc, true, false);
        for limit in [false, true] {
            let mut args = vec!["subdivide", "--scheme", cli, "--levels", "2"];
            if limit {
                args.push("--limit");
            }
            if creased {
                args.extend(["--creases", creases.to_str().unwrap()]);
            }
            let what = format!("{name} {cli} limit={limit}");
            let run = |input: &Path, out: &Path, fmt: &str| {
                let mut a = args.clone();
                a.insert(1, input.to_str().unwrap());
                a.extend(["--format", fmt, "-o", out.to_str().unwrap()]);
                let (ok, err) = fairsub(&a);
                assert!(ok, "{what}: {err}");
                read_out(out)
            };
            let ascii = run(&ply, &dir.join("out-a.ply"), "ply-ascii");
            let binary = run(&ply, &dir.join("out-b.ply"), "ply");
            let want = expected(scheme, &ply, creased.then_some(creases.as_path()), 2, limit);
            check_values(&ascii, &want, &format!("{what} ascii"));
            check_values(&binary, &want, &format!("{what} binary"));
            for (a, b) in ascii.rows.iter().zip(&binary.rows) {
                assert_eq!(a, b, "{what}: ascii and binary outputs differ");
            }
            let bare = run(&plain, &dir.join("out-p.ply"), "ply");
            assert_eq!(
                bare.props.len(),
                3,
                "{what}: a net without data gets x y z only"
            );
            for (p, q) in positions(&binary).iter().zip(&positions(&bare)) {
                for k in 0..3 {
                    assert!(
                        (p[k] - q[k]).abs() <= 1e-12,
                        "{what}: positions {p:?} vs {q:?}"
                    );
                }
            }
        }
    }
}

#[test]
fn catmull_clark_carries_vertex_data_through_its_stencils() {
    run_net("cc_torus_smooth.obj", &CatmullClark, "catmull-clark", false);
    run_net("cc_mixed_ngons.obj", &CatmullClark, "catmull-clark", false);
}

#[test]
fn loop_carries_vertex_data_through_its_stencils() {
    run_net("loop_icosa.obj", &Loop, "loop", false);
    run_net("loop_tri_grid.obj", &Loop, "loop", false);
}

/// Sharp rules apply to the data too: creases, corners and semi-sharp edges.
#[test]
fn creased_nets_carry_vertex_data_with_the_sharp_rules() {
    run_net(
        "cc_cube_semisharp.obj",
        &CatmullClark,
        "catmull-clark",
        true,
    );
    run_net("cc_pole7_crease.obj", &CatmullClark, "catmull-clark", true);
    run_net("loop_octa_semisharp.obj", &Loop, "loop", true);
    run_net("loop_dart_corner.obj", &Loop, "loop", true);
}

/// The peer's points (`v` lines, or `lp` with `--limit`), in its vertex order.
fn peer_points(text: &str, limit: bool) -> Vec<[f64; 3]> {
    let key = if limit { "lp" } else { "v" };
    text.lines()
        .filter_map(|l| {
            let t: Vec<&str> = l.split_whitespace().collect();
            (t.first() == Some(&key)).then(|| [1, 2, 3].map(|i| t[i].parse::<f64>().unwrap()))
        })
        .collect()
}

/// OpenSubdiv refines the float channels (alpha, nx, quality) as a vertex primvar: the peer
/// refines the net with those channels as its points (the weights do not depend on the
/// points), and a second run with the net's own points says which of fairsub's vertices each of
/// the peer's is (by position, within 1e-6). Point by point within 1e-6.
#[test]
fn slow_float_channels_match_opensubdiv_vertex_primvars() {
    if crate::common::skip_slow("osd_refine") {
        return;
    }
    let peer = std::env::var_os("FAIRSUB_PEER")
        .map(PathBuf::from)
        .unwrap_or_else(|| root().join("target/peer/osd_refine"));
    if !peer.exists() {
        let msg = format!("{} missing (run tests/peer/build.sh)", peer.display());
        if std::env::var_os("FAIRSUB_REQUIRE_PEER").is_some() {
            panic!("FAIRSUB_REQUIRE_PEER is set and {msg}");
        }
        println!("ply_data: peer comparison skipped: {msg}");
        return;
    }
    let float_channels = [3usize, 4, 5];
    let mut compared = 0;
    let mut worst: f64 = 0.0;
    for (name, cli, osd) in [
        ("cc_torus_smooth.obj", "catmull-clark", "catmark"),
        ("cc_cube_semisharp.obj", "catmull-clark", "catmark"),
        ("cc_pole7_crease.obj", "catmull-clark", "catmark"),
        ("loop_octa_semisharp.obj", "loop", "loop"),
        ("loop_dart_corner.obj", "loop", "loop"),
    ] {
        let net = read_net(name);
        let dir = scratch(&format!("peer-{name}"));
        let creases = dir.join("tags.txt");
        std::fs::write(&creases, &net.tags).unwrap();
        let ply = dir.join("net.ply");
        write_ply(&ply, &net, Enc::Little, true, false);
        // The same OBJ net with the float channels as its points.
        let source = std::fs::read_to_string(root().join("tests/data/osd").join(name)).unwrap();
        let mut k = 0;
        let mut data_obj = String::new();
        for l in source.lines() {
            if l.split_whitespace().next() == Some("v") {
                let d = float_channels.map(|c| value(k, c));
                data_obj.push_str(&format!("v {:?} {:?} {:?}\n", d[0], d[1], d[2]));
                k += 1;
            } else {
                data_obj.push_str(l);
                data_obj.push('\n');
            }
        }
        let data_path = dir.join("data.obj");
        std::fs::write(&data_path, data_obj).unwrap();
        for limit in [false, true] {
            let what = format!("{name} limit={limit}");
            let osd_run = |input: &Path, out: &Path| {
                let mut c = Command::new(&peer);
                c.args(["--scheme", osd, "--levels", "2"]);
                if limit {
                    c.arg("--limit");
                }
                let o = c.arg(input).arg(out).output().unwrap();
                assert!(
                    o.status.success(),
                    "{what}: peer: {}",
                    String::from_utf8_lossy(&o.stderr)
                );
                peer_points(&std::fs::read_to_string(out).unwrap(), limit)
            };
            let at = osd_run(
                &root().join("tests/data/osd").join(name),
                &dir.join("pos.txt"),
            );
            let data = osd_run(&data_path, &dir.join("data.txt"));
            let out = dir.join("out.ply");
            let mut args = vec!["subdivide", ply.to_str().unwrap(), "--scheme", cli];
            args.extend(["--levels", "2", "-o", out.to_str().unwrap()]);
            args.extend(["--creases", creases.to_str().unwrap()]);
            if limit {
                args.push("--limit");
            }
            let (ok, err) = fairsub(&args);
            assert!(ok, "{what}: {err}");
            let ours = read_out(&out);
            let pos = positions(&ours);
            assert_eq!(pos.len(), at.len(), "{what}: vertex counts");
            let cols = float_channels.map(|c| ours.column(CHANNELS[c].0).unwrap());
            for (i, p) in at.iter().enumerate() {
                let near: Vec<usize> = (0..pos.len())
                    .filter(|&j| (0..3).all(|k| (pos[j][k] - p[k]).abs() <= 1e-6))
                    .collect();
                assert_eq!(
                    near.len(),
                    1,
                    "{what}: peer vertex {i} at {p:?} matches {near:?}"
                );
                let row = &ours.rows[near[0]];
                for (k, &col) in cols.iter().enumerate() {
                    let d = (row[col] - data[i][k]).abs();
                    assert!(
                        d <= 1e-6,
                        "{what}: peer vertex {i} channel {k}: {} vs {}",
                        row[col],
                        data[i][k]
                    );
                    worst = worst.max(d);
                }
                compared += 1;
            }
        }
    }
    println!(
        "ply_data: {compared} vertices agree with OpenSubdiv's vertex primvars, worst {worst:.2e}"
    );
}

/// A list-typed vertex property is skipped with a warning that names it; a NaN in a property is
/// an error naming the vertex and the property; OBJ output warns that the data is dropped.
#[test]
fn bad_properties_are_named_and_obj_output_warns() {
    let net = read_net("cc_cube_semisharp.obj");
    let dir = scratch("bad");
    let ply = dir.join("list.ply");
    write_ply(&ply, &net, Enc::Ascii, true, true);
    let out = dir.join("out.ply");
    // One Catmull-Clark step of `input` into `output`.
    let refine1 = |input: &Path, output: &Path| {
        let (i, o) = (input.to_str().unwrap(), output.to_str().unwrap());
        fairsub(&["subdivide", i, "-s", "catmull-clark", "-l", "1", "-o", o])
    };
    let (ok, err) = refine1(&ply, &out);
    assert!(ok, "{err}");
    assert!(err.contains("vertex list property 'ids' skipped"), "{err}");
    let o = read_out(&out);
    assert!(o.column("ids").is_none() && o.column("red").is_some());
    // NaN in a float channel, on the line of vertex 3.
    let text = std::fs::read_to_string(&ply).unwrap();
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    let first = lines.iter().position(|l| l == "end_header").unwrap() + 1;
    let mut toks: Vec<String> = lines[first + 3]
        .split_whitespace()
        .map(String::from)
        .collect();
    toks[2] = "nan".into(); // alpha (x y alpha nx z ...)
    lines[first + 3] = toks.join(" ");
    let nan = dir.join("nan.ply");
    std::fs::write(&nan, lines.join("\n") + "\n").unwrap();
    let (ok, err) = refine1(&nan, &out);
    assert!(!ok);
    let line = first + 4;
    assert!(
        err.contains(&format!(":{line}"))
            && err.contains("vertex 3")
            && err.contains("'alpha' is not finite"),
        "{err}"
    );
    let obj = dir.join("out.obj");
    let (ok, err) = refine1(&ply, &obj);
    assert!(ok, "{err}");
    assert!(
        err.contains("OBJ cannot hold the per-vertex properties (alpha, nx, red, green, blue, quality, temperature, label)"),
        "{err}"
    );
}

/// Every scheme that refines nets carries the data through the stencils of its own steps:
/// `level_stencils` (which follows the steps of `refine_uniform`, also for the schemes that
/// carry state from step to step: adjustable TPS, pgs-dscc, polar nets) gives the output data,
/// and the positions are those of the run without data (the non-box schemes too: a net without
/// given FCVs has the barycentres as its FCVs, affine in its points).
#[test]
fn every_refining_scheme_carries_vertex_data() {
    use fairsub::schemes::registry::registry;
    let dir = scratch("all");
    let nets = ["cc_cube.obj", "loop_icosa.obj", "cc_mixed_ngons.obj"];
    let mut files = Vec::new();
    for name in nets {
        let net = read_net(name);
        let (plain, data) = (
            dir.join(format!("p-{name}.ply")),
            dir.join(format!("d-{name}.ply")),
        );
        write_ply(&plain, &net, Enc::Little, false, false);
        write_ply(&data, &net, Enc::Little, true, false);
        files.push((plain, data));
    }
    let mut carried = Vec::new();
    for scheme in registry().names_with(|c| c.refine) {
        let spec = registry().lookup(scheme).unwrap();
        let rules = registry()
            .descriptor(spec.id)
            .mesh_rules(&spec)
            .unwrap()
            .unwrap();
        // The first net the scheme takes.
        let out_p = dir.join("p.ply");
        let Some((_, data)) = files.iter().find(|(p, _)| {
            let args = ["subdivide", p.to_str().unwrap(), "-s", scheme, "-l", "2"];
            fairsub(&[&args[..], &["-o", out_p.to_str().unwrap()]].concat()).0
        }) else {
            panic!("{scheme} takes none of {nets:?}");
        };
        let out_d = dir.join("d.ply");
        let args = ["subdivide", data.to_str().unwrap(), "-s", scheme, "-l", "2"];
        let (ok, err) = fairsub(&[&args[..], &["-o", out_d.to_str().unwrap()]].concat());
        assert!(ok, "{scheme}: {err}");
        let (bare, ours) = (read_out(&out_p), read_out(&out_d));
        let what = format!("{scheme} on {}", data.display());
        let want = expected(rules.as_ref(), data, None, 2, false);
        check_values(&ours, &want, &what);
        assert_eq!(bare.rows.len(), ours.rows.len(), "{what}");
        for (p, q) in positions(&ours).iter().zip(&positions(&bare)) {
            for k in 0..3 {
                assert!(
                    (p[k] - q[k]).abs() <= 1e-12,
                    "{what}: positions {p:?} vs {q:?}"
                );
            }
        }
        carried.push(scheme);
    }
    println!("ply_data: data carried by {carried:?}");
    assert!(carried.len() >= 8, "{carried:?}");
}
