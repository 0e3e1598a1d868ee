//! Limit positions, Bezier conversion, tessellation, and the cost of an EG cap against a
//! Catmull-Clark cap with the same rings.
//!
//! - `limit/*`: building the limit-position stencils of every vertex of a 100k-face torus and
//!   applying them (Catmull-Clark on quads, Loop on triangles);
//! - `bezier/cc-10k`: the Catmull-Clark patch complex of a regular 10k-quad torus (one bi-3
//!   B-spline to Bezier conversion per face);
//! - `tessellate/cc-10k-n8`: that complex sampled 8 x 8 per patch into a watertight mesh;
//! - `caps/{eg,cc}/valence-n`: the whole surface of the gallery's convex c-net of valence
//!   `n` (one extraordinary vertex, three rings of quads) with 8 rings and the fill. Both
//!   complexes have the same regular patches and the same number of ring and fill patches, so
//!   the ratio of the two times is the cost of an EG cap against a Catmull-Clark cap.

#[path = "../bench/meshes.rs"]
mod meshes;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use fairsub::gallery::{CnetShape, cnet};
use fairsub::schemes::catmull_clark::surface::catmull_clark_complex;
use fairsub::schemes::eg::surface::{EgOptions, eg_complex};
use fairsub::schemes::{CatmullClark, Loop, Scheme};
use fairsub::surface::ComplexOptions as CcComplexOptions;
use fairsub::surface::Fallback;
use fairsub::surface::tessellate::tessellate;
use std::hint::black_box;
use std::time::Duration;

fn limit(c: &mut Criterion) {
    let quads = meshes::quad_torus(100_000);
    let tris = meshes::tri_torus(100_000);
    let _ = (quads.num_edges(), tris.num_edges());
    let mut g = c.benchmark_group("limit");
    g.bench_function("cc-100k/build", |b| {
        b.iter(|| black_box(CatmullClark::limit_stencils(&quads)))
    });
    let t = CatmullClark::limit_stencils(&quads);
    let mut out = vec![[0.0; 3]; t.num_rows()];
    g.bench_function("cc-100k/apply", |b| {
        b.iter(|| t.apply_into(black_box(quads.positions()), &mut out))
    });
    g.bench_function("loop-100k/build", |b| {
        b.iter(|| black_box(Loop.limit_stencils(&tris).expect("triangles")))
    });
    let t = Loop.limit_stencils(&tris).expect("triangles");
    let mut out = vec![[0.0; 3]; t.num_rows()];
    g.bench_function("loop-100k/apply", |b| {
        b.iter(|| t.apply_into(black_box(tris.positions()), &mut out))
    });
    g.finish();
}

fn patches(c: &mut Criterion) {
    let torus = meshes::quad_torus(10_000);
    let opts = CcComplexOptions {
        rings: 6,
        fill: true,
    };
    let mut g = c.benchmark_group("bezier");
    g.bench_function("cc-10k", |b| {
        b.iter(|| black_box(catmull_clark_complex(&torus, opts, |_| {}).expect("ok")))
    });
    g.finish();
    let complex = catmull_clark_complex(&torus, opts, |_| {}).expect("ok");
    let mut g = c.benchmark_group("tessellate");
    g.bench_function("cc-10k-n8", |b| {
        b.iter(|| black_box(tessellate(&complex, 8)))
    });
    g.finish();
}

fn caps(c: &mut Criterion) {
    let rings = 8;
    let mut g = c.benchmark_group("caps");
    for n in [3, 5] {
        let net = cnet(n, CnetShape::Convex, 3);
        let eg = EgOptions {
            rings,
            fill: true,
            fallback: Fallback::Error,
        };
        let cc = CcComplexOptions { rings, fill: true };
        g.bench_with_input(BenchmarkId::new("eg", n), &net, |b, net| {
            b.iter(|| black_box(eg_complex(net, eg, |_| {}).expect("EG has rules")))
        });
        g.bench_with_input(BenchmarkId::new("cc", n), &net, |b, net| {
            b.iter(|| black_box(catmull_clark_complex(net, cc, |_| {}).expect("ok")))
        });
    }
    g.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .sample_size(10)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(1));
    targets = limit, patches, caps
}
criterion_main!(benches);
