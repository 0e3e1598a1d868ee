//! Acceptance tests of the bi-2 family (PGS, PolBS, TPS, adjustable TPS, mixed nets): the
//! paper's polynomials, eigenvalues and limit points reproduced from the schemes' own stencils,
//! the reductions to uniform bi-2 refinement at `n = 4`, injective characteristic maps, and
//! continuity of the patch complexes on gallery nets.

use fairsub::PolyMesh;
use fairsub::analysis::{bi2, certify, continuity};
use fairsub::bezier::BezierPatch;
use fairsub::gallery::{self, CnetShape};
use fairsub::geom::{self, Point};
use fairsub::schemes::bi2::pgs::{PgsParams, ds_net};
use fairsub::schemes::bi2::ternary::{TpsParams, regular_patch};
use fairsub::schemes::bi2::{AdjustableTps, Pgs, Tps, polar};
use fairsub::schemes::{self, DooSabin, Scheme};
use fairsub::surface::{self, ComplexOptions, PatchComplex, Provenance};

use fairsub::schemes::bi2::descriptor::Bi2Kind;

const SCHEMES: [Bi2Kind; 4] = [
    Bi2Kind::Pgs,
    Bi2Kind::Polar,
    Bi2Kind::Tps,
    Bi2Kind::TpsAdjustable,
];

#[test]
fn published_numbers_n3_to_12() {
    for scheme in SCHEMES {
        for n in 3..=12 {
            for c in bi2::published(scheme, n).unwrap() {
                let q = &c.quantity;
                if q.contains("printed c_2") {
                    // The printed c_2 = cos(pi / n) does not give the subsubdominant eigenvalue
                    // (it even exceeds the subdominant one); cos(4 pi / n) does (checked below).
                    assert!(c.difference > 1e-2, "{scheme:?} n={n}: {q}");
                } else if q.contains(".082") {
                    // nu_3 = 0.0820418..., printed truncated.
                    assert!(c.difference < 5e-5, "{scheme:?} n={n}: {q}: {}", c.computed);
                } else {
                    assert!(
                        c.difference < 1e-12,
                        "{scheme:?} n={n}: {q}: published {} computed {}",
                        c.published,
                        c.computed
                    );
                }
            }
        }
    }
}

#[test]
fn pgs_subdominant_exceeds_one_half_for_n_above_4() {
    for n in 5..=12 {
        let p = PgsParams::new(n).unwrap();
        assert!(p.lambda > 0.5, "n={n}: {}", p.lambda);
    }
    assert!((PgsParams::new(4).unwrap().lambda - 0.5).abs() < 1e-15);
}

#[test]
fn characteristic_maps_are_injective_n3_to_12() {
    for scheme in SCHEMES {
        for n in 3..=12 {
            let (ring, lambda) = bi2::characteristic_ring(scheme, n).unwrap();
            let c = certify::certify_ring(&ring, lambda);
            assert!(c.injective, "{scheme:?} n={n}: {c:?}");
        }
    }
}

#[test]
fn analysis_is_reachable_through_local_matrix() {
    for scheme in ["pgs", "polar-bi2", "tps", "tps-adjustable"] {
        let lm = fairsub::analysis::local::local_matrix(scheme, 5).unwrap();
        assert!(lm.rotation_defect() < 1e-14, "{scheme}");
        assert!(fairsub::analysis::local::characteristic_ring(scheme, 5).is_ok());
    }
}

fn bi2_mask_close(s: &fairsub::stencil::Stencil, expect: &[(usize, f64)]) {
    let e = s.entries();
    assert_eq!(e.len(), expect.len(), "{e:?}");
    for &(i, w) in expect {
        let got = e
            .iter()
            .find(|x| x.0 as usize == i)
            .map(|x| x.1)
            .unwrap_or(0.0);
        assert!((got - w).abs() < 1e-15, "source {i}: {got} vs {w}");
    }
}

