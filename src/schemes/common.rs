//! Small helpers shared by the scheme modules.
//!
//! Refinement visits every vertex ring and writes one stencil row per child point, so it must not
//! allocate per element: rings are walked with the mesh's one walker
//! ([`PolyMesh::outgoing`](crate::mesh::PolyMesh::outgoing)), and [`RowBuf`] collects one stencil
//! row in a reused buffer, merges duplicate sources and appends it to a [`StencilTable`].

use super::split_child::{bare_child, child_extras, child_mesh, last_child};
use crate::error::{Error, Result};
use crate::geom::Point;
use crate::mesh::PolyMesh;
use crate::mesh::split::UniformSplit;
use crate::mesh::tags::SubdOptions as Opts;
use crate::schemes::sdc::crease::SharpLevel;
use crate::stencil::{Stencil, StencilTable, Terms};

/// `cos(2 pi k / n)`, exact at the multiples of 30 degrees where the value is rational (so that
/// regular weights such as 1/16 or 9/16 come out exactly).
pub(crate) fn cos_2pi(k: i64, n: i64) -> f64 {
    let r = k.rem_euclid(n);
    if (12 * r) % n == 0 {
        match 12 * r / n {
            0 => return 1.0,
            2 | 10 => return 0.5,
            3 | 9 => return 0.0,
            4 | 8 => return -0.5,
            6 => return -1.0,
            _ => {}
        }
    }
    (2.0 * std::f64::consts::PI * r as f64 / n as f64).cos()
}

/// `sin(2 pi k / n)`, exact where [`cos_2pi`] is.
pub(crate) fn sin_2pi(k: i64, n: i64) -> f64 {
    cos_2pi(4 * k - n, 4 * n)
}

/// Fails when a child net would need more points than `u32` indices can name.
pub(crate) fn check_child_size(scheme: &str, points: usize) -> Result<()> {
    if points > u32::MAX as usize {
        return Err(Error::Unsupported(format!(
            "one {scheme} step would create {points} points, more than fairsub's 32-bit indices \
             allow; refine a part of the net or use fewer levels"
        )));
    }
    Ok(())
}

/// The error of a triangle scheme naming the first face of `mesh` that is not a triangle
/// (`needs` says who needs triangles: "Loop subdivision needs", "Loop patches need"), with the
/// way out: triangulate, or use Catmull-Clark.
pub(crate) fn require_triangles(mesh: &PolyMesh, needs: &str) -> Result<()> {
    let hint = format!(
        "; triangulate the net or use {}",
        crate::schemes::options::ids::CATMULL_CLARK
    );
    crate::mesh::tri_split::require_triangles(mesh, needs, &hint)
}

/// A reusable buffer for one stencil row.
#[derive(Debug, Default)]
pub(crate) struct RowBuf {
    pairs: Vec<(u32, f64)>,
}

impl RowBuf {
    /// Adds `w` times source `i`.
    #[inline]
    pub(crate) fn add(&mut self, i: u32, w: f64) {
        self.pairs.push((i, w));
    }

    /// Takes the row out as a [`Stencil`] (duplicates merged, exact zeros dropped) and clears
    /// the buffer: the single-row form of [`RowBuf::flush_into`], for callers that need one
    /// rule at a time (adaptive refinement).
    pub(crate) fn take_stencil(&mut self) -> Stencil {
        Stencil::from_pairs(self.pairs.drain(..).map(|(i, w)| (i as usize, w)))
    }

    /// Sorts the row by source, merges duplicate sources (degenerate nets can name a vertex
    /// twice in one rule), drops exact zeros, appends the row to `table` and clears the buffer.
    pub(crate) fn flush_into(&mut self, table: &mut StencilTable) {
        self.pairs.sort_unstable_by_key(|p| p.0);
        let mut k = 0;
        for r in 0..self.pairs.len() {
            if k > 0 && self.pairs[k - 1].0 == self.pairs[r].0 {
                self.pairs[k - 1].1 += self.pairs[r].1;
            } else {
                self.pairs[k] = self.pairs[r];
                k += 1;
            }
        }
        self.pairs.truncate(k);
        self.pairs.retain(|p| p.1 != 0.0);
        table.push_pairs(&self.pairs);
        self.pairs.clear();
    }
}

impl Terms for RowBuf {
    #[inline]
    fn add(&mut self, i: u32, w: f64) {
        self.pairs.push((i, w));
    }
}

/// What the level loop of a one-shot kernel ([`refine_one_shot`]) asks of a scheme whose
/// refinement is a direct point kernel on a uniform split of the mesh layer (Catmull-Clark on
/// the quad split, Loop on the triangle split): the rules and points are the scheme's own, the
/// child nets come from the split ([`super::split_child`]); the loop is written once.
pub(crate) trait OneShot {
    /// The rules of one step on one level (plain, or with the level's sharp features).
    type Rules<'a>;
    /// The split the scheme refines on.
    type Split: UniformSplit;
    /// The rules for `mesh` under `opts`.
    fn rules<'a>(mesh: &'a PolyMesh, opts: &Opts) -> Self::Rules<'a>;
    /// The child points of one step, from the direct kernel.
    fn points(mesh: &PolyMesh, rules: &Self::Rules<'_>) -> Vec<Point>;
    /// The level's sharp features, when its rules have them.
    fn sharp<'r, 'a: 'r>(rules: &'r Self::Rules<'a>) -> Option<&'r SharpLevel<'a>>;
}

