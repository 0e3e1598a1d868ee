//! fairsub against the two Rust subdivision crates a user would pick instead, in one process
//! (issue 49): `opensubdiv-rs` (a port of OpenSubdiv's Sdc/Vtr/Far) and `subdiv-kernels`
//! (stencil tables per level). Run by `bench/run_rust_peers.sh`.
//!
//! ```text
//! fairsub-rust-peers [FACES] [LEVELS] [REPS] [MARKDOWN]      # defaults 100k 3 1, none
//! ```
//!
//! With MARKDOWN (a file name), the check and the times are also written there as two Markdown
//! tables (`bench/run_rust_peers.sh` puts its generated header above them).
//!
//! Each mesh is built from the same flat arrays as `bench/meshes.rs` (the file is included):
//! two small closed smoke nets (a cube, valence 3; a triangular prism, a triangle next to quads)
//! and two closed nets of about FACES quads (the regular torus of `bench/run_peer.sh`, and
//! `quad-evs`, a triangle torus refined twice, with a valence-3 or -6 vertex in every 2 x 2
//! block). Each program refines it LEVELS times by Catmull-Clark from the flat arrays (mesh or
//! topology construction included), best of REPS turns (the programs take turns). fairsub runs
//! on all cores (rayon's global pool) and on a one-thread pool; both crates are single-threaded
//! (subdiv-kernels' `parallel` feature only adds the rayon dependency in 0.1.0).
//!
//! The refined points are checked against fairsub's: the numbering differs (OpenSubdiv numbers
//! face points, then edge points, then vertex points per level), so every peer point is matched
//! to fairsub's point with the nearest coordinates (both sets sorted by x, candidates within the
//! tolerance window), the match must be one to one, and the faces must then be the same (each
//! face as a cyclic sequence, compared as sorted lists). The tolerance is relative to the bounding
//! box diagonal: 1e-9 where every Catmull-Clark weight is a dyadic rational (the regular torus:
//! valence 4 only), 1e-6 on nets with other valences, because both crates take the weights as
//! `f32` (1/9 or 1/36 rounded to 24 bits: about 3e-8 relative per level), while fairsub's are
//! `f64`. The largest distance is printed either way.

#[path = "../../meshes.rs"]
mod meshes;

use fairsub::PolyMesh;
use fairsub::geom::Point;
use fairsub::schemes;
use std::collections::HashMap;
use std::num::NonZeroU8;
use std::time::Instant;

type Res<T> = Result<T, Box<dyn std::error::Error + Send + Sync>>;

/// A mesh as flat arrays, the input all three programs start from.
struct Flat {
    name: String,
    points: Vec<Point>,
    face_start: Vec<u32>,
    corners: Vec<u32>,
    /// Relative tolerance of the point check (see the module comment).
    tol: f64,
}

/// A refined mesh: points and faces (flat).
struct Refined {
    points: Vec<Point>,
    face_start: Vec<u32>,
    corners: Vec<u32>,
}

fn main() {
    if let Err(e) = run() {
        eprintln!("error: {e}");
        std::process::exit(1);
    }
}

