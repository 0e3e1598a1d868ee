//! Uniform Catmull-Clark and Loop refinement of generated closed tori (1k to 1M input faces,
//! levels 1 to 4), split the way OpenSubdiv splits it:
//!
//! - `topology`: the connectivity of every level (faces, half-edges, edge numbering), from the
//!   input net (what `Far::TopologyRefiner::RefineUniform` does);
//! - `geometry`: the points of every level by the fused rule kernels, on the prebuilt levels
//!   (what `Far::PrimvarRefiner::Interpolate` does, level after level);
//! - `stencils`: one application of the precomputed table from the control points to the last
//!   level ([`fairsub::schemes::level_stencils`], the animation path; `Osd::CpuEvaluator`),
//!   plain and packed (`-packed`, [`PackedStencilTable`]);
//! - `one_shot`: [`fairsub::schemes::refine_levels`], topology and points together, as the
//!   `subdivide` command runs it.
//!
//! Sizes are capped so a run stays in minutes: a pair (input faces, level) is measured when the
//! result has at most about 4M faces (1k: levels 1-4, 10k: 1-4, 100k: 1-2, 1M: 1).
//! `cargo bench --bench refinement -- catmull-clark/topology` picks one group.

#[path = "../bench/meshes.rs"]
mod meshes;

use criterion::{BenchmarkId, Criterion, SamplingMode, criterion_group, criterion_main};
use fairsub::PolyMesh;
use fairsub::geom::Point;
use fairsub::schemes::{self, CatmullClark, Loop, Scheme};
use fairsub::stencil::PackedStencilTable;
use std::hint::black_box;
use std::time::Duration;

/// Input sizes (faces).
const SIZES: [usize; 4] = [1_000, 10_000, 100_000, 1_000_000];
/// Largest result measured (faces).
const MAX_RESULT: usize = 4_200_000;

/// The measured `(input faces, level)` pairs.
fn cases() -> Vec<(usize, usize)> {
    let mut v = Vec::new();
    for &n in &SIZES {
        for level in 1..=4 {
            if n << (2 * level) <= MAX_RESULT {
                v.push((n, level));
            }
        }
    }
    v
}

/// One scheme's kernels, behind one interface for the bench loops.
trait Kernel {
    fn name(&self) -> &'static str;
    fn mesh(&self, faces: usize) -> PolyMesh;
    fn scheme(&self) -> &dyn Scheme;
    /// Number of points of the child of `m`.
    fn child_points(&self, m: &PolyMesh) -> usize;
    fn points(&self, m: &PolyMesh, src: &[Point]) -> Vec<Point>;
    fn child(&self, m: &PolyMesh, positions: Vec<Point>) -> PolyMesh;
}

struct Cc;
struct Lp;

impl Kernel for Cc {
    fn name(&self) -> &'static str {
        "catmull-clark"
    }
    fn mesh(&self, faces: usize) -> PolyMesh {
        meshes::quad_torus(faces)
    }
    fn scheme(&self) -> &dyn Scheme {
        &CatmullClark
    }
    fn child_points(&self, m: &PolyMesh) -> usize {
        m.num_vertices() + m.num_edges() + m.num_faces()
    }
    fn points(&self, m: &PolyMesh, src: &[Point]) -> Vec<Point> {
        CatmullClark::refine_points(m, src)
    }
    fn child(&self, m: &PolyMesh, positions: Vec<Point>) -> PolyMesh {
        CatmullClark::child_mesh(m, positions)
    }
}

impl Kernel for Lp {
    fn name(&self) -> &'static str {
        "loop"
    }
    fn mesh(&self, faces: usize) -> PolyMesh {
        meshes::tri_torus(faces)
    }
    fn scheme(&self) -> &dyn Scheme {
        &Loop
    }
    fn child_points(&self, m: &PolyMesh) -> usize {
        m.num_vertices() + m.num_edges()
    }
    fn points(&self, m: &PolyMesh, src: &[Point]) -> Vec<Point> {
        Loop::refine_points(m, src).expect("triangles")
    }
    fn child(&self, m: &PolyMesh, positions: Vec<Point>) -> PolyMesh {
        Loop::child_mesh(m, positions).expect("triangles")
    }
}

