//! The fairsub side of the OpenSubdiv comparison (`bench/run_peer.sh`), and a small toolbox for
//! it: generating the meshes, timing stencil re-application, comparing the two programs' outputs.
//!
//! ```text
//! fairsub-bench gen quad-torus|tri-torus|creased-quad-torus FACES OUT.obj
//! fairsub-bench phases IN.obj SCHEME LEVELS OUT.ply
//! fairsub-bench reapply IN.obj SCHEME LEVELS REPS
//! fairsub-bench compare A.ply B.ply
//! fairsub-bench caps VALENCE RINGS REPS
//! fairsub-bench patch-table IN.obj RINGS POINTS REPS OUT.bin
//! fairsub-bench compare-points A.bin B.bin
//! fairsub-bench complex IN.obj RINGS
//! fairsub-bench eval IN.obj RINGS POINTS REPS
//! ```
//!
//! - `gen` writes a closed torus of about FACES quads or triangles (`100k`, `1M`, ...);
//!   `creased-quad-torus` adds OpenSubdiv crease and corner tags (`meshes::torus_crease_tags`).
//! - `phases` runs the path of `fairsub subdivide` (read, refine, write) and prints each phase's
//!   time.
//! - `reapply` builds the factorized stencil table from the control points to the points of
//!   level LEVELS (the tables of each step, composed) and times its application to the control
//!   points, plain and packed ([`PackedStencilTable`]), on one thread and on two (minimum over
//!   REPS runs).
//! - `compare` checks that two binary PLY outputs describe the same refined mesh: counts,
//!   bounding boxes, the largest distance between each point and the nearest point of the other
//!   file, and, with vertices matched that way, the same faces.
//! - `caps` times the EG surface against the Catmull-Clark surface of the gallery's convex
//!   c-net of the given valence (one extraordinary vertex, three rings of quads), both with
//!   RINGS rings and the fill: the two complexes differ only in the cap, so the ratio of the
//!   times is the cost of an EG cap against a Catmull-Clark cap (minimum over REPS runs).
//!
//! - `patch-table` (the patch-table peer, `bench/run_patch_peer.sh`): builds the Catmull-Clark
//!   complex with RINGS rings and the fill alone, then the complex with its patch stencil table
//!   (`PatchTable::build_with`: tracked beside the points), re-applies the table,
//!   and evaluates the complex at the POINTS-point grid of [`grid_points`] (point, first and
//!   second derivatives, normal, curvatures), printing each phase's time (minimum over REPS);
//!   the evaluated points go to OUT.bin (little-endian f64 x y z per point) for comparison with
//!   OpenSubdiv's.
//! - `complex` times the Catmull-Clark complex alone (RINGS rings and the caps), the unit the
//!   patch table's build costs a multiple of.
//! - `compare-points` compares two such point files: how many points agree to 1e-9, 1e-6,
//!   1e-3, and the largest distance.
//! - `eval` builds the Catmull-Clark complex (RINGS rings and the caps) once and times
//!   `Surface::new` (the evaluation index), `Surface::evaluate_many` and
//!   `Surface::evaluate_into` (into a buffer allocated once) at the POINTS-point grid of
//!   [`grid_points`] (minimum over REPS; issue 17's target is 1 s for 10^6 points of a
//!   10k-face net). `RAYON_NUM_THREADS=1` for one thread.
//! - `gen quad-evs FACES OUT.obj`: a triangle torus refined twice by Catmull-Clark: about FACES
//!   quads with an extraordinary vertex (valence 3 or 6) in every 2 x 2 block of faces' corner.
//!
//! Run through cargo: `cargo run --release --example fairsub-bench -- gen quad-torus 100k t.obj`.

#[path = "meshes.rs"]
mod meshes;

use fairsub::geom::Point;
use fairsub::io::MeshFormat;
use fairsub::schemes;
use fairsub::stencil::PackedStencilTable;
use std::collections::HashMap;
use std::path::Path;
use std::time::Instant;

