//! Mixed bi-2 meshes (Section 5 and Fig. 15 of the bi-2 paper): regular bi-2 regions, PGS at
//! extraordinary facets, TPS at extraordinary vertices and PolBS at poles, in one surface.
//!
//! # How binary and ternary rings meet
//!
//! They never have to. Every vertex of a quad net with four quads carries one exact bi-2 patch
//! of the *input* net, and these regular patches leave one hole per extraordinary element: the
//! patches of a facet's corners (PGS), the patch of an extraordinary vertex (TPS), the cap
//! inside the ring next to a pole (PolBS). Each hole is filled by its own scheme's nested rings,
//! computed from the element's local net alone: ring 1 joins the regular patches around the
//! hole exactly as a uniformly refined bi-2 net would (its outer points are bi-2 refinement of
//! the input), and ring `l + 1` joins ring `l` by the scheme's construction. So a binary ring
//! sequence (PGS, contraction `lambda_sub`; PolBS, radial 1/2) and a ternary one (TPS, 1/3 and
//! faster) sit side by side inside the same C^1 bi-2 surface, each joined C^1 to the shared
//! regular patches; no net is refined globally. The elements must be separated: the vertices
//! around each hole must be regular (see [`classify`]); otherwise the error names the vertex.
//!
//! Whole-net refinement of a mixed net is not possible (the paper: "it is difficult to imagine
//! how pure mesh refinement would cope"): [`Bi2Mixed::refine`] refines a net whose elements
//! are all of one kind with that kind's scheme, and refuses a net that mixes kinds.

use super::{Pgs, PolarBi2, Tps};
use crate::error::{Error, Result};
use crate::geom::{self, Point};
use crate::mesh::{Element, PolyMesh};
use crate::schemes::options::ids;
use crate::schemes::{Refinement, Scheme};
use crate::stencil::StencilTable;

/// An extraordinary element of a bi-2 net and the scheme that fills its hole.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Bi2Element {
    /// A facet that is not a quad (PGS).
    Facet(u32),
    /// An interior vertex of valence `!= 4` surrounded by quads (TPS).
    Vertex(u32),
    /// A pole: an interior vertex surrounded by triangles (PolBS).
    Pole(u32),
}

/// The extraordinary elements of `mesh`: poles ([`super::polar::find_poles`]), facets that are
/// not quads and not in a pole's fan, and interior vertices of valence `!= 4` whose faces are
/// all quads.
pub fn elements(mesh: &PolyMesh) -> Vec<Bi2Element> {
    let poles = super::polar::find_poles(mesh);
    let mut in_fan = vec![false; mesh.num_faces()];
    let mut out = Vec::new();
    for &p in &poles {
        for f in mesh.vertex_faces(p as usize) {
            in_fan[f as usize] = true;
        }
        out.push(Bi2Element::Pole(p));
    }
    for (f, &fan) in in_fan.iter().enumerate() {
        if !fan && mesh.face_size(f) != 4 {
            out.push(Bi2Element::Facet(f as u32));
        }
    }
    for v in 0..mesh.num_vertices() {
        if mesh.is_boundary_vertex(v) || mesh.valence(v) == 4 {
            continue;
        }
        if mesh
            .vertex_faces(v)
            .iter()
            .all(|&f| mesh.face_size(f as usize) == 4)
        {
            out.push(Bi2Element::Vertex(v as u32));
        }
    }
    out
}

/// The kinds of elements present: (facets, vertices, poles).
pub fn classify(mesh: &PolyMesh) -> (bool, bool, bool) {
    let el = elements(mesh);
    (
        el.iter().any(|e| matches!(e, Bi2Element::Facet(_))),
        el.iter().any(|e| matches!(e, Bi2Element::Vertex(_))),
        el.iter().any(|e| matches!(e, Bi2Element::Pole(_))),
    )
}

