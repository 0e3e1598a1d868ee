//! Closest points on the exact surface (`surface::closest`) and exact moments
//! (`analysis::moments`) on a 12k-face Catmull-Clark net with extraordinary vertices (issue
//! 46's target: 10^6 query points in seconds).
//!
//! - `project/cc-12k/index`: the projection index (charts, sample grids, R*-tree);
//! - `project/cc-12k/1e6-points`: 10^6 closest points (rayon, all cores), the query points the
//!   surface's own points at random parameters pushed along their normals by up to 2% of the
//!   net's size either way (a scan's typical distance);
//! - `project/cc-12k/1e4-far-points`: 10^4 points at up to 20% of the size (more charts
//!   within reach of each);
//! - `measure/cc-12k`: area, volume, centroids and inertia of the whole surface.
//!
//! The net is the gallery's `torus-evs` refined four times with Catmull-Clark (12288 quads),
//! its surface with 2 rings, as in the `eval` benchmark.

use criterion::{Criterion, criterion_group, criterion_main};
use fairsub::analysis::moments::{MeasureOptions, measure};
use fairsub::schemes::registry::{ids, registry};
use fairsub::schemes::{CatmullClark, refine_levels};
use fairsub::surface::ComplexOptions;
use fairsub::surface::closest::ProjectionIndex;
use fairsub::surface::eval::Surface;
use std::hint::black_box;
use std::time::Duration;

/// `n` points at distances up to `reach` (of the net's size) from the surface.
fn queries(s: &Surface, faces: u64, n: usize, reach: f64) -> Vec<[f64; 3]> {
    let mut x = 0x2545_f491_4f6c_dd1du64;
    let mut next = move || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        x
    };
    let unit = |r: u64| (r >> 11) as f64 / (1u64 << 53) as f64;
    let (lo, hi) = fairsub::geom::bounding_box(
        s.complex()
            .patches
            .iter()
            .flat_map(|p| p.cps.iter().copied()),
    )
    .expect("patches");
    let size = fairsub::geom::dist(lo, hi);
    (0..n)
        .map(|_| {
            let e = s
                .evaluate((next() % faces) as u32, unit(next()), unit(next()))
                .expect("in the domain");
            let t = (2.0 * unit(next()) - 1.0) * reach * size;
            fairsub::geom::axpy(e.point, t, e.normal)
        })
        .collect()
}

fn project(c: &mut Criterion) {
    let net = fairsub::mesh::nets::torus_with_evs();
    let mesh = refine_levels(&CatmullClark, &net, 4, |_| {}).expect("refines");
    let spec = registry()
        .lookup(ids::CATMULL_CLARK.name())
        .expect("catmull-clark");
    let opts = ComplexOptions {
        rings: 2,
        fill: true,
    };
    let s = Surface::build(&spec, &mesh, opts).expect("surface");
    let nf = mesh.num_faces() as u64;
    let near = queries(&s, nf, 1_000_000, 0.02);
    let far = queries(&s, nf, 10_000, 0.2);
    let mut g = c.benchmark_group("project");
    g.sample_size(10);
    g.measurement_time(Duration::from_secs(20));
    g.bench_function("cc-12k/index", |b| {
        b.iter(|| black_box(ProjectionIndex::new(&s)))
    });
    s.projection_index();
    g.bench_function("cc-12k/1e6-points", |b| {
        b.iter(|| black_box(s.closest_points(&near).len()))
    });
    g.bench_function("cc-12k/1e4-far-points", |b| {
        b.iter(|| black_box(s.closest_points(&far).len()))
    });
    g.finish();
    let mut g = c.benchmark_group("measure");
    g.sample_size(10);
    g.bench_function("cc-12k", |b| {
        b.iter(|| black_box(measure(s.complex(), &MeasureOptions::default())))
    });
    g.finish();
}

criterion_group!(benches, project);
criterion_main!(benches);
