//! Continuity certificates of patch complexes: measured C^0, C^1, C^2 and G^1 defects across
//! every shared boundary, grouped by the kind of join (regular-regular, ring k - ring k+1,
//! ring - cap, ...), with the place of each maximum.
//!
//! Shared boundaries come from [`crate::surface::adjacency::shared_boundaries`] (T-junctions
//! included). Along each shared piece the two patches are evaluated at matching points; the
//! cross-boundary derivatives of order 1 and 2 are compared after matching the
//! parameterizations: if the piece covers a parameter length `dt` of patch A and `ds` of patch
//! B, B's transversal parameter is taken to scale by the same ratio `rho = dt / ds` (as between
//! subdivision rings), so C^1 compares `D_A` with `D_B / rho` and C^2 `D2_A` with `D2_B / rho^2`,
//! `D` the derivative across the boundary pointing from A into B. The G^1 defect is the angle
//! between the unit normals. Defects are absolute (model units per unit of A's parameter);
//! the report also gives them relative to the size of the complex.

use crate::bezier::{BezierPatch, Side};
use crate::geom::{self, Point};
use crate::surface::adjacency::{SharedBoundary, default_tolerance, shared_boundaries};
use crate::surface::{PatchComplex, Provenance};
use serde::Serialize;
use std::collections::BTreeMap;

/// Where a defect was measured.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct Location {
    /// First patch.
    pub patch_a: usize,
    /// Second patch.
    pub patch_b: usize,
    /// Provenance of the first patch.
    pub provenance_a: Provenance,
    /// Provenance of the second patch.
    pub provenance_b: Provenance,
    /// The point.
    pub point: Point,
}

/// Maxima of the defects over a set of shared boundaries.
#[derive(Debug, Clone, Serialize, Default)]
pub struct Defects {
    /// Number of shared pieces measured.
    pub pieces: usize,
    /// Largest positional gap.
    pub c0: f64,
    /// Largest first cross-derivative mismatch.
    pub c1: f64,
    /// Largest second cross-derivative mismatch.
    pub c2: f64,
    /// Largest angle between normals, radians.
    pub g1: f64,
    /// The rounding floor of the normals where the largest G^1 defect sits: how far the two
    /// unit normals can turn when every coefficient of the two patches moves by one unit in
    /// the last place of its patch's largest coordinate. A defect
    /// below its floor is what the doubles of the control points can hold, not the
    /// construction's; thin, nearly folded patches (beside a semi-sharp crease under a dual
    /// scheme) have floors far above 1e-8 rad.
    pub g1_rounding: f64,
    /// Largest part of a G^1 defect above the rounding floor of its place: `max(0, G1 - floor)`.
    pub g1_beyond_rounding: f64,
    /// Where the largest C^0 defect sits.
    pub c0_at: Option<Location>,
    /// Where the largest C^1 defect sits.
    pub c1_at: Option<Location>,
    /// Where the largest C^2 defect sits.
    pub c2_at: Option<Location>,
    /// Where the largest G^1 defect sits.
    pub g1_at: Option<Location>,
}

impl Defects {
    /// Whether no piece was measured.
    pub fn is_empty(&self) -> bool {
        self.pieces == 0
    }

    fn merge(&mut self, o: &Defects) {
        self.pieces += o.pieces;
        if o.c0 > self.c0 {
            self.c0 = o.c0;
            self.c0_at = o.c0_at;
        }
        if o.c1 > self.c1 {
            self.c1 = o.c1;
            self.c1_at = o.c1_at;
        }
        if o.c2 > self.c2 {
            self.c2 = o.c2;
            self.c2_at = o.c2_at;
        }
        if o.g1 > self.g1 {
            self.g1 = o.g1;
            self.g1_at = o.g1_at;
            self.g1_rounding = o.g1_rounding;
        }
        self.g1_beyond_rounding = self.g1_beyond_rounding.max(o.g1_beyond_rounding);
    }
}

/// A patch side that no other patch shares.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct OpenSide {
    /// The patch.
    pub patch: usize,
    /// Its side (`U0`, `U1`, `V0`, `V1`).
    pub side: &'static str,
    /// Provenance of the patch.
    pub provenance: Provenance,
    /// Midpoint of the side.
    pub midpoint: Point,
}

/// At most this many open sides are listed in a report.
pub const MAX_LISTED_OPEN_SIDES: usize = 200;

