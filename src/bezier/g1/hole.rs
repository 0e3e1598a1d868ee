//! The scheme-independent description of a hole ([`Hole`]) and its conventions, and the data
//! vector the cap's linear map acts on.
//!
//! # Conventions
//!
//! A hole has `n >= 3` sectors (2 for a closed hole of quad sectors, the half-plane cap of
//! [`super`], "Two sectors") numbered counterclockwise around the normal `T0 x T1` of the
//! given tangent plane. Sector `s` lies between spoke `s` and spoke `s + 1` (indices mod `n`);
//! spoke `s` starts at the centre `C` with the derivative
//! `t_s = cos(2 pi s / n) T0 + sin(2 pi s / n) T1` (per unit of the cap's parameter) and ends at
//! the spoke end `E_s` on the outer boundary. So `T0` is the derivative along spoke 0 and `T1`
//! the derivative a quarter turn further, both at the cap's parameter speed: the provider scales
//! them (e.g. by the characteristic map of the scheme), and the cap's shape depends on it.
//!
//! **Quad layout** (two segments per sector: Catmull-Clark, EG, QAS+, guided, Doo-Sabin, PGS,
//! TPS, non-box cells). Sector `s` is one cap patch `P_s(u, v)` on `[0, 1]^2` with
//! `P_s(0, 0) = C`, spoke `s` its side `v = 0` and spoke `s + 1` its side `u = 0`
//! (`P_s(u, 0) = P_(s-1)(0, u)`). Its outer boundary is
//! * segment 0 (`a`): the side `u = 1`, parametrised by `v`, from `E_s` (`v = 0`) to the corner
//!   `K_s` (`v = 1`);
//! * segment 1 (`b`): the side `v = 1`, parametrised by `u`, from `E_(s+1)` (`u = 0`) to `K_s`.
//!
//! Each segment carries `boundary` (the ring's boundary curve) and `cross`, the ring's first
//! derivative across the segment pointing *into* the hole, per unit of the cap's transversal
//! parameter, as a Bezier curve in the segment's parameter: `cross_a(v) = -dP_s/du (1, v)`,
//! `cross_b(u) = -dP_s/dv (u, 1)`. For a ring patch of the same parameter size as the cap piece
//! (the usual case: the hole of a sector is one face of the last level) this is just the ring
//! patch's own derivative off that side, continued.
//!
//! **Split layout** ([`Layout::Split`]`(m)`, `2 m` segments per sector: QAS+^3 and the guided
//! macro-patch variants, whose last ring's inner sides are splines of `m` polynomial pieces).
//! Sector `s` is an `m x m` grid of pieces `P_s^(a, b)` on `[a/m, (a+1)/m] x [b/m, (b+1)/m]`,
//! each a patch in its own local `[0, 1]^2`; the sector's `(u, v)` as in the quad layout. Its
//! segments are, in order, the `m` pieces of side `u = 1` (piece `b` on `v` in
//! `[b/m, (b+1)/m]`, from the spoke end towards the corner) and then the `m` pieces of side
//! `v = 1` (piece `a`, from `E_(s+1)` towards the corner), each parametrised like the quad
//! segment it is part of, its `cross` **per unit of the piece's** transversal parameter (`1/m`
//! of the sector's): for a ring piece of the same size as the cap piece, its own derivative.
//!
//! **Open quad layout** ([`Layout::OpenQuad`], [`Hole::is_open`]: a boundary vertex of `n` quads,
//! Catmull-Clark's and its fallback schemes'). The sectors of the quad layout, numbered from
//! the boundary: spoke `s` (`s = 0..=n`) leaves the centre with
//! `t_s = cos(pi s / n) T0 + sin(pi s / n) T1`; spoke `0` (side `v = 0` of sector `0`) and
//! spoke `n` (side `u = 0` of sector `n - 1`) are boundary curves of the surface, not joins.
//! The segments are those of the quad layout.
//!
//! **Triangle layout** (one segment per sector: Loop; a fan of triangles `C, E_s, E_(s+1)`).
//! Segment `s` runs from `E_s` (`t = 0`) to `E_(s+1)` (`t = 1`), `cross` is the derivative of
//! the ring in the direction of the chart vector from the segment's midpoint `M_s` to the centre,
//! in the affine chart of the sector triangle in which the segment has unit speed (for a ring
//! triangle `E_(s+1) E_s X` across the segment: the direction `(E_s + E_(s+1)) / 2 - X`). The
//! ring must be a three-direction lattice at every spoke end (valence 6 there, as Loop's rings
//! are), so that in the chart at `E_(s+1)` the next segment's direction is `C - E_s`. Such a
//! hole is converted to a quad hole ([`Hole::to_quad_layout`]) by splitting every segment at its
//! midpoint: quad sector `j` is the kite `C, M_j, E_(j+1), M_(j+1)` under the bilinear map of the
//! unit square, its spoke `j` ends at `M_j` (so `t_j` is the derivative towards `M_j`). The
//! kites' cross derivatives are the ring's derivatives in the bilinear map's varying direction;
//! their spoke-end twist is `kappa = 1` ([`QuadHole::kappa`], derivation in [`super`]).
//!
//! **Open triangle layout** ([`Layout::OpenTriangle`], [`Hole::is_open`]: Loop at a boundary
//! vertex of `n` triangles). The segments of the triangle layout, sector `0` next to the
//! outgoing boundary edge; spokes `s = 0..=n` end at `E_s`, spokes `0` and `n` on the boundary.
//! Kites would leave two half-triangles at the boundary spokes, so every fan triangle is one
//! quad sector instead: the bilinear image of the unit square with corners `C, E_s, M_s,
//! E_(s+1)` (a straight corner at `M_s`), spoke `s` its side `v = 0`, segment `a` the first half
//! of segment `s` (`t = v / 2`), segment `b` the second half reversed (`t = 1 - u / 2`), with
//! `cross_a(v) = (1 - v) X + T / 2` and `cross_b(u) = (1 - u) X - T / 2` (`T` the segment's
//! derivative, `X` its median derivative). At an inner spoke end `E_s` the two fan triangles are
//! mirror images in the ring's lattice chart, but their cross derivatives there run along the
//! outer edges, not opposite: their sum is `-(E_s - C) / 2`, so the relation holds with
//! `w(1) = w1 = -1/2`, and the twists `C - (E_s + E_(s+1)) / 2` and `C - (E_(s-1) + E_s) / 2`
//! add up to `-3/2 (E_s - C)`: `kappa = 3/2` (derivation in [`super`]). One triangle (a corner
//! under Loop's corner rule) is one sector whose spokes are `T0` and `T1` themselves (a
//! quarter-turn of the chart).

