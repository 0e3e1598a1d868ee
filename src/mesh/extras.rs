//! What a net may carry besides its polygons: sharp features (edge and vertex sharpness,
//! holes), face-varying data (texture coordinates per face corner) and per-vertex data
//! (colours and other PLY properties), and the tolerant constructor for the non-manifold nets
//! that Catmull-Clark and Loop take.
//!
//! Most nets carry nothing ([`PolyMesh::extras`] is `None`), and the refinement kernels keep
//! their plain path for them. Catmull-Clark and Loop refine the extras with the net (sharpness
//! by OpenSubdiv's rules, face-varying data by its face-varying rules, vertex data by the
//! vertex stencils), so a refined level carries its own; readers fill them from tags, `vt`
//! lines and PLY properties, writers write them back.

use super::tags::{SubdOptions, Tags};
use super::{FaceIndex, NONE, PolyMesh, Topology, uniform_size};
use crate::error::{Error, Result};
use crate::geom::Point;
use std::sync::OnceLock;

/// The sharp edges of a net: `(edge, sharpness)` with sharpness `> 0`, by edge index, or by
/// end points for a refined level whose edges are not numbered yet (the last level of a
/// one-shot refinement builds its connectivity only on first use).
#[derive(Debug, Clone, PartialEq)]
pub enum SharpEdges {
    /// By edge index, increasing.
    ById(Vec<(u32, f32)>),
    /// By end points.
    ByPair(Vec<([u32; 2], f32)>),
}

impl Default for SharpEdges {
    fn default() -> Self {
        SharpEdges::ById(Vec::new())
    }
}

impl SharpEdges {
    /// Whether no edge is sharp.
    pub fn is_empty(&self) -> bool {
        match self {
            SharpEdges::ById(v) => v.is_empty(),
            SharpEdges::ByPair(v) => v.is_empty(),
        }
    }

    /// Number of sharp edges.
    pub fn len(&self) -> usize {
        match self {
            SharpEdges::ById(v) => v.len(),
            SharpEdges::ByPair(v) => v.len(),
        }
    }
}

/// How a per-vertex property was stored in its file (for writing it back the same way).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ScalarKind {
    /// 8-bit unsigned (colours 0..255).
    U8,
    /// 8-bit signed.
    I8,
    /// 16-bit unsigned.
    U16,
    /// 16-bit signed.
    I16,
    /// 32-bit unsigned.
    U32,
    /// 32-bit signed.
    I32,
    /// Single precision.
    F32,
    /// Double precision.
    F64,
}

impl ScalarKind {
    /// Whether the kind holds integers.
    pub fn is_integer(self) -> bool {
        !matches!(self, ScalarKind::F32 | ScalarKind::F64)
    }

    /// The value a file of this kind stores for `x`: integer kinds round to the nearest integer
    /// (halves away from zero) and clamp to their range (a colour channel that a stencil with
    /// negative weights takes past 255 is written as 255); `F32` rounds to single precision.
    pub fn stored(self, x: f64) -> f64 {
        let clamp = |lo: f64, hi: f64| x.round().clamp(lo, hi);
        match self {
            ScalarKind::U8 => clamp(0.0, 255.0),
            ScalarKind::I8 => clamp(-128.0, 127.0),
            ScalarKind::U16 => clamp(0.0, 65535.0),
            ScalarKind::I16 => clamp(-32768.0, 32767.0),
            ScalarKind::U32 => clamp(0.0, 4294967295.0),
            ScalarKind::I32 => clamp(-2147483648.0, 2147483647.0),
            ScalarKind::F32 => x.clamp(-f64::from(f32::MAX), f64::from(f32::MAX)) as f32 as f64,
            ScalarKind::F64 => x,
        }
    }
}

/// Per-vertex data refined with the net by the vertex stencils (colours, other properties).
#[derive(Debug, Clone, PartialEq)]
pub struct VertexData {
    /// The property names, one per channel (PLY names such as `red`, `quality`).
    pub names: Vec<String>,
    /// How the file stored each channel.
    pub kinds: Vec<ScalarKind>,
    /// The values, vertex after vertex (`names.len()` per vertex).
    pub values: Vec<f64>,
}

