//! The scheme's limit surface at given points ([`limit_surface`]): a complex with as many
//! rings as the points need, each extraordinary element refined only as far as its own points
//! need where the scheme honours per-element ring counts ([`RingTargets`]: Catmull-Clark), and
//! an estimate of those counts for quad meshes ([`quad_corner_targets`]).

use super::index::Leaf;
use super::{Evaluation, MAX_EXACT_RINGS, Surface};
use crate::bezier::complex::Provenance;
use crate::bezier::domain::Shape;
use crate::error::{Error, Result};
use crate::host::adaptive::{RingTargets, with_ring_targets};
use crate::mesh::{Element, PolyMesh};
use std::collections::HashMap;
use std::sync::Arc;

/// The rings of every element in the first complex of [`limit_surface`].
pub const FIRST_RINGS: usize = 2;

/// [`FIRST_RINGS`] for every element: the start of [`limit_surface`].
pub fn first_targets() -> RingTargets {
    RingTargets {
        base: FIRST_RINGS,
        per: HashMap::new(),
    }
}

/// Raises element `e`'s count in `m` to at least `need`.
fn raise(m: &mut HashMap<Element, usize>, e: Element, need: usize) {
    let x = m.entry(e).or_insert(0);
    *x = (*x).max(need);
}

/// The larger count per element of `a` and `b` (the reduction of the parallel folds).
fn merge(mut a: HashMap<Element, usize>, b: HashMap<Element, usize>) -> HashMap<Element, usize> {
    for (e, n) in b {
        raise(&mut a, e, n);
    }
    a
}

/// Evaluations of the scheme's limit surface at `points` (`(face, u, v)`), and the rings
/// used ([`limit_surface`]). At an extraordinary element itself the cap's corner is the
/// scheme's limit point with the tangent plane of its limit masks (every cap and fill is built
/// so); its derivatives and curvatures there are the cap's (the limit surface's
/// parametrisation is singular there). A cone point (a corner tag without two sharp edges,
/// [`crate::bezier::g1::Fan::Cone`]) has no tangent plane: there the normal is the cap
/// piece's limit from its interior and the curvatures are NaN. `build(rings)` builds the
/// surface (callers add their size checks and progress there).
///
/// # Errors
/// Those of `build` and of [`Surface::evaluate`], for the first point that fails.
pub fn evaluate_limit(
    points: &[(u32, f64, f64)],
    build: &mut dyn FnMut(usize) -> Result<Surface>,
) -> Result<(Vec<Evaluation>, usize)> {
    let (s, rings) = limit_surface(points, build)?;
    let mut out = vec![Evaluation::default(); points.len()];
    s.evaluate_into(points, &mut out).map_err(|(_, e)| e)?;
    Ok((out, rings))
}

/// The surface on which [`evaluate_limit`] evaluates `points`, and its most rings: starting
/// from 2 rings, the complex is rebuilt until every point that fell on a cap or fill patch has
/// as many rings as it needs ([`Surface`]'s cells tell how near the extraordinary element they
/// are), at most [`MAX_EXACT_RINGS`]. Each element gets the rings its own points need
/// ([`RingTargets`], which Catmull-Clark honours; the other schemes build the most rings
/// everywhere): on 10^6 random points of a 10k-face net most elements need 5 or 6 rings and a
/// few 10. Every point is located (in parallel), none evaluated: callers that stream many
/// evaluations evaluate them afterwards.
///
/// # Errors
/// Those of `build`, and [`Surface::evaluate`]'s for the first point (by index) that lies
/// outside its face's domain or on no patch.
pub fn limit_surface(
    points: &[(u32, f64, f64)],
    build: &mut dyn FnMut(usize) -> Result<Surface>,
) -> Result<(Surface, usize)> {
    limit_surface_from(points, first_targets(), build)
}

