//! Evaluation of an exact surface at any `(face, u, v)` of its input net: position, first and
//! second derivatives with respect to the face's parameters, normal, Gauss and mean curvature,
//! and which patch (and where in it) the point lies in.
//!
//! A [`Surface`] is a patch complex whose patches carry the [`Domain`] of their input face (the
//! adaptive host records it for the schemes whose [`Capabilities`] say `eval`: Catmull-Clark,
//! Loop, and EG, the QAS+ family and guided subdivision, whose caps tile each sector's face in
//! their rings' chart, see [`crate::schemes::eg::surface`] and [`crate::schemes::guided::surface`];
//! the dual schemes Doo-Sabin, DS^CC and PGS, whose patches of input vertices cover a quarter
//! of each face around them as [`Piece`](crate::bezier::complex::Piece)s; TPS, laid out like
//! them, whose rings are cells in thirds of the quarters at extraordinary vertices, see
//! `crate::schemes::bi2::surface::cells`). The parameter domain of quads, n-gons and
//! triangles (and of the dual schemes' faces) is documented in [`crate::bezier::domain`]. Each cell of a face is either covered by one patch or split into
//! children, so the cells form a quadtree per face: a point is located by descending it, one
//! hash look-up per level (`O(log)` of the patch size, independent of the number of patches).
//! A cell whose children are thirds (TPS) is in the index too, marked as split in thirds, so
//! the descent takes the 3 x 3 grid there (the dyadic schemes have no such marks: their
//! descent is the quadtree's).
//!
//! Patch parameters are mapped to face parameters by affine maps with dyadic coefficients
//! (exact in floating point); derivatives go through the chain rule of that map. Points in the
//! hole inside the last ring lie on the cap or fill patch of their cell: Catmull-Clark's G^1
//! cap patch of a sector has its `(0, 0)` at the centre, `u` along the sector's first spoke and
//! `v` along its second, so it covers the sector's remaining square exactly as the cell's own
//! coordinates rotated to the centre corner; the Hermite-Coons fill and Loop's fill have the
//! cell's own corners. Loop's G^1 cap is made of kites, each covering halves of two fan
//! triangles: a point of a fan triangle is mapped to the kite that holds it by inverting the
//! kite's bilinear map in the triangle's lattice chart ([`kite`]), and derivatives go through
//! the inverse function rule (the map is not affine there); `patch` names that kite and
//! `patch_uv` its parameters. Loop's triangles, stored as collapsed bi-4 patches `X(u, v) = T(u (1 -
//! v), v)`, are evaluated as the triangles `T` they represent (barycentric derivatives, defined at
//! the collapsed corner too); their `patch_uv` is the stored patch's `(u, v)`.
//!
//! [`evaluate_limit`] evaluates the scheme's limit surface itself: it builds the complex with as
//! many rings as the points need (a point at distance about `2^-k` of an extraordinary element,
//! in face parameters, needs about `k` rings), up to [`MAX_EXACT_RINGS`].

mod kite;
mod triangle;

use crate::bezier::Derivatives;
use crate::bezier::complex::{Domain, PatchComplex, Provenance};
use crate::bezier::domain::{Affine, MAX_DEPTH, Shape};
use crate::error::{Error, Result};
use crate::geom::Point;
use crate::host::ComplexOptions;
use crate::mesh::PolyMesh;
use crate::schemes::descriptor::Capabilities;
use crate::schemes::{Spec, registry};
use serde::Serialize;
use std::collections::HashMap;

/// Rings [`evaluate_limit`] computes at most. Points nearer an extraordinary element than about
/// `2^-MAX_EXACT_RINGS` of their face are evaluated on the cap inside that ring, which differs
/// from the limit surface by about `lambda^MAX_EXACT_RINGS` times the element's size
/// (`4e-11` for Catmull-Clark at valence 5, `lambda = 0.55`).
pub const MAX_EXACT_RINGS: usize = 40;

