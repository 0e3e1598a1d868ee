//! Reading a patch table off a construction: the construction run on displaced control points.
//!
//! The construction `F` maps the net's points `P` (n x 3) to the complex's coefficients and the
//! caps' data, `F(P) = W P + c` with the same sparse `W` for x, y and z. For a displacement `D`
//! that is non-zero on one *colour class* of points only, `F(P + D) - F(P) = W D`. The classes
//! are a distance-`R` colouring of the net (two points of one class are more than `R` faces
//! apart), so that no coefficient depends on two points of a class; the displacement of point
//! `j` of the class is `s (1, a_j, b_j)` with two codes `a_j = 1 + (j + 1/2) / n` and
//! `b_j = 1 + (pi(j) + 1/2) / n` (`pi` a fixed permutation). A coefficient whose difference is
//! `(dx, dy, dz)` then depends on the point `j` with `a_j = dy / dx` with weight `dx / s`, and
//! `dz / dx = b_j` confirms it. Where the confirmation fails, two points of one class met in one
//! coefficient: the colouring is redone with a larger `R` (3, 6, 12, then every point its own
//! class). Differences at the rounding level of the coefficients (relative `1e-13`) count as
//! no dependence.
//!
//! Runs: one per colour class (16 on a regular quad net at `R = 3`) plus two checks, in
//! parallel. The checks: the table applied to `P` equals `F(P)` (the rest is the constant `c`,
//! kept only when it is not rounding, i.e. when options fix points), and applied to randomly
//! moved points it equals the construction's complex of those points to `1e-9` of the net's
//! size; else the construction is not linear (or changes its structure) and the build fails.

use super::{PatchTable, hole_points};
use crate::bezier::complex::PatchComplex;
use crate::error::{Error, Result};
use crate::geom::Point;
use crate::mesh::PolyMesh;
use crate::stencil::StencilTable;
use rayon::prelude::*;

/// A construction: the complex of a net with the given points (its topology fixed).
pub type Construction<'a> = dyn Fn(&PolyMesh) -> Result<PatchComplex> + Sync + 'a;

/// Relative level below which a difference counts as rounding.
const ROUNDING: f64 = 1e-13;
/// Weights below this (relative to the probe size) whose code does not confirm are dropped
/// as rounding rather than taken for a clash of two points.
const SMALL: f64 = 1e-9;
/// Largest deviation (relative to the net's size) the checks accept.
pub const CHECK: f64 = 1e-9;

/// The table of the complex `construct` computes from `mesh` (see the [module](self)
/// documentation).
///
/// # Errors
/// Whatever the construction reports; [`Error::Unsupported`] when it changes its structure
/// under displacement or is not linear in the points.
pub fn build(mesh: &PolyMesh, construct: &Construction<'_>) -> Result<PatchTable> {
    let base = construct(mesh)?;
    build_from(mesh, &base, construct)
}

