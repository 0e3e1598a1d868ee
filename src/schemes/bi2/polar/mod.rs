//! Polar Bi-2 Subdivision (PolBS), Section 3 of the bi-2 paper: bi-2 subdivision of polar
//! nets, where a pole `p` is surrounded by a fan of triangles and rings of quads.
//!
//! # Polar nets and the conversion of caps
//!
//! A polar net around a pole `p` of valence `n` holds per sector `i` the points `a_i` (the
//! fan's ring), `b_i` and `c_i` (the next two rings, along the spoke of `a_i`). (The paper's
//! Fig. 9 is lost; this labelling is forced by the rules below.) A prism-like net has an
//! `n`-gon cap instead: [`to_polar_layout`] replaces every facet that is not a quad by a pole at
//! its centroid (or at a point the user gives) and the fan of triangles from it, which is the
//! paper's redesign of prisms (Fig. 8) and keeps the cap's vertices at valence 4.
//!
//! # Rules (the paper's numbering)
//!
//! The circular direction is never refined; the radial direction is refined by binary bi-2
//! (Chaikin) subdivision, except next to the pole:
//! - `b^new = 3/4 a + 1/4 b`, `c^new = 1/4 a + 3/4 b` (the Chaikin points of the spoke segment
//!   `a b`; every spoke segment farther out gets the same two points);
//! - (11) `a_i^new = (1 - sum_j gamma_j) p + sum_j gamma_j a_(i+j)`;
//! - (12) `p^new = (1 - alpha) p + alpha a_mean`, `alpha = 1/4`;
//! - (15) `gamma_j = (1/2 + cos(2 pi j / n)) / n`, so `beta = sum gamma_j = 1/2`;
//! - (16) the limit point `2/3 p + 1/3 a_mean`.
//!
//! One step is therefore Doo-Sabin's construction restricted to the radial direction: every
//! face corner gets the point of its face's spoke edge next to it (`a^new` for the spoke to the
//! pole, `p^new` for the pole), F-faces and the E-faces of circular edges are kept, the
//! degenerate E-faces of spoke edges and V-faces are dropped. A circular boundary ring is kept
//! (the doubled layer of the Doo-Sabin boundary rules, so the limit boundary is the ring's
//! periodic quadratic B-spline). [`PolarBi2`] refines *polar layouts*: nets whose faces are
//! pole fans and quads in rings around the poles (edge kinds are propagated from the poles);
//! anything else is an error naming the element (way out: `bi2-mixed --rings K`).

use crate::error::{Error, Result};
use crate::geom::Point;
use crate::mesh::Element;
use crate::mesh::PolyMesh;
use crate::schemes::options::ids;
use crate::schemes::{Refinement, Scheme, finish_refinement};
use crate::stencil::{Stencil, StencilTable};

/// `alpha` of (12).
pub const ALPHA: f64 = 0.25;

/// The parameters of PolBS at valence `n`.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct PolarParams {
    /// Valence of the pole.
    pub n: usize,
    /// `alpha = 1/4` of (12).
    pub alpha: f64,
    /// `gamma_0 .. gamma_(n-1)` of (15).
    pub gamma: Vec<f64>,
    /// `beta = sum gamma_j` (1/2).
    pub beta: f64,
}

impl PolarParams {
    /// The parameters at valence `n >= 3`.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for `n < 3`.
    pub fn new(n: usize) -> Result<PolarParams> {
        super::at_least_three(n, "a pole needs a valence of at least 3")?;
        let gamma: Vec<f64> = (0..n)
            .map(|j| (0.5 + super::cos_2pi(j as i64, n as i64)) / n as f64)
            .collect();
        let beta = gamma.iter().sum();
        Ok(PolarParams {
            n,
            alpha: ALPHA,
            gamma,
            beta,
        })
    }
}

mod layout;

pub use layout::{EdgeKind, PolarNet, Pole, edge_kinds, find_poles, is_cap, to_polar_layout};

/// PolBS as a whole-mesh scheme (name `polar-bi2`): prism-like caps are converted to poles at
/// their centroids (or at the given points) on the first step, then the net is refined
/// radially. A net with no pole and no cap has nothing polar: it is refined as
/// [`super::Bi2Mixed`] refines it (TPS at extraordinary vertices, PGS at facets). See the
/// [module](self) documentation.
#[derive(Debug, Clone, Default)]
pub struct PolarBi2 {
    /// User-given poles: `(input face, position)` for caps that should not use the centroid.
    pub poles: Vec<(usize, Point)>,
}