fn run() -> Res<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let faces =
        meshes::parse_count(args.first().map_or("100k", |s| s.as_str())).ok_or("bad face count")?;
    let levels: usize = args.get(1).map_or(Ok(3), |s| s.parse())?;
    let reps: usize = args.get(2).map_or(Ok(1), |s| s.parse())?;
    let markdown = args.get(3);
    if !(1..=6).contains(&levels) {
        return Err("LEVELS must be 1 to 6".into());
    }
    let one = rayon::ThreadPoolBuilder::new().num_threads(1).build()?;

    let nets = vec![cube(), prism(), torus(faces), quad_evs(faces)?];
    // Warm-up (rayon's pools start, first-touch allocations), not timed.
    run_fairsub(&nets[0], levels)?;
    one.install(|| run_fairsub(&nets[0], levels))?;
    let mut rows = Vec::new();
    let mut checks = Vec::new();
    for net in &nets {
        let (mut t_fs, mut t_fs1, mut t_osd, mut t_sk) = (f64::MAX, f64::MAX, f64::MAX, f64::MAX);
        let mut outs = None;
        for _ in 0..reps.max(1) {
            let (a, t) = timed(|| run_fairsub(net, levels))?;
            t_fs = t_fs.min(t);
            let (_, t) = one.install(|| timed(|| run_fairsub(net, levels)))?;
            t_fs1 = t_fs1.min(t);
            let (b, t) = timed(|| run_opensubdiv_rs(net, levels))?;
            t_osd = t_osd.min(t);
            let (c, t) = timed(|| run_subdiv_kernels(net, levels))?;
            t_sk = t_sk.min(t);
            outs = Some((a, b, c));
        }
        let (a, b, c) = outs.expect("at least one turn");
        let d_osd =
            check(&a, &b, net.tol).map_err(|e| format!("{}: opensubdiv-rs: {e}", net.name))?;
        let d_sk =
            check(&a, &c, net.tol).map_err(|e| format!("{}: subdiv-kernels: {e}", net.name))?;
        println!(
            "{}: {} vertices, {} faces at level {levels}; largest distance / diagonal: \
             opensubdiv-rs {d_osd:.2e}, subdiv-kernels {d_sk:.2e} (tolerance {:.0e}): equal",
            net.name,
            a.points.len(),
            a.face_start.len() - 1,
            net.tol
        );
        checks.push(format!(
            "| {} | {d_osd:.1e} | {d_sk:.1e} | {:.0e} |",
            net.name, net.tol
        ));
        rows.push((net.name.clone(), t_fs, t_fs1, t_osd, t_sk));
    }
    println!();
    println!(
        "Catmull-Clark to level {levels}, in process, from flat arrays, best of {reps} (milliseconds)"
    );
    println!(
        "{:<28} {:>10} {:>10} {:>14} {:>14} {:>10} {:>10}",
        "mesh", "fairsub", "fairsub 1t", "opensubdiv-rs", "subdiv-kernels", "osd-rs/fs", "sk/fs"
    );
    let threads = rayon::current_num_threads();
    let mut md = format!(
        "| mesh (Catmull-Clark to level {levels}) | opensubdiv-rs: largest distance / diagonal \
         | subdiv-kernels | tolerance |\n| --- | --- | --- | --- |\n{}\n\n\
         | mesh: milliseconds, best of {reps} | fairsub ({threads} threads) | fairsub (1 thread) \
         | opensubdiv-rs | subdiv-kernels | opensubdiv-rs / fairsub | subdiv-kernels / fairsub |\n\
         | --- | --- | --- | --- | --- | --- | --- |\n",
        checks.join("\n")
    );
    for (name, fs, fs1, osd, sk) in rows {
        md.push_str(&format!(
            "| {name} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1}x | {:.1}x |\n",
            fs * 1e3,
            fs1 * 1e3,
            osd * 1e3,
            sk * 1e3,
            osd / fs,
            sk / fs
        ));
        println!(
            "{name:<28} {:>10.1} {:>10.1} {:>14.1} {:>14.1} {:>9.1}x {:>9.1}x",
            fs * 1e3,
            fs1 * 1e3,
            osd * 1e3,
            sk * 1e3,
            osd / fs,
            sk / fs
        );
    }
    println!("ratios: the peer's time over fairsub's on all cores ({threads} threads)");
    if let Some(path) = markdown {
        std::fs::write(path, md)?;
    }
    Ok(())
}

fn timed<T>(f: impl FnOnce() -> Res<T>) -> Res<(T, f64)> {
    let t0 = Instant::now();
    let r = f()?;
    Ok((r, t0.elapsed().as_secs_f64()))
}

// --- the nets ---------------------------------------------------------------------------------

fn flat(name: &str, points: Vec<Point>, faces: &[&[u32]], tol: f64) -> Flat {
    let mut face_start = vec![0];
    let mut corners = Vec::new();
    for f in faces {
        corners.extend_from_slice(f);
        face_start.push(corners.len() as u32);
    }
    Flat {
        name: name.into(),
        points,
        face_start,
        corners,
        tol,
    }
}

fn cube() -> Flat {
    let p = (0..8)
        .map(|i| [(i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64])
        .collect();
    let f: [&[u32]; 6] = [
        &[0, 2, 3, 1],
        &[4, 5, 7, 6],
        &[0, 1, 5, 4],
        &[2, 6, 7, 3],
        &[0, 4, 6, 2],
        &[1, 3, 7, 5],
    ];
    flat("smoke: cube", p, &f, 1e-6)
}

fn prism() -> Flat {
    let s = 3f64.sqrt() / 2.0;
    let p = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.5, s, 0.0],
        [0.0, 0.0, 1.5],
        [1.0, 0.0, 1.5],
        [0.5, s, 1.5],
    ];
    let f: [&[u32]; 5] = [
        &[0, 2, 1],
        &[3, 4, 5],
        &[0, 1, 4, 3],
        &[1, 2, 5, 4],
        &[2, 0, 3, 5],
    ];
    flat("smoke: triangular prism", p, &f, 1e-6)
}