use super::conversion::Conversion;
pub use super::fan::{CornerAngle, Fan, Layout};
use crate::error::{Error, Result};
use crate::geom::{Point, axpy, scale};

/// The largest number of pieces per sector side of a [`Layout::Split`] hole (the cap map grows
/// like `(n m^2 d^2)^3`).
pub const MAX_PIECES: usize = 4;

/// One outer boundary segment of a sector: the ring's boundary curve and its cross-boundary
/// derivative into the hole (conventions in the module documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct Segment {
    /// Bezier coefficients of the boundary curve.
    pub boundary: Vec<Point>,
    /// Bezier coefficients of the first cross-boundary derivative, pointing into the hole.
    pub cross: Vec<Point>,
}

/// A hole inside the last ring of a patch complex (conventions in the module documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct Hole {
    /// The centre: the scheme's limit point.
    pub centre: Point,
    /// `[T0, T1]`: spoke `s` leaves the centre with derivative
    /// `cos(2 pi s / n) T0 + sin(2 pi s / n) T1`. They span the limit tangent plane.
    pub tangents: [Point; 2],
    /// Per sector (counterclockwise about `T0 x T1`), its one or two outer segments.
    pub sectors: Vec<Vec<Segment>>,
    /// The kind of fan the hole is and so the shape of its G^1 conditions ([`Fan`]): closed
    /// around its centre ([`Fan::Closed`]); an open fan at a boundary vertex, whose spokes `0`
    /// and `n` are boundary curves ([`Fan::Open`], [`Layout::OpenQuad`]); beside an infinitely
    /// sharp crease, spokes `0` and `n` the crease's exact cubics and `T0` pinned to its
    /// derivative at the centre, so the caps on both sides share it
    /// ([`Fan::Crease`], [`super::ring::crease_tangents`]); around a dart, `n + 1` spokes over
    /// a full turn with spokes `0` and `n` the one sharp edge ([`Fan::Dart`]); `n` of the `m`
    /// sectors around an interior vertex whose other sectors are holes (OpenSubdiv's hole
    /// faces: [`Fan::Wedge`], the centre and plane the vertex's own); a sector between two
    /// sharp edges at a corner, both `T0` and `T1` pinned ([`Fan::Corner`], the chart angle of
    /// the sector); a cone point, a vertex the corner rule keeps with fewer than two sharp
    /// edges and so a tangent cone, not a plane: every spoke tangent zero, the G^1 relation
    /// holding along every spoke up to the apex ([`Fan::Cone`] closed, [`Fan::DartCone`] with
    /// one sharp edge; the provider's plane vectors are zero). One field, not a flag per kind:
    /// no hole can be two kinds at once.
    pub kind: Fan,
}