impl PolarBi2 {
    /// The spoke edge of face `f` at its corner `h` (the edge of `h` or of `prev(h)` that is
    /// radial), or `None` at a pole corner.
    fn corner_spoke(mesh: &PolyMesh, kinds: &[EdgeKind], is_pole: &[bool], h: u32) -> Option<u32> {
        if is_pole[mesh.he_from(h) as usize] {
            return None;
        }
        if kinds[mesh.he_edge(h) as usize] == EdgeKind::Radial {
            Some(h)
        } else {
            Some(mesh.he_prev(h))
        }
    }
}

/// One radial step of a polar layout (see the [module](self) documentation).
///
/// # Errors
/// [`Error::Unsupported`] when the net is not a polar layout.
pub fn radial_step(mesh: &PolyMesh) -> Result<Refinement> {
    Ok(radial_step_detailed(mesh)?.refinement)
}

/// A radial step with the child indices of its points.
#[derive(Debug, Clone)]
pub struct RadialStep {
    /// The refinement.
    pub refinement: Refinement,
    /// Child point `p^new` of each pole (`u32::MAX` for other vertices).
    pub pole_point: Vec<u32>,
    /// For every edge: the child points on it next to the start and the end of its
    /// [`PolyMesh::edge_halfedge`] (`u32::MAX` where there is none: circular edges, pole ends).
    pub spoke_point: Vec<[u32; 2]>,
}

/// [`radial_step`] with the child indices of its points.
///
/// # Errors
/// As [`radial_step`].
pub fn radial_step_detailed(mesh: &PolyMesh) -> Result<RadialStep> {
    let poles = find_poles(mesh);
    let kinds = edge_kinds(mesh, &poles)?;
    let nv = mesh.num_vertices();
    let mut is_pole = vec![false; nv];
    for &p in &poles {
        is_pole[p as usize] = true;
    }
    check_valences(mesh, &is_pole)?;
    let mut rows: Vec<Stencil> = Vec::new();
    let pole_pt = pole_points(mesh, &poles, &mut rows);
    let spoke_pt = spoke_points(mesh, &kinds, &is_pole, &mut rows)?;
    let mut kept = vec![UNSET; nv];
    for (v, slot) in kept.iter_mut().enumerate() {
        if mesh.is_boundary_vertex(v) {
            *slot = rows.len() as u32;
            rows.push(Stencil::point(v));
        }
    }
    let points = ChildPoints {
        kinds: &kinds,
        is_pole: &is_pole,
        pole_pt: &pole_pt,
        spoke_pt: &spoke_pt,
        kept: &kept,
    };
    let (face_start, corners) = points.faces(mesh);
    if corners.contains(&UNSET) {
        return Err(Error::Unsupported(
            "the polar layout is inconsistent (a face corner without a spoke point)".into(),
        ));
    }
    let table = StencilTable::from_rows(nv, rows, 8);
    Ok(RadialStep {
        refinement: finish_refinement(mesh, table, face_start, corners)?,
        pole_point: pole_pt,
        spoke_point: spoke_pt,
    })
}

/// A child index not (yet) given.
const UNSET: u32 = u32::MAX;

/// Every vertex but the poles has valence 4 (3 on a circular boundary), else an error naming
/// the vertex.
fn check_valences(mesh: &PolyMesh, is_pole: &[bool]) -> Result<()> {
    for (v, &pole) in is_pole.iter().enumerate() {
        if pole {
            continue;
        }
        let k = mesh.valence(v);
        let ok = if mesh.is_boundary_vertex(v) {
            k == 3
        } else {
            k == 4
        };
        if !ok {
            return Err(Error::Unsupported(format!(
                "vertex {v} has valence {k}; in a polar layout every vertex but the poles has \
                 valence 4 (3 on a circular boundary); write the exact surface of other nets \
                 with {} --rings K",
                ids::BI2_MIXED
            )));
        }
    }
    Ok(())
}

