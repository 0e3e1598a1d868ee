//! Semi-sharp creases under the bi-2 schemes with element rings (TPS, adjustable TPS, the mixed
//! and polar nets): fairsub's construction spends them by the family's dual step with the dual
//! crease rules, near the features only (`schemes::bi2::surface`: Doo-Sabin's construction
//! beside TPS's elements clear of the features for TPS; PGS's construction for the mixed and
//! polar nets, whose spent net is a PGS net; `docs/guide/src/creases.md`). Closed creased nets
//! give closed G^1 surfaces, TPS's elements join the dual strips G^1, sharpness 10 carried
//! through the construction is the infinitely sharp crease, `--prepare none` keeps the refusal,
//! sharpness 9 is built, and the patch tables re-apply through the construction.

use crate::sharp_helpers::support;
use support::creased_cube;

use fairsub::analysis::continuity;
use fairsub::host::ComplexOptions;
use fairsub::mesh::{Extras, PolyMesh, SharpEdges};
use fairsub::schemes::descriptor::SurfaceOutput;
use fairsub::schemes::options::PrepareMode;
use fairsub::schemes::registry::registry;

/// The schemes whose semi-sharp creases are spent before their rules.
const SCHEMES: &[&str] = &["tps", "tps-adjustable", "bi2-mixed", "polar-bi2"];

const RINGS: ComplexOptions = ComplexOptions {
    rings: 3,
    fill: true,
};

fn build(scheme: &str, mesh: &PolyMesh, prepare: PrepareMode) -> fairsub::Result<SurfaceOutput> {
    let mut spec = registry().lookup(scheme).expect("scheme");
    spec.params.prepare = prepare;
    fairsub::surface::build(&spec, mesh, RINGS, &mut |_| {})
}

/// The gallery cube (six quads, eight valence-3 vertices) with the edges `tags` picks
/// (`tags(edge index, face 0's first two edges)`) tagged.
fn tagged_cube(tags: impl Fn(usize, [usize; 2]) -> Option<f32>) -> PolyMesh {
    let cube = fairsub::gallery::all()
        .into_iter()
        .find(|(n, _)| n == "cube")
        .expect("gallery cube")
        .1;
    let h0 = cube.face_halfedge(0);
    let first = [
        cube.he_edge(h0) as usize,
        cube.he_edge(cube.he_next(h0)) as usize,
    ];
    let sharp: Vec<(u32, f32)> = (0..cube.num_edges())
        .filter_map(|e| tags(e, first).map(|s| (e as u32, s)))
        .collect();
    cube.with_extras(Some(Extras {
        sharp_edges: SharpEdges::ById(sharp),
        ..Extras::default()
    }))
}

/// OpenSubdiv's `catmark_cube_creases0` pattern: two edges of a face, sharpness 2, a chain
/// through a valence-3 vertex ending at two darts.
fn two_edge_chain() -> PolyMesh {
    tagged_cube(|e, first| first.contains(&e).then_some(2.0))
}

/// `catmark_cube_creases1`'s pattern at lower sharpness: every edge but one at 2.5 (junctions
/// of three creases at every corner), the last at 0.1.
fn all_edges() -> PolyMesh {
    tagged_cube(|e, first| Some(if e == first[0] { 0.1 } else { 2.5 }))
}

#[test]
fn closed_semi_sharp_nets_give_closed_g1_surfaces() {
    let nets = [
        ("two-edge chain 2", two_edge_chain()),
        ("all edges 2.5 / 0.1", all_edges()),
        ("cube 2.5 / 0.7", creased_cube(2.5, 0.7)),
        ("cube 10 / 1.5", creased_cube(10.0, 1.5)),
    ];
    for scheme in SCHEMES {
        for (name, net) in &nets {
            let out = build(scheme, net, PrepareMode::Auto)
                .unwrap_or_else(|e| panic!("{scheme} {name}: {e}"));
            let r = continuity::check(&out.complex);
            eprintln!(
                "{scheme} {name}: {} patches, open {}, C0 {:.1e}, G1 {:.1e}, sharp {} (C0 {:.1e})",
                out.complex.len(),
                r.open_sides,
                r.all.c0,
                r.all.g1,
                r.sharp.pieces,
                r.sharp.c0
            );
            assert_eq!(r.open_sides, 0, "{scheme} {name}: cracks");
            assert!(r.all.c0 < 1e-12 && r.sharp.c0 < 1e-12, "{scheme} {name}");
            assert!(r.all.g1 < 1e-8, "{scheme} {name}: G1 {:e}", r.all.g1);
            // the infinitely sharp equator stays a sharp join, the spent creases are smooth
            assert_eq!(r.sharp.pieces > 0, name.contains("10"), "{scheme} {name}");
            // the note names the construction and the sharpest features
            let note = out
                .notes
                .iter()
                .find(|n| n.contains("with fairsub's crease construction"))
                .unwrap_or_else(|| panic!("{scheme} {name}: no note in {:?}", out.notes));
            // TPS by Doo-Sabin's construction beside its elements; the mixed and polar nets,
            // whose spent net is a PGS net, by PGS's construction (near the features only)
            let how = if scheme.starts_with("tps") {
                "clear of the features get"
            } else {
                "built by pgs's construction, which takes those steps only near the features"
            };
            assert!(note.contains(how), "{note}");
            assert!(note.contains("sharpness"), "{note}");
        }
    }
}