/// The degrees of a hole's segments: every boundary has degree `boundary`, every cross
/// derivative degree `cross`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Degrees {
    /// Degree of the boundary curves.
    pub boundary: usize,
    /// Degree of the cross-derivative curves.
    pub cross: usize,
}

impl Hole {
    /// A hole with its centre and sectors, the spoke tangents still unset (zero): the form in
    /// which the schemes hand their hole data to [`super::ring::cap_in_plane`], which fits the
    /// tangents in the limit tangent plane.
    pub fn untangented(centre: Point, sectors: Vec<Vec<Segment>>) -> Hole {
        Hole::untangented_as(centre, sectors, Fan::Closed)
    }

    /// [`Hole::untangented`] of the given kind.
    pub fn untangented_as(centre: Point, sectors: Vec<Vec<Segment>>, kind: Fan) -> Hole {
        Hole {
            centre,
            tangents: [[0.0; 3]; 2],
            sectors,
            kind,
        }
    }

    /// This hole as a cone point's ([`Fan::Cone`] for a closed hole, [`Fan::DartCone`] for a
    /// dart's fan; other kinds unchanged).
    pub fn into_cone(self) -> Hole {
        let kind = match self.kind {
            Fan::Closed => Fan::Cone,
            Fan::Dart => Fan::DartCone,
            k => k,
        };
        Hole { kind, ..self }
    }

    /// [`Hole::untangented`] for an open fan of sectors around a boundary vertex
    /// ([`Fan::Open`], [`Layout::OpenQuad`]).
    pub fn untangented_open(centre: Point, sectors: Vec<Vec<Segment>>) -> Hole {
        Hole::untangented_as(centre, sectors, Fan::Open)
    }

    /// [`Hole::untangented`] for a sector between the two infinitely sharp edges of a crease
    /// vertex ([`Fan::Crease`]).
    pub fn untangented_crease(centre: Point, sectors: Vec<Vec<Segment>>) -> Hole {
        Hole::untangented_as(centre, sectors, Fan::Crease)
    }

    /// [`Hole::untangented`] for the fan around a dart ([`Fan::Dart`]): sector `0` starts at
    /// the sharp edge and sector `n - 1` ends at it.
    pub fn untangented_dart(centre: Point, sectors: Vec<Vec<Segment>>) -> Hole {
        Hole::untangented_as(centre, sectors, Fan::Dart)
    }

    /// [`Hole::untangented`] for `n` of the `m` sectors around an interior vertex whose other
    /// sectors are holes ([`Fan::Wedge`]).
    pub fn untangented_wedge(centre: Point, sectors: Vec<Vec<Segment>>, m: usize) -> Hole {
        Hole::untangented_as(centre, sectors, Fan::Wedge(m))
    }

    /// [`Hole::untangented`] for a sector between two sharp edges at a corner
    /// ([`Fan::Corner`]).
    pub fn untangented_corner(
        centre: Point,
        sectors: Vec<Vec<Segment>>,
        angle: CornerAngle,
    ) -> Hole {
        Hole::untangented_as(centre, sectors, Fan::Corner(angle))
    }

    /// Whether the hole is an open fan (spokes `0` and `n` not a join: [`Fan::is_open`]).
    pub fn is_open(&self) -> bool {
        self.kind.is_open()
    }

