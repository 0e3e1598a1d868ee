//! Whole-net refinement (`fairsub subdivide --levels N [--limit]`) and the stencil table of
//! a refinement.

use super::{Options, Source};
use crate::cli::Computed;
use crate::cli::subdivide;
use crate::error::Result;
use crate::geom::Point;
use crate::mesh::PolyMesh;
use crate::stencil::StencilTable;

/// A refined net, as `subdivide --levels N` computes it.
#[derive(Debug, Clone)]
pub enum Refined {
    /// The refined net (hole faces removed; with `limit`, every point at its limit).
    Net(PolyMesh),
    /// A non-box scheme's limit mesh (the refined quads split around their face control
    /// vertices, every point at its limit) with the exact limit normal per vertex.
    LimitMesh(PolyMesh, Vec<Point>),
    /// A non-box scheme's refined net in its FCV layout (the FCVs are the last points).
    FcvNet(PolyMesh),
}

impl Refined {
    /// The refined net (the limit mesh of [`Refined::LimitMesh`]).
    pub fn into_net(self) -> PolyMesh {
        match self {
            Refined::Net(m) | Refined::FcvNet(m) | Refined::LimitMesh(m, _) => m,
        }
    }
}

/// Refines `net` `levels` times with `scheme` (a name or alias from [`schemes`](super::schemes)),
/// with every point at its limit position when `limit`: `fairsub subdivide NET --scheme
/// SCHEME --levels LEVELS [--limit]`.
///
/// # Errors
/// An unknown scheme, an option the scheme does not take, a net the scheme does not take
/// (naming the element), or a refinement over the memory budget.
///
/// ```
/// use fairsub::{Options, refine};
/// let fine = refine("gallery:cube", "catmull-clark", 2, false, &Options::default())?;
/// assert_eq!(fine.into_net().num_faces(), 96);
/// // sqrt(3) on an icosahedron: three faces per face per step
/// let (ico, _) = fairsub::read_net("gallery:icosahedron", false)?;
/// let t = refine(&ico, "sqrt3", 1, false, &Options::default())?.into_net();
/// assert_eq!(t.num_faces(), 60);
/// # Ok::<(), fairsub::Error>(())
/// ```
pub fn refine(
    net: impl Into<Source>,
    scheme: &str,
    levels: usize,
    limit: bool,
    options: &Options,
) -> Result<Refined> {
    let (name, given) = net.into().split();
    let mut a = options.args(name, scheme)?;
    a.levels = Some(levels);
    a.limit = limit;
    let budget = crate::cli::limits::max_memory();
    crate::cli::limits::with_budget(budget, || {
        let p = subdivide::prepare(&a, given)?;
        let (computed, _) = subdivide::finish(&a, &p)?;
        Ok(match computed {
            Computed::Net(m) => Refined::Net(m),
            Computed::FcvNet(m) => Refined::FcvNet(m),
            Computed::LimitMesh(m, n) => Refined::LimitMesh(m, n),
            Computed::Complex(..) => unreachable!("a --levels job refines the net"),
        })
    })
}

/// The stencil table from the control points of `net` to the points of its `levels`-fold
/// refinement by `scheme`, with the refined net: applying the table to moved control points
/// refines them without refining the net again.
///
/// ```
/// use fairsub::{Options, level_stencils};
/// let (net, _) = fairsub::read_net("gallery:cube", false)?;
/// let (fine, table) = level_stencils(&net, "catmull-clark", 2, &Options::default())?;
/// assert_eq!((table.num_sources(), table.num_rows()), (8, fine.num_vertices()));
/// let moved: Vec<_> = net.positions().iter().map(|p| [p[0] * 2.0, p[1], p[2]]).collect();
/// let again = table.apply(&moved);
/// for (a, b) in again.iter().zip(fine.positions()) {
///     assert!((a[0] - 2.0 * b[0]).abs() < 1e-12 && (a[1] - b[1]).abs() < 1e-12);
/// }
/// # Ok::<(), fairsub::Error>(())
/// ```
pub fn level_stencils(
    net: impl Into<Source>,
    scheme: &str,
    levels: usize,
    options: &Options,
) -> Result<(PolyMesh, StencilTable)> {
    let (name, given) = net.into().split();
    let mut a = options.args(name, scheme)?;
    a.levels = Some(levels);
    let budget = crate::cli::limits::max_memory();
    crate::cli::limits::with_budget(budget, || {
        let p = subdivide::prepare(&a, given)?;
        let scheme = subdivide::mesh_rules(&p.spec)?;
        crate::cli::limits::check_levels(scheme.as_ref(), &p.mesh, levels)?;
        crate::schemes::level_stencils(scheme.as_ref(), &p.mesh, levels)
    })
}