/// [`build`] with the construction's complex of `mesh` already computed.
pub fn build_from(
    mesh: &PolyMesh,
    base: &PatchComplex,
    construct: &Construction<'_>,
) -> Result<PatchTable> {
    let debug = std::env::var_os("FAIRSUB_TABLE_DEBUG").is_some();
    let clock = std::time::Instant::now();
    let lap = |what: &str| {
        if debug {
            eprintln!("  {what}: {:.1} ms", clock.elapsed().as_secs_f64() * 1e3);
        }
    };
    let n = mesh.num_vertices();
    let p0 = mesh.positions().to_vec();
    let y0 = outputs(base);
    let (lo, hi) = bounds(&p0);
    let s = crate::geom::dist(lo, hi).max(1e-300);
    let ymax = y0.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
    let tau = ROUNDING * (ymax + s);
    let sig = signature(base);
    let skip = cap_patch_rows(base);
    let codes = Codes::new(n);
    let adjacency = VertexFaces::new(mesh);
    let mut entries = None;
    let mut clash = 0;
    for radius in [3usize, 6, 12, usize::MAX] {
        let colour = adjacency.colouring(radius);
        let classes = colour.iter().copied().max().map_or(0, |c| c as usize + 1);
        let runs: Vec<Result<Decoded>> = (0..classes as u32)
            .into_par_iter()
            .map(|c| {
                let mut pts = p0.clone();
                for (j, p) in pts.iter_mut().enumerate() {
                    if colour[j] == c {
                        let d = [s, s * codes.a(j), s * codes.b(j)];
                        *p = crate::geom::add(*p, d);
                    }
                }
                let y = construct_same(mesh, pts, construct, &sig)?;
                Ok(decode(&y0, &y, &skip, c, &colour, &codes, s, tau))
            })
            .collect();
        let runs: Vec<Decoded> = runs.into_iter().collect::<Result<_>>()?;
        if debug {
            let bad = runs.iter().filter(|d| d.is_err()).count();
            eprintln!("radius {radius}: {classes} classes, {bad} with clashes");
        }
        if let Some(Err(r)) = runs.iter().find(|d| d.is_err()) {
            clash = *r;
            continue;
        }
        entries = Some(
            runs.into_iter()
                .flat_map(|d| d.expect("checked"))
                .collect::<Vec<_>>(),
        );
        break;
    }
    let Some(entries) = entries else {
        // every point its own class and still no single point: not linear
        return Err(Error::Unsupported(format!(
            "the construction is not linear in the control points: coefficient row {clash} \
             ({}) does not move like one point's weight times its displacement",
            describe_row(base, clash)
        )));
    };
    lap("probe runs");
    let rows = assemble(n, y0.len(), entries);
    lap("assembled");
    let constants = constant_part(&y0, &rows.apply(&p0), &skip, tau);
    let table = PatchTable::from_parts(base, rows, constants)?;
    check(&table, &p0, base, s, "the net's points")?;
    lap("checked at the net's points");
    check_moved(&table, mesh, construct, &sig, s)?;
    lap("checked at moved points");
    Ok(table)
}

/// The constant part `c = F(P) - W P` of the outputs `y0 = F(P)` given `w = W P`: zero on the
/// cap patches' rows (`skip`), and empty when it is all at the rounding level `tau`.
fn constant_part(y0: &[Point], w: &[Point], skip: &[bool], tau: f64) -> Vec<Point> {
    let mut constants: Vec<Point> = y0
        .iter()
        .zip(w)
        .map(|(y, v)| crate::geom::sub(*y, *v))
        .collect();
    for (c, &k) in constants.iter_mut().zip(skip) {
        if k {
            *c = [0.0; 3];
        }
    }
    let cmax = constants
        .iter()
        .flatten()
        .fold(0.0f64, |m, x| m.max(x.abs()));
    if cmax <= 1e3 * tau {
        constants.clear();
    }
    constants
}

/// The second check: the table applied to randomly moved points (by `0.05 s`) equals the
/// construction's complex of those points, whose structure (`sig`) must not change.
fn check_moved(
    table: &PatchTable,
    mesh: &PolyMesh,
    construct: &Construction<'_>,
    sig: &Signature,
    s: f64,
) -> Result<()> {
    let moved = moved_points(mesh.positions(), 0.05 * s, 0);
    let mut m = mesh.clone();
    m.set_positions(moved.clone());
    let truth = construct(&m)?;
    if signature(&truth) != *sig {
        return Err(changed_structure());
    }
    check(table, &moved, &truth, s, "randomly moved points")
}

/// The rows of the coefficients of cap patches (tabulated by the cap steps instead).
fn cap_patch_rows(c: &PatchComplex) -> Vec<bool> {
    let mut in_cap = vec![false; c.len()];
    for st in &c.caps {
        for k in st.first..st.first + st.count {
            in_cap[k as usize] = true;
        }
    }
    let mut skip = Vec::new();
    for (p, patch) in c.patches.iter().enumerate() {
        skip.extend(std::iter::repeat_n(in_cap[p], patch.cps.len()));
    }
    for st in &c.caps {
        skip.extend(std::iter::repeat_n(
            false,
            hole_points(&st.hole, &st.plane).len(),
        ));
    }
    skip
}