/// [`limit_surface`] starting from the ring counts `first` instead of 2 rings everywhere (for
/// example [`quad_corner_targets`]: when they are what the points need, one construction).
///
/// # Errors
/// As [`limit_surface`].
pub fn limit_surface_from(
    points: &[(u32, f64, f64)],
    first: RingTargets,
    build: &mut dyn FnMut(usize) -> Result<Surface>,
) -> Result<(Surface, usize)> {
    use rayon::prelude::*;
    use std::sync::atomic::{AtomicUsize, Ordering};
    let mut targets = first;
    loop {
        let rings = targets.max();
        let (s, honoured) = with_ring_targets(Arc::new(targets.clone()), || build(rings));
        let s = s?;
        // the level of a cap: the element's own count where the rules honour the counts (deeper
        // where its hole waited: the cap's cell depth), else the rings of all
        let level = |e: Element, depth: u8| {
            if honoured {
                targets.of(Some(e)).max(usize::from(depth))
            } else {
                rings
            }
        };
        let failed = AtomicUsize::new(usize::MAX);
        let needs = points
            .par_iter()
            .enumerate()
            .fold(
                HashMap::new,
                |mut m: HashMap<Element, usize>, (i, &(f, u, v))| {
                    match s.locate(f, u, v) {
                        Ok((at, cell, _)) => {
                            if let Provenance::Cap { element, .. } =
                                s.complex.provenance[at.patch as usize]
                            {
                                let k = s.rings_needed(at, cell);
                                if k > 0 {
                                    raise(
                                        &mut m,
                                        element,
                                        level(element, at.domain(&s.complex).depth) + k,
                                    );
                                }
                            }
                        }
                        Err(_) => {
                            failed.fetch_min(i, Ordering::Relaxed);
                        }
                    }
                    m
                },
            )
            .reduce(HashMap::new, merge);
        let failed = failed.into_inner();
        if failed != usize::MAX {
            let (f, u, v) = points[failed];
            return Err(s.locate(f, u, v).err().unwrap_or_else(|| {
                Error::InvalidArgument(format!("point {}: not located", failed + 1))
            }));
        }
        let mut grew = false;
        for (e, need) in needs {
            let need = need.min(MAX_EXACT_RINGS);
            if need > targets.of(Some(e)) {
                targets.per.insert(e, need);
                grew = true;
            }
        }
        if !grew {
            return Ok((s, rings));
        }
    }
}

/// The rings the `points` need at the extraordinary corners of the quads of `mesh` (interior
/// vertices of valence other than 4, boundary vertices of more than two quads) under Catmull-Clark's halving of the
/// hole per ring: a point at distance `d` (the larger of its two parameter distances) from such
/// a corner needs `floor(-log2 d) + 1` rings, at least 2. An estimate without a construction
/// for [`limit_surface_from`], which checks it (other faces, and holes that wait, are found
/// there); it is exact for the caps of isolated extraordinary vertices of quad meshes.
pub fn quad_corner_targets(mesh: &PolyMesh, points: &[(u32, f64, f64)]) -> RingTargets {
    use rayon::prelude::*;
    // interior vertices of valence other than 4, boundary vertices of more than two quads
    // (the regular boundary has two, a corner one: no hole there unless features make one,
    // which the check finds)
    let corner_is_extraordinary: Vec<bool> = (0..mesh.num_vertices())
        .map(|v| {
            if mesh.is_boundary_vertex(v) {
                mesh.vertex_faces(v).len() > 2
            } else {
                mesh.valence(v) != 4
            }
        })
        .collect();
    let per = points
        .par_iter()
        .fold(
            HashMap::new,
            |mut m: HashMap<Element, usize>, &(f, u, v)| {
                let fu = f as usize;
                if fu >= mesh.num_faces() || mesh.face_size(fu) != 4 {
                    return m;
                }
                let face = mesh.face(fu);
                for (k, c) in [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
                    .iter()
                    .enumerate()
                {
                    let x = face[k];
                    if !corner_is_extraordinary[x as usize] {
                        continue;
                    }
                    let d: f64 = (u - c[0]).abs().max((v - c[1]).abs());
                    if d > 0.0 && d < 0.25 {
                        let need = (-d.log2()).floor() as usize + 1;
                        raise(&mut m, Element::Vertex(x), need.min(MAX_EXACT_RINGS));
                    }
                }
                m
            },
        )
        .reduce(HashMap::new, merge);
    RingTargets {
        base: FIRST_RINGS,
        per,
    }
}

impl Surface {
    /// Extra rings a point of a cap or fill cell needs to lie on ring patches: `k` where its
    /// distance to the nearest cell corner (the extraordinary element is one of them) is about
    /// `2^-k` of the cell; 0 for points of ring and regular patches and for the corners.
    fn rings_needed(&self, at: &Leaf, cell: [f64; 2]) -> usize {
        if !matches!(
            self.complex.provenance[at.patch as usize],
            Provenance::Cap { .. }
        ) {
            return 0;
        }
        let [x, y] = cell;
        let d = match at.shape {
            Shape::Quad => [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
                .iter()
                .map(|c: &[f64; 2]| (x - c[0]).abs().max((y - c[1]).abs()))
                .fold(f64::INFINITY, f64::min),
            Shape::Triangle => (x + y).min(1.0 - x).min(1.0 - y),
        };
        if d <= 0.0 {
            return 0;
        }
        let dom = at.domain(&self.complex);
        // a pole's cap: its cells are halves, the pole at y = 1 of the cell (halves are not
        // turned), and each ring halves the cap's cell toward it
        let d = if dom.halves != 0 { 1.0 - y } else { d };
        if d <= 0.0 {
            return 0;
        }
        // each ring shrinks the hole by 3 where the cap's cell is a third (TPS), else by 2
        let per_ring = if dom.splits_in_thirds(dom.depth) {
            3f64.log2()
        } else if dom.splits_at_ratio(dom.depth) {
            // adjustable TPS: the hole shrinks by its ratio
            -dom.ratio().log2()
        } else {
            1.0
        };
        (-d.log2() / per_ring).floor().max(0.0) as usize + 1
    }
}
