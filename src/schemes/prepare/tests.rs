use super::map::{Cell, FaceCell};
use super::*;
use crate::bezier::domain::{Affine, Shape};
use crate::mesh::nets;
use crate::schemes::registry::{ids, registry};

fn prepared(id: crate::schemes::SchemeId, mesh: &PolyMesh, mode: Mode) -> Prepared {
    let mut spec = Spec::new(id);
    spec.params.prepare = mode;
    prepare(registry().descriptor(id), &spec, mesh, Purpose::Patches).expect("prepared")
}

/// The area of the image of `[0, 1]^2` under a cell's map.
fn area(c: &Cell) -> f64 {
    (c.map.e[0][0] * c.map.e[1][1] - c.map.e[0][1] * c.map.e[1][0]).abs()
}

/// The area each input face (sub-face) gets from the cells of `map`'s faces (quarters, or
/// the whole face).
fn covered_area(mesh: &PolyMesh, map: &ParamMap) -> std::collections::BTreeMap<(u32, u32), f64> {
    let mut out = std::collections::BTreeMap::new();
    for (g, c) in map.faces.iter().enumerate() {
        let cells: Vec<Cell> = match c {
            FaceCell::Whole(c) => vec![*c],
            FaceCell::Quarters(q) => q.iter().flatten().copied().collect(),
            FaceCell::Nowhere => Vec::new(),
        };
        let _ = (g, mesh);
        for c in cells {
            *out.entry((c.face, c.sub)).or_insert(0.0) += area(&c);
        }
    }
    out
}

#[crate::unit::test]
fn the_catmull_clark_step_makes_quads_of_the_quarters() {
    let mesh = nets::octahedron();
    let p = prepared(ids::TPS, &mesh, Mode::Auto);
    assert!(p.mesh.is_all_quads());
    assert_eq!(p.applied.len(), 1);
    assert_eq!(p.applied[0].step, "one Catmull-Clark step");
    assert_eq!(p.applied[0].count, 8);
    let map = p.map.as_ref().expect("a map");
    assert_eq!(map.faces.len(), p.mesh.num_faces());
    // child face h of parent corner h is sub-face k of the triangle, with its own corner 0 at
    // the sub-face's corner 0
    for (h, c) in map.faces.iter().enumerate() {
        let g = mesh.he_face(h as u32);
        let k = h as u32 - mesh.face_halfedge(g as usize);
        assert_eq!(
            *c,
            FaceCell::Whole(Cell {
                face: g,
                sub: k,
                map: Affine::IDENTITY
            })
        );
    }
    // every sub-face is covered once
    for (_, a) in covered_area(&p.mesh, map) {
        assert_eq!(a, 1.0);
    }
}

fn dual_child(m: &PolyMesh) -> PolyMesh {
    use crate::schemes::Scheme;
    crate::schemes::DooSabin.refine(m).expect("a step").mesh
}

#[crate::unit::test]
fn the_dual_step_tiles_the_quarters_of_the_input_faces() {
    // the cube: every quad's four quarters split in four, each by one child face
    let mesh = nets::cube();
    let p = prepared(ids::BI2_MIXED, &nets::split_edge_cube(), Mode::Auto);
    assert_eq!(p.applied[0].step, "one PGS step");
    assert_eq!(p.applied[0].kind, Kind::Applied);
    let map = ParamMap::input(&mesh).dual_step(&mesh, &dual_child(&mesh));
    for (_, a) in covered_area(&mesh, &map) {
        assert!((a - 1.0).abs() < 1e-15, "{a}");
    }
    // the quarter of a child face at a corner point is the child of the parent quarter
    // toward that face, (0, 0) at the quarter's centre
    let q = map.faces[0].quarter(0, 4).expect("a quarter");
    let want = Shape::Quad
        .child_map(0)
        .compose(&Shape::Quad.child_map(2))
        .compose(&Shape::Quad.corner_map(2));
    assert_eq!(q.map, want);
    // the split-edge cube: the child toward the valence-2 vertex of its quarters lies over
    // no face (the step leaves its V-face out), everything else is covered once
    let m = nets::split_edge_cube();
    let map = ParamMap::input(&m).dual_step(&m, &dual_child(&m));
    let v2 = (0..m.num_vertices())
        .find(|&v| m.valence(v) == 2)
        .expect("the valence-2 vertex");
    for ((f, sub), a) in covered_area(&m, &map) {
        let corner = if m.face_size(f as usize) == 4 {
            None
        } else {
            Some(m.face(f as usize)[sub as usize] as usize)
        };
        let want = if corner == Some(v2) { 0.75 } else { 1.0 };
        assert!((a - want).abs() < 1e-15, "face {f} sub-face {sub}: {a}");
    }
}

#[crate::unit::test]
fn nothing_is_applied_without_need_or_under_none() {
    let cube = nets::cube();
    for id in [ids::TPS, ids::DOO_SABIN, ids::PGS, ids::CATMULL_CLARK] {
        let p = prepared(id, &cube, Mode::Auto);
        assert!(!p.changed(), "{id}");
        assert!(p.notes(id.name()).is_empty());
    }
    let p = prepared(ids::TPS, &nets::octahedron(), Mode::None);
    assert!(!p.changed());
    assert_eq!(p.mesh.num_faces(), 8);
}

