//! Throughput on large inputs: the measurements that used to be `#[ignore]` timing tests (the
//! project measures performance in benchmarks, never in tests).
//!
//! - `ply/write-3x1500^2`: writing about 270 MB of binary PLY (three 1500 x 1500 quad grids),
//!   then reading it back and validating the same arrays as a `PolyMesh`;
//! - `render/highlight-1024-1-thread`: a 1024 x 1024 highlight-line picture (2 x 2
//!   supersampling) of the default net's 10-ring Catmull-Clark surface on one thread, and its
//!   PNG encoding;
//! - `bezier/{derivatives,normal,eval}`: per-call cost of the hot evaluators of a bi-3 patch;
//! - `adjacency/100k-t-junctions`: shared boundaries of a 300 x 300 bilinear grid with every
//!   seventh patch split into quarters (2:1 T-junctions), about 10^5 patches;
//! - `tessellate/torus-90k-n4`: a closed torus of 300 x 300 bi-3 patches with every seventh
//!   split into quarters, tessellated 4 x 4 per patch into a watertight mesh.
//!
//! `cargo bench --bench large` (one group: `cargo bench --bench large -- adjacency`).

#[path = "../bench/meshes.rs"]
mod meshes;

use criterion::{Criterion, criterion_group, criterion_main};
use fairsub::bezier::BezierPatch;
use fairsub::io::{self, MeshFormat};
use fairsub::mesh::PolyMesh;
use fairsub::render::{self, Mode, RenderOptions, Scene};
use fairsub::schemes::catmull_clark::surface::catmull_clark_complex;
use fairsub::surface::adjacency::shared_boundaries;
use fairsub::surface::tessellate::tessellate;
use fairsub::surface::{ComplexOptions, PatchComplex, Provenance};
use std::hint::black_box;
use std::time::Duration;

/// `copies` stacked `n x n` quad grids as flat arrays (positions, face starts, corners).
fn stacked_grids(n: usize, copies: usize) -> (Vec<[f64; 3]>, Vec<u32>, Vec<u32>) {
    let w = n as u32 + 1;
    let mut pos = Vec::with_capacity((n + 1) * (n + 1) * copies);
    let mut starts = vec![0u32];
    let mut corners = Vec::with_capacity(4 * n * n * copies);
    for c in 0..copies {
        let base = pos.len() as u32;
        for i in 0..=n {
            for j in 0..=n {
                pos.push([i as f64, j as f64, ((i * j) as f64).sin() + c as f64]);
            }
        }
        for i in 0..n {
            for j in 0..n {
                let v = base + (i * (n + 1) + j) as u32;
                corners.extend_from_slice(&[v, v + w, v + w + 1, v + 1]);
                starts.push(corners.len() as u32);
            }
        }
    }
    (pos, starts, corners)
}