type Res<T> = Result<T, Box<dyn std::error::Error>>;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let a: Vec<&str> = args.iter().map(|s| s.as_str()).collect();
    let r = match a.as_slice() {
        ["gen", kind, faces, out] => gen_mesh(kind, faces, out),
        ["phases", input, scheme, levels, out] => phases(input, scheme, levels.parse().ok(), out),
        ["reapply", input, scheme, levels, reps] => {
            reapply(input, scheme, levels.parse().ok(), reps.parse().ok())
        }
        ["compare", x, y] => compare(x, y),
        ["caps", valence, rings, reps] => caps(valence.parse().ok(), rings.parse().ok(), reps),
        ["compare-points", a, b] => compare_points(a, b),
        ["complex", input, rings] => complex_only(input, rings.parse().ok()),
        ["eval", input, rings, points, reps] => {
            eval_only(input, rings.parse().ok(), points, reps.parse().ok())
        }
        ["patch-table", input, rings, points, reps, out] => {
            patch_table(input, rings.parse().ok(), points, reps.parse().ok(), out)
        }
        _ => Err(
            "usage: fairsub-bench gen quad-torus|tri-torus|creased-quad-torus FACES OUT.obj | phases IN SCHEME \
                  LEVELS OUT.ply | reapply IN SCHEME LEVELS REPS | compare A.ply B.ply | caps \
                  VALENCE RINGS REPS | patch-table IN.obj RINGS POINTS REPS OUT.bin | compare-points A B | complex IN.obj RINGS | eval IN.obj RINGS POINTS REPS"
                .into(),
        ),
    };
    if let Err(e) = r {
        eprintln!("fairsub-bench: {e}");
        std::process::exit(1);
    }
}

fn gen_mesh(kind: &str, faces: &str, out: &str) -> Res<()> {
    let faces = meshes::parse_count(faces).ok_or("bad face count")?;
    if kind == "quad-evs" {
        // 12 quads per triangle after two steps
        let (m, n) = meshes::torus_dims(faces / 24);
        let (p, fs, c) = meshes::tri_torus_arrays(m, n);
        let tri = fairsub::PolyMesh::from_flat(p, fs, c)?;
        let cc = schemes::by_name("catmull-clark")?;
        let q = schemes::refine_levels(cc.as_ref(), &tri, 2, |_| {})?;
        fairsub::io::write_mesh(Path::new(out), &q, MeshFormat::Obj)?;
        println!(
            "{out}: {} vertices, {} faces",
            q.num_vertices(),
            q.num_faces()
        );
        return Ok(());
    }
    let (m, n) = match kind {
        "quad-torus" | "creased-quad-torus" => meshes::torus_dims(faces),
        "tri-torus" => meshes::torus_dims(faces / 2),
        _ => return Err(format!("unknown mesh kind '{kind}'").into()),
    };
    let (p, fs, c) = if kind == "tri-torus" {
        meshes::tri_torus_arrays(m, n)
    } else {
        meshes::quad_torus_arrays(m, n)
    };
    fairsub::io::write_polygons(Path::new(out), &p, &fs, &c, MeshFormat::Obj)?;
    if kind == "creased-quad-torus" {
        use std::io::Write;
        let mut f = std::fs::OpenOptions::new().append(true).open(out)?;
        f.write_all(meshes::torus_crease_tags(m, n).as_bytes())?;
    }
    println!("{out}: {} vertices, {} faces", p.len(), fs.len() - 1);
    Ok(())
}

