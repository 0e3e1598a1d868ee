//! The dual split (the topology of Doo-Sabin's family: Doo-Sabin, DS^CC, PGS), without any
//! weights: every corner of a face gets a point, and the child faces are one F-face per parent
//! face (its corner points), one E-face per edge (the four corner points beside it) and one
//! V-face per vertex (the corner points around it). A scheme supplies the masks; where it keeps
//! sharp features it also says which edges get Chaikin points (the two points along a sharp or
//! boundary edge, which then close the E-face on its one side, or each side's half of it), which
//! boundary vertices keep a point of their own, and how a vertex's V-face splits into the
//! sectors between its sharp edges ([`DualFeatures`]).
//!
//! One split serves a whole net's step and a step over selected faces (the adaptive levels):
//! only the faces selected are split, a V-face is made where the scheme says the vertex's fan is
//! whole, and the child points are numbered as [`DualOrder`] says.

use super::{MeshView, NONE, PolyMesh};

/// The sectors of a vertex's fan between its sharp edges: one V-face each.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Sector {
    /// Indices into the vertex's outgoing half-edges (counter-clockwise; on the boundary from
    /// the outgoing boundary edge) of the faces of the sector, in order.
    pub faces: Vec<usize>,
    /// The sharp edge the sector starts at (counter-clockwise), or `None` when the vertex has
    /// no sharp edge (one sector, the whole fan).
    pub open: Option<u32>,
    /// The sharp edge it ends at: the same as `open` at a dart (one sharp edge inside the
    /// surface, none on the boundary).
    pub close: Option<u32>,
}

impl Sector {
    /// The one sector of a vertex without sharp edges inside the surface: its whole fan (its
    /// outgoing half-edges `hs`), between its boundary edges on the boundary.
    pub fn whole_fan(mesh: &PolyMesh, v: usize, hs: &[u32]) -> Sector {
        let (open, close) = whole_fan_ends(&mesh.view(), v, hs);
        Sector {
            faces: (0..hs.len()).collect(),
            open,
            close,
        }
    }
}

/// The sharp edges a whole fan starts and ends at: its boundary edges on the boundary.
fn whole_fan_ends(m: &MeshView<'_>, v: usize, hs: &[u32]) -> (Option<u32>, Option<u32>) {
    if !m.is_boundary_vertex(v) {
        return (None, None);
    }
    let last = *hs.last().expect("a vertex has a face");
    (
        Some(m.he_edge[hs[0] as usize]),
        Some(m.he_edge[m.faces.prev(last) as usize]),
    )
}

/// A child point of the dual split.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DualPoint {
    /// The point of a face corner: half-edge `h` of the face, at its start vertex.
    Corner(u32),
    /// A Chaikin point of edge `edge`: near the start (`end == 0`) or the end (`1`) of the
    /// edge's half-edge.
    Chaikin {
        /// The parent edge.
        edge: u32,
        /// Which end it is near.
        end: u8,
    },
    /// The kept point of a boundary vertex.
    Kept(u32),
}

/// What a child face of the dual split is ([`DualSplit::face`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DualFace {
    /// The F-face of a parent face.
    Face(u32),
    /// An E-face (whole, or one side's half at an edge with Chaikin points).
    Edge,
    /// The V-face of one sector of a parent vertex.
    Vertex(VFace),
}

/// A V-face: the vertex and the sharp edges its sector lies between.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct VFace {
    /// The parent vertex.
    pub vertex: u32,
    /// The sector's opening sharp edge ([`Sector::open`]; [`NONE`] for none).
    pub open: u32,
    /// The sector's closing sharp edge ([`Sector::close`]; [`NONE`] for none).
    pub close: u32,
}

/// How the child points are numbered.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DualOrder {
    /// Face by face, in the order of the selected faces: a face's corner points, each followed
    /// by the two Chaikin points of its edge when the edge is met first, then the kept points
    /// of the face's corners met first; V-faces in the order their vertices are met (the
    /// adaptive levels).
    ByFace,
    /// A whole net's step: corner points by half-edge, Chaikin points by edge, kept points by
    /// vertex; V-faces by vertex.
    ByKind,
}

/// Where a scheme keeps sharp features (see the [module](self) documentation).
pub trait DualFeatures {
    /// Whether edge `e` (a side of a selected face) gets two Chaikin points.
    fn chaikin(&mut self, e: usize) -> bool;
    /// Whether vertex `v` (a corner of a selected face) gets a kept point.
    fn kept(&mut self, v: usize) -> bool;
    /// The V-faces of vertex `v` (`hs` its outgoing half-edges).
    fn v_faces(&mut self, v: usize, hs: &[u32]) -> VFaces;
}