#[test]
fn pgs_reduces_to_bi2_at_n4() {
    let p = PgsParams::new(4).unwrap();
    assert_eq!((p.mu, p.w1, p.w2, p.alpha), (1.0, 0.5, 0.125, 0.5));
    // Rule (4) with p from (1) (mu = 1: the mean of a) is the bi-2 mask 9, 3, 1, 3 / 16, and
    // rule (3) keeps p the mean of the new a.
    let net = ds_net(4, |_, _| 0.0).unwrap();
    let corners: Vec<usize> = net.face(0).iter().map(|&v| v as usize).collect();
    let pbar = fairsub::stencil::Stencil::from_pairs(corners.iter().map(|&v| (v, 0.25)));
    let h0 = net.face_halfedge(0);
    for i in 0..4 {
        let s = Pgs::corner_stencil_with_centre(&net, h0 + i as u32, &pbar);
        bi2_mask_close(
            &s,
            &[
                (corners[i], 9.0 / 16.0),
                (corners[(i + 1) % 4], 3.0 / 16.0),
                (corners[(i + 2) % 4], 1.0 / 16.0),
                (corners[(i + 3) % 4], 3.0 / 16.0),
            ],
        );
    }
    let pn = Pgs::centre_update(&net, 0, &pbar);
    bi2_mask_close(&pn, &corners.iter().map(|&v| (v, 0.25)).collect::<Vec<_>>());
    // On a quad net PGS is Doo-Sabin (uniform bi-2 refinement), stencil for stencil.
    let grid = gallery::open_grid();
    let a = Pgs.refine(&grid).unwrap();
    let b = DooSabin.refine(&grid).unwrap();
    assert_eq!(a.stencils, b.stencils);
}

/// The corner points and centre of a patch, in any order.
fn key_points(p: &BezierPatch) -> Vec<Point> {
    vec![
        p.eval(0.0, 0.0),
        p.eval(1.0, 0.0),
        p.eval(0.0, 1.0),
        p.eval(1.0, 1.0),
        p.eval(0.5, 0.5),
    ]
}

fn same_point_sets(a: &[Point], b: &[Point], tol: f64) -> bool {
    a.iter().all(|p| b.iter().any(|q| geom::dist(*p, *q) < tol))
        && b.iter().all(|p| a.iter().any(|q| geom::dist(*p, *q) < tol))
}

fn patch_of(m: &PolyMesh, c: &[fairsub::stencil::Stencil]) -> BezierPatch {
    BezierPatch::new(2, 2, c.iter().map(|s| s.apply(m.positions())).collect())
}

#[test]
fn tps_reduces_to_ternary_refinement_at_n4() {
    let p = TpsParams::new(4).unwrap();
    assert!((p.alpha1 - 28.0 / 81.0).abs() < 1e-16 && (p.alpha2 - 4.0 / 81.0).abs() < 1e-16);
    // Rule (18) at n = 4 is the ternary vertex mask (1, 7, 1) x (1, 7, 1) / 81.
    assert!((1.0 - p.alpha1 - p.alpha2 - 49.0 / 81.0).abs() < 1e-15);
    // One step on a regular grid: the patch of every interior vertex child is the middle third
    // of its parent's patch, i.e. TPS is ternary bi-2 refinement of the same surface.
    let grid = gallery::open_grid();
    let fine = Tps.refine(&grid).unwrap().mesh;
    let w = fairsub::schemes::bi2::ternary::uniform_widths(&fine);
    let mut checked = 0;
    for v in 0..grid.num_vertices() {
        let (Some(pc), Some(cc)) = (
            fairsub::schemes::doo_sabin::surface::regular_vertex_patch(&grid, v),
            regular_patch(&fine, &w, v),
        ) else {
            continue;
        };
        let parent = patch_of(&grid, &pc);
        let child = patch_of(&fine, &cc);
        let third = parent.subpatch(1.0 / 3.0, 2.0 / 3.0, 1.0 / 3.0, 2.0 / 3.0);
        assert!(
            same_point_sets(&key_points(&child), &key_points(&third), 1e-12),
            "vertex {v}"
        );
        checked += 1;
    }
    assert_eq!(checked, grid.num_vertices());
}

#[test]
fn adjustable_steps_are_exact_knot_insertion() {
    // Two steps with e = 0.2 on a regular grid: the patch of the twice-refined vertex child is
    // the middle piece of the middle piece of its parent's patch.
    let grid = gallery::open_grid();
    let adj = AdjustableTps::new(0.2);
    let (fine, w) = adj.refine_levels_exact(&grid, 2, |_| {}).unwrap();
    let (e, s) = (0.2, 0.6);
    let lo = e + s * e;
    for v in 0..grid.num_vertices() {
        let parent = patch_of(
            &grid,
            &fairsub::schemes::doo_sabin::surface::regular_vertex_patch(&grid, v).unwrap(),
        );
        let child = patch_of(&fine, &regular_patch(&fine, &w, v).unwrap());
        let mid = parent.subpatch(lo, 1.0 - lo, lo, 1.0 - lo);
        assert!(
            same_point_sets(&key_points(&child), &key_points(&mid), 1e-12),
            "vertex {v}"
        );
    }
    // e = 1/3 gives back TPS.
    let a = AdjustableTps::new(1.0 / 3.0);
    let net = gallery::cnet(5, CnetShape::Saddle, 3);
    let x = a.refine(&net).unwrap().mesh;
    let y = Tps.refine(&net).unwrap().mesh;
    for (p, q) in x.positions().iter().zip(y.positions()) {
        assert!(geom::dist(*p, *q) < 1e-13);
    }
}

