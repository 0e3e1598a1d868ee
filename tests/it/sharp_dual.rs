//! Sharp features in the dual (bi-2) schemes' patch output (`schemes::doo_sabin::sharp`): the net
//! is cut along its infinitely sharp creases and the crease ends and junctions are kept as
//! corners, so both sides of a crease end on the quadratic B-spline of the crease polygon and the
//! surface stays closed (no open side, C^0 everywhere); what the construction cannot take is
//! refused with the element named.

use fairsub::analysis::continuity;
use fairsub::bezier::Side;
use fairsub::geom::{Point, dist};
use fairsub::host::ComplexOptions;
use fairsub::mesh::{Extras, PolyMesh, SharpEdges};
use fairsub::schemes::registry::registry;

/// The gallery cube refined once by Catmull-Clark (24 quads, eight valence-3 vertices), with two
/// infinitely sharp crease loops: the equator `z = 0` and the meridian `y = 0`. They cross at the
/// two face points of the `x = +-1` faces (junctions of four sharp edges) and pass through
/// regular vertices only.
fn creased_cube() -> PolyMesh {
    creased_cube_with(true)
}

/// The cube of [`creased_cube`] with the equator crease, and the meridian one when `meridian`.
fn creased_cube_with(meridian: bool) -> PolyMesh {
    let cube = fairsub::gallery::all()
        .into_iter()
        .find(|(n, _)| n == "cube")
        .expect("gallery cube")
        .1;
    let cc = fairsub::schemes::by_name("catmull-clark").expect("catmull-clark");
    let m = fairsub::schemes::refine_levels(cc.as_ref(), &cube, 1, |_| {}).expect("refine");
    let p = m.positions();
    let on = |v: usize, k: usize| p[v][k].abs() < 1e-12;
    let mut sharp = Vec::new();
    for e in 0..m.num_edges() {
        let h = m.edge_halfedge(e);
        let (a, b) = (m.he_from(h) as usize, m.he_to(h) as usize);
        if (on(a, 2) && on(b, 2)) || (meridian && on(a, 1) && on(b, 1)) {
            sharp.push((e as u32, 10.0f32));
        }
    }
    assert_eq!(
        sharp.len(),
        if meridian { 16 } else { 8 },
        "loops of eight edges"
    );
    m.with_extras(Some(Extras {
        sharp_edges: SharpEdges::ById(sharp),
        ..Extras::default()
    }))
}

fn build(scheme: &str, mesh: &PolyMesh) -> fairsub::error::Result<fairsub::host::SurfaceOutput> {
    let spec = registry().lookup(scheme)?;
    let opts = ComplexOptions {
        rings: 3,
        fill: true,
    };
    fairsub::surface::build(&spec, mesh, opts, &mut |_| {})
}

/// The midpoints of every patch side, and the patch corners.
fn side_points(c: &fairsub::bezier::complex::PatchComplex) -> (Vec<Point>, Vec<Point>) {
    let (mut mids, mut corners) = (Vec::new(), Vec::new());
    for p in &c.patches {
        for side in [Side::U0, Side::U1, Side::V0, Side::V1] {
            let [u, v] = side.domain_point(0.5);
            mids.push(p.eval(u, v));
            let [u, v] = side.domain_point(0.0);
            corners.push(p.eval(u, v));
        }
    }
    (mids, corners)
}

fn count_near(pts: &[Point], q: Point) -> usize {
    pts.iter().filter(|&&p| dist(p, q) < 1e-12).count()
}

