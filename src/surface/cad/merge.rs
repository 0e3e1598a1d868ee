//! One B-spline face per input face: the patches (and dual pieces) that lie in one input face
//! (one quad sub-face of an n-gon) merged exactly into one tensor-product B-spline in the
//! face's own parameters.
//!
//! Every patch of a complex whose [`Domain`] is tracked covers an axis-parallel rectangle of
//! its face's `[0, 1]^2` (the maps of dyadic cells, cells in thirds, ratio cells and halves are
//! all axis-parallel; a patch's own axes may be swapped or reversed against the face's, which
//! re-indexing its coefficients undoes exactly). The rectangles of one face tile it; the
//! union of their sides, extended across the face, is a tensor grid whose cells each lie in
//! one patch. The merged face is the B-spline on that grid:
//!
//! * **degree**: the largest of the face's patches in each direction (the others are degree
//!   raised, exactly);
//! * **knots**: each grid line `u = u_a` gets multiplicity `p - r`, where `r` is the order of
//!   continuity that holds across the whole line, measured: for every pair of grid cells across
//!   it that lie in different patches, the jumps of the derivatives of order `0, 1, ...` (in
//!   face parameters) must be rounding noise: at most the tolerance (`1e-13` of the complex's
//!   size) at the face's scale, or `1e-11` of the derivative, or (first try, orders below
//!   `p` only) within the rounding level that cells as narrow as a semi-sharp crease's `2^-6`
//!   amplify. The spline is then checked against every patch; near patches it misses, the
//!   lines take the orders of the strict test, and when that misses too every knot gets multiplicity `p` (C^0: exact,
//!   more control points). So rings of Catmull-Clark's bi-3 patches (C^2) give multiplicity
//!   `p - 2`, the line to a C^1 cap `p - 1`;
//! * **control points**: by blossoming (`spline`): control point `i` is the blossom of the
//!   patch covering the widest grid cell of its support at the knots `t_{i+1}, ..., t_{i+p}`.
//!
//! A face whose patches do not tile it (a domain the host did not track, triangles, the
//! criss-cross triangles of non-box, Loop's kites) is not merged: its patches stay faces of
//! their own. A merged face is checked against its patches at points of every patch; one that
//! deviates by more than `1e-10` of the complex's size (which would be a bug) is not used.

use super::spline::{SplineSurface, support_spans};
use crate::bezier::domain::{Domain, Shape};
use crate::bezier::{BezierPatch, curve};
use crate::geom::{Point, dist};
use crate::surface::PatchComplex;
use std::collections::BTreeMap;

/// Part of a patch over a rectangle of an input face, as a Bezier patch in the face's own
/// parameter directions.
#[derive(Debug, Clone)]
pub(crate) struct FacePiece {
    /// The patch of the complex it comes from.
    pub patch: usize,
    /// The part of the patch's parameter square it is (`[lo, hi]`).
    pub window: [[f64; 2]; 2],
    /// `[[u0, u1], [v0, v1]]` in the face's (sub-face's) parameters.
    pub rect: [[f64; 2]; 2],
    /// The piece over `rect`, `u` along the face's `u`.
    pub bezier: BezierPatch,
}

/// Key of an input face's (sub-face's) group: `(face, sub)`.
pub(crate) type FaceKey = (u32, u32);

