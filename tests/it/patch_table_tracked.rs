//! Catmull-Clark's patch table tracked beside the points (`PatchTable::tracked`, factored: the
//! refinement levels' own stencils and each patch's B-spline net, expanded to one row per Bezier
//! coefficient on demand) against the table probed off the construction
//! (`PatchTable::build_probed`): the same expanded rows to 1e-12 on
//! gallery nets and OpenSubdiv's tagged nets (creases, corners, semi-sharp features, boundaries),
//! and re-applied to moved points equal to the complex recomputed from them to 1e-12. Where the
//! construction takes a step that is not tracked (the Hermite-Coons fill at boundary
//! extraordinary vertices), `tracked` declines and `build` probes.

use fairsub::PolyMesh;
use fairsub::schemes::registry::registry;
use fairsub::surface::table::{PatchTable, probe};
use fairsub::surface::{ComplexOptions, PatchComplex};
use std::path::Path;

fn gallery(name: &str) -> PolyMesh {
    fairsub::gallery::all()
        .into_iter()
        .find(|(n, _)| n == name)
        .unwrap_or_else(|| panic!("no gallery net {name}"))
        .1
}

fn osd(name: &str) -> PolyMesh {
    let p = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("tests/data/osd/{name}.obj"));
    fairsub::io::read_mesh(&p).expect("osd net").mesh
}

/// Largest coefficient difference of two complexes of one structure, relative to `size`.
fn deviation(a: &PatchComplex, b: &PatchComplex) -> f64 {
    assert_eq!(a.len(), b.len(), "patch counts");
    assert_eq!(a.provenance, b.provenance, "provenance");
    let (d, _) = probe::max_deviation(a, b);
    d
}

fn size(m: &PolyMesh) -> f64 {
    probe::net_size(m.positions())
}

/// Tracked against probed, and the tracked table re-applied to moved points; `Some(caps)` when
/// the net was tracked.
fn check(what: &str, mesh: &PolyMesh, rings: usize) -> Option<usize> {
    let spec = registry().lookup("catmull-clark").expect("registered");
    let opts = ComplexOptions { rings, fill: true };
    let (complex, tracked) = PatchTable::tracked(&spec, mesh, opts).expect(what)?;
    let plain = fairsub::surface::build(&spec, mesh, opts, &mut |_| {})
        .expect(what)
        .complex;
    assert_eq!(
        complex.patches, plain.patches,
        "{what}: tracking changes the complex"
    );
    assert_eq!(complex.provenance, plain.provenance, "{what}: provenance");
    // the tracked table is factored: per bi-3 patch its net's 16 rows over the levels, then the
    // caps' data rows (the expanded rows: one per Bezier coefficient)
    let layered = tracked.layered().expect("tracked tables are factored");
    let np = tracked.num_patches();
    let nets = (0..np).filter(|&p| !tracked.is_cap_patch(p)).count();
    let data = tracked.rows().num_rows() - tracked.first_row(np);
    assert_eq!(
        layered.num_rows(),
        16 * nets + data,
        "{what}: factored rows"
    );
    let probed = PatchTable::build_probed(&spec, mesh, opts).expect(what);
    assert!(
        probed.layered().is_none(),
        "{what}: probed tables are expanded"
    );
    let d = tracked.rows_deviation(&probed);
    assert!(
        d <= 1e-12,
        "{what}: tracked rows differ from probed by {d:.3e}"
    );
    assert_eq!(tracked.caps(), probed.caps(), "{what}: caps");
    let s = size(mesh);
    let at_net = deviation(&tracked.apply(mesh.positions()).expect(what), &complex);
    assert!(
        at_net <= 1e-12 * s,
        "{what}: at the net's points {at_net:.3e}"
    );
    for seed in [1, 2] {
        let moved = probe::moved_points(mesh.positions(), 0.05 * s, seed);
        let mut m = mesh.clone();
        m.set_positions(moved.clone());
        let truth = fairsub::surface::build(&spec, &m, opts, &mut |_| {})
            .expect(what)
            .complex;
        let got = tracked.apply(&moved).expect(what);
        let d = deviation(&got, &truth);
        assert!(d <= 1e-12 * s, "{what}: moved points (seed {seed}) {d:.3e}");
        // the factored rows into the complex, nets converted in place: the same bits
        let mut reused = complex.clone();
        tracked.apply_into(&moved, &mut reused).expect(what);
        assert!(
            reused.patches == got.patches && reused.caps == got.caps,
            "{what}: apply_into differs from apply (seed {seed})"
        );
    }
    Some(tracked.caps().len())
}

#[test]
fn tracked_tables_equal_probed_ones_on_gallery_nets() {
    let mut caps = 0;
    for (name, rings) in [
        ("cube", 2),
        ("cube", 3),
        ("torus-evs", 2),
        ("prism-5", 2),
        ("cnet-3-saddle", 2),
        ("cnet-5-convex", 3),
        ("cnet-6-raised", 2),
        ("tetrahedron", 2),
        ("icosahedron", 1),
    ] {
        let c = check(name, &gallery(name), rings)
            .unwrap_or_else(|| panic!("{name}: closed net, every step tracked"));
        caps += c;
    }
    assert!(caps >= 30, "G^1 caps tracked: {caps}");
}

#[test]
fn tracked_tables_take_tagged_nets_and_decline_the_fill() {
    let mut tracked = Vec::new();
    let mut declined = Vec::new();
    for name in [
        "cc_cube_infsharp",
        "cc_cube_semisharp",
        "cc_crease_extraordinary",
        "cc_corner_tags",
        "cc_boundary_tags",
        "cc_boundary_valences",
        "cc_chain_chaikin",
    ] {
        match check(name, &osd(name), 2) {
            Some(_) => tracked.push(name),
            None => declined.push(name),
        }
    }
    eprintln!("tracked {tracked:?}, probed {declined:?}");
    // boundary tags under OpenSubdiv's rules: tracked through the sharp level's stencils; the
    // others have extraordinary vertices on features, closed by the Hermite-Coons fill
    assert!(tracked.contains(&"cc_boundary_tags"), "{tracked:?}");
    assert!(declined.contains(&"cc_cube_infsharp"), "{declined:?}");
    // an open grid: boundary patches, no extraordinary vertex: tracked
    assert!(check("open-grid", &gallery("open-grid"), 2).is_some());
    // a declined net gets the probed table from `build`
    let spec = registry().lookup("catmull-clark").expect("registered");
    let opts = ComplexOptions {
        rings: 2,
        fill: true,
    };
    let m = osd("cc_cube_infsharp");
    let t = PatchTable::build(&spec, &m, opts).expect("probed fallback");
    let c = fairsub::surface::build(&spec, &m, opts, &mut |_| {}).expect("complex");
    assert!(deviation(&t.apply(m.positions()).expect("apply"), &c.complex) <= 1e-12 * size(&m));
}
