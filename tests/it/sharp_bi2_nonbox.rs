//! Creases and corners under the dual bi-2 schemes (Doo-Sabin, DS^CC, PGS, PGS after DS^CC
//! steps) and non-box: fairsub's crease constructions (`schemes::doo_sabin::sharp`,
//! `schemes::nonbox::sharp`, `docs/guide/src/creases.md`) on the team's
//! tagged nets and on nets built here. Closed creased nets give closed surfaces, every smooth
//! join is G^1, the patches are the limit of `--levels`, evaluation and patch tables work
//! through the construction, sharpness 10 is the infinitely sharp crease, and the distance to
//! it halves with every unit of sharpness.

use crate::sharp_helpers::support;
use support::{osd, table_reapplies};

use fairsub::analysis::continuity;
use fairsub::bezier::complex::PatchComplex;
use fairsub::geom::{Point, dist};
use fairsub::host::ComplexOptions;
use fairsub::mesh::{PolyMesh, SharpEdges};
use fairsub::schemes::registry::registry;
use fairsub::surface::eval::Surface;

/// The schemes with creases of their own.
const SCHEMES: &[&str] = &[
    "doo-sabin",
    "doo-sabin-cc",
    "pgs",
    "pgs-dscc",
    "nonbox",
    "nonbox-4dir",
];

fn complex(scheme: &str, mesh: &PolyMesh, rings: usize) -> PatchComplex {
    let spec = registry().lookup(scheme).expect("scheme");
    let opts = ComplexOptions { rings, fill: true };
    fairsub::surface::build(&spec, mesh, opts, &mut |_| {})
        .unwrap_or_else(|e| panic!("{scheme}: {e}"))
        .complex
}

/// The creased cube of the crease tests ([`support::creased_cube`]).
fn cube(equator: f32, top: f32) -> PolyMesh {
    support::creased_cube(equator, top)
}

#[test]
fn closed_creased_nets_give_closed_g1_surfaces() {
    let nets = [
        ("cc_pole7_crease", osd("cc_pole7_crease")),
        ("cc_chain_chaikin", osd("cc_chain_chaikin")),
        ("cube 2.5 / 0.7", cube(2.5, 0.7)),
        ("cube 10 / 1.5", cube(10.0, 1.5)),
    ];
    for scheme in SCHEMES {
        for (name, net) in &nets {
            let c = complex(scheme, net, 2);
            let r = continuity::check(&c);
            eprintln!(
                "{scheme} {name}: {} patches, open {}, C0 {:.1e}, G1 {:.1e}, sharp {} (C0 {:.1e})",
                c.len(),
                r.open_sides,
                r.all.c0,
                r.all.g1,
                r.sharp.pieces,
                r.sharp.c0
            );
            assert_eq!(r.open_sides, 0, "{scheme} {name}: cracks");
            assert!(r.all.c0 < 1e-12 && r.sharp.c0 < 1e-12, "{scheme} {name}");
            assert!(r.all.g1 < 1e-8, "{scheme} {name}: G1 {:e}", r.all.g1);
            // the infinitely sharp equator is reported as a sharp join, nothing else is
            assert_eq!(r.sharp.pieces > 0, name.contains("10"), "{scheme} {name}");
        }
    }
}

/// The limit points of the faces of `mesh` refined `levels` times by the dual scheme `scheme`:
/// its corner rules keep every face's centroid, which is the limit point of the face.
fn dual_face_limits(scheme: &str, mesh: &PolyMesh, levels: usize) -> Vec<Point> {
    let s = fairsub::schemes::by_name(scheme).expect("scheme");
    let m = fairsub::schemes::refine_levels(s.as_ref(), mesh, levels, |_| {}).expect("refine");
    let mut pts: Vec<Point> = (0..m.num_faces()).map(|f| m.face_centroid(f)).collect();
    pts.sort_by(|a, b| a[0].total_cmp(&b[0]));
    pts
}