/// The patch (or its part `window`) over an axis-parallel rectangle of its face, or `None`
/// when the domain's map is not axis-parallel or the domain cannot be merged.
fn face_piece(
    patch: usize,
    bezier: &BezierPatch,
    window: Option<[[f64; 2]; 2]>,
    d: &Domain,
) -> Option<(FaceKey, FacePiece)> {
    if !d.is_tracked()
        || d.shape != Shape::Quad
        || d.criss_cross_triangle().is_some()
        || d.sub == Domain::WHOLE
    {
        return None;
    }
    let m = d.patch_map();
    let [[a, b], [c, e]] = m.e; // e0 = (a, b), e1 = (c, e)
    let swap = if b == 0.0 && c == 0.0 && a != 0.0 && e != 0.0 {
        false
    } else if a == 0.0 && e == 0.0 && b != 0.0 && c != 0.0 {
        true
    } else {
        return None;
    };
    let mut p = match window {
        Some([lo, hi]) => bezier.subpatch(lo[0], hi[0], lo[1], hi[1]),
        None => bezier.clone(),
    };
    // in face terms: the patch's u runs along face u (no swap) or face v (swap); after the
    // transposition the piece's u (the patch's v) runs along face u with scale c
    let (du, dv) = if swap { (c, b) } else { (a, e) };
    if swap {
        p = p.transposed();
    }
    if du < 0.0 {
        p = p.reversed_u();
    }
    if dv < 0.0 {
        p = p.reversed_v();
    }
    let o = m.origin;
    let rect = [
        [o[0].min(o[0] + du), o[0].max(o[0] + du)],
        [o[1].min(o[1] + dv), o[1].max(o[1] + dv)],
    ];
    let inside = rect
        .iter()
        .all(|r| r[0] >= -1e-12 && r[1] <= 1.0 + 1e-12 && r[1] > r[0]);
    inside.then_some((
        (d.face, d.sub),
        FacePiece {
            patch,
            window: window.unwrap_or([[0.0, 0.0], [1.0, 1.0]]),
            rect,
            bezier: p,
        },
    ))
}

/// The pieces of the complex grouped by input face (sub-face), and for every patch the part of
/// its parameter square that no group holds (as windows `[lo, hi]`; empty when a patch is
/// covered whole).
pub(crate) struct Grouped {
    /// The groups, by face key.
    pub groups: BTreeMap<FaceKey, Vec<FacePiece>>,
    /// For every patch, the windows of its parameter square left over.
    pub leftover: Vec<Vec<[[f64; 2]; 2]>>,
}

/// Groups the patches and pieces of the complex by input face.
pub(crate) fn group(c: &PatchComplex) -> Grouped {
    let mut groups: BTreeMap<FaceKey, Vec<FacePiece>> = BTreeMap::new();
    let mut windows: Vec<Vec<[[f64; 2]; 2]>> = vec![Vec::new(); c.len()];
    for i in 0..c.len() {
        if let Some(d) = c.domain(i)
            && let Some((k, fp)) = face_piece(i, &c.patches[i], None, &d)
        {
            groups.entry(k).or_default().push(fp);
            windows[i].push([[0.0, 0.0], [1.0, 1.0]]);
        }
    }
    for pc in &c.pieces {
        let i = pc.patch as usize;
        if i >= c.len() {
            continue;
        }
        if let Some((k, fp)) = face_piece(i, &c.patches[i], Some(pc.window), &pc.domain) {
            groups.entry(k).or_default().push(fp);
            windows[i].push(pc.window);
        }
    }
    let leftover = windows.iter().map(|w| uncovered(w)).collect();
    Grouped { groups, leftover }
}

/// The parts of `[0, 1]^2` outside the union of the windows, as the cells of the grid of the
/// windows' sides.
fn uncovered(windows: &[[[f64; 2]; 2]]) -> Vec<[[f64; 2]; 2]> {
    let lines = |k: usize| {
        let mut v: Vec<f64> = vec![0.0, 1.0];
        for w in windows {
            v.push(w[0][k].clamp(0.0, 1.0));
            v.push(w[1][k].clamp(0.0, 1.0));
        }
        v.sort_by(f64::total_cmp);
        v.dedup_by(|a, b| (*a - *b).abs() <= 1e-12);
        v
    };
    let (us, vs) = (lines(0), lines(1));
    let mut out = Vec::new();
    for a in us.windows(2) {
        for b in vs.windows(2) {
            let mid = [0.5 * (a[0] + a[1]), 0.5 * (b[0] + b[1])];
            let covered = windows
                .iter()
                .any(|w| (0..2).all(|k| mid[k] > w[0][k] && mid[k] < w[1][k]));
            if !covered {
                out.push([[a[0], b[0]], [a[1], b[1]]]);
            }
        }
    }
    out
}