#[test]
fn pgs_rules_are_stationary() {
    // With alpha from (8), p^new from (3) equals (1) on the refined DS-net (the appendix).
    for n in [3, 5, 6, 7, 10] {
        let net = ds_net(n, |x, y| 0.3 * (x * 1.7).sin() + 0.1 * x * y).unwrap();
        let fine = Pgs.refine(&net).unwrap().mesh;
        let p0 = Pgs::centre_stencil(&net, 0).unwrap();
        let p1 = Pgs::centre_update(&net, 0, &p0).apply(net.positions());
        // The facet's child is face 0 of the refined net (Doo-Sabin layout).
        let q1 = Pgs::centre_stencil(&fine, 0)
            .unwrap()
            .apply(fine.positions());
        assert!(geom::dist(p1, q1) < 1e-13, "n={n}");
    }
}

fn opts(rings: usize) -> ComplexOptions {
    ComplexOptions { rings, fill: true }
}

fn build(scheme: &str, m: &PolyMesh, rings: usize) -> (PatchComplex, Vec<String>) {
    surface::complex_with_notes(scheme, m, opts(rings), Default::default(), |_| {}).unwrap()
}

/// Every join but the fill's spokes is C^1 (up to the per-piece scaling of the rings) and
/// tangent-continuous; the whole complex is C^0.
fn assert_c1(scheme: &str, name: &str, c: &PatchComplex, conformal: bool) {
    let r = continuity::check(c);
    assert!(
        r.all.c0 < 1e-12 * r.size.max(1.0),
        "{scheme} {name}: C0 {}",
        r.all.c0
    );
    let sc = fairsub::analysis::scaled::continuity_up_to_scaling(c);
    for (kind, d) in &sc.by_kind {
        if kind == "cap|cap" {
            continue;
        }
        assert!(
            d.c1_relative < 1e-10 && d.g1 < 1e-10 && d.kappa_min > 0.0,
            "{scheme} {name}: {kind}: {d:?}"
        );
        if conformal {
            let k = &r.by_kind[kind];
            assert!(
                k.c1 < 1e-12 * r.size.max(1.0),
                "{scheme} {name}: {kind}: C1 {}",
                k.c1
            );
        }
    }
}

fn dsnet(n: usize) -> PolyMesh {
    ds_net(n, |x, y| -0.15 * (x * x + y * y)).unwrap()
}

#[test]
fn pgs_and_doo_sabin_complexes_are_c1() {
    for n in [3, 5, 6, 8] {
        for (name, m) in [
            ("cnet-convex", gallery::cnet(n, CnetShape::Convex, 3)),
            ("cnet-saddle", gallery::cnet(n, CnetShape::Saddle, 3)),
            ("ds-net", dsnet(n)),
            ("prism", gallery::prism(n)),
        ] {
            for scheme in ["pgs", "pgs-dscc", "doo-sabin"] {
                let (c, _) = build(scheme, &m, 3);
                assert_c1(scheme, name, &c, true);
            }
        }
    }
    let (c, _) = build("pgs", &gallery::cube(), 3);
    assert_eq!(continuity::check(&c).open_sides, 0);
}

#[test]
fn pgs_and_doo_sabin_are_laid_out_patch_for_patch() {
    let m = dsnet(5);
    let (a, _) = build("pgs", &m, 3);
    let (b, _) = build("doo-sabin", &m, 3);
    assert_eq!(a.provenance, b.provenance);
    // DS^CC has the same layout, so all three compare patch for patch (here and on a prism).
    let (d, _) = build("doo-sabin-cc", &m, 3);
    assert_eq!(a.provenance, d.provenance);
    let p = gallery::prism(6);
    let (x, _) = build("pgs", &p, 3);
    let (y, _) = build("doo-sabin-cc", &p, 3);
    assert_eq!(x.provenance, y.provenance);
    // Regular patches agree; rings differ (the rules differ).
    for (k, p) in a.provenance.iter().enumerate() {
        if matches!(p, Provenance::Regular { .. }) {
            assert_eq!(a.patches[k], b.patches[k]);
        }
    }
}

