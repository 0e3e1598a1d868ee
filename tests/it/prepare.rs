//! The preparation stage (`fairsub::schemes::prepare`): every step on a net of fairsub's own
//! that needs it. For each step: the note names the step and the elements; `--prepare none`
//! keeps the scheme's refusal; evaluation at `(face, u, v)` of the input faces agrees with the
//! written patches to 1e-12 (and is continuous across a grid of every face); the patch table
//! re-applied to moved input points equals the surface rebuilt from them to 1e-12; `--levels`
//! refines the prepared net.

use fairsub::geom::dist;
use fairsub::mesh::PolyMesh;
use fairsub::schemes::prepare::Mode;
use fairsub::schemes::registry::ids;
use fairsub::schemes::{SchemeId, Spec};
use fairsub::surface::ComplexOptions;
use fairsub::surface::eval::Surface;
use fairsub::surface::table::{PatchTable, probe};

use crate::eval_helpers::faces;
use crate::eval_helpers::support;
use faces::{face_points, jump_across};
use support::{gallery, irregular_boundary_nets, via_obj, written_from};

/// A net of fairsub's own that needs a step, the scheme, and the words its note names.
struct Case {
    net: &'static str,
    scheme: SchemeId,
    step: &'static str,
    /// The scheme's refusal under `--prepare none` (a part of it).
    refusal: &'static str,
}

fn net(name: &str) -> PolyMesh {
    match name {
        "split-edge-cube" => fairsub::mesh::nets::split_edge_cube(),
        "l-shape" | "cnet-5-notched" => {
            irregular_boundary_nets()
                .into_iter()
                .find(|(n, _)| *n == name)
                .expect("the net")
                .1
        }
        "open-grid-edge-only" => {
            let mut ex = fairsub::mesh::Extras::default();
            ex.options.boundary = Some(fairsub::mesh::tags::BoundaryInterpolation::EdgeOnly);
            gallery("open-grid").with_extras(Some(ex))
        }
        _ => gallery(name),
    }
}

/// Every step: the Catmull-Clark step (triangles, pentagons), one step of the dual scheme
/// itself (interior vertices of valence 2), the Doo-Sabin then Catmull-Clark steps of TPS
/// (valence 2, extraordinary boundary vertices), the PGS step of the mixed and polar nets
/// (valence 2).
fn cases() -> Vec<Case> {
    let cc = "one Catmull-Clark step";
    let ds_cc = "one Doo-Sabin step, then one Catmull-Clark step";
    vec![
        Case {
            net: "octahedron",
            scheme: ids::TPS,
            step: cc,
            refusal: "face 0 has 3 sides; tps refines quad nets (q-nets): apply one \
                      Catmull-Clark step first",
        },
        Case {
            net: "prism-5",
            scheme: ids::TPS_ADJUSTABLE,
            step: cc,
            refusal: "has 5 sides; tps-adjustable refines quad nets",
        },
        Case {
            net: "split-edge-cube",
            scheme: ids::TPS,
            step: ds_cc,
            refusal: "has 5 sides; tps refines quad nets",
        },
        Case {
            net: "l-shape",
            scheme: ids::TPS,
            step: ds_cc,
            refusal: "is a boundary vertex with 3 quads; tps has no rules for extraordinary \
                      boundary vertices",
        },
        Case {
            net: "cnet-5-notched",
            scheme: ids::TPS_ADJUSTABLE,
            step: ds_cc,
            refusal: "is a boundary vertex with 4 quads; tps-adjustable has no rules",
        },
        Case {
            net: "open-grid-edge-only",
            scheme: ids::TPS,
            step: ds_cc,
            refusal: "under the boundary mode edge-only: tps's boundary rules keep every corner",
        },
        Case {
            net: "split-edge-cube",
            scheme: ids::DOO_SABIN,
            step: "one Doo-Sabin step",
            refusal: "is an interior vertex of valence 2, which doo-sabin patches do not take",
        },
        Case {
            net: "split-edge-cube",
            scheme: ids::DOO_SABIN_CC,
            step: "one DS^CC step",
            refusal: "is an interior vertex of valence 2, which doo-sabin-cc patches do not take",
        },
        Case {
            net: "split-edge-cube",
            scheme: ids::PGS,
            step: "one PGS step",
            refusal: "is an interior vertex of valence 2, which pgs patches do not take",
        },
        Case {
            net: "split-edge-cube",
            scheme: ids::BI2_MIXED,
            step: "one PGS step",
            refusal: "bi2-mixed needs every extraordinary element surrounded by regular vertices",
        },
    ]
}