#[test]
fn dual_patches_are_the_limit_of_the_refined_nets() {
    // every corner of a patch of the adaptive host is the limit point of a face, kept by every
    // later level: it is a face centroid of the net refined uniformly (--levels) as deep
    for scheme in ["doo-sabin", "doo-sabin-cc"] {
        for (name, net) in [
            ("cube 2.5 / 0.7", cube(2.5, 0.7)),
            ("cc_chain_chaikin", osd("cc_chain_chaikin")),
        ] {
            let c = complex(scheme, &net, 1);
            let deepest = c
                .provenance
                .iter()
                .filter_map(support::level_of)
                .max()
                .unwrap_or(0);
            let pts = dual_face_limits(scheme, &net, deepest);
            let mut worst: f64 = 0.0;
            let mut checked = 0;
            for (p, prov) in c.patches.iter().zip(&c.provenance) {
                if support::level_of(prov) != Some(deepest) {
                    continue;
                }
                for (u, v) in [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)] {
                    worst = worst.max(support::nearest(&pts, p.eval(u, v)));
                    checked += 1;
                }
            }
            eprintln!("{scheme} {name}: level {deepest}, {checked} corners, worst {worst:.1e}");
            assert!(checked > 0 && worst < 1e-12, "{scheme} {name}: {worst:e}");
        }
    }
}

#[test]
fn levels_keep_closed_creased_nets_closed() {
    for scheme in SCHEMES {
        let s = fairsub::schemes::by_name(scheme).expect("scheme");
        for name in ["cc_pole7_crease", "cc_chain_chaikin"] {
            let net = osd(name);
            let m = fairsub::schemes::refine_levels(s.as_ref(), &net, 3, |_| {}).expect(name);
            assert!(m.boundary_loops().is_empty(), "{scheme} {name}: a boundary");
        }
    }
}

/// The points of the faces of the cube's lower half (every corner at `z <= 0`: the faces along
/// the equator and those below, away from the top loop), on a grid of each.
fn lower_points(mesh: &PolyMesh) -> Vec<(u32, f64, f64)> {
    let p = mesh.positions();
    let mut out = Vec::new();
    for f in 0..mesh.num_faces() {
        if mesh.face(f).iter().all(|&v| p[v as usize][2] < 1e-12) {
            for i in 0..=4 {
                for j in 0..=4 {
                    out.push((f as u32, f64::from(i) / 4.0, f64::from(j) / 4.0));
                }
            }
        }
    }
    out
}

fn evaluate(scheme: &str, mesh: &PolyMesh, pts: &[(u32, f64, f64)]) -> Vec<Point> {
    let spec = registry().lookup(scheme).expect("scheme");
    let s = Surface::build(
        &spec,
        mesh,
        ComplexOptions {
            rings: 2,
            fill: true,
        },
    )
    .expect("surface");
    pts.iter()
        .map(|&(f, u, v)| s.evaluate(f, u, v).expect("a face point").point)
        .collect()
}

fn largest(a: &[Point], b: &[Point]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| dist(*x, *y))
        .fold(0.0, f64::max)
}

#[test]
fn sharpness_ten_is_the_infinitely_sharp_crease() {
    let reference = cube(10.0, 0.0);
    let pts = lower_points(&reference);
    assert!(pts.len() > 500);
    for scheme in ["doo-sabin", "pgs", "nonbox"] {
        // the net cut along the crease from the start (no semi-sharp feature)
        let cut = evaluate(scheme, &reference, &pts);
        // the same crease refined by the semi-sharp construction (the top loop is semi-sharp):
        // its sharp rules until the top loop is spent, then the cut
        let infinite = evaluate(scheme, &cube(10.0, 0.5), &pts);
        let same = largest(&cut, &infinite);
        // a finite sharpness gives another surface near the crease (non-box: its faces reach
        // the crease; the dual schemes' faces end a strip short of it, see the guide)
        let finite = largest(&evaluate(scheme, &cube(2.0, 0.5), &pts), &infinite);
        eprintln!(
            "{scheme}: sharpness 10 against the cut net {same:.1e}, sharpness 2 {finite:.1e}"
        );
        assert!(same < 1e-9, "{scheme}: {same:e}");
        if scheme == "nonbox" {
            assert!(finite > 1e-3, "{scheme}: {finite:e}");
        }
    }
}