#[test]
fn tps_complexes_are_c1() {
    for n in [3, 5, 6, 8] {
        for shape in [CnetShape::Convex, CnetShape::Saddle] {
            let m = gallery::cnet(n, shape, 3);
            let (c, _) = build("tps", &m, 3);
            // 2n patches per ring.
            let ring1 = c
                .provenance
                .iter()
                .filter(|p| matches!(p, Provenance::Ring { ring: 1, .. }))
                .count();
            assert_eq!(ring1, 2 * n);
            assert_c1("tps", shape.name(), &c, true);
            let (c, _) = build("tps-adjustable", &m, 3);
            assert_c1("tps-adjustable", shape.name(), &c, false);
        }
    }
    // Extraordinary vertices next to each other: separated by one whole-net step (noted).
    for scheme in ["tps", "tps-adjustable"] {
        let (c, notes) = build(scheme, &gallery::cube(), 2);
        assert_eq!(notes.len(), 1, "{notes:?}");
        assert_eq!(continuity::check(&c).open_sides, 0);
        assert_c1(scheme, "cube", &c, scheme == "tps");
    }
}

#[test]
fn polar_complexes_are_c1() {
    for n in [3, 5, 8, 12] {
        let m = gallery::prism(n);
        let (c, _) = build("polar-bi2", &m, 4);
        assert_eq!(continuity::check(&c).open_sides, 0, "n={n}");
        let sc = fairsub::analysis::scaled::continuity_up_to_scaling(&c);
        // The polar cap is C^1 across its spokes too (a periodic spline circularly).
        assert!(
            sc.all.c1_relative < 1e-10 && sc.all.g1 < 1e-9,
            "n={n}: {sc:?}"
        );
        assert_c1("polar-bi2", "prism", &c, false);
        // Rings of n patches.
        let ring2 = c
            .provenance
            .iter()
            .filter(|p| matches!(p, Provenance::Ring { ring: 2, .. }))
            .count();
        assert_eq!(ring2, 2 * n, "two poles");
    }
}

#[test]
fn mixed_mesh_joins_binary_and_ternary_rings_c1() {
    // Two ternary splits of a pentagonal prism: two pentagon facets with DS-nets (PGS) and ten
    // separated vertices of valence 3 (TPS), the rest regular bi-2: the layout of Fig. 15.
    let m = fairsub::schemes::bi2::mixed::fig15_like_net(5).unwrap();
    assert_eq!(
        m.num_faces(),
        fairsub::schemes::bi2::mixed::ternary_split(
            &fairsub::schemes::bi2::mixed::ternary_split(&gallery::prism(5)).unwrap()
        )
        .unwrap()
        .num_faces()
    );
    let els = fairsub::schemes::bi2::mixed::elements(&m);
    use fairsub::schemes::bi2::mixed::Bi2Element;
    assert_eq!(
        els.iter()
            .filter(|e| matches!(e, Bi2Element::Facet(_)))
            .count(),
        2
    );
    assert_eq!(
        els.iter()
            .filter(|e| matches!(e, Bi2Element::Vertex(_)))
            .count(),
        10
    );
    let (c, _) = build("bi2-mixed", &m, 3);
    assert_eq!(continuity::check(&c).open_sides, 0);
    assert_c1("bi2-mixed", "prism-ternary", &c, true);
    // The net itself cannot be refined as one net.
    let e = schemes::by_name("bi2-mixed")
        .unwrap()
        .refine(&m)
        .unwrap_err()
        .to_string();
    assert!(e.contains("--rings"), "{e}");
    // Poles in a mixed net: the polar layout of a prism.
    let pm = polar::to_polar_layout(&gallery::prism(6), &[])
        .unwrap()
        .mesh;
    let (c, _) = build("bi2-mixed", &pm, 3);
    assert_eq!(continuity::check(&c).open_sides, 0);
    assert_c1("bi2-mixed", "polar-prism", &c, false);
}

#[test]
fn mixed_rings_equal_the_doo_sabin_machinery_rings() {
    for n in [3, 5, 7] {
        let m = dsnet(n);
        let (a, _) = build("pgs", &m, 3);
        let (b, _) = build("bi2-mixed", &m, 3);
        assert_eq!(a.len(), b.len(), "n={n}");
        // The rings and regular patches: PGS closes its holes with the G^1 cap, bi2-mixed keeps
        // the bi-2 centroid fill, so the caps are compared by count only.
        let pts = |c: &PatchComplex| -> Vec<Vec<Point>> {
            c.patches
                .iter()
                .zip(&c.provenance)
                .filter(|(_, p)| !matches!(p, Provenance::Cap { .. }))
                .map(|(q, _)| key_points(q))
                .collect()
        };
        let (pa, pb) = (pts(&a), pts(&b));
        assert_eq!(pa.len(), pb.len(), "n={n}");
        assert!(pa.len() < a.len(), "n={n}: no cap");
        for p in &pa {
            assert!(
                pb.iter().any(|q| same_point_sets(p, q, 1e-12)),
                "n={n}: a patch of the pgs complex is missing from the mixed one"
            );
        }
    }
}

