//! Areas per input face when the input faces are fan triangles of the polygons the patches'
//! domains refer to (`nonbox-4dir` read on a quasi-four-directional triangle mesh, whose
//! triangles `(V_i, V_(i+1), FCV)` fan the polygons of the net with FCVs the complex is built
//! on: [`FanTriangle`]).
//!
//! Every part of a patch ([`super::parts`]) lies in one cell of a polygon (of a quad sub-face
//! of an n-gon). The fan triangles' sides are lines the cells follow: on a quad the polygon's
//! two diagonals, on an n-gon the diagonals of its sub-faces from the corner to the centre
//! (and the sub-faces' sides). A dyadic cell such a line meets, it crosses along one of the
//! cell's own diagonals. So a part is either held by one fan triangle (the four S_3^1
//! triangles of a criss-cross cell, cells off the lines), or it is a whole quad patch over a
//! cell that a line halves (the G^1 cap sector or the Coons fill at a vertex): the patch maps
//! its square's corners to the cell's, so the line is the square's diagonal `u = v` or
//! `u + v = 1`. Such a patch is split there, each half integrated as the lower triangle of the
//! patch read through a symmetry of the square ([`View`]). A part is held by a triangle when
//! the corners of its image in the cell are (the image is a convex polygon: the maps are
//! affine; a criss-cross triangle's image is the cell triangle itself).

use super::{FaceAreas, Part, View, parts, sum_parts};
use crate::analysis::moments::Region;
use crate::bezier::domain::{Domain, FanTriangle};
use crate::error::{Error, Result};
use crate::surface::PatchComplex;
use std::collections::HashMap;

/// Slack of the containment tests, in cell coordinates (the cell maps are dyadic, so exact;
/// this only absorbs the rounding of a composed map).
const EPS: f64 = 1e-9;

/// The fan triangles of each host polygon: (input face, its triangle).
type ByHost = HashMap<u32, Vec<(u32, FanTriangle)>>;

/// The area over each input face `fans[t]` of the surface `c`, whose patches' domains refer
/// to the fan triangles' host polygons (integrated as in [`super::super::measure`], to
/// relative tolerance `tol`).
///
/// # Errors
/// A patch over a host polygon that no fan triangle has, or one that lies across two fan
/// triangles other than along a diagonal of its parameter square (neither occurs in the
/// complexes of `nonbox-4dir`).
pub fn fan_face_areas(c: &PatchComplex, fans: &[FanTriangle], tol: f64) -> Result<FaceAreas> {
    let mut by_host = ByHost::new();
    for (t, f) in fans.iter().enumerate() {
        by_host.entry(f.host).or_default().push((t as u32, *f));
    }
    let mut split = Vec::new();
    for p in parts(c) {
        split.extend(over_fans(p, &by_host)?);
    }
    Ok(sum_parts(c, &split, fans.len(), tol))
}

/// The corners of `region` in the parameters it is given in.
fn corners(region: Region) -> Vec<[f64; 2]> {
    match region {
        Region::Rect(lo, hi) => vec![lo, [hi[0], lo[1]], hi, [lo[0], hi[1]]],
        Region::Lower(lo, s) => vec![lo, [lo[0] + s, lo[1]], [lo[0] + s, lo[1] + s]],
    }
}

/// `p` given to the fan triangle that holds it, or its two halves to theirs (see the
/// [module](self) documentation); a part over no polygon stays over no face.
fn over_fans(p: Part, by_host: &ByHost) -> Result<Vec<Part>> {
    let (Some(host), Some((d, to_domain))) = (p.face, p.cell) else {
        return Ok(vec![Part { face: None, ..p }]);
    };
    if !d.is_tracked() {
        return Ok(vec![Part { face: None, ..p }]);
    }
    let tris = by_host.get(&host).ok_or_else(|| {
        Error::InvalidArgument(format!(
            "per-face areas: patch {} lies over polygon {host} of the net with FCVs, which \
             no input triangle fans",
            p.patch
        ))
    })?;
    let held_by = |pts: &[[f64; 2]]| -> Option<u32> {
        if d.sub == Domain::WHOLE {
            return None;
        }
        tris.iter()
            .find(|(_, f)| pts.iter().all(|&q| f.holds(d.sub, q, EPS)))
            .map(|&(t, _)| t)
    };
    if let Some(k) = d.criss_cross_triangle() {
        // the cell's triangle k: corner k, corner k + 1, the centre
        let quad = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        let k = usize::from(k);
        let cell = d.cell_map();
        let pts = [quad[k], quad[(k + 1) % 4], [0.5, 0.5]].map(|q| cell.apply(q));
        if let Some(t) = held_by(&pts) {
            return Ok(vec![Part { face: Some(t), ..p }]);
        }
    } else {
        let to_face = d.patch_map().compose(&to_domain);
        let image = |view: View, region: Region| -> Vec<[f64; 2]> {
            corners(region)
                .into_iter()
                .map(|q| to_face.apply(view.stored(q)))
                .collect()
        };
        if let Some(t) = held_by(&image(p.view, p.region)) {
            return Ok(vec![Part { face: Some(t), ..p }]);
        }
        let whole = matches!(p.region, Region::Rect(lo, hi) if lo == [0.0; 2] && hi == [1.0; 2]);
        if whole && p.view == View::Plain {
            let lower = Region::Lower([0.0, 0.0], 1.0);
            for halves in [
                [View::Plain, View::Transposed],
                [View::ReversedU, View::ReversedUTransposed],
            ] {
                let [a, b] = halves.map(|v| held_by(&image(v, lower)));
                if let (Some(a), Some(b)) = (a, b) {
                    return Ok([(halves[0], a), (halves[1], b)]
                        .map(|(view, t)| Part {
                            view,
                            region: lower,
                            face: Some(t),
                            ..p
                        })
                        .to_vec());
                }
            }
        }
    }
    Err(Error::InvalidArgument(format!(
        "per-face areas: patch {} lies across the fan triangles of polygon {host} of the net \
         with FCVs other than along a diagonal of its parameter square; its area cannot be \
         given to input triangles",
        p.patch
    )))
}
