//! The face-varying topology of one level: which vertices carry several values (seams), which
//! edges are discontinuous, and how each value of a vertex refines (OpenSubdiv's
//! `Vtr::FVarLevel` semantics, described in `docs/opensubdiv-rules.md` section 9).
//!
//! Every vertex gets its values in the order of its faces (counter-clockwise, a boundary vertex
//! starting at its leading boundary edge), each value the *span* of consecutive faces that
//! carry it, and a [`Tag`]: matching (the vertex's own rules apply), corner (it stays), crease
//! (`3/4 u + 1/8 (u_a + u_b)` along the fvar boundary of its span), semi-sharp (a corner while
//! sharp features inside its span decay), dependent (a corner because the other value of a
//! two-value vertex is semi-sharp).

use crate::mesh::tags::{BoundaryInterpolation, FvarInterpolation, SubdOptions};
use crate::mesh::{MeshView, NONE, PolyMesh};
use crate::schemes::sdc::crease::{Scratch, SharpLevel, decrement};

/// Infinite sharpness (OpenSubdiv's `SHARPNESS_INFINITE`).
const INFINITE: f32 = 10.0;

/// How one value of a vertex refines. `start` and `end` are the first and last face of its
/// span in the vertex's face order.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Tag {
    /// The value topology matches the vertex's: the vertex rules apply.
    Match,
    /// The value stays.
    Corner,
    /// The crease rule along the ends of its span.
    Crease { start: u32, end: u32 },
    /// A corner while the sharp features inside its span are semi-sharp.
    SemiSharp { start: u32, end: u32 },
    /// A corner because the other value is semi-sharp (corners-plus1/plus2).
    DepSharp { start: u32, end: u32 },
}

impl Tag {
    /// Whether the value stays (OpenSubdiv's `isCorner`: everything but a crease).
    pub fn stays(self) -> bool {
        !matches!(self, Tag::Crease { .. } | Tag::Match)
    }

    /// The span ends of a value that has them.
    pub fn span(self) -> Option<(u32, u32)> {
        match self {
            Tag::Crease { start, end }
            | Tag::SemiSharp { start, end }
            | Tag::DepSharp { start, end } => Some((start, end)),
            _ => None,
        }
    }
}

/// A span of faces around a vertex that carry one value.
#[derive(Debug, Clone, Copy, Default)]
struct Span {
    size: u32,
    start: u32,
    disjoint: i32,
    semi: u32,
}

/// The face-varying topology of one level (see the module documentation).
pub(super) struct FvLevel<'a> {
    pub m: MeshView<'a>,
    /// The value of each face corner (half-edge).
    pub corner_value: &'a [u32],
    /// The seam class of each value (`FaceVarying::classes`; empty: the value itself).
    classes: &'a [u32],
    /// The sibling (position among its vertex's values) of each face corner.
    pub sibling: Vec<u32>,
    /// Per vertex: offsets into `ring`; the corners (outgoing half-edges) at the vertex, in
    /// face order for a manifold vertex.
    ring_start: Vec<u32>,
    ring: Vec<u32>,
    /// Per vertex: offsets into `values` / `tags`.
    value_start: Vec<u32>,
    values: Vec<u32>,
    tags: Vec<Tag>,
    /// Per edge: offsets into `edge_hes`, the half-edges (faces) of each edge.
    edge_start: Vec<u32>,
    edge_hes: Vec<u32>,
    /// Per edge: values differ across it at one of its ends (a seam).
    pub discts: Vec<bool>,
    /// Per edge: refined linearly (a seam or boundary under `boundaries` / `all`).
    pub linear: Vec<bool>,
    edges: Vec<f32>,
    vertices: Vec<f32>,
    sharp: Option<SharpLevel<'a>>,
}

impl<'a> FvLevel<'a> {
    /// The number of the level's vertices.
    pub fn num_vertices(&self) -> usize {
        self.value_start.len() - 1
    }

