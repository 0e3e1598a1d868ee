//! One ternary step on a bi-2 net with knot widths: the vertex classification, the vertex,
//! edge and face children (blossoms of the split pieces), the extraordinary vertex rule (18),
//! the boundary phantoms, and the limit stencils.

use super::*;
use crate::mesh::NONE;
use crate::mesh::ternary_split::{self, TernaryCell, TernarySplit};

/// The kind of a vertex for ternary refinement.
#[derive(Debug, Clone, Copy, PartialEq)]
enum VKind {
    /// Interior, valence 4.
    Regular,
    /// Interior, valence `n != 4` (`n >= 3`).
    Extraordinary,
    /// Boundary with two quads.
    Boundary,
    /// Boundary with one quad.
    Corner,
}

fn classify(mesh: &PolyMesh, name: &str) -> Result<Vec<VKind>> {
    for f in 0..mesh.num_faces() {
        if mesh.face_size(f) != 4 {
            return Err(Error::Unsupported(format!(
                "face {f} has {} sides; {name} refines quad nets (q-nets): apply one \
                 Catmull-Clark step first (fairsub subdivide --scheme {} --levels 1), \
                 or use {} or {}, which take n-gons",
                mesh.face_size(f),
                ids::CATMULL_CLARK,
                ids::PGS,
                ids::BI2_MIXED
            )));
        }
    }
    (0..mesh.num_vertices())
        .map(|v| {
            let k = mesh.outgoing(v).count();
            if mesh.is_boundary_vertex(v) {
                match k {
                    1 => Ok(VKind::Corner),
                    2 => Ok(VKind::Boundary),
                    _ => Err(Error::Unsupported(format!(
                        "vertex {v} is a boundary vertex with {k} quads; {name} has no rules for \
                         extraordinary boundary vertices (way out: {} or {}, whose \
                         boundary rules take them)",
                        ids::PGS,
                        ids::DOO_SABIN
                    ))),
                }
            } else {
                match k {
                    4 => Ok(VKind::Regular),
                    k if k >= 3 => Ok(VKind::Extraordinary),
                    _ => Err(Error::Unsupported(format!(
                        "vertex {v} is an interior vertex of valence {k}; {name} needs valence \
                         at least 3 (no primal step changes a valence: one {} step removes it, \
                         then one {} step makes the net quads again, as --prepare auto does)",
                        ids::DOO_SABIN,
                        ids::CATMULL_CLARK
                    ))),
                }
            }
        })
        .collect()
}

/// Weighted 3x3 tensor rule over a grid of vertex indices: `grid[ku][kv]`.
fn tensor3(grid: &[[u32; 3]; 3], wu: [f64; 3], wv: [f64; 3], out: &mut Stencil) {
    for (ku, col) in grid.iter().enumerate() {
        for (kv, &x) in col.iter().enumerate() {
            let w = wu[ku] * wv[kv];
            if w != 0.0 {
                out.add(x as usize, w);
            }
        }
    }
}

/// The 3x3 grid `grid[ku][kv]` of a regular, boundary or corner vertex with the knot widths
/// of its three pieces along `u` and along `v` (phantoms are copies with mirrored widths). `u`
/// runs along the vertex's first outgoing half-edge (the boundary half-edge on the boundary),
/// `v` counter-clockwise from it.
fn vertex_grid(
    mesh: &PolyMesh,
    w: &Widths,
    v: usize,
    kind: VKind,
) -> ([[u32; 3]; 3], [f64; 3], [f64; 3]) {
    let hs: Vec<u32> = mesh.outgoing(v).collect();
    let to = |h: u32| mesh.he_to(h);
    let diag = |h: u32| mesh.he_to(mesh.he_next(h));
    let vi = v as u32;
    match kind {
        VKind::Regular => {
            let [h0, h1, h2, h3] = [hs[0], hs[1], hs[2], hs[3]];
            let grid = [
                [diag(h2), to(h2), diag(h1)],
                [to(h3), vi, to(h1)],
                [diag(h3), to(h0), diag(h0)],
            ];
            let wu = [w[h2 as usize][1], w[h0 as usize][0], w[h0 as usize][1]];
            let wv = [w[h3 as usize][1], w[h1 as usize][0], w[h1 as usize][1]];
            (grid, wu, wv)
        }
        VKind::Boundary => {
            // u along the boundary (bl, v, br), v inwards (phantom, v, in).
            let (h0, h1) = (hs[0], hs[1]);
            let p1 = mesh.he_prev(h1);
            let bl = mesh.he_from(p1);
            let grid = [
                [bl, bl, diag(h1)],
                [vi, vi, to(h1)],
                [to(h0), to(h0), diag(h0)],
            ];
            let wu = [w[p1 as usize][0], w[h0 as usize][0], w[h0 as usize][1]];
            let wi = w[h1 as usize][0];
            (grid, wu, [wi, wi, w[h1 as usize][1]])
        }
        VKind::Corner => {
            let h0 = hs[0];
            let p0 = mesh.he_prev(h0);
            let (u1, u2, x) = (to(h0), mesh.he_from(p0), diag(h0));
            let grid = [[vi, vi, u2], [vi, vi, u2], [u1, u1, x]];
            let wa = w[h0 as usize][0];
            let wb = w[p0 as usize][1];
            (
                grid,
                [wa, wa, w[h0 as usize][1]],
                [wb, wb, w[p0 as usize][0]],
            )
        }
        VKind::Extraordinary => unreachable!("extraordinary vertices have no grid"),
    }
}