/// Rule (12): the child `p^new` of every pole, pushed to `rows`; per vertex its pole point's
/// index (`UNSET` for other vertices).
fn pole_points(mesh: &PolyMesh, poles: &[u32], rows: &mut Vec<Stencil>) -> Vec<u32> {
    let mut pole_pt = vec![UNSET; mesh.num_vertices()];
    for &p in poles {
        let hs: Vec<u32> = mesh.outgoing(p as usize).collect();
        let n = hs.len();
        let mut s = Stencil::new();
        s.add(p as usize, 1.0 - ALPHA);
        for &h in &hs {
            s.add(mesh.he_to(h) as usize, ALPHA / n as f64);
        }
        pole_pt[p as usize] = rows.len() as u32;
        rows.push(s.merged());
    }
    pole_pt
}

/// The child points on spoke edges, pushed to `rows`: the two Chaikin points of a spoke
/// segment, rule (11) on a spoke from a pole. Per edge: `[near from(edge half-edge), near to]`.
fn spoke_points(
    mesh: &PolyMesh,
    kinds: &[EdgeKind],
    is_pole: &[bool],
    rows: &mut Vec<Stencil>,
) -> Result<Vec<[u32; 2]>> {
    let mut spoke_pt = vec![[UNSET; 2]; mesh.num_edges()];
    for e in 0..mesh.num_edges() {
        if kinds[e] != EdgeKind::Radial {
            continue;
        }
        let h = mesh.edge_halfedge(e);
        let (a, b) = (mesh.he_from(h) as usize, mesh.he_to(h) as usize);
        match (is_pole[a], is_pole[b]) {
            (true, true) => {
                return Err(Error::Unsupported(format!(
                    "edge {e} joins two poles; poles must be separated by rings of quads"
                )));
            }
            (false, false) => {
                spoke_pt[e][0] = rows.len() as u32;
                rows.push(Stencil::from_pairs([(a, 0.75), (b, 0.25)]));
                spoke_pt[e][1] = rows.len() as u32;
                rows.push(Stencil::from_pairs([(a, 0.25), (b, 0.75)]));
            }
            (pa, _) => {
                let (p, v, k) = if pa { (a, b, 1) } else { (b, a, 0) };
                spoke_pt[e][k] = rows.len() as u32;
                rows.push(ring_point_stencil(mesh, p, v)?);
            }
        }
    }
    Ok(spoke_pt)
}

/// The child points of one radial step, by the parent element they belong to.
struct ChildPoints<'a> {
    kinds: &'a [EdgeKind],
    is_pole: &'a [bool],
    pole_pt: &'a [u32],
    spoke_pt: &'a [[u32; 2]],
    kept: &'a [u32],
}

impl ChildPoints<'_> {
    /// The point of face corner `h`: its pole's point or the point of its spoke edge next to
    /// it.
    fn corner(&self, mesh: &PolyMesh, h: u32) -> u32 {
        match PolarBi2::corner_spoke(mesh, self.kinds, self.is_pole, h) {
            None => self.pole_pt[mesh.he_from(h) as usize],
            Some(g) => {
                let e = mesh.he_edge(g) as usize;
                let v = mesh.he_from(h);
                let first = mesh.he_from(mesh.edge_halfedge(e)) == v;
                self.spoke_pt[e][if first { 0 } else { 1 }]
            }
        }
    }

    /// The child faces: every face's F-face, then the E-face of every circular edge (closed
    /// by the kept points on a boundary), as face starts and corners.
    fn faces(&self, mesh: &PolyMesh) -> (Vec<u32>, Vec<u32>) {
        let corner_pt = |h: u32| self.corner(mesh, h);
        let mut face_start = vec![0u32];
        let mut corners = Vec::new();
        for f in 0..mesh.num_faces() {
            let h0 = mesh.face_halfedge(f);
            for h in h0..h0 + mesh.face_size(f) as u32 {
                corners.push(corner_pt(h));
            }
            face_start.push(corners.len() as u32);
        }
        for (e, &kind) in self.kinds.iter().enumerate() {
            if kind != EdgeKind::Circular {
                continue;
            }
            let h = mesh.edge_halfedge(e);
            let quad = match mesh.he_twin(h) {
                Some(t) => [
                    corner_pt(mesh.he_next(h)),
                    corner_pt(h),
                    corner_pt(mesh.he_next(t)),
                    corner_pt(t),
                ],
                None => [
                    corner_pt(mesh.he_next(h)),
                    corner_pt(h),
                    self.kept[mesh.he_from(h) as usize],
                    self.kept[mesh.he_to(h) as usize],
                ],
            };
            corners.extend_from_slice(&quad);
            face_start.push(corners.len() as u32);
        }
        (face_start, corners)
    }
}