fn spec(id: SchemeId, mode: Mode) -> Spec {
    let mut s = Spec::new(id);
    s.params.prepare = mode;
    s
}

const OPTS: ComplexOptions = ComplexOptions {
    rings: 2,
    fill: true,
};

#[test]
fn each_step_is_named_in_a_note_and_none_keeps_the_refusal() {
    for c in cases() {
        let mesh = net(c.net);
        let what = format!("{} under {}", c.net, c.scheme);
        let out = fairsub::surface::build(&spec(c.scheme, Mode::Auto), &mesh, OPTS, &mut |_| {})
            .unwrap_or_else(|e| panic!("{what}: {e}"));
        let note = &out.notes[0];
        assert!(
            note.starts_with(&format!("prepared for {}: {} first", c.scheme, c.step)),
            "{what}: {note}"
        );
        let refused =
            fairsub::surface::build(&spec(c.scheme, Mode::None), &mesh, OPTS, &mut |_| {})
                .expect_err("refused without preparation")
                .to_string();
        assert!(refused.contains(c.refusal), "{what}: {refused}");
        assert!(!refused.contains("prepared"), "{what}: {refused}");
    }
}

/// Whether face point `p` of `mesh` lies where a prepared net has no face: the corner of the
/// quarter at an interior vertex of valence 2 (the dual step leaves its V-face out; see
/// `fairsub::schemes::prepare::map`).
fn at_valence_2(mesh: &PolyMesh, (f, u, v): (u32, f64, f64)) -> bool {
    let face = mesh.face(f as usize);
    let n = face.len();
    let (k, x, y) = if n == 4 {
        let k = match (u >= 0.5, v >= 0.5) {
            (false, false) => 0,
            (true, false) => 1,
            (true, true) => 2,
            (false, true) => 3,
        };
        // the quarter's own coordinates, corner k at (0, 0)
        let (a, b) = [(u, v), (1.0 - v, u), (1.0 - u, 1.0 - v), (v, 1.0 - u)][k];
        (k, 2.0 * a, 2.0 * b)
    } else {
        let k = (u.floor() as usize).min(n - 1);
        (k, u - k as f64, v)
    };
    let w = face[k] as usize;
    !mesh.is_boundary_vertex(w) && mesh.valence(w) == 2 && x < 0.5 && y < 0.5
}

#[test]
fn eval_on_the_input_faces_agrees_with_the_written_patches() {
    for c in cases() {
        let mesh = net(c.net);
        let what = format!("{} under {}", c.net, c.scheme);
        let (mesh, path) = via_obj(&mesh, &format!("prepare-{}-{}", c.net, c.scheme));
        let written = written_from(&path, c.net, c.scheme.name(), OPTS.rings);
        let s = Surface::build(&spec(c.scheme, Mode::Auto), &mesh, OPTS).expect(&what);
        assert_eq!(s.complex().len(), written.len(), "{what}: same patches");
        let (mut worst, mut evaluated, mut on_caps) = (0.0f64, 0, 0);
        for p in face_points(&mesh, 40, 7) {
            let (f, u, v) = p;
            match s.evaluate(f, u, v) {
                Ok(e) => {
                    let w = written.patches[e.patch].eval(e.patch_uv[0], e.patch_uv[1]);
                    worst = worst.max(dist(w, e.point));
                    evaluated += 1;
                    if matches!(
                        s.complex().provenance[e.patch],
                        fairsub::bezier::complex::Provenance::Cap { .. }
                    ) {
                        on_caps += 1;
                    }
                }
                Err(e) => {
                    assert!(at_valence_2(&mesh, p), "{what}: ({f}, {u}, {v}): {e}");
                    assert!(e.to_string().contains("no patch"), "{what}: {e}");
                }
            }
        }
        eprintln!("{what}: {evaluated} points, {on_caps} on caps, largest difference {worst:.2e}");
        assert!(worst <= 1e-12, "{what}: {worst:e}");
        // (the open grid's caps, at the corners' triangles of the dual step, cover a few
        // thousandths of a face away from its corners: random points miss them)
        assert!(
            on_caps > 0 || c.net == "open-grid-edge-only",
            "{what}: no point on a cap"
        );
        // continuity across the lines i / 8 of every face (the prepared faces' cells are
        // quarters and quarters of quarters of the input faces)
        let xs: Vec<f64> = (1..8).map(|i| f64::from(i) / 8.0).collect();
        let jump = jump_across(&mesh, &s, &xs, 1e-10, &|m, p| !at_valence_2(m, p));
        eprintln!("{what}: largest jump {jump:.2e}");
        assert!(jump < 1e-7, "{what}: jump {jump:e}");
    }
}

