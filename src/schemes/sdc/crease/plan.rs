//! Sharpness values and the rules as plans: the classification of a vertex (smooth, dart,
//! crease, corner), the masks to combine and their blend weights while a semi-sharp feature
//! decays ([`VertexPlan`], [`EdgePlan`], [`LimitPlan`]).

/// Sharpness at or above which a feature is infinitely sharp.
pub(crate) const INFINITE: f32 = 10.0;

/// Whether a sharpness value is sharp at all.
#[inline]
pub(super) fn sharp(s: f32) -> bool {
    s > 0.0
}

/// Whether a sharpness value is semi-sharp (decays with refinement).
#[inline]
pub(super) fn semi_sharp(s: f32) -> bool {
    s > 0.0 && s < INFINITE
}

/// The sharpness of a child feature under uniform creasing: one less, 0 from 1 on down,
/// infinitely sharp features stay.
#[inline]
pub(crate) fn decrement(s: f32) -> f32 {
    if s <= 0.0 {
        0.0
    } else if s >= INFINITE {
        INFINITE
    } else if s > 1.0 {
        s - 1.0
    } else {
        0.0
    }
}

/// The rule of a vertex.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Rule {
    /// No sharp feature.
    Smooth,
    /// One sharp edge (refined by the smooth rule).
    Dart,
    /// Two sharp edges.
    Crease,
    /// A sharp vertex or more than two sharp edges.
    Corner,
}

/// The rule of a vertex of sharpness `s` with `sharp_edges` sharp incident edges.
#[inline]
pub(crate) fn classify(s: f32, sharp_edges: usize) -> Rule {
    if sharp(s) {
        return Rule::Corner;
    }
    match sharp_edges {
        0 => Rule::Smooth,
        1 => Rule::Dart,
        2 => Rule::Crease,
        _ => Rule::Corner,
    }
}

/// One of the masks a vertex rule combines.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum VertexMask {
    /// The scheme's smooth mask.
    Smooth,
    /// `3/4 v + 1/8 (a + b)` along the crease through `a` and `b`.
    Crease(u32, u32),
    /// `v`.
    Corner,
}

/// A term of a plan.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Emit {
    /// The scheme's smooth mask, scaled.
    Smooth(f64),
    /// A parent vertex with a weight.
    Vertex(u32, f64),
}

/// How a vertex point is computed: one mask, or a blend of the parent's and the child's
/// rules while a semi-sharp feature decays (`w` on the parent's).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum VertexPlan {
    /// One mask.
    Single(VertexMask),
    /// `w M_parent + (1 - w) M_child`.
    Blend {
        /// The parent's mask.
        parent: VertexMask,
        /// The child's mask.
        child: VertexMask,
        /// The parent's weight.
        w: f64,
    },
}

/// The crease (and boundary) vertex mask `3/4 v + 1/8 (a + b)`: the weight of the vertex and
/// of each of its two crease neighbours. Face-varying refinement uses it too.
pub(crate) const CREASE_VERTEX: (f64, f64) = (0.75, 0.125);

/// The crease (and boundary) edge mask: the weight of each end of the edge, the midpoint.
pub(crate) const CREASE_EDGE: f64 = 0.5;

pub(super) fn emit_mask(v: u32, mask: VertexMask, scale: f64, out: &mut impl FnMut(Emit)) {
    match mask {
        VertexMask::Smooth => out(Emit::Smooth(scale)),
        VertexMask::Crease(a, b) => {
            let (vw, ew) = CREASE_VERTEX;
            out(Emit::Vertex(v, vw * scale));
            out(Emit::Vertex(a, ew * scale));
            out(Emit::Vertex(b, ew * scale));
        }
        VertexMask::Corner => out(Emit::Vertex(v, scale)),
    }
}

impl VertexPlan {
    /// Emits the terms of the plan for vertex `v`.
    #[inline]
    pub fn emit(self, v: u32, mut out: impl FnMut(Emit)) {
        match self {
            VertexPlan::Single(m) => emit_mask(v, m, 1.0, &mut out),
            VertexPlan::Blend { parent, child, w } => {
                emit_mask(v, parent, w, &mut out);
                emit_mask(v, child, 1.0 - w, &mut out);
            }
        }
    }
}

/// How an edge point is computed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum EdgePlan {
    /// The scheme's smooth mask.
    Smooth,
    /// The midpoint.
    Crease,
    /// `s E_crease + (1 - s) E_smooth` with the edge's sharpness `s` (not clamped: under
    /// Chaikin creasing an edge whose halves both decay may have `s > 1`, and OpenSubdiv then
    /// extrapolates).
    Blend(f64),
}

impl EdgePlan {
    /// Emits the terms of the plan for the edge from `a` to `b`.
    #[inline]
    pub fn emit(self, a: u32, b: u32, mut out: impl FnMut(Emit)) {
        let crease = match self {
            EdgePlan::Smooth => return out(Emit::Smooth(1.0)),
            EdgePlan::Crease => 1.0,
            EdgePlan::Blend(s) => {
                out(Emit::Smooth(1.0 - s));
                s
            }
        };
        out(Emit::Vertex(a, CREASE_EDGE * crease));
        out(Emit::Vertex(b, CREASE_EDGE * crease));
    }
}

/// The limit mask of a vertex.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum LimitPlan {
    /// The scheme's smooth limit mask.
    Smooth,
    /// `2/3 v + 1/6 (a + b)`: the cubic B-spline of the crease through `a` and `b`.
    Crease(u32, u32),
    /// `v`.
    Corner,
}

impl LimitPlan {
    /// Emits the terms of the limit mask of vertex `v` (the smooth mask as `Emit::Smooth(1)`).
    #[inline]
    pub fn emit(self, v: u32, mut out: impl FnMut(Emit)) {
        match self {
            LimitPlan::Smooth => out(Emit::Smooth(1.0)),
            LimitPlan::Crease(a, b) => {
                out(Emit::Vertex(v, 2.0 / 3.0));
                out(Emit::Vertex(a, 1.0 / 6.0));
                out(Emit::Vertex(b, 1.0 / 6.0));
            }
            LimitPlan::Corner => out(Emit::Vertex(v, 1.0)),
        }
    }
}