impl VertexData {
    /// Number of channels.
    pub fn width(&self) -> usize {
        self.names.len()
    }

    /// Number of vertices the data covers.
    pub fn num_points(&self) -> usize {
        self.values.len().checked_div(self.width()).unwrap_or(0)
    }

    /// The data of the points `table` makes from these points (row `i` gives point `i`): each
    /// channel goes through the table's own apply, as positions do (the channels in groups of
    /// [`VertexData::GROUP`], as `[f64; GROUP]` points), so refinement and limit projection
    /// treat the data exactly as OpenSubdiv's `PrimvarRefiner::Interpolate` treats vertex
    /// primvars: the same weights as the positions. Values stay unrounded (`f64`) until written.
    ///
    /// # Panics
    /// When the table's sources are not these points.
    pub fn through(&self, table: &crate::stencil::StencilTable) -> VertexData {
        let (w, n) = (self.width(), self.num_points());
        assert_eq!(
            table.num_sources(),
            n,
            "vertex data and stencil sources differ"
        );
        let rows = table.num_rows();
        let mut values = vec![0.0; rows * w];
        let mut src = vec![[0.0; Self::GROUP]; n];
        let mut out = vec![[0.0; Self::GROUP]; rows];
        for c0 in (0..w).step_by(Self::GROUP) {
            let k = Self::GROUP.min(w - c0);
            for (s, v) in src.iter_mut().zip(self.values.chunks_exact(w)) {
                s[..k].copy_from_slice(&v[c0..c0 + k]);
            }
            table.apply_into(&src, &mut out);
            for (o, v) in out.iter().zip(values.chunks_exact_mut(w)) {
                v[c0..c0 + k].copy_from_slice(&o[..k]);
            }
        }
        VertexData {
            names: self.names.clone(),
            kinds: self.kinds.clone(),
            values,
        }
    }

    /// Channels applied together by [`VertexData::through`].
    pub const GROUP: usize = 4;

    /// The data of the vertices `keep` lists, in that order.
    pub fn select(&self, keep: impl Iterator<Item = usize>) -> VertexData {
        let w = self.width();
        let mut values = Vec::new();
        for v in keep {
            values.extend_from_slice(&self.values[v * w..(v + 1) * w]);
        }
        VertexData {
            names: self.names.clone(),
            kinds: self.kinds.clone(),
            values,
        }
    }
}

/// Face-varying data: one value index per face corner into a list of 2D values (texture
/// coordinates), refined by OpenSubdiv's face-varying rules.
#[derive(Debug, Clone, PartialEq)]
pub struct FaceVarying {
    /// The values.
    pub values: Vec<[f64; 2]>,
    /// The value of each face corner (half-edge order: face after face).
    pub corners: Vec<u32>,
    /// The property names the values came from (`u v` for OBJ `vt`, the PLY names).
    pub names: [String; 2],
    /// Per value, the class its seams are judged by: empty for values as read (every value
    /// its own class); on a refined level the class of the parent value a vertex point's
    /// value comes from (OpenSubdiv inherits a refined level's seams from the parent level
    /// instead of comparing value indices again, and a base vertex may give one value two
    /// siblings, see `schemes::sdc::fvar`), a new class for every other value.
    pub classes: Vec<u32>,
}

/// The extras of a net (see the module documentation).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Extras {
    /// Sharp edges.
    pub sharp_edges: SharpEdges,
    /// Sharp vertices `(vertex, sharpness > 0)`, by vertex.
    pub sharp_vertices: Vec<(u32, f32)>,
    /// Hole faces, increasing.
    pub holes: Vec<u32>,
    /// Whether the sharpening by topology (boundaries, corners, non-manifold features, the
    /// holes of boundary `none`) has been applied: false for a net as read, true for a refined
    /// level (it is applied once, to the base net).
    pub sharpened: bool,
    /// Face-varying data.
    pub uv: Option<FaceVarying>,
    /// Per-vertex data.
    pub vertex_data: Option<VertexData>,
    /// The subdivision options the net's file asks for (its tags); a scheme's options given on
    /// the command line override them.
    pub options: SubdOptions,
}