/// The vertex child of a regular, boundary or corner vertex: middle x middle over its grid.
fn vertex_child_regular(mesh: &PolyMesh, w: &Widths, v: usize, kind: VKind, e: f64) -> Stencil {
    let (grid, wu, wv) = vertex_grid(mesh, w, v, kind);
    let mut s = Stencil::new();
    tensor3(
        &grid,
        middle_child_weights(wu[0], wu[1], wu[2], e),
        middle_child_weights(wv[0], wv[1], wv[2], e),
        &mut s,
    );
    s.merged()
}

/// The exact bi-2 patch (nine coefficient stencils, row-major, `u` along the vertex's first
/// outgoing half-edge) of a vertex of a ternary net with knot widths `w`, when the vertex is
/// regular (four quads), a boundary vertex with two quads or a corner; `None` otherwise.
pub fn regular_patch(mesh: &PolyMesh, w: &Widths, v: usize) -> Option<Vec<Stencil>> {
    if mesh
        .vertex_faces(v)
        .iter()
        .any(|&f| mesh.face_size(f as usize) != 4)
    {
        return None;
    }
    let k = mesh.outgoing(v).count();
    let kind = match (mesh.is_boundary_vertex(v), k) {
        (false, 4) => VKind::Regular,
        (true, 2) => VKind::Boundary,
        (true, 1) => VKind::Corner,
        _ => return None,
    };
    let (grid, wu, wv) = vertex_grid(mesh, w, v, kind);
    let net: [[Stencil; 3]; 3] =
        std::array::from_fn(|a| std::array::from_fn(|b| Stencil::point(grid[a][b] as usize)));
    Some(crate::schemes::bi2::bi2_patch_stencils(&net, wu, wv))
}

/// Rule (18) at an extraordinary vertex.
fn vertex_child_extraordinary(
    mesh: &PolyMesh,
    w: &Widths,
    v: usize,
    rules: &TernaryRules,
) -> Result<Stencil> {
    let hs: Vec<u32> = mesh.outgoing(v).collect();
    let n = hs.len();
    let h1 = w[hs[0] as usize][1] / w[hs[0] as usize][0];
    let (a1, a2) = rules.alphas(n, h1)?;
    let mut s = Stencil::new();
    s.add(v, 1.0 - a1 - a2);
    for &h in &hs {
        s.add(mesh.he_to(h) as usize, a1 / n as f64);
        s.add(mesh.he_to(mesh.he_next(h)) as usize, a2 / n as f64);
    }
    Ok(s.merged())
}

/// The edge child of half-edge `h` (`v -> w`) next to `v`: end (along) x middle (across).
fn edge_child(mesh: &PolyMesh, w: &Widths, h: u32, e: f64) -> Stencil {
    let (v, x) = (mesh.he_from(h), mesh.he_to(h));
    let hi = h as usize;
    let t = end_child_weight(w[hi][0], w[hi][1], e);
    // Left face (of h): v's other neighbour yl, x's other neighbour xl.
    let p = mesh.he_prev(h);
    let yl = mesh.he_from(p);
    let xl = mesh.he_to(mesh.he_next(h));
    let wc = w[p as usize][1];
    let wl = w[p as usize][0];
    let (yr, xr, wr) = match mesh.he_twin(h) {
        Some(tw) => {
            let nt = mesh.he_next(tw);
            (
                mesh.he_to(nt),
                mesh.he_from(mesh.he_prev(tw)),
                w[nt as usize][1],
            )
        }
        // Boundary edge: the phantom side copies the edge (mirrored width).
        None => (v, x, wc),
    };
    let m = middle_child_weights(wr, wc, wl, e);
    let mut s = Stencil::new();
    for (k, (a, b)) in [(yr, xr), (v, x), (yl, xl)].into_iter().enumerate() {
        s.add(a as usize, (1.0 - t) * m[k]);
        s.add(b as usize, t * m[k]);
    }
    s.merged()
}