/// The surface and its derivatives at one point of an input face.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Evaluation {
    /// The input face.
    pub face: u32,
    /// The face parameter `u`.
    pub u: f64,
    /// The face parameter `v`.
    pub v: f64,
    /// Index of the patch in the complex.
    pub patch: usize,
    /// Where the stored patch is evaluated (its own `(u, v)`).
    pub patch_uv: [f64; 2],
    /// The point.
    pub point: Point,
    /// `d/du` (face parameters).
    pub du: Point,
    /// `d/dv`.
    pub dv: Point,
    /// `d^2/du^2`.
    pub duu: Point,
    /// `d^2/du dv`.
    pub duv: Point,
    /// `d^2/dv^2`.
    pub dvv: Point,
    /// Unit normal `du x dv / |du x dv|` (its limit where that vanishes; NaN if undetermined).
    pub normal: Point,
    /// Gauss curvature (NaN where the tangent plane is not determined by `du`, `dv`).
    pub gauss: f64,
    /// Mean curvature, signed as in [`crate::bezier`] (NaN like `gauss`).
    pub mean: f64,
}

/// Where a face point lies: its patch, the patch's domain and the point in the cell's
/// coordinates.
#[derive(Debug, Clone, Copy)]
struct Located {
    patch: usize,
    domain: Domain,
    /// The map from the cell's frame to the patch's parameters when the cell holds a part of
    /// the patch (a [`crate::bezier::complex::Piece`]), else `None` (the frame is the patch's).
    window: Option<Affine>,
    cell: [f64; 2],
}

/// What covers a cell: a patch (`piece == u32::MAX`) or piece `piece` of the complex; or,
/// with `piece == THIRDS`, no patch: the cell splits in thirds (its children are
/// [`Shape::third_map`]'s, see [`crate::bezier::domain`]). Cells absent from the index split
/// dyadically.
#[derive(Debug, Clone, Copy)]
struct Entry {
    patch: u32,
    piece: u32,
}

/// [`Entry::piece`] of a cell that splits in thirds.
const THIRDS: u32 = u32::MAX - 1;

/// The hasher of the cell index: the multiply-rotate of the Fx family (the keys are small
/// integers from the complex itself, not input an adversary picks, and SipHash's cost would
/// dominate a look-up).
#[derive(Debug, Clone, Copy, Default)]
struct CellHasher(u64);

impl std::hash::Hasher for CellHasher {
    fn finish(&self) -> u64 {
        self.0
    }

    fn write(&mut self, bytes: &[u8]) {
        for chunk in bytes.chunks(8) {
            let mut b = [0u8; 8];
            b[..chunk.len()].copy_from_slice(chunk);
            self.write_u64(u64::from_le_bytes(b));
        }
    }

    fn write_u64(&mut self, x: u64) {
        self.0 = (self.0.rotate_left(5) ^ x).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }

    fn write_u32(&mut self, x: u32) {
        self.write_u64(u64::from(x));
    }

    fn write_u8(&mut self, x: u8) {
        self.write_u64(u64::from(x));
    }

    fn write_u128(&mut self, x: u128) {
        self.write_u64(x as u64);
        self.write_u64((x >> 64) as u64);
    }
}

/// The cell index: `(face, sub, depth, path)` -> the patch covering that cell.
type Cells = HashMap<(u32, u32, u8, u128), Entry, std::hash::BuildHasherDefault<CellHasher>>;

/// A patch complex that can be evaluated at `(face, u, v)` of its input net.
#[derive(Debug, Clone)]
pub struct Surface {
    complex: PatchComplex,
    /// Corners of each input face.
    sides: Vec<u32>,
    /// The triangles whose cells are quads (a 3-gon of three quad sub-faces: the dual
    /// schemes), not barycentric triangles (Loop).
    tri_strips: Vec<bool>,
    /// Cell `(face, sub, depth, path)` -> the patch or piece covering it.
    cells: Cells,
    /// The kites of G^1 caps of triangle holes (Loop's): kite `s` -> kite `s - 1`, which
    /// covers the other half of kite `s`'s fan triangle ([`kite`]).
    kites: HashMap<usize, usize>,
}

/// The error for a scheme whose patches do not carry face domains.
fn not_supported(spec: &Spec) -> Error {
    Error::Unsupported(format!(
        "eval of scheme {} is not supported yet (eval takes: {})",
        spec.name(),
        registry().names_with(|c: Capabilities| c.eval).join(", ")
    ))
}

/// Whether surfaces of `spec` can be evaluated ([`Capabilities`]' `eval`): the error
/// [`Surface::build`] gives otherwise, naming the schemes that can.
pub fn supported(spec: &Spec) -> Result<()> {
    if registry().entry(spec.id).capabilities().eval {
        Ok(())
    } else {
        Err(not_supported(spec))
    }
}