impl Extras {
    /// Whether the extras hold sharp features (sharpness or holes).
    pub fn has_features(&self) -> bool {
        !(self.sharp_edges.is_empty() && self.sharp_vertices.is_empty() && self.holes.is_empty())
    }

    /// Whether there is nothing in them (a plain net).
    pub fn is_empty(&self) -> bool {
        !self.has_features()
            && self.uv.is_none()
            && self.vertex_data.is_none()
            && self.options.is_empty()
    }
}

impl PolyMesh {
    /// Builds a mesh from flat face arrays accepting everything OpenSubdiv accepts (see
    /// `mesh::general`): non-manifold edges and vertices, faces that repeat a vertex, vertices
    /// that no face uses (kept, in their place). Still refused, naming the element: no faces,
    /// faces with fewer than three corners, indices out of range, non-finite coordinates.
    ///
    /// A manifold net without unused vertices gets the same mesh as [`PolyMesh::from_flat`].
    pub fn from_flat_general(
        positions: Vec<Point>,
        face_start: Vec<u32>,
        corners: Vec<u32>,
    ) -> Result<PolyMesh> {
        let nf = super::face_count(&positions, &face_start)?;
        let nv = positions.len();
        let mut repeats = false;
        // The linear repeated-corner test (comparing every pair of corners cost k^2 in a k-gon:
        // `info` on a 200k-gon took 5 s here).
        let mut last_face = Vec::new();
        for f in 0..nf {
            let face = &corners[face_start[f] as usize..face_start[f + 1] as usize];
            super::check_face(face, f, nv)?;
            repeats |= super::repeated_corner(face, f as u32, &mut last_face).is_some();
        }
        super::check_finite(&positions)?;
        let mut used = vec![false; nv];
        for &v in &corners {
            used[v as usize] = true;
        }
        let uniform = uniform_size(&face_start);
        let strict = (!repeats && used.iter().all(|&u| u))
            .then(|| Topology::build(nv, &face_start, &corners, uniform, false).ok())
            .flatten();
        let topo = match strict {
            Some(t) => t,
            None => Self::general_topology(nv, &face_start, &corners, uniform),
        };
        Ok(Self::assemble(
            positions,
            face_start,
            corners,
            uniform,
            topo,
            Vec::new(),
        ))
    }

    /// The tolerant topology of a base net (OpenSubdiv's edge identification).
    pub(super) fn general_topology(
        nv: usize,
        face_start: &[u32],
        corners: &[u32],
        uniform: u32,
    ) -> Topology {
        let he_face = super::csr::halfedge_faces(face_start, corners.len(), uniform);
        let faces = FaceIndex::new(face_start, &he_face, uniform);
        let (raw, count, nm) = super::general::osd_edges(faces, corners);
        Topology::build_general(nv, faces, corners, &raw, count, &nm, &[])
    }

    /// A mesh from refinement whose connectivity the kernel built itself (the tolerant path of
    /// Catmull-Clark and Loop), or `None` to build it on first use (tolerantly): nothing is
    /// checked.
    pub(crate) fn from_trusted_parts(
        positions: Vec<Point>,
        face_start: Vec<u32>,
        corners: Vec<u32>,
        topo: Option<Topology>,
    ) -> PolyMesh {
        let uniform = uniform_size(&face_start);
        PolyMesh {
            positions,
            face_start: OnceLock::from(face_start),
            corners,
            uniform,
            topo: topo.map(OnceLock::from).unwrap_or_default(),
            edges: OnceLock::new(),
            dropped: Vec::new(),
            extras: None,
        }
    }

    /// Whether the net is manifold (every net but those of [`PolyMesh::from_flat_general`]
    /// with non-manifold features or unused vertices, and their refinements).
    pub fn is_manifold(&self) -> bool {
        self.topology().nm.is_none()
    }

