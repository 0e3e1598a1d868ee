//! How big a net becomes under refinement, known before refining: the sizes front ends check
//! against a memory budget before they allocate anything (`subdivide --levels 30` on a cube
//! would need 10^19 faces; Doo-Sabin's face rule on a 200,000-gon 4 10^10 stencil entries).
//!
//! [`NetSize`] counts what a refinement step allocates: vertices, edges, faces, corners, and
//! the sums of squared face sizes and valences that dense rules (a Doo-Sabin face point uses
//! every corner of its face) make grow quadratically. Each [`super::Scheme`] maps the size of a
//! net to the size of its child with [`super::Scheme::step_size`]; the default is the primal
//! quad split below, and schemes with other topologies name theirs ([`dual`], [`triangle`],
//! [`ternary`], ...). The formulas are exact on closed nets and upper bounds with boundaries
//! (boundary layers doubled, Chaikin points); `tests/limits.rs` compares them with real
//! refinements of the gallery for every scheme.

use crate::mesh::PolyMesh;

/// The size of a net, as far as the cost of refining it goes. Counts are `f64` so that the
/// estimates of many levels do not overflow.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct NetSize {
    /// Vertices.
    pub vertices: f64,
    /// Edges.
    pub edges: f64,
    /// Faces.
    pub faces: f64,
    /// Corners (the sum of the face sizes: the half-edges).
    pub corners: f64,
    /// Boundary edges.
    pub boundary_edges: f64,
    /// Faces that are not triangles.
    pub non_triangles: f64,
    /// The sum of the squared face sizes.
    pub face_squares: f64,
    /// The sum of the squared valences.
    pub valence_squares: f64,
    /// Entries of the stencil table of the step that made this net (0 for an input net).
    pub stencil: f64,
}

impl NetSize {
    /// The size of `mesh`.
    pub fn of(mesh: &PolyMesh) -> NetSize {
        let mut s = NetSize {
            vertices: mesh.num_vertices() as f64,
            edges: mesh.num_edges() as f64,
            faces: mesh.num_faces() as f64,
            corners: mesh.corners().len() as f64,
            ..NetSize::default()
        };
        let starts = mesh.face_starts();
        for f in 0..mesh.num_faces() {
            let k = (starts[f + 1] - starts[f]) as f64;
            s.face_squares += k * k;
            if k != 3.0 {
                s.non_triangles += 1.0;
            }
        }
        // Valences from the edges (no walks around vertices), boundary edges from the corners:
        // an edge used by one corner only.
        let mut valence = vec![0u32; mesh.num_vertices()];
        for e in mesh.edges() {
            valence[e[0] as usize] += 1;
            valence[e[1] as usize] += 1;
        }
        s.valence_squares = valence.iter().map(|&d| f64::from(d) * f64::from(d)).sum();
        s.boundary_edges = (2.0 * s.edges - s.corners).max(0.0);
        s
    }

    /// Bytes a net of this size takes in memory with its topology (positions, corners, face
    /// offsets, twins, edges and their lists), plus the stencil table that produced it:
    /// 24 bytes per vertex, 20 per corner (corner, twin, edge, face of each half-edge,
    /// rounded up), 12 per edge, 4 per face and 12 per stencil entry.
    pub fn bytes(&self) -> f64 {
        24.0 * self.vertices
            + 20.0 * self.corners
            + 12.0 * self.edges
            + 4.0 * self.faces
            + 12.0 * self.stencil
    }
}

/// The primal quad split of Catmull-Clark: a point per vertex, edge and face; every `k`-gon
/// becomes `k` quads. Stencils: face points use their face, edge points two faces and two
/// ends, vertex points their faces and neighbours.
pub fn primal_quad(s: &NetSize) -> NetSize {
    let vertices = s.vertices + s.edges + s.faces;
    NetSize {
        vertices,
        edges: 2.0 * s.edges + s.corners,
        faces: s.corners,
        corners: 4.0 * s.corners,
        boundary_edges: 2.0 * s.boundary_edges,
        non_triangles: s.corners,
        face_squares: 16.0 * s.corners,
        valence_squares: s.face_squares + 16.0 * s.edges + s.valence_squares,
        stencil: s.vertices + 4.0 * s.edges + 3.0 * s.corners + s.face_squares,
    }
}

/// [`primal_quad`] for nets that carry one face control vertex per face after their
/// vertices (the non-box layout): one more point per child face.
pub fn primal_quad_with_face_points(s: &NetSize) -> NetSize {
    let mut c = primal_quad(s);
    c.vertices += c.faces;
    c.stencil += 4.0 * c.faces;
    c
}

/// The dual split of Doo-Sabin and the bi-2 schemes: a point per corner; a face per face,
/// edge and vertex. Every child point of a corner of a `k`-gon uses all `k` points of the face
/// (the dense rule: the stencil grows with the squared face sizes). Boundaries (Chaikin
/// points, boundary layers) add at most three points per boundary edge.
pub fn dual(s: &NetSize) -> NetSize {
    let vertices = s.corners + 3.0 * s.boundary_edges;
    NetSize {
        vertices,
        edges: 2.0 * vertices,
        faces: s.faces + s.edges + s.vertices,
        corners: 4.0 * vertices,
        boundary_edges: 2.0 * s.boundary_edges,
        non_triangles: s.faces + s.edges + s.vertices,
        face_squares: s.face_squares + 16.0 * s.edges + s.valence_squares,
        valence_squares: 16.0 * vertices,
        stencil: s.face_squares + 4.0 * s.corners + 3.0 * s.boundary_edges,
    }
}