fn phases(input: &str, scheme: &str, levels: Option<usize>, out: &str) -> Res<()> {
    let levels = levels.ok_or("bad level count")?;
    let t0 = Instant::now();
    let mesh = fairsub::io::read_mesh(Path::new(input))?.mesh;
    let t1 = Instant::now();
    let s = schemes::by_name(scheme)?;
    let mut last = Instant::now();
    let fine = schemes::refine_levels(s.as_ref(), &mesh, levels, |l| {
        let now = Instant::now();
        println!("  level {l}: {:8.1} ms", (now - last).as_secs_f64() * 1e3);
        last = now;
    })?;
    let t2 = Instant::now();
    fairsub::io::write_mesh(Path::new(out), &fine, MeshFormat::PlyBinary)?;
    let t3 = Instant::now();
    let ms = |a: Instant, b: Instant| (b - a).as_secs_f64() * 1e3;
    println!(
        "read {:.1} ms, refine {:.1} ms, write {:.1} ms; {} vertices, {} faces",
        ms(t0, t1),
        ms(t1, t2),
        ms(t2, t3),
        fine.num_vertices(),
        fine.num_faces()
    );
    Ok(())
}

fn reapply(input: &str, scheme: &str, levels: Option<usize>, reps: Option<usize>) -> Res<()> {
    let (levels, reps) = (levels.ok_or("bad levels")?, reps.ok_or("bad reps")?.max(1));
    let mesh = fairsub::io::read_mesh(Path::new(input))?.mesh;
    let s = schemes::by_name(scheme)?;
    let t0 = Instant::now();
    if levels == 0 {
        return Err("LEVELS must be at least 1".into());
    }
    let (m, table) = schemes::level_stencils(s.as_ref(), &mesh, levels)?;
    let build = t0.elapsed().as_secs_f64();
    let t0 = Instant::now();
    let packed = PackedStencilTable::new(&table);
    let pack = t0.elapsed().as_secs_f64();
    let src: Vec<Point> = mesh.positions().to_vec();
    let mut out = vec![[0.0; 3]; table.num_rows()];
    // The four variants take turns, so a change of load on the machine hits them alike.
    let pools = [1, 2].map(|n| rayon::ThreadPoolBuilder::new().num_threads(n).build());
    let [one, two] = pools;
    let pools = [one?, two?];
    let mut best = [f64::INFINITY; 4];
    for _ in 0..reps {
        for (k, b) in best.iter_mut().enumerate() {
            let pool = &pools[k % 2];
            let t = Instant::now();
            if k < 2 {
                pool.install(|| table.apply_into(&src, &mut out));
            } else {
                pool.install(|| packed.apply_into(&src, &mut out));
            }
            *b = b.min(t.elapsed().as_secs_f64());
        }
    }
    let [t1, t2, p1, p2] = best;
    // The applied table must reproduce the refined points.
    let err = out
        .iter()
        .zip(m.positions())
        .map(|(a, b)| fairsub::geom::dist(*a, *b))
        .fold(0.0, f64::max);
    let rows = table.num_rows() as f64;
    println!(
        "stencils {} rows, {} entries ({:.1} per row), built in {:.0} ms; max deviation from \
         refinement {err:.1e}",
        table.num_rows(),
        table.num_entries(),
        table.num_entries() as f64 / rows,
        build * 1e3
    );
    println!(
        "packed: {} distinct weights stored for {} entries, {:.0} MB against {:.0} MB, packed in \
         {:.0} ms",
        packed.num_stored_weights(),
        table.num_entries(),
        packed.heap_bytes() as f64 / 1e6,
        table.heap_bytes() as f64 / 1e6,
        pack * 1e3
    );
    for (name, one, two) in [("table", t1, t2), ("packed", p1, p2)] {
        println!(
            "{name} apply 1 thread: {:.2} ms ({:.1} M points/s); 2 threads: {:.2} ms ({:.1} M \
             points/s, {:.2}x)",
            one * 1e3,
            rows / one / 1e6,
            two * 1e3,
            rows / two / 1e6,
            one / two
        );
    }
    Ok(())
}

/// Points and faces of a binary little-endian PLY with `double` coordinates and
/// `list uchar int` faces (what fairsub and the peer write).
struct Ply {
    points: Vec<Point>,
    faces: Vec<Vec<u32>>,
}