    /// Fails, naming the first non-manifold element, unless the net is manifold: for the
    /// operations that need a manifold net (exact patches, analysis, other schemes).
    pub fn require_manifold(&self, what: &str) -> Result<()> {
        let Some(nm) = &self.topology().nm else {
            return Ok(());
        };
        if let Some(&e) = nm.edges.first() {
            let [a, b] = self.edge(e as usize);
            let faces: Vec<u32> = nm.edge_sides(e).iter().map(|&h| self.he_face(h)).collect();
            return Err(Error::Unsupported(format!(
                "{what} a manifold net, but edge {a}-{b} is non-manifold (used by faces {faces:?}); \
                 only the schemes with OpenSubdiv's rules (Catmull-Clark, Loop) refine such nets (--levels)"
            )));
        }
        let v = nm.vertices.first().copied().unwrap_or(0);
        let why = if self.topology().vert_he[v as usize] == NONE {
            "is used by no face"
        } else {
            "joins separate fans of faces"
        };
        Err(Error::Unsupported(format!(
            "{what} a manifold net, but vertex {v} {why} (non-manifold); only the schemes with \
             OpenSubdiv's rules (Catmull-Clark, Loop) refine such nets (--levels)"
        )))
    }

    /// Whether vertex `v` is non-manifold (see `mesh::general`).
    #[inline]
    pub fn is_nonmanifold_vertex(&self, v: usize) -> bool {
        self.topology().nm.as_ref().is_some_and(|nm| nm.vertex[v])
    }

    /// The extras the net carries (`None` for a plain net).
    pub fn extras(&self) -> Option<&Extras> {
        self.extras.as_deref()
    }

    /// Replaces the extras (`None` or empty extras make a plain net).
    pub fn set_extras(&mut self, extras: Option<Extras>) {
        self.extras = extras
            .filter(|e| !e.is_empty() || e.sharpened)
            .map(Box::new);
    }

    /// The net with these extras.
    pub fn with_extras(mut self, extras: Option<Extras>) -> PolyMesh {
        self.set_extras(extras);
        self
    }

    /// Takes the extras out.
    pub fn take_extras(&mut self) -> Option<Extras> {
        self.extras.take().map(|b| *b)
    }

    /// The mesh index of input vertex `v` (input vertices that no face used were dropped by
    /// [`PolyMesh::from_flat`]); `None` for a dropped vertex or one out of range.
    pub fn input_vertex(&self, v: usize) -> Option<u32> {
        let below = self.dropped.partition_point(|&d| d < v);
        if self.dropped.get(below) == Some(&v) {
            return None;
        }
        let m = v - below;
        (m < self.num_vertices()).then_some(m as u32)
    }

    /// The edge between vertices `a` and `b`, the first created one if there are several (as
    /// OpenSubdiv's `findEdge`).
    pub fn find_edge(&self, a: u32, b: u32) -> Option<u32> {
        let t = self.topology();
        if let Some(nm) = &t.nm {
            for (v, w) in [(a, b), (b, a)] {
                if nm.vertex[v as usize] {
                    return nm
                        .vertex_edges(v)
                        .iter()
                        .map(|&(e, _)| e)
                        .filter(|&e| {
                            let [x, y] = self.edge(e as usize);
                            (x, y) == (v, w) || (x, y) == (w, v)
                        })
                        .min();
                }
            }
        }
        if t.vert_he.get(a as usize).is_none_or(|&h| h == NONE) {
            return None;
        }
        let from = |v: u32, w: u32| self.find_halfedge(v as usize, w as usize);
        from(a, b).or_else(|| from(b, a)).map(|h| self.he_edge(h))
    }