/// The V-faces of a vertex ([`DualFeatures::v_faces`]).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum VFaces {
    /// None (its fan is not whole, or the boundary is not made).
    None,
    /// One: its whole fan ([`Sector::whole_fan`]).
    Whole,
    /// One per sector between its sharp edges.
    Sectors(Vec<Sector>),
}

/// One dual step of a net over its selected faces (see the [module](self) documentation).
#[derive(Debug, Clone)]
pub struct DualSplit {
    /// The child points, in order.
    pub points: Vec<DualPoint>,
    /// The corner point of each parent half-edge ([`NONE`] outside the selection).
    pub corner_pt: Vec<u32>,
    /// The two Chaikin points of each parent edge ([`NONE`] where it has none).
    pub edge_pt: Vec<[u32; 2]>,
    /// The kept point of each parent vertex ([`NONE`] where it has none).
    pub kept: Vec<u32>,
    /// The selected faces, sorted (the F-faces are the first child faces, in this order).
    pub sel_faces: Vec<u32>,
    /// Child face offsets into `corners`.
    pub face_start: Vec<u32>,
    /// Child face corners ([`NONE`] where a sector's sharp edge has no Chaikin point: see
    /// [`DualSplit::is_complete`]). The F-faces come first (one per selected face), then the
    /// E-faces, then the V-faces.
    pub corners: Vec<u32>,
    /// The number of E-faces.
    pub num_e_faces: usize,
    /// The V-faces, in order.
    pub v_faces: Vec<VFace>,
    /// The vertices whose sectors were asked for and given, in order.
    pub v_done: Vec<u32>,
}

impl DualSplit {
    /// Whether every child face corner is a child point (a sector's sharp edge without its
    /// Chaikin points is a neighbourhood the features contradict).
    pub fn is_complete(&self) -> bool {
        !self.corners.contains(&NONE)
    }

    /// The number of child faces.
    pub fn num_faces(&self) -> usize {
        self.face_start.len() - 1
    }

    /// What child face `i` is.
    pub fn face(&self, i: usize) -> DualFace {
        let nf = self.sel_faces.len();
        if i < nf {
            DualFace::Face(self.sel_faces[i])
        } else if i < nf + self.num_e_faces {
            DualFace::Edge
        } else {
            DualFace::Vertex(self.v_faces[i - nf - self.num_e_faces])
        }
    }
}

/// The dual split of the faces `sel_faces` of `mesh` (any order; the split sorts them), with
/// the sharp features of `features`, numbered by `order` ([`DualOrder::ByKind`] needs every
/// face selected).
///
/// # Panics
/// Panics when `order` is [`DualOrder::ByKind`] and not every face is selected.
pub fn dual_split(
    mesh: &PolyMesh,
    mut sel_faces: Vec<u32>,
    features: &mut dyn DualFeatures,
    order: DualOrder,
) -> DualSplit {
    let m = mesh;
    let mv = m.view();
    let (nv, nf, ne) = (m.num_vertices(), m.num_faces(), m.num_edges());
    sel_faces.sort_unstable();
    // the whole net's sizes: a corner point per half-edge, F-, E- and V-faces
    let nh = m.num_halfedges();
    let (points, faces) = match order {
        DualOrder::ByKind => {
            // (Chaikin and kept points only on the boundary)
            let nb = mv.edge_he.iter().filter(|&&h| mv.twin(h) == NONE).count();
            (nh + 3 * nb, nf + ne + nv)
        }
        DualOrder::ByFace => (0, 0),
    };
    let mut s = DualSplit {
        points: Vec::with_capacity(points),
        corner_pt: vec![NONE; nh],
        edge_pt: vec![[NONE; 2]; ne],
        kept: vec![NONE; nv],
        sel_faces,
        face_start: Vec::with_capacity(faces + 1),
        corners: Vec::with_capacity(if points == 0 {
            0
        } else {
            2 * nh + 4 * ne + 3 * nv
        }),
        num_e_faces: 0,
        v_faces: Vec::with_capacity(faces.saturating_sub(nf + ne)),
        v_done: Vec::with_capacity(faces.saturating_sub(nf + ne)),
    };
    s.number_points(m, features, order);
    s.face_start.push(0);
    s.f_faces(&mv);
    s.e_faces(&mv);
    s.make_v_faces(&mv, features, order);
    s
}