impl Surface {
    /// The surface of `mesh` under `spec` with `opts` (rings, fill), ready to evaluate.
    ///
    /// # Errors
    /// [`Error::Unsupported`] for a scheme without `eval` in its [`Capabilities`]; whatever
    /// the scheme reports for the net.
    pub fn build(spec: &Spec, mesh: &PolyMesh, opts: ComplexOptions) -> Result<Surface> {
        supported(spec)?;
        let out = super::build(spec, mesh, opts, &mut |_| {})?;
        Ok(Surface::new(mesh, out.complex))
    }

    /// The surface of a complex built on `mesh` (patches without a domain are not found by
    /// [`Surface::evaluate`]).
    pub fn new(mesh: &PolyMesh, complex: PatchComplex) -> Surface {
        let mut cells = Cells::with_capacity_and_hasher(
            complex.len() + complex.pieces.len(),
            Default::default(),
        );
        let mut tri_strips = vec![false; mesh.num_faces()];
        let mut index = |d: Domain, entry: Entry| {
            if let Some(t) = tri_strips.get_mut(d.face as usize) {
                *t |= d.shape == Shape::Quad && mesh.face_size(d.face as usize) == 3;
            }
            cells
                .entry((d.face, d.sub, d.depth, d.path))
                .or_insert(entry);
            // the ancestors whose children are in thirds, so that `locate` descends them so
            for l in (1..=d.depth).filter(|&l| d.thirds != 0 && d.splits_in_thirds(l)) {
                let (depth, path) = d.ancestor_key(l - 1);
                let split = Entry {
                    patch: u32::MAX,
                    piece: THIRDS,
                };
                cells.entry((d.face, d.sub, depth, path)).or_insert(split);
            }
        };
        for i in 0..complex.len() {
            if let Some(d) = complex.domain(i) {
                let piece = u32::MAX;
                index(
                    d,
                    Entry {
                        patch: i as u32,
                        piece,
                    },
                );
            }
        }
        for (k, p) in complex.pieces.iter().enumerate() {
            let piece = k as u32;
            index(
                p.domain,
                Entry {
                    patch: p.patch,
                    piece,
                },
            );
        }
        let mut kites = HashMap::new();
        for step in &complex.caps {
            if step.hole.sectors.first().is_some_and(|s| s.len() == 1) {
                let (first, n) = (step.first as usize, step.count as usize);
                for s in 0..n {
                    kites.insert(first + s, first + (s + n - 1) % n);
                }
            }
        }
        Surface {
            complex,
            sides: (0..mesh.num_faces())
                .map(|f| mesh.face_size(f) as u32)
                .collect(),
            tri_strips,
            cells,
            kites,
        }
    }

    /// The patch complex.
    pub fn complex(&self) -> &PatchComplex {
        &self.complex
    }

    /// The face's sub-face and the point in its coordinates, after checking the parameters
    /// against the face's domain ([`crate::bezier::domain`]).
    fn face_point(&self, face: u32, u: f64, v: f64) -> Result<(u32, Shape, [f64; 2])> {
        let n = *self.sides.get(face as usize).ok_or_else(|| {
            Error::InvalidArgument(format!(
                "face {face} does not exist: the net has {} faces (0..{})",
                self.sides.len(),
                self.sides.len()
            ))
        })?;
        let bad = |domain: &str| {
            Error::InvalidArgument(format!(
                "face {face} ({n} sides): (u, v) = ({u}, {v}) is outside its domain {domain}"
            ))
        };
        if !(u.is_finite() && v.is_finite()) {
            return Err(bad("(u and v must be finite numbers)"));
        }
        match n {
            3 if !self.tri_strips[face as usize] => {
                if u < 0.0 || v < 0.0 || u + v > 1.0 + 1e-12 {
                    return Err(bad("u, v >= 0, u + v <= 1"));
                }
                Ok((0, Shape::Triangle, [u, v]))
            }
            4 => {
                if !(0.0..=1.0).contains(&u) || !(0.0..=1.0).contains(&v) {
                    return Err(bad("[0, 1] x [0, 1]"));
                }
                Ok((0, Shape::Quad, [u, v]))
            }
            _ => {
                if !(0.0..=f64::from(n)).contains(&u) || !(0.0..=1.0).contains(&v) {
                    return Err(bad(&format!(
                        "[0, {n}] x [0, 1] (sub-face floor(u), see `fairsub eval --help`)"
                    )));
                }
                let sub = (u.floor() as u32).min(n - 1);
                Ok((sub, Shape::Quad, [u - f64::from(sub), v]))
            }
        }
    }

