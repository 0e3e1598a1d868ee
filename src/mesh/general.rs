//! Half-edge connectivity that tolerates everything OpenSubdiv accepts: edges shared by more
//! than two faces, edges used twice in one direction (opposite orientations), vertices where
//! several fans of faces meet, faces that repeat a vertex (even consecutively: a degenerate
//! edge), and vertices no face uses.
//!
//! Catmull-Clark and Loop refine such nets as OpenSubdiv does (their non-manifold features are
//! infinitely sharp, see `schemes::sdc::crease`), so they need one representation for
//! them. It is the ordinary [`Topology`] with two relaxations:
//!
//! - edges are identified as OpenSubdiv's `Vtr::Level` identifies them, not by twins: a face
//!   side `a -> b` joins the first edge created between `a` and `b` unless that edge already
//!   belongs to the same face (then the side is an edge of its own, as both sides of a spike in
//!   `f a b a c` are), and a side `a -> a` is always an edge of its own. So `he_edge` maps every
//!   side of an edge with three faces to the same edge, while `twin` pairs only the two sides of
//!   a manifold interior edge;
//! - the non-manifold edges and vertices are flagged in a [`NonManifold`] side table, with what
//!   their rules need (the incident edges and faces of a non-manifold vertex, the sides of a
//!   non-manifold edge), since rotation by twins does not reach them. Manifold vertices keep
//!   the ordinary walks (`vert_he` is their boundary half-edge or their smallest outgoing one).
//!
//! A net that is manifold everywhere gets exactly the topology of the strict build (same
//! twins, edge numbering and vertex half-edges) and no side table.

use super::{FaceIndex, NONE, Topology};
use std::collections::HashMap;

/// The non-manifold part of a [`Topology`] (see the module documentation).
#[derive(Debug, Clone, Default)]
pub(crate) struct NonManifold {
    /// Whether each edge is non-manifold (degenerate, used twice by one face, used by more than
    /// two faces or twice in one direction; refinement passes the flag to the child edges).
    pub edge: Vec<bool>,
    /// Whether each vertex is non-manifold (incident to a non-manifold edge, joining several
    /// fans, used by no face; refinement passes the flag to the child vertex).
    pub vertex: Vec<bool>,
    /// The non-manifold vertices in increasing order; entry `k` of the tables below.
    pub vertices: Vec<u32>,
    /// Offsets of vertex `vertices[k]`'s entries in `vert_edges` (`vertices.len() + 1`).
    pub vert_edge_start: Vec<u32>,
    /// Incident edges of the non-manifold vertices with the vertex's end (0: the edge's first
    /// end, that of its first half-edge; 1: the other): a degenerate edge appears twice.
    pub vert_edges: Vec<(u32, u8)>,
    /// Offsets of vertex `vertices[k]`'s outgoing half-edges in `vert_out`.
    pub vert_out_start: Vec<u32>,
    /// Outgoing half-edges (face corners) of the non-manifold vertices, in increasing order.
    pub vert_out: Vec<u32>,
    /// The non-manifold edges in increasing order; entry `k` of `edge_sides_start`.
    pub edges: Vec<u32>,
    /// Offsets of edge `edges[k]`'s half-edges in `edge_sides`.
    pub edge_sides_start: Vec<u32>,
    /// The half-edges (face sides) of the non-manifold edges, in increasing order.
    pub edge_sides: Vec<u32>,
}

impl NonManifold {
    /// Entry of non-manifold vertex `v` in the tables.
    #[inline]
    fn vertex_entry(&self, v: u32) -> usize {
        self.vertices
            .binary_search(&v)
            .expect("a non-manifold vertex is listed")
    }

    /// Incident edges of non-manifold vertex `v`, with `v`'s end in each.
    pub fn vertex_edges(&self, v: u32) -> &[(u32, u8)] {
        let k = self.vertex_entry(v);
        &self.vert_edges[self.vert_edge_start[k] as usize..self.vert_edge_start[k + 1] as usize]
    }

    /// Outgoing half-edges (one per face corner at `v`) of non-manifold vertex `v`.
    pub fn vertex_out(&self, v: u32) -> &[u32] {
        let k = self.vertex_entry(v);
        &self.vert_out[self.vert_out_start[k] as usize..self.vert_out_start[k + 1] as usize]
    }

    /// The half-edges of non-manifold edge `e`.
    pub fn edge_sides(&self, e: u32) -> &[u32] {
        let k = self
            .edges
            .binary_search(&e)
            .expect("a non-manifold edge is listed");
        &self.edge_sides[self.edge_sides_start[k] as usize..self.edge_sides_start[k + 1] as usize]
    }
}