#[test]
fn patch_tables_map_from_the_input_points() {
    for c in cases() {
        let mesh = net(c.net);
        let what = format!("{} under {}", c.net, c.scheme);
        let sp = spec(c.scheme, Mode::Auto);
        let table = PatchTable::build(&sp, &mesh, OPTS).expect(&what);
        assert_eq!(
            table.num_sources(),
            mesh.num_vertices(),
            "{what}: input points"
        );
        let s = probe::net_size(mesh.positions());
        let moved = probe::moved_points(mesh.positions(), 0.05 * s, 11);
        let mut m = mesh.clone();
        m.set_positions(moved.clone());
        let truth = fairsub::surface::build(&sp, &m, OPTS, &mut |_| {})
            .expect(&what)
            .complex;
        let (d, _) = probe::max_deviation(&table.apply(&moved).expect(&what), &truth);
        eprintln!("{what}: re-applied table {d:.2e}");
        assert!(d <= 1e-12 * s, "{what}: moved points {d:e}");
    }
}

/// The mixed and polar nets separate their elements by the family's own constructions
/// (`fairsub::schemes::bi2::surface`'s elements): TPS's whole-net steps on a net of
/// extraordinary vertices (the cube), else the PGS step (the prism's pentagons, the L-shape's
/// boundary vertex); the note says which, `--prepare none` refuses, and the surface evaluates on
/// the input faces.
#[test]
fn mixed_and_polar_nets_separate_their_elements() {
    let tps = "a net whose elements are all extraordinary vertices is a tps net";
    let pgs = "one pgs step makes every element a facet";
    for (name, id, note) in [
        ("cube", ids::BI2_MIXED, tps),
        ("cube", ids::POLAR_BI2, tps),
        ("prism-5", ids::BI2_MIXED, pgs),
        ("l-shape", ids::BI2_MIXED, pgs),
        ("cnet-5-notched", ids::POLAR_BI2, pgs),
        ("tetrahedron", ids::POLAR_BI2, pgs),
        ("open-grid-edge-only", ids::BI2_MIXED, pgs),
    ] {
        let mesh = net(name);
        let what = format!("{name} under {id}");
        let out = fairsub::surface::build(&spec(id, Mode::Auto), &mesh, OPTS, &mut |_| {})
            .unwrap_or_else(|e| panic!("{what}: {e}"));
        assert!(
            out.notes.iter().any(|n| n.contains(note)),
            "{what}: {:?}",
            out.notes
        );
        let refused = fairsub::surface::build(&spec(id, Mode::None), &mesh, OPTS, &mut |_| {})
            .expect_err("refused without preparation")
            .to_string();
        let named = [
            "is not regular",
            "has no DS-net",
            "does not have valence 4",
            "under the boundary mode edge-only",
        ];
        assert!(
            named.iter().any(|n| refused.contains(n)),
            "{what}: {refused}"
        );
        let s = Surface::build(&spec(id, Mode::Auto), &mesh, OPTS).expect(&what);
        let pts = face_points(&mesh, 20, 3);
        let bad = pts
            .iter()
            .filter(|&&(f, u, v)| s.evaluate(f, u, v).is_err())
            .count();
        assert_eq!(bad, 0, "{what}: points that do not evaluate");
    }
}