fn torus(faces: usize) -> Flat {
    let (m, n) = meshes::torus_dims(faces);
    let (points, face_start, corners) = meshes::quad_torus_arrays(m, n);
    Flat {
        name: format!("quad torus, {} quads", m * n),
        points,
        face_start,
        corners,
        tol: 1e-9,
    }
}

fn quad_evs(faces: usize) -> Res<Flat> {
    // As `fairsub-bench gen quad-evs`: 12 quads per triangle after two steps.
    let (m, n) = meshes::torus_dims(faces / 24);
    let (p, fs, c) = meshes::tri_torus_arrays(m, n);
    let tri = PolyMesh::from_flat(p, fs, c)?;
    let cc = schemes::by_name("catmull-clark")?;
    let q = schemes::refine_levels(cc.as_ref(), &tri, 2, |_| {})?;
    Ok(Flat {
        name: format!("quad-evs, {} quads", q.num_faces()),
        points: q.positions().to_vec(),
        face_start: q.face_starts().to_vec(),
        corners: q.corners().to_vec(),
        tol: 1e-6,
    })
}

// --- the three programs -----------------------------------------------------------------------

fn run_fairsub(net: &Flat, levels: usize) -> Res<Refined> {
    let mesh = PolyMesh::from_flat(
        net.points.clone(),
        net.face_start.clone(),
        net.corners.clone(),
    )?;
    let cc = schemes::by_name("catmull-clark")?;
    let fine = schemes::refine_levels(cc.as_ref(), &mesh, levels, |_| {})?;
    Ok(Refined {
        points: fine.positions().to_vec(),
        face_start: fine.face_starts().to_vec(),
        corners: fine.corners().to_vec(),
    })
}

fn run_opensubdiv_rs(net: &Flat, levels: usize) -> Res<Refined> {
    use opensubdiv_rs::far::{
        PrimvarRefiner, TopologyDescriptor, TopologyRefinerFactory, UniformOptions,
    };
    use opensubdiv_rs::sdc;
    let sizes: Vec<usize> = net
        .face_start
        .windows(2)
        .map(|w| (w[1] - w[0]) as usize)
        .collect();
    let desc = TopologyDescriptor::new(net.points.len(), &sizes, &net.corners);
    // The nets are closed: the boundary rule plays no part.
    let mut refiner = TopologyRefinerFactory::create(
        desc,
        sdc::SchemeType::Catmark,
        sdc::Options::default()
            .with_vtx_boundary_interpolation(sdc::VtxBoundaryInterpolation::EdgeAndCorner),
    )
    .map_err(|e| format!("{e:?}"))?;
    refiner.refine_uniform(UniformOptions::new(levels));
    let primvar = PrimvarRefiner::new(&refiner);
    let mut pts = net.points.clone();
    for l in 1..=levels {
        let mut next = vec![[0.0f64; 3]; refiner.level(l).num_vertices()];
        primvar.interpolate(l, &pts, &mut next);
        pts = next;
    }
    let last = refiner.level(levels);
    let mut face_start = vec![0u32];
    let mut corners = Vec::with_capacity(4 * last.num_faces());
    for f in 0..last.num_faces() {
        corners.extend_from_slice(last.face_vertices(f));
        face_start.push(corners.len() as u32);
    }
    Ok(Refined {
        points: pts,
        face_start,
        corners,
    })
}

fn run_subdiv_kernels(net: &Flat, levels: usize) -> Res<Refined> {
    use subdiv_kernels::topology::Mesh;
    use subdiv_kernels::{Refiner, Scheme, SchemeOptions, UniformRefine};
    // The crate takes the edge list as input: each undirected edge once, in first-seen order.
    let mut seen: HashMap<(u32, u32), ()> = HashMap::with_capacity(net.corners.len());
    let mut edges = Vec::with_capacity(net.corners.len() / 2 + 1);
    for w in net.face_start.windows(2) {
        let f = &net.corners[w[0] as usize..w[1] as usize];
        for (i, &a) in f.iter().enumerate() {
            let b = f[(i + 1) % f.len()];
            let key = (a.min(b), a.max(b));
            if seen.insert(key, ()).is_none() {
                edges.push([key.0, key.1]);
            }
        }
    }
    let mesh = Mesh {
        vertex_count: net.points.len() as u32,
        face_vertex_counts: net.face_start.windows(2).map(|w| w[1] - w[0]).collect(),
        face_vertex_indices: net.corners.clone(),
        edge_creases: vec![0.0; edges.len()],
        edge_vertices: edges,
        vertex_corners: vec![0.0; net.points.len()],
    };
    let refiner = Refiner::new(mesh, Scheme::CatmullClark, SchemeOptions::default())
        .map_err(|e| format!("{e:?}"))?;
    let lv = NonZeroU8::new(levels as u8).ok_or("levels")?;
    let result = refiner
        .refine_uniform(&UniformRefine::from(lv))
        .map_err(|e| format!("{e:?}"))?;
    let points = result.interpolate(&net.points);
    let mut face_start = vec![0u32];
    let mut acc = 0u32;
    for &n in &result.topology.face_vertex_counts {
        acc += n;
        face_start.push(acc);
    }
    Ok(Refined {
        points,
        face_start,
        corners: result.topology.face_vertex_indices,
    })
}

