//! OpenSubdiv's sharp features, written once for Catmull-Clark and Loop: sharpness values,
//! the sharpening of a base net by its topology and boundary option, the vertex rules (smooth,
//! dart, crease, corner), the subdivision of sharpness (uniform and Chaikin) and the blending
//! of rules while a semi-sharp feature decays. `docs/opensubdiv-rules.md` states the rules with
//! their sources (OpenSubdiv's `Sdc::Crease`, `Sdc::Scheme`, `Far::TopologyRefinerFactory`);
//! this module implements them, reading OpenSubdiv's sources only to understand them.
//!
//! The schemes differ only in their smooth masks, so the rules here produce *plans*
//! ([`VertexPlan`], [`EdgePlan`], [`LimitPlan`]): which masks to combine with which weights,
//! the crease and corner masks given by their vertices, the smooth mask named ([`Emit::Smooth`])
//! for the scheme to write. Catmull-Clark's and Loop's kernels apply the plans to stencil rows
//! and to point data alike, so refinement, level stencils and limit positions share them.
//!
//! Sharpness is single precision (`f32`), as OpenSubdiv stores it, so that blend weights and
//! Chaikin averages are the same numbers as OpenSubdiv's.

use crate::mesh::tags::{BoundaryInterpolation, CreaseMethod, SubdOptions};
use crate::mesh::{Extras, MeshView, NONE, NonManifold, PolyMesh, SharpEdges};

pub(crate) mod adaptive;
mod plan;

pub(crate) use plan::*;

/// An incident edge of a vertex: its index and its other end.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Spoke {
    /// The edge.
    pub edge: u32,
    /// Its other end (the vertex itself for a degenerate edge).
    pub other: u32,
}

/// A reusable buffer for the incident edges of one vertex.
#[derive(Debug, Default)]
pub(crate) struct Scratch {
    spokes: Vec<Spoke>,
    child: Vec<f32>,
}

/// The sharpness of one level in dense arrays, with the topology queries the rules need.
pub(crate) struct SharpLevel<'a> {
    mesh: &'a PolyMesh,
    m: MeshView<'a>,
    nm: Option<&'a NonManifold>,
    /// Sharpness per edge.
    pub edges: Vec<f32>,
    /// Sharpness per vertex.
    pub vertices: Vec<f32>,
    /// Vertices whose point is not the plain smooth rule: a sharp vertex, a sharp incident
    /// edge (boundary edges are sharp), a non-manifold vertex.
    pub special: Vec<bool>,
    /// Hole faces (sorted), those of the net and those that boundary `none` makes.
    pub holes: Vec<u32>,
    chaikin: bool,
}