/// Runs the `fairsub` binary: success, standard output, standard error.
fn fairsub(args: &[&str]) -> (bool, String, String) {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_fairsub"))
        .args(args)
        .output()
        .expect("the binary runs");
    let text = |b: &[u8]| String::from_utf8_lossy(b).into_owned();
    (out.status.success(), text(&out.stdout), text(&out.stderr))
}

#[test]
fn levels_refine_the_prepared_net() {
    let out = support::tmp("fairsub-prepare", "octahedron-tps-1.obj");
    let path = out.to_str().expect("utf-8");
    let words = [
        "subdivide",
        "gallery:octahedron",
        "--scheme",
        "tps",
        "--levels",
        "1",
        "-o",
        path,
    ];
    let (ok, _, err) = fairsub(&words);
    assert!(ok, "{err}");
    assert!(
        err.contains("note: prepared for tps: one Catmull-Clark step first"),
        "{err}"
    );
    // 8 triangles, 24 quads after the Catmull-Clark step, 9 each after the TPS step
    let m = fairsub::io::read_mesh(&out).expect("written").mesh;
    assert_eq!(m.num_faces(), 24 * 9);
    let (ok, _, err) = fairsub(&[&words[..], &["--prepare", "none"]].concat());
    assert!(!ok);
    assert!(
        err.contains("face 0 has 3 sides; tps refines quad nets"),
        "{err}"
    );
    // the mixed net's refinement takes one kind of element: one PGS step first (the
    // split-edge cube has pentagons and extraordinary vertices of quads)
    let (_, cube) = via_obj(&net("split-edge-cube"), "prepare-levels-split-edge-cube");
    let words = [
        "subdivide",
        &cube,
        "--scheme",
        "bi2-mixed",
        "--levels",
        "1",
        "-o",
        path,
    ];
    let (ok, _, err) = fairsub(&words);
    assert!(ok, "{err}");
    assert!(
        err.contains("prepared for bi2-mixed: one PGS step first"),
        "{err}"
    );
}

#[test]
fn info_says_what_would_be_prepared() {
    let (ok, text, err) = fairsub(&["info", "gallery:octahedron", "--scheme", "tps"]);
    assert!(ok, "{err}");
    assert!(
        text.contains("tps patches: one Catmull-Clark step (applied); tps needs every face a quad (face 0 (3 sides)"),
        "{text}"
    );
    assert!(
        text.contains("tps prepared net: 26 vertices, 24 faces"),
        "{text}"
    );
    let (ok, text, err) = fairsub(&["info", "gallery:cube", "--scheme", "bi2-mixed", "--json"]);
    assert!(ok, "{err}");
    let j: serde_json::Value = serde_json::from_str(&text).expect("json");
    let p = &j["preparation"]["patches"][0];
    assert_eq!(p["kind"], "own", "{p}");
    assert_eq!(p["count"], 8, "{p}");
    let (ok, text, _) = fairsub(&["info", "gallery:cube", "--scheme", "catmull-clark"]);
    assert!(ok);
    assert!(
        text.contains("catmull-clark patches: nothing to prepare"),
        "{text}"
    );
}