// --- the check --------------------------------------------------------------------------------

/// Matches every point of `b` to the point of `a` with the nearest coordinates, checks the match
/// is one to one with every distance within `tol` times `a`'s bounding box diagonal, and that
/// the faces are then the same; returns the largest distance over the diagonal.
fn check(a: &Refined, b: &Refined, tol: f64) -> Res<f64> {
    if a.points.len() != b.points.len() || a.face_start.len() != b.face_start.len() {
        return Err(format!(
            "{} vertices and {} faces against fairsub's {} and {}",
            b.points.len(),
            b.face_start.len() - 1,
            a.points.len(),
            a.face_start.len() - 1
        )
        .into());
    }
    let (mut lo, mut hi) = ([f64::MAX; 3], [f64::MIN; 3]);
    for p in &a.points {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let diag = ((0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>()).sqrt();
    let eps = tol * diag;
    let mut order: Vec<u32> = (0..a.points.len() as u32).collect();
    order.sort_unstable_by(|&i, &j| a.points[i as usize][0].total_cmp(&a.points[j as usize][0]));
    let xs: Vec<f64> = order.iter().map(|&i| a.points[i as usize][0]).collect();
    let mut map = vec![u32::MAX; b.points.len()];
    let mut taken = vec![false; a.points.len()];
    let mut worst = 0.0f64;
    for (bi, q) in b.points.iter().enumerate() {
        let start = xs.partition_point(|&x| x < q[0] - eps);
        let mut best = (f64::MAX, u32::MAX);
        for (&x, &ai) in xs[start..].iter().zip(&order[start..]) {
            if x > q[0] + eps {
                break;
            }
            let p = a.points[ai as usize];
            let d = ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt();
            if d < best.0 {
                best = (d, ai);
            }
        }
        if best.0 > eps {
            return Err(
                format!("point {bi} {q:?} has no point of fairsub's within {tol:e}").into(),
            );
        }
        if std::mem::replace(&mut taken[best.1 as usize], true) {
            return Err(format!("point {bi}: the matching is not one to one").into());
        }
        map[bi] = best.1;
        worst = worst.max(best.0);
    }
    let canon = |f: Vec<u32>| {
        let k = (0..f.len()).min_by_key(|&i| f[i]).unwrap_or(0);
        let mut g = f[k..].to_vec();
        g.extend_from_slice(&f[..k]);
        g
    };
    let faces = |r: &Refined, m: Option<&[u32]>| {
        let mut v: Vec<Vec<u32>> = r
            .face_start
            .windows(2)
            .map(|w| {
                let f = &r.corners[w[0] as usize..w[1] as usize];
                canon(f.iter().map(|&i| m.map_or(i, |m| m[i as usize])).collect())
            })
            .collect();
        v.sort_unstable();
        v
    };
    if faces(a, None) != faces(b, Some(&map)) {
        return Err("the points match but the faces differ".into());
    }
    Ok(worst / diag)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn refined(net: &Flat) -> Refined {
        run_fairsub(net, 1).expect("the cube refines")
    }

    /// The check passes on a renumbered copy and fails on a moved point or a changed face.
    #[test]
    fn check_can_fail() {
        let a = refined(&cube());
        let n = a.points.len() as u32;
        // Renumber: reverse the vertex order.
        let rev = |i: u32| n - 1 - i;
        let b = Refined {
            points: a.points.iter().rev().copied().collect(),
            face_start: a.face_start.clone(),
            corners: a.corners.iter().map(|&i| rev(i)).collect(),
        };
        assert_eq!(check(&a, &b, 1e-9).expect("same mesh"), 0.0);
        let mut moved = Refined {
            points: b.points.clone(),
            ..b
        };
        moved.points[5][1] += 1e-6;
        assert!(check(&a, &moved, 1e-9).is_err());
        let mut flipped = Refined {
            points: a.points.clone(),
            face_start: a.face_start.clone(),
            corners: a.corners.clone(),
        };
        flipped.corners.swap(0, 1);
        assert!(check(&a, &flipped, 1e-9).is_err());
    }
}
