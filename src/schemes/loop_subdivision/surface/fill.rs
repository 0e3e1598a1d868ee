//! Loop's Hermite fill (fairsub's own construction, documented in [`super`]): the C^0 quartic
//! triangles that close a hole without a G^1 cap (extraordinary boundary vertices, `--rings 0`
//! holes whose ring is not complete after the extra levels, or `--no-fill`'s opposite: the
//! holes the cap cannot take), its Hermite edge curves and the per-vertex jets they share.

use super::{Level, ring6, tri_index, triangle_to_tensor};
use crate::bezier::complex::{PatchComplex, Provenance};
use crate::bezier::convert::cubic_bspline_to_bezier;
use crate::geom::{self, Point};
use crate::host::adaptive::{Curves, Tag, edge_curve};
use crate::mesh::{Element, PolyMesh};
use crate::schemes::common::{cos_2pi, sin_2pi};
use crate::schemes::loop_subdivision::Rules;
use crate::schemes::loop_subdivision::limit::tangent_mask;
use crate::schemes::sdc::crease::adaptive::{chord_vertices, crease_curve};
use crate::stencil::Stencil;
use std::collections::HashMap;

/// Limit position of `a` and the derivative along the edge `a -> b` (unit edge parameter), for
/// the Hermite edges of the fill; the chord of the limit points at a vertex with a sharp
/// feature other than a plain boundary ([`chord_vertices`]).
pub(super) fn limit_and_derivative(
    m: &PolyMesh,
    jets: &mut Jets,
    a: usize,
    b: usize,
) -> (Point, Point) {
    let pos = m.positions();
    let la = jets.limit(m, a);
    let chord = |jets: &mut Jets| geom::sub(jets.limit(m, b), la);
    if jets.chord.as_ref().is_some_and(|c| c[a]) {
        return (la, chord(jets));
    }
    let fourier = jets
        .modes(m, a)
        .map(|md| (md.n, md.c, md.s, md.index.get(&(b as u32)).copied()));
    if let Some((n, c, s, j)) = fourier {
        let Some(j) = j else {
            return (la, chord(jets));
        };
        // (2/n) sum_i cos(2 pi (i - j)/n) p_i = (2/n) (cos(t j) C + sin(t j) S).
        let w = 2.0 / n as f64;
        let (n, j) = (n as i64, j as i64);
        let d = geom::axpy([0.0; 3], w * cos_2pi(j, n), c);
        return (la, geom::axpy(d, w * sin_2pi(j, n), s));
    }
    let ring: Vec<Stencil> = if m.is_boundary_vertex(a) {
        match ring6(m, a) {
            Some(r) => r.to_vec(),
            None => return (la, chord(jets)),
        }
    } else {
        m.outgoing_halfedges(a)
            .iter()
            .map(|&h| Stencil::point(m.he_to(h) as usize))
            .collect()
    };
    let Some(j) = ring.iter().position(|s| s.entries() == [(b as u32, 1.0)]) else {
        return (la, chord(jets));
    };
    let n = ring.len();
    let mut d = [0.0; 3];
    for (s, (c, _)) in ring.iter().zip(tangent_mask(n, j)) {
        d = geom::axpy(d, (2.0 / n as f64) * c, s.apply(pos));
    }
    (la, d)
}

/// Interior valences above which the fill's tangents come from Fourier sums
/// ([`FanModes`]); at and below it they are the masks' sums as before, to the bit.
pub(super) const FOURIER_ABOVE: usize = 32;

/// The mode-1 sums `C = sum_i cos(2 pi i / n) p_i`, `S = sum_i sin(2 pi i / n) p_i` of an
/// interior vertex's ring `p_i` (outgoing order), and each neighbour's first position in it.
struct FanModes {
    n: usize,
    c: Point,
    s: Point,
    index: HashMap<u32, usize>,
}

/// The fill's limit points and fan sums, each computed once per vertex: at a vertex of valence
/// `n` each costs `O(n)`, and the vertex has `n` edges to fill (`n^2` when asked per edge).
pub(super) struct Jets<'m> {
    /// The level's rules (its sharp level built once), for the limit points.
    rules: Rules<'m>,
    /// With sharp features: the vertices whose derivatives are chords.
    chord: Option<Vec<bool>>,
    limits: HashMap<usize, Point>,
    modes: HashMap<usize, Option<FanModes>>,
}

impl<'m> Jets<'m> {
    /// The jets of `level`, none computed yet.
    pub(super) fn new(level: &'m Level) -> Self {
        Jets {
            rules: Rules::new(&level.mesh, &level.options()),
            chord: level
                .sharp
                .as_ref()
                .and_then(|_| chord_vertices(&level.mesh)),
            limits: HashMap::new(),
            modes: HashMap::new(),
        }
    }

    fn limit(&mut self, m: &PolyMesh, v: usize) -> Point {
        let rules = &self.rules;
        *self
            .limits
            .entry(v)
            .or_insert_with(|| rules.limit_stencil(v).apply(m.positions()))
    }

