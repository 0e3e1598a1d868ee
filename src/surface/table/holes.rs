//! The G^1 caps of a patch table: each cap's data rows (centre, plane vectors, the hole's
//! segments) and how the hole is read back from them at [`super::PatchTable::apply`].

use crate::bezier::BezierPatch;
use crate::bezier::complex::CapStep;
use crate::bezier::g1::{Centre, Hole, Segment};
use crate::geom::Point;

/// How a cap's hole data are laid out in the table's rows: per sector, per segment, the number
/// of boundary and cross coefficients.
pub type HoleShape = Vec<Vec<(u32, u32)>>;

/// A G^1 cap of the complex as the table repeats it.
#[derive(Debug, Clone, PartialEq)]
pub struct TableCap {
    /// The cap's data as the construction recorded them (tangents unset); the table replaces
    /// every point of it by its row.
    pub step: CapStep,
    /// First of the cap's data rows: centre, the two plane vectors, then per sector and segment
    /// the boundary coefficients followed by the cross coefficients.
    pub data_row: u32,
    /// The cap map the construction chose for this hole (degree and centre condition): the
    /// map [`super::PatchTable::apply_data`] applies.
    pub degree: usize,
    /// See [`TableCap::degree`].
    pub centre: Centre,
}

impl TableCap {
    /// Number of data rows.
    pub fn data_len(&self) -> usize {
        hole_points(&self.step.hole, &self.step.plane).len()
    }

    /// The hole's segment sizes.
    pub fn shape(&self) -> HoleShape {
        self.step
            .hole
            .sectors
            .iter()
            .map(|sec| {
                sec.iter()
                    .map(|s| (s.boundary.len() as u32, s.cross.len() as u32))
                    .collect()
            })
            .collect()
    }
}

/// The points of a cap step in data-row order: centre, plane vectors, segments.
pub(crate) fn hole_points(hole: &Hole, plane: &[Point; 2]) -> Vec<Point> {
    let mut d = vec![hole.centre, plane[0], plane[1]];
    for sec in &hole.sectors {
        for seg in sec {
            d.extend_from_slice(&seg.boundary);
            d.extend_from_slice(&seg.cross);
        }
    }
    d
}

/// A hole of shape `shape` (an open fan when `open`) read from `vals` (centre first, see
/// [`TableCap::data_row`]), and its plane vectors.
pub(super) fn hole_from(vals: &[Point], shape: &HoleShape, like: &Hole) -> (Hole, [Point; 2]) {
    let mut k = 3;
    let mut take = |n: u32| {
        let v = vals[k..k + n as usize].to_vec();
        k += n as usize;
        v
    };
    let sectors = shape
        .iter()
        .map(|sec| {
            sec.iter()
                .map(|&(b, c)| Segment {
                    boundary: take(b),
                    cross: take(c),
                })
                .collect()
        })
        .collect();
    let hole = Hole::untangented_as(vals[0], sectors, like.kind);
    (hole, [vals[1], vals[2]])
}

/// The patches of the sectors `kept` of a cap built whole (a cap the complex keeps in part,
/// [`CapStep::kept`]); `None` when the cap lacks one of them.
pub(super) fn kept_sectors(built: Vec<BezierPatch>, kept: &[u32]) -> Option<Vec<BezierPatch>> {
    let mut all: Vec<Option<BezierPatch>> = built.into_iter().map(Some).collect();
    kept.iter()
        .map(|&s| all.get_mut(s as usize).and_then(Option::take))
        .collect()
}