/// The points of `mesh` refined `levels` times by `scheme` (`--levels`).
fn refined(scheme: &str, mesh: &PolyMesh, levels: usize) -> Vec<Point> {
    let s = fairsub::schemes::by_name(scheme).expect("scheme");
    let m = fairsub::schemes::refine_levels(s.as_ref(), mesh, levels, |_| {}).expect("refine");
    m.positions().to_vec()
}

fn largest_pointwise(a: &[Point], b: &[Point]) -> f64 {
    assert_eq!(a.len(), b.len(), "the same child layout");
    largest(a, b)
}

#[test]
fn sharpness_at_least_the_levels_is_the_infinitely_sharp_crease() {
    // --levels 3: a crease of sharpness 3 or more is sharp on every step, so the refined net
    // is point for point the one of the infinitely sharp crease; below 3 it is not
    for scheme in SCHEMES {
        let infinite = refined(scheme, &cube(10.0, 0.0), 3);
        for s in [3.0f32, 3.5, 6.0, 9.9] {
            let d = largest_pointwise(&refined(scheme, &cube(s, 0.0), 3), &infinite);
            assert!(d < 1e-12, "{scheme} sharpness {s}: {d:e}");
        }
        let below = refined(scheme, &cube(2.5, 0.0), 3);
        let d = largest_pointwise(&below, &infinite);
        eprintln!("{scheme}: sharpness 2.5 against infinite after 3 levels {d:.3e}");
        assert!(d > 1e-4, "{scheme}: {d:e}");
    }
}

#[test]
fn the_last_step_blends_linearly_in_the_fractional_sharpness() {
    // sharpness 1 + t: sharp on the first step, OpenSubdiv's blend with weight t on the second;
    // every point of the second level is linear in t (the child layout is the same for t > 0)
    for scheme in SCHEMES {
        let at = |t: f32| refined(scheme, &cube(1.0 + t, 0.0), 2);
        let (p25, p50, p75, p100) = (at(0.25), at(0.5), at(0.75), at(1.0));
        let mut worst: f64 = 0.0;
        for i in 0..p50.len() {
            for k in 0..3 {
                worst = worst.max((p50[i][k] - 0.5 * (p25[i][k] + p75[i][k])).abs());
                worst = worst.max((p100[i][k] - (2.0 * p75[i][k] - p50[i][k])).abs());
            }
        }
        let moved = largest_pointwise(&p25, &p100);
        eprintln!("{scheme}: linear to {worst:.1e}, t = 1/4 to 1 moves {moved:.3e}");
        assert!(worst < 1e-12, "{scheme}: {worst:e}");
        assert!(moved > 1e-3, "{scheme}: {moved:e}");
    }
}