    /// The patch holding a face point: the face's cells descended from the root.
    fn locate(&self, face: u32, u: f64, v: f64) -> Result<Located> {
        let (sub, shape, mut p) = self.face_point(face, u, v)?;
        let mut path = 0u128;
        // the place value of the next level's child index in the path (see `Domain::path`)
        let mut place = Some(1u128);
        for depth in 0..=MAX_DEPTH {
            let hit = self.cells.get(&(face, sub, depth, path)).copied();
            let thirds = hit.is_some_and(|e| e.piece == THIRDS);
            if let Some(e) = hit.filter(|_| !thirds) {
                let (domain, window) = match self.complex.pieces.get(e.piece as usize) {
                    Some(piece) => (piece.domain, Some(piece.window_map())),
                    None => (
                        self.complex
                            .domain(e.patch as usize)
                            .expect("indexed patches have domains"),
                        None,
                    ),
                };
                return Ok(Located {
                    patch: e.patch as usize,
                    domain,
                    window,
                    cell: p,
                });
            }
            let (k, map, radix) = if thirds {
                let k = Shape::third_at(p);
                (k, Shape::third_map(k), 9)
            } else {
                let k = shape.child_at(p);
                (k, shape.child_map(k), 4)
            };
            p = map.invert(p);
            let Some(next) = place
                .and_then(|w| u128::from(k).checked_mul(w))
                .and_then(|x| path.checked_add(x))
            else {
                break;
            };
            path = next;
            place = place.and_then(|w| w.checked_mul(radix));
        }
        Err(Error::InvalidArgument(format!(
            "no patch of the surface covers face {face} at (u, v) = ({u}, {v}): the hole inside \
             the last ring is open (--no-fill), or the patches there carry no face domain (the \
             dual schemes' quarters of faces at boundary vertices)"
        )))
    }

    /// The surface at parameter `(u, v)` of input face `face` (see [`crate::bezier::domain`]
    /// for the domains of quads, n-gons and triangles).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] naming the face for a face index out of range, `(u, v)`
    /// outside the face's domain, or a point no patch covers (the hole left open).
    pub fn evaluate(&self, face: u32, u: f64, v: f64) -> Result<Evaluation> {
        let at = self.locate(face, u, v)?;
        let d = at.domain;
        let mut index = at.patch;
        let patch = &self.complex.patches[at.patch];
        let mut q = d.shape.corner_map(d.rot).invert(at.cell);
        // the map from the patch's parameters to the face's
        let mut patch_map = d.patch_map();
        if let Some(w) = at.window {
            q = w.apply(q);
            patch_map = patch_map.compose(&w.inverse());
        }
        let (dp, normal, patch_uv) = match d.shape {
            Shape::Quad => {
                let dp = patch.derivatives(q[0], q[1]);
                let n = patch.normal_from(q[0], q[1], &dp);
                (dp, n, q)
            }
            Shape::Triangle if self.kites.contains_key(&at.patch) => {
                let (neighbour, uv) = kite::locate(q);
                if neighbour {
                    index = self.kites[&at.patch];
                }
                let patch = &self.complex.patches[index];
                let dp = patch.derivatives(uv[0], uv[1]);
                let n = patch.normal_from(uv[0], uv[1], &dp);
                (kite::to_chart(&dp, uv, neighbour), n, uv)
            }
            Shape::Triangle => {
                let dp = triangle::derivatives(patch, q)?;
                let toward = [1.0 / 3.0 - q[0], 1.0 / 3.0 - q[1]];
                let n = dp.normal_toward(toward).unwrap_or([f64::NAN; 3]);
                let uv = if q[1] < 1.0 {
                    [q[0] / (1.0 - q[1]), q[1]]
                } else {
                    [0.0, 1.0]
                };
                (dp, n, uv)
            }
        };
        let df = chain(&dp, patch_map.inverse_linear());
        let curv = df.curvature();
        Ok(Evaluation {
            face,
            u,
            v,
            patch: index,
            patch_uv,
            point: df.p,
            du: df.du,
            dv: df.dv,
            duu: df.duu,
            duv: df.duv,
            dvv: df.dvv,
            normal,
            gauss: curv.map_or(f64::NAN, |c| c.gauss),
            mean: curv.map_or(f64::NAN, |c| c.mean),
        })
    }