/// The triangle split of Loop: a point per vertex and edge, every triangle into four.
pub fn triangle(s: &NetSize) -> NetSize {
    NetSize {
        vertices: s.vertices + s.edges,
        edges: 2.0 * s.edges + 3.0 * s.faces,
        faces: 4.0 * s.faces,
        corners: 12.0 * s.faces,
        boundary_edges: 2.0 * s.boundary_edges,
        non_triangles: 0.0,
        face_squares: 36.0 * s.faces,
        valence_squares: s.valence_squares + 36.0 * s.edges,
        stencil: s.vertices + 6.0 * s.edges,
    }
}

/// The four-directional non-box split: triangle nets as [`triangle`]; other faces first
/// become a fan of triangles around a face point (a point per vertex, edge, face and corner).
pub fn four_directional(s: &NetSize) -> NetSize {
    if s.non_triangles == 0.0 {
        return triangle(s);
    }
    let faces = 4.0 * s.corners;
    NetSize {
        vertices: s.vertices + s.edges + s.faces + s.corners,
        edges: 1.5 * faces + s.boundary_edges,
        faces,
        corners: 3.0 * faces,
        boundary_edges: 2.0 * s.boundary_edges,
        non_triangles: 0.0,
        face_squares: 9.0 * faces,
        valence_squares: s.valence_squares + s.face_squares + 36.0 * (s.edges + s.corners),
        stencil: 2.0 * s.vertices + 6.0 * s.edges + s.face_squares + 4.0 * s.corners,
    }
}

/// The ternary split of the primal ternary bi-2 schemes (TPS, adjustable TPS, polar bi-2):
/// every quad into nine (a `k`-gon counts as `k / 4` quads), boundary layers doubled.
pub fn ternary(s: &NetSize) -> NetSize {
    let faces = 2.25 * s.corners + 4.0 * s.boundary_edges;
    let vertices = s.vertices + 2.0 * s.edges + s.corners + 4.0 * s.boundary_edges;
    NetSize {
        vertices,
        edges: 3.0 * s.edges + 3.0 * s.corners + 4.0 * s.boundary_edges,
        faces,
        corners: 4.0 * faces,
        boundary_edges: 3.0 * s.boundary_edges,
        non_triangles: faces,
        face_squares: 16.0 * faces,
        valence_squares: s.valence_squares + 16.0 * (vertices - s.vertices),
        stencil: 16.0 * vertices + s.face_squares,
    }
}

/// The larger of two estimates, count by count (a scheme that refines each element by the
/// rules of its kind, like the mixed bi-2 nets).
pub fn larger(a: &NetSize, b: &NetSize) -> NetSize {
    NetSize {
        vertices: a.vertices.max(b.vertices),
        edges: a.edges.max(b.edges),
        faces: a.faces.max(b.faces),
        corners: a.corners.max(b.corners),
        boundary_edges: a.boundary_edges.max(b.boundary_edges),
        non_triangles: a.non_triangles.max(b.non_triangles),
        face_squares: a.face_squares.max(b.face_squares),
        valence_squares: a.valence_squares.max(b.valence_squares),
        stencil: a.stencil.max(b.stencil),
    }
}

/// The sizes after each of `levels` steps of `step` from `start` (stops early once a count is
/// infinite: the estimate is then out of every budget anyway).
pub fn levels(start: NetSize, levels: usize, step: impl Fn(&NetSize) -> NetSize) -> Vec<NetSize> {
    let mut out = Vec::with_capacity(levels.min(64));
    let mut s = start;
    for _ in 0..levels {
        s = step(&s);
        out.push(s);
        if !s.bytes().is_finite() {
            break;
        }
    }
    out
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    #[crate::unit::test]
    fn cube_sizes_are_exact_for_the_closed_splits() {
        let cube = crate::mesh::nets::cube();
        let s = NetSize::of(&cube);
        assert_eq!(
            (s.vertices, s.edges, s.faces, s.corners, s.boundary_edges),
            (8.0, 12.0, 6.0, 24.0, 0.0)
        );
        assert_eq!((s.face_squares, s.valence_squares), (96.0, 72.0));
        let c = primal_quad(&s);
        assert_eq!(
            (c.vertices, c.edges, c.faces, c.corners),
            (26.0, 48.0, 24.0, 96.0)
        );
        let d = dual(&s);
        assert_eq!((d.vertices, d.faces), (24.0, 26.0));
        let t = ternary(&s);
        assert_eq!((t.vertices, t.edges, t.faces), (56.0, 108.0, 54.0));
    }

    #[crate::unit::test]
    fn thirty_levels_overflow_no_count() {
        let s = NetSize::of(&crate::mesh::nets::cube());
        let l = levels(s, 30, primal_quad);
        assert_eq!(l.len(), 30);
        assert!((l[29].faces - 6.0 * 4f64.powi(30)).abs() < 1.0);
        assert!(l[29].bytes() > 1e20);
    }
}