#[test]
fn the_chaikin_points_of_a_fractional_crease_have_the_blend_s_values() {
    // one Doo-Sabin step of the cube with its equator at sharpness w < 1: the two points of a
    // crease edge (a, b) are w (3/4 a + 1/4 b) + (1 - w) (c1 + c2) / 2, where c1, c2 are the
    // corner points at a of the two faces of the edge (the smooth E-face's side there), laid
    // out after the corner points (child point h: the corner of half-edge h), two per sharp
    // edge in edge order
    let s = fairsub::schemes::by_name("doo-sabin").expect("scheme");
    for w in [0.25f32, 0.6, 1.0] {
        let net = cube(w, 0.0);
        let child = fairsub::schemes::refine_levels(s.as_ref(), &net, 1, |_| {}).expect("refine");
        let (p, q) = (net.positions(), child.positions());
        let w = f64::from(w);
        let mut k = net.num_halfedges();
        let mut worst: f64 = 0.0;
        let mut sharp: Vec<usize> = match &net.extras().expect("tags").sharp_edges {
            SharpEdges::ById(v) => v.iter().map(|x| x.0 as usize).collect(),
            SharpEdges::ByPair(_) => unreachable!("the cube tags edges by id"),
        };
        sharp.sort_unstable();
        for e in sharp {
            let h = net.edge_halfedge(e);
            let t = net.he_twin(h).expect("a closed net");
            let (a, b) = (net.he_from(h) as usize, net.he_to(h) as usize);
            let corners = [
                (h as usize, net.he_next(t) as usize),
                (net.he_next(h) as usize, t as usize),
            ];
            for ((c1, c2), (x, y)) in [(corners[0], (a, b)), (corners[1], (b, a))] {
                let along =
                    |u: Point, v: Point, t: f64| [0, 1, 2].map(|i| u[i] + t * (v[i] - u[i]));
                let chaikin = along(p[x], p[y], 0.25);
                let mid = along(q[c1], q[c2], 0.5);
                let expect = along(mid, chaikin, w);
                worst = worst.max(dist(q[k], expect));
                k += 1;
            }
        }
        assert!(worst < 1e-14, "w {w}: {worst:e}");
    }
}

#[test]
fn evaluation_and_patch_tables_work_through_creases() {
    let net = osd("cc_pole7_crease");
    for scheme in ["doo-sabin", "pgs", "nonbox"] {
        let spec = registry().lookup(scheme).expect("scheme");
        let s = Surface::build(
            &spec,
            &net,
            ComplexOptions {
                rings: 2,
                fill: true,
            },
        )
        .expect("surface");
        // every face point lies on the patch evaluation names
        let mut worst: f64 = 0.0;
        for f in 0..net.num_faces() as u32 {
            let n = net.face_size(f as usize);
            let width = if n == 4 { 1.0 } else { n as f64 };
            for i in 0..=6 {
                for j in 0..=6 {
                    let (u, v) = (width * f64::from(i) / 6.0, f64::from(j) / 6.0);
                    let e = s.evaluate(f, u, v).expect("a face point");
                    let p = s.complex().patches[e.patch].eval(e.patch_uv[0], e.patch_uv[1]);
                    worst = worst.max(dist(p, e.point));
                }
            }
        }
        assert!(worst < 1e-12, "{scheme}: {worst:e}");
        table_reapplies(scheme, "cc_pole7_crease", &net, |_| true);
    }
}

#[test]
fn what_the_constructions_do_not_take_is_refused_by_name() {
    let spec = |s: &str| registry().lookup(s).expect("scheme");
    let opts = ComplexOptions {
        rings: 2,
        fill: true,
    };
    // infinitely sharp darts: the dual patches cannot fade the crease out
    let e = fairsub::surface::build(&spec("doo-sabin"), &osd("cc_torus_dart"), opts, &mut |_| {})
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("vertex 0 is a dart of an infinitely sharp crease"),
        "{e}"
    );
    // the bi-2 schemes with element rings take infinitely sharp creases only: with
    // --prepare none (the default spends them first, tests/it/semisharp_rings.rs)
    let mut strict = spec("tps");
    strict.params.prepare = fairsub::schemes::options::PrepareMode::None;
    let e = fairsub::surface::build(&strict, &cube(2.5, 0.0), opts, &mut |_| {})
        .unwrap_err()
        .to_string();
    assert!(e.contains("semi-sharp crease value 2.5"), "{e}");
    // a corner tag inside the surface
    let mut net = cube(2.5, 0.0);
    let mut ex = net.extras().cloned().unwrap();
    ex.sharp_vertices = vec![(0, 3.0)];
    net = net.with_extras(Some(ex));
    let e = fairsub::surface::build(&spec("pgs"), &net, opts, &mut |_| {})
        .unwrap_err()
        .to_string();
    assert!(e.contains("vertex 0 is tagged as a corner"), "{e}");
}