impl DualSplit {
    /// The child points, numbered by `order` (see [`DualOrder`]).
    fn number_points(&mut self, m: &PolyMesh, features: &mut dyn DualFeatures, order: DualOrder) {
        let (nv, nf, ne, nh) = (
            m.num_vertices(),
            m.num_faces(),
            m.num_edges(),
            m.num_halfedges(),
        );
        let mut chaikin_known = vec![false; ne];
        let mut kept_known = vec![false; nv];
        match order {
            DualOrder::ByFace => {
                let sel_faces = std::mem::take(&mut self.sel_faces);
                for &f in &sel_faces {
                    let h0 = m.face_halfedge(f as usize);
                    for h in h0..h0 + m.face_size(f as usize) as u32 {
                        self.corner_pt[h as usize] = self.push(DualPoint::Corner(h));
                        let e = m.he_edge(h) as usize;
                        if !chaikin_known[e] {
                            chaikin_known[e] = true;
                            if features.chaikin(e) {
                                self.push_chaikin(e);
                            }
                        }
                    }
                    for &x in m.face(f as usize) {
                        if !kept_known[x as usize] {
                            kept_known[x as usize] = true;
                            if features.kept(x as usize) {
                                self.kept[x as usize] = self.push(DualPoint::Kept(x));
                            }
                        }
                    }
                }
                self.sel_faces = sel_faces;
            }
            DualOrder::ByKind => {
                assert_eq!(
                    self.sel_faces.len(),
                    nf,
                    "a whole net's step selects every face"
                );
                self.points.extend((0..nh as u32).map(DualPoint::Corner));
                for (h, c) in self.corner_pt.iter_mut().enumerate() {
                    *c = h as u32;
                }
                for e in 0..ne {
                    if features.chaikin(e) {
                        self.push_chaikin(e);
                    }
                }
                for v in 0..nv {
                    if features.kept(v) {
                        self.kept[v] = self.push(DualPoint::Kept(v as u32));
                    }
                }
            }
        }
    }

    /// The V-faces: of every vertex (`ByKind`) or of the vertices in the order the selected
    /// faces meet them (`ByFace`), one per sector the features give.
    fn make_v_faces(
        &mut self,
        mv: &MeshView<'_>,
        features: &mut dyn DualFeatures,
        order: DualOrder,
    ) {
        let nv = mv.vert_he.len();
        let vertices: Vec<u32> = match order {
            DualOrder::ByKind => (0..nv as u32).collect(),
            DualOrder::ByFace => {
                let mut met = vec![false; nv];
                let mut out = Vec::new();
                for &f in &self.sel_faces {
                    for &x in mv.face_corners(f as usize) {
                        if !met[x as usize] {
                            met[x as usize] = true;
                            out.push(x);
                        }
                    }
                }
                out
            }
        };
        let mut hs = Vec::new();
        for v in vertices {
            hs.clear();
            for h in mv.outgoing(v as usize) {
                hs.push(h);
            }
            match features.v_faces(v as usize, &hs) {
                VFaces::None => continue,
                VFaces::Whole => {
                    self.v_done.push(v);
                    let (open, close) = whole_fan_ends(mv, v as usize, &hs);
                    self.push_sector_face(mv, v as usize, (open, close), hs.iter().copied());
                }
                VFaces::Sectors(sectors) => {
                    self.v_done.push(v);
                    for sector in sectors {
                        let corners = sector.faces.iter().map(|&i| hs[i]);
                        self.push_sector_face(mv, v as usize, (sector.open, sector.close), corners);
                    }
                }
            }
        }
    }

    fn push(&mut self, p: DualPoint) -> u32 {
        self.points.push(p);
        (self.points.len() - 1) as u32
    }

    fn push_chaikin(&mut self, e: usize) {
        for end in 0..2u8 {
            self.edge_pt[e][end as usize] = self.push(DualPoint::Chaikin {
                edge: e as u32,
                end,
            });
        }
    }

    fn push_face(&mut self, corners: &[u32]) {
        self.corners.extend_from_slice(corners);
        self.face_start.push(self.corners.len() as u32);
    }