    /// The shape of the hole's G^1 conditions ([`Fan`]).
    pub fn fan(&self) -> Fan {
        self.kind
    }

    /// Number of sectors.
    pub fn valence(&self) -> usize {
        self.sectors.len()
    }

    /// Checks the shape of the hole and returns its layout and segment degrees.
    pub fn layout(&self) -> Result<(Layout, Degrees)> {
        let n = self.sectors.len();
        // one sector: a corner of an open triangle fan, or the one face of a crease's side
        let open = self.is_open();
        let least = match (open, self.sectors.first().map(Vec::len)) {
            (true, Some(1)) => 1,
            (true, _) if matches!(self.kind, Fan::Crease | Fan::Corner(_) | Fan::Wedge(_)) => 1,
            (true, _) => 2,
            // two quad (or split) sectors: the half-plane cap of a valence-2 vertex
            (false, Some(k))
                if matches!(self.kind, Fan::Closed | Fan::Cone)
                    && k >= 2
                    && k.is_multiple_of(2) =>
            {
                2
            }
            _ => 3,
        };
        if n < least {
            return Err(Error::InvalidArgument(format!(
                "a G^1 cap needs at least {least} sectors, the hole has {n}"
            )));
        }
        let segs = self.sectors[0].len();
        let layout = match segs {
            2 if open => Layout::OpenQuad,
            1 if open => Layout::OpenTriangle,
            k if open => {
                return Err(Error::InvalidArgument(format!(
                    "sector 0 of the open hole has {k} segments; an open fan takes one (a fan \
                     of triangles) or two (quads) per sector"
                )));
            }
            1 => Layout::Triangle,
            2 => Layout::Quad,
            k if k.is_multiple_of(2) && k <= 2 * MAX_PIECES => Layout::Split(k / 2),
            k => {
                return Err(Error::InvalidArgument(format!(
                    "sector 0 of the hole has {k} segments; a sector has one, or two per piece \
                     of a side (at most {MAX_PIECES} pieces)"
                )));
            }
        };
        let first = &self.sectors[0][0];
        let deg = Degrees {
            boundary: first.boundary.len().saturating_sub(1),
            cross: first.cross.len().saturating_sub(1),
        };
        for (s, sec) in self.sectors.iter().enumerate() {
            if sec.len() != segs {
                return Err(Error::InvalidArgument(format!(
                    "sector {s} of the hole has {} segments, sector 0 has {segs}",
                    sec.len()
                )));
            }
            for (k, seg) in sec.iter().enumerate() {
                if seg.boundary.is_empty() || seg.cross.is_empty() {
                    return Err(Error::InvalidArgument(format!(
                        "segment {k} of sector {s} has no coefficients"
                    )));
                }
                if seg.boundary.len() != deg.boundary + 1 || seg.cross.len() != deg.cross + 1 {
                    return Err(Error::InvalidArgument(format!(
                        "segment {k} of sector {s} has degrees ({}, {}), segment 0 of sector 0 \
                         ({}, {}); all segments of a hole share their degrees",
                        seg.boundary.len() - 1,
                        seg.cross.len() - 1,
                        deg.boundary,
                        deg.cross
                    )));
                }
                let finite = seg
                    .boundary
                    .iter()
                    .chain(&seg.cross)
                    .all(|p| p.iter().all(|x| x.is_finite()));
                if !finite {
                    return Err(Error::InvalidArgument(format!(
                        "segment {k} of sector {s} has a non-finite coefficient"
                    )));
                }
            }
        }
        let pts = [self.centre, self.tangents[0], self.tangents[1]];
        if !pts.iter().all(|p| p.iter().all(|x| x.is_finite())) {
            return Err(Error::InvalidArgument(
                "the hole's centre or tangents are not finite".into(),
            ));
        }
        Ok((layout, deg))
    }

    /// The data vector of the hole, the input of [`super::CapMap`]: the centre, `T0`, `T1`, then
    /// per sector and segment the boundary coefficients followed by the cross coefficients.
    pub fn data(&self) -> Vec<Point> {
        let mut d = vec![self.centre, self.tangents[0], self.tangents[1]];
        for sec in &self.sectors {
            for seg in sec {
                d.extend_from_slice(&seg.boundary);
                d.extend_from_slice(&seg.cross);
            }
        }
        d
    }

