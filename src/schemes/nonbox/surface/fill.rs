//! The fill of the cells left after the last ring (the construction the module documentation
//! of [`super`] describes): one bi-3 Coons patch per cell, each edge's cubic defined once (the
//! emitted cell's exact curve, the boundary's B-spline, or the Hermite interpolant of the limit
//! positions and edge derivatives).

use super::*;

/// The derivative of the limit surface at vertex `a` along its edge to `b` (unit edge
/// parameter), see the [module](super) documentation.
fn edge_derivative(level: &Level, jets: &mut Jets, a: usize, b: usize) -> Point {
    let m = &level.net.mesh;
    let pts = &level.points;
    let chord = |jets: &mut Jets| geom::sub(jets.limit(level, b), jets.limit(level, a));
    let Some(g) = m.find_halfedge(a, b) else {
        return chord(jets);
    };
    if let Some(r) = corner_fcvs(m, g) {
        let q: Vec<Point> = r.iter().map(|s| s.apply(pts)).collect();
        return geom::scale(geom::sub(geom::add(q[0], q[3]), geom::add(q[1], q[2])), 0.5);
    }
    let (u1, u2) = jets.tangents(level, a);
    if !m.is_boundary_vertex(a) {
        let (j, k) = jets.fan_index(m, a, g);
        let t = (2.0 * j as f64 - 1.0) * PI / k as f64;
        let s = 2.0 * 2f64.sqrt() / k as f64;
        return geom::scale(
            geom::add(geom::scale(u1, t.cos()), geom::scale(u2, t.sin())),
            s,
        );
    }
    let c = chord(jets);
    let n = geom::normalize(geom::cross(u1, u2));
    geom::sub(c, geom::scale(n, geom::dot(c, n)))
}

/// The fill's limit points, limit tangents and fan positions, each computed once per vertex:
/// at a vertex of valence `n` each is an `O(n)` stencil or walk, and the vertex has `n` edges
/// to fill (`n^2` when asked per edge).
#[derive(Default)]
struct Jets {
    limits: HashMap<usize, Point>,
    tangents: HashMap<usize, (Point, Point)>,
    /// Position of each outgoing half-edge in its vertex's fan, for the fans walked so far.
    fan: HashMap<u32, usize>,
    /// The number of outgoing half-edges of each vertex walked.
    fan_len: HashMap<usize, usize>,
}

impl Jets {
    fn limit(&mut self, level: &Level, v: usize) -> Point {
        *self
            .limits
            .entry(v)
            .or_insert_with(|| NonBox::limit_stencil(&level.net, v).apply(&level.points))
    }

    fn tangents(&mut self, level: &Level, v: usize) -> (Point, Point) {
        *self.tangents.entry(v).or_insert_with(|| {
            let (t1, t2) = NonBox::tangent_stencils(&level.net, v);
            (t1.apply(&level.points), t2.apply(&level.points))
        })
    }

    /// The position of `g` among `v`'s outgoing half-edges (0 when it is not one), and their
    /// number.
    fn fan_index(&mut self, m: &PolyMesh, v: usize, g: u32) -> (usize, usize) {
        let fan = &mut self.fan;
        let k = *self.fan_len.entry(v).or_insert_with(|| {
            let mut k = 0;
            for (j, h) in m.outgoing(v).enumerate() {
                fan.insert(h, j);
                k = j + 1;
            }
            k
        });
        (self.fan.get(&g).copied().unwrap_or(0), k)
    }
}

/// The other boundary neighbour of boundary vertex `v` (not `w`), or the ghost `2 v - w` at a
/// corner (a vertex with one face).
fn boundary_continuation(level: &Level, v: usize, w: usize) -> Point {
    let m = &level.net.mesh;
    let pos = &level.points;
    let nb = m.vertex_neighbors(v);
    if crate::schemes::nonbox::sharp::is_corner(m, v) {
        return geom::sub(geom::scale(pos[v], 2.0), pos[w]);
    }
    let (first, last) = (nb[0] as usize, nb[nb.len() - 1] as usize);
    pos[if first == w { last } else { first }]
}

/// The fill curve of edge `a -> b` (see the [module](self) documentation).
fn fill_edge(level: &Level, jets: &mut Jets, a: usize, b: usize) -> [Point; 4] {
    let m = &level.net.mesh;
    let pos = &level.points;
    let h = m.find_halfedge(a, b).or_else(|| m.find_halfedge(b, a));
    if let Some(h) = h
        && m.he_twin(h).is_none()
    {
        let d = [
            boundary_continuation(level, a, b),
            pos[a],
            pos[b],
            boundary_continuation(level, b, a),
        ];
        return cubic_bspline_to_bezier(&d);
    }
    let p0 = jets.limit(level, a);
    let p3 = jets.limit(level, b);
    let d0 = edge_derivative(level, jets, a, b);
    let d3 = edge_derivative(level, jets, b, a);
    [
        p0,
        geom::axpy(p0, 1.0 / 3.0, d0),
        geom::axpy(p3, 1.0 / 3.0, d3),
        p3,
    ]
}

/// The Coons fill of the marked cells of the last level.
pub(super) fn fill(
    level: &Level,
    marked: &[(u32, Tag)],
    curves: &mut Curves<4>,
    out: &mut PatchComplex,
) {
    let m = &level.net.mesh;
    let mut jets = Jets::default();
    for &(f, tag) in marked {
        let c = m.face(f as usize);
        let mut edge = |k: usize| -> [Point; 4] {
            edge_curve(curves, c[k], c[(k + 1) % 4], |a, b| {
                fill_edge(level, &mut jets, a, b)
            })
        };
        let v0 = edge(0);
        let u1 = edge(1);
        let mut v1 = edge(2);
        v1.reverse();
        let mut u0 = edge(3);
        u0.reverse();
        let element = tag.element.unwrap_or(Element::Vertex(c[0]));
        // the fill patch has the cell's own corners: its domain is the cell
        out.push_in(
            BezierPatch::coons(3, &v0, &u1, &v1, &u0),
            Provenance::Cap {
                element,
                sector: tag.sector,
            },
            tag.domain,
        );
        if m.extras().is_some() {
            // sides on the boundary of a net with sharp features (crease sides or the
            // boundary) and on a crease left inside the surface
            let h0 = m.face_halfedge(f as usize);
            let sides = [Side::V0, Side::U1, Side::V1, Side::U0];
            for (k, side) in sides.into_iter().enumerate() {
                let h = h0 + k as u32;
                let crease = level
                    .uncut
                    .as_ref()
                    .is_some_and(|u| u[m.he_edge(h) as usize]);
                if m.he_twin(h).is_none() || crease {
                    out.mark_sharp(out.len() - 1, side.index());
                }
            }
        }
    }
}