fn read_ply(path: &str) -> Res<Ply> {
    let bytes = std::fs::read(path)?;
    let end = bytes
        .windows(11)
        .position(|w| w == b"end_header\n")
        .ok_or("no PLY header")?
        + 11;
    let header = std::str::from_utf8(&bytes[..end])?;
    if !header.contains("binary_little_endian") {
        return Err(format!("{path}: not binary little endian").into());
    }
    let count = |el: &str| -> Res<usize> {
        let line = header
            .lines()
            .find(|l| l.starts_with(&format!("element {el} ")))
            .ok_or(format!("{path}: no element {el}"))?;
        Ok(line
            .split_whitespace()
            .nth(2)
            .ok_or("bad element line")?
            .parse()?)
    };
    let (nv, nf) = (count("vertex")?, count("face")?);
    let mut at = end;
    let f64_at = |at: &mut usize| -> f64 {
        let v = f64::from_le_bytes(bytes[*at..*at + 8].try_into().expect("8 bytes"));
        *at += 8;
        v
    };
    let mut points = Vec::with_capacity(nv);
    for _ in 0..nv {
        points.push([f64_at(&mut at), f64_at(&mut at), f64_at(&mut at)]);
    }
    let mut faces = Vec::with_capacity(nf);
    for _ in 0..nf {
        let k = bytes[at] as usize;
        at += 1;
        let f: Vec<u32> = (0..k)
            .map(|i| u32::from_le_bytes(bytes[at + 4 * i..at + 4 * i + 4].try_into().unwrap()))
            .collect();
        at += 4 * k;
        faces.push(f);
    }
    Ok(Ply { points, faces })
}

fn compare(a: &str, b: &str) -> Res<()> {
    let (pa, pb) = (read_ply(a)?, read_ply(b)?);
    println!(
        "{a}: {} vertices, {} faces; {b}: {} vertices, {} faces",
        pa.points.len(),
        pa.faces.len(),
        pb.points.len(),
        pb.faces.len()
    );
    if pa.points.len() != pb.points.len() || pa.faces.len() != pb.faces.len() {
        return Err("counts differ".into());
    }
    let bbox = |p: &[Point]| fairsub::geom::bounding_box(p.iter().copied()).expect("points");
    let (ba, bb) = (bbox(&pa.points), bbox(&pb.points));
    println!("bounding boxes: {ba:?} / {bb:?}");
    // Match every point of b to the nearest point of a through a hash grid.
    let diag = fairsub::geom::dist(ba.0, ba.1);
    let cell = diag * 1e-6;
    let key = |p: &Point| {
        [
            (p[0] / cell).floor() as i64,
            (p[1] / cell).floor() as i64,
            (p[2] / cell).floor() as i64,
        ]
    };
    let mut grid: HashMap<[i64; 3], Vec<u32>> = HashMap::with_capacity(pa.points.len());
    for (i, p) in pa.points.iter().enumerate() {
        grid.entry(key(p)).or_default().push(i as u32);
    }
    let mut map = vec![u32::MAX; pb.points.len()];
    let mut worst = 0.0f64;
    for (i, p) in pb.points.iter().enumerate() {
        let k = key(p);
        let mut best = (f64::INFINITY, u32::MAX);
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    if let Some(c) = grid.get(&[k[0] + dx, k[1] + dy, k[2] + dz]) {
                        for &j in c {
                            let d = fairsub::geom::dist(*p, pa.points[j as usize]);
                            if d < best.0 {
                                best = (d, j);
                            }
                        }
                    }
                }
            }
        }
        if best.1 == u32::MAX {
            return Err(format!("{b}: vertex {i} at {p:?} has no counterpart in {a}").into());
        }
        worst = worst.max(best.0);
        map[i] = best.1;
    }
    let mut hit = vec![false; pa.points.len()];
    for &j in &map {
        hit[j as usize] = true;
    }
    if hit.iter().any(|h| !h) {
        return Err("the nearest-point matching is not one to one".into());
    }
    println!(
        "largest distance between matched points: {worst:.3e} (bounding box diagonal {diag:.3})"
    );
    let canon = |f: &[u32]| {
        let k = (0..f.len()).min_by_key(|&i| f[i]).expect("non-empty face");
        let mut g = f[k..].to_vec();
        g.extend_from_slice(&f[..k]);
        g
    };
    let mut fa: Vec<Vec<u32>> = pa.faces.iter().map(|f| canon(f)).collect();
    let mut fb: Vec<Vec<u32>> = pb
        .faces
        .iter()
        .map(|f| canon(&f.iter().map(|&v| map[v as usize]).collect::<Vec<_>>()))
        .collect();
    fa.sort_unstable();
    fb.sort_unstable();
    if fa != fb {
        return Err("the faces differ".into());
    }
    println!("faces: identical (same vertex cycles, same orientation)");
    if worst > 1e-9 * diag.max(1.0) {
        return Err(format!("points differ by {worst:.3e}").into());
    }
    Ok(())
}