fn ply(c: &mut Criterion) {
    let (pos, starts, corners) = stacked_grids(1500, 3);
    let dir = std::env::temp_dir().join(format!("fairsub-bench-large-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let p = dir.join("big.ply");
    let mut g = c.benchmark_group("ply");
    g.sample_size(10).measurement_time(Duration::from_secs(30));
    g.bench_function("write-3x1500^2", |b| {
        b.iter(|| {
            io::write_polygons(&p, &pos, &starts, &corners, MeshFormat::PlyBinary).expect("write")
        })
    });
    g.bench_function("read-3x1500^2", |b| {
        b.iter(|| black_box(io::read_mesh(&p).expect("read").mesh.num_faces()))
    });
    g.bench_function("validate-3x1500^2", |b| {
        b.iter(|| {
            let m = PolyMesh::from_flat(pos.clone(), starts.clone(), corners.clone());
            black_box(m.expect("valid").num_faces())
        })
    });
    g.finish();
    let _ = std::fs::remove_dir_all(dir);
}

fn picture(c: &mut Criterion) {
    let net = fairsub::gallery::default_net();
    let complex = fairsub::surface::complex(
        "catmull-clark",
        &net,
        ComplexOptions {
            rings: 10,
            fill: true,
        },
        |_| {},
    )
    .expect("complex");
    let scene = Scene::patches(complex, Some(net));
    let o = RenderOptions {
        width: 1024,
        height: 1024,
        supersample: 2,
        mode: Mode::Highlight,
        legend: false,
        ..RenderOptions::default()
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("pool");
    let mut g = c.benchmark_group("render");
    g.sample_size(10).measurement_time(Duration::from_secs(20));
    g.bench_function("highlight-1024-1-thread", |b| {
        b.iter(|| pool.install(|| black_box(render::render(&scene, &o).expect("render"))))
    });
    let out = render::render(&scene, &o).expect("render");
    g.bench_function("png-1024", |b| {
        b.iter(|| black_box(out.image.to_png().expect("png").len()))
    });
    g.finish();
}

fn evaluators(c: &mut Criterion) {
    let mut state = 3u64;
    let mut next = || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((state >> 11) as f64) / ((1u64 << 53) as f64) * 2.0 - 1.0
    };
    let p = BezierPatch::from_fn(3, 3, |_, _| [next(), next(), next()]);
    let us: Vec<f64> = (0..1000).map(|k| k as f64 / 1000.0).collect();
    let mut g = c.benchmark_group("bezier");
    g.bench_function("derivatives-1000", |b| {
        b.iter(|| {
            us.iter()
                .map(|&u| p.derivatives(u, 0.3).duv[0])
                .sum::<f64>()
        })
    });
    g.bench_function("normal-1000", |b| {
        b.iter(|| us.iter().map(|&u| p.normal(u, 0.3)[0]).sum::<f64>())
    });
    g.bench_function("eval-1000", |b| {
        b.iter(|| us.iter().map(|&u| p.eval(u, 0.3)[0]).sum::<f64>())
    });
    g.finish();
}

/// The four quarters of `p` (split at `u = v = 1/2`).
fn quarters(p: &BezierPatch) -> [BezierPatch; 4] {
    let (a, b) = p.split_u(0.5);
    let (a0, a1) = a.split_v(0.5);
    let (b0, b1) = b.split_v(0.5);
    [a0, a1, b0, b1]
}

/// `c` with every seventh patch replaced by its quarters (appended at the end).
fn split_every_seventh(c: &PatchComplex) -> PatchComplex {
    let mut out = PatchComplex::new();
    for (k, (p, prov)) in c.patches.iter().zip(&c.provenance).enumerate() {
        if k % 7 != 0 {
            out.push(p.clone(), *prov);
        }
    }
    for k in (0..c.len()).step_by(7) {
        for q in quarters(&c.patches[k]) {
            out.push(q, c.provenance[k]);
        }
    }
    out
}

fn adjacency(c: &mut Criterion) {
    let m = 300;
    let mut grid = PatchComplex::new();
    for i in 0..m {
        for j in 0..m {
            let q = |a: usize, b: usize| [(i + a) as f64, (j + b) as f64, 0.0];
            grid.push(
                BezierPatch::new(1, 1, vec![q(0, 0), q(0, 1), q(1, 0), q(1, 1)]),
                Provenance::Unknown,
            );
        }
    }
    let split = split_every_seventh(&grid);
    let mut g = c.benchmark_group("adjacency");
    g.sample_size(10).measurement_time(Duration::from_secs(20));
    g.bench_function("100k-t-junctions", |b| {
        b.iter(|| black_box(shared_boundaries(&split, 1e-9).len()))
    });
    g.finish();
}

fn tessellation(c: &mut Criterion) {
    // The regular Catmull-Clark surface of a 300 x 300 quad torus: 90k bi-3 patches.
    let torus = meshes::quad_torus(90_000);
    let opts = ComplexOptions {
        rings: 0,
        fill: true,
    };
    let complex = catmull_clark_complex(&torus, opts, |_| {}).expect("complex");
    let split = split_every_seventh(&complex);
    let mut g = c.benchmark_group("tessellate");
    g.sample_size(10).measurement_time(Duration::from_secs(20));
    g.bench_function("torus-90k-n4", |b| {
        b.iter(|| black_box(tessellate(&split, 4).num_triangles()))
    });
    g.finish();
}

criterion_group!(benches, ply, picture, evaluators, adjacency, tessellation);
criterion_main!(benches);
