//! Evaluation of an exact surface at any `(face, u, v)` of its input net: position, first and
//! second derivatives with respect to the face's parameters, normal, Gauss and mean curvature,
//! and which patch (and where in it) the point lies in.
//!
//! A [`Surface`] is a patch complex whose patches carry the [`Domain`](crate::bezier::domain::Domain) of their input face (the
//! adaptive host records it for the schemes whose [`Capabilities`] say `eval`: Catmull-Clark,
//! Loop, and EG, the QAS+ family and guided subdivision, whose caps tile each sector's face in
//! their rings' chart, see [`crate::schemes::eg::surface`] and [`crate::schemes::guided::surface`];
//! the dual schemes Doo-Sabin, DS^CC and PGS, whose patches of input vertices cover a quarter
//! of each face around them as [`Piece`](crate::bezier::complex::Piece)s; TPS, laid out like
//! them, whose rings are cells in thirds of the quarters at extraordinary vertices, see
//! `crate::schemes::bi2::surface::thirds`). The parameter domain of quads, n-gons and
//! triangles (and of the dual schemes' faces) is documented in [`crate::bezier::domain`]. Each cell of a face is either covered by one patch or split into
//! children, so the cells form a tree per face: a point is located by descending it, one
//! array step per level (`index`; `O(log)` of the patch size, independent of the number of
//! patches, and no step at all on a face one patch covers).
//! A cell whose children are thirds (TPS) is split 3 x 3 in the tree (`index`), so the
//! descent takes the 3 x 3 grid there (the dyadic schemes have no such cells: their descent
//! is the quadtree's).
//!
//! Patch parameters are mapped to face parameters by affine maps with dyadic coefficients
//! (exact in floating point); derivatives go through the chain rule of that map. Points in the
//! hole inside the last ring lie on the cap or fill patch of their cell: Catmull-Clark's G^1
//! cap patch of a sector has its `(0, 0)` at the centre, `u` along the sector's first spoke and
//! `v` along its second, so it covers the sector's remaining square exactly as the cell's own
//! coordinates rotated to the centre corner; the Hermite-Coons fill and Loop's fill have the
//! cell's own corners. Loop's G^1 cap is made of kites, each covering halves of two fan
//! triangles: a point of a fan triangle is mapped to the kite that holds it by inverting the
//! kite's bilinear map in the triangle's lattice chart (`kite`), and derivatives go through
//! the inverse function rule (the map is not affine there); `patch` names that kite and
//! `patch_uv` its parameters. Loop's cap at a boundary vertex covers each fan triangle with one
//! patch whose bilinear map has a straight corner at the outer edge's midpoint
//! (`fan_piece`, likewise inverted; at that one point the derivatives are one-sided limits
//! taken just inside). Loop's triangles, stored as collapsed bi-4 patches `X(u, v) = T(u (1 -
//! v), v)`, are evaluated as the triangles `T` they represent (barycentric derivatives, defined at
//! the collapsed corner too); their `patch_uv` is the stored patch's `(u, v)`. Non-box's
//! regular cells are covered by the four cubic triangles of their criss-cross (the cell split
//! by both diagonals, [`Domain::criss_cross`](crate::bezier::domain::Domain::criss_cross)):
//! the cell is one leaf, and a point is mapped to its triangle's barycentric parameters by
//! the affine maps of `crisscross`, then evaluated as Loop's triangles are. `nonbox-4dir`'s
//! triangles are fan triangles of the polygons its complex is built on
//! ([`FanTriangle`], [`Surface::of_scheme`]): a point is mapped to its polygon first.
//! A pole's fan triangles (polar bi-2) are collapsed quads whose radial rings are cells
//! halved along one axis (`bezier::domain`'s `halves`; the tree splits such a cell in two).
//!
//! [`evaluate_limit`] evaluates the scheme's limit surface itself: it builds the complex with as
//! many rings as the points need (a point at distance about `2^-k` of an extraordinary element,
//! in face parameters, needs about `k` rings), up to [`MAX_EXACT_RINGS`].