#[crate::unit::test]
fn the_dual_steps_leave_tagged_nets_to_the_scheme() {
    // a semi-sharp crease beside a hole tag on the split-edge cube: the Doo-Sabin step
    // carries the crease but not the hole, so the net is given to the scheme as it is, with a
    // note
    let m = nets::split_edge_cube();
    let tags = crate::mesh::Extras {
        sharp_edges: crate::mesh::SharpEdges::ById(vec![(0, 2.0)]),
        holes: vec![m.num_faces() as u32 - 1],
        ..Default::default()
    };
    let m = m.with_extras(Some(tags));
    let p = prepared(ids::DOO_SABIN, &m, Mode::Auto);
    assert!(!p.changed());
    let notes = p.notes(ids::DOO_SABIN.name());
    assert_eq!(notes.len(), 1);
    assert!(
        notes[0].contains("does not carry the net's sharp-feature tags"),
        "{}",
        notes[0]
    );
    // the Catmull-Clark step carries them (each sharp edge becomes two)
    let t = crate::mesh::nets::prism(3);
    let tags = crate::mesh::Extras {
        sharp_edges: crate::mesh::SharpEdges::ById(vec![(0, 10.0)]),
        ..Default::default()
    };
    let p = prepared(ids::TPS, &t.with_extras(Some(tags)), Mode::Auto);
    assert!(p.changed());
    let ex = p.mesh.extras().expect("tags");
    assert_eq!(ex.sharp_edges.len(), 2);
}

/// `mesh` with the semi-sharp edges `(a, b, sharpness)` (by their end points).
fn with_creases(mesh: PolyMesh, creases: &[(u32, u32, f32)]) -> PolyMesh {
    let sharp = creases.iter().map(|&(a, b, s)| ([a, b], s)).collect();
    mesh.with_extras(Some(crate::mesh::Extras {
        sharp_edges: crate::mesh::SharpEdges::ByPair(sharp),
        ..Default::default()
    }))
}

/// The mixed and polar nets build the surface of a net with semi-sharp creases by PGS's
/// construction with the spending steps counted as rings (`bi2::surface::spent_by_pgs`): it
/// is the surface of the whole-net PGS steps that spend the sharpness followed by the scheme
/// on the spent net (the construction they took before, and TPS still takes with Doo-Sabin
/// steps), point for point on every input face.
#[crate::unit::test]
fn pgs_construction_equals_the_whole_net_spending_steps() {
    use crate::surface::eval::Surface;
    let opts = crate::host::ComplexOptions {
        rings: 2,
        fill: true,
    };
    let nets = [
        // a loop around the top face (2.5: three steps) and a side edge fading out (0.7)
        with_creases(
            nets::cube(),
            &[
                (0, 1, 2.5),
                (1, 2, 2.5),
                (2, 3, 2.5),
                (3, 0, 2.5),
                (4, 5, 0.7),
            ],
        ),
        // a pentagonal prism (poles for polar-bi2) with one cap's rim at 1.5
        with_creases(
            nets::prism(5),
            &[
                (15, 16, 1.5),
                (16, 17, 1.5),
                (17, 18, 1.5),
                (18, 19, 1.5),
                (19, 15, 1.5),
            ],
        ),
    ];
    for id in [ids::BI2_MIXED, ids::POLAR_BI2] {
        let spec = Spec::new(id);
        for (i, net) in nets.iter().enumerate() {
            let steps = crate::schemes::doo_sabin::sharp::spending_steps(net);
            assert!(steps >= 2, "net {i}");
            let local = Surface::build(&spec, net, opts).expect("PGS's construction");
            // the whole-net steps, then the scheme on the spent net, moved to the input faces
            let (mut spent, mut map) = (net.clone(), None);
            for _ in 0..steps {
                let (child, next) = NetStep::Pgs
                    .apply(&spec, &spent, map.as_ref())
                    .expect("a PGS step");
                spent = child;
                map = Some(next);
            }
            assert!(!crate::schemes::doo_sabin::sharp::has_semi_sharp(&spent));
            let on_spent = Surface::build(&spec, &spent, opts).expect("the spent net");
            let mut complex = on_spent.complex().clone();
            map.expect("steps").lift(&spent, &mut complex);
            let whole = Surface::new(net, complex);
            let mut worst = 0.0f64;
            let mut count = 0;
            for f in 0..net.num_faces() as u32 {
                for a in 1..8 {
                    for b in 1..8 {
                        let (u, v) = (f64::from(a) / 8.0, f64::from(b) / 8.0);
                        let (Ok(p), Ok(q)) = (local.evaluate(f, u, v), whole.evaluate(f, u, v))
                        else {
                            continue;
                        };
                        worst = worst.max(crate::geom::dist(p.point, q.point));
                        count += 1;
                    }
                }
            }
            eprintln!("{id} net {i}: {steps} steps, {count} points, {worst:.1e}");
            assert!(
                count > 49 * net.num_faces() / 2,
                "{id} net {i}: {count} points"
            );
            assert!(worst < 1e-12, "{id} net {i}: {worst:e}");
        }
    }
}
