//! Evaluation at `(face, u, v)` (`surface::eval`): 10^6 points of a 12k-face Catmull-Clark
//! net with extraordinary vertices (issue 17's target: at most 1 s).
//!
//! - `eval/cc-12k/build`: the surface with 2 rings, the caps and the per-face cell index;
//! - `eval/cc-12k/1e6-points`: 10^6 evaluations (point, derivatives to second order, normal,
//!   curvatures) at random parameters of random faces, one after another on one thread;
//! - `eval/cc-12k/1e6-points-parallel`: the same through `Surface::evaluate_many` (rayon).
//!
//! The net is the gallery's `torus-evs` (48 quads, two vertices of valence 3 and two of valence
//! 5) refined four times with Catmull-Clark: 12288 quads, the extraordinary vertices kept.

use criterion::{Criterion, criterion_group, criterion_main};
use fairsub::schemes::registry::{ids, registry};
use fairsub::schemes::{CatmullClark, refine_levels};
use fairsub::surface::ComplexOptions;
use fairsub::surface::eval::Surface;
use std::hint::black_box;
use std::time::Duration;

fn eval(c: &mut Criterion) {
    let net = fairsub::mesh::nets::torus_with_evs();
    let mesh = refine_levels(&CatmullClark, &net, 4, |_| {}).expect("refines");
    let spec = registry()
        .lookup(ids::CATMULL_CLARK.name())
        .expect("catmull-clark");
    let opts = ComplexOptions {
        rings: 2,
        fill: true,
    };
    let mut g = c.benchmark_group("eval");
    g.bench_function("cc-12k/build", |b| {
        b.iter(|| black_box(Surface::build(&spec, &mesh, opts).expect("surface")))
    });
    let s = Surface::build(&spec, &mesh, opts).expect("surface");
    let nf = mesh.num_faces() as u64;
    let mut x = 0x2545_f491_4f6c_dd1du64;
    let mut next = move || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        x
    };
    let unit = |r: u64| (r >> 11) as f64 / (1u64 << 53) as f64;
    let pts: Vec<(u32, f64, f64)> = (0..1_000_000)
        .map(|_| ((next() % nf) as u32, unit(next()), unit(next())))
        .collect();
    g.bench_function("cc-12k/1e6-points", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for &(f, u, v) in &pts {
                acc += s.evaluate(f, u, v).expect("in the domain").point[0];
            }
            black_box(acc)
        })
    });
    g.bench_function("cc-12k/1e6-points-parallel", |b| {
        b.iter(|| black_box(s.evaluate_many(&pts).len()))
    });
    g.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(5));
    targets = eval
}
criterion_main!(benches);