/// A 6 x 6 grid, bent, with an infinitely sharp crease of two edges in its middle row (a dart
/// at each end, vertices 23 and 25).
fn grid_with_dart_chain() -> PolyMesh {
    let n = 6;
    let mut p = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (i as f64 - 3.0, j as f64 - 3.0);
            p.push([x, y, 0.05 * (x * x - 0.5 * y * y)]);
        }
    }
    let faces: Vec<[usize; 4]> = (0..n)
        .flat_map(|j| {
            (0..n).map(move |i| {
                let a = j * (n + 1) + i;
                [a, a + 1, a + n + 2, a + n + 1]
            })
        })
        .collect();
    let m = PolyMesh::new(p, &faces).expect("grid");
    let edge = |a: u32, b: u32| m.find_edge(a, b).expect("an edge");
    let sharp = vec![(edge(23, 24), 10.0), (edge(24, 25), 10.0)];
    m.with_extras(Some(fairsub::mesh::Extras {
        sharp_edges: SharpEdges::ById(sharp),
        ..Default::default()
    }))
}

/// Infinitely sharp creases that end at darts inside the surface (OpenSubdiv's
/// `cc_cube_infsharp` and `cc_torus_dart`, and [`grid_with_dart_chain`]): non-box refines the
/// uncut net (a dart by the smooth rule, as OpenSubdiv's rules say), reads the patches off a copy
/// cut along every crease, and closes each dart's fan with the dart cap ([`Fan::Dart`], centred
/// at the dart's limit point in its tangent plane, from `nonbox::local::dart`). Until
/// 2026-12-07 those chains were not cut and their cells waited: the C^0 fill closed a strip
/// along each (3.6e-4 rad on the grid at 3 rings). The patches off the darts' faces are the
/// same at 1 and at 3 rings (exact), and the patch table re-applies.
///
/// [`Fan::Dart`]: fairsub::bezier::g1::Fan::Dart
#[test]
fn nonbox_caps_the_darts_of_creases_ending_inside_the_surface() {
    use fairsub::bezier::g1::Fan;
    let is_dart = |h: &fairsub::bezier::g1::Hole| matches!(h.kind, Fan::Dart);
    let grid = grid_with_dart_chain();
    let nets = [
        (
            "cc_cube_infsharp",
            osd("cc_cube_infsharp"),
            vec![1, 2],
            true,
        ),
        ("cc_torus_dart", osd("cc_torus_dart"), vec![0, 2], true),
        ("grid", grid.clone(), vec![23, 25], false),
    ];
    for scheme in ["nonbox", "nonbox-4dir"] {
        for (name, net, darts, closed) in &nets {
            let c = complex(scheme, net, 3);
            let r = continuity::check(&c);
            let caps = c.caps.iter().filter(|s| is_dart(&s.hole)).count();
            eprintln!(
                "{scheme} {name}: {} patches, {caps} dart caps, open {}, G1 {:.1e}, sharp {}",
                c.len(),
                r.open_sides,
                r.all.g1,
                r.sharp.pieces,
            );
            assert_eq!(caps, darts.len(), "{scheme} {name}");
            assert_eq!(support::fill_patches(&c), 0, "{scheme} {name}");
            if *closed {
                assert_eq!(r.open_sides, 0, "{scheme} {name}: cracks");
            }
            assert!(r.all.c0 < 1e-12 && r.sharp.c0 < 1e-12, "{scheme} {name}");
            assert!(r.all.g1 < 1e-10, "{scheme} {name}: G1 {:e}", r.all.g1);
            assert!(
                r.sharp.pieces > 0,
                "{scheme} {name}: the creases are sharp joins"
            );
            if scheme == "nonbox" {
                // off the darts' faces the surface does not depend on the rings
                let pts: Vec<(u32, f64, f64)> = (0..net.num_faces())
                    .filter(|&f| !net.face(f).iter().any(|v| darts.contains(v)))
                    .flat_map(|f| {
                        (0..=4).flat_map(move |i| {
                            (0..=4).map(move |j| (f as u32, f64::from(i) / 4.0, f64::from(j) / 4.0))
                        })
                    })
                    .collect();
                let surface = |rings: usize| {
                    let spec = registry().lookup(scheme).expect("scheme");
                    Surface::build(&spec, net, ComplexOptions { rings, fill: true })
                        .expect("surface")
                };
                let at = |rings: usize| {
                    let s = surface(rings);
                    pts.iter()
                        .map(|&(f, u, v)| s.evaluate(f, u, v).expect("a face point").point)
                        .collect::<Vec<Point>>()
                };
                let d = largest(&at(1), &at(3));
                eprintln!(
                    "{name}: {} points off the darts, 1 against 3 rings {d:.1e}",
                    pts.len()
                );
                assert!(d < 1e-12, "{name}: {d:e}");
                // the surface of the net its own `--levels 1` makes (which refines each dart by
                // the smooth rule) lies on this one, caps included (both at level 3)
                let s = fairsub::schemes::by_name(scheme).expect("scheme");
                let once =
                    fairsub::schemes::refine_levels(s.as_ref(), net, 1, |_| {}).expect("one step");
                let samples: Vec<Point> = complex(scheme, &once, 2)
                    .patches
                    .iter()
                    .flat_map(|p| [p.eval(0.25, 0.25), p.eval(0.75, 0.5)])
                    .collect();
                let here = surface(3);
                let off = here
                    .closest_points(&samples)
                    .iter()
                    .map(|c| c.as_ref().expect("a closest point").distance)
                    .fold(0.0, f64::max);
                eprintln!(
                    "{name}: level 1's surface {off:.1e} off, {} points",
                    samples.len()
                );
                assert!(off < 1e-10, "{name}: {off:e}");
            }
        }
    }
    let caps = table_reapplies("nonbox", "grid with a dart chain", &grid, is_dart);
    assert_eq!(caps, 2, "the table's dart caps");
}