/// Edge identities of a base net as OpenSubdiv's `Vtr::Level` finds them (see the module
/// documentation): one raw edge id per half-edge, in order of creation (so the ids already
/// count in order of first occurrence), their number, and which of them are non-manifold by
/// construction (degenerate, twice in one face, more than two faces, twice in one direction).
pub(crate) fn osd_edges(faces: FaceIndex<'_>, corners: &[u32]) -> (Vec<u32>, usize, Vec<bool>) {
    let nh = corners.len();
    let mut he_edge = vec![NONE; nh];
    // First edge created per unordered vertex pair.
    let mut first: HashMap<(u32, u32), u32> = HashMap::with_capacity(nh);
    // Per edge: its first end, its last face, its number of faces.
    let mut v0: Vec<u32> = Vec::with_capacity(nh);
    let mut last_face: Vec<u32> = Vec::with_capacity(nh);
    let mut count: Vec<u32> = Vec::with_capacity(nh);
    let mut nm: Vec<bool> = Vec::with_capacity(nh);
    for h in 0..nh as u32 {
        let (a, b) = (corners[h as usize], corners[faces.next(h) as usize]);
        let f = faces.face(h);
        let mut found = if a == b {
            None
        } else {
            first.get(&(a.min(b), a.max(b))).copied()
        };
        if let Some(e) = found {
            let e = e as usize;
            if last_face[e] == f {
                // The edge already occurs in this face: this side is an edge of its own.
                nm[e] = true;
                found = None;
            } else if count[e] > 1 || v0[e] == a {
                nm[e] = true;
            }
        }
        let e = match found {
            Some(e) => e,
            None => {
                let e = v0.len() as u32;
                v0.push(a);
                last_face.push(NONE);
                count.push(0);
                // Degenerate edges and second instances are non-manifold.
                nm.push(a == b || first.contains_key(&(a.min(b), a.max(b))));
                if a != b {
                    first.entry((a.min(b), a.max(b))).or_insert(e);
                }
                e
            }
        };
        last_face[e as usize] = f;
        count[e as usize] += 1;
        he_edge[h as usize] = e;
    }
    let ne = v0.len();
    (he_edge, ne, nm)
}

impl Topology {
    /// The topology of a net whose edges are given: `raw_edge[h]` names the edge of half-edge
    /// `h` (any ids below `raw_count`; they are renumbered in order of first occurrence),
    /// `raw_nm[e]` flags raw edges that are non-manifold whatever their sides (inherited from a
    /// parent level, or found by [`osd_edges`]), `nm_vertex` (empty or one flag per vertex)
    /// vertices that are non-manifold by inheritance. Twins pair the two opposite sides of every
    /// other edge with exactly two sides; everything else non-manifold is found here. Nothing is
    /// refused: this is the tolerant build (see the module documentation).
    pub(crate) fn build_general(
        nv: usize,
        faces: FaceIndex<'_>,
        corners: &[u32],
        raw_edge: &[u32],
        raw_count: usize,
        raw_nm: &[bool],
        nm_vertex: &[bool],
    ) -> Topology {
        let mut edges = Edges::renumber(raw_edge, raw_count, raw_nm);
        let twin = edges.pair_twins(faces, corners);
        // Outgoing half-edges per vertex (CSR, in increasing order).
        let outs = Buckets::of(corners, nv);
        let (vertex_nm, vert_he) =
            vertex_halfedges(faces, corners, &edges, &twin, &outs, nm_vertex);
        let any_nm = vertex_nm.iter().any(|&b| b) || edges.nm.iter().any(|&b| b);
        let nm = any_nm.then(|| side_table(faces, corners, &edges, &vertex_nm, &outs));
        let he_face = if faces.uniform == 0 {
            faces.he_face.to_vec()
        } else {
            Vec::new()
        };
        Topology {
            he_face,
            twin,
            he_edge: edges.he_edge,
            edge_he: edges.edge_he,
            vert_he,
            nm,
        }
    }
}

/// Items bucketed by key (CSR): bucket `k` is `items[start[k]..start[k + 1]]`.
struct Buckets {
    start: Vec<u32>,
    items: Vec<u32>,
}

impl Buckets {
    /// The indices `i` of `keys` bucketed by `keys[i] < n`, each bucket in increasing order.
    fn of(keys: &[u32], n: usize) -> Buckets {
        let (start, items) = super::csr::buckets(keys, n);
        Buckets { start, items }
    }

    /// Bucket `k`.
    #[inline]
    fn get(&self, k: usize) -> &[u32] {
        &self.items[self.start[k] as usize..self.start[k + 1] as usize]
    }
}

/// The edges of the tolerant build, numbered by first occurrence.
struct Edges {
    /// Edge of each half-edge.
    he_edge: Vec<u32>,
    /// First half-edge of each edge.
    edge_he: Vec<u32>,
    /// Whether each edge is non-manifold (inherited, then as found).
    nm: Vec<bool>,
    /// The sides (half-edges) of each edge, in half-edge order.
    sides: Buckets,
}

impl Edges {
    /// Renumbers the raw edge ids of the half-edges by first occurrence, keeping their
    /// inherited non-manifold flags.
    fn renumber(raw_edge: &[u32], raw_count: usize, raw_nm: &[bool]) -> Edges {
        let nh = raw_edge.len();
        let mut new_id = vec![NONE; raw_count];
        let mut he_edge = vec![0u32; nh];
        let mut edge_he: Vec<u32> = Vec::new();
        let mut nm: Vec<bool> = Vec::new();
        for h in 0..nh {
            let r = raw_edge[h] as usize;
            if new_id[r] == NONE {
                new_id[r] = edge_he.len() as u32;
                edge_he.push(h as u32);
                nm.push(raw_nm.get(r).copied().unwrap_or(false));
            }
            he_edge[h] = new_id[r];
        }
        drop(new_id);
        let sides = Buckets::of(&he_edge, edge_he.len());
        Edges {
            he_edge,
            edge_he,
            nm,
            sides,
        }
    }