impl<'a> SharpLevel<'a> {
    /// The sharp level of `mesh` under `opts`, or `None` when the plain rules give the same
    /// points (no sharp feature, a manifold net, boundaries interpolated edge-and-corner or no
    /// boundary): the kernels then keep their plain path.
    pub fn new(mesh: &'a PolyMesh, opts: &SubdOptions) -> Option<SharpLevel<'a>> {
        let ex = mesh.extras();
        let features = ex.is_some_and(Extras::has_features);
        let t = mesh.topology();
        let m = mesh.view();
        let boundary_matters = opts.boundary() != BoundaryInterpolation::EdgeAndCorner
            && !ex.is_some_and(|e| e.sharpened)
            && m.twin.contains(&NONE);
        if !features && t.nm.is_none() && !boundary_matters {
            return None;
        }
        let (ne, nv) = (mesh.num_edges(), mesh.num_vertices());
        let mut edges = vec![0f32; ne];
        let mut vertices = vec![0f32; nv];
        let mut holes = Vec::new();
        let mut sharpened = false;
        if let Some(ex) = ex {
            match &ex.sharp_edges {
                SharpEdges::ById(v) => v.iter().for_each(|&(e, s)| edges[e as usize] = s),
                SharpEdges::ByPair(v) => {
                    for &([a, b], s) in v {
                        if let Some(e) = mesh.find_edge(a, b) {
                            edges[e as usize] = s;
                        }
                    }
                }
            }
            ex.sharp_vertices
                .iter()
                .for_each(|&(v, s)| vertices[v as usize] = s);
            holes.clone_from(&ex.holes);
            sharpened = ex.sharpened;
        }
        let mut level = SharpLevel {
            mesh,
            m,
            nm: t.nm.as_deref(),
            edges,
            vertices,
            special: Vec::new(),
            holes,
            chaikin: opts.crease_method() == CreaseMethod::Chaikin,
        };
        if !sharpened {
            level.sharpen(opts.boundary());
        }
        let mut special = vec![false; nv];
        for (e, &s) in level.edges.iter().enumerate() {
            if sharp(s) {
                let h = m.edge_he[e];
                special[m.from(h) as usize] = true;
                special[m.to(h) as usize] = true;
            }
        }
        for (v, sp) in special.iter_mut().enumerate() {
            *sp |= sharp(level.vertices[v]) || level.nm.is_some_and(|nm| nm.vertex[v]);
        }
        level.special = special;
        Some(level)
    }

    /// Whether semi-sharp edges decay by OpenSubdiv's Chaikin rule (else uniformly).
    pub fn chaikin(&self) -> bool {
        self.chaikin
    }

    /// Number of sides (faces) of edge `e`.
    fn edge_faces(&self, e: u32) -> usize {
        match self.nm {
            Some(nm) if nm.edge[e as usize] => nm.edge_sides(e).len(),
            _ => 1 + usize::from(self.m.twin(self.m.edge_he[e as usize]) != NONE),
        }
    }

    /// OpenSubdiv's sharpening of a base net (docs/opensubdiv-rules.md, section 2.1): holes
    /// at the boundary for `none`, boundary and non-manifold edges infinitely sharp, corners
    /// for edge-and-corner, non-manifold vertices except those inside a non-manifold crease.
    fn sharpen(&mut self, boundary: BoundaryInterpolation) {
        let nv = self.vertices.len();
        let mut scratch = Scratch::default();
        if boundary == BoundaryInterpolation::None {
            let mut hole = vec![false; self.mesh.num_faces()];
            for &f in &self.holes {
                hole[f as usize] = true;
            }
            for v in 0..nv {
                let nm = self.nm.is_some_and(|nm| nm.vertex[v]);
                let on_boundary = nm || self.m.is_boundary_vertex(v);
                if !on_boundary {
                    continue;
                }
                self.spokes(v as u32, &mut scratch.spokes);
                let exclude = scratch.spokes.iter().any(|s| {
                    self.edge_faces(s.edge) == 1 && self.edges[s.edge as usize] < INFINITE
                });
                if exclude {
                    self.for_each_face(v as u32, |f| hole[f as usize] = true);
                }
            }
            self.holes = (0..hole.len() as u32)
                .filter(|&f| hole[f as usize])
                .collect();
        }
        for e in 0..self.edges.len() as u32 {
            let nm = self.nm.is_some_and(|nm| nm.edge[e as usize]);
            if nm || self.edge_faces(e) < 2 {
                self.edges[e as usize] = INFINITE;
            }
        }
        for v in 0..nv as u32 {
            let nm = self.nm.is_some_and(|nm| nm.vertex[v as usize]);
            let (faces, edges) = self.counts(v);
            if faces == 1 && edges == 2 && boundary == BoundaryInterpolation::EdgeAndCorner {
                self.vertices[v as usize] = INFINITE;
            } else if nm {
                self.spokes(v, &mut scratch.spokes);
                let (mut nm_edges, mut boundary_edges) = (0, 0);
                for s in &scratch.spokes {
                    nm_edges += usize::from(self.nm.is_some_and(|t| t.edge[s.edge as usize]));
                    boundary_edges += usize::from(self.edge_faces(s.edge) == 1);
                }
                let fin = nm_edges == 2 && boundary_edges == 0 && faces > edges;
                if !fin {
                    self.vertices[v as usize] = INFINITE;
                }
            }
        }
    }

    /// `(faces, edges)` at vertex `v` (a face counted once per corner at `v`).
    fn counts(&self, v: u32) -> (usize, usize) {
        match self.nm {
            Some(nm) if nm.vertex[v as usize] => (nm.vertex_out(v).len(), nm.vertex_edges(v).len()),
            _ => {
                let n = self.m.outgoing(v as usize).count();
                (n, n + usize::from(self.m.is_boundary_vertex(v as usize)))
            }
        }
    }

    /// Calls `f` with every face at `v` (once per corner).
    fn for_each_face(&self, v: u32, mut f: impl FnMut(u32)) {
        match self.nm {
            Some(nm) if nm.vertex[v as usize] => {
                nm.vertex_out(v).iter().for_each(|&h| f(self.m.face(h)))
            }
            _ => self.m.outgoing(v as usize).for_each(|h| f(self.m.face(h))),
        }
    }

    /// The incident edges of `v` into `out`: for a manifold vertex counter-clockwise from its
    /// vertex half-edge (the incoming boundary edge last), for a non-manifold one in edge
    /// order (a degenerate edge twice).
    pub fn spokes(&self, v: u32, out: &mut Vec<Spoke>) {
        out.clear();
        let m = &self.m;
        match self.nm {
            Some(nm) if nm.vertex[v as usize] => {
                for &(e, end) in nm.vertex_edges(v) {
                    let h = m.edge_he[e as usize];
                    let other = if end == 0 { m.to(h) } else { m.from(h) };
                    out.push(Spoke { edge: e, other });
                }
            }
            _ => {
                let mut last = NONE;
                for h in m.outgoing(v as usize) {
                    out.push(Spoke {
                        edge: m.he_edge[h as usize],
                        other: m.to(h),
                    });
                    last = h;
                }
                if last != NONE && m.twin(m.vert_he[v as usize]) == NONE {
                    let p = m.faces.prev(last);
                    out.push(Spoke {
                        edge: m.he_edge[p as usize],
                        other: m.from(p),
                    });
                }
            }
        }
    }

    /// The child sharpness of the half of edge `e` at its end `v`, given the incident edges
    /// of `v` (`spokes`, as [`SharpLevel::spokes`] gives them).
    fn child_half_with(&self, e: u32, spokes: &[Spoke]) -> f32 {
        let s = self.edges[e as usize];
        if !self.chaikin || spokes.len() < 2 || !semi_sharp(s) {
            return decrement(s);
        }
        let (mut sum, mut count) = (0f32, 0usize);
        for sp in spokes {
            let x = self.edges[sp.edge as usize];
            if semi_sharp(x) {
                sum += x;
                count += 1;
            }
        }
        let mut t = s;
        if count > 1 {
            let avg = (sum - s) / (count - 1) as f32;
            t = 0.75 * s + 0.25 * avg;
        }
        t -= 1.0;
        if sharp(t) { t } else { 0.0 }
    }

    /// The child sharpness of the half of edge `e` at its end `v`.
    pub fn child_half(&self, e: u32, v: u32, scratch: &mut Scratch) -> f32 {
        let s = self.edges[e as usize];
        if !self.chaikin || !semi_sharp(s) {
            return decrement(s);
        }
        let mut spokes = std::mem::take(&mut scratch.spokes);
        self.spokes(v, &mut spokes);
        let c = self.child_half_with(e, &spokes);
        scratch.spokes = spokes;
        c
    }

    /// The plan of the edge point of edge `e` (ends `a`, `b` of its first half-edge).
    pub fn edge_plan(&self, e: u32, scratch: &mut Scratch) -> EdgePlan {
        let s = self.edges[e as usize];
        if !sharp(s) {
            return EdgePlan::Smooth;
        }
        let h = self.m.edge_he[e as usize];
        let (a, b) = (self.m.from(h), self.m.to(h));
        let ca = self.child_half(e, a, scratch);
        let cb = self.child_half(e, b, scratch);
        if sharp(ca) && sharp(cb) {
            EdgePlan::Crease
        } else {
            EdgePlan::Blend(s as f64)
        }
    }

    /// The plan of the vertex point of `v` (a [`SharpLevel::special`] vertex; any vertex
    /// works).
    pub fn vertex_plan(&self, v: u32, scratch: &mut Scratch) -> VertexPlan {
        let mut spokes = std::mem::take(&mut scratch.spokes);
        self.spokes(v, &mut spokes);
        let plan = self.plan_with(v, &spokes, &mut scratch.child);
        scratch.spokes = spokes;
        plan
    }

    fn plan_with(&self, v: u32, spokes: &[Spoke], child: &mut Vec<f32>) -> VertexPlan {
        let ps = self.vertices[v as usize];
        let edge_s = |sp: &Spoke| self.edges[sp.edge as usize];
        let pk = spokes.iter().filter(|sp| sharp(edge_s(sp))).count();
        let prule = classify(ps, pk);
        if matches!(prule, Rule::Smooth | Rule::Dart) {
            return VertexPlan::Single(VertexMask::Smooth);
        }
        let ends = |sharp_of: &dyn Fn(usize) -> bool| {
            let mut it = (0..spokes.len()).filter(|&i| sharp_of(i));
            let a = it.next().map_or(v, |i| spokes[i].other);
            let b = it.next().map_or(v, |i| spokes[i].other);
            (a, b)
        };
        let pmask = if prule == Rule::Crease {
            let (a, b) = ends(&|i| sharp(edge_s(&spokes[i])));
            VertexMask::Crease(a, b)
        } else {
            VertexMask::Corner
        };
        let cs = decrement(ps);
        child.clear();
        child.extend(
            spokes
                .iter()
                .map(|sp| self.child_half_with(sp.edge, spokes)),
        );
        let ck = child.iter().filter(|&&c| sharp(c)).count();
        let crule = classify(cs, ck);
        if crule == prule {
            return VertexPlan::Single(pmask);
        }
        let cmask = match crule {
            Rule::Smooth | Rule::Dart => VertexMask::Smooth,
            Rule::Crease => {
                let (a, b) = ends(&|i| sharp(child[i]));
                VertexMask::Crease(a, b)
            }
            Rule::Corner => VertexMask::Corner,
        };
        // OpenSubdiv's fractional weight: the mean of the sharpness values that decay to 0.
        let (mut sum, mut count) = (0f32, 0u32);
        if sharp(ps) && !sharp(cs) {
            sum = ps;
            count = 1;
        }
        for (i, sp) in spokes.iter().enumerate() {
            let s = edge_s(sp);
            let decays = if self.chaikin {
                sharp(s) && !sharp(child[i])
            } else {
                sharp(s) && s <= 1.0
            };
            if decays {
                sum += s;
                count += 1;
            }
        }
        let w = if count == 0 {
            0.0
        } else {
            (sum / count as f32).min(1.0)
        };
        VertexPlan::Blend {
            parent: pmask,
            child: cmask,
            w: w as f64,
        }
    }

    /// The limit mask of `v` at this level (semi-sharp features count as sharp).
    pub fn limit_plan(&self, v: u32, scratch: &mut Scratch) -> LimitPlan {
        let mut spokes = std::mem::take(&mut scratch.spokes);
        self.spokes(v, &mut spokes);
        let mut sharp_ends = spokes
            .iter()
            .filter(|sp| sharp(self.edges[sp.edge as usize]))
            .map(|sp| sp.other);
        let plan = if spokes.is_empty() {
            LimitPlan::Corner
        } else {
            match classify(
                self.vertices[v as usize],
                spokes
                    .iter()
                    .filter(|sp| sharp(self.edges[sp.edge as usize]))
                    .count(),
            ) {
                Rule::Smooth | Rule::Dart => LimitPlan::Smooth,
                Rule::Crease => {
                    let a = sharp_ends.next().unwrap_or(v);
                    let b = sharp_ends.next().unwrap_or(v);
                    LimitPlan::Crease(a, b)
                }
                Rule::Corner => LimitPlan::Corner,
            }
        };
        scratch.spokes = spokes;
        plan
    }

    /// The extras of the child level, given where the child's edge halves lie: `half(h, at_to)`
    /// names the child edge on the half of edge(h) at the start (`false`) or the end (`true`)
    /// of parent half-edge `h` (as an id, or as the end points when the child has no
    /// numbered edges); `child_faces(f)` lists the child faces of parent face `f`. Face-varying
    /// and vertex data are left to the caller.
    pub fn child_extras(
        &self,
        half: impl Fn(u32, bool) -> ChildEdge,
        child_faces: impl Fn(u32, &mut Vec<u32>),
    ) -> Extras {
        let mut scratch = Scratch::default();
        let (mut by_id, mut by_pair) = (Vec::new(), Vec::new());
        for (e, &s) in self.edges.iter().enumerate() {
            if !sharp(s) {
                continue;
            }
            let h = self.m.edge_he[e];
            for (at_to, v) in [(false, self.m.from(h)), (true, self.m.to(h))] {
                let c = self.child_half(e as u32, v, &mut scratch);
                if sharp(c) {
                    match half(h, at_to) {
                        ChildEdge::Id(id) => by_id.push((id, c)),
                        ChildEdge::Pair(p) => by_pair.push((p, c)),
                    }
                }
            }
        }
        let sharp_edges = if by_pair.is_empty() {
            by_id.sort_unstable_by_key(|p| p.0);
            by_id.dedup_by_key(|p| p.0);
            SharpEdges::ById(by_id)
        } else {
            SharpEdges::ByPair(by_pair)
        };
        let sharp_vertices = self
            .vertices
            .iter()
            .enumerate()
            .filter_map(|(v, &s)| {
                let c = decrement(s);
                sharp(c).then_some((v as u32, c))
            })
            .collect();
        let mut holes = Vec::new();
        let mut buf = Vec::new();
        for &f in &self.holes {
            buf.clear();
            child_faces(f, &mut buf);
            holes.extend_from_slice(&buf);
        }
        holes.sort_unstable();
        Extras {
            sharp_edges,
            sharp_vertices,
            holes,
            sharpened: true,
            uv: None,
            vertex_data: None,
            options: SubdOptions::default(),
        }
    }
}

/// Where a child edge is: its index, or its end points when the child's edges are not
/// numbered (the last level of a one-shot refinement).
#[derive(Debug, Clone, Copy)]
pub(crate) enum ChildEdge {
    /// The child edge's index.
    Id(u32),
    /// Its end points.
    Pair([u32; 2]),
}

/// Receives the terms of an edge point under OpenSubdiv's edge rules ([`edge_terms`]).
pub(crate) trait EdgeTerms {
    /// The scheme's smooth edge mask, times `s`.
    fn smooth(&mut self, s: f64);
    /// Weight `w` on parent vertex `u`.
    fn vertex(&mut self, u: u32, w: f64);
}

/// The terms of the point of edge `e` under OpenSubdiv's edge rules, for Catmull-Clark and Loop
/// alike: with the level's features (`sharp`), the edge's plan (smooth, crease midpoint, or a
/// blend of the two while a semi-sharp edge decays); without them, the midpoint on a boundary
/// edge and the smooth mask elsewhere.
#[inline(always)]
pub(crate) fn edge_terms(
    m: &MeshView<'_>,
    e: usize,
    sharp: Option<&SharpLevel<'_>>,
    scratch: &mut Scratch,
    out: &mut impl EdgeTerms,
) {
    let plan = match sharp {
        Some(sl) => sl.edge_plan(e as u32, scratch),
        None if m.twin(m.edge_he[e]) == NONE => {
            // EdgePlan::Crease's terms, emitted here: passing `out` to the plan's closure kept
            // the kernel's accumulator in memory for every point (+6% instructions of
            // Catmull-Clark's `--levels 3`, callgrind)
            let h = m.edge_he[e];
            out.vertex(m.from(h), CREASE_EDGE);
            out.vertex(m.to(h), CREASE_EDGE);
            return;
        }
        None => EdgePlan::Smooth,
    };
    if plan == EdgePlan::Smooth {
        return out.smooth(1.0);
    }
    let h = m.edge_he[e];
    plan.emit(m.from(h), m.to(h), |t| match t {
        Emit::Smooth(s) => out.smooth(s),
        Emit::Vertex(u, w) => out.vertex(u, w),
    });
}
