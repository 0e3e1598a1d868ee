//! Helpers shared by the tests of open-fan caps at extraordinary boundary vertices
//! (`tests/it/boundary_caps.rs`, `tests/it/loop_boundary_caps.rs`).

use fairsub::bezier::complex::PatchComplex;
use fairsub::geom::{cross, dist, normalize};
use fairsub::mesh::PolyMesh;
use fairsub::schemes::registry::registry;
use fairsub::surface::ComplexOptions;
use fairsub::surface::table::{PatchTable, probe};

/// The number of open-fan caps of a complex.
pub fn open_caps(c: &PatchComplex) -> usize {
    c.caps.iter().filter(|s| s.hole.is_open()).count()
}

/// The centre and unit normal there of the open cap nearest to `at`.
pub fn centre_and_normal(c: &PatchComplex, at: [f64; 3]) -> ([f64; 3], [f64; 3]) {
    let step = c
        .caps
        .iter()
        .filter(|s| s.hole.is_open())
        .min_by(|a, b| dist(a.hole.centre, at).total_cmp(&dist(b.hole.centre, at)))
        .expect("an open cap");
    let p = &c.patches[step.first as usize];
    let d = p.derivatives(0.0, 0.0);
    (p.eval(0.0, 0.0), normalize(cross(d.du, d.dv)))
}

/// `scheme`'s patch table of `mesh` (2 rings) holds `want` open caps and re-applies to points
/// moved by 5% of the net's size (`seed`) within 1e-12 of it.
pub fn table_reapplies(scheme: &str, name: &str, mesh: &PolyMesh, want: usize, seed: u64) {
    let spec = registry().lookup(scheme).expect("registered");
    let what = format!("{name} under {scheme}");
    let opts = ComplexOptions {
        rings: 2,
        fill: true,
    };
    let table = PatchTable::build(&spec, mesh, opts).expect(&what);
    let open = table
        .caps()
        .iter()
        .filter(|c| c.step.hole.is_open())
        .count();
    assert_eq!(open, want, "{what}: open caps in the table");
    let s = probe::net_size(mesh.positions());
    let moved = probe::moved_points(mesh.positions(), 0.05 * s, seed);
    let mut m = mesh.clone();
    m.set_positions(moved.clone());
    let truth = fairsub::surface::build(&spec, &m, opts, &mut |_| {})
        .expect(&what)
        .complex;
    let (d, _) = probe::max_deviation(&table.apply(&moved).expect(&what), &truth);
    assert!(d <= 1e-12 * s, "{what}: moved points {d:.3e}");
}