#[test]
fn creases_close_on_the_crease_polygons_b_spline() {
    let net = creased_cube();
    let p = net.positions().to_vec();
    for scheme in ["doo-sabin", "doo-sabin-cc", "pgs"] {
        let out = build(scheme, &net).unwrap_or_else(|e| panic!("{scheme}: {e}"));
        assert!(
            out.notes.iter().any(|n| n.contains("cut along its 16")),
            "{scheme}: the cut is noted: {:?}",
            out.notes
        );
        let c = &out.complex;
        let report = continuity::check(c);
        assert_eq!(report.open_sides, 0, "{scheme}: the surface is closed");
        assert!(
            report.all.c0 < 1e-12 && report.sharp.c0 < 1e-12,
            "{scheme}: C0 gap {} at a join, {} on a crease",
            report.all.c0,
            report.sharp.c0
        );
        // The crease sides are marked: `check` reports the creases apart as sharp joins (the
        // two sides of a crease meet at an angle: 0.79 rad at the largest), and every other
        // join is G^1 (unmarked, the crease joins made the smooth kinds' largest angle that).
        eprintln!(
            "{scheme}: sharp pieces {} (g1 {:.3}), smooth pieces {} (g1 {:.3e})",
            report.sharp.pieces, report.sharp.g1, report.all.pieces, report.all.g1
        );
        assert!(report.sharp.pieces > 0, "{scheme}: crease joins reported");
        assert!(
            report.sharp.g1 > 0.5,
            "{scheme}: the crease joins are not smooth: {}",
            report.sharp.g1
        );
        assert!(
            report.all.g1 < 1e-8,
            "{scheme}: smooth joins G^1, largest {} rad",
            report.all.g1
        );
        let (mids, corners) = side_points(c);
        // Every crease vertex of valence 2 in its loop: the crease curve passes through
        // (u + 6 v + w) / 8, on both sides (the midpoint of a regular boundary patch's side).
        let mut checked = 0;
        for v in 0..net.num_vertices() {
            let crease_nbrs: Vec<usize> = net
                .outgoing_halfedges(v)
                .into_iter()
                .map(|h| net.he_to(h) as usize)
                .filter(|&w| {
                    let same = |k: usize| p[v][k].abs() < 1e-12 && p[w][k].abs() < 1e-12;
                    same(1) || same(2)
                })
                .collect();
            match crease_nbrs.len() {
                2 => {
                    let (u, w) = (p[crease_nbrs[0]], p[crease_nbrs[1]]);
                    let q: Point = std::array::from_fn(|k| (u[k] + 6.0 * p[v][k] + w[k]) / 8.0);
                    assert!(
                        count_near(&mids, q) >= 2,
                        "{scheme}: crease point of vertex {v} on both sides"
                    );
                    checked += 1;
                }
                4 => {
                    // A junction: each of its four quadrants' corner patches interpolates it.
                    assert!(
                        count_near(&corners, p[v]) >= 4,
                        "{scheme}: junction {v} kept by its four quadrants"
                    );
                    checked += 1;
                }
                _ => {}
            }
        }
        assert_eq!(checked, 14, "{scheme}: 12 crease vertices and 2 junctions");
    }
}

