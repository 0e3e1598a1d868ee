//! Checked flat polygon arrays, the common input of the mesh writers: a [`PolyMesh`]'s faces
//! or a tessellation that was never built into one.
//!
//! [`PolyMesh`]: crate::mesh::PolyMesh

use crate::error::{Error, Result};
use crate::geom::Point;

/// Checked flat polygon arrays, the common input of the mesh writers.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Polygons<'a> {
    pub positions: &'a [Point],
    /// `num_faces + 1` offsets (or empty for no faces, or when `uniform != 0`).
    pub face_start: &'a [u32],
    pub corners: &'a [u32],
    /// The common face size when the offsets are implicit, else 0.
    pub uniform: usize,
    /// Largest face size.
    pub max_face: usize,
}

impl<'a> Polygons<'a> {
    /// Faces of `size` corners each (implicit offsets), from a mesh whose connectivity is
    /// valid by construction; only the coordinates are checked.
    pub fn uniform(positions: &'a [Point], size: usize, corners: &'a [u32]) -> Result<Self> {
        Self::check_finite(positions)?;
        debug_assert!(size >= 3 && corners.len().is_multiple_of(size));
        Ok(Polygons {
            positions,
            face_start: &[],
            corners,
            uniform: size,
            max_face: size,
        })
    }

    /// Fails when a coordinate is not finite, naming the first such vertex.
    fn check_finite(positions: &[Point]) -> Result<()> {
        // Checked in parallel: a refined net has millions of points.
        match first_index(positions.len(), |v| {
            !positions[v].iter().all(|c| c.is_finite())
        }) {
            Some(v) => Err(Error::InvalidOutput(format!(
                "cannot write vertex {v}: its coordinates {:?} are not all finite (the \
                 computation overflowed: the input's coordinates are too large; scale them down)",
                positions[v]
            ))),
            None => Ok(()),
        }
    }

    /// Checks offsets, indices and coordinates; errors name the face or vertex.
    pub fn new(
        positions: &'a [Point],
        face_start: &'a [u32],
        corners: &'a [u32],
    ) -> Result<Polygons<'a>> {
        use rayon::prelude::*;
        Self::check_finite(positions)?;
        let mut max_face = 0;
        if !face_start.is_empty() {
            if face_start[0] != 0 {
                return Err(Error::InvalidArgument(format!(
                    "face offsets must start at 0, not {}",
                    face_start[0]
                )));
            }
            let last = face_start[face_start.len() - 1] as usize;
            if last != corners.len() {
                return Err(Error::InvalidArgument(format!(
                    "face offsets end at {last} but there are {} corners",
                    corners.len()
                )));
            }
            let nf = face_start.len() - 1;
            if let Some(f) = first_index(nf, |f| {
                face_start[f + 1] < face_start[f] || face_start[f + 1] - face_start[f] < 3
            }) {
                let pair = &face_start[f..f + 2];
                if pair[1] < pair[0] {
                    return Err(Error::InvalidArgument(format!(
                        "face offsets decrease at face {f} ({} then {})",
                        pair[0], pair[1]
                    )));
                }
                let n = pair[1] - pair[0];
                return Err(Error::InvalidArgument(format!(
                    "face {f} has {n} corners; a face needs at least 3"
                )));
            }
            max_face = (0..nf)
                .into_par_iter()
                .with_min_len(CHECK_CHUNK)
                .map(|f| (face_start[f + 1] - face_start[f]) as usize)
                .max()
                .unwrap_or(0);
        } else if !corners.is_empty() {
            return Err(Error::InvalidArgument(
                "corners given without face offsets".to_string(),
            ));
        }
        if let Some(c) = first_index(corners.len(), |c| corners[c] as usize >= positions.len()) {
            let f = face_start.partition_point(|&s| s as usize <= c) - 1;
            return Err(Error::InvalidArgument(format!(
                "face {f} refers to vertex {}, but there are only {} vertices",
                corners[c],
                positions.len()
            )));
        }
        Ok(Polygons {
            positions,
            face_start,
            corners,
            uniform: 0,
            max_face,
        })
    }

    /// Number of faces.
    pub fn num_faces(&self) -> usize {
        self.corners
            .len()
            .checked_div(self.uniform)
            .unwrap_or_else(|| self.face_start.len().saturating_sub(1))
    }

    /// Offset of face `f`'s first corner (`f = num_faces` gives the end).
    pub fn face_offset(&self, f: usize) -> usize {
        if self.uniform != 0 {
            self.uniform * f
        } else {
            self.face_start[f] as usize
        }
    }

    /// Corners of face `f`.
    pub fn face(&self, f: usize) -> &'a [u32] {
        &self.corners[self.face_offset(f)..self.face_offset(f + 1)]
    }

    /// The faces in order.
    pub fn faces(&self) -> impl Iterator<Item = &'a [u32]> + '_ {
        (0..self.num_faces()).map(|f| self.face(f))
    }
}

/// Indices per parallel task in [`first_index`].
const CHECK_CHUNK: usize = 1 << 16;

/// The first index in `0..n` for which `bad` holds: blocks of indices are scanned in parallel,
/// each sequentially (rayon's per-item `position_first` is far slower on tens of millions).
fn first_index(n: usize, bad: impl Fn(usize) -> bool + Sync) -> Option<usize> {
    use rayon::prelude::*;
    (0..n.div_ceil(CHECK_CHUNK))
        .into_par_iter()
        .find_map_first(|c| (c * CHECK_CHUNK..((c + 1) * CHECK_CHUNK).min(n)).find(|&i| bad(i)))
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    #[crate::unit::test]
    fn bad_arrays_are_named() {
        let pos = [[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let msg =
            |p: &[Point], fs: &[u32], c: &[u32]| Polygons::new(p, fs, c).unwrap_err().to_string();
        assert!(msg(&pos, &[0, 3], &[0, 1, 7]).contains("face 0 refers to vertex 7"));
        assert!(msg(&pos, &[0, 2], &[0, 1]).contains("face 0 has 2 corners"));
        let bad = [[0.0; 3], [f64::NAN, 0.0, 0.0], [0.0, 1.0, 0.0]];
        assert!(msg(&bad, &[0, 3], &[0, 1, 2]).contains("cannot write vertex 1"));
        assert!(msg(&pos, &[0, 3], &[0, 1]).contains("3 but there are 2 corners"));
        assert!(msg(&pos, &[1, 3], &[0, 1, 2]).contains("must start at 0, not 1"));
        assert!(msg(&pos, &[], &[0, 1, 2]).contains("without face offsets"));
        let p = Polygons::new(&pos, &[0, 3], &[0, 1, 2]).unwrap();
        assert_eq!(p.faces().collect::<Vec<_>>(), [&[0, 1, 2]]);
    }
}