/// Rule (11): the new ring point on the spoke from pole `p` to its fan vertex `v`.
fn ring_point_stencil(mesh: &PolyMesh, p: usize, v: usize) -> Result<Stencil> {
    let hs: Vec<u32> = mesh.outgoing(p).collect();
    let n = hs.len();
    let prm = PolarParams::new(n)?;
    let i = hs
        .iter()
        .position(|&h| mesh.he_to(h) as usize == v)
        .ok_or_else(|| Error::Unsupported(format!("vertex {v} is not next to pole {p}")))?;
    let mut s = Stencil::new();
    s.add(p, 1.0 - prm.beta);
    for (j, &g) in prm.gamma.iter().enumerate() {
        s.add(mesh.he_to(hs[(i + j) % n]) as usize, g);
    }
    Ok(s.merged())
}

impl PolarBi2 {
    /// The stencils of the conversion of `mesh` to its polar layout `net`: the vertices stay,
    /// each new pole is its cap's centroid. A user-given pole is not an affine combination of
    /// the net: it becomes a constant, which stencils cannot hold, so it is refused rather than
    /// lost.
    fn conversion(&self, mesh: &PolyMesh, net: &PolarNet) -> Result<StencilTable> {
        let nv = mesh.num_vertices();
        let mut conv = StencilTable::with_capacity(nv, net.mesh.num_vertices(), 4);
        for v in 0..nv {
            conv.push(Stencil::point(v));
        }
        for p in &net.poles {
            if let Element::Face(f) = p.element {
                let verts = mesh.face(f as usize);
                let given = self.poles.iter().any(|x| x.0 == f as usize);
                // A user-given pole is not an affine combination of the net: it becomes a
                // constant, which stencils cannot hold. Refuse rather than lose it.
                if given {
                    return Err(Error::Unsupported(format!(
                        "a user-given pole for face {f} cannot be expressed as refinement \
                         stencils of the input net; use polar::to_polar_layout and refine the \
                         polar net it returns"
                    )));
                }
                let w = 1.0 / verts.len() as f64;
                conv.push(Stencil::from_pairs(verts.iter().map(|&x| (x as usize, w))));
            }
        }
        Ok(conv)
    }
}

impl Scheme for PolarBi2 {
    fn step_size(&self, s: &crate::schemes::growth::NetSize) -> crate::schemes::growth::NetSize {
        crate::schemes::growth::ternary(s)
    }

