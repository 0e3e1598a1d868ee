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
        let nh = corners.len();
        let to = |h: u32| corners[faces.next(h) as usize];
        // Renumber the edges by first occurrence.
        let mut new_id = vec![NONE; raw_count];
        let mut he_edge = vec![0u32; nh];
        let mut edge_he: Vec<u32> = Vec::new();
        let mut edge_nm: Vec<bool> = Vec::new();
        for h in 0..nh {
            let r = raw_edge[h] as usize;
            if new_id[r] == NONE {
                new_id[r] = edge_he.len() as u32;
                edge_he.push(h as u32);
                edge_nm.push(raw_nm.get(r).copied().unwrap_or(false));
            }
            he_edge[h] = new_id[r];
        }
        drop(new_id);
        let ne = edge_he.len();
        // Sides per edge (CSR, in half-edge order).
        let (side_start, sides) = super::csr::buckets(&he_edge, ne);
        let mut twin = vec![NONE; nh];
        for e in 0..ne {
            let s = &sides[side_start[e] as usize..side_start[e + 1] as usize];
            match *s {
                [h1, h2] if !edge_nm[e] => {
                    let opposite = corners[h1 as usize] == to(h2) && to(h1) == corners[h2 as usize];
                    if opposite && faces.face(h1) != faces.face(h2) {
                        twin[h1 as usize] = h2;
                        twin[h2 as usize] = h1;
                    } else {
                        edge_nm[e] = true;
                    }
                }
                [_] => {}
                _ => edge_nm[e] = true,
            }
        }
        // Outgoing half-edges per vertex (CSR, in increasing order).
        let (out_start, out_he) = super::csr::buckets(corners, nv);
        let outs = |v: usize| &out_he[out_start[v] as usize..out_start[v + 1] as usize];
        let mut vertex_nm: Vec<bool> = (0..nv)
            .map(|v| nm_vertex.get(v).copied().unwrap_or(false) || outs(v).is_empty())
            .collect();
        for e in 0..ne {
            if edge_nm[e] {
                let h = edge_he[e];
                vertex_nm[corners[h as usize] as usize] = true;
                vertex_nm[to(h) as usize] = true;
            }
        }
        let mut vert_he = vec![NONE; nv];
        for v in 0..nv {
            let o = outs(v);
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
                let count = super::topology::fan_len(&twin, faces, start, o.len());
                if count != o.len() || boundary_starts > 1 {
                    vertex_nm[v] = true;
                }
            }
            vert_he[v] = if vertex_nm[v] { first } else { start };
        }
        let any_nm = vertex_nm.iter().any(|&b| b) || edge_nm.iter().any(|&b| b);
        let nm = any_nm.then(|| {
            let end_of = |h: u32, at_from: bool| -> u8 {
                // The end of edge(h) that the start (or the end) of h is.
                let e = he_edge[h as usize] as usize;
                let first = edge_he[e];
                let from_is_0 = h == first || corners[h as usize] == corners[first as usize];
                u8::from(from_is_0 != at_from)
            };
            let mut t = NonManifold {
                edge: edge_nm.clone(),
                vertex: vertex_nm.clone(),
                vert_edge_start: vec![0],
                vert_out_start: vec![0],
                edge_sides_start: vec![0],
                ..NonManifold::default()
            };
            for v in 0..nv {
                if !vertex_nm[v] {
                    continue;
                }
                t.vertices.push(v as u32);
                let mut es: Vec<(u32, u8)> = Vec::new();
                for &h in outs(v) {
                    let p = faces.prev(h);
                    for pair in [
                        (he_edge[h as usize], end_of(h, true)),
                        (he_edge[p as usize], end_of(p, false)),
                    ] {
                        if !es.contains(&pair) {
                            es.push(pair);
                        }
                    }
                }
                es.sort_unstable();
                t.vert_edges.extend_from_slice(&es);
                t.vert_edge_start.push(t.vert_edges.len() as u32);
                t.vert_out.extend_from_slice(outs(v));
                t.vert_out_start.push(t.vert_out.len() as u32);
            }
            for e in 0..ne {
                if edge_nm[e] {
                    t.edges.push(e as u32);
                    t.edge_sides.extend_from_slice(
                        &sides[side_start[e] as usize..side_start[e + 1] as usize],
                    );
                    t.edge_sides_start.push(t.edge_sides.len() as u32);
                }
            }
            Box::new(t)
        });
        let he_face = if faces.uniform == 0 {
            faces.he_face.to_vec()
        } else {
            Vec::new()
        };
        Topology {
            he_face,
            twin,
            he_edge,
            edge_he,
            vert_he,
            nm,
        }
    }
}