fn caps(valence: Option<usize>, rings: Option<usize>, reps: &str) -> Res<()> {
    use fairsub::gallery::{CnetShape, cnet};
    use fairsub::schemes::catmull_clark::surface::catmull_clark_complex;
    use fairsub::schemes::eg::surface::{EgOptions, eg_complex};
    use fairsub::surface::ComplexOptions as CcComplexOptions;
    use fairsub::surface::Fallback;
    let (n, rings) = (valence.ok_or("bad valence")?, rings.ok_or("bad rings")?);
    let reps: usize = reps.parse::<usize>()?.max(1);
    let net = cnet(n, CnetShape::Convex, 3);
    let best = |f: &dyn Fn() -> Res<usize>| -> Res<(f64, usize)> {
        let mut t_min = f64::INFINITY;
        let mut patches = 0;
        for _ in 0..reps {
            let t = Instant::now();
            patches = f()?;
            t_min = t_min.min(t.elapsed().as_secs_f64());
        }
        Ok((t_min, patches))
    };
    let eg_opts = EgOptions {
        rings,
        fill: true,
        fallback: Fallback::Error,
    };
    let cc_opts = CcComplexOptions { rings, fill: true };
    let (te, pe) = best(&|| Ok(eg_complex(&net, eg_opts, |_| {})?.0.len()))?;
    let (tc, pc) = best(&|| Ok(catmull_clark_complex(&net, cc_opts, |_| {})?.len()))?;
    println!(
        "valence {n}, {rings} rings + fill: EG {:.3} ms ({pe} patches), Catmull-Clark {:.3} ms \
         ({pc} patches), EG / CC = {:.2}",
        te * 1e3,
        tc * 1e3,
        te / tc
    );
    Ok(())
}

/// The evaluation grid of the patch-table peer (the same in `osd_peer patches`): per face in
/// order a `k x k` grid of parameters `((a + 1/2) / k, (b + 1/2) / k)`, `k` the smallest with
/// `faces k^2 >= count`, cut at `count` points.
fn grid_points(faces: usize, count: usize) -> Vec<(u32, f64, f64)> {
    let mut k = 1;
    while faces * k * k < count {
        k += 1;
    }
    let mut pts = Vec::with_capacity(count);
    'all: for f in 0..faces {
        for a in 0..k {
            for b in 0..k {
                if pts.len() == count {
                    break 'all;
                }
                let t = |x: usize| (x as f64 + 0.5) / k as f64;
                pts.push((f as u32, t(a), t(b)));
            }
        }
    }
    pts
}