/// The elements of a net with more than one kind of element (none when all are of one kind):
/// what the mixed net's refinement cannot take (the preparation's test,
/// [`crate::schemes::prepare::Need::Scheme`]).
pub fn mixed_kinds(mesh: &PolyMesh, _: &crate::schemes::descriptor::Spec) -> Vec<Element> {
    let (f, v, p) = classify(mesh);
    if u8::from(f) + u8::from(v) + u8::from(p) <= 1 {
        return Vec::new();
    }
    elements(mesh)
        .into_iter()
        .map(|e| match e {
            Bi2Element::Facet(f) => Element::Face(f),
            Bi2Element::Vertex(v) | Bi2Element::Pole(v) => Element::Vertex(v),
        })
        .collect()
}

/// The mixed bi-2 scheme (name `bi2-mixed`). Its exact surface (`--rings K`) takes any mix of
/// elements ([`crate::schemes::bi2::surface::mixed_complex`]); its net refinement only a net with one
/// kind of element (see the [module](self) documentation).
#[derive(Debug, Clone, Copy, Default)]
pub struct Bi2Mixed;

/// Which single scheme refines a net under `bi2-mixed`.
fn chosen(mesh: &PolyMesh) -> Result<Box<dyn Scheme>> {
    match classify(mesh) {
        (_, false, false) => Ok(Box::new(Pgs)),
        (false, true, false) => Ok(Box::new(Tps)),
        (false, false, true) => Ok(Box::new(PolarBi2::default())),
        (f, v, p) => {
            let mut kinds = Vec::new();
            if f {
                kinds.push("facets that are not quads (PGS, binary)");
            }
            if v {
                kinds.push("extraordinary vertices (TPS, ternary)");
            }
            if p {
                kinds.push("poles (PolBS, radial only)");
            }
            Err(Error::Unsupported(format!(
                "{}: this net has {}; no single net refinement holds binary, ternary and \
                 radial rules at once (the bi-2 paper, Section 5), so there is no refined net: \
                 write the exact surface with --rings K, or refine with {}, {} or {} \
                 alone",
                ids::BI2_MIXED,
                kinds.join(" and "),
                ids::PGS,
                ids::TPS,
                ids::POLAR_BI2,
            )))
        }
    }
}

impl Scheme for Bi2Mixed {
    fn step_size(&self, s: &crate::schemes::growth::NetSize) -> crate::schemes::growth::NetSize {
        use crate::schemes::growth;
        // one kind of element per net: the larger of the binary (PGS) and ternary splits
        growth::larger(&growth::dual(s), &growth::ternary(s))
    }

    fn name(&self) -> &'static str {
        crate::schemes::options::ids::BI2_MIXED.name()
    }

    /// One step of the net's single kind of scheme (PGS when there is no element); an error
    /// for a net that mixes kinds.
    fn refine(&self, mesh: &PolyMesh) -> Result<Refinement> {
        chosen(mesh)?.refine(mesh)
    }

    /// `levels` steps of the scheme chosen for the input net.
    fn refine_uniform(
        &self,
        mesh: &PolyMesh,
        levels: usize,
        progress: &mut dyn FnMut(usize),
    ) -> Result<PolyMesh> {
        chosen(mesh)?.refine_uniform(mesh, levels, progress)
    }

    /// The steps of the scheme chosen for the input net.
    fn refine_steps(
        &self,
        mesh: &PolyMesh,
        levels: usize,
        step: &mut dyn FnMut(&PolyMesh, &mut Refinement) -> Result<()>,
    ) -> Result<PolyMesh> {
        chosen(mesh)?.refine_steps(mesh, levels, step)
    }

    /// The limit stencils of the chosen scheme.
    fn limit_stencils(&self, mesh: &PolyMesh) -> Result<StencilTable> {
        chosen(mesh)?.limit_stencils(mesh)
    }
}