/// A loop of infinitely sharp creases around one face (OpenSubdiv's `catmark_fvar_project0`):
/// non-box's cut leaves each of the four crease vertices a copy of three cells outside the loop
/// (an open fan) and one of one cell on the island (a crease fan of one sector, where the
/// boundary of the island passes: [`one_cell_copies_get_crease_fans`]), all G^1-capped. The
/// copies share the vertex's element; until each copy was its own hole, the four cells made
/// one hole of no fan, filled C^0 without a note: 2.3e-3 rad, halving with every ring; until
/// 2026-12-07 the island copies kept the fill (named in the notes).
#[test]
fn each_copy_of_a_cut_crease_vertex_is_its_own_hole() {
    use fairsub::bezier::g1::Fan;
    let net = osd("catmark_fvar_project0");
    for scheme in ["nonbox", "nonbox-4dir"] {
        let s = rings3(scheme, &net);
        let r = continuity::check(&s.complex);
        assert!(r.all.g1 < 1e-10, "{scheme}: G1 {:e}", r.all.g1);
        let kinds: Vec<(bool, usize)> = s
            .complex
            .caps
            .iter()
            .map(|c| (matches!(c.hole.kind, Fan::Crease), c.hole.sectors.len()))
            .collect();
        let island = kinds.iter().filter(|&&k| k == (true, 1)).count();
        let outside = kinds.iter().filter(|&&k| k == (false, 3)).count();
        assert_eq!(
            (kinds.len(), island, outside),
            (8, 4, 4),
            "{scheme}: {kinds:?}"
        );
        assert_eq!(support::fill_patches(&s.complex), 0, "{scheme}");
        assert!(
            s.complex.uncapped.is_empty(),
            "{scheme}: {:?}",
            s.complex.uncapped
        );
        // the patch table repeats the eight open-fan caps on moved points
        let caps = table_reapplies(scheme, "catmark_fvar_project0", &net, |h| h.is_open());
        assert_eq!(caps, 8, "{scheme}");
    }
}