fn eval_only(input: &str, rings: Option<usize>, points: &str, reps: Option<usize>) -> Res<()> {
    use fairsub::surface::{ComplexOptions, eval};
    let rings = rings.ok_or("bad ring count")?;
    let reps = reps.ok_or("bad reps")?.max(1);
    let count = meshes::parse_count(points).ok_or("bad point count")?;
    let mesh = fairsub::io::read_mesh(Path::new(input))?.mesh;
    let spec = fairsub::schemes::registry::registry().lookup("catmull-clark")?;
    let opts = ComplexOptions { rings, fill: true };
    let complex = fairsub::surface::build(&spec, &mesh, opts, &mut |_| {})?.complex;
    let pts = grid_points(mesh.num_faces(), count);
    let ms = |t: Instant| t.elapsed().as_secs_f64() * 1e3;
    let (mut index_ms, mut eval_ms, mut into_ms, mut failed) =
        (f64::INFINITY, f64::INFINITY, f64::INFINITY, 0);
    let mut out = vec![eval::Evaluation::default(); pts.len()];
    for _ in 0..reps {
        let t = Instant::now();
        let surface = eval::Surface::new(&mesh, complex.clone());
        index_ms = index_ms.min(ms(t));
        let t = Instant::now();
        let r = surface.evaluate_many(&pts);
        eval_ms = eval_ms.min(ms(t));
        failed = r.iter().filter(|e| e.is_err()).count();
        drop(r);
        let t = Instant::now();
        let r = surface.evaluate_into(&pts, &mut out);
        into_ms = into_ms.min(ms(t));
        if let Err((i, e)) = r {
            return Err(format!("point {i}: {e}").into());
        }
    }
    println!(
        "{} faces, {} patches: index {index_ms:.1} ms, evaluate {} points {eval_ms:.1} ms \
         ({failed} failed), evaluate_into a reused buffer {into_ms:.1} ms ({} threads)",
        mesh.num_faces(),
        complex.len(),
        pts.len(),
        rayon::current_num_threads()
    );
    Ok(())
}

fn patch_table(
    input: &str,
    rings: Option<usize>,
    points: &str,
    reps: Option<usize>,
    out: &str,
) -> Res<()> {
    use fairsub::surface::{ComplexOptions, eval, table::PatchTable};
    let rings = rings.ok_or("bad ring count")?;
    let reps = reps.ok_or("bad reps")?.max(1);
    let count = meshes::parse_count(points).ok_or("bad point count")?;
    let mesh = fairsub::io::read_mesh(Path::new(input))?.mesh;
    let spec = fairsub::schemes::registry::registry().lookup("catmull-clark")?;
    let opts = ComplexOptions { rings, fill: true };
    let construct = |m: &fairsub::PolyMesh| {
        fairsub::surface::build(&spec, m, opts, &mut |_| {}).map(|o| o.complex)
    };
    let ms = |t: Instant| t.elapsed().as_secs_f64() * 1e3;
    let (mut complex_ms, mut table_ms, mut index_ms) =
        (f64::INFINITY, f64::INFINITY, f64::INFINITY);
    let (mut apply_ms, mut eval_ms, mut into_ms) = (f64::INFINITY, f64::INFINITY, f64::INFINITY);
    let mut reapply_ms = f64::INFINITY;
    let pts = grid_points(mesh.num_faces(), count);
    let mut buf = vec![eval::Evaluation::default(); pts.len()];
    let mut result = Vec::new();
    let mut sizes = (0, 0, 0, 0, 0);
    for _ in 0..reps {
        let t = Instant::now();
        construct(&mesh)?;
        complex_ms = complex_ms.min(ms(t));
        let t = Instant::now();
        let (complex, table) = PatchTable::build_with(&spec, &mesh, opts)?;
        table_ms = table_ms.min(ms(t));
        let t = Instant::now();
        let mut again = table.apply(mesh.positions())?;
        apply_ms = apply_ms.min(ms(t));
        // the animation loop: into the complex of the previous frame, its storage reused
        // (as OpenSubdiv's UpdateValues writes into buffers allocated once)
        let t = Instant::now();
        table.apply_into(mesh.positions(), &mut again)?;
        reapply_ms = reapply_ms.min(ms(t));
        let t = Instant::now();
        let surface = eval::Surface::new(&mesh, again);
        index_ms = index_ms.min(ms(t));
        let t = Instant::now();
        let r = surface.evaluate_many(&pts);
        eval_ms = eval_ms.min(ms(t));
        let t = Instant::now();
        surface
            .evaluate_into(&pts, &mut buf)
            .map_err(|(i, e)| format!("point {i}: {e}"))?;
        into_ms = into_ms.min(ms(t));
        sizes = match table.layered() {
            Some(l) => {
                let (level_weights, row_weights) = l.num_entries();
                (
                    complex.len(),
                    l.num_points() - l.num_sources(),
                    level_weights,
                    row_weights,
                    table.caps().len(),
                )
            }
            None => (complex.len(), 0, 0, table.rows().num_entries(), 0),
        };
        result = r;
    }
    let mut bytes = Vec::with_capacity(24 * pts.len());
    let mut failed = 0;
    for r in &result {
        let p = match r {
            Ok(e) => e.point,
            Err(_) => {
                failed += 1;
                [f64::NAN; 3]
            }
        };
        for x in p {
            bytes.extend_from_slice(&x.to_le_bytes());
        }
    }
    std::fs::write(out, bytes)?;
    println!(
        "fairsub catmull-clark, {} faces, {rings} rings + G^1 caps: {} patches, factored table: \
         {} refined points ({} weights), {} net and cap data weights, {} caps",
        mesh.num_faces(),
        sizes.0,
        sizes.1,
        sizes.2,
        sizes.3,
        sizes.4
    );
    println!(
        "build: complex and table {table_ms:.1} ms + evaluation index {index_ms:.1} ms = {:.1} ms \
         (the complex alone: {complex_ms:.1} ms)",
        table_ms + index_ms
    );
    println!(
        "re-apply the table to the control points: {apply_ms:.1} ms; into the complex (its \
         storage reused): {reapply_ms:.1} ms"
    );
    println!(
        "evaluate {} points (point, d1, d2, normal, curvature): {eval_ms:.1} ms ({failed} failed); \
         evaluate_into a reused buffer: {into_ms:.1} ms",
        pts.len()
    );
    Ok(())
}

