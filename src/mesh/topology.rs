//! Building half-edge connectivity: twins, edge numbering, manifoldness and orientation
//! checks.

use super::{CHUNK, FaceIndex, NONE, Topology};
use crate::error::MeshError;
use rayon::prelude::*;

impl Topology {
    /// Builds half-edge connectivity and checks manifoldness and orientation (the first problem
    /// in half-edge order, then in vertex order, is reported). `uniform` is the common face size
    /// or 0 (then `face_start` may be empty). Runs in parallel over blocks of half-edges and
    /// vertices.
    pub(super) fn build(
        nv: usize,
        face_start: &[u32],
        corners: &[u32],
        uniform: u32,
        relaxed: bool,
    ) -> std::result::Result<Topology, MeshError> {
        let he_face = super::csr::halfedge_faces(face_start, corners.len(), uniform);
        let faces = FaceIndex::new(face_start, &he_face, uniform);
        let out = Outgoing::new(faces, corners, nv);
        let twin = match_twins(&out)?;
        let (he_edge, edge_he) = number_edges(&twin);
        let vert_he = vertex_halfedges(&out, &twin, relaxed)?;
        Ok(Topology {
            he_face,
            twin,
            he_edge,
            edge_he,
            vert_he,
            nm: None,
        })
    }

    /// The topology of a manifold net whose faces all have one size (no face table), from its
    /// arrays: what the uniform splits derive for their children.
    pub(super) fn of_uniform_manifold(
        twin: Vec<u32>,
        he_edge: Vec<u32>,
        edge_he: Vec<u32>,
        vert_he: Vec<u32>,
    ) -> Topology {
        Topology {
            he_face: Vec::new(),
            twin,
            he_edge,
            edge_he,
            vert_he,
            nm: None,
        }
    }
}

/// Outgoing half-edges bucketed per vertex (CSR), in half-edge order; a large bucket is sorted
/// by (end vertex, half-edge), so the half-edges a -> b are one run found by binary search and
/// matching twins costs O(log valence) also around a vertex of high valence.
struct Outgoing<'a> {
    faces: FaceIndex<'a>,
    corners: &'a [u32],
    out_start: Vec<u32>,
    out_he: Vec<u32>,
}

impl<'a> Outgoing<'a> {
    /// The buckets of the faces' half-edges over `nv` vertices, the large ones sorted.
    fn new(faces: FaceIndex<'a>, corners: &'a [u32], nv: usize) -> Outgoing<'a> {
        let (out_start, mut out_he) = super::csr::buckets(corners, nv);
        sort_buckets(&mut out_he, &out_start, |h: u32| {
            corners[faces.next(h) as usize]
        });
        Outgoing {
            faces,
            corners,
            out_start,
            out_he,
        }
    }

    /// The end vertex of half-edge `h`.
    #[inline]
    fn to(&self, h: u32) -> u32 {
        self.corners[self.faces.next(h) as usize]
    }

    /// The outgoing half-edges of vertex `v`.
    #[inline]
    fn outs(&self, v: u32) -> &[u32] {
        &self.out_he[self.out_start[v as usize] as usize..self.out_start[v as usize + 1] as usize]
    }

    /// The half-edges a -> b, in increasing half-edge order: a scan of a small bucket, a
    /// binary search of a sorted large one.
    #[inline]
    fn run(&self, a: u32, b: u32) -> impl Iterator<Item = u32> + Clone + '_ {
        let s = self.outs(a);
        let s = if s.len() > SMALL_BUCKET {
            let lo = s.partition_point(|&g| self.to(g) < b);
            &s[lo..lo + s[lo..].partition_point(|&g| self.to(g) == b)]
        } else {
            s
        };
        s.iter().copied().filter(move |&g| self.to(g) == b)
    }
}

/// The twin of every half-edge (the first opposite one, [`NONE`] on the boundary), or the
/// first edge in half-edge order that is non-manifold or used twice in one direction.
fn match_twins(out: &Outgoing<'_>) -> std::result::Result<Vec<u32>, MeshError> {
    let (corners, faces) = (out.corners, out.faces);
    let mut twin = vec![NONE; corners.len()];
    let bad_edge = twin
        .par_chunks_mut(CHUNK)
        .enumerate()
        .filter_map(|(c, chunk)| {
            for (k, slot) in chunk.iter_mut().enumerate() {
                let h = (c * CHUNK + k) as u32;
                let (a, b) = (corners[h as usize], out.to(h));
                // Same-direction duplicates: orientation conflict or a non-manifold edge.
                let (same, opp) = (out.run(a, b), out.run(b, a));
                let n_same = same.clone().count();
                let mut n_opp = 0;
                for g in opp.clone() {
                    if n_opp == 0 {
                        *slot = g;
                    }
                    n_opp += 1;
                }
                if n_same + n_opp > 2 {
                    let mut faces: Vec<usize> =
                        same.chain(opp).map(|g| faces.face(g) as usize).collect();
                    faces.sort_unstable();
                    let edge = [a.min(b) as usize, a.max(b) as usize];
                    return Some((h, MeshError::NonManifoldEdge { edge, faces }));
                }
                if n_same == 2 {
                    let mut faces: Vec<usize> = same.map(|g| faces.face(g) as usize).collect();
                    faces.sort_unstable();
                    let e = MeshError::InconsistentOrientation {
                        edge: [a as usize, b as usize],
                        faces: [faces[0], faces[1]],
                    };
                    return Some((h, e));
                }
            }
            None
        })
        .min_by_key(|(h, _)| *h);
    match bad_edge {
        Some((_, e)) => Err(e),
        None => Ok(twin),
    }
}