/// The construction's complex of `mesh` with points `pts`, checked to have the structure `sig`.
fn construct_same(
    mesh: &PolyMesh,
    pts: Vec<Point>,
    construct: &Construction<'_>,
    sig: &Signature,
) -> Result<Vec<Point>> {
    let mut m = mesh.clone();
    m.set_positions(pts);
    let c = construct(&m)?;
    if signature(&c) != *sig {
        return Err(changed_structure());
    }
    Ok(outputs(&c))
}

/// The error of a construction whose structure depends on the points.
fn changed_structure() -> Error {
    Error::Unsupported(
        "the construction changes its patches (count, degrees, provenance or caps) when the \
         control points move: it has no patch table for this net"
            .into(),
    )
}

/// What must not change between runs: per patch degrees and provenance, per cap its range
/// and hole shape.
type Signature = (
    Vec<(usize, usize)>,
    Vec<crate::bezier::complex::Provenance>,
    Vec<(u32, u32, Vec<Vec<(usize, usize)>>)>,
);

fn signature(c: &PatchComplex) -> Signature {
    (
        c.patches.iter().map(|p| (p.deg_u, p.deg_v)).collect(),
        c.provenance.clone(),
        c.caps
            .iter()
            .map(|s| {
                let shape = s
                    .hole
                    .sectors
                    .iter()
                    .map(|sec| {
                        sec.iter()
                            .map(|g| (g.boundary.len(), g.cross.len()))
                            .collect()
                    })
                    .collect();
                (s.first, s.count, shape)
            })
            .collect(),
    )
}

/// Every coefficient of every patch in order, then every cap's data points: the table's rows.
fn outputs(c: &PatchComplex) -> Vec<Point> {
    let mut y: Vec<Point> = c
        .patches
        .iter()
        .flat_map(|p| p.cps.iter().copied())
        .collect();
    for st in &c.caps {
        y.extend(hole_points(&st.hole, &st.plane));
    }
    y
}

/// The diagonal of the points' bounding box: the net's size the checks are relative to.
pub fn net_size(p: &[Point]) -> f64 {
    let (lo, hi) = bounds(p);
    crate::geom::dist(lo, hi)
}

/// Bounding box of the points.
fn bounds(p: &[Point]) -> (Point, Point) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for q in p {
        for k in 0..3 {
            lo[k] = lo[k].min(q[k]);
            hi[k] = hi[k].max(q[k]);
        }
    }
    if p.is_empty() {
        return ([0.0; 3], [0.0; 3]);
    }
    (lo, hi)
}

/// The two codes of each point.
struct Codes {
    n: usize,
    perm: Vec<u32>,
}

impl Codes {
    fn new(n: usize) -> Codes {
        // a multiplier coprime to n permutes 0..n
        let mult = [7919u64, 104_729, 1_299_709]
            .into_iter()
            .find(|&p| !(n as u64).is_multiple_of(p))
            .expect("n has at most two of these prime factors below 2^32");
        let perm = (0..n as u64)
            .map(|j| ((j * mult + 13) % n.max(1) as u64) as u32)
            .collect();
        Codes { n, perm }
    }

    fn a(&self, j: usize) -> f64 {
        1.0 + (j as f64 + 0.5) / self.n as f64
    }

    fn b(&self, j: usize) -> f64 {
        1.0 + (self.perm[j] as f64 + 0.5) / self.n as f64
    }
}

/// The entries `(row, source, weight)` one class contributes, or the first row where two points
/// of the class met.
type Decoded = std::result::Result<Vec<(u32, u32, f64)>, usize>;