/// The continuity report of a complex.
#[derive(Debug, Clone, Serialize)]
pub struct ContinuityReport {
    /// Number of patches.
    pub patches: usize,
    /// Diagonal of the bounding box of all coefficients (the scale of "relative" defects).
    pub size: f64,
    /// Patch sides that no other patch shares (the complex's boundary, or a crack).
    pub open_sides: usize,
    /// The first [`MAX_LISTED_OPEN_SIDES`] open sides, where a crack would show.
    pub open: Vec<OpenSide>,
    /// All shared pieces except the sharp ones.
    pub all: Defects,
    /// Shared pieces along sharp features (infinitely sharp creases the surface keeps: C^0
    /// joins, their C^1 and G^1 "defects" are the crease's angle), kept out of `all` and
    /// `by_kind`; left out of the JSON when there is none.
    #[serde(skip_serializing_if = "Defects::is_empty")]
    pub sharp: Defects,
    /// Per kind of join, e.g. `regular|regular`, `ring1|ring2`, `ring6|cap`.
    pub by_kind: BTreeMap<String, Defects>,
}

/// Samples per shared piece.
const SAMPLES: usize = 9;

/// Derivatives across side `side` of `p` at side parameter `t`, pointing out of the patch:
/// `(point, first, second, normal, the normal's rounding floor)`. Where the patch is singular (its partials vanish or are
/// parallel: the apex of a cone point's cap, a pole) the normal is the limit along the side,
/// from the side's middle: the tangent plane along the join, which two patches G^1 across
/// the side share even at an apex that has no tangent plane of its own; elsewhere on a
/// singular point, and where that limit does not exist, the limit from the interior
/// ([`BezierPatch::normal_from`]).
fn across(p: &BezierPatch, side: Side, t: f64) -> (Point, Point, Point, Point, f64) {
    let [u, v] = side.domain_point(t);
    let d = p.derivatives(u, v);
    let toward = if t < 0.5 { 1.0 } else { -1.0 };
    let along = match side {
        Side::U0 | Side::U1 => [0.0, toward],
        Side::V0 | Side::V1 => [toward, 0.0],
    };
    let (n, floor) = if d.is_regular() {
        (p.normal_from(u, v, &d), normal_rounding(p, &d, along))
    } else {
        match d.normal_toward(along) {
            Some(n) => (n, normal_rounding(p, &d, along)),
            // the normal of an interior limit: no floor claimed
            None => (p.normal_from(u, v, &d), 0.0),
        }
    };
    match side {
        Side::U1 => (d.p, d.du, d.duu, n, floor),
        Side::U0 => (d.p, geom::scale(d.du, -1.0), d.duu, n, floor),
        Side::V1 => (d.p, d.dv, d.dvv, n, floor),
        Side::V0 => (d.p, geom::scale(d.dv, -1.0), d.dvv, n, floor),
    }
}

/// The rounding floor of a polynomial patch's unit normal at a point (radians): the
/// first-order bound of the angle the normal turns when every coefficient moves by at most one
/// unit in the last place of the patch's largest coordinate `M` (`eps M` per coordinate,
/// `sqrt 3 eps M` per point). A partial of degree `d` is `d` times a Bernstein combination of
/// coefficient differences, so it moves by at most `2 sqrt 3 d eps M`; a second partial by
/// `4 sqrt 3 d (d - 1) eps M` (mixed: `4 sqrt 3 d_u d_v eps M`). The normal is the direction of
/// `x cross y` (`du x dv` at a regular point; at a collapsed side or corner the first term of
/// [`crate::bezier::Derivatives::normal_toward`] along the side, `a x dv + du x b`), which turns
/// by at most `|delta n| / |n|` with `|delta (x cross y)| <= |delta x| |y| + |x| |delta y|`.
/// Exact doubles cannot do better, whatever computed them. Zero where the normal needs a
/// further term (both partials and their first changes vanish) and for rational patches.
fn normal_rounding(p: &BezierPatch, d: &crate::bezier::Derivatives, along: [f64; 2]) -> f64 {
    if p.weights.is_some() {
        return 0.0;
    }
    let m = p
        .cps
        .iter()
        .flat_map(|q| q.iter())
        .fold(0.0f64, |m, x| m.max(x.abs()));
    let e = 3f64.sqrt() * f64::EPSILON * m;
    let (du, dv) = (p.deg_u as f64, p.deg_v as f64);
    let (e_u, e_v) = (2.0 * du * e, 2.0 * dv * e);
    let (n, dn) = if d.is_regular() {
        (
            geom::cross(d.du, d.dv),
            e_u * geom::norm(d.dv) + geom::norm(d.du) * e_v,
        )
    } else {
        let (e_uu, e_uv, e_vv) = (
            4.0 * du * (du - 1.0).max(0.0) * e,
            4.0 * du * dv * e,
            4.0 * dv * (dv - 1.0).max(0.0) * e,
        );
        let [hu, hv] = along;
        let a = geom::add(geom::scale(d.duu, hu), geom::scale(d.duv, hv));
        let b = geom::add(geom::scale(d.duv, hu), geom::scale(d.dvv, hv));
        let (e_a, e_b) = (
            hu.abs() * e_uu + hv.abs() * e_uv,
            hu.abs() * e_uv + hv.abs() * e_vv,
        );
        (
            geom::add(geom::cross(a, d.dv), geom::cross(d.du, b)),
            e_a * geom::norm(d.dv)
                + geom::norm(a) * e_v
                + e_u * geom::norm(b)
                + geom::norm(d.du) * e_b,
        )
    };
    let len = geom::norm(n);
    if len > 0.0 { dn / len } else { 0.0 }
}