    /// The number of the level's edges.
    pub fn num_edges(&self) -> usize {
        self.discts.len()
    }

    /// The face-varying topology of `mesh` with corner values `corner_value` under `opts`.
    pub fn new(
        mesh: &'a PolyMesh,
        corner_value: &'a [u32],
        opts: &SubdOptions,
        base: bool,
        classes: &'a [u32],
    ) -> FvLevel<'a> {
        let m = mesh.view();
        let (nv, ne, nh) = (mesh.num_vertices(), mesh.num_edges(), mesh.num_halfedges());
        let sharp = SharpLevel::new(mesh, opts);
        let (edges, vertices) = match &sharp {
            Some(sl) => (sl.edges.clone(), sl.vertices.clone()),
            None => {
                // The plain path: boundary edges infinitely sharp, edge-and-corner corners.
                let e = (0..ne)
                    .map(|e| {
                        if m.twin(m.edge_he[e]) == NONE {
                            INFINITE
                        } else {
                            0.0
                        }
                    })
                    .collect();
                let corner = opts.boundary() == BoundaryInterpolation::EdgeAndCorner;
                let v = (0..nv)
                    .map(|v| {
                        if corner && m.vert_he[v] != NONE && m.is_corner(v) {
                            INFINITE
                        } else {
                            0.0
                        }
                    })
                    .collect();
                (e, v)
            }
        };
        let (edge_start, edge_hes) = csr(ne, nh, |h| m.he_edge[h]);
        let (ring_start, mut ring) = csr(nv, nh, |h| m.from(h as u32));
        let mut manifold = vec![false; nv];
        for v in 0..nv {
            let r = &mut ring[ring_start[v] as usize..ring_start[v + 1] as usize];
            manifold[v] = !r.is_empty() && !mesh.is_nonmanifold_vertex(v) && order_ring(&m, r);
        }
        let mut lv = FvLevel {
            m,
            corner_value,
            classes,
            sibling: vec![0; nh],
            ring_start,
            ring,
            value_start: Vec::with_capacity(nv + 1),
            values: Vec::new(),
            tags: Vec::new(),
            edge_start,
            edge_hes,
            discts: vec![false; ne],
            linear: vec![false; ne],
            edges,
            vertices,
            sharp,
        };
        lv.find_values(base);
        lv.find_seams();
        lv.tag_values(&manifold, opts);
        lv
    }

    /// The corners at vertex `v` (in face order when manifold).
    pub fn ring(&self, v: usize) -> &[u32] {
        &self.ring[self.ring_start[v] as usize..self.ring_start[v + 1] as usize]
    }

    /// The half-edges of edge `e`, one per face.
    pub fn edge_faces(&self, e: usize) -> &[u32] {
        &self.edge_hes[self.edge_start[e] as usize..self.edge_start[e + 1] as usize]
    }

    /// The values of vertex `v`, in sibling order.
    pub fn values(&self, v: usize) -> &[u32] {
        &self.values[self.value_start[v] as usize..self.value_start[v + 1] as usize]
    }

    /// The tags of the values of vertex `v`.
    pub fn tags(&self, v: usize) -> &[Tag] {
        &self.tags[self.value_start[v] as usize..self.value_start[v + 1] as usize]
    }

    /// The values at both ends of edge `h`'s edge as face `face(h)` carries them.
    pub fn edge_values(&self, h: u32) -> [u32; 2] {
        let n = self.m.faces.next(h);
        [self.corner_value[h as usize], self.corner_value[n as usize]]
    }

    /// The sibling values per vertex, in the order of its corners. On the base net (`base`)
    /// they are assigned as OpenSubdiv assigns them (`FVarLevel::completeTopologyFromFaceValues`):
    /// walking the corners in ring order (OpenSubdiv's: from the lowest face, or from the
    /// face whose edge out of the vertex is a boundary edge), a corner whose value equals the
    /// previous corner's shares its sibling; a corner with another value is looked up among the
    /// values found so far, except that while exactly two are known and the value differs from
    /// the first, it is taken as new without comparing it with the second. So values
    /// alternating around a vertex (`a b a b`) give three siblings (`a`, `b` and a second `b`
    /// for the last run), which OpenSubdiv refines as separate values (its regression shapes
    /// `catmark_bishop`, `_car`, `_rook`, whose faces all carry the same four `vt`, need it).
    /// OpenSubdiv carries refined levels' siblings over from their parents instead, so there
    /// (`!base`, where every value index belongs to one vertex) equal values are one sibling.
    fn find_values(&mut self, base: bool) {
        let nv = self.ring_start.len() - 1;
        self.value_start.push(0);
        for v in 0..nv {
            let first = self.values.len();
            let mut prev: Option<(u32, usize)> = None;
            for k in self.ring_start[v]..self.ring_start[v + 1] {
                let h = self.ring[k as usize];
                let val = self.corner_value[h as usize];
                let known = self.values.len() - first;
                let s = match prev {
                    Some((p, s)) if p == val => s,
                    Some(_) if base && known == 2 && self.values[first] != val => known,
                    _ => self.values[first..]
                        .iter()
                        .position(|&x| x == val)
                        .unwrap_or(known),
                };
                if s == known {
                    self.values.push(val);
                }
                prev = Some((val, s));
                self.sibling[h as usize] = s as u32;
            }
            self.value_start.push(self.values.len() as u32);
        }
        self.tags = vec![Tag::Match; self.values.len()];
    }

    /// The discontinuous edges: the faces of the edge disagree at one of its ends (values
    /// compared by their seam class, so a refined level inherits its parent's seams).
    fn find_seams(&mut self) {
        let class = |v: u32| self.classes.get(v as usize).copied().unwrap_or(v);
        for e in 0..self.discts.len() {
            let hs = self.edge_faces(e);
            let a = self.m.from(hs[0]);
            let key = |h: u32| {
                let [x, y] = self.edge_values(h).map(class);
                if self.m.from(h) == a { [x, y] } else { [y, x] }
            };
            let first = key(hs[0]);
            self.discts[e] = hs[1..].iter().any(|&h| key(h) != first);
        }
    }

    /// Tags every value (OpenSubdiv's `completeTopologyFromFaceValues`).
    fn tag_values(&mut self, manifold: &[bool], opts: &SubdOptions) {
        let fvar = opts.fvar();
        let linear_boundaries =
            matches!(fvar, FvarInterpolation::All | FvarInterpolation::Boundaries);
        let dependent = matches!(
            fvar,
            FvarInterpolation::CornersPlus1 | FvarInterpolation::CornersPlus2
        );
        let corners_sharp = fvar != FvarInterpolation::None;
        let smooth_corners_sharp =
            opts.boundary() != BoundaryInterpolation::EdgeAndCorner && corners_sharp;
        let plus2 = fvar == FvarInterpolation::CornersPlus2;
        let sharpen_darts = plus2 || linear_boundaries;
        let nv = manifold.len();
        let mut mismatch = vec![false; nv];
        for e in 0..self.discts.len() {
            if self.discts[e] {
                self.linear[e] = linear_boundaries;
                let h = self.m.edge_he[e];
                mismatch[self.m.from(h) as usize] = true;
                mismatch[self.m.to(h) as usize] = true;
            }
        }
        for v in 0..nv {
            let ring = self.ring(v).to_vec();
            let boundary = ring.iter().any(|&h| self.m.twin(h) == NONE);
            if self.values(v).len() > 1 {
                mismatch[v] = true;
            }
            if boundary && !mismatch[v] {
                if linear_boundaries && !ring.is_empty() {
                    mismatch[v] = true;
                    for &h in &ring {
                        if self.m.twin(h) == NONE {
                            self.linear[self.m.he_edge[h as usize] as usize] = true;
                        }
                        let p = self.m.faces.prev(h);
                        if self.m.twin(p) == NONE {
                            self.linear[self.m.he_edge[p as usize] as usize] = true;
                        }
                    }
                } else if ring.len() == 1 && smooth_corners_sharp {
                    mismatch[v] = true;
                }
            }
        }
        for v in 0..nv {
            if !mismatch[v] {
                continue;
            }
            let nvals = self.values(v).len();
            let s = self.vertices[v];
            let boundary = self.ring(v).iter().any(|&h| self.m.twin(h) == NONE);
            let all_corners = linear_boundaries
                || s >= INFINITE
                || !manifold[v]
                || (dependent && nvals > 2)
                || (sharpen_darts && nvals == 1 && !boundary);
            let (a, b) = (
                self.value_start[v] as usize,
                self.value_start[v + 1] as usize,
            );
            if all_corners {
                self.tags[a..b].fill(Tag::Corner);
                continue;
            }
            let spans = self.spans(v, boundary);
            let mut all_corners = false;
            let mut to_sharpen = false;
            if dependent && nvals == 2 {
                all_corners = spans[0].disjoint != 0 || spans[1].disjoint != 0;
                if plus2 {
                    all_corners |= spans[0].size == 1 || spans[1].size == 1;
                }
                to_sharpen = spans[0].semi != spans[1].semi;
            }
            if all_corners {
                self.tags[a..b].fill(Tag::Corner);
                continue;
            }
            let n = self.ring(v).len() as u32;
            let semi_vertex = s > 0.0 && s < INFINITE;
            for (i, sp) in spans.iter().enumerate() {
                self.tags[a + i] = if sp.disjoint != 0 || (sp.size == 1 && corners_sharp) {
                    Tag::Corner
                } else {
                    let (start, end) = (sp.start, (sp.start + sp.size + n - 1) % n);
                    if sp.semi > 0 || semi_vertex {
                        Tag::SemiSharp { start, end }
                    } else if to_sharpen {
                        Tag::DepSharp { start, end }
                    } else {
                        Tag::Crease { start, end }
                    }
                };
            }
        }
    }

    /// Edge `k` of vertex `v`'s face order: the leading edge of face `k`.
    fn ring_edge(&self, v: usize, k: u32) -> usize {
        self.m.he_edge[self.ring(v)[k as usize] as usize] as usize
    }

    /// The spans of the values of manifold vertex `v` (OpenSubdiv's `gatherValueSpans`).
    fn spans(&self, v: usize, boundary: bool) -> Vec<Span> {
        let nvals = self.values(v).len();
        let ring = self.ring(v);
        let n = ring.len();
        let mut spans = vec![Span::default(); nvals];
        let inf = |e: usize| self.edges[e] >= INFINITE;
        let semi = |e: usize| self.edges[e] > 0.0 && self.edges[e] < INFINITE;
        if nvals == 1 {
            let s = &mut spans[0];
            let mut edges: Vec<usize> = (0..n as u32).map(|k| self.ring_edge(v, k)).collect();
            if boundary {
                edges.push(self.m.he_edge[self.m.faces.prev(ring[n - 1]) as usize] as usize);
            }
            for (i, &e) in edges.iter().enumerate() {
                if self.discts[e] {
                    if s.size != 0 {
                        s.disjoint = 1;
                        break;
                    }
                    s.size = n as u32;
                    s.start = i as u32;
                } else if inf(e) {
                    s.disjoint = 1;
                    break;
                } else if semi(e) {
                    s.semi += 1;
                }
            }
            return spans;
        }
        let sib = |k: usize| self.sibling[ring[k] as usize] as usize;
        spans[0].size = 1;
        if !boundary && sib(n - 1) == 0 {
            let e = self.ring_edge(v, 0);
            if self.discts[e] || inf(e) {
                spans[0].disjoint = 1;
            } else if semi(e) {
                spans[0].semi += 1;
            }
        }
        for i in 1..n {
            let s = sib(i);
            if s == sib(i - 1) {
                let e = self.ring_edge(v, i as u32);
                if self.discts[e] {
                    spans[s].disjoint += 1;
                } else if inf(e) {
                    spans[s].disjoint = 1;
                } else if semi(e) {
                    spans[s].semi += 1;
                }
            } else {
                if spans[s].size > 0 {
                    spans[s].disjoint += 1;
                }
                spans[s].start = i as u32;
            }
            spans[s].size += 1;
        }
        if !boundary && sib(n - 1) == 0 {
            spans[0].disjoint -= 1;
        }
        spans
    }

    /// The two crease end values of the span `start..=end` of vertex `v`: the value after `v`
    /// in its first face and the value before `v` in its last.
    pub fn crease_ends(&self, v: usize, start: u32, end: u32) -> [u32; 2] {
        let ring = self.ring(v);
        let h0 = ring[start as usize];
        let h1 = ring[end as usize];
        [
            self.corner_value[self.m.faces.next(h0) as usize],
            self.corner_value[self.m.faces.prev(h1) as usize],
        ]
    }

    /// The corner weight of a semi-sharp value of `v` whose span is `start..=end`: the mean
    /// sharpness of the features inside it that decay to 0 in this step (OpenSubdiv's
    /// `ComputeFractionalWeightAtVertex`), at most 1.
    pub fn fractional_weight(&self, v: usize, start: u32, end: u32) -> f64 {
        let n = self.ring(v).len() as u32;
        let s = self.vertices[v];
        let (mut sum, mut count) = (0f32, 0u32);
        if s > 0.0 && decrement(s) <= 0.0 {
            sum += s;
            count += 1;
        }
        let mut scratch = Scratch::default();
        let mut k = start;
        while k != end {
            k = (k + 1) % n;
            let e = self.ring_edge(v, k);
            let p = self.edges[e];
            let c = match &self.sharp {
                Some(sl) => sl.child_half(e as u32, v as u32, &mut scratch),
                None => decrement(p),
            };
            if p > 0.0 && c <= 0.0 {
                sum += p;
                count += 1;
            }
        }
        if count == 0 {
            0.0
        } else {
            f64::from((sum / count as f32).min(1.0))
        }
    }
}

