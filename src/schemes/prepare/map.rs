//! The parameter map of a preparation: where each face of the prepared net lies in the input
//! net's faces, and how the domains of a complex built on the prepared net are moved into the
//! input faces ([`ParamMap::lift`]), so that evaluation at `(face, u, v)` addresses the user's
//! faces (`crate::surface::eval`).
//!
//! The input faces keep their domains ([`crate::bezier::domain`]): a quad `[0, 1]^2`, an
//! n-gon (triangles included) the strip of its `n` quad sub-faces, sub-face `k` the quarter at
//! corner `k`. A step's child faces are then:
//!
//! * **Catmull-Clark step.** Child face `h` is the quad of parent corner `h` (vertex point,
//!   edge point of the outgoing edge, face point, edge point of the incoming edge), which is
//!   exactly the parent's quarter at that corner (child `k` of a quad, sub-face `k` of an
//!   n-gon), with the same corner first: a [`FaceCell::Whole`] cell.
//! * **Dual step** (Doo-Sabin, DS^CC, PGS). Child vertex `h` (the point of parent corner `h`,
//!   vertex `v` of face `g`) lies in the quarter `Q` of `g` at `v`, and as for the dual
//!   schemes' own levels its patch covers `Q`: the quarter of each child face at that vertex
//!   is the child of `Q` toward that face, `(0, 0)` at the centre of `Q` (corner 2 of that
//!   child): child 0 (toward `v`) for the V-face of `v`, 1 for the E-face of the outgoing edge
//!   of `g` at `v`, 2 for the F-face of `g`, 3 for the E-face of the incoming edge. A child face
//!   straddles several input faces, so only its quarters have cells: [`FaceCell::Quarters`].
//!   The points of a step's boundary rules (Chaikin points, kept corners) lie over no face
//!   (as in `crate::schemes::doo_sabin::surface`). At the two points of an interior vertex of
//!   valence 2 the step leaves the V-face out, and the three faces left cannot tile `Q` by
//!   affine images of quarters: their quarters keep their children of `Q`, and child 0 of
//!   `Q` (the corner of the input face's quarter at the vertex, `[0, 1/4]^2` of a quad at
//!   that corner) lies over no face of the prepared net, so evaluation there is an error.
//!
//! The map of several steps is composed step by step (the quarter of a parent face is the
//! parent's cell's child, or its quarter cell). A domain of the prepared net keeps its chain of
//! children below a frame: the image of its face's (or quarter's) cell in the input face
//! ([`crate::bezier::complex::Domain::framed_in`]).

use crate::bezier::complex::{Domain, PatchComplex};
use crate::bezier::domain::{Affine, Shape};
use crate::mesh::PolyMesh;

/// A region of an input face: sub-face `sub` of face `face` (`0` for a quad), the image of
/// `[0, 1]^2` under `map` in that (sub-)face's coordinates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cell {
    /// The input face.
    pub face: u32,
    /// Its sub-face (`0` for a quad).
    pub sub: u32,
    /// From the region's `[0, 1]^2` to the (sub-)face's coordinates.
    pub map: Affine,
}

impl Cell {
    /// The region's child `k` with its `(0, 0)` at the child's corner `rot` (see
    /// [`Shape::child_map`], [`Shape::corner_map`]).
    fn child(&self, k: u8, rot: u8) -> Cell {
        Cell {
            map: self
                .map
                .compose(&Shape::Quad.child_map(k))
                .compose(&Shape::Quad.corner_map(rot)),
            ..*self
        }
    }
}

/// Where one face of a prepared net lies in the input faces.
#[derive(Debug, Clone, PartialEq)]
pub enum FaceCell {
    /// The whole face (a quad: `[0, 1]^2`, corner 0 at `(0, 0)`, `u` toward corner 1).
    Whole(Cell),
    /// The quarter at each corner (the face's child `k`, or sub-face `k` of an n-gon), `None`
    /// where it lies over no input face.
    Quarters(Vec<Option<Cell>>),
    /// Over no input face (the boundary layer of a step's boundary rules).
    Nowhere,
}

impl FaceCell {
    /// The quarter at corner `k` of a face with `sides` corners.
    pub fn quarter(&self, k: usize, sides: usize) -> Option<Cell> {
        match self {
            FaceCell::Whole(c) if sides == 4 => Some(c.child(k as u8, 0)),
            FaceCell::Quarters(q) => q.get(k).copied().flatten(),
            _ => None,
        }
    }
}

/// Where each face of a prepared net lies in the input faces (see the [module](self)
/// documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct ParamMap {
    /// Per face of the prepared net.
    pub faces: Vec<FaceCell>,
}