    /// The F-faces: each selected face's corner points.
    fn f_faces(&mut self, m: &MeshView<'_>) {
        self.face_start.reserve(self.sel_faces.len());
        for &f in &self.sel_faces {
            let h0 = m.faces.start(f as usize);
            let hs = h0..h0 + m.face_corners(f as usize).len() as u32;
            self.corners.extend(hs.map(|h| self.corner_pt[h as usize]));
            self.face_start.push(self.corners.len() as u32);
        }
    }

    /// The E-faces: whole between two selected faces, one half per selected side at an edge
    /// with Chaikin points. A half-edge's face is selected when it has a corner point.
    fn e_faces(&mut self, m: &MeshView<'_>) {
        for e in 0..m.edge_he.len() {
            let h = m.edge_he[e];
            let pts = self.edge_pt[e];
            let cp = |x: u32| self.corner_pt[x as usize];
            let half = |s: u32| {
                let (near_from, near_to) = if s == h {
                    (pts[0], pts[1])
                } else {
                    (pts[1], pts[0])
                };
                [cp(m.faces.next(s)), cp(s), near_from, near_to]
            };
            let mut quads: [Option<[u32; 4]>; 2] = [None, None];
            let t = m.twin(h);
            let selected = |x: u32| cp(x) != NONE;
            match t {
                NONE if pts[0] != NONE => quads[0] = Some(half(h)),
                NONE => continue,
                _ if pts[0] != NONE => {
                    for (k, s) in [h, t].into_iter().enumerate() {
                        if selected(s) {
                            quads[k] = Some(half(s));
                        }
                    }
                }
                _ if selected(h) && selected(t) => {
                    let next = |x: u32| m.faces.next(x);
                    quads[0] = Some([cp(next(h)), cp(h), cp(next(t)), cp(t)]);
                }
                _ => continue,
            }
            for q in quads.into_iter().flatten() {
                self.push_face(&q);
                self.num_e_faces += 1;
            }
        }
    }

    /// The V-face of one sector of `v` (its sharp edges `open`, `close`, the half-edges
    /// `corners` of its faces at `v`): the Chaikin point of its opening edge near `v`, its
    /// corner points, the Chaikin point of its closing edge (once at a dart) and the kept point.
    /// A face of fewer than three corners (interior valence 2) is dropped.
    fn push_sector_face(
        &mut self,
        m: &MeshView<'_>,
        v: usize,
        (open, close): (Option<u32>, Option<u32>),
        corners: impl Iterator<Item = u32>,
    ) {
        let near = |s: &Self, e: u32| {
            let k = usize::from(m.from(m.edge_he[e as usize]) as usize != v);
            s.edge_pt[e as usize][k]
        };
        let start = self.corners.len();
        if let Some(e) = open {
            self.corners.push(near(self, e));
        }
        for h in corners {
            self.corners.push(self.corner_pt[h as usize]);
        }
        if let Some(e) = close
            && open != Some(e)
        {
            self.corners.push(near(self, e));
        }
        if self.kept[v] != NONE {
            self.corners.push(self.kept[v]);
        }
        if self.corners.len() - start < 3 {
            // interior valence 2: the 2-sided V-face is dropped
            self.corners.truncate(start);
            return;
        }
        self.face_start.push(self.corners.len() as u32);
        self.v_faces.push(VFace {
            vertex: v as u32,
            open: open.unwrap_or(NONE),
            close: close.unwrap_or(NONE),
        });
    }
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;
    use crate::mesh::nets;