/// The input-face points of `a` and `b` below `z` (in `b`) at seven places of each of the
/// creased cube's 96 faces: how many, the largest distance between them, and between `b` and
/// `c` there.
fn below_top_loop(
    a: &fairsub::surface::eval::Surface,
    b: &fairsub::surface::eval::Surface,
    c: &fairsub::surface::eval::Surface,
    z: f64,
) -> (usize, f64, f64) {
    let (mut below, mut same, mut other) = (0, 0.0f64, 0.0f64);
    for f in 0..96u32 {
        let near_sides = [(0.5, 0.02), (0.98, 0.5), (0.5, 0.98), (0.02, 0.5)];
        for (u, v) in [(0.2, 0.3), (0.5, 0.5), (0.8, 0.9)]
            .into_iter()
            .chain(near_sides)
        {
            let p = a.evaluate(f, u, v).expect("a face").point;
            if p[2] > z {
                continue;
            }
            below += 1;
            let q = b.evaluate(f, u, v).expect("a face").point;
            same = same.max(fairsub::geom::dist(p, q));
            let r = c.evaluate(f, u, v).expect("a face").point;
            other = other.max(fairsub::geom::dist(q, r));
        }
    }
    (below, same, other)
}

/// TPS and adjustable TPS on the cube with the equator tagged 10 beside a semi-sharp top loop:
/// every extraordinary vertex of this cube is within reach of a feature, so the surface is
/// Doo-Sabin's crease construction with the top loop's one ring more, and below the top loop
/// it is Doo-Sabin's surface of the equator cut from the start (the infinitely sharp crease),
/// point for point on the input faces; an equator of sharpness 0.5 is another surface there.
#[test]
fn sharpness_ten_is_the_infinitely_sharp_crease() {
    use fairsub::surface::eval::Surface;
    let ds = registry().lookup("doo-sabin").expect("doo-sabin");
    let four = ComplexOptions { rings: 4, ..RINGS };
    let cut = Surface::build(&ds, &creased_cube(10.0, 0.0), four).expect("doo-sabin");
    for scheme in ["tps", "tps-adjustable"] {
        let spec = registry().lookup(scheme).expect(scheme);
        let spent = Surface::build(&spec, &creased_cube(10.0, 0.5), RINGS).expect(scheme);
        let finite = Surface::build(&spec, &creased_cube(0.5, 0.5), RINGS).expect(scheme);
        let (below, same, other) = below_top_loop(&cut, &spent, &finite, 0.2);
        eprintln!(
            "{scheme}: {below} points below the top loop, 10 against the cut {same:.1e}, 0.5 \
             {other:.1e}"
        );
        assert!(below >= 350, "{scheme}: {below}");
        assert!(same < 1e-9, "{scheme}: {same:e}");
        assert!(other > 1e-4, "{scheme}: {other:e}");
    }
}

/// Asserts that `out` is closed (no open side), C^0 to 1e-12 and G^1 to 1e-8.
fn closed_and_g1(scheme: &str, out: &SurfaceOutput) {
    let r = continuity::check(&out.complex);
    eprintln!(
        "{scheme}: {} patches, open {}, G1 {:.1e}",
        out.complex.len(),
        r.open_sides,
        r.all.g1
    );
    assert_eq!(r.open_sides, 0, "{scheme}");
    assert!(
        r.all.c0 < 1e-12 && r.all.g1 < 1e-8,
        "{scheme}: {:e}",
        r.all.g1
    );
}