    /// Twins for the edges with exactly two opposite sides in different faces (not flagged
    /// before); every other edge with more than one side is flagged non-manifold.
    fn pair_twins(&mut self, faces: FaceIndex<'_>, corners: &[u32]) -> Vec<u32> {
        let to = |h: u32| corners[faces.next(h) as usize];
        let mut twin = vec![NONE; corners.len()];
        for e in 0..self.edge_he.len() {
            match *self.sides.get(e) {
                [h1, h2] if !self.nm[e] => {
                    let opposite = corners[h1 as usize] == to(h2) && to(h1) == corners[h2 as usize];
                    if opposite && faces.face(h1) != faces.face(h2) {
                        twin[h1 as usize] = h2;
                        twin[h2 as usize] = h1;
                    } else {
                        self.nm[e] = true;
                    }
                }
                [_] => {}
                _ => self.nm[e] = true,
            }
        }
        twin
    }
}

/// Which vertices are non-manifold (inherited in `nm_vertex`, unused, on a non-manifold edge,
/// or joining several fans) and each vertex's half-edge: the boundary outgoing one of a
/// manifold vertex, else the first outgoing one.
fn vertex_halfedges(
    faces: FaceIndex<'_>,
    corners: &[u32],
    edges: &Edges,
    twin: &[u32],
    outs: &Buckets,
    nm_vertex: &[bool],
) -> (Vec<bool>, Vec<u32>) {
    let nv = outs.start.len() - 1;
    let to = |h: u32| corners[faces.next(h) as usize];
    let mut vertex_nm: Vec<bool> = (0..nv)
        .map(|v| nm_vertex.get(v).copied().unwrap_or(false) || outs.get(v).is_empty())
        .collect();
    for (e, &h) in edges.edge_he.iter().enumerate() {
        if edges.nm[e] {
            vertex_nm[corners[h as usize] as usize] = true;
            vertex_nm[to(h) as usize] = true;
        }
    }
    let mut vert_he = vec![NONE; nv];
    for v in 0..nv {
        let o = outs.get(v);
        let Some(&first) = o.first() else { continue };
        let mut start = first;
        let mut boundary_starts = 0;
        for &h in o {
            if twin[h as usize] == NONE {
                boundary_starts += 1;
                start = h;
            }
        }
        if !vertex_nm[v] {
            // One fan: the rotation from `start` reaches every outgoing half-edge.
            let count = super::topology::fan_len(twin, faces, start, o.len());
            if count != o.len() || boundary_starts > 1 {
                vertex_nm[v] = true;
            }
        }
        vert_he[v] = if vertex_nm[v] { first } else { start };
    }
    (vertex_nm, vert_he)
}

/// The [`NonManifold`] side table: the flags, and the incident edges and outgoing half-edges
/// of every non-manifold vertex and the sides of every non-manifold edge.
fn side_table(
    faces: FaceIndex<'_>,
    corners: &[u32],
    edges: &Edges,
    vertex_nm: &[bool],
    outs: &Buckets,
) -> Box<NonManifold> {
    let end_of = |h: u32, at_from: bool| -> u8 {
        // The end of edge(h) that the start (or the end) of h is.
        let e = edges.he_edge[h as usize] as usize;
        let first = edges.edge_he[e];
        let from_is_0 = h == first || corners[h as usize] == corners[first as usize];
        u8::from(from_is_0 != at_from)
    };
    let mut t = NonManifold {
        edge: edges.nm.clone(),
        vertex: vertex_nm.to_vec(),
        vert_edge_start: vec![0],
        vert_out_start: vec![0],
        edge_sides_start: vec![0],
        ..NonManifold::default()
    };
    for (v, _) in vertex_nm.iter().enumerate().filter(|(_, nm)| **nm) {
        t.vertices.push(v as u32);
        let mut es: Vec<(u32, u8)> = Vec::new();
        for &h in outs.get(v) {
            let p = faces.prev(h);
            for pair in [
                (edges.he_edge[h as usize], end_of(h, true)),
                (edges.he_edge[p as usize], end_of(p, false)),
            ] {
                if !es.contains(&pair) {
                    es.push(pair);
                }
            }
        }
        es.sort_unstable();
        t.vert_edges.extend_from_slice(&es);
        t.vert_edge_start.push(t.vert_edges.len() as u32);
        t.vert_out.extend_from_slice(outs.get(v));
        t.vert_out_start.push(t.vert_out.len() as u32);
    }
    for (e, _) in edges.nm.iter().enumerate().filter(|(_, nm)| **nm) {
        t.edges.push(e as u32);
        t.edge_sides.extend_from_slice(edges.sides.get(e));
        t.edge_sides_start.push(t.edge_sides.len() as u32);
    }
    Box::new(t)
}