    fn name(&self) -> &'static str {
        crate::schemes::options::ids::POLAR_BI2.name()
    }

    /// Converts caps to poles (no-op on a polar layout), then one radial step; a net without
    /// poles is refined as `bi2-mixed` refines it.
    fn refine(&self, mesh: &PolyMesh) -> Result<Refinement> {
        let net = to_polar_layout(mesh, &self.poles)?;
        if net.poles.is_empty() {
            return super::Bi2Mixed.refine(mesh);
        }
        if net.mesh.num_vertices() == mesh.num_vertices() {
            return radial_step(mesh);
        }
        // The conversion adds poles: compose its (trivial) stencils with the step.
        let r = radial_step(&net.mesh)?;
        let stencils = r.stencils.compose(&self.conversion(mesh, &net)?);
        Ok(Refinement {
            mesh: r.mesh,
            stencils,
        })
    }

    /// Converts caps once, then `levels` radial steps (as `refine_uniform`), each with its
    /// stencils (the first composed with the conversion's); a net without poles is refined as
    /// `bi2-mixed` refines it.
    fn refine_steps(
        &self,
        mesh: &PolyMesh,
        levels: usize,
        step: &mut dyn FnMut(&PolyMesh, &mut Refinement) -> Result<()>,
    ) -> Result<PolyMesh> {
        let net = to_polar_layout(mesh, &self.poles)?;
        if net.poles.is_empty() {
            return super::Bi2Mixed.refine_steps(mesh, levels, step);
        }
        if levels == 0 {
            return Ok(mesh.clone());
        }
        let mut r = radial_step(&net.mesh)?;
        if net.mesh.num_vertices() != mesh.num_vertices() {
            r.stencils = r.stencils.compose(&self.conversion(mesh, &net)?);
        }
        step(mesh, &mut r)?;
        let mut m = r.mesh;
        for _ in 1..levels {
            let mut r = radial_step(&m)?;
            step(&m, &mut r)?;
            m = r.mesh;
        }
        Ok(m)
    }

    /// Converts caps once (with the user's poles), then `levels` radial steps.
    fn refine_uniform(
        &self,
        mesh: &PolyMesh,
        levels: usize,
        progress: &mut dyn FnMut(usize),
    ) -> Result<PolyMesh> {
        let net = to_polar_layout(mesh, &self.poles)?;
        if net.poles.is_empty() {
            return super::Bi2Mixed.refine_uniform(mesh, levels, progress);
        }
        let mut m = net.mesh;
        for l in 0..levels {
            m = radial_step(&m)?.mesh;
            progress(l + 1);
        }
        Ok(m)
    }

    /// Limit points: (16) at poles and at the ring next to a pole (the ring's points converge
    /// to the pole's limit point under refinement: the cap contracts to it), the centre of the
    /// bi-2 patch at vertices with four quads (and on circular boundaries with the doubled
    /// layer).
    fn limit_stencils(&self, mesh: &PolyMesh) -> Result<StencilTable> {
        let poles = find_poles(mesh);
        let nv = mesh.num_vertices();
        let mut pole_of = vec![u32::MAX; nv];
        for &p in &poles {
            pole_of[p as usize] = p;
            for x in mesh.vertex_neighbors(p as usize) {
                pole_of[x as usize] = p;
            }
        }
        let mut table = StencilTable::with_capacity(nv, nv, 9);
        for (v, &pv) in pole_of.iter().enumerate() {
            if pv != u32::MAX {
                let p = pv as usize;
                let hs: Vec<u32> = mesh.outgoing(p).collect();
                let n = hs.len() as f64;
                let mut s = Stencil::new();
                s.add(p, 2.0 / 3.0);
                for &h in &hs {
                    s.add(mesh.he_to(h) as usize, 1.0 / (3.0 * n));
                }
                table.push(s.merged());
                continue;
            }
            let Some(coef) = crate::schemes::doo_sabin::surface::regular_vertex_patch(mesh, v)
            else {
                return Err(Error::Unsupported(format!(
                    "vertex {v} is not in a polar layout (it has no regular bi-2 patch and is not \
                     next to a pole): {} has no limit position for it; write the exact \
                     surface with --rings K",
                    ids::POLAR_BI2
                )));
            };
            // The patch's centre value: Bernstein weights (1/4, 1/2, 1/4) in both directions.
            let b = [0.25, 0.5, 0.25];
            let mut s = Stencil::new();
            for i in 0..3 {
                for j in 0..3 {
                    s.add_scaled(&coef[3 * i + j], b[i] * b[j]);
                }
            }
            table.push(s.merged());
        }
        Ok(table)
    }
}

/// The canonical polar net of valence `n` for analysis: the pole (vertex 0), then per sector
/// `s` the points `a_s, b_s, c_s` (vertices `1 + 3s .. 3 + 3s`) on the spoke at angle
/// `2 pi s / n`, radii 1, 2, 3, heights `height(x, y)`.
pub fn polar_net(n: usize, height: impl Fn(f64, f64) -> f64) -> Result<PolyMesh> {
    super::at_least_three(n, "a polar net needs a valence of at least 3")?;
    let mut pos = vec![[0.0, 0.0, height(0.0, 0.0)]];
    for s in 0..n {
        let (c, sn) = (
            super::cos_2pi(s as i64, n as i64),
            super::cos_2pi(4 * s as i64 - n as i64, 4 * n as i64),
        );
        for r in 1..=3 {
            let (x, y) = (r as f64 * c, r as f64 * sn);
            pos.push([x, y, height(x, y)]);
        }
    }
    let id = |s: usize, r: usize| 1 + 3 * (s % n) + r;
    let mut faces: Vec<Vec<usize>> = Vec::new();
    for s in 0..n {
        faces.push(vec![0, id(s, 0), id(s + 1, 0)]);
        for r in 0..2 {
            faces.push(vec![id(s, r), id(s, r + 1), id(s + 1, r + 1), id(s + 1, r)]);
        }
    }
    PolyMesh::new(pos, &faces)
}