    /// The fan sums of interior vertex `v` of valence above [`FOURIER_ABOVE`], else `None`.
    fn modes(&mut self, m: &PolyMesh, v: usize) -> Option<&FanModes> {
        self.modes
            .entry(v)
            .or_insert_with(|| {
                if m.is_boundary_vertex(v) {
                    return None;
                }
                let ring: Vec<u32> = m.outgoing(v).map(|h| m.he_to(h)).collect();
                let n = ring.len();
                if n <= FOURIER_ABOVE {
                    return None;
                }
                let pos = m.positions();
                let (mut c, mut s) = ([0.0; 3], [0.0; 3]);
                let mut index = HashMap::with_capacity(n);
                for (i, &w) in ring.iter().enumerate() {
                    c = geom::axpy(c, cos_2pi(i as i64, n as i64), pos[w as usize]);
                    s = geom::axpy(s, sin_2pi(i as i64, n as i64), pos[w as usize]);
                    index.entry(w).or_insert(i);
                }
                Some(FanModes { n, c, s, index })
            })
            .as_ref()
    }
}

/// The other boundary neighbour of boundary vertex `v` (not `w`), or the ghost `2 v - w` at a
/// corner.
fn boundary_continuation(m: &PolyMesh, v: usize, w: usize) -> Point {
    let pos = m.positions();
    let hs = m.outgoing_halfedges(v);
    let first = m.he_to(hs[0]) as usize;
    let last = m.he_from(m.he_prev(*hs.last().expect("a vertex has a face"))) as usize;
    let other = if first == w { last } else { first };
    if m.vertex_faces(v).len() == 1 {
        geom::sub(geom::scale(pos[v], 2.0), pos[w])
    } else {
        pos[other]
    }
}

/// The edge curve `a -> b` of `level`'s fill (see the module documentation), as a quartic:
/// with sharp features, an infinitely sharp edge between crease or corner vertices takes its
/// exact crease curve ([`crease_curve`]).
fn fill_edge(level: &Level, jets: &mut Jets, a: usize, b: usize) -> [Point; 5] {
    let m = &level.mesh;
    let pos = m.positions();
    let crease = crease_curve(level, a as u32, b as u32);
    let cubic = match m.find_halfedge(a, b).or_else(|| m.find_halfedge(b, a)) {
        _ if crease.is_some() => crease.expect("checked"),
        Some(h) if m.he_twin(h).is_none() => {
            let d = [
                boundary_continuation(m, a, b),
                pos[a],
                pos[b],
                boundary_continuation(m, b, a),
            ];
            cubic_bspline_to_bezier(&d)
        }
        _ => {
            let (p0, d0) = limit_and_derivative(m, jets, a, b);
            let (p3, d3) = limit_and_derivative(m, jets, b, a);
            [
                p0,
                geom::axpy(p0, 1.0 / 3.0, d0),
                geom::axpy(p3, 1.0 / 3.0, d3),
                p3,
            ]
        }
    };
    let q = crate::bezier::curve::raise(&cubic);
    [q[0], q[1], q[2], q[3], q[4]]
}

/// The Hermite fill of the marked triangles of the last level.
pub(super) fn fill(
    level: &Level,
    marked: &[(u32, Tag)],
    curves: &mut Curves<5>,
    out: &mut PatchComplex,
) {
    let m = &level.mesh;
    let mut jets = Jets::new(level);
    for &(f, tag) in marked {
        let c = m.face(f as usize);
        let mut tri = [[0.0; 3]; 15];
        for k in 0..3 {
            let e = edge_curve(curves, c[k], c[(k + 1) % 3], |a, b| {
                fill_edge(level, &mut jets, a, b)
            });
            for (r, p) in e.iter().enumerate() {
                let mut idx = [0usize; 3];
                idx[k] = 4 - r;
                idx[(k + 1) % 3] = r;
                tri[tri_index(idx[0], idx[1], idx[2])] = *p;
            }
        }
        // Discrete harmonic interior: x = (S_x + S / 4) / 7 with S_x the sum of the four
        // boundary neighbours of x in the Bezier net and S the sum over the three.
        let interior = [[2, 1, 1], [1, 2, 1], [1, 1, 2]];
        let sums: Vec<Point> = interior
            .iter()
            .map(|&[i, j, k]| {
                let mut s = [0.0; 3];
                for d in [
                    [1, 0, -1],
                    [1, -1, 0],
                    [0, 1, -1],
                    [-1, 1, 0],
                    [0, -1, 1],
                    [-1, 0, 1],
                ] {
                    let (a, b, cc) = (i as i32 + d[0], j as i32 + d[1], k as i32 + d[2]);
                    let n = [a as usize, b as usize, cc as usize];
                    if !interior.contains(&n) {
                        s = geom::add(s, tri[tri_index(n[0], n[1], n[2])]);
                    }
                }
                s
            })
            .collect();
        let total = geom::add(geom::add(sums[0], sums[1]), sums[2]);
        for (x, s) in interior.iter().zip(&sums) {
            tri[tri_index(x[0], x[1], x[2])] = geom::scale(geom::axpy(*s, 0.25, total), 1.0 / 7.0);
        }
        let element = tag.element.unwrap_or(Element::Vertex(c[0]));
        out.push_in(
            triangle_to_tensor(&tri),
            Provenance::Cap {
                element,
                sector: tag.sector,
            },
            tag.domain,
        );
        super::sharp::mark_sides(level, f as usize, out);
    }
}