#[test]
fn fills_meet_at_the_limit_points() {
    // The fill's centre coefficient is the element's limit point, which the scheme's limit
    // stencils give on the input net.
    let cases: Vec<(&str, PolyMesh, usize)> = vec![
        ("pgs", gallery::cnet(5, CnetShape::Convex, 3), 0),
        ("tps", gallery::cnet(5, CnetShape::Convex, 3), 0),
        ("tps", gallery::cnet(3, CnetShape::Saddle, 3), 0),
    ];
    for (scheme, m, v) in cases {
        let s = schemes::by_name(scheme).unwrap();
        let lim = s.limit_stencils(&m).unwrap().apply(m.positions())[v];
        let (c, _) = build(scheme, &m, 2);
        let caps: Vec<&BezierPatch> = c
            .patches
            .iter()
            .zip(&c.provenance)
            .filter(|(_, p)| matches!(p, Provenance::Cap { .. }))
            .map(|x| x.0)
            .collect();
        assert!(!caps.is_empty());
        for cap in caps {
            let corners = [cap.cp(0, 0), cap.cp(2, 0), cap.cp(0, 2), cap.cp(2, 2)];
            assert!(
                corners.iter().any(|q| geom::dist(*q, lim) < 1e-12),
                "{scheme}: {corners:?} vs {lim:?}"
            );
        }
    }
    // Polar: the pole's limit (16).
    let pm = polar::to_polar_layout(&gallery::prism(5), &[])
        .unwrap()
        .mesh;
    let pole = polar::find_poles(&pm)[0] as usize;
    let lim = fairsub::schemes::bi2::PolarBi2::default()
        .limit_stencils(&pm)
        .unwrap()
        .apply(pm.positions())[pole];
    let (c, _) = build("polar-bi2", &pm, 2);
    let hit = c
        .patches
        .iter()
        .zip(&c.provenance)
        .filter(|(_, p)| matches!(p, Provenance::Cap { .. }))
        .any(|(p, _)| geom::dist(p.cp(0, 0), lim) < 1e-12);
    assert!(hit);
}

#[test]
fn refined_nets_through_the_registry() {
    let cnet = gallery::cnet(5, CnetShape::Convex, 3);
    for (scheme, m) in [
        ("pgs", gallery::prism(5)),
        ("pgs", gallery::cube()),
        ("tps", cnet.clone()),
        ("tps-adjustable", cnet.clone()),
        ("polar-bi2", gallery::prism(7)),
        ("bi2-mixed", dsnet(5)),
        ("bi2-mixed", cnet.clone()),
    ] {
        let s = schemes::by_name(scheme).unwrap();
        let r = schemes::refine_levels(s.as_ref(), &m, 2, |_| {}).unwrap();
        assert!(r.num_vertices() > m.num_vertices(), "{scheme}");
    }
    // A ternary step splits every quad into 9 and grows a strip of 3 quads along every
    // boundary edge and a quad at every corner.
    let t = Tps.refine(&cnet).unwrap().mesh;
    let b = cnet.boundary_loops()[0].len();
    let corners = (0..cnet.num_vertices())
        .filter(|&v| cnet.is_boundary_vertex(v) && cnet.vertex_faces(v).len() == 1)
        .count();
    assert_eq!(t.num_faces(), 9 * cnet.num_faces() + 3 * b + corners);
    assert_eq!(t.boundary_loops().len(), 1);
    // The radial step keeps the poles' valence (the circular direction is not refined).
    let pm = polar::to_polar_layout(&gallery::prism(7), &[])
        .unwrap()
        .mesh;
    let r = polar::radial_step(&pm).unwrap().mesh;
    assert_eq!(polar::find_poles(&r).len(), 2);
    // Radial refinement only: every pole keeps valence 7.
    for p in polar::find_poles(&r) {
        assert_eq!(r.valence(p as usize), 7);
    }
}