/// Vertex half-edges: the boundary outgoing half-edge, else the first; unless `relaxed`, the
/// first vertex (in vertex order) whose faces are not one fan is refused.
fn vertex_halfedges(
    out: &Outgoing<'_>,
    twin: &[u32],
    relaxed: bool,
) -> std::result::Result<Vec<u32>, MeshError> {
    let mut vert_he = vec![NONE; out.out_start.len() - 1];
    let bad_vertex = vert_he
        .par_chunks_mut(CHUNK)
        .enumerate()
        .filter_map(|(c, chunk)| {
            for (k, slot) in chunk.iter_mut().enumerate() {
                let v = c * CHUNK + k;
                let outs = out.outs(v as u32);
                let Some(&first) = outs.iter().min() else {
                    continue; // unreferenced vertex (only in refinement output; never queried)
                };
                // The start is the boundary half-edge (the last in half-edge order if
                // several), else the first half-edge: independent of the bucket order.
                let mut start = first;
                let mut boundary_starts = 0;
                let mut last_boundary = None;
                for &h in outs {
                    if twin[h as usize] == NONE {
                        boundary_starts += 1;
                        last_boundary = last_boundary.max(Some(h));
                    }
                }
                if let Some(h) = last_boundary {
                    start = h;
                }
                let count = fan_len(twin, out.faces, start, outs.len());
                if !relaxed && (count != outs.len() || boundary_starts > 1) {
                    let fans = boundary_starts.max(2);
                    return Some((v, MeshError::NonManifoldVertex { vertex: v, fans }));
                }
                *slot = start;
            }
            None
        })
        .min_by_key(|(v, _)| *v);
    match bad_vertex {
        Some((_, e)) => Err(e),
        None => Ok(vert_he),
    }
}

/// The number of faces reached by counter-clockwise rotation from the outgoing half-edge
/// `start` (stopping at a boundary or back at `start`), at most `limit + 1`: a vertex with
/// `limit` outgoing half-edges is one fan when it reaches them all.
pub(super) fn fan_len(twin: &[u32], faces: FaceIndex<'_>, start: u32, limit: usize) -> usize {
    let mut count = 1;
    let mut h = start;
    loop {
        let t = twin[faces.prev(h) as usize];
        if t == NONE || t == start {
            break;
        }
        h = t;
        count += 1;
        if count > limit {
            break;
        }
    }
    count
}

/// Buckets of at most this many outgoing half-edges stay in half-edge order and are scanned;
/// larger ones (vertices of high valence) are sorted and searched.
const SMALL_BUCKET: usize = 16;

/// Sorts each vertex's bucket of outgoing half-edges (`out_he[out_start[v]..out_start[v + 1]]`)
/// with more than [`SMALL_BUCKET`] entries by (end vertex, half-edge), in parallel over blocks
/// of vertices.
fn sort_buckets(out_he: &mut [u32], out_start: &[u32], to: impl Fn(u32) -> u32 + Sync) {
    let nv = out_start.len() - 1;
    let mut parts = Vec::with_capacity(nv.div_ceil(CHUNK));
    let mut rest = out_he;
    for c in 0..nv.div_ceil(CHUNK) {
        let vs = c * CHUNK..((c + 1) * CHUNK).min(nv);
        let len = (out_start[vs.end] - out_start[vs.start]) as usize;
        let (part, tail) = rest.split_at_mut(len);
        parts.push((vs, part));
        rest = tail;
    }
    parts.into_par_iter().for_each(|(vs, part)| {
        let base = out_start[vs.start];
        for v in vs {
            let bucket = (out_start[v] - base) as usize..(out_start[v + 1] - base) as usize;
            if bucket.len() > SMALL_BUCKET {
                part[bucket].sort_unstable_by_key(|&h| (to(h), h));
            }
        }
    });
}

/// Numbers the edges of a half-edge mesh from its twins, in the order of their first half-edge
/// (`h` with no twin or `h < twin[h]`): returns `(he_edge, edge_he)`. Runs in parallel (a count,
/// a scan and two fill passes).
pub(crate) fn number_edges(twin: &[u32]) -> (Vec<u32>, Vec<u32>) {
    use std::sync::atomic::{AtomicU32, Ordering::Relaxed};
    let nh = twin.len();
    let first = |h: usize| {
        let t = twin[h];
        t == NONE || (h as u32) < t
    };
    let blocks = nh.div_ceil(CHUNK);
    let block = |c: usize| c * CHUNK..((c + 1) * CHUNK).min(nh);
    let counts: Vec<usize> = (0..blocks)
        .into_par_iter()
        .map(|c| block(c).filter(|&h| first(h)).count())
        .collect();
    let ne: usize = counts.iter().sum();
    let he_edge: Vec<AtomicU32> = (0..nh)
        .into_par_iter()
        .map(|_| AtomicU32::new(NONE))
        .collect();
    let mut edge_he = vec![0u32; ne];
    let mut parts = Vec::with_capacity(blocks);
    let mut rest = &mut edge_he[..];
    let mut base = 0;
    for &n in &counts {
        let (part, tail) = rest.split_at_mut(n);
        parts.push((base, part));
        base += n;
        rest = tail;
    }
    parts
        .into_par_iter()
        .enumerate()
        .for_each(|(c, (base, part))| {
            let mut k = 0;
            for h in block(c) {
                if first(h) {
                    he_edge[h].store((base + k) as u32, Relaxed);
                    part[k] = h as u32;
                    k += 1;
                }
            }
        });
    (0..blocks).into_par_iter().for_each(|c| {
        for h in block(c) {
            if !first(h) {
                he_edge[h].store(he_edge[twin[h] as usize].load(Relaxed), Relaxed);
            }
        }
    });
    let he_edge = he_edge.into_iter().map(AtomicU32::into_inner).collect();
    (he_edge, edge_he)
}