/// What row `r` of a complex's outputs is: a patch's coefficient (with the patch's
/// provenance) or a G^1 cap's data.
fn describe_row(c: &PatchComplex, r: usize) -> String {
    use crate::bezier::complex::Provenance;
    let mut k = 0;
    for (p, patch) in c.patches.iter().enumerate() {
        k += patch.cps.len();
        if r < k {
            let what = match c.provenance[p] {
                Provenance::Regular { face } => format!("regular, face {face}"),
                Provenance::Ring {
                    element,
                    ring,
                    sector,
                } => {
                    format!(
                        "ring {ring} of {}, sector {sector}",
                        crate::host::caps::describe(element)
                    )
                }
                Provenance::Cap { element, sector } => {
                    format!(
                        "cap of {}, sector {sector}",
                        crate::host::caps::describe(element)
                    )
                }
                Provenance::Unknown => "unknown".into(),
            };
            return format!("patch {p}: {what}");
        }
    }
    "data of a G^1 cap".into()
}

/// The entries `(row, source, weight)` class `c` contributes, or the first row where two points
/// of the class met in one coefficient.
#[allow(clippy::too_many_arguments)]
fn decode(
    y0: &[Point],
    y: &[Point],
    skip: &[bool],
    c: u32,
    colour: &[u32],
    codes: &Codes,
    s: f64,
    tau: f64,
) -> Decoded {
    let n = codes.n as f64;
    let mut out = Vec::new();
    for (r, (a, b)) in y0.iter().zip(y).enumerate() {
        if skip[r] {
            continue;
        }
        let d = crate::geom::sub(*b, *a);
        if d[0].abs() <= tau {
            if d[1].abs() > 4.0 * tau || d[2].abs() > 4.0 * tau {
                return Err(r);
            }
            continue;
        }
        let (ry, rz) = (d[1] / d[0], d[2] / d[0]);
        let j = ((ry - 1.0) * n - 0.5).round();
        let ok = j >= 0.0
            && j < n
            && colour[j as usize] == c
            && (ry - codes.a(j as usize)).abs() < 0.1 / n
            && (rz - codes.b(j as usize)).abs() < 0.1 / n;
        if ok {
            out.push((r as u32, j as u32, d[0] / s));
        } else if d[0].abs() > SMALL * s {
            return Err(r);
        }
    }
    Ok(out)
}

/// The table of `rows` rows over `n` sources from its entries (any order).
fn assemble(n: usize, rows: usize, mut entries: Vec<(u32, u32, f64)>) -> StencilTable {
    entries.par_sort_unstable_by_key(|e| (e.0, e.1));
    let mut t = StencilTable::with_capacity(n, rows, 16);
    let mut k = 0;
    let mut pairs: Vec<(u32, f64)> = Vec::new();
    for r in 0..rows as u32 {
        pairs.clear();
        while k < entries.len() && entries[k].0 == r {
            pairs.push((entries[k].1, entries[k].2));
            k += 1;
        }
        t.push_pairs(&pairs);
    }
    t
}

/// Checks the table applied to `pts` against the construction's complex `truth` of them.
fn check(
    table: &PatchTable,
    pts: &[Point],
    truth: &PatchComplex,
    s: f64,
    what: &str,
) -> Result<()> {
    let got = table.apply(pts)?;
    let (dev, at) = max_deviation(&got, truth);
    if dev > CHECK * s {
        return Err(Error::Unsupported(format!(
            "the construction is not linear in the control points: the table applied to {what} \
             differs from the complex by {dev:.3e} at patch {at} (net size {s:.3e})"
        )));
    }
    Ok(())
}

/// The largest coefficient difference between two complexes of one structure, and its patch.
pub fn max_deviation(a: &PatchComplex, b: &PatchComplex) -> (f64, usize) {
    let mut worst = (0.0, 0);
    for (i, (p, q)) in a.patches.iter().zip(&b.patches).enumerate() {
        if p.cps.len() != q.cps.len() {
            return (f64::INFINITY, i);
        }
        for (x, y) in p.cps.iter().zip(&q.cps) {
            let d = crate::geom::dist(*x, *y);
            if d > worst.0 || d.is_nan() {
                worst = (d, i);
            }
        }
    }
    if a.len() != b.len() {
        return (f64::INFINITY, a.len().min(b.len()));
    }
    worst
}