/// The face child of corner `h` (next to `from(h)`) of a quad: end x end.
fn face_child(mesh: &PolyMesh, w: &Widths, h: u32, e: f64) -> Stencil {
    let p = mesh.he_prev(h);
    let t1 = end_child_weight(w[h as usize][0], w[h as usize][1], e);
    let t2 = end_child_weight(w[p as usize][1], w[p as usize][0], e);
    let (v, w1, x, w2) = (
        mesh.he_from(h),
        mesh.he_to(h),
        mesh.he_to(mesh.he_next(h)),
        mesh.he_from(p),
    );
    Stencil::from_pairs([
        (v as usize, (1.0 - t1) * (1.0 - t2)),
        (w1 as usize, t1 * (1.0 - t2)),
        (w2 as usize, (1.0 - t1) * t2),
        (x as usize, t1 * t2),
    ])
}

/// One ternary step of a quad net with knot widths: the child net, its stencils and its
/// widths, on the mesh layer's ternary split ([`TernarySplit`], whose layout the child keeps):
/// vertex children `0..V` (child `v` of vertex `v`); edge children `V + 2e + k` (`k = 0` next
/// to the start of the edge's half-edge, `1` next to its end); face children `V + 2E + h`
/// (next to the start of half-edge `h`); then the boundary layer.
///
/// # Errors
/// [`Error::Unsupported`] for non-quad faces, boundary vertices with more than two quads and
/// interior vertices of valence 2, naming the element and the way out.
pub fn ternary_step(
    mesh: &PolyMesh,
    widths: &Widths,
    rules: &TernaryRules,
    name: &str,
) -> Result<(Refinement, Widths)> {
    let kinds = classify(mesh, name)?;
    // The child points and faces (the boundary layer's numbering among them).
    let split = TernarySplit::new(mesh);
    check_child_size(name, split.num_points)?;
    let mut rows: Vec<Stencil> = Vec::with_capacity(split.num_points);
    primal_rows(mesh, widths, rules, &kinds, &mut rows)?;
    boundary_layer_rows(mesh, widths, &kinds, &split.outer_edge, rules.e, &mut rows);
    debug_assert_eq!(rows.len(), split.num_points);
    let table = StencilTable::from_rows(mesh.num_vertices(), rows, 9);
    let cw = child_widths(mesh, widths, &split.cells, split.corners.len(), rules.e);
    let r = finish_refinement(mesh, table, split.face_start, split.corners)?;
    Ok((r, cw))
}

/// The stencils of the children of the net's own elements, in the split's order: vertex
/// children, the two children of each edge, the child of each face corner.
fn primal_rows(
    mesh: &PolyMesh,
    widths: &Widths,
    rules: &TernaryRules,
    kinds: &[VKind],
    rows: &mut Vec<Stencil>,
) -> Result<()> {
    let e = rules.e;
    for (v, &kind) in kinds.iter().enumerate() {
        rows.push(match kind {
            VKind::Extraordinary => vertex_child_extraordinary(mesh, widths, v, rules)?,
            k => vertex_child_regular(mesh, widths, v, k, e),
        });
    }
    for ei in 0..mesh.num_edges() {
        let h = mesh.edge_halfedge(ei);
        rows.push(edge_child(mesh, widths, h, e));
        let back = mesh.he_twin(h);
        rows.push(match back {
            Some(t) => edge_child(mesh, widths, t, e),
            None => edge_child_reversed_boundary(mesh, widths, h, e),
        });
    }
    for h in 0..mesh.num_halfedges() as u32 {
        rows.push(face_child(mesh, widths, h, e));
    }
    Ok(())
}