    /// [`Surface::evaluate`] at many points, in parallel; the results in the order of `points`.
    pub fn evaluate_many(&self, points: &[(u32, f64, f64)]) -> Vec<Result<Evaluation>> {
        use rayon::prelude::*;
        points
            .par_iter()
            .with_min_len(1024)
            .map(|&(f, u, v)| self.evaluate(f, u, v))
            .collect()
    }

    /// Extra rings a point of a cap or fill cell needs to lie on ring patches: `k` where its
    /// distance to the nearest cell corner (the extraordinary element is one of them) is about
    /// `2^-k` of the cell; 0 for points of ring and regular patches and for the corners.
    fn rings_needed(&self, at: &Located) -> usize {
        if !matches!(self.complex.provenance[at.patch], Provenance::Cap { .. }) {
            return 0;
        }
        let [x, y] = at.cell;
        let d = match at.domain.shape {
            Shape::Quad => [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
                .iter()
                .map(|c: &[f64; 2]| (x - c[0]).abs().max((y - c[1]).abs()))
                .fold(f64::INFINITY, f64::min),
            Shape::Triangle => (x + y).min(1.0 - x).min(1.0 - y),
        };
        if d <= 0.0 {
            return 0;
        }
        // each ring shrinks the hole by 3 where the cap's cell is a third (TPS), else by 2
        let dom = at.domain;
        let per_ring = if dom.splits_in_thirds(dom.depth) {
            3f64.log2()
        } else {
            1.0
        };
        (-d.log2() / per_ring).floor().max(0.0) as usize + 1
    }
}

/// Derivatives in face parameters from those in patch parameters, `inv[a][b] = d p_a / d q_b`
/// (the patch map is affine, so no second-order term of the map enters).
fn chain(d: &Derivatives, inv: [[f64; 2]; 2]) -> Derivatives {
    let first = [d.du, d.dv];
    let second = [[d.duu, d.duv], [d.duv, d.dvv]];
    let d1 = |c: usize| -> Point {
        let mut r = [0.0; 3];
        for (a, f) in first.iter().enumerate() {
            r = crate::geom::axpy(r, inv[a][c], *f);
        }
        r
    };
    let d2 = |c: usize, e: usize| -> Point {
        let mut r = [0.0; 3];
        for (a, row) in second.iter().enumerate() {
            for (b, s) in row.iter().enumerate() {
                r = crate::geom::axpy(r, inv[a][c] * inv[b][e], *s);
            }
        }
        r
    };
    Derivatives {
        p: d.p,
        du: d1(0),
        dv: d1(1),
        duu: d2(0, 0),
        duv: d2(0, 1),
        dvv: d2(1, 1),
    }
}

/// Evaluations of the scheme's limit surface at `points` (`(face, u, v)`), and the rings
/// used: starting from 2 rings, the complex is rebuilt with as many rings as the points that
/// fell on cap or fill patches need ([`Surface`]'s cells tell how near the extraordinary
/// element they are), until none needs more or [`MAX_EXACT_RINGS`] is reached. At an
/// extraordinary element itself the cap's corner is the scheme's limit point with the tangent
/// plane of its limit masks (every cap and fill is built so); its derivatives and curvatures
/// there are the cap's (the limit surface's parametrisation is singular there). `build(rings)`
/// builds the surface (callers add their size checks and progress there).
///
/// # Errors
/// Those of `build` and of [`Surface::evaluate`], for the first point that fails.
pub fn evaluate_limit(
    points: &[(u32, f64, f64)],
    build: &mut dyn FnMut(usize) -> Result<Surface>,
) -> Result<(Vec<Evaluation>, usize)> {
    let mut rings = 2;
    loop {
        let s = build(rings)?;
        let mut need = rings;
        let mut out = Vec::with_capacity(points.len());
        for &(f, u, v) in points {
            let at = s.locate(f, u, v)?;
            need = need.max(rings + s.rings_needed(&at));
            out.push(s.evaluate(f, u, v)?);
        }
        let next = need.min(MAX_EXACT_RINGS);
        if next <= rings {
            return Ok((out, rings));
        }
        rings = next;
    }
}