/// A ternary split of every face of a polygon mesh: an `n`-gon becomes a central `n`-gon (its
/// corners two thirds of the way to the centroid, so a quad splits uniformly), `n` corner quads and `n` edge quads; edges are split at
/// thirds. Facets get DS-nets and vertices keep their valence, so two splits separate every
/// extraordinary element from the others: the kind of net of the paper's Fig. 15 (see
/// [`fig15_like_net`]). A topological construction for making test and demo nets, not a
/// subdivision scheme (the positions are piecewise linear).
///
/// # Errors
/// When the split net is invalid (cannot happen for a valid input mesh).
pub fn ternary_split(m: &PolyMesh) -> Result<PolyMesh> {
    let nh = m.num_halfedges();
    let mut pos: Vec<Point> = m.positions().to_vec();
    // Edge children per half-edge: next to from(h).
    let mut ec = vec![0usize; nh];
    for h in 0..nh as u32 {
        if m.he_twin(h).is_some_and(|t| t < h) {
            // The twin's pair serves this half-edge too (see `near`).
            ec[h as usize] = usize::MAX;
            continue;
        }
        let (a, b) = (
            m.position(m.he_from(h) as usize),
            m.position(m.he_to(h) as usize),
        );
        ec[h as usize] = pos.len();
        pos.push(geom::lerp(a, b, 1.0 / 3.0));
        pos.push(geom::lerp(a, b, 2.0 / 3.0));
    }
    let near = |h: u32, at_from: bool| -> usize {
        match m.he_twin(h) {
            Some(t) if t < h => ec[t as usize] + usize::from(at_from),
            _ => ec[h as usize] + usize::from(!at_from),
        }
    };
    let mut fc = vec![0usize; nh];
    for f in 0..m.num_faces() {
        let c = m.face_centroid(f);
        let h0 = m.face_halfedge(f);
        for h in h0..h0 + m.face_size(f) as u32 {
            fc[h as usize] = pos.len();
            pos.push(geom::lerp(m.position(m.he_from(h) as usize), c, 2.0 / 3.0));
        }
    }
    let mut faces: Vec<Vec<usize>> = Vec::new();
    for f in 0..m.num_faces() {
        let h0 = m.face_halfedge(f);
        let k = m.face_size(f) as u32;
        faces.push((h0..h0 + k).map(|h| fc[h as usize]).collect());
        for i in 0..k {
            let h = h0 + i;
            let hp = h0 + (i + k - 1) % k;
            let hn = h0 + (i + 1) % k;
            let v = m.he_from(h) as usize;
            faces.push(vec![v, near(h, true), fc[h as usize], near(hp, false)]);
            faces.push(vec![
                near(h, true),
                near(h, false),
                fc[hn as usize],
                fc[h as usize],
            ]);
        }
    }
    PolyMesh::new(pos, &faces)
}

/// A net in the spirit of the paper's Fig. 15 (whose mesh is lost with the figure): two ternary
/// splits ([`ternary_split`]) of the `n`-sided prism of the gallery, its points then smoothed
/// by 20 Taubin steps (Laplacian weights 0.5, -0.53) so that the net is rounded. Its
/// two `n`-gons are PGS facets, its `2 n` cap corners of valence 3 are TPS vertices, everything
/// else is regular bi-2: binary and ternary rings in one surface (`fairsub subdivide --scheme
/// bi2-mixed`).
///
/// # Errors
/// For `n < 3`.
pub fn fig15_like_net(n: usize) -> Result<PolyMesh> {
    if n < 3 {
        return Err(Error::InvalidArgument(format!(
            "a prism needs n >= 3 sides (got {n})"
        )));
    }
    let mut m = ternary_split(&ternary_split(&crate::mesh::nets::prism(n))?)?;
    let nbrs: Vec<Vec<u32>> = (0..m.num_vertices())
        .map(|v| m.vertex_neighbors(v))
        .collect();
    for step in 0..40 {
        let w = if step % 2 == 0 { 0.5 } else { -0.53 };
        let old = m.positions().to_vec();
        let pos: Vec<Point> = old
            .iter()
            .zip(&nbrs)
            .map(|(&p, nb)| {
                let mut avg = [0.0; 3];
                for &q in nb {
                    avg = geom::add(avg, old[q as usize]);
                }
                let avg = geom::scale(avg, 1.0 / nb.len() as f64);
                geom::lerp(p, avg, w)
            })
            .collect();
        m.set_positions(pos);
    }
    Ok(m)
}