/// Kept corners of the cut net with two or more cells on one side (OpenSubdiv's
/// `catmark_inf_crease0` and `catmark_inf_crease1`: three infinitely sharp edges meeting at a
/// vertex of four faces) get Catmull-Clark's corner cap under non-box; the C^0 fill closed
/// them until 2026-12-07 (0.87 and 0.57 rad). Both are then G^1 everywhere
/// (`catmark_inf_crease0`'s copy of one cell where a crease turns: [`one_cell_copies_get_crease_fans`]).
#[test]
fn kept_corners_with_two_cells_get_corner_caps() {
    use fairsub::bezier::g1::Fan;
    let corner = |h: &fairsub::bezier::g1::Hole| matches!(h.kind, Fan::Corner(_));
    for scheme in ["nonbox", "nonbox-4dir"] {
        for (name, g1) in [
            ("catmark_inf_crease1", 1e-10),
            ("catmark_inf_crease0", 1e-10),
        ] {
            let net = osd(name);
            let s = rings3(scheme, &net);
            let caps = s.complex.caps.iter().filter(|c| corner(&c.hole)).count();
            let r = continuity::check(&s.complex);
            eprintln!("{scheme} {name}: {caps} corner caps, G1 {:.1e}", r.all.g1);
            assert!(caps >= 1, "{scheme} {name}: no corner cap");
            assert!(r.all.g1 < g1, "{scheme} {name}: G1 {:e}", r.all.g1);
            assert!(
                !s.notes.iter().any(|n| n.contains("a hole of 2 sectors")),
                "{scheme} {name}: {:?}",
                s.notes
            );
        }
        let caps = table_reapplies(
            scheme,
            "catmark_inf_crease1",
            &osd("catmark_inf_crease1"),
            corner,
        );
        assert!(caps >= 1, "{scheme}: the table's corner caps");
    }
}

/// A copy of a vertex with one cell on a boundary that passes (where a crease turns at a
/// vertex that is no corner, the cut leaves a copy with one cell on the inner side; or a
/// vertex of one face on an edge-only boundary) gets Catmull-Clark's crease fan of one sector
/// (`nonbox::surface::g1`, spokes the boundary curve's halves, in the plane of its tangent and
/// `F - (a + b) / 2`, `nonbox::boundary`): no fill patch is left. Until 2026-12-07 the fill
/// closed them: 1.1e-3 rad on `catmark_inf_crease0`, 1.6e-3 on `loop_triangle_edgeonly`.
#[test]
fn one_cell_copies_get_crease_fans() {
    use fairsub::bezier::g1::Fan;
    let one_cell =
        |h: &fairsub::bezier::g1::Hole| matches!(h.kind, Fan::Crease) && h.sectors.len() == 1;
    for scheme in ["nonbox", "nonbox-4dir"] {
        for (name, fans) in [("catmark_inf_crease0", 1), ("loop_triangle_edgeonly", 9)] {
            let net = osd(name);
            let s = rings3(scheme, &net);
            let caps = s.complex.caps.iter().filter(|c| one_cell(&c.hole)).count();
            let r = continuity::check(&s.complex);
            eprintln!("{scheme} {name}: {caps} one-cell fans, G1 {:.1e}", r.all.g1);
            assert_eq!(caps, fans, "{scheme} {name}");
            assert_eq!(support::fill_patches(&s.complex), 0, "{scheme} {name}");
            assert!(r.all.g1 < 1e-10, "{scheme} {name}: G1 {:e}", r.all.g1);
        }
        let caps = table_reapplies(
            scheme,
            "catmark_inf_crease0",
            &osd("catmark_inf_crease0"),
            one_cell,
        );
        assert!(caps >= 1, "{scheme}: the table's one-cell fans");
    }
}

/// `scheme`'s surface of `net` at 3 rings with the fill.
fn rings3(scheme: &str, net: &PolyMesh) -> fairsub::host::SurfaceOutput {
    let spec = registry().lookup(scheme).expect("scheme");
    let opts = ComplexOptions {
        rings: 3,
        fill: true,
    };
    fairsub::surface::build(&spec, net, opts, &mut |_| {}).expect("builds")
}