#[test]
fn errors_name_the_element_and_the_way_out() {
    let e = Tps.refine(&gallery::prism(5)).unwrap_err().to_string();
    assert!(e.contains("face 0") && e.contains("catmull-clark"), "{e}");
    // polar-bi2 on a net with an extraordinary vertex among quads: TPS rings there, noted.
    let (_, notes) = build("polar-bi2", &gallery::cnet(5, CnetShape::Convex, 3), 2);
    assert!(
        notes[0].contains("vertex 0") && notes[0].contains("bi2-mixed"),
        "{notes:?}"
    );
    // A DS-net's facet is not a prism-like cap: PGS there.
    let (_, notes) = build("polar-bi2", &dsnet(5), 2);
    assert!(notes[0].contains("face 0"), "{notes:?}");
    // A net mixing binary facets and ternary vertices has no refined net.
    let mixed = fairsub::schemes::bi2::mixed::fig15_like_net(5).unwrap();
    let e = schemes::by_name("polar-bi2")
        .unwrap()
        .refine(&mixed)
        .unwrap_err()
        .to_string();
    assert!(e.contains("--rings"), "{e}");
    assert!(PgsParams::new(2).is_err() && TpsParams::new(2).is_err());
    assert!(bi2::local_matrix(Bi2Kind::Tps, 2).is_err());
    let e = AdjustableTps::new(0.6)
        .refine(&gallery::cnet(5, CnetShape::Convex, 2))
        .unwrap_err()
        .to_string();
    assert!(e.contains("(0, 1/2)"), "{e}");
}

#[test]
fn adjustable_tps_for_other_split_ratios() {
    for e in [0.15, 0.25, 0.3] {
        for n in 3..=12 {
            for c in bi2::published_with(Bi2Kind::TpsAdjustable, n, e).unwrap() {
                assert!(
                    c.difference < 1e-12,
                    "e={e} n={n}: {}: {} vs {}",
                    c.quantity,
                    c.published,
                    c.computed
                );
            }
            let (ring, lambda) =
                bi2::characteristic_ring_with(Bi2Kind::TpsAdjustable, n, e).unwrap();
            assert!(
                certify::certify_ring(&ring, lambda).injective,
                "e={e} n={n}"
            );
        }
    }
}

#[test]
fn pgs_dscc_preprocesses_twice() {
    let m = gallery::prism(5);
    let s = schemes::by_name("pgs-dscc").unwrap();
    let a = schemes::refine_levels(s.as_ref(), &m, 3, |_| {}).unwrap();
    let b = fairsub::schemes::bi2::Pgs::refine_levels_with(
        &m,
        3,
        fairsub::schemes::bi2::PgsOptions { dscc_steps: 2 },
    )
    .unwrap();
    assert_eq!(a.positions(), b.positions());
    let c = fairsub::schemes::DooSabinCc.refine(&m).unwrap().mesh;
    let c = fairsub::schemes::DooSabinCc.refine(&c).unwrap().mesh;
    let c = Pgs.refine(&c).unwrap().mesh;
    assert_eq!(a.positions(), c.positions());
}

#[test]
fn regular_spectrum_alphas_give_lambda_squared_and_fourth() {
    use fairsub::schemes::bi2::AlphaRule;
    use fairsub::schemes::bi2::ternary::{TernaryRules, adjustable_lambda};
    // fairsub's alternative rule for adjustable TPS: the stationary frequency-0 block has the
    // eigenvalues 1, lambda^2, lambda^4 (trace and determinant), unlike the paper's rule.
    for n in 3..=12 {
        let rules = TernaryRules::adjustable_with(0.2, AlphaRule::RegularSpectrum).unwrap();
        let (a1, a2, fallback) = rules.stationary_alphas(n).unwrap();
        assert!(!fallback, "n={n}");
        let m = rules.frequency0_block(rules.ring_ratio(), a1, a2);
        let tr = m[0][0] + m[1][1] + m[2][2];
        let det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
        let l = adjustable_lambda(0.2, (2.0 * std::f64::consts::PI / n as f64).cos());
        assert!(
            (tr - (1.0 + l * l + l.powi(4))).abs() < 1e-12,
            "n={n}: {tr}"
        );
        assert!((det - l.powi(6)).abs() < 1e-12, "n={n}: {det}");
        // The paper's rule (TPS's limit point) differs except where it falls back (n = 3).
        let (b1, _, fb) = TernaryRules::adjustable(0.2)
            .unwrap()
            .stationary_alphas(n)
            .unwrap();
        assert_eq!(fb, n == 3, "n={n}");
        assert!(fb || (a1 - b1).abs() > 1e-6, "n={n}: {a1} {b1}");
        // (22) and the limit point from an input net are unchanged; the map stays injective.
        for c in bi2::published_rules(Bi2Kind::TpsAdjustable, n, rules).unwrap() {
            assert!(c.difference < 1e-12, "n={n}: {}", c.quantity);
        }
        let (ring, lambda) =
            bi2::characteristic_ring_rules(Bi2Kind::TpsAdjustable, n, rules).unwrap();
        assert!(certify::certify_ring(&ring, lambda).injective, "n={n}");
    }
}