/// The points moved by a pseudo-random displacement (seeded: the same for the same `seed`) of
/// size up to `size` per coordinate.
pub fn moved_points(p: &[Point], size: f64, seed: u64) -> Vec<Point> {
    let mut state = seed ^ 0x9e37_79b9_7f4a_7c15u64;
    let mut next = move || {
        // splitmix64
        state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    p.iter()
        .map(|q| {
            [
                q[0] + size * next(),
                q[1] + size * next(),
                q[2] + size * next(),
            ]
        })
        .collect()
}

/// The faces around each vertex, for colourings by distance.
struct VertexFaces {
    start: Vec<u32>,
    faces: Vec<u32>,
    corners: Vec<Vec<u32>>,
}

impl VertexFaces {
    fn new(m: &PolyMesh) -> VertexFaces {
        let nv = m.num_vertices();
        let corners: Vec<Vec<u32>> = (0..m.num_faces()).map(|f| m.face(f).to_vec()).collect();
        let mut count = vec![0u32; nv + 1];
        for c in corners.iter().flatten() {
            count[*c as usize + 1] += 1;
        }
        for v in 0..nv {
            count[v + 1] += count[v];
        }
        let mut fill = count.clone();
        let mut faces = vec![0u32; count[nv] as usize];
        for (f, c) in corners.iter().enumerate() {
            for &v in c {
                faces[fill[v as usize] as usize] = f as u32;
                fill[v as usize] += 1;
            }
        }
        VertexFaces {
            start: count,
            faces,
            corners,
        }
    }

    /// The vertices in breadth-first order (each component from its lowest vertex): greedy
    /// colouring in a spatially coherent order needs fewer colours (a regular quad grid at
    /// radius 3: 16 to 20 against 27 in the order of a refined net's vertex blocks).
    fn bfs_order(&self) -> Vec<u32> {
        let nv = self.start.len() - 1;
        let mut seen = vec![false; nv];
        let mut order = Vec::with_capacity(nv);
        for s in 0..nv {
            if seen[s] {
                continue;
            }
            seen[s] = true;
            let mut k = order.len();
            order.push(s as u32);
            while k < order.len() {
                let x = order[k] as usize;
                k += 1;
                for &f in &self.faces[self.start[x] as usize..self.start[x + 1] as usize] {
                    for &w in &self.corners[f as usize] {
                        if !std::mem::replace(&mut seen[w as usize], true) {
                            order.push(w);
                        }
                    }
                }
            }
        }
        order
    }

    /// A greedy colouring in which two points of one colour are more than `radius` steps apart
    /// (a step joins two corners of a face); `usize::MAX`: every point its own colour.
    fn colouring(&self, radius: usize) -> Vec<u32> {
        let nv = self.start.len() - 1;
        if radius == usize::MAX {
            return (0..nv as u32).collect();
        }
        const NONE: u32 = u32::MAX;
        let mut colour = vec![NONE; nv];
        let mut seen = vec![u32::MAX; nv];
        let mut used: Vec<u32> = Vec::new();
        let mut frontier: Vec<u32> = Vec::new();
        let mut next: Vec<u32> = Vec::new();
        for v in self.bfs_order() {
            let v = v as usize;
            used.clear();
            frontier.clear();
            frontier.push(v as u32);
            seen[v] = v as u32;
            for _ in 0..radius {
                next.clear();
                for &x in &frontier {
                    let (a, b) = (self.start[x as usize], self.start[x as usize + 1]);
                    for &f in &self.faces[a as usize..b as usize] {
                        for &w in &self.corners[f as usize] {
                            if seen[w as usize] != v as u32 {
                                seen[w as usize] = v as u32;
                                next.push(w);
                                if colour[w as usize] != NONE {
                                    used.push(colour[w as usize]);
                                }
                            }
                        }
                    }
                }
                std::mem::swap(&mut frontier, &mut next);
            }
            used.sort_unstable();
            used.dedup();
            let c = used
                .iter()
                .enumerate()
                .find(|&(i, &u)| i as u32 != u)
                .map_or(used.len() as u32, |(i, _)| i as u32);
            colour[v] = c;
        }
        colour
    }
}