/// The last step of [`refine_one_shot`]: the child keeps no half-edges (built on first use, if
/// ever) unless the parent is not manifold.
fn last_step<K: OneShot, P: std::borrow::Borrow<PolyMesh>>(
    parent: P,
    opts: &Opts,
    bare: impl FnOnce(P, Vec<Point>) -> PolyMesh,
) -> PolyMesh {
    let p = parent.borrow();
    let rules = K::rules(p, opts);
    let positions = K::points(p, &rules);
    if !p.is_manifold() {
        return child_mesh::<K::Split>(p, positions, K::sharp(&rules));
    }
    let extras = K::sharp(&rules).map(|sl| child_extras::<K::Split>(p, sl, None));
    drop(rules);
    bare(parent, positions).with_extras(extras)
}

/// `levels` steps of a one-shot kernel: each parent dropped as soon as its child exists, the
/// last parent taken apart before its child is allocated, `progress(level)` after each step.
/// `check` runs on every parent before its step (size limits).
pub(crate) fn refine_one_shot<K: OneShot>(
    mesh: &PolyMesh,
    levels: usize,
    mut progress: impl FnMut(usize),
    check: impl Fn(&PolyMesh) -> Result<()>,
    opts: &Opts,
) -> Result<PolyMesh> {
    let mut owned: Option<PolyMesh> = None;
    for l in 0..levels {
        check(owned.as_ref().unwrap_or(mesh))?;
        let child = if l + 1 < levels {
            let p = owned.as_ref().unwrap_or(mesh);
            let rules = K::rules(p, opts);
            child_mesh::<K::Split>(p, K::points(p, &rules), K::sharp(&rules))
        } else {
            match owned.take() {
                None => last_step::<K, _>(mesh, opts, bare_child::<K::Split>),
                Some(parent) => last_step::<K, _>(parent, opts, last_child::<K::Split>),
            }
        };
        owned = Some(child);
        progress(l + 1);
    }
    Ok(owned.unwrap_or_else(|| mesh.clone()))
}

/// `impl Scheme for $unit` by `$configured::default()`: a scheme's unit type (`CatmullClark`,
/// `Loop`) is its configured type with OpenSubdiv's default options, method for method.
macro_rules! scheme_by_default {
    ($unit:ty => $configured:ty) => {
        impl $crate::schemes::Scheme for $unit {
            fn name(&self) -> &'static str {
                <$configured>::default().name()
            }

            fn step_size(
                &self,
                s: &$crate::schemes::growth::NetSize,
            ) -> $crate::schemes::growth::NetSize {
                <$configured>::default().step_size(s)
            }

            fn refine(
                &self,
                mesh: &$crate::mesh::PolyMesh,
            ) -> $crate::error::Result<$crate::schemes::Refinement> {
                <$configured>::default().refine(mesh)
            }

            fn refine_uniform(
                &self,
                mesh: &$crate::mesh::PolyMesh,
                levels: usize,
                progress: &mut dyn FnMut(usize),
            ) -> $crate::error::Result<$crate::mesh::PolyMesh> {
                <$configured>::default().refine_uniform(mesh, levels, progress)
            }

            fn limit_stencils(
                &self,
                mesh: &$crate::mesh::PolyMesh,
            ) -> $crate::error::Result<$crate::stencil::StencilTable> {
                <$configured>::default().limit_stencils(mesh)
            }

            fn face_varying(&self) -> Option<$crate::schemes::sdc::fvar::FvarRules> {
                <$configured>::default().face_varying()
            }
        }
    };
}
pub(crate) use scheme_by_default;

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    #[crate::unit::test]
    fn rows_merge() {
        let mut t = StencilTable::new(3);
        let mut row = RowBuf::default();
        row.add(2, 0.25);
        row.add(0, 0.5);
        row.add(2, 0.25);
        row.add(1, 0.0);
        row.flush_into(&mut t);
        assert_eq!(t.row(0), (&[0u32, 2][..], &[0.5, 0.5][..]));
    }

    #[crate::unit::test]
    fn exact_trigonometry() {
        assert_eq!(cos_2pi(1, 6), 0.5);
        assert_eq!(cos_2pi(1, 4), 0.0);
        assert_eq!(cos_2pi(-1, 3), -0.5);
        assert_eq!(sin_2pi(1, 4), 1.0);
        assert_eq!(sin_2pi(1, 12), 0.5);
        for n in 1i64..20 {
            for k in -3i64..25 {
                let x = 2.0 * std::f64::consts::PI * k.rem_euclid(n) as f64 / n as f64;
                assert!((cos_2pi(k, n) - x.cos()).abs() < 1e-14);
                assert!((sin_2pi(k, n) - x.sin()).abs() < 1e-14);
            }
        }
    }
}