#[test]
fn what_a_cut_cannot_take_is_refused_by_name() {
    let base = creased_cube();
    let with = |f: &dyn Fn(&mut Extras)| {
        let mut ex = base.extras().cloned().unwrap();
        f(&mut ex);
        base.clone().with_extras(Some(ex))
    };
    // A semi-sharp crease loop: the dual hosts refine it until spent (fairsub's crease
    // construction); the element-ring schemes spend it by whole-net dual steps first
    // (tests/it/semisharp_rings.rs) and, with --prepare none, name it; one semi-sharp edge
    // in an infinitely sharp loop leaves two infinitely sharp darts, refused.
    let equator = creased_cube_with(false);
    let mut ex = equator.extras().cloned().unwrap();
    if let SharpEdges::ById(v) = &mut ex.sharp_edges {
        v.iter_mut().for_each(|p| p.1 = 2.5);
    }
    let semi = equator.with_extras(Some(ex));
    assert!(build("doo-sabin", &semi).is_ok());
    assert!(build("bi2-mixed", &semi).is_ok());
    let mut strict = registry().lookup("bi2-mixed").expect("scheme");
    strict.params.prepare = fairsub::schemes::options::PrepareMode::None;
    let opts = ComplexOptions {
        rings: 3,
        fill: true,
    };
    let e = fairsub::surface::build(&strict, &semi, opts, &mut |_| {})
        .unwrap_err()
        .to_string();
    assert!(e.contains("semi-sharp crease value 2.5"), "{e}");
    let one = with(&|ex| {
        if let SharpEdges::ById(v) = &mut ex.sharp_edges {
            v[0].1 = 2.5;
        }
    });
    let e = build("doo-sabin", &one).unwrap_err().to_string();
    assert!(e.contains("is a dart of an infinitely sharp crease"), "{e}");
    // A dart: only the first edge of the list sharp.
    let dart = with(&|ex| {
        if let SharpEdges::ById(v) = &mut ex.sharp_edges {
            v.truncate(3);
        }
    });
    let e = build("pgs", &dart).unwrap_err().to_string();
    assert!(e.contains("is a dart"), "{e}");
    // A corner tag inside the surface, off the creases: vertex 0 is a cube corner.
    let corner = with(&|ex| ex.sharp_vertices = vec![(0, 10.0)]);
    let e = build("doo-sabin", &corner).unwrap_err().to_string();
    assert!(e.contains("vertex 0 is tagged as a corner"), "{e}");
}

