//! Bucketing by key in compressed-row form (CSR), the one way the topology builders group
//! half-edges: by start vertex (outgoing half-edges), by edge (the sides of an edge), by face.

/// The indices `0..keys.len()` bucketed by key: `(start, items)`, bucket `k` being
/// `items[start[k]..start[k + 1]]`, each bucket in increasing index order; `n` buckets (every
/// key is below `n`).
pub(super) fn buckets(keys: &[u32], n: usize) -> (Vec<u32>, Vec<u32>) {
    let mut start = vec![0u32; n + 1];
    for &k in keys {
        start[k as usize + 1] += 1;
    }
    for k in 0..n {
        start[k + 1] += start[k];
    }
    let mut fill = start.clone();
    let mut items = vec![0u32; keys.len()];
    for (i, &k) in keys.iter().enumerate() {
        items[fill[k as usize] as usize] = i as u32;
        fill[k as usize] += 1;
    }
    (start, items)
}

/// The face of each of the `nh` half-edges of faces with offsets `face_start`, or nothing when
/// the faces have a common size `uniform` (the face is then `h / uniform`).
pub(super) fn halfedge_faces(face_start: &[u32], nh: usize, uniform: u32) -> Vec<u32> {
    if uniform != 0 {
        return Vec::new();
    }
    let mut he_face = vec![0u32; nh];
    for (f, w) in face_start.windows(2).enumerate() {
        he_face[w[0] as usize..w[1] as usize].fill(f as u32);
    }
    he_face
}