/// A semi-sharp loop on the top face of the creased cube leaves its four bottom corners
/// (valence 3) clear: they keep TPS's rings and cap, which join Doo-Sabin's strip around the
/// loop and the regular patches G^1 (closed surface); without the loop the surface there is
/// TPS's own, patch for patch on the bottom corners' cells.
#[test]
fn tps_elements_clear_of_the_features_join_the_dual_strips() {
    use fairsub::surface::eval::Surface;
    for scheme in ["tps", "tps-adjustable"] {
        let out = build(scheme, &creased_cube(0.0, 2.5), PrepareMode::Auto)
            .unwrap_or_else(|e| panic!("{scheme}: {e}"));
        let note = out
            .notes
            .iter()
            .find(|n| n.contains("clear of the features get"))
            .unwrap_or_else(|| panic!("{scheme}: {:?}", out.notes));
        assert!(note.contains(": 4 extraordinary vertices clear"), "{note}");
        closed_and_g1(scheme, &out);
        // near the bottom corners the surface is TPS's of the net without the loop
        let spec = registry().lookup(scheme).expect(scheme);
        let with = Surface::build(&spec, &creased_cube(0.0, 2.5), RINGS).expect(scheme);
        let without = Surface::build(&spec, &creased_cube(0.0, 0.0), RINGS).expect(scheme);
        let (mut near, mut worst) = (0, 0.0f64);
        for f in 0..96u32 {
            for k in 0..25 {
                let (u, v) = (
                    0.05 + 0.225 * f64::from(k / 5),
                    0.05 + 0.225 * f64::from(k % 5),
                );
                let p = without.evaluate(f, u, v).expect("a face").point;
                if p[2] > -0.6 {
                    continue;
                }
                near += 1;
                let q = with.evaluate(f, u, v).expect("a face").point;
                worst = worst.max(fairsub::geom::dist(p, q));
            }
        }
        eprintln!("{scheme}: {near} points near the bottom, against TPS's own {worst:.1e}");
        assert!(near >= 300, "{scheme}: {near}");
        assert!(worst < 1e-12, "{scheme}: {worst:e}");
    }
}

/// The mixed and polar nets take PGS's construction on a net with semi-sharp features
/// (`bi2::surface::spent_by_pgs`; its equality with the whole-net PGS steps is a unit test of
/// `schemes::prepare`): the equator tagged 10 beside a semi-sharp top loop is the crease cut
/// from the start, so below the top loop the surface is PGS's of the net without it (both with
/// the one ring the top loop's step adds), point for point on the input faces; an equator of
/// sharpness 0.5 is another surface there.
#[test]
fn sharpness_ten_under_the_mixed_and_polar_nets_is_the_cut() {
    use fairsub::surface::eval::Surface;
    let pgs = registry().lookup("pgs").expect("pgs");
    let four = ComplexOptions { rings: 4, ..RINGS };
    let cut = Surface::build(&pgs, &creased_cube(10.0, 0.0), four).expect("pgs");
    for scheme in ["bi2-mixed", "polar-bi2"] {
        let spec = registry().lookup(scheme).expect(scheme);
        let spent = Surface::build(&spec, &creased_cube(10.0, 0.5), RINGS).expect(scheme);
        // (below 1: from sharpness 1 on the dual construction differs from the cut only inside
        // the crease strip, which input faces do not address; creases.md's limits)
        let finite = Surface::build(&spec, &creased_cube(0.5, 0.5), RINGS).expect(scheme);
        let (mut same, mut other, mut below) = (0.0f64, 0.0f64, 0);
        for f in 0..96u32 {
            let near_sides = [(0.5, 0.02), (0.98, 0.5), (0.5, 0.98), (0.02, 0.5)];
            for (u, v) in [(0.2, 0.3), (0.5, 0.5), (0.8, 0.9)]
                .into_iter()
                .chain(near_sides)
            {
                let p = cut.evaluate(f, u, v).expect("a face").point;
                if p[2] > 0.2 {
                    continue;
                }
                below += 1;
                let q = spent.evaluate(f, u, v).expect(scheme).point;
                same = same.max(fairsub::geom::dist(p, q));
                let r = finite.evaluate(f, u, v).expect(scheme).point;
                other = other.max(fairsub::geom::dist(p, r));
            }
        }
        eprintln!(
            "{scheme}: {below} points below the top loop, 10 against the cut {same:.1e}, 0.5 \
             {other:.1e}"
        );
        assert!(below >= 350, "{scheme}: {below}");
        assert!(same < 1e-9, "{scheme}: {same:e}");
        assert!(other > 1e-4, "{scheme}: {other:e}");
    }
}

#[test]
fn prepare_none_keeps_the_refusal() {
    for scheme in SCHEMES {
        let e = build(scheme, &creased_cube(2.5, 0.0), PrepareMode::None)
            .err()
            .unwrap_or_else(|| panic!("{scheme}: built"))
            .to_string();
        assert!(
            e.contains("has the semi-sharp crease value 2.5")
                && e.contains(&format!(
                    "{scheme}'s patches take infinitely sharp creases only"
                )),
            "{scheme}: {e}"
        );
    }
}

/// Sharpness 9 on the 96-quad cube: nine whole-net dual steps would make about 386 * 4^8
/// faces (TPS refused it until 2026-12-07, the mixed and polar nets until the day before); the
/// constructions refine only near the crease.
#[test]
fn sharpness_nine_is_built_near_the_crease_only() {
    for scheme in SCHEMES {
        let out = build(scheme, &creased_cube(9.0, 0.0), PrepareMode::Auto)
            .unwrap_or_else(|e| panic!("{scheme}: {e}"));
        closed_and_g1(scheme, &out);
        assert!(
            out.complex.len() < 200_000,
            "{scheme}: {}",
            out.complex.len()
        );
    }
}