/// The connectivity of `levels` levels (points left zero: a fresh zeroed buffer costs no work
/// per point), edges numbered on every level.
fn topology(k: &dyn Kernel, mesh: &PolyMesh, levels: usize) -> Vec<PolyMesh> {
    let mut out: Vec<PolyMesh> = Vec::with_capacity(levels);
    for _ in 0..levels {
        let parent = out.last().unwrap_or(mesh);
        let child = k.child(parent, vec![[0.0; 3]; k.child_points(parent)]);
        let _ = child.num_edges();
        out.push(child);
    }
    out
}

fn bench_scheme(c: &mut Criterion, k: &dyn Kernel) {
    let cases = cases();
    let meshes: Vec<(usize, PolyMesh)> = SIZES
        .iter()
        .map(|&n| {
            let m = k.mesh(n);
            let _ = m.num_edges();
            (n, m)
        })
        .collect();
    let input = |n: usize| &meshes.iter().find(|(s, _)| *s == n).expect("size").1;
    let id = |n: usize, level: usize| BenchmarkId::new(format!("{}k", n / 1000), level);

    let mut g = c.benchmark_group(format!("{}/topology", k.name()));
    // Equal iterations per sample: a large case runs 10 times, not the 55 of linear sampling.
    g.sampling_mode(SamplingMode::Flat);
    for &(n, level) in &cases {
        g.bench_with_input(id(n, level), &level, |b, &level| {
            b.iter(|| black_box(topology(k, input(n), level)))
        });
    }
    g.finish();

    let mut g = c.benchmark_group(format!("{}/geometry", k.name()));
    // Equal iterations per sample: a large case runs 10 times, not the 55 of linear sampling.
    g.sampling_mode(SamplingMode::Flat);
    for &(n, level) in &cases {
        let mesh = input(n);
        // Levels 0..level-1 prebuilt; the measured loop computes the points of levels 1..level.
        let mut parents = vec![mesh.clone()];
        parents.extend(topology(k, mesh, level - 1));
        g.bench_with_input(id(n, level), &level, |b, _| {
            b.iter(|| {
                let mut p = k.points(&parents[0], parents[0].positions());
                for m in &parents[1..] {
                    p = k.points(m, &p);
                }
                black_box(p)
            })
        });
    }
    g.finish();

    let mut g = c.benchmark_group(format!("{}/stencils", k.name()));
    // Equal iterations per sample: a large case runs 10 times, not the 55 of linear sampling.
    g.sampling_mode(SamplingMode::Flat);
    for &(n, level) in &cases {
        // Tables of the largest cases would need gigabytes: keep to results of 1M faces.
        if n << (2 * level) > 1_100_000 {
            continue;
        }
        let mesh = input(n);
        let (_, table) = schemes::level_stencils(k.scheme(), mesh, level).expect("refines");
        let packed = PackedStencilTable::new(&table);
        let mut out = vec![[0.0; 3]; table.num_rows()];
        g.bench_with_input(id(n, level), &level, |b, _| {
            b.iter(|| table.apply_into(black_box(mesh.positions()), &mut out))
        });
        let packed_id = BenchmarkId::new(format!("{}k-packed", n / 1000), level);
        g.bench_with_input(packed_id, &level, |b, _| {
            b.iter(|| packed.apply_into(black_box(mesh.positions()), &mut out))
        });
    }
    g.finish();

    let mut g = c.benchmark_group(format!("{}/one_shot", k.name()));
    // Equal iterations per sample: a large case runs 10 times, not the 55 of linear sampling.
    g.sampling_mode(SamplingMode::Flat);
    for &(n, level) in &cases {
        g.bench_with_input(id(n, level), &level, |b, &level| {
            b.iter(|| {
                black_box(schemes::refine_levels(k.scheme(), input(n), level, |_| {}).expect("ok"))
            })
        });
    }
    g.finish();
}

fn refinement(c: &mut Criterion) {
    bench_scheme(c, &Cc);
    bench_scheme(c, &Lp);
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .sample_size(10)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(1));
    targets = refinement
}
criterion_main!(benches);