    /// Attaches the tags of a file: creases to the edges they name, corners to their vertices,
    /// holes to their faces (input numbering, mapped through dropped vertices). Errors name the
    /// tag's line: a vertex or face out of range or dropped, two vertices that share no edge.
    /// The tags' options are kept in [`Extras::options`] (a scheme's options override them).
    pub fn with_tags(mut self, tags: &Tags, path: &std::path::Path) -> Result<PolyMesh> {
        if tags.is_empty() {
            return Ok(self);
        }
        let err = |line: usize, msg: String| Error::Parse {
            path: path.to_path_buf(),
            line,
            msg,
        };
        let vertex = |m: &PolyMesh, v: u32, line: usize, what: &str| {
            m.input_vertex(v as usize).ok_or_else(|| {
                err(
                    line,
                    format!(
                        "{what} tag names vertex {v} (counted from 0), which {}",
                        if (v as usize) < m.num_vertices() + m.dropped.len() {
                            "no face uses (it was dropped)"
                        } else {
                            "does not exist"
                        }
                    ),
                )
            })
        };
        let mut ex = self.take_extras().unwrap_or_default();
        let mut edges: Vec<(u32, f32)> = match std::mem::take(&mut ex.sharp_edges) {
            SharpEdges::ById(v) => v,
            SharpEdges::ByPair(_) => Vec::new(),
        };
        for c in &tags.creases {
            let a = vertex(&self, c.a, c.line, "crease")?;
            let b = vertex(&self, c.b, c.line, "crease")?;
            let e = self.find_edge(a, b).ok_or_else(|| {
                err(
                    c.line,
                    format!(
                        "crease tag names vertices {} and {}, which share no edge",
                        c.a, c.b
                    ),
                )
            })?;
            edges.push((e, c.sharpness));
        }
        ex.sharp_edges = SharpEdges::ById(last_per_key(edges));
        let mut verts = std::mem::take(&mut ex.sharp_vertices);
        for c in &tags.corners {
            verts.push((vertex(&self, c.vertex, c.line, "corner")?, c.sharpness));
        }
        ex.sharp_vertices = last_per_key(verts);
        for h in &tags.holes {
            if h.face as usize >= self.num_faces() {
                return Err(err(
                    h.line,
                    format!(
                        "hole tag names face {} (counted from 0), but the net has {} faces",
                        h.face,
                        self.num_faces()
                    ),
                ));
            }
            ex.holes.push(h.face);
        }
        ex.holes.sort_unstable();
        ex.holes.dedup();
        ex.options = tags.options.or(ex.options);
        self.set_extras(Some(ex));
        Ok(self)
    }

    /// Whether face `f` is a hole.
    pub fn is_hole(&self, f: usize) -> bool {
        self.extras()
            .is_some_and(|e| e.holes.binary_search(&(f as u32)).is_ok())
    }

    /// The net without its hole faces (for output: holes are refined for support, not
    /// written). Vertices are kept (those of holes only are then used by no face); the
    /// face-varying data follows the faces. A net without holes is returned as it is.
    pub fn without_holes(self) -> PolyMesh {
        let Some(ex) = self.extras() else {
            return self;
        };
        if ex.holes.is_empty() {
            return self;
        }
        let holes = ex.holes.clone();
        let mut keep_face = vec![true; self.num_faces()];
        for &f in &holes {
            keep_face[f as usize] = false;
        }
        let mut face_start = vec![0u32];
        let mut corners = Vec::new();
        let mut uv_corners = Vec::new();
        let uv = self.extras().and_then(|e| e.uv.as_ref());
        for f in 0..self.num_faces() {
            if !keep_face[f] {
                continue;
            }
            let h0 = self.face_halfedge(f) as usize;
            let face = self.face(f);
            corners.extend_from_slice(face);
            if let Some(uv) = uv {
                uv_corners.extend_from_slice(&uv.corners[h0..h0 + face.len()]);
            }
            face_start.push(corners.len() as u32);
        }
        let mut ex = self.extras().cloned().unwrap_or_default();
        ex.holes.clear();
        ex.sharp_edges = SharpEdges::ById(Vec::new());
        if let Some(uv) = &mut ex.uv {
            uv.corners = uv_corners;
        }
        // Connectivity on first use: output needs none.
        let mut m = PolyMesh::from_trusted_parts(self.positions, face_start, corners, None);
        m.set_extras(Some(ex));
        m
    }
}

/// Sorts `(key, value)` pairs by key keeping the last value given for a key, and drops zero
/// values (a later tag overrides an earlier one, as OpenSubdiv's factory assigns them in order).
fn last_per_key(mut v: Vec<(u32, f32)>) -> Vec<(u32, f32)> {
    // Stable sort: for equal keys the input order remains; keep the last of each run.
    v.sort_by_key(|p| p.0);
    let mut out: Vec<(u32, f32)> = Vec::with_capacity(v.len());
    for p in v {
        match out.last_mut() {
            Some(last) if last.0 == p.0 => *last = p,
            _ => out.push(p),
        }
    }
    out.retain(|p| p.1 > 0.0);
    out
}