/// The sorted distinct values of the rectangles' sides in direction `k` (values closer than
/// `1e-12` are one: the maps of cells in thirds round once per level).
fn grid_lines(pieces: &[FacePiece], k: usize) -> Vec<f64> {
    let mut v: Vec<f64> = pieces
        .iter()
        .flat_map(|p| [p.rect[k][0], p.rect[k][1]])
        .collect();
    v.sort_by(f64::total_cmp);
    v.dedup_by(|a, b| (*a - *b).abs() <= 1e-12);
    v
}

/// Index of the grid line nearest `x`.
fn line_index(lines: &[f64], x: f64) -> usize {
    let i = lines.partition_point(|&l| l < x);
    if i == 0 {
        0
    } else if i == lines.len() || (x - lines[i - 1]) < (lines[i] - x) {
        i - 1
    } else {
        i
    }
}

/// The tensor grid of a face's pieces: the grid lines and the piece covering each cell, or
/// `None` when the pieces do not tile `[0, 1]^2` once.
struct Grid {
    lines: [Vec<f64>; 2],
    /// `owner[a * nb + b]`: the piece over cell `(a, b)`.
    owner: Vec<usize>,
}

impl Grid {
    fn new(pieces: &[FacePiece]) -> Option<Grid> {
        let lines = [grid_lines(pieces, 0), grid_lines(pieces, 1)];
        let full = |l: &Vec<f64>| {
            l.len() >= 2 && l[0].abs() <= 1e-12 && (l[l.len() - 1] - 1.0).abs() <= 1e-12
        };
        if !full(&lines[0]) || !full(&lines[1]) {
            return None;
        }
        let nb = lines[1].len() - 1;
        let mut owner = vec![usize::MAX; (lines[0].len() - 1) * nb];
        for (k, p) in pieces.iter().enumerate() {
            let a0 = line_index(&lines[0], p.rect[0][0]);
            let a1 = line_index(&lines[0], p.rect[0][1]);
            let b0 = line_index(&lines[1], p.rect[1][0]);
            let b1 = line_index(&lines[1], p.rect[1][1]);
            for a in a0..a1 {
                for b in b0..b1 {
                    if owner[a * nb + b] != usize::MAX {
                        return None;
                    }
                    owner[a * nb + b] = k;
                }
            }
        }
        owner
            .iter()
            .all(|&o| o != usize::MAX)
            .then_some(Grid { lines, owner })
    }

    fn nb(&self) -> usize {
        self.lines[1].len() - 1
    }

    fn owner(&self, a: usize, b: usize) -> usize {
        self.owner[a * self.nb() + b]
    }
}

/// The piece `k` over grid cell `[[u0, u1], [v0, v1]]`, raised to `(p, q)`.
fn over_cell(
    piece: &BezierPatch,
    rect: [[f64; 2]; 2],
    cell: [[f64; 2]; 2],
    p: usize,
    q: usize,
) -> BezierPatch {
    let loc = |x: f64, k: usize| (x - rect[k][0]) / (rect[k][1] - rect[k][0]);
    piece
        .subpatch(
            loc(cell[0][0], 0),
            loc(cell[0][1], 0),
            loc(cell[1][0], 1),
            loc(cell[1][1], 1),
        )
        .raised_to(p, q)
        .expect("p, q are the largest degrees")
}