    /// Moves the hole by `by`: its centre and boundary curves (tangents and cross-boundary
    /// derivatives are vectors and stay).
    pub fn translate(&mut self, by: Point) {
        self.centre = crate::geom::add(self.centre, by);
        for seg in self.sectors.iter_mut().flatten() {
            for p in &mut seg.boundary {
                *p = crate::geom::add(*p, by);
            }
        }
    }

    /// [`Hole::data`] about the centre: the centre and every boundary coefficient less the
    /// centre (the tangents and cross derivatives are vectors and stay). A cap map is affine,
    /// so the cap of these data plus the centre is the cap of the hole; but a map is exact
    /// only to its certificate (about 5e-11 for the bi-4 split caps), relative to the data it
    /// is applied to. On absolute coordinates that error is relative to the distance from the
    /// origin, which does not shrink with the hole: QAS+^3's caps on `torus-evs` (coordinates
    /// about 2.75) had C^0 gaps of 7.1e-11 inside a sector at every ring count, so a G^1 defect
    /// that doubled with every ring (1.6e-8 rad at 3 rings). About the centre it is relative
    /// to the hole's size and shrinks with it.
    pub fn data_about_centre(&self) -> Vec<Point> {
        let c = self.centre;
        let mut d = vec![[0.0; 3], self.tangents[0], self.tangents[1]];
        for sec in &self.sectors {
            for seg in sec {
                d.extend(seg.boundary.iter().map(|&p| crate::geom::sub(p, c)));
                d.extend_from_slice(&seg.cross);
            }
        }
        d
    }

    /// The quad-layout hole a triangle hole stands for (kites, or the straight-corner pieces
    /// of an open fan, see the module documentation); a quad or split hole is returned as it
    /// is (its segments raised to one degree), with `kappa = 0`, `w1 = 0`. Its segments have
    /// degree `max(boundary, cross + 1)` for a triangle hole.
    pub fn to_quad_layout(&self) -> Result<QuadHole> {
        let (layout, deg) = self.layout()?;
        let data = self.data();
        let conv = Conversion::cached(self.valence(), layout, deg);
        let q = conv.apply(&data);
        let segs = 2 * layout.pieces();
        let per = 2 * segs * (conv.degree + 1);
        let m = conv.degree + 1;
        let sectors: Vec<Vec<Segment>> = (0..self.valence())
            .map(|s| {
                let b = 3 + s * per;
                (0..segs)
                    .map(|k| Segment {
                        boundary: q[b + 2 * k * m..b + (2 * k + 1) * m].to_vec(),
                        cross: q[b + (2 * k + 1) * m..b + (2 * k + 2) * m].to_vec(),
                    })
                    .collect()
            })
            .collect();
        Ok(QuadHole {
            hole: Hole {
                sectors,
                ..self.clone()
            },
            kappa: conv.kappa,
            w1: conv.w1,
        })
    }
}

/// A hole in quad layout with the spoke-end twist `kappa` and spoke-end value `w1` of its G^1
/// weight (both 0 for rings that are a tensor-product grid at the spoke ends; `kappa = 1` for
/// kites split from a triangle fan; `kappa = 3/2`, `w1 = -1/2` for the straight-corner pieces
/// of an open triangle fan).
#[derive(Debug, Clone, PartialEq)]
pub struct QuadHole {
    /// The hole (two segments per sector).
    pub hole: Hole,
    /// `-w'(1)` of the spoke weight
    /// `w(u) = 2 cos(theta) (1 - u)^2 + (2 w1 + kappa) u (1 - u) + w1 u^2`.
    pub kappa: f64,
    /// `w(1)`: 0 where the two pieces at a spoke end are mirror images of one chart (their
    /// cross derivatives opposite).
    pub w1: f64,
}

/// `cos(2 pi s / n) T0 + sin(2 pi s / n) T1` (`pi s / n` on an open fan, [`Fan`]).
pub fn spoke_tangent(tangents: &[Point; 2], n: usize, fan: Fan, s: usize) -> Point {
    let th = super::system::spoke_angle_at(n, fan, s);
    axpy(scale(tangents[0], th.cos()), th.sin(), tangents[1])
}