/// Groups `0..n` by `key` into `keys` buckets: (offsets, members), members in increasing order.
fn csr(keys: usize, n: usize, key: impl Fn(usize) -> u32) -> (Vec<u32>, Vec<u32>) {
    let mut start = vec![0u32; keys + 1];
    for i in 0..n {
        start[key(i) as usize + 1] += 1;
    }
    for k in 0..keys {
        start[k + 1] += start[k];
    }
    let mut fill = start.clone();
    let mut out = vec![0u32; n];
    for i in 0..n {
        let k = key(i) as usize;
        out[fill[k] as usize] = i as u32;
        fill[k] += 1;
    }
    (start, out)
}

/// Orders the corners of a manifold vertex by faces: a boundary vertex from its leading
/// boundary edge, each next corner across the previous face's trailing edge. False (the order
/// left alone) when the corners do not form one fan.
fn order_ring(m: &MeshView<'_>, ring: &mut [u32]) -> bool {
    let start = ring
        .iter()
        .copied()
        .find(|&h| m.twin(h) == NONE)
        .unwrap_or(ring[0]);
    let mut ordered = Vec::with_capacity(ring.len());
    let mut h = start;
    loop {
        ordered.push(h);
        if ordered.len() > ring.len() {
            return false;
        }
        let t = m.twin(m.faces.prev(h));
        if t == NONE || t == start {
            break;
        }
        h = t;
    }
    if ordered.len() != ring.len() {
        return false;
    }
    ring.copy_from_slice(&ordered);
    true
}