/// The order of continuity across the common side of `left` (ending at `u = 1`) and `right`
/// (starting at `u = 0`), both of degree `(p, q)` over cells of widths `wl`, `wr` in face
/// parameters: the largest `r` such that for every order `j <= r` the jump of the `j`-th
/// derivative (in face parameters) is rounding noise, either small at the face's scale
/// (`jump / j! <= tol`, the change it would make to points one face width away) or relative to
/// the derivative itself (`jump <= 1e-11 max |d_j|`); `p + 1` when every order passes (one
/// polynomial), `None` when the sides do not even meet.
///
/// `lenient` also takes a jump within the rounding level of the narrower cell's control
/// points as noise (`256 eps` of the coefficients' size in `j`-th differences), but only up to
/// order `p - 1`: it may lift a line to `C^{p-1}` (multiplicity 1), never remove it. Real
/// jumps of order `p` between the narrow cells beside a semi-sharp crease (`2^-6` of the face)
/// are that small too, and a knot removed there makes the face miss its patches.
fn continuity(
    left: &BezierPatch,
    right: &BezierPatch,
    wl: f64,
    wr: f64,
    tol: f64,
    lenient: bool,
) -> Option<usize> {
    let p = left.deg_u;
    let q = left.deg_v;
    // the rounding level of the coefficients, and of a j-th derivative computed from them
    let size = left
        .cps
        .iter()
        .chain(&right.cps)
        .flat_map(|x| x.iter())
        .fold(0.0f64, |m, x| m.max(x.abs()));
    let w = wl.min(wr);
    let mut fact = 1.0;
    let mut falling = 1.0;
    for j in 0..=p {
        if j > 0 {
            fact *= j as f64;
            falling *= (p + 1 - j) as f64;
        }
        let sl = falling / wl.powi(j as i32);
        let sr = falling / wr.powi(j as i32);
        let holds = (0..=q).all(|l| {
            let dl = difference(|i| left.cp(p - j + i, l), j);
            let dr = difference(|i| right.cp(i, l), j);
            (0..3).all(|c| {
                let (a, b) = (dl[c] * sl, dr[c] * sr);
                let jump = (a - b).abs();
                let noise = 256.0 * f64::EPSILON * size * falling * (2.0 / w).powi(j as i32);
                jump / fact <= tol
                    || jump <= 1e-11 * a.abs().max(b.abs())
                    || (lenient && j < p && jump <= noise)
            })
        });
        if !holds {
            return j.checked_sub(1);
        }
    }
    Some(p + 1)
}

/// The forward difference of order `j` of the points `f(0), ..., f(j)`.
fn difference(f: impl Fn(usize) -> Point, j: usize) -> Point {
    let mut pts: Vec<Point> = (0..=j).map(&f).collect();
    for r in 0..j {
        for i in 0..j - r {
            for c in 0..3 {
                pts[i][c] = pts[i + 1][c] - pts[i][c];
            }
        }
    }
    pts[0]
}

/// Most grid cells per piece a merged face may have (see [`merge_face`]).
const MAX_CELLS_PER_PIECE: usize = 16;

/// Most control points a merged face may have, per control point of its pieces (raised to the
/// face's degree; see [`merge_face`]).
const MAX_POINTS_RATIO: usize = 2;

/// What [`merge_face`] found: the surface and how far it is from the pieces.
pub(crate) struct Merged {
    /// The face's B-spline.
    pub surface: SplineSurface,
    /// Largest deviation from the pieces at the sample points.
    pub deviation: f64,
    /// Whether the measured continuity had to be given up for multiplicity `p` (C^0) at every
    /// knot, because the spline with the measured multiplicities deviated from the pieces.
    pub c0: bool,
}

/// The pieces, their grid and common degree.
struct Layout<'a> {
    pieces: &'a [FacePiece],
    grid: Grid,
    deg: [usize; 2],
    /// The pieces raised to `deg`.
    raised: Vec<BezierPatch>,
}