pub(crate) mod charts;
mod crisscross;
mod fan_piece;
mod index;
mod kite;
mod limit;
pub use limit::{
    FIRST_RINGS, evaluate_limit, first_targets, limit_surface, limit_surface_from,
    quad_corner_targets,
};
mod triangle;

use crate::bezier::Derivatives;
use crate::bezier::complex::PatchComplex;
use crate::bezier::domain::{FanTriangle, Shape};
use crate::error::{Error, Result};
use crate::geom::Point;
use crate::host::ComplexOptions;
use crate::mesh::PolyMesh;
use crate::schemes::descriptor::Capabilities;
use crate::schemes::{Spec, registry};
use index::{CellTree, Leaf};
use serde::Serialize;
use std::collections::{HashMap, HashSet};

/// Rings [`evaluate_limit`] computes at most. Points nearer an extraordinary element than about
/// `2^-MAX_EXACT_RINGS` of their face are evaluated on the cap inside that ring, which differs
/// from the limit surface by about `lambda^MAX_EXACT_RINGS` times the element's size
/// (`4e-11` for Catmull-Clark at valence 5, `lambda = 0.55`).
pub const MAX_EXACT_RINGS: usize = 40;

/// The surface and its derivatives at one point of an input face.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
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

/// A patch complex that can be evaluated at `(face, u, v)` of its input net.
#[derive(Debug, Clone)]
pub struct Surface {
    complex: PatchComplex,
    /// Corners of each face the domains refer to (the input faces, unless `fans` is set).
    sides: Vec<u32>,
    /// The input faces when they are fan triangles of the faces the domains refer to
    /// ([`Surface::of_scheme`]); empty otherwise.
    fans: Vec<FanTriangle>,
    /// The triangles whose cells are quads (a 3-gon of three quad sub-faces: the dual
    /// schemes), not barycentric triangles (Loop).
    tri_strips: Vec<bool>,
    /// The triangles that are a pole's fan triangles (PolBS): one collapsed quad `[0, 1]^2`,
    /// not a strip ([`crate::bezier::domain`]'s poles).
    pole_triangles: Vec<bool>,
    /// The cells of every face and the patch or piece covering each ([`index`]).
    cells: CellTree,
    /// The spatial index of [`Surface::closest_point`], built on first use.
    pub(crate) projection: std::sync::OnceLock<crate::surface::closest::ProjectionIndex>,
    /// The kites of G^1 caps of triangle holes (Loop's): kite `s` -> kite `s - 1`, which
    /// covers the other half of kite `s`'s fan triangle ([`kite`]).
    kites: HashMap<usize, usize>,
    /// The patches of G^1 caps of open triangle fans (Loop's at boundary vertices), each over
    /// its fan triangle whole ([`fan_piece`]).
    fan_pieces: HashSet<usize>,
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
        Surface::of_scheme(spec, mesh, out.complex)
    }

    /// The surface of a complex built on `mesh` under `spec`: [`Surface::new`], with the input
    /// faces mapped to the faces the domains refer to where the scheme's
    /// [`Descriptor::eval_faces`](crate::schemes::descriptor::Descriptor::eval_faces) says so
    /// (`nonbox-4dir` on a triangle mesh).
    ///
    /// # Errors
    /// Those of the scheme's `eval_faces`.
    pub fn of_scheme(spec: &Spec, mesh: &PolyMesh, complex: PatchComplex) -> Result<Surface> {
        let fans = registry().descriptor(spec.id).eval_faces(spec, mesh)?;
        let mut s = Surface::new(mesh, complex);
        if let Some(fans) = fans.filter(|f| f.len() == mesh.num_faces()) {
            // the domains refer to the host faces the fan triangles lie in
            let hosts = fans.iter().map(|t| t.host as usize + 1).max().unwrap_or(0);
            let mut sides = vec![4; hosts];
            for t in &fans {
                sides[t.host as usize] = t.sides;
            }
            s = Surface::assemble(sides, s.complex);
            s.fans = fans;
        }
        Ok(s)
    }

    /// The surface of a complex built on `mesh` (patches without a domain are not found by
    /// [`Surface::evaluate`]).
    pub fn new(mesh: &PolyMesh, complex: PatchComplex) -> Surface {
        let sides: Vec<u32> = (0..mesh.num_faces())
            .map(|f| mesh.face_size(f) as u32)
            .collect();
        Surface::assemble(sides, complex)
    }

    /// The surface of a complex whose domains refer to faces with `sides` corners.
    fn assemble(sides: Vec<u32>, complex: PatchComplex) -> Surface {
        let fans = Vec::new();
        let mut tri_strips = vec![false; sides.len()];
        // a triangle whose cells are halves from level 1 on (a pole's fan) and all in its
        // first root cell is one collapsed quad; a 3-gon cap turned into a pole has halves in
        // all three sub-faces (its strip)
        let mut halved = vec![false; sides.len()];
        let mut strip = vec![false; sides.len()];
        let quad_domains = (0..complex.len())
            .filter_map(|i| complex.domain(i))
            .chain(complex.pieces.iter().map(|p| p.domain));
        for d in quad_domains {
            let f = d.face as usize;
            if f < sides.len() && d.shape == Shape::Quad && sides[f] == 3 {
                tri_strips[f] = true;
                halved[f] |= d.splits_in_halves(1);
                strip[f] |= d.sub != 0;
            }
        }
        let pole_triangles: Vec<bool> = halved.iter().zip(&strip).map(|(h, s)| *h && !s).collect();
        for (t, &p) in tri_strips.iter_mut().zip(&pole_triangles) {
            *t &= !p;
        }
        let cells = CellTree::new(&sides, &pole_triangles, &complex);
        let mut kites = HashMap::new();
        let mut fan_pieces = HashSet::new();
        for step in &complex.caps {
            // (a partly kept cap is of quad sectors: `nonbox`'s, beside hole faces)
            if step.hole.sectors.first().is_some_and(|s| s.len() == 1) && step.kept.is_none() {
                let (first, n) = (step.first as usize, step.count as usize);
                for s in 0..n {
                    if step.hole.is_open() {
                        fan_pieces.insert(first + s);
                    } else {
                        kites.insert(first + s, first + (s + n - 1) % n);
                    }
                }
            }
        }
        Surface {
            complex,
            sides,
            fans,
            tri_strips,
            pole_triangles,
            cells,
            projection: std::sync::OnceLock::new(),
            kites,
            fan_pieces,
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
            3 if self.pole_triangles[face as usize] => {
                if !(0.0..=1.0).contains(&u) || !(0.0..=1.0).contains(&v) {
                    return Err(bad(
                        "[0, 1] x [0, 1] (a pole's fan triangle: (0, 0) at the corner after the \
                         pole, v = 1 the pole)",
                    ));
                }
                Ok((0, Shape::Quad, [u, v]))
            }
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

    /// A point of a fan triangle input face ([`FanTriangle`]): its host face, the host's
    /// sub-face and the point in its coordinates, and the derivative of those by `(u, v)`.
    fn fan_point(&self, face: u32, u: f64, v: f64) -> Result<(u32, u32, [f64; 2], Jacobian)> {
        let t = self.fans.get(face as usize).ok_or_else(|| {
            Error::InvalidArgument(format!(
                "face {face} does not exist: the net has {} faces (0..{})",
                self.fans.len(),
                self.fans.len()
            ))
        })?;
        if !(u.is_finite() && v.is_finite()) || u < 0.0 || v < 0.0 || u + v > 1.0 + 1e-12 {
            return Err(Error::InvalidArgument(format!(
                "face {face} (3 sides): (u, v) = ({u}, {v}) is outside its domain u, v >= 0, \
                 u + v <= 1"
            )));
        }
        let (sub, p, jac) = t.to_host(u, v);
        Ok((t.host, sub, p, jac))
    }

    /// The leaf holding a face point (the face's cells descended from the root) and the
    /// point in its cell's coordinates.
    /// With fan faces (`fans`), the host face's leaf and the derivative of the host face's
    /// parameters by the input face's (`None` otherwise).
    fn locate(&self, face: u32, u: f64, v: f64) -> Result<(&Leaf, [f64; 2], Option<Jacobian>)> {
        let (host, sub, shape, p, jac) = if self.fans.is_empty() {
            let (sub, shape, p) = self.face_point(face, u, v)?;
            (face, sub, shape, p, None)
        } else {
            let (host, sub, p, jac) = self.fan_point(face, u, v)?;
            (host, sub, Shape::Quad, p, Some(jac))
        };
        let found = self.cells.locate(host, sub, shape, p);
        found.map(|(leaf, cell)| (leaf, cell, jac)).ok_or_else(|| {
            Error::InvalidArgument(format!(
                "no patch of the surface covers face {face} at (u, v) = ({u}, {v}): the face \
                 is one of the net's hole faces (OpenSubdiv's hole tag: no surface there), the \
                 hole inside the last ring is open (--no-fill), or the patches there carry no \
                 face domain (the quarters at boundary vertices under boundary mode none)"
            ))
        })
    }

    /// The surface at parameter `(u, v)` of input face `face` (see [`crate::bezier::domain`]
    /// for the domains of quads, n-gons and triangles).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] naming the face for a face index out of range, `(u, v)`
    /// outside the face's domain, or a point no patch covers (the hole left open).
    pub fn evaluate(&self, face: u32, u: f64, v: f64) -> Result<Evaluation> {
        let (at, cell, fan) = self.locate(face, u, v)?;
        self.evaluate_located(face, u, v, at, cell, fan)
    }

    /// [`Surface::evaluate`] at the point `cell` of leaf `at` (with `fan`, the derivative of
    /// the host face's parameters by the input face's), recorded as `(face, u, v)`.
    fn evaluate_located(
        &self,
        face: u32,
        u: f64,
        v: f64,
        at: &Leaf,
        cell: [f64; 2],
        fan: Option<Jacobian>,
    ) -> Result<Evaluation> {
        let (mut df, index, patch_uv, normal) = self.leaf_derivatives(at, cell, true)?;
        if let Some(jac) = fan {
            df = chain(&df, jac);
        }
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

    /// The surface at the point `cell` of leaf `at`, with its derivatives by the face's
    /// parameters (before a fan triangle's map), the patch evaluated, where in it, and (with
    /// `with_normal`, else NaN) the unit normal: [`Surface::evaluate`] without the search and
    /// the curvature (what `closest`'s Newton steps need).
    fn leaf_derivatives(
        &self,
        at: &Leaf,
        cell: [f64; 2],
        with_normal: bool,
    ) -> Result<(Derivatives, usize, [f64; 2], Point)> {
        let maps = self.cells.maps(at);
        let mut index = at.patch as usize;
        let patch = &self.complex.patches[index];
        let mut q = maps.corner_point(cell);
        if let Some(w) = maps.window {
            q = w.apply(q);
        }
        let none = [f64::NAN; 3];
        let (dp, normal, patch_uv) = match at.shape {
            Shape::Quad if at.criss_cross.is_some() && index + 3 < self.complex.len() => {
                let (k, st, jac) = crisscross::locate(q);
                index += k;
                let dp = triangle::derivatives(&self.complex.patches[index], st)?;
                let n = with_normal
                    .then(|| dp.normal_toward([1.0 / 3.0 - st[0], 1.0 / 3.0 - st[1]]))
                    .flatten()
                    .unwrap_or(none);
                (crisscross::to_cell(&dp, jac), n, triangle::stored_uv(st))
            }
            Shape::Quad => {
                let dp = patch.derivatives(q[0], q[1]);
                let n = if with_normal {
                    patch.normal_from(q[0], q[1], &dp)
                } else {
                    none
                };
                (dp, n, q)
            }
            Shape::Triangle if self.kites.contains_key(&index) => {
                let (neighbour, uv) = kite::locate(q);
                if neighbour {
                    index = self.kites[&index];
                }
                let patch = &self.complex.patches[index];
                let dp = patch.derivatives(uv[0], uv[1]);
                let n = if with_normal {
                    patch.normal_from(uv[0], uv[1], &dp)
                } else {
                    none
                };
                (kite::to_chart(&dp, uv, neighbour), n, uv)
            }
            Shape::Triangle if self.fan_pieces.contains(&index) => {
                let uv = fan_piece::locate(q);
                let n = if with_normal {
                    patch.normal_from(uv[0], uv[1], &patch.derivatives(uv[0], uv[1]))
                } else {
                    none
                };
                (fan_piece::chart_derivatives(patch, uv), n, uv)
            }
            Shape::Triangle => {
                let dp = triangle::derivatives(patch, q)?;
                let n = with_normal
                    .then(|| dp.normal_toward([1.0 / 3.0 - q[0], 1.0 / 3.0 - q[1]]))
                    .flatten()
                    .unwrap_or(none);
                (dp, n, triangle::stored_uv(q))
            }
        };
        Ok((chain(&dp, maps.chain), index, patch_uv, normal))
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

    /// [`Surface::evaluate`] at many points into `out` (`out[i]` for `points[i]`), in parallel,
    /// without a `Result` or an allocation per point: the batch path of the CLI, the Python
    /// package and the benchmarks. On failure it returns the index of the first point that
    /// fails with its error; the entries of `out` are then unspecified.
    ///
    /// # Errors
    /// `(i, e)` for the first point `i` that [`Surface::evaluate`] refuses; `(0, e)` when
    /// `out` and `points` differ in length.
    pub fn evaluate_into(
        &self,
        points: &[(u32, f64, f64)],
        out: &mut [Evaluation],
    ) -> std::result::Result<(), (usize, Error)> {
        use rayon::prelude::*;
        if out.len() != points.len() {
            return Err((
                0,
                Error::InvalidArgument(format!(
                    "{} points but room for {} evaluations",
                    points.len(),
                    out.len()
                )),
            ));
        }
        const CHUNK: usize = 2048;
        let first = out
            .par_chunks_mut(CHUNK)
            .zip(points.par_chunks(CHUNK))
            .enumerate()
            .filter_map(|(c, (out, pts))| {
                for (j, (o, &(f, u, v))) in out.iter_mut().zip(pts).enumerate() {
                    match self.evaluate(f, u, v) {
                        Ok(e) => *o = e,
                        Err(e) => return Some((c * CHUNK + j, e)),
                    }
                }
                None
            })
            .min_by_key(|(i, _)| *i);
        first.map_or(Ok(()), Err)
    }

    /// The first of `points` (by index) that lies outside its face's domain or on no patch,
    /// with [`Surface::evaluate`]'s error for it (checked in parallel, nothing evaluated): what
    /// a caller checks before streaming the evaluations of many points.
    pub fn first_unlocated(&self, points: &[(u32, f64, f64)]) -> Option<(usize, Error)> {
        use rayon::prelude::*;
        points
            .par_iter()
            .enumerate()
            .filter_map(|(i, &(f, u, v))| self.locate(f, u, v).err().map(|e| (i, e)))
            .min_by_key(|(i, _)| *i)
    }
}

/// `jac[a][b]`: the derivative of parameter `a` of one chart by parameter `b` of another.
type Jacobian = [[f64; 2]; 2];

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