#[test]
fn patch_tables_reapply_through_the_spending_step() {
    // The table of a net whose creases are spent first is the table of the whole construction
    // (the spending steps, the cut, the scheme's rings and caps) as a linear map of the input
    // points: moved input points give the complex built from them (1e-12 of the net's size).
    // (OpenSubdiv's creases0 pattern: two whole-net steps of the six-face cube; the larger
    // creased nets of the other tests make the probed tables of these schemes cost seconds each)
    let net = two_edge_chain();
    for scheme in SCHEMES {
        support::table_reapplies(
            scheme,
            &format!("two-edge chain under {scheme}"),
            &net,
            |_| true,
        );
    }
}

/// Hole tags beside semi-sharp creases (refused before 2026-12-07: the dual steps carry no
/// hole): the hole faces are removed before the spending steps, as the dual schemes' patches
/// remove them, so the surface is that of the net with those faces deleted outright, patch for
/// patch, and G^1 with the hole's boundary open.
#[test]
fn hole_faces_are_removed_before_the_spending_steps() {
    let chain = two_edge_chain();
    let ex = chain.extras().cloned().expect("tags");
    let fairsub::mesh::SharpEdges::ById(tags) = &ex.sharp_edges else {
        panic!("tags by edge index");
    };
    // the face across from the chain (face 0) is the hole
    let hole = 1;
    let tagged = chain.clone().with_extras(Some(Extras {
        holes: vec![hole as u32],
        ..ex.clone()
    }));
    let kept: Vec<Vec<usize>> = (0..chain.num_faces())
        .filter(|&f| f != hole)
        .map(|f| chain.face(f).iter().map(|&v| v as usize).collect())
        .collect();
    let open = PolyMesh::new(chain.positions().to_vec(), &kept).expect("the open box");
    let sharp = tags
        .iter()
        .map(|&(e, s)| {
            let h = chain.edge_halfedge(e as usize);
            let e = open
                .find_edge(chain.he_from(h), chain.he_to(h))
                .expect("kept");
            (e, s)
        })
        .collect();
    let open = open.with_extras(Some(Extras {
        sharp_edges: SharpEdges::ById(sharp),
        ..Extras::default()
    }));
    for scheme in SCHEMES {
        let out =
            build(scheme, &tagged, PrepareMode::Auto).unwrap_or_else(|e| panic!("{scheme}: {e}"));
        let want =
            build(scheme, &open, PrepareMode::Auto).unwrap_or_else(|e| panic!("{scheme}: {e}"));
        assert!(
            out.notes.iter().any(|n| n.contains("1 hole faces removed")),
            "{scheme}: {:?}",
            out.notes
        );
        let r = continuity::check(&out.complex);
        assert!(
            r.all.c0 < 1e-12 && r.all.g1 < 1e-8,
            "{scheme}: G1 {:e}",
            r.all.g1
        );
        assert!(r.open_sides > 0, "{scheme}: the hole's boundary");
        let (a, b) = (&out.complex.patches, &want.complex.patches);
        assert_eq!(a.len(), b.len(), "{scheme}: patch counts");
        let worst = a
            .iter()
            .zip(b)
            .flat_map(|(p, q)| {
                p.cps
                    .iter()
                    .zip(&q.cps)
                    .map(|(x, y)| fairsub::geom::dist(*x, *y))
            })
            .fold(0.0f64, f64::max);
        eprintln!(
            "{scheme}: {} patches, against the open box {worst:.1e}",
            a.len()
        );
        assert!(worst < 1e-12, "{scheme}: {worst:e}");
        // evaluation keeps addressing the input faces; the hole's face has no surface
        let spec = registry().lookup(scheme).expect("scheme");
        let s = fairsub::surface::eval::Surface::build(&spec, &tagged, RINGS).expect(scheme);
        let w = fairsub::surface::eval::Surface::build(&spec, &open, RINGS).expect(scheme);
        for f in (0..chain.num_faces()).filter(|&f| f != hole) {
            let g = f - usize::from(f > hole);
            for (u, v) in [(0.3, 0.6), (0.5, 0.5), (0.9, 0.2)] {
                let p = s.evaluate(f as u32, u, v).expect("a kept face").point;
                let q = w.evaluate(g as u32, u, v).expect("the open box").point;
                assert!(fairsub::geom::dist(p, q) < 1e-12, "{scheme} face {f}");
            }
        }
        assert!(
            s.evaluate(hole as u32, 0.5, 0.5).is_err(),
            "{scheme}: the hole"
        );
    }
}