impl Layout<'_> {
    /// Cell `(a, b)` as `[[u0, u1], [v0, v1]]`.
    fn cell(&self, a: usize, b: usize) -> [[f64; 2]; 2] {
        let l = &self.grid.lines;
        [[l[0][a], l[0][a + 1]], [l[1][b], l[1][b + 1]]]
    }

    /// The continuity across interior line `k` of direction `dir` (0: `u = u_k`), the least
    /// over the cells along it; `None` where the sides do not meet.
    fn line_continuity(&self, dir: usize, k: usize, tol: f64, lenient: bool) -> Option<usize> {
        let n_other = self.grid.lines[1 - dir].len() - 1;
        let [p, q] = self.deg;
        let mut r = usize::MAX;
        for o in 0..n_other {
            let ((a0, b0), (a1, b1)) = if dir == 0 {
                ((k - 1, o), (k, o))
            } else {
                ((o, k - 1), (o, k))
            };
            let (kl, kr) = (self.grid.owner(a0, b0), self.grid.owner(a1, b1));
            if kl == kr {
                continue;
            }
            let (cl, cr) = (self.cell(a0, b0), self.cell(a1, b1));
            let mut l = over_cell(&self.raised[kl], self.pieces[kl].rect, cl, p, q);
            let mut rr = over_cell(&self.raised[kr], self.pieces[kr].rect, cr, p, q);
            if dir == 1 {
                l = l.transposed();
                rr = rr.transposed();
            }
            let (wl, wr) = (cl[dir][1] - cl[dir][0], cr[dir][1] - cr[dir][0]);
            r = r.min(continuity(&l, &rr, wl, wr, tol, lenient)?);
        }
        Some(r)
    }

    /// The continuity across every interior line of direction `dir`.
    fn orders(&self, dir: usize, tol: f64, lenient: bool) -> Option<Vec<usize>> {
        (1..self.grid.lines[dir].len() - 1)
            .map(|k| self.line_continuity(dir, k, tol, lenient))
            .collect()
    }

    /// The knot vector of direction `dir` with interior line `k` at multiplicity `p - r_k`.
    fn knots(&self, dir: usize, orders: &[usize]) -> Vec<f64> {
        let lines = &self.grid.lines[dir];
        let p = self.deg[dir];
        let mut knots = vec![lines[0]; p + 1];
        for (k, &r) in orders.iter().enumerate() {
            knots.extend(std::iter::repeat_n(lines[k + 1], p.saturating_sub(r)));
        }
        knots.extend(std::iter::repeat_n(lines[lines.len() - 1], p + 1));
        knots
    }

    /// The grid lines of direction `dir` within `p + 1` cells of piece `k` (interior line
    /// indices, 0-based as in [`Layout::orders`]).
    fn lines_near(&self, dir: usize, k: usize) -> std::ops::Range<usize> {
        let lines = &self.grid.lines[dir];
        let r = self.pieces[k].rect[dir];
        let (a0, a1) = (line_index(lines, r[0]), line_index(lines, r[1]));
        let reach = self.deg[dir] + 1;
        let lo = a0.saturating_sub(reach).max(1) - 1;
        let hi = (a1 + reach).min(lines.len() - 2);
        lo..hi.max(lo)
    }

    /// The spline on knot vectors `ku`, `kv` whose control points are the blossoms of the
    /// pieces (exact when the pieces lie in its space).
    fn spline(&self, ku: Vec<f64>, kv: Vec<f64>) -> SplineSurface {
        let [p, q] = self.deg;
        let (na, nb) = (self.grid.lines[0].len() - 1, self.grid.nb());
        let su = support_spans(&ku, p);
        let sv = support_spans(&kv, q);
        let mut cps = Vec::with_capacity(su.len() * sv.len());
        for (i, &ka) in su.iter().enumerate() {
            let a = line_index(&self.grid.lines[0], ku[ka]).min(na - 1);
            for (j, &kb) in sv.iter().enumerate() {
                let b = line_index(&self.grid.lines[1], kv[kb]).min(nb - 1);
                let k = self.grid.owner(a, b);
                cps.push(blossom(
                    &self.raised[k],
                    self.pieces[k].rect,
                    &ku[i + 1..=i + p],
                    &kv[j + 1..=j + q],
                ));
            }
        }
        SplineSurface {
            deg: [p, q],
            knots: [ku, kv],
            cps,
        }
    }
}