fn compare_points(a: &str, b: &str) -> Res<()> {
    let read = |p: &str| -> Res<Vec<f64>> {
        Ok(std::fs::read(p)?
            .chunks_exact(8)
            .map(|c| f64::from_le_bytes(c.try_into().expect("8 bytes")))
            .collect())
    };
    let (x, y) = (read(a)?, read(b)?);
    if x.len() != y.len() {
        return Err(format!("{} against {} values", x.len(), y.len()).into());
    }
    let d: Vec<f64> = x
        .chunks_exact(3)
        .zip(y.chunks_exact(3))
        .map(|(p, q)| {
            ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt()
        })
        .collect();
    let n = d.len() as f64;
    let within = |t: f64| d.iter().filter(|&&e| e <= t).count() as f64 / n * 100.0;
    let worst = d.iter().copied().fold(0.0f64, f64::max);
    println!(
        "points: {} compared; within 1e-9: {:.2}%, 1e-6: {:.2}%, 1e-3: {:.2}%; largest distance {worst:.3e}",
        d.len(),
        within(1e-9),
        within(1e-6),
        within(1e-3)
    );
    Ok(())
}

fn complex_only(input: &str, rings: Option<usize>) -> Res<()> {
    let rings = rings.ok_or("bad ring count")?;
    let mesh = fairsub::io::read_mesh(Path::new(input))?.mesh;
    let spec = fairsub::schemes::registry::registry().lookup("catmull-clark")?;
    let opts = fairsub::surface::ComplexOptions { rings, fill: true };
    let t = Instant::now();
    let c = fairsub::surface::build(&spec, &mesh, opts, &mut |_| {})?.complex;
    println!(
        "catmull-clark complex, {} faces, {rings} rings + caps: {} patches in {:.1} ms",
        mesh.num_faces(),
        c.len(),
        t.elapsed().as_secs_f64() * 1e3
    );
    Ok(())
}