/// Interior vertices of valence 2 on a net with semi-sharp creases (OpenSubdiv's
/// `catmark_val2_interior` tags them beside infinitely sharp ones): the dual step that removes
/// them carries the creases with the dual crease rules (an infinitely sharp crease stays one, a
/// semi-sharp one loses a unit), as the dual schemes' own levels do, so it is applied (given to
/// the scheme unprepared and refused until 2026-12-07). The surface is the scheme's on the net
/// its own `--levels 1` makes, patch for patch.
#[test]
fn valence_two_vertices_beside_creases_get_the_dual_step() {
    use fairsub::mesh::{Extras, SharpEdges};
    let cube = net("split-edge-cube");
    let edge = |a: u32, b: u32| cube.find_edge(a, b).expect("an edge");
    // the loop around a face without a vertex of valence 2, semi-sharp; then also an
    // infinitely sharp loop around the pentagon of the valence-2 vertex. The net Doo-Sabin's
    // own `--levels 1` makes of the second was refused by its patches ("vertex 40 is a dart")
    // until the dart caps; it is built now, its sharp loop kept.
    let loop_of = |f: usize, s: f32| {
        let c = cube.face(f).to_vec();
        (0..c.len())
            .map(|i| (edge(c[i], c[(i + 1) % c.len()]), s))
            .collect::<Vec<_>>()
    };
    let plain = (0..cube.num_faces())
        .rfind(|&f| cube.face(f).iter().all(|&v| cube.valence(v as usize) > 2))
        .expect("a face without a vertex of valence 2");
    let semi = loop_of(plain, 1.5);
    let pentagon = (0..cube.num_faces())
        .find(|&f| cube.face(f).iter().any(|&v| cube.valence(v as usize) == 2))
        .expect("a face with the vertex of valence 2");
    let both = [semi.clone(), loop_of(pentagon, f32::INFINITY)].concat();
    let smooth = fairsub::surface::build(
        &spec(ids::DOO_SABIN, Mode::Auto),
        &cube,
        ComplexOptions {
            rings: 3,
            fill: true,
        },
        &mut |_| {},
    )
    .expect("the untagged net");
    let opts = ComplexOptions {
        rings: 3,
        fill: true,
    };
    for (sharp, kept) in [(semi, false), (both, true)] {
        let tagged = cube.clone().with_extras(Some(Extras {
            sharp_edges: SharpEdges::ById(sharp),
            ..Extras::default()
        }));
        for (id, step) in [
            (ids::DOO_SABIN, "one Doo-Sabin step"),
            (ids::DOO_SABIN_CC, "one DS^CC step"),
            (ids::PGS, "one PGS step"),
        ] {
            let name = id.name();
            let out = fairsub::surface::build(&spec(id, Mode::Auto), &tagged, opts, &mut |_| {})
                .unwrap_or_else(|e| panic!("{name}: {e}"));
            assert!(
                out.notes
                    .iter()
                    .any(|n| n.contains(step) && n.contains("valence 3 or more")),
                "{name}: {:?}",
                out.notes
            );
            let e = fairsub::surface::build(&spec(id, Mode::None), &tagged, opts, &mut |_| {})
                .err()
                .unwrap_or_else(|| panic!("{name}: built unprepared"))
                .to_string();
            assert!(e.contains("interior vertex of valence 2"), "{name}: {e}");
            let scheme = fairsub::schemes::by_name(name).expect("the scheme");
            let once = fairsub::schemes::refine_levels(scheme.as_ref(), &tagged, 1, |_| {})
                .expect("one step");
            let want = fairsub::surface::build(&spec(id, Mode::Auto), &once, opts, &mut |_| {})
                .unwrap_or_else(|e| panic!("{name} on its level 1: {e}"));
            let (a, b) = (&out.complex.patches, &want.complex.patches);
            assert_eq!(a.len(), b.len(), "{name}: patch counts");
            let worst = a
                .iter()
                .zip(b)
                .flat_map(|(p, q)| p.cps.iter().zip(&q.cps).map(|(x, y)| dist(*x, *y)))
                .fold(0.0f64, f64::max);
            let r = fairsub::analysis::continuity::check(&out.complex);
            eprintln!(
                "{name}: {} patches, against level 1 {worst:.1e}, G1 {:.1e}, sharp {}",
                a.len(),
                r.all.g1,
                r.sharp.pieces
            );
            assert!(worst < 1e-12, "{name}: {worst:e}");
            // G^1 off the sharp loop; the spent crease smooth, the infinitely sharp one kept
            assert!(r.all.g1 < 1e-8 && (r.sharp.pieces > 0) == kept, "{name}");
            if id == ids::DOO_SABIN {
                // the crease changes the surface (so a dropped crease cannot pass)
                assert_ne!(a.len(), smooth.complex.patches.len(), "the crease");
            }
        }
    }
}