    /// Plain features: Chaikin points on boundary edges, kept points at the given vertices,
    /// a V-face (the whole fan) everywhere.
    struct Plain<'a> {
        mesh: &'a PolyMesh,
        kept: &'a [usize],
    }

    impl DualFeatures for Plain<'_> {
        fn chaikin(&mut self, e: usize) -> bool {
            self.mesh.is_boundary_edge(e)
        }
        fn kept(&mut self, v: usize) -> bool {
            self.kept.contains(&v)
        }
        fn v_faces(&mut self, _: usize, _: &[u32]) -> VFaces {
            VFaces::Whole
        }
    }

    fn all(m: &PolyMesh) -> Vec<u32> {
        (0..m.num_faces() as u32).collect()
    }

    #[crate::unit::test]
    fn whole_net_counts_and_layout() {
        // closed: a corner per half-edge; F-, E- and V-faces of every face, edge and vertex
        let cube = nets::cube();
        let mut f = Plain {
            mesh: &cube,
            kept: &[],
        };
        let s = dual_split(&cube, all(&cube), &mut f, DualOrder::ByKind);
        assert_eq!(s.points.len(), 24);
        assert!((0..24).all(|h| s.corner_pt[h] == h as u32));
        assert_eq!(s.num_faces(), 6 + 12 + 8);
        assert!(s.is_complete());
        // an open 3 x 3 grid: two Chaikin points per boundary edge (12), corners kept
        let grid = nets::quad_grid(3, |_, _| 0.0);
        let corners: Vec<usize> = (0..16).filter(|&v| grid.valence(v) == 2).collect();
        let mut f = Plain {
            mesh: &grid,
            kept: &corners,
        };
        let s = dual_split(&grid, all(&grid), &mut f, DualOrder::ByKind);
        assert_eq!(s.points.len(), 36 + 24 + 4);
        assert!(matches!(s.points[36], DualPoint::Chaikin { end: 0, .. }));
        assert!(matches!(s.points[60], DualPoint::Kept(0)));
        assert_eq!(s.num_faces(), 9 + 24 + 16);
        assert_eq!((s.num_e_faces, s.v_faces.len()), (24, 16));
        // a corner's V-face: Chaikin point, its one corner point, Chaikin point, kept point
        let i = (0..s.num_faces())
            .position(|i| matches!(s.face(i), DualFace::Vertex(VFace { vertex: 0, .. })))
            .unwrap();
        let (a, b) = (s.face_start[i] as usize, s.face_start[i + 1] as usize);
        assert_eq!(s.corners[a..b].len(), 4);
        assert_eq!(s.corners[b - 1], s.kept[0]);
    }

    #[crate::unit::test]
    fn face_order_numbers_the_same_split_face_by_face() {
        let grid = nets::quad_grid(3, |_, _| 0.0);
        let mut f = Plain {
            mesh: &grid,
            kept: &[0],
        };
        let by_kind = dual_split(&grid, all(&grid), &mut f, DualOrder::ByKind);
        let by_face = dual_split(&grid, all(&grid), &mut f, DualOrder::ByFace);
        // the same points, renumbered; the same faces once renamed
        let mut a = by_kind.points.clone();
        let mut b = by_face.points.clone();
        let key = |p: &DualPoint| format!("{p:?}");
        a.sort_by_key(key);
        b.sort_by_key(key);
        assert_eq!(a, b);
        let rename = |s: &DualSplit, i: usize| -> Vec<String> {
            let (x, y) = (s.face_start[i] as usize, s.face_start[i + 1] as usize);
            s.corners[x..y]
                .iter()
                .map(|&c| key(&s.points[c as usize]))
                .collect()
        };
        let mut fa: Vec<_> = (0..by_kind.num_faces())
            .map(|i| rename(&by_kind, i))
            .collect();
        let mut fb: Vec<_> = (0..by_face.num_faces())
            .map(|i| rename(&by_face, i))
            .collect();
        fa.sort();
        fb.sort();
        assert_eq!(fa, fb);
        // face order: the first face's corners come first, then its edges' Chaikin points
        assert_eq!(by_face.points[0], DualPoint::Corner(0));
        assert!(matches!(by_face.points[1], DualPoint::Chaikin { .. }));
    }

    #[crate::unit::test]
    fn a_selection_splits_only_its_faces() {
        // one face of a cube: its F-face alone (no E-face has both sides, no fan is whole
        // where the features say so)
        let cube = nets::cube();
        struct Partial<'a>(&'a PolyMesh, Vec<bool>);
        impl DualFeatures for Partial<'_> {
            fn chaikin(&mut self, _: usize) -> bool {
                false
            }
            fn kept(&mut self, _: usize) -> bool {
                false
            }
            fn v_faces(&mut self, _: usize, hs: &[u32]) -> VFaces {
                let whole = hs.iter().all(|&h| self.1[self.0.he_face(h) as usize]);
                if whole { VFaces::Whole } else { VFaces::None }
            }
        }
        let mut sel = vec![false; 6];
        sel[2] = true;
        let s = dual_split(&cube, vec![2], &mut Partial(&cube, sel), DualOrder::ByFace);
        assert_eq!(s.points.len(), 4);
        assert_eq!((s.num_faces(), s.face(0)), (1, DualFace::Face(2)));
        assert!(s.v_done.is_empty());
        let h0 = cube.face_halfedge(2);
        assert_eq!(s.corner_pt[h0 as usize], 0);
        assert_eq!(s.corner_pt[0], NONE);
    }
}
