//! The shape of a hole's G^1 conditions ([`Fan`]: which spokes join two sectors, over which
//! turn they run, which are pinned) and its layout ([`Layout`]: how the ring's segments meet
//! the cap's sectors), both read off a [`Hole`] and keys of the cached cap maps.

#[cfg(doc)]
use super::hole::Hole;

/// The chart angle of a corner's sector ([`Fan::Corner`]): a quarter-turn when the sector is
/// convex (its sharp edges less than a half-turn apart around it), three quarters when it is
/// reflex, so that the chart turns the way the surface does.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum CornerAngle {
    /// A quarter-turn: spoke `n` leaves the centre along `T1`.
    Convex,
    /// Three quarters of a turn: spoke `n` leaves the centre along `-T1`.
    Reflex,
}

/// How a hole's spokes run around its centre and which of them join two sectors: the shape
/// of the G^1 conditions, read off a [`Hole`] by [`Hole::fan`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Fan {
    /// A hole closed around its centre: `n` spokes over a full turn, every one a join.
    Closed,
    /// An open fan at a boundary vertex: `n + 1` spokes over a half-turn (a quarter-turn for
    /// one sector), spokes `0` and `n` free boundary curves.
    Open,
    /// [`Fan::Open`] beside a crease: spokes `0` and `n` the Hermite cubics
    /// of their end data, `T0` pinned.
    Crease,
    /// A fan around a dart: `n + 1` spokes over a full turn, spokes `0` and
    /// `n` one Hermite cubic, the only spoke without the G^1 relation.
    Dart,
    /// `n` of the `m` sectors around an interior vertex, the others holes:
    /// `n + 1` spokes over `2 pi n / m`, spokes `0` and `n` free.
    Wedge(usize),
    /// A sector between two sharp edges at a corner: `n + 1` spokes over a
    /// quarter-turn (convex) or three (reflex), spokes `0` and `n` the Hermite cubics of their
    /// end data, `T0` and `T1` pinned.
    Corner(CornerAngle),
    /// A hole closed around a cone point (a vertex the corner rule keeps
    /// without two sharp edges to give it a tangent plane): the spokes of [`Fan::Closed`],
    /// every one a join, but every spoke tangent pinned to zero (the cap's corners at the apex
    /// are singular) and `w(0) = 2 cos(pi / n)`, the angles of a half-turn.
    Cone,
    /// [`Fan::Dart`] around a cone point with one sharp edge: spokes `0` and `n` the sharp edge, every spoke tangent zero, the
    /// weights of [`Fan::Cone`].
    DartCone,
}

impl Fan {
    /// Whether spokes `0` and `n` are distinct ends of the fan, not a join of two sectors.
    pub fn is_open(self) -> bool {
        !matches!(self, Fan::Closed | Fan::Cone)
    }

    /// Whether the fan closes a cone point: its spoke tangents are zero ([`Fan::Cone`],
    /// [`Fan::DartCone`]).
    pub fn is_cone(self) -> bool {
        matches!(self, Fan::Cone | Fan::DartCone)
    }

    /// Whether the fan runs around a dart: spoke `n` is spoke `0` ([`Fan::Dart`],
    /// [`Fan::DartCone`]).
    pub fn is_dart(self) -> bool {
        matches!(self, Fan::Dart | Fan::DartCone)
    }

    /// Whether the provider's two plane vectors are the spoke tangents `T0, T1` themselves,
    /// not fitted: a corner's sector (the two sharp edges' derivatives) and a cone point's
    /// fans (zero).
    pub fn pins_plane(self) -> bool {
        matches!(self, Fan::Corner(_)) || self.is_cone()
    }

    /// `Some(m)` for `n` of the `m` sectors around a vertex ([`Fan::Wedge`]).
    pub fn wedge(self) -> Option<usize> {
        match self {
            Fan::Wedge(m) => Some(m),
            _ => None,
        }
    }

    /// `Some(angle)` for a corner's sector ([`Fan::Corner`]).
    pub fn corner(self) -> Option<CornerAngle> {
        match self {
            Fan::Corner(a) => Some(a),
            _ => None,
        }
    }

    /// Whether the fan's spokes `0` and `n` are the cubic Hermite interpolants of their end
    /// data (a crease's or a dart's fan).
    pub fn hermite_ends(self) -> bool {
        matches!(
            self,
            Fan::Crease | Fan::Dart | Fan::DartCone | Fan::Corner(_)
        )
    }

    /// The fan a cap map of `layout` builds for the holes of kind `self`: closed for a closed
    /// layout, open (at least) for an open one; a crease or dart only on the one-piece open
    /// layouts; a cone on both (closed or dart).
    pub fn on(self, layout: Layout) -> Fan {
        match (layout.is_open(), self) {
            (false, Fan::Cone) => Fan::Cone,
            (false, _) => Fan::Closed,
            (true, Fan::Closed) => Fan::Open,
            (true, f) => f,
        }
    }
}

/// Layout of a hole.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Layout {
    /// Two segments per sector meeting at a corner.
    Quad,
    /// One segment per sector (a fan of triangles on a three-direction lattice).
    Triangle,
    /// A quad sector split into an `m x m` grid of pieces (`m >= 2`): `2 m` segments per
    /// sector, `m` along each outer side (the inner sides of macro-patch rings).
    Split(usize),
    /// The quad layout on an open fan of `n` sectors around a boundary vertex ([`Hole::is_open`]):
    /// `n + 1` spokes over a half-turn, `t_s = cos(pi s / n) T0 + sin(pi s / n) T1`, spokes `0`
    /// and `n` on the boundary of the surface.
    OpenQuad,
    /// The triangle layout on an open fan of `n` triangles around a boundary vertex (Loop's):
    /// one segment per sector, each fan triangle one cap patch with a straight corner at the
    /// segment's midpoint (module documentation), `n + 1` spokes over a half-turn as in
    /// [`Layout::OpenQuad`].
    OpenTriangle,
}

impl Layout {
    /// Pieces per sector side: `m` of [`Layout::Split`], 1 otherwise.
    pub fn pieces(self) -> usize {
        match self {
            Layout::Split(m) => m,
            _ => 1,
        }
    }

    /// Whether the layout is an open fan around a boundary vertex ([`Hole::is_open`]).
    pub fn is_open(self) -> bool {
        matches!(self, Layout::OpenQuad | Layout::OpenTriangle)
    }

    /// The fewest sectors a hole of this layout has: 3; 1 for an open fan (one piece between
    /// its two boundary spokes over a quarter-turn of the chart: a corner, whose spokes are
    /// `T0` and `T1`; or the one face on a side of a crease, whose spokes are the crease's two
    /// halves, `T1 = -T0`, [`super::ring::crease_tangents`]).
    pub fn min_sectors(self) -> usize {
        match self {
            Layout::OpenTriangle | Layout::OpenQuad => 1,
            _ => 3,
        }
    }

    /// The fewest sectors of a hole of this layout and kind: [`Layout::min_sectors`], but 2
    /// for a closed hole of quad sectors (one patch or split), the half-plane cap of a
    /// valence-2 vertex ([`super`], "Two sectors"), or a cone point's ([`Fan::Cone`]: a
    /// half-turn chart, `w(0) = 0`, certified from bi-3 on).
    pub fn min_sectors_of(self, fan: Fan) -> usize {
        match (self, fan) {
            (Layout::Quad | Layout::Split(_), Fan::Closed | Fan::Cone) => 2,
            _ => self.min_sectors(),
        }
    }
}