/// The stencils of the boundary layer, in the split's order: the middle children of boundary
/// and corner vertices (a corner's two and itself), then the two end children of each
/// boundary edge's outer edge.
fn boundary_layer_rows(
    mesh: &PolyMesh,
    widths: &Widths,
    kinds: &[VKind],
    outer_edge: &[u32],
    e: f64,
    rows: &mut Vec<Stencil>,
) {
    for (v, &kind) in kinds.iter().enumerate() {
        match kind {
            VKind::Boundary => {
                let hs: Vec<u32> = mesh.outgoing(v).collect();
                let p1 = mesh.he_prev(hs[1]);
                let (bl, br) = (mesh.he_from(p1), mesh.he_to(hs[0]));
                let m = middle_child_weights(
                    widths[p1 as usize][0],
                    widths[hs[0] as usize][0],
                    widths[hs[0] as usize][1],
                    e,
                );
                rows.push(Stencil::from_pairs([
                    (bl as usize, m[0]),
                    (v, m[1]),
                    (br as usize, m[2]),
                ]));
            }
            VKind::Corner => {
                let h0 = mesh.vertex_halfedge(v);
                let p0 = mesh.he_prev(h0);
                let wa = widths[h0 as usize][0];
                let m = middle_child_weights(wa, wa, widths[h0 as usize][1], e);
                rows.push(Stencil::from_pairs([
                    (v, m[0] + m[1]),
                    (mesh.he_to(h0) as usize, m[2]),
                ]));
                let wb = widths[p0 as usize][1];
                let m = middle_child_weights(wb, wb, widths[p0 as usize][0], e);
                rows.push(Stencil::from_pairs([
                    (v, m[0] + m[1]),
                    (mesh.he_from(p0) as usize, m[2]),
                ]));
                rows.push(Stencil::point(v));
            }
            _ => {}
        }
    }
    for (ei, &oe) in outer_edge.iter().enumerate() {
        if oe == NONE {
            continue;
        }
        let h = mesh.edge_halfedge(ei) as usize;
        let (a, b) = (
            mesh.he_from(h as u32) as usize,
            mesh.he_to(h as u32) as usize,
        );
        let t = end_child_weight(widths[h][0], widths[h][1], e);
        rows.push(Stencil::from_pairs([(a, 1.0 - t), (b, t)]));
        let t = end_child_weight(widths[h][1], widths[h][0], e);
        rows.push(Stencil::from_pairs([(b, 1.0 - t), (a, t)]));
    }
}

/// The child knot widths, per child face corner: `(along, across)` for each side, read off
/// the chart of the cell's parent face.
fn child_widths(
    mesh: &PolyMesh,
    widths: &Widths,
    cells: &[TernaryCell],
    num_corners: usize,
    e: f64,
) -> Widths {
    let sigma = 1.0 - 2.0 * e;
    let chart = |f: usize, k: usize| chart_widths(mesh, widths, f, k, e);
    let mut cw: Widths = Vec::with_capacity(num_corners);
    let mut inner: (u32, ChartWidths) = (NONE, ([[0.0; 4]; 4], [[0.0; 4]; 4]));
    for &cell in cells {
        match cell {
            TernaryCell::Inner { face, i, j } => {
                // (a face's nine cells come together: its chart once)
                if inner.0 != face {
                    inner = (face, chart(face as usize, 0));
                }
                let (uw, vw) = &inner.1;
                let (i, j) = (i as usize, j as usize);
                cw.extend_from_slice(&[
                    [uw[i][j], uw[i + 1][j]],
                    [vw[i + 1][j], vw[i + 1][j + 1]],
                    [uw[i + 1][j + 1], uw[i][j + 1]],
                    [vw[i][j + 1], vw[i][j]],
                ]);
            }
            TernaryCell::Strip { edge, q } => {
                let h = mesh.edge_halfedge(edge as usize);
                let f = mesh.he_face(h) as usize;
                let (uw, vw) = chart(f, (h - mesh.face_halfedge(f)) as usize);
                let q = q as usize;
                let along = [uw[0][0], uw[1][0], uw[2][0], uw[3][0]];
                let across_row = [vw[0][0], vw[1][0], vw[2][0], vw[3][0]];
                // the outer children are end pieces across: e times the parent's width across
                let across_out = across_row.map(|x| x / sigma * e);
                cw.extend_from_slice(&[
                    [along[q], along[q + 1]],
                    [across_out[q + 1], across_row[q + 1]],
                    [along[q + 1], along[q]],
                    [across_row[q], across_out[q]],
                ]);
            }
            TernaryCell::Corner(v) => {
                let h0 = mesh.vertex_halfedge(v as usize);
                let f = mesh.he_face(h0) as usize;
                let (uw, vw) = chart(f, (h0 - mesh.face_halfedge(f)) as usize);
                let (wu, wv) = (uw[0][0] / sigma, vw[0][0] / sigma);
                cw.extend_from_slice(&[
                    [e * wu, sigma * wu],
                    [e * wv, sigma * wv],
                    [sigma * wu, e * wu],
                    [sigma * wv, e * wv],
                ]);
            }
        }
    }
    cw
}

