//! Re-applying a patch table into an existing complex (the animation loop's call) and the G^1
//! caps of every re-apply, built in parallel: the one step of an apply that is not a table.

use super::{PatchTable, cap_failed, hole_from};
use crate::bezier::BezierPatch;
use crate::bezier::complex::PatchComplex;
use crate::bezier::g1::ring;
use crate::error::{Error, Result};
use crate::geom::Point;
use rayon::prelude::*;

impl PatchTable {
    /// [`PatchTable::apply`] into `complex`, a complex of this table (the construction's, or
    /// one [`PatchTable::apply`] made), reusing its patches' storage: the animation loop's
    /// call. The patches, caps and cap data equal [`PatchTable::apply`]'s bit for bit. The
    /// factored Catmull-Clark table computes each bi-3 net on the stack and converts it in
    /// place, allocating no patch ([`PatchTable::apply`] allocates every one); the other
    /// tables compute [`PatchTable::apply`]'s values and copy them.
    ///
    /// # Errors
    /// When `points` has the wrong length, `complex` has other patch shapes than the table
    /// (nothing is written then), or a G^1 cap cannot be built for the moved points: the
    /// patches are then partly moved (rebuild the table and the complex).
    pub fn apply_into(&self, points: &[Point], complex: &mut PatchComplex) -> Result<()> {
        let same_shapes = complex.patches.len() == self.num_patches()
            && complex
                .patches
                .iter()
                .zip(&self.shapes)
                .all(|(p, &(du, dv))| {
                    (p.deg_u as u32, p.deg_v as u32) == (du, dv)
                        && p.cps.len() == (p.deg_u + 1) * (p.deg_v + 1)
                });
        if !same_shapes {
            return Err(Error::InvalidArgument(format!(
                "the complex is not this table's: {} patches of other shapes than the table's {}",
                complex.patches.len(),
                self.num_patches()
            )));
        }
        if !self.constants.is_empty() {
            *complex = self.apply(points)?;
            return Ok(());
        }
        self.check_points(points)?;
        let data = self
            .rows
            .values_into(&self.layout(), points, &mut complex.patches);
        self.build_caps(&data, &mut complex.patches)?;
        complex.caps = self.cap_steps(&data);
        if complex.provenance != self.provenance {
            complex.provenance = self.provenance.clone();
        }
        if complex.sharp_sides != self.sharp_sides {
            complex.sharp_sides = self.sharp_sides.clone();
        }
        if complex.domains != self.domains {
            complex.domains = self.domains.clone();
        }
        if complex.pieces != self.pieces {
            complex.pieces = self.pieces.clone();
        }
        Ok(())
    }

    /// Builds every G^1 cap from the caps' data values `data` (in parallel: the one step of
    /// the apply that is not a table) and puts its patches in place; the error of the first
    /// cap by index that cannot be built.
    pub(super) fn build_caps(&self, data: &[Point], patches: &mut [BezierPatch]) -> Result<()> {
        let built: Vec<Result<Vec<BezierPatch>>> = self
            .caps
            .par_iter()
            .enumerate()
            .map(|(k, cap)| {
                let r = self.data_index(cap);
                let (hole, plane) =
                    hole_from(&data[r..r + cap.data_len()], &cap.shape(), &cap.step.hole);
                ring::cap_from_plane(hole, plane, cap.step.options)
                    .map(|b| b.patches)
                    .map_err(|e| cap_failed(k, cap, e))
            })
            .collect();
        for (k, (cap, b)) in self.caps.iter().zip(built).enumerate() {
            self.place_cap(k, cap, b?, patches)?;
        }
        Ok(())
    }
}