impl ParamMap {
    /// The input net's own faces: a quad is its whole `[0, 1]^2`, an n-gon its sub-faces.
    pub fn input(mesh: &PolyMesh) -> ParamMap {
        ParamMap {
            faces: (0..mesh.num_faces())
                .map(|f| {
                    let n = mesh.face_size(f);
                    let whole = |sub: usize| Cell {
                        face: f as u32,
                        sub: sub as u32,
                        map: Affine::IDENTITY,
                    };
                    if n == 4 {
                        FaceCell::Whole(whole(0))
                    } else {
                        FaceCell::Quarters((0..n).map(|k| Some(whole(k))).collect())
                    }
                })
                .collect(),
        }
    }

    /// The map of a net made of some of this map's net's faces, in the order `kept` lists
    /// them (hole faces removed, the net cut along its creases: the faces stay the same).
    pub fn select(&self, kept: &[usize]) -> ParamMap {
        ParamMap {
            faces: kept.iter().map(|&f| self.faces[f].clone()).collect(),
        }
    }

    /// The quarter at corner `k` of face `g` of the net this map belongs to.
    pub fn quarter(&self, mesh: &PolyMesh, g: usize, k: usize) -> Option<Cell> {
        self.faces
            .get(g)
            .and_then(|c| c.quarter(k, mesh.face_size(g)))
    }

    /// A domain of a face of `mesh` (the net this map belongs to) in the input faces.
    pub fn lift_domain(&self, mesh: &PolyMesh, d: Domain) -> Domain {
        let g = d.face as usize;
        if !d.is_tracked() || g >= mesh.num_faces() {
            return Domain::UNTRACKED;
        }
        match &self.faces[g] {
            FaceCell::Whole(c) if mesh.face_size(g) == 4 => d.framed_in(c.face, c.sub, c.map),
            FaceCell::Whole(_) | FaceCell::Nowhere => Domain::UNTRACKED,
            FaceCell::Quarters(q) => match d.peel(mesh.face_size(g)) {
                Some((k, rest)) => match q.get(k as usize).copied().flatten() {
                    Some(c) => rest.framed_in(c.face, c.sub, c.map),
                    None => Domain::UNTRACKED,
                },
                None => Domain::UNTRACKED,
            },
        }
    }

    /// Moves every domain of `complex` (built on `mesh`, the net this map belongs to) into the
    /// input faces.
    pub fn lift(&self, mesh: &PolyMesh, complex: &mut PatchComplex) {
        for d in complex.domains.iter_mut().flatten() {
            *d = self.lift_domain(mesh, *d);
        }
        for p in &mut complex.pieces {
            p.domain = self.lift_domain(mesh, p.domain);
        }
    }

    /// The map after a Catmull-Clark step from `parent` (this map's net) to its child, whose
    /// face `h` is the quad of parent corner `h` with that corner first.
    pub fn catmull_clark_step(&self, parent: &PolyMesh) -> ParamMap {
        let faces = (0..parent.num_halfedges() as u32)
            .map(|h| {
                let g = parent.he_face(h) as usize;
                let k = (h - parent.face_halfedge(g)) as usize;
                self.quarter(parent, g, k)
                    .map_or(FaceCell::Nowhere, FaceCell::Whole)
            })
            .collect();
        ParamMap { faces }
    }

    /// The map after a dual step from `parent` (this map's net) to `child` (the layout of
    /// `crate::schemes::doo_sabin`: child point `h < H` for parent corner `h`, then the points
    /// of the boundary rules; a child face is the F-face of a parent face, the V-face of a
    /// parent vertex or the E-face of a parent edge, told apart by its corners).
    pub fn dual_step(&self, parent: &PolyMesh, child: &PolyMesh) -> ParamMap {
        let nh = parent.num_halfedges() as u32;
        let faces = (0..child.num_faces())
            .map(|c| {
                let corners = child.face(c);
                let points: Vec<u32> = corners.iter().copied().filter(|&x| x < nh).collect();
                // F-face: all corners of one parent face; V-face: all around one parent
                // vertex; else the E-face of an edge (two corners in each of its faces)
                let f_face = points
                    .windows(2)
                    .all(|w| parent.he_face(w[0]) == parent.he_face(w[1]));
                let v_face = points
                    .windows(2)
                    .all(|w| parent.he_from(w[0]) == parent.he_from(w[1]));
                let quarters: Vec<Option<Cell>> = corners
                    .iter()
                    .map(|&x| {
                        if x >= nh {
                            return None;
                        }
                        let toward = if f_face && corners.len() == points.len() {
                            2
                        } else if v_face {
                            0
                        } else if points.contains(&parent.he_next(x)) {
                            1
                        } else {
                            3
                        };
                        let g = parent.he_face(x) as usize;
                        let k = (x - parent.face_halfedge(g)) as usize;
                        self.quarter(parent, g, k).map(|q| q.child(toward, 2))
                    })
                    .collect();
                if quarters.iter().all(Option::is_none) {
                    FaceCell::Nowhere
                } else {
                    FaceCell::Quarters(quarters)
                }
            })
            .collect();
        ParamMap { faces }
    }
}