/// Merges the pieces of one input face into one B-spline surface on `[0, 1]^2` (see the
/// module doc); `None` when they do not tile the face, do not meet, the result deviates by
/// more than `limit` even with C^0 knots, or the face would cost far more than its patches:
/// its grid has more than [`MAX_CELLS_PER_PIECE`] cells per piece (plus 64), or the spline more
/// than [`MAX_POINTS_RATIO`] times the pieces' control points.
///
/// A semi-sharp crease of sharpness `s` along a face's side puts knot lines `2^-s` apart along
/// that side, and the tensor grid extends them across the face: two creased sides meeting at
/// a corner make a `2^s x 2^s` grid (OpenSubdiv's car, `s = 6`: 4,096 cells, 361 patches), which
/// at multiplicity 1 (the C^2 of Catmull-Clark's patches) is 4,489 control points, fewer than
/// the patches' 5,776; at multiplicity `p` (C^0) it would be 37,249.
pub(crate) fn merge_face(pieces: &[FacePiece], tol: f64, limit: f64) -> Option<Merged> {
    let grid = Grid::new(pieces)?;
    let cells = (grid.lines[0].len() - 1) * grid.nb();
    if cells > MAX_CELLS_PER_PIECE * pieces.len() + 64 {
        return None;
    }
    let p = pieces.iter().map(|x| x.bezier.deg_u).max()?.max(1);
    let q = pieces.iter().map(|x| x.bezier.deg_v).max()?.max(1);
    let raised = pieces
        .iter()
        .map(|x| x.bezier.raised_to(p, q).expect("largest degrees"))
        .collect();
    let layout = Layout {
        pieces,
        grid,
        deg: [p, q],
        raised,
    };
    let strict = [layout.orders(0, tol, false)?, layout.orders(1, tol, false)?];
    let lenient = [layout.orders(0, tol, true)?, layout.orders(1, tol, true)?];
    let zero = [vec![0; strict[0].len()], vec![0; strict[1].len()]];
    let mut tries = vec![lenient.clone(), strict.clone(), zero];
    if lenient == strict {
        tries.remove(0);
    }
    let mut k = 0;
    while k < tries.len() {
        let orders = tries[k].clone();
        let surface = layout.spline(layout.knots(0, &orders[0]), layout.knots(1, &orders[1]));
        let devs = deviations(&surface, pieces);
        let deviation = devs.iter().fold(0.0f64, |m, &d| m.max(d));
        if deviation <= limit {
            let own: usize = pieces.len() * (p + 1) * (q + 1);
            if surface.cps.len() > MAX_POINTS_RATIO * own {
                return None;
            }
            return Some(Merged {
                surface,
                deviation,
                c0: orders.iter().flatten().all(|&r| r == 0)
                    && strict.iter().flatten().any(|&r| r > 0),
            });
        }
        if k == 0 && orders == lenient && lenient != strict {
            // the lenient orders where the pieces agree, the strict ones near those that do not
            let mut mixed = lenient.clone();
            for (piece, _) in devs.iter().enumerate().filter(|(_, d)| **d > limit) {
                for dir in 0..2 {
                    for line in layout.lines_near(dir, piece) {
                        mixed[dir][line] = strict[dir][line];
                    }
                }
            }
            if mixed != strict {
                tries.insert(1, mixed);
            }
        }
        k += 1;
    }
    None
}

/// The tensor blossom of `b` (over `rect` of the face) at face parameters `us`, `vs`.
fn blossom(b: &BezierPatch, rect: [[f64; 2]; 2], us: &[f64], vs: &[f64]) -> Point {
    let loc = |x: f64, k: usize| (x - rect[k][0]) / (rect[k][1] - rect[k][0]);
    let su: Vec<f64> = us.iter().map(|&x| loc(x, 0)).collect();
    let sv: Vec<f64> = vs.iter().map(|&x| loc(x, 1)).collect();
    let col: Vec<Point> = (0..=b.deg_v)
        .map(|l| {
            let c: Vec<Point> = (0..=b.deg_u).map(|i| b.cp(i, l)).collect();
            curve::blossom(&c, &su)
        })
        .collect();
    curve::blossom(&col, &sv)
}

/// The largest distance between the surface and each piece at 5 points of the piece.
fn deviations(s: &SplineSurface, pieces: &[FacePiece]) -> Vec<f64> {
    pieces
        .iter()
        .map(|pc| {
            let mut worst: f64 = 0.0;
            for (x, y) in [(0.5, 0.5), (0.1, 0.2), (0.9, 0.15), (0.2, 0.85), (0.8, 0.9)] {
                let u = pc.rect[0][0] + x * (pc.rect[0][1] - pc.rect[0][0]);
                let v = pc.rect[1][0] + y * (pc.rect[1][1] - pc.rect[1][0]);
                worst = worst.max(dist(s.eval(u, v), pc.bezier.eval(x, y)));
            }
            worst
        })
        .collect()
}