fn fairsub_cli(args: &[&str]) -> (bool, String, String) {
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_fairsub"))
        .args(args)
        .output()
        .unwrap();
    (
        o.status.success(),
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

#[test]
fn cli_subdivide_every_bi2_scheme_nets_and_patches() {
    let dir = std::env::temp_dir().join(format!("fairsub-bi2-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = |name: &str| dir.join(name).to_string_lossy().into_owned();
    let cases = [
        ("pgs", "gallery:prism-5"),
        ("pgs-dscc", "gallery:prism-5"),
        ("polar-bi2", "gallery:prism-5"),
        ("tps", "gallery:cnet-5-saddle"),
        ("tps-adjustable", "gallery:cnet-5-saddle"),
        ("bi2-mixed", "gallery:cnet-5-saddle"),
        ("doo-sabin", "gallery:prism-5"),
        ("doo-sabin-cc", "gallery:prism-5"),
    ];
    for (scheme, net) in cases {
        let obj = out(&format!("{scheme}.obj"));
        let (ok, _, err) = fairsub_cli(&[
            "subdivide",
            net,
            "--scheme",
            scheme,
            "--levels",
            "2",
            "-o",
            &obj,
        ]);
        assert!(ok, "{scheme} --levels: {err}");
        let refined = fairsub::io::read_mesh(std::path::Path::new(&obj))
            .unwrap()
            .mesh;
        assert!(refined.num_faces() > 50, "{scheme}");
        for (ext, fill) in [("bv", true), ("igs", true), ("bv", false)] {
            let file = out(&format!("{scheme}-{fill}.{ext}"));
            let mut args = vec![
                "subdivide",
                net,
                "--scheme",
                scheme,
                "--rings",
                "3",
                "-o",
                &file,
            ];
            if !fill {
                args.push("--no-fill");
            }
            let (ok, _, err) = fairsub_cli(&args);
            assert!(ok, "{scheme} --rings .{ext}: {err}");
            assert!(
                std::fs::metadata(&file).unwrap().len() > 1000,
                "{scheme} .{ext}"
            );
        }
        // The filled surface is closed around the centre; without the fill it is not.
        let filled = fairsub::io::read_bv(std::path::Path::new(&out(&format!("{scheme}-true.bv"))))
            .unwrap()
            .patches;
        let open = fairsub::io::read_bv(std::path::Path::new(&out(&format!("{scheme}-false.bv"))))
            .unwrap()
            .patches;
        assert!(filled.len() > open.len(), "{scheme}");
    }
    // Options of the adjustable and polar schemes.
    let f = out("adj.bv");
    let (ok, _, err) = fairsub_cli(&[
        "subdivide",
        "gallery:cnet-6-convex",
        "--scheme",
        "tps-adjustable",
        "--split-ratio",
        "0.25",
        "--rings",
        "3",
        "-o",
        &f,
    ]);
    assert!(ok, "{err}");
    let f = out("pole.bv");
    let (ok, _, err) = fairsub_cli(&[
        "subdivide",
        "gallery:prism-5",
        "--scheme",
        "polar-bi2",
        "--pole",
        "1:0,0,1.5",
        "--rings",
        "3",
        "-o",
        &f,
    ]);
    assert!(ok, "{err}");
    let (ok, _, err) = fairsub_cli(&[
        "subdivide",
        "gallery:prism-5",
        "--scheme",
        "pgs",
        "--split-ratio",
        "0.25",
        "--rings",
        "3",
        "-o",
        &f,
    ]);
    assert!(!ok && err.contains("apply to tps-adjustable"), "{err}");
    let (ok, _, err) = fairsub_cli(&[
        "subdivide",
        "gallery:prism-5",
        "--scheme",
        "polar-bi2",
        "--pole",
        "1:0,0",
        "--rings",
        "3",
        "-o",
        &f,
    ]);
    assert!(!ok && err.contains("FACE:X,Y,Z"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn cli_analyze_prints_the_published_numbers() {
    for (scheme, formula) in [
        ("pgs", "(5), (6)"),
        ("polar-bi2", "(13), (14)"),
        ("tps", "(19), (20)"),
        ("tps-adjustable", "(22)"),
    ] {
        let (ok, out, err) =
            fairsub_cli(&["analyze", "--scheme", scheme, "--valence", "7", "--json"]);
        assert!(ok, "{scheme}: {err}");
        let v: serde_json::Value = serde_json::from_str(&out).unwrap();
        let published = v["published"].as_array().unwrap();
        assert!(published.len() >= 4, "{scheme}");
        assert!(
            published
                .iter()
                .any(|p| p["quantity"].as_str().unwrap().contains(formula)),
            "{scheme}: {published:?}"
        );
        assert_eq!(v["characteristic_map"]["injective"], true, "{scheme}");
    }
    let (ok, out, _) = fairsub_cli(&[
        "analyze",
        "--scheme",
        "tps-adjustable",
        "--valence",
        "5",
        "--split-ratio",
        "0.3",
    ]);
    assert!(ok);
    assert!(out.contains("(22), e = 0.3"), "{out}");
    // fairsub's alternative alphas: frequency 0 at lambda^2, so mu / lambda^2 drops (n = 5:
    // from 1.389 to 1.085, the largest eigenvalue below lambda now of frequency 2).
    let ratio = |rule: &str| -> f64 {
        let (ok, out, err) = fairsub_cli(&[
            "analyze",
            "--scheme",
            "tps-adjustable",
            "--valence",
            "5",
            "--alpha-rule",
            rule,
            "--json",
        ]);
        assert!(ok, "{err}");
        let v: serde_json::Value = serde_json::from_str(&out).unwrap();
        v["spectrum"]["mu_over_lambda_squared"].as_f64().unwrap()
    };
    assert!((ratio("tps-limit-point") - 1.389171).abs() < 1e-6);
    assert!((ratio("regular-spectrum") - 1.085183).abs() < 1e-6);
    let (ok, _, err) = fairsub_cli(&[
        "analyze",
        "--scheme",
        "tps",
        "--valence",
        "5",
        "--alpha-rule",
        "regular-spectrum",
    ]);
    assert!(!ok && err.contains("apply to tps-adjustable"), "{err}");
}

#[test]
fn cli_check_certifies_c1_up_to_scaling() {
    for (net, scheme) in [
        ("gallery:prism-5", "polar-bi2"),
        ("gallery:cnet-6-saddle", "tps-adjustable"),
        ("gallery:prism-6", "pgs"),
    ] {
        let (ok, out, err) =
            fairsub_cli(&["check", net, "--scheme", scheme, "--rings", "3", "--json"]);
        assert!(ok, "{scheme}: {err}");
        let v: serde_json::Value = serde_json::from_str(&out).unwrap();
        let kinds = v["c1_up_to_scaling"]["by_kind"].as_object().unwrap();
        assert!(kinds.len() >= 5, "{scheme}");
        for (kind, d) in kinds {
            if kind == "cap|cap" {
                continue; // the fill's spokes: C^0 by design
            }
            assert!(
                d["c1_relative"].as_f64().unwrap() < 1e-10
                    && d["kappa_min"].as_f64().unwrap() > 0.0,
                "{scheme} {kind}: {d}"
            );
        }
    }
}

#[test]
fn gallery_surfaces_are_c1_under_every_bi2_scheme() {
    // Every gallery net each scheme takes: C^0 everywhere, C^1 (up to per-piece scaling)
    // across every patch and ring boundary; only the fill's spokes (cap|cap) are C^0.
    let mut built = 0;
    for (name, m) in gallery::all() {
        if name.starts_with("cnet-") && !name.contains("-saddle") {
            continue; // the saddles stand for the c-nets (convex ones are tested above)
        }
        for scheme in [
            "pgs",
            "pgs-dscc",
            "polar-bi2",
            "tps",
            "tps-adjustable",
            "bi2-mixed",
            "doo-sabin",
            "doo-sabin-cc",
        ] {
            let Ok((c, _)) =
                surface::complex_with_notes(scheme, &m, opts(2), Default::default(), |_| {})
            else {
                continue;
            };
            built += 1;
            let r = continuity::check(&c);
            assert!(
                r.all.c0 < 1e-12 * r.size.max(1.0),
                "{scheme} {name}: C0 {}",
                r.all.c0
            );
            for (kind, d) in fairsub::analysis::scaled::continuity_up_to_scaling(&c).by_kind {
                if kind == "cap|cap" {
                    continue;
                }
                assert!(
                    d.c1_relative < 1e-9 && d.g1 < 1e-9 && d.kappa_min > 0.0,
                    "{scheme} {name}: {kind}: {d:?}"
                );
            }
        }
    }
    eprintln!("{built} gallery surfaces certified");
    assert!(built >= 60, "{built}");
}