fn kind_name(p: &Provenance) -> String {
    p.group_name()
}

/// Measures one shared piece.
fn measure(c: &PatchComplex, sb: &SharedBoundary) -> Defects {
    let (pa, pb) = (&c.patches[sb.a], &c.patches[sb.b]);
    let rho = (sb.t[1] - sb.t[0]) / (sb.s[1] - sb.s[0]).abs();
    let mut d = Defects {
        pieces: 1,
        ..Defects::default()
    };
    for k in 0..SAMPLES {
        let t = sb.t[0] + (sb.t[1] - sb.t[0]) * k as f64 / (SAMPLES - 1) as f64;
        let s = sb.map_to_b(t);
        let (xa, da, dda, na, ra) = across(pa, sb.side_a, t);
        let (xb, db, ddb, nb, rb) = across(pb, sb.side_b, s);
        // B's outward derivative points back into A: the derivative from A into B is -db.
        let c0 = geom::dist(xa, xb);
        let c1 = geom::norm(geom::add(da, geom::scale(db, 1.0 / rho)));
        let c2 = geom::norm(geom::sub(dda, geom::scale(ddb, 1.0 / (rho * rho))));
        let g1 = if geom::norm(na) > 0.0 && geom::norm(nb) > 0.0 {
            geom::norm(geom::cross(na, nb)).atan2(geom::dot(na, nb))
        } else {
            0.0
        };
        let loc = Location {
            patch_a: sb.a,
            patch_b: sb.b,
            provenance_a: c.provenance[sb.a],
            provenance_b: c.provenance[sb.b],
            point: xa,
        };
        if c0 > d.c0 || d.c0_at.is_none() {
            d.c0 = c0;
            d.c0_at = Some(loc);
        }
        if c1 > d.c1 || d.c1_at.is_none() {
            d.c1 = c1;
            d.c1_at = Some(loc);
        }
        if c2 > d.c2 || d.c2_at.is_none() {
            d.c2 = c2;
            d.c2_at = Some(loc);
        }
        if g1 > d.g1 || d.g1_at.is_none() {
            d.g1 = g1;
            d.g1_at = Some(loc);
            d.g1_rounding = ra + rb;
        }
        d.g1_beyond_rounding = d.g1_beyond_rounding.max(g1 - ra - rb);
    }
    d
}

/// Measures the continuity of a patch complex across all its shared boundaries.
pub fn check(c: &PatchComplex) -> ContinuityReport {
    let tol = default_tolerance(c);
    let shared = shared_boundaries(c, tol);
    let size = geom::bounding_box(c.patches.iter().flat_map(|p| p.cps.iter().copied()))
        .map(|(lo, hi)| geom::dist(lo, hi))
        .unwrap_or(0.0);
    // Open sides: non-collapsed sides whose parameter range is not fully covered.
    let uncovered = crate::surface::adjacency::open_sides(c, &shared, tol);
    let open_sides = uncovered.len();
    let open = uncovered
        .iter()
        .take(MAX_LISTED_OPEN_SIDES)
        .map(|&(i, side)| {
            let [u, v] = side.domain_point(0.5);
            OpenSide {
                patch: i,
                side: match side {
                    Side::U0 => "U0",
                    Side::U1 => "U1",
                    Side::V0 => "V0",
                    Side::V1 => "V1",
                },
                provenance: c.provenance[i],
                midpoint: c.patches[i].eval(u, v),
            }
        })
        .collect();
    let mut all = Defects::default();
    let mut sharp = Defects::default();
    let mut by_kind: BTreeMap<String, Defects> = BTreeMap::new();
    let masks = c.sharp_masks();
    for sb in &shared {
        let d = measure(c, sb);
        if masks[sb.a] & (1 << sb.side_a.index()) != 0
            || masks[sb.b] & (1 << sb.side_b.index()) != 0
        {
            sharp.merge(&d);
            continue;
        }
        let (mut ka, mut kb) = (
            kind_name(&c.provenance[sb.a]),
            kind_name(&c.provenance[sb.b]),
        );
        if ka > kb {
            std::mem::swap(&mut ka, &mut kb);
        }
        by_kind.entry(format!("{ka}|{kb}")).or_default().merge(&d);
        all.merge(&d);
    }
    ContinuityReport {
        patches: c.len(),
        size,
        open_sides,
        open,
        all,
        sharp,
        by_kind,
    }
}