/// An open 8 x 8 grid (a wavy height field) with a crease across it along row 4 and a crease
/// from the middle of that row to the far boundary: a junction of three sharp edges whose lower
/// side has two faces, and three crease ends on the boundary.
fn creased_grid() -> PolyMesh {
    let n = 8usize;
    let id = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    let mut pos = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (i as f64 / n as f64, j as f64 / n as f64);
            pos.push([
                x,
                y,
                0.3 * (3.0 * x).sin() * (2.0 * y).cos() + 0.2 * (y - 0.5).abs(),
            ]);
        }
    }
    let mut corners = Vec::new();
    for j in 0..n {
        for i in 0..n {
            corners.extend_from_slice(&[id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    let face_start = (0..=(n * n) as u32).map(|f| 4 * f).collect();
    let m = PolyMesh::from_flat(pos, face_start, corners).expect("grid");
    let mut sharp: Vec<(u32, f32)> = (0..n)
        .map(|i| (id(i, 4), id(i + 1, 4)))
        .chain((4..n).map(|j| (id(4, j), id(4, j + 1))))
        .map(|(a, b)| (m.find_edge(a, b).expect("edge"), 10.0))
        .collect();
    sharp.sort_by_key(|p| p.0);
    m.with_extras(Some(Extras {
        sharp_edges: SharpEdges::ById(sharp),
        ..Extras::default()
    }))
}

#[test]
fn a_junction_with_two_faces_on_one_side_is_kept() {
    let net = creased_grid();
    let mut plain = net.clone();
    plain.set_extras(None);
    let junction = net.positions()[4 * 9 + 4];
    for scheme in ["doo-sabin", "doo-sabin-cc", "pgs"] {
        let open_plain = continuity::check(&build(scheme, &plain).unwrap().complex).open_sides;
        let c = build(scheme, &net).unwrap().complex;
        let report = continuity::check(&c);
        // The grid's boundary, split once more at each of the three crease ends on it; the
        // creases themselves are shared (without the kept junction the sides part: 43).
        assert_eq!(report.open_sides, open_plain + 3, "{scheme}: no crack");
        assert!(report.all.c0 < 1e-12, "{scheme}: C0 {}", report.all.c0);
        let (_, corners) = side_points(&c);
        assert!(
            count_near(&corners, junction) >= 3,
            "{scheme}: the junction is interpolated on its three sides"
        );
    }
    // TPS and polar bi-2 keep corners of one face only: the preparation cuts the net and
    // takes a dual step first (tests/it/prepare_tagged.rs), which makes the junction's copies
    // corners of one face; without it they refuse the junction by name
    for scheme in ["tps", "polar-bi2"] {
        let out = build(scheme, &net).unwrap_or_else(|e| panic!("{scheme}: {e}"));
        let all = out.notes.join(" | ");
        assert!(all.contains("cut along its creases"), "{scheme}: {all}");
        let report = continuity::check(&out.complex);
        assert!(report.all.c0 < 1e-12, "{scheme}: C0 {}", report.all.c0);
        assert!(report.sharp.pieces > 0, "{scheme}: the creases");
        let mut spec = registry().lookup(scheme).expect("scheme");
        spec.params.prepare = fairsub::schemes::prepare::Mode::None;
        let opts = ComplexOptions {
            rings: 3,
            fill: true,
        };
        let e = fairsub::surface::build(&spec, &net, opts, &mut |_| {})
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("vertex 40") && e.contains("2 faces on one side"),
            "{e}"
        );
    }
}

/// The bi-2 schemes on their own ring hosts (TPS, adjustable TPS, polar, mixed) mark the crease
/// sides too: on the cube with the equator crease (no junction, which their boundary rules could
/// not keep), `check` reports the crease apart and every other join is G^1.
#[test]
fn ring_hosts_report_creases_as_sharp_joins() {
    let net = creased_cube_with(false);
    for scheme in ["doo-sabin", "pgs", "tps", "tps-adjustable", "bi2-mixed"] {
        let out = build(scheme, &net).unwrap_or_else(|e| panic!("{scheme}: {e}"));
        let report = continuity::check(&out.complex);
        eprintln!(
            "{scheme}: open {}, sharp pieces {} (g1 {:.3}, c0 {:.1e}), smooth {} (g1 {:.3e})",
            report.open_sides,
            report.sharp.pieces,
            report.sharp.g1,
            report.sharp.c0,
            report.all.pieces,
            report.all.g1
        );
        assert_eq!(report.open_sides, 0, "{scheme}: closed");
        assert!(report.sharp.pieces > 0, "{scheme}: crease joins reported");
        assert!(report.sharp.c0 < 1e-12, "{scheme}: no crack on the crease");
        assert!(report.sharp.g1 > 0.5, "{scheme}: {}", report.sharp.g1);
        assert!(report.all.g1 < 1e-8, "{scheme}: {}", report.all.g1);
    }
}

/// An open 8 x 8 grid with an L-shaped crease: along row 4 from the left boundary to the middle
/// vertex 40, then up column 4 to the top boundary. At vertex 40 the crease turns around the one
/// face 35 (its north-west face): the cut gives that sector a copy of 40 with a single face, which
/// must follow the crease polygon like the other side's copy (three faces), not stay put.
fn l_creased_grid() -> PolyMesh {
    let mut m = creased_grid();
    let n = 8usize;
    let id = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    let mut sharp: Vec<(u32, f32)> = (0..4)
        .map(|i| (id(i, 4), id(i + 1, 4)))
        .chain((4..n).map(|j| (id(4, j), id(4, j + 1))))
        .map(|(a, b)| (m.find_edge(a, b).expect("edge"), 10.0))
        .collect();
    sharp.sort_by_key(|p| p.0);
    m.set_extras(Some(Extras {
        sharp_edges: SharpEdges::ById(sharp),
        ..Extras::default()
    }));
    m
}

#[test]
fn a_crease_turning_around_one_face_stays_closed() {
    let net = l_creased_grid();
    let mut plain = net.clone();
    plain.set_extras(None);
    for scheme in ["doo-sabin", "doo-sabin-cc", "pgs"] {
        let open_plain = continuity::check(&build(scheme, &plain).unwrap().complex).open_sides;
        let c = build(scheme, &net).unwrap().complex;
        let report = continuity::check(&c);
        eprintln!(
            "{scheme}: open {} (plain {open_plain}), c0 {:.2e}, sharp c0 {:.2e}",
            report.open_sides, report.all.c0, report.sharp.c0
        );
        // The grid's boundary split once more at each of the two crease ends on it.
        assert_eq!(report.open_sides, open_plain + 2, "{scheme}: no crack");
        assert!(report.all.c0 < 1e-12 && report.sharp.c0 < 1e-12, "{scheme}");
    }
}

/// A bent L-shaped 4 x 4 grid without its 2 x 2 corner block: the concave corner (vertex 12) is
/// a boundary vertex of three quads, and two crease chains of sharpness 7 run into it from the
/// boundary, so OpenSubdiv's corner rule keeps it while the creases last.
fn l_grid_with_semi_sharp_corner() -> PolyMesh {
    let mut index = std::collections::HashMap::new();
    let mut pos = Vec::new();
    for j in 0..=4i32 {
        for i in 0..=4i32 {
            if i > 2 && j > 2 {
                continue;
            }
            index.insert((i, j), pos.len());
            let (x, y) = (f64::from(i), f64::from(j));
            pos.push([
                x + 0.1 * (1.3 * y).sin(),
                y + 0.1 * (0.7 * x).cos(),
                0.3 * (0.9 * x + 0.4 * y).sin() + 0.15 * x * y / 4.0,
            ]);
        }
    }
    let mut faces = Vec::new();
    for j in 0..4 {
        for i in 0..4 {
            if i >= 2 && j >= 2 {
                continue;
            }
            faces.push(vec![
                index[&(i, j)],
                index[&(i + 1, j)],
                index[&(i + 1, j + 1)],
                index[&(i, j + 1)],
            ]);
        }
    }
    let m = PolyMesh::new(pos, &faces).expect("the L grid");
    assert_eq!(index[&(2, 2)], 12);
    let chains = [
        [(2, 0), (2, 1)],
        [(2, 1), (2, 2)],
        [(0, 2), (1, 2)],
        [(1, 2), (2, 2)],
    ];
    let sharp = chains
        .iter()
        .map(|[a, b]| {
            let e = m
                .find_edge(index[a] as u32, index[b] as u32)
                .expect("an edge");
            (e, 7.0)
        })
        .collect();
    m.with_extras(Some(Extras {
        sharp_edges: SharpEdges::ById(sharp),
        ..Extras::default()
    }))
}

/// Measured 2026-12-07 on main: where semi-sharp creases meet at a boundary vertex with more
/// than two faces (OpenSubdiv's `catmark_helmet`, sharpness 7), its hole had no cap data at
/// the level after the creases were spent and took the centroid fill: 2.4e-2 rad across its
/// spokes here, 0.30 rad on the helmet, under Doo-Sabin, DS^CC, PGS and the schemes built on
/// PGS. Holes are now given the extra levels while creases refine (`g1::no_cap_yet`), and the
/// next level caps it G^1.
#[test]
fn a_boundary_vertex_where_semi_sharp_creases_meet_gets_its_g1_cap() {
    let net = l_grid_with_semi_sharp_corner();
    for scheme in ["doo-sabin", "doo-sabin-cc", "pgs", "bi2-mixed"] {
        let out = build(scheme, &net).unwrap_or_else(|e| panic!("{scheme}: {e}"));
        let r = continuity::check(&out.complex);
        let caps = r
            .by_kind
            .iter()
            .filter(|(k, _)| k.as_str() == "cap|cap")
            .map(|(_, d)| d.pieces)
            .sum::<usize>();
        eprintln!(
            "{scheme}: {} patches, G1 {:.1e}, {caps} cap joins",
            out.complex.len(),
            r.all.g1
        );
        assert!(r.all.c0 < 1e-12, "{scheme}: C0 {:e}", r.all.c0);
        assert!(r.all.g1 < 1e-8, "{scheme}: G1 {:e}", r.all.g1);
        assert!(caps > 0, "{scheme}: the corner's cap");
    }
}