/// The knot widths of the 4 x 4 child points of quad `f` in its chart rotated to start at
/// corner `k` ([`ternary_split::grid`]): along `u` and along `v`, each the parent's width of
/// the piece times `1 - 2e` (the end pieces) or `e` (the middle ones).
fn chart_widths(mesh: &PolyMesh, widths: &Widths, f: usize, k: usize, e: f64) -> ChartWidths {
    let sigma = 1.0 - 2.0 * e;
    let h0f = mesh.face_halfedge(f);
    let hk = |j: usize| h0f + ((k + j) % 4) as u32;
    let (h0, h1, h2, h3) = (hk(0), hk(1), hk(2), hk(3));
    let wd = |h: u32, i: usize| widths[h as usize][i];
    let wu = [wd(h0, 0), wd(h0, 1), wd(h2, 0), wd(h2, 1)];
    let wv = [wd(h3, 1), wd(h1, 0), wd(h1, 1), wd(h3, 0)];
    let mut uw = [[0.0; 4]; 4];
    let mut vw = [[0.0; 4]; 4];
    for i in 0..4 {
        for j in 0..4 {
            let c = match (i >= 2, j >= 2) {
                (false, false) => 0,
                (true, false) => 1,
                (true, true) => 2,
                (false, true) => 3,
            };
            let fu = if i == 0 || i == 3 { sigma } else { e };
            let fv = if j == 0 || j == 3 { sigma } else { e };
            uw[i][j] = fu * wu[c];
            vw[i][j] = fv * wv[c];
        }
    }
    (uw, vw)
}

/// Index of the edge child of [`ternary_step`] on the edge of half-edge `h`, next to `from(h)`
/// (`near_from`) or to `to(h)`.
pub fn edge_child_index(mesh: &PolyMesh, h: u32, near_from: bool) -> usize {
    ternary_split::edge_child(mesh, h, near_from) as usize
}

/// Index of the face child of [`ternary_step`] next to `from(h)` in the face of `h`.
pub fn face_child_index(mesh: &PolyMesh, h: u32) -> usize {
    ternary_split::face_child(mesh, h) as usize
}

/// The knot widths of a face's 4 x 4 child points in its chart, along `u` and along `v`.
type ChartWidths = ([[f64; 4]; 4], [[f64; 4]; 4]);

/// The edge child next to the end of boundary half-edge `h` (`a -> b`, no twin): the mirror of
/// [`edge_child`] for the reversed direction, whose phantom side is the edge itself.
fn edge_child_reversed_boundary(mesh: &PolyMesh, w: &Widths, h: u32, e: f64) -> Stencil {
    let hi = h as usize;
    let (a, b) = (mesh.he_from(h), mesh.he_to(h));
    let t = end_child_weight(w[hi][1], w[hi][0], e);
    // Across at b: inside the face the neighbour of b is to(next(h)); of a, from(prev(h)).
    let nx = mesh.he_next(h);
    let p = mesh.he_prev(h);
    let (yb, ya) = (mesh.he_to(nx), mesh.he_from(p));
    let wc = w[nx as usize][0];
    let wi = w[nx as usize][1];
    let m = middle_child_weights(wc, wc, wi, e);
    let mut s = Stencil::new();
    for (k, (x, y)) in [(b, a), (b, a), (yb, ya)].into_iter().enumerate() {
        s.add(x as usize, (1.0 - t) * m[k]);
        s.add(y as usize, t * m[k]);
    }
    s.merged()
}

/// Limit stencils of a uniform ternary net (TPS): (21) at extraordinary vertices, the centre
/// value of the vertex's bi-2 patch elsewhere.
pub(super) fn ternary_limit_stencils(mesh: &PolyMesh, name: &str) -> Result<StencilTable> {
    let kinds = classify(mesh, name)?;
    let nv = mesh.num_vertices();
    let mut table = StencilTable::with_capacity(nv, nv, 9);
    for (v, &kind) in kinds.iter().enumerate() {
        let s = match kind {
            VKind::Extraordinary => {
                let hs: Vec<u32> = mesh.outgoing(v).collect();
                let n = hs.len();
                let p = TpsParams::new(n)?;
                let mut s = Stencil::new();
                s.add(v, 1.0 - p.tau1 - p.tau2);
                for &h in &hs {
                    s.add(mesh.he_to(h) as usize, p.tau1 / n as f64);
                    s.add(mesh.he_to(mesh.he_next(h)) as usize, p.tau2 / n as f64);
                }
                s.merged()
            }
            k => {
                // The centre value of the bi-2 patch: (1, 6, 1) / 8 in both directions, which
                // is the middle rule with e -> 1/2 (a sub-piece of width 0 at the centre).
                vertex_child_regular(mesh, &uniform_widths(mesh), v, k, 0.5)
            }
        };
        table.push(s);
    }
    Ok(table)
}
