//! Acceptance tests of non-box subdivision: the regular mask (3), the published spectrum, limit
//! and tangent formulas, non-negative weights, both variants giving the same surface, the
//! boundary rules, the Bezier table, FCV files and the characteristic-map certificates.

use fairsub::PolyMesh;
use fairsub::analysis::nonbox as anb;
use fairsub::geom::{self, Point};
use fairsub::io::fcv::{choose_fcv_net, fcv_net_from_file, fcv_obj_string, parse_fcv_obj};
use fairsub::schemes::nonbox::bezier::{cell_triangles, eval_triangle};
use fairsub::schemes::nonbox::fourdir::{FourDirNet, classify, triangulate};
use fairsub::schemes::nonbox::mask::{
    PeriodicGrid, derived_block, printed_block, vector_subdivide,
};
use fairsub::schemes::nonbox::{FcvNet, NonBox, NonBox4Dir, a_k, step_stencils};
use std::f64::consts::PI;

/// A small deterministic pseudo-random generator (integers, so dyadic arithmetic stays exact).
struct Lcg(u64);

impl Lcg {
    fn int(&mut self, lo: i64, hi: i64) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        let r = (self.0 >> 33) as i64;
        (lo + r.rem_euclid(hi - lo + 1)) as f64
    }
    fn point(&mut self) -> Point {
        [self.int(-40, 40), self.int(-40, 40), self.int(-40, 40)]
    }
}

/// An `n x n` torus grid: vertex `(i, j)` is `j n + i`, face `(i, j)` (lower-left corner
/// `(i, j)`) is `j n + i`.
fn torus(n: usize, rng: &mut Lcg) -> FcvNet {
    let id = |i: usize, j: usize| (j % n) * n + (i % n);
    let pos: Vec<Point> = (0..n * n).map(|_| rng.point()).collect();
    let mut faces = Vec::new();
    for j in 0..n {
        for i in 0..n {
            faces.push(vec![id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    let mesh = PolyMesh::new(pos, &faces).unwrap();
    let fcv = (0..n * n).map(|_| rng.point()).collect();
    FcvNet::new(mesh, fcv).unwrap()
}

/// An open `m x m` grid with vertices at `(i, j, z)`, FCVs at the cell centres with random
/// heights (x, y are the parameters: the scheme reproduces linear functions).
fn open_grid(m: usize, rng: &mut Lcg) -> FcvNet {
    let gid = |i: usize, j: usize| j * (m + 1) + i;
    let mut pos = Vec::new();
    for j in 0..=m {
        for i in 0..=m {
            pos.push([i as f64, j as f64, rng.int(-8, 8) / 4.0]);
        }
    }
    let mut faces = Vec::new();
    let mut fcv = Vec::new();
    for j in 0..m {
        for i in 0..m {
            faces.push(vec![
                gid(i, j),
                gid(i + 1, j),
                gid(i + 1, j + 1),
                gid(i, j + 1),
            ]);
            fcv.push([i as f64 + 0.5, j as f64 + 0.5, rng.int(-8, 8) / 4.0]);
        }
    }
    FcvNet::new(PolyMesh::new(pos, &faces).unwrap(), fcv).unwrap()
}

fn perturbed(net: FcvNet, rng: &mut Lcg) -> FcvNet {
    let mut n = net;
    for p in &mut n.fcv {
        for c in p.iter_mut() {
            *c += rng.int(-4, 4) / 16.0;
        }
    }
    n
}

fn max_dist(a: &[Point], b: &[Point]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(p, q)| geom::dist(*p, *q))
        .fold(0.0, f64::max)
}

// ---------------------------------------------------------------------------------------------
// Rules and the regular mask

#[test]
fn a_k_is_proposition_1() {
    assert_eq!(a_k(3), 0.75);
    assert!((a_k(4) - 0.5).abs() < 1e-15);
    for k in 4..=30 {
        let l = 0.5 + 0.25 * (2.0 * PI / k as f64).cos();
        assert!((a_k(k) - (0.75 - l * l)).abs() < 1e-15);
        // The G^1 range of Section 4: (1 - cos(2 pi / k)) / 4 < a_k <= 3/4.
        assert!(a_k(k) > 0.25 - 0.25 * (2.0 * PI / k as f64).cos() && a_k(k) <= 0.75);
    }
}

#[test]
fn regular_refinement_is_vector_subdivision_of_mask_3() {
    let n = 6;
    let mut rng = Lcg(7);
    let net = torus(n, &mut rng);
    let m = &net.mesh;
    // Mask coordinates: vertex (i, j) at b = (i, j); the FCV at b - (1/2, 1/2) is that of the
    // face with lower-left corner (i - 1, j - 1).
    let fid =
        |i: i64, j: i64| (j.rem_euclid(n as i64) as usize) * n + i.rem_euclid(n as i64) as usize;
    let data = PeriodicGrid {
        n,
        vertex: (0..n * n).map(|k| m.position(k)).collect(),
        fcv: (0..n * n)
            .map(|k| {
                let (i, j) = ((k % n) as i64, (k / n) as i64);
                net.fcv[fid(i - 1, j - 1)]
            })
            .collect(),
    };
    let fine = vector_subdivide(derived_block, &data);
    let step = NonBox::step(&net).unwrap();
    let pts = step.net.points();
    let (nv, ne) = (m.num_vertices(), m.num_edges());
    let vid = |i: i64, j: i64| fid(i, j);
    let edge = |a: usize, b: usize| {
        let h = m
            .find_halfedge(a, b)
            .or_else(|| m.find_halfedge(b, a))
            .unwrap();
        m.he_edge(h) as usize
    };
    let nc = nv + ne + m.num_faces();
    let mut checked = 0;
    for ay in 0..2 * n as i64 {
        for ax in 0..2 * n as i64 {
            let k = (ay as usize) * 2 * n + ax as usize;
            // Fine vertex at the coarse point (ax / 2, ay / 2).
            let child = match (ax % 2, ay % 2) {
                (0, 0) => vid(ax / 2, ay / 2),
                (1, 0) => nv + edge(vid((ax - 1) / 2, ay / 2), vid((ax + 1) / 2, ay / 2)),
                (0, 1) => nv + edge(vid(ax / 2, (ay - 1) / 2), vid(ax / 2, (ay + 1) / 2)),
                _ => nv + ne + fid((ax - 1) / 2, (ay - 1) / 2),
            };
            assert_eq!(fine.vertex[k], pts[child], "vertex {ax} {ay}");
            // Fine FCV: the fine cell with lower-left fine corner (ax - 1, ay - 1); its corner
            // with even coordinates is the parent vertex, the coarse cell containing it the
            // parent face; the child FCV is that of the parent corner.
            let (cx, cy) = (ax - 1, ay - 1);
            let (px, py) = (
                if cx.rem_euclid(2) == 0 { cx } else { cx + 1 },
                if cy.rem_euclid(2) == 0 { cy } else { cy + 1 },
            );
            let v0 = vid(px.div_euclid(2), py.div_euclid(2));
            let f0 = fid(cx.div_euclid(2), cy.div_euclid(2));
            let h0 = m.face_halfedge(f0);
            let h = (h0..h0 + 4).find(|&h| m.he_from(h) as usize == v0).unwrap();
            assert_eq!(fine.fcv[k], pts[nc + h as usize], "fcv {ax} {ay}");
            checked += 2;
        }
    }
    assert_eq!(checked, 2 * 4 * n * n);
}

#[test]
fn printed_mask_3_differs_from_the_generators_in_two_blocks() {
    let mut differ = Vec::new();
    let mut sum_printed = [[0i32; 2]; 2];
    let mut sum_derived = [[0i32; 2]; 2];
    for y in -3..=3 {
        for x in -3..=3 {
            let (p, d) = (printed_block([x, y]), derived_block([x, y]));
            if p != d {
                differ.push(([x, y], p, d));
            }
            for i in 0..2 {
                for j in 0..2 {
                    sum_printed[i][j] += p[i][j];
                    sum_derived[i][j] += d[i][j];
                }
            }
        }
    }
    // A_(0,0) and A_(0,1): second rows printed (0, 1/8), derived (1/4, 1/2) and (1/4, 1/4).
    assert_eq!(
        differ,
        vec![
            ([0, 0], [[4, 1], [0, 1]], [[4, 1], [2, 4]]),
            ([0, 1], [[1, 0], [0, 1]], [[1, 0], [2, 2]]),
        ]
    );
    // The derived mask sums to [3 2; 1 2] (eigenvalues 1 and 4, eigenvector (2/3, 1/3) = the
    // integrals of the generators); the printed one to [3 2; 1/2 3/2], which has no eigenvalue 4.
    assert_eq!(sum_derived, [[24, 16], [8, 16]]);
    assert_eq!(sum_printed, [[24, 16], [4, 12]]);
    // Subdivision with the printed mask does not keep constants; the derived one does.
    let n = 4;
    let ones = PeriodicGrid {
        n,
        vertex: vec![[1.0; 3]; n * n],
        fcv: vec![[1.0; 3]; n * n],
    };
    let d = vector_subdivide(derived_block, &ones);
    assert!(d.vertex.iter().chain(&d.fcv).all(|p| *p == [1.0; 3]));
    let p = vector_subdivide(printed_block, &ones);
    assert!(p.vertex.iter().chain(&p.fcv).any(|q| *q != [1.0; 3]));
}

#[test]
fn rules_reproduce_the_paper_formulas_on_a_cube() {
    let net = FcvNet::barycentric(fairsub::gallery::cube());
    let st = step_stencils(&net.mesh);
    let pts = net.points();
    let out = st.apply(&pts);
    // Vertex (-1,-1,-1), valence 3: (1 - 3/4) V + (3/4)/3 sum of its three face centres.
    let v = 0;
    let fs = net.mesh.vertex_faces(v);
    let mut expect = geom::scale(pts[v], 0.25);
    for f in fs {
        expect = geom::axpy(expect, 0.25, net.fcv[f as usize]);
    }
    assert!(geom::dist(out[v], expect) < 1e-15);
    // Every row is affine.
    assert!(st.max_affine_defect() < 1e-15);
}

// ---------------------------------------------------------------------------------------------
// Analysis (Section 4)

#[test]
fn blocks_and_eigenvalues_are_the_published_ones_for_k_3_to_12() {
    for k in 3..=12 {
        let lm = anb::local_matrix(k).unwrap();
        assert_eq!(lm.matrix.nrows(), 10 * k + 1);
        assert!(lm.rotation_defect() < 1e-15);
        let blocks = lm.fourier_blocks().unwrap();
        for b in &blocks {
            let m = b.frequency;
            let printed = if m == 0 {
                anb::published_b0(k).map(|x| fairsub::analysis::C64::new(x, 0.0))
            } else {
                anb::published_bm(k, m)
            };
            let dev = (&b.matrix - &printed)
                .iter()
                .fold(0.0f64, |d, z| d.max(z.norm()));
            assert!(dev < 1e-15, "k = {k}, m = {m}: block differs by {dev}");
            let p = anb::characteristic_polynomial(&b.matrix);
            let roots: Vec<_> = anb::block_eigenvalues(k, m)
                .into_iter()
                .map(|x| fairsub::analysis::C64::new(x, 0.0))
                .collect();
            let q = fairsub::analysis::poly_from_roots(&roots);
            for (x, y) in p.iter().zip(&q) {
                assert!((x - y).norm() < 1e-12, "k = {k}, m = {m}: {p:?} vs {q:?}");
            }
        }
        let spec = fairsub::analysis::spectrum(&lm.matrix);
        let lambda = 0.5 + 0.25 * (2.0 * PI / k as f64).cos();
        assert!((spec.dominant - 1.0).abs() < 1e-12);
        assert!(
            (spec.lambda - lambda).abs() < 1e-12,
            "k = {k}: {}",
            spec.lambda
        );
        assert_eq!(spec.lambda_multiplicity, 2, "k = {k}");
        // The printed eigenvalues are all there with at least their printed multiplicity.
        for m in 0..k {
            let full = anb::block_eigenvalues(k, m);
            let printed = anb::printed_block_eigenvalues(k, m);
            assert_eq!(full.len(), if m == 0 { 11 } else { 10 });
            for x in &printed {
                let need = printed.iter().filter(|&y| y == x).count();
                assert!(full.iter().filter(|&y| y == x).count() >= need);
            }
        }
        for c in anb::published_comparisons(k).unwrap() {
            if c.quantity.starts_with("sum of the printed") {
                assert!((c.difference - 0.125).abs() < 1e-12, "k = {k}: {c:?}");
            } else {
                assert!(c.difference < 1e-12, "k = {k}: {c:?}");
            }
        }
    }
}

#[test]
fn four_dir_local_matrix_is_the_same() {
    for k in [3, 4, 5, 7] {
        let a = anb::local_matrix(k).unwrap().matrix;
        let b = anb::local_matrix_4dir(k).unwrap().matrix;
        assert!((a - b).abs().max() < 1e-15);
    }
}

#[test]
fn limit_and_tangent_formulas_are_the_left_eigenvectors() {
    for k in 3..=12 {
        let lm = anb::local_matrix(k).unwrap();
        let l = lm.limit_stencil().unwrap();
        let f = anb::limit_point_formula(k);
        for (a, b) in l.iter().zip(&f) {
            assert!((a - b).abs() < 1e-12, "k = {k}");
        }
        let lambda = 0.5 + 0.25 * (2.0 * PI / k as f64).cos();
        assert!(anb::tangent_deviation(&lm, lambda) < 1e-10, "k = {k}");
        // The same stencils are what NonBox::limit_stencil uses on a mesh.
        let net = anb::local_fcv_net(k, 2);
        let labels = anb::labelled_points(&net.mesh, net.mesh.vertex_halfedge(0)).unwrap();
        let s = NonBox::limit_stencil(&net, 0);
        for &(i, w) in s.entries() {
            let pos = labels.iter().position(|&x| x == i as usize).unwrap();
            assert!((w - f[pos]).abs() < 1e-15);
        }
    }
}

#[test]
fn characteristic_maps_are_certified_injective_for_k_3_to_12() {
    for k in 3..=12 {
        let (ring, lambda) = anb::characteristic_ring(k).unwrap();
        assert_eq!(ring.len(), 36 * k);
        let cert = fairsub::analysis::certify::certify_ring(&ring, lambda);
        assert!(cert.injective, "k = {k}: {cert:?}");
    }
}

#[test]
fn all_weights_are_non_negative_for_every_k() {
    for k in 3..=20 {
        let mut nets = vec![
            anb::local_fcv_net(k, 3),
            FcvNet::barycentric(fairsub::gallery::prism(k)),
        ];
        // An open fan: boundary vertices with 1..k faces.
        let c = fairsub::gallery::cnet(k, fairsub::gallery::CnetShape::Saddle, 2);
        nets.push(FcvNet::barycentric(c));
        for net in &nets {
            for t in [step_stencils(&net.mesh), NonBox::limit_stencils(net)] {
                for r in 0..t.num_rows() {
                    let (_, w) = t.row(r);
                    assert!(w.iter().all(|&x| x >= 0.0), "k = {k}, row {r}: {w:?}");
                    assert!((w.iter().sum::<f64>() - 1.0).abs() < 1e-14);
                }
            }
        }
        let lm = anb::local_matrix(k).unwrap();
        assert!(lm.matrix.iter().all(|&x| x >= 0.0));
    }
    // Every larger k: the only weights that depend on k are 1 - a_k and a_k / k (V-vertex and
    // FCV rules) and the limit weights 1 / (1 + 4 a_k), 4 a_k / (k (1 + 4 a_k)); the others are
    // the constants 1/8 .. 1/2 checked above. Since (1/2 + cos(2 pi / k) / 4)^2 lies in
    // [1/16, 9/16], a_k lies in [3/16, 11/16] for k >= 4 (a_3 = 3/4), so all are non-negative.
    for k in 3..=100_000usize {
        let a = a_k(k);
        assert!((3.0 / 16.0..=0.75).contains(&a), "k = {k}: a_k = {a}");
        let kf = k as f64;
        for w in [
            1.0 - a,
            a / kf,
            1.0 / (1.0 + 4.0 * a),
            4.0 * a / (kf * (1.0 + 4.0 * a)),
        ] {
            assert!(w >= 0.0, "k = {k}");
        }
    }
    // Boundary NFCV rules of every kind on an open grid (corner faces included).
    let net = open_grid(3, &mut Lcg(1));
    let t = step_stencils(&net.mesh);
    for r in 0..t.num_rows() {
        assert!(t.row(r).1.iter().all(|&x| x >= 0.0));
    }
}

// ---------------------------------------------------------------------------------------------
// Variants, limits, boundaries

fn test_nets() -> Vec<FcvNet> {
    let mut rng = Lcg(11);
    vec![
        perturbed(FcvNet::barycentric(fairsub::gallery::cube()), &mut rng),
        FcvNet::barycentric(fairsub::gallery::tetrahedron()),
        perturbed(FcvNet::barycentric(fairsub::gallery::prism(5)), &mut rng),
        perturbed(
            FcvNet::barycentric(fairsub::gallery::torus_with_evs()),
            &mut rng,
        ),
        perturbed(FcvNet::barycentric(fairsub::gallery::open_pipe()), &mut rng),
        FcvNet::scaled(fairsub::gallery::cube(), 1.5).unwrap(),
    ]
}

#[test]
fn four_directional_and_quad_variants_give_the_same_points_and_limits() {
    for net in test_nets() {
        let mut quad = net.clone();
        let mut tri = triangulate(&net);
        for _ in 0..3 {
            quad = NonBox::step(&quad).unwrap().net;
            tri = NonBox4Dir::step(&tri).unwrap().0;
            assert_eq!(tri.mesh.num_vertices(), quad.num_points());
            assert!(max_dist(tri.mesh.positions(), &quad.points()) < 1e-12);
        }
        let lq = NonBox::limit_stencils(&quad).apply(&quad.points());
        let lt = NonBox4Dir::limit_stencils(&tri)
            .unwrap()
            .apply(tri.mesh.positions());
        assert!(max_dist(&lq, &lt) < 1e-12);
        // The types are recovered from the refined triangle mesh alone.
        let t = classify(&tri.mesh).unwrap();
        assert_eq!(t, tri.type2);
    }
}

/// The paper's four stencils of the four-directional variant written on the triangle mesh
/// directly (not through the quad variant).
fn four_dir_by_hand(net: &FourDirNet) -> Vec<Point> {
    let m = &net.mesh;
    let p = m.positions();
    let t2 = &net.type2;
    let mut out = Vec::new();
    for v in 0..m.num_vertices() {
        let nb = m.vertex_neighbors(v);
        if m.is_boundary_vertex(v) {
            let (a, b) = (nb[0] as usize, nb[nb.len() - 1] as usize);
            if m.vertex_faces(v).len() == 2 {
                out.push(p[v]); // a corner of the polygon mesh (one polygon = two triangles)
            } else {
                out.push(geom::add(
                    geom::scale(p[v], 0.75),
                    geom::scale(geom::add(p[a], p[b]), 0.125),
                ));
            }
            continue;
        }
        // Type-1 V-vertex: type-2 neighbours; type-2 V-vertex: type-1 neighbours.
        let other: Vec<usize> = nb
            .iter()
            .map(|&w| w as usize)
            .filter(|&w| t2[w] != t2[v])
            .collect();
        let k = other.len();
        let a = a_k(k);
        let mut q = geom::scale(p[v], 1.0 - a);
        for w in other {
            q = geom::axpy(q, a / k as f64, p[w]);
        }
        out.push(q);
    }
    for e in 0..m.num_edges() {
        let [a, b] = m.edge(e);
        let (a, b) = (a as usize, b as usize);
        let h = m.edge_halfedge(e);
        if !t2[a] && !t2[b] {
            // Type-1 E-vertex: barycentre of the two triangles' four vertices.
            match m.he_twin(h) {
                None => out.push(geom::scale(geom::add(p[a], p[b]), 0.5)),
                Some(t) => {
                    let c = m.he_from(m.he_prev(h)) as usize;
                    let d = m.he_from(m.he_prev(t)) as usize;
                    out.push(geom::scale(
                        geom::add(geom::add(p[a], p[b]), geom::add(p[c], p[d])),
                        0.25,
                    ));
                }
            }
        } else {
            // Type-2 E-vertex: 1/4 V^I + 1/2 V^II + 1/8 (the type-2 neighbours of V^I next to
            // V^II on either side; ghosts a + b - V^II across boundary type-1 edges).
            let (vi, vii) = if t2[a] { (b, a) } else { (a, b) };
            let nb: Vec<usize> = m.vertex_neighbors(vi).iter().map(|&w| w as usize).collect();
            let pos = nb.iter().position(|&w| w == vii).unwrap();
            let boundary = m.is_boundary_vertex(vi);
            let side = |dir: isize| -> Point {
                let n = nb.len() as isize;
                let one = pos as isize + dir;
                let two = pos as isize + 2 * dir;
                if boundary && (two < 0 || two >= n) {
                    let w = nb[one as usize];
                    geom::sub(geom::add(p[vi], p[w]), p[vii])
                } else {
                    p[nb[two.rem_euclid(n) as usize]]
                }
            };
            let mut q = geom::scale(p[vi], 0.25);
            q = geom::axpy(q, 0.5, p[vii]);
            q = geom::axpy(q, 0.125, side(1));
            q = geom::axpy(q, 0.125, side(-1));
            out.push(q);
        }
    }
    out
}

/// Largest distance from a point of `a` to its nearest point of `b`, and back.
fn set_distance(a: &[Point], b: &[Point]) -> f64 {
    assert_eq!(a.len(), b.len());
    let one = |x: &[Point], y: &[Point]| {
        x.iter()
            .map(|p| {
                y.iter()
                    .map(|q| geom::dist(*p, *q))
                    .fold(f64::INFINITY, f64::min)
            })
            .fold(0.0, f64::max)
    };
    one(a, b).max(one(b, a))
}

#[test]
fn four_stencils_of_the_triangle_variant_by_hand() {
    for net in test_nets() {
        let tri = triangulate(&net);
        let (child, _) = NonBox4Dir::step(&tri).unwrap();
        let d = set_distance(&four_dir_by_hand(&tri), child.mesh.positions());
        assert!(d < 1e-12, "{d}");
        // And once more from the refined (all valence-4 type-2) mesh.
        let (grand, _) = NonBox4Dir::step(&child).unwrap();
        let d = set_distance(&four_dir_by_hand(&child), grand.mesh.positions());
        assert!(d < 1e-12, "{d}");
    }
}

#[test]
fn limits_are_fixed_under_refinement() {
    for net in test_nets() {
        let l0 = NonBox::limit_stencils(&net).apply(&net.points());
        let step = NonBox::step(&net).unwrap();
        let l1 = NonBox::limit_stencils(&step.net).apply(&step.net.points());
        let (nv, ne) = (net.mesh.num_vertices(), net.mesh.num_edges());
        for v in 0..nv {
            assert!(geom::dist(l0[v], l1[v]) < 1e-12);
        }
        // The limit at a face centre is the limit of the face vertex of the child.
        for f in 0..net.mesh.num_faces() {
            assert!(geom::dist(l0[nv + f], l1[nv + ne + f]) < 1e-12);
        }
    }
}

#[test]
fn cell_table_is_the_limit_of_the_rules() {
    // Interior and boundary cells of an open grid; x, y are the parameters.
    let net = open_grid(5, &mut Lcg(3));
    let fine = NonBox::refine_levels(&net, 4, |_| {}).unwrap();
    let lim = NonBox::limit_stencils(&fine).apply(&fine.points());
    let pts = net.points();
    let mut checked = 0;
    let mut regular_cells = 0;
    for f in 0..net.mesh.num_faces() {
        let Some(tris) = cell_triangles(&net.mesh, f, &pts) else {
            continue;
        };
        regular_cells += 1;
        let c = net.mesh.face(f);
        let (x0, y0) = (
            net.mesh.position(c[0] as usize)[0],
            net.mesh.position(c[0] as usize)[1],
        );
        for q in &lim {
            let (u, v) = (q[0] - x0, q[1] - y0);
            if !(0.0..=1.0).contains(&u) || !(0.0..=1.0).contains(&v) {
                continue;
            }
            // Triangle k of the cell (edge from corner k to corner k + 1; corners (0,0), (1,0),
            // (1,1), (0,1)) and barycentric coordinates.
            let (k, l) = if v <= u && v <= 1.0 - u {
                (0, [1.0 - u - v, u - v, 2.0 * v])
            } else if u >= v && u >= 1.0 - v {
                (1, [u - v, u + v - 1.0, 2.0 * (1.0 - u)])
            } else if v >= u && v >= 1.0 - u {
                (2, [u + v - 1.0, v - u, 2.0 * (1.0 - v)])
            } else {
                (3, [v - u, 1.0 - u - v, 2.0 * u])
            };
            let s = eval_triangle(&tris[k], l);
            assert!(geom::dist(s, *q) < 1e-12, "cell {f}: {s:?} vs {q:?}");
            checked += 1;
        }
    }
    // Every cell is regular, the four at corners (one face, diagonal ghost) included.
    assert_eq!(regular_cells, 25);
    assert!(checked > 25 * 200, "{checked}");
}

#[test]
fn boundary_rules_give_the_cubic_b_spline_boundary_curve() {
    let mut rng = Lcg(5);
    let net = perturbed(FcvNet::barycentric(fairsub::gallery::open_pipe()), &mut rng);
    let loops = net.mesh.boundary_loops();
    assert_eq!(loops.len(), 2);
    let step = NonBox::step(&net).unwrap();
    let child_loops = step.net.mesh.boundary_loops();
    let p = net.mesh.positions();
    let q = step.net.mesh.positions();
    for lp in &loops {
        let n = lp.len();
        // Chaikin-style cubic B-spline refinement of the closed boundary polygon.
        let mut expect = Vec::new();
        for i in 0..n {
            let (a, v, b) = (
                p[lp[(i + n - 1) % n] as usize],
                p[lp[i] as usize],
                p[lp[(i + 1) % n] as usize],
            );
            expect.push(geom::add(
                geom::scale(v, 0.75),
                geom::scale(geom::add(a, b), 0.125),
            ));
            expect.push(geom::scale(geom::add(v, b), 0.5));
        }
        let cl = child_loops
            .iter()
            .find(|c| c.contains(&lp[0]))
            .expect("the V-vertex keeps its index");
        let start = cl.iter().position(|&v| v == lp[0]).unwrap();
        let got: Vec<Point> = (0..cl.len())
            .map(|i| q[cl[(start + i) % cl.len()] as usize])
            .collect();
        assert!(max_dist(&got, &expect) < 1e-12);
        // Limit positions on the boundary: the cubic B-spline's points (a + 4 v + b) / 6.
        let lim = NonBox::limit_stencils(&net).apply(&net.points());
        for i in 0..n {
            let (a, v, b) = (
                p[lp[(i + n - 1) % n] as usize],
                p[lp[i] as usize],
                p[lp[(i + 1) % n] as usize],
            );
            let e = geom::scale(geom::add(geom::add(a, b), geom::scale(v, 4.0)), 1.0 / 6.0);
            assert!(geom::dist(lim[lp[i] as usize], e) < 1e-12);
        }
    }
}

#[test]
fn ghost_fcvs_reproduce_the_boundary_rules_and_commute_with_refinement() {
    // On a regular boundary the NFCV rule with ghosts equals the interior rule on the net
    // extended by ghosts, and the ghosts of the child are the child of the ghosts: compare an
    // open grid's refinement with the same grid extended by a ghost row of cells below.
    let m = 6;
    let net = open_grid(m, &mut Lcg(9));
    let fine = NonBox::refine_levels(&net, 2, |_| {}).unwrap();
    let lim = NonBox::limit_stencils(&fine).apply(&fine.points());
    // Limit positions along the bottom boundary are the cubic B-spline of the bottom row.
    let row: Vec<Point> = (0..=m).map(|i| net.mesh.position(i)).collect();
    for q in lim
        .iter()
        .filter(|q| q[1] == 0.0 && q[0] >= 1.0 && q[0] <= (m - 1) as f64)
    {
        let t = q[0];
        let i = (t.floor() as usize).min(m - 2);
        let s = t - i as f64;
        // Uniform cubic B-spline segment i over row[i-1..i+2] at s.
        let b = [
            (1.0 - s).powi(3) / 6.0,
            (3.0 * s.powi(3) - 6.0 * s * s + 4.0) / 6.0,
            (-3.0 * s.powi(3) + 3.0 * s * s + 3.0 * s + 1.0) / 6.0,
            s.powi(3) / 6.0,
        ];
        let mut e = [0.0; 3];
        for (k, w) in b.iter().enumerate() {
            e = geom::axpy(e, *w, row[i + k - 1]);
        }
        assert!(geom::dist(e, *q) < 1e-12, "{q:?} vs {e:?}");
    }
    // The boundary NFCV weights: 3/8 V0 + 1/8 V1 + 3/8 FCV0 + 1/8 FCV1 and at a corner
    // 1/2 V0 + 1/8 Va + 1/8 Vb + 1/4 FCV0.
    let st = step_stencils(&net.mesh);
    let nc = net.mesh.num_vertices() + net.mesh.num_edges() + net.mesh.num_faces();
    let h = net.mesh.find_halfedge(1, 2).unwrap(); // bottom edge of face 1, from vertex 1
    let (idx, w) = st.row(nc + h as usize);
    let mut pairs: Vec<(u32, f64)> = idx.iter().copied().zip(w.iter().copied()).collect();
    pairs.sort_by_key(|p| p.0);
    let nv = net.mesh.num_vertices() as u32;
    assert_eq!(
        pairs,
        vec![(1, 0.375), (2, 0.125), (nv, 0.125), (nv + 1, 0.375)]
    );
    let h = net.mesh.find_halfedge(0, 1).unwrap(); // corner face 0 at its corner vertex 0
    let (idx, w) = st.row(nc + h as usize);
    let mut pairs: Vec<(u32, f64)> = idx.iter().copied().zip(w.iter().copied()).collect();
    pairs.sort_by_key(|p| p.0);
    assert_eq!(
        pairs,
        vec![(0, 0.5), (1, 0.125), (m as u32 + 1, 0.125), (nv, 0.25)]
    );
}

#[test]
fn limit_normals_of_a_plane_and_a_cube() {
    let mut net = open_grid(4, &mut Lcg(2));
    for p in &mut net.fcv {
        p[2] = 0.0;
    }
    let flat: Vec<Point> = net
        .mesh
        .positions()
        .iter()
        .map(|p| [p[0], p[1], 0.0])
        .collect();
    net.mesh.set_positions(flat);
    for n in NonBox::limit_normals(&net) {
        assert!(geom::dist(n, [0.0, 0.0, 1.0]) < 1e-12, "{n:?}");
    }
    let cube = FcvNet::barycentric(fairsub::gallery::cube());
    let normals = NonBox::limit_normals(&cube);
    let lim = NonBox::limit_stencils(&cube).apply(&cube.points());
    for (n, p) in normals.iter().zip(&lim) {
        // By symmetry the normal is radial.
        assert!(
            geom::dist(*n, geom::normalize(*p)) < 1e-12,
            "{n:?} at {p:?}"
        );
    }
}

// ---------------------------------------------------------------------------------------------
// Scheme interface, FCV files, types

#[test]
fn scheme_refine_carries_fcvs_across_levels() {
    let cube = fairsub::gallery::cube();
    let s = fairsub::schemes::by_name("nonbox").unwrap();
    let m = fairsub::schemes::refine_levels(s.as_ref(), &cube, 3, |_| {}).unwrap();
    let direct = NonBox::refine_levels(&FcvNet::barycentric(cube.clone()), 3, |_| {}).unwrap();
    assert_eq!(m.num_vertices(), direct.num_points());
    assert!(max_dist(m.positions(), &direct.points()) < 1e-12);
    let lim = s.limit_stencils(&m).unwrap().apply(m.positions());
    let ld = NonBox::limit_stencils(&direct).apply(&direct.points());
    assert!(max_dist(&lim, &ld) < 1e-12);
    // The refinement stencils of a plain mesh include the FCV insertion.
    let r = s.refine(&cube).unwrap();
    assert_eq!(r.stencils.num_sources(), 8);
    assert!(max_dist(&r.stencils.apply(cube.positions()), r.mesh.positions()) < 1e-15);
    // nonbox-4dir through the same interface: triangles, same points.
    let s4 = fairsub::schemes::by_name("nonbox-4dir").unwrap();
    let t = fairsub::schemes::refine_levels(s4.as_ref(), &cube, 3, |_| {}).unwrap();
    assert!(t.is_all_triangles());
    assert!(max_dist(t.positions(), &direct.points()) < 1e-12);
    let lt = s4.limit_stencils(&t).unwrap().apply(t.positions());
    assert!(max_dist(&lt, &ld) < 1e-12);
}

#[test]
fn fcv_scale_scales_about_the_origin() {
    let cube = fairsub::gallery::cube();
    for s in [0.5, 1.0, 1.5] {
        let net = FcvNet::scaled(cube.clone(), s).unwrap();
        for (f, p) in net.fcv.iter().enumerate() {
            let c = cube.face_centroid(f);
            assert!(geom::dist(*p, geom::scale(c, s)) < 1e-15);
        }
    }
    // Larger FCVs push the surface out: the limit at a face centre moves with the scale.
    let centre = |s: f64| {
        let net = FcvNet::scaled(cube.clone(), s).unwrap();
        let l = NonBox::limit_stencil(&net, 8).apply(&net.points());
        geom::norm(l)
    };
    assert!(centre(0.5) < centre(1.0) && centre(1.0) < centre(1.5));
    assert!(FcvNet::scaled(cube, f64::NAN).is_err());
}

#[test]
fn fcv_side_files_parse_and_report_lines() {
    let cube = fairsub::gallery::cube();
    let p = std::path::Path::new("cube.fcv");
    let text = "# six faces\n0 0 -2\n*\n\n0 -1.5, 0   # commas are fine\n*\n*\n1 2 3\n";
    let net = fcv_net_from_file(cube.clone(), text, p, 1.0).unwrap();
    assert_eq!(net.fcv[0], [0.0, 0.0, -2.0]);
    assert_eq!(net.fcv[1], cube.face_centroid(1));
    assert_eq!(net.fcv[2], [0.0, -1.5, 0.0]);
    assert_eq!(net.fcv[5], [1.0, 2.0, 3.0]);
    let err = |t: &str| {
        fcv_net_from_file(cube.clone(), t, p, 1.0)
            .unwrap_err()
            .to_string()
    };
    let e = err("0 0 0\n1 2\n");
    assert!(
        e.contains("cube.fcv:2:") && e.contains("three numbers"),
        "{e}"
    );
    let e = err("0 0 0\n1 x 2\n");
    assert!(
        e.contains(":2:") && e.contains("'x' is not a number"),
        "{e}"
    );
    let e = err("*\n*\n");
    assert!(e.contains("2 FCV lines but the net has 6 faces"), "{e}");
    let e = err("*\n*\n*\n*\n*\n*\n\n*\n");
    assert!(e.contains(":8:") && e.contains("one too many"), "{e}");
    let e = err("*\n*\n*\n*\n*\n0 0 inf\n");
    assert!(e.contains(":6:") && e.contains("not finite"), "{e}");
}

#[test]
fn fcv_obj_round_trip() {
    let net = FcvNet::scaled(fairsub::gallery::cube(), 1.5).unwrap();
    let text = fcv_obj_string(&net).unwrap();
    assert!(text.contains("# fcv 6:"));
    let (back, notes) = parse_fcv_obj(&text, std::path::Path::new("c.obj")).unwrap();
    assert!(notes.is_empty(), "{notes:?}");
    assert_eq!(back.points(), net.points());
    // The same text through the plain mesh writer of the layout mesh.
    let mut plain = Vec::new();
    let lm = net.to_layout_mesh();
    fairsub::io::write_polygons_to(
        &mut plain,
        lm.positions(),
        lm.face_starts(),
        lm.corners(),
        fairsub::io::MeshFormat::Obj,
    )
    .unwrap();
    let (back, _) = parse_fcv_obj(
        std::str::from_utf8(&plain).unwrap(),
        std::path::Path::new("c.obj"),
    )
    .unwrap();
    assert_eq!(back.points(), net.points());
    // A wrong count in the marker is an error naming its line.
    let bad = text.replace("# fcv 6:", "# fcv 5:");
    let e = parse_fcv_obj(&bad, std::path::Path::new("c.obj"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("c.obj:2:"), "{e}");
    // A plain net gets barycentres, with a note.
    let (plain_net, notes) = parse_fcv_obj(
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
        std::path::Path::new("t.obj"),
    )
    .unwrap();
    assert_eq!(plain_net.fcv[0], [1.0 / 3.0, 1.0 / 3.0, 0.0]);
    assert_eq!(notes.len(), 1);
}

#[test]
fn types_of_triangle_meshes() {
    // The tetrahedron and the icosahedron admit no types; the octahedron admits three (poles).
    assert!(classify(&fairsub::gallery::tetrahedron()).is_err());
    assert!(classify(&fairsub::gallery::icosahedron()).is_err());
    let t = classify(&fairsub::gallery::octahedron()).unwrap();
    assert_eq!(t.iter().filter(|&&x| x).count(), 2);
    // Types of triangulated nets are found even when the FCVs are not last.
    let net = triangulate(&FcvNet::barycentric(fairsub::gallery::prism(6)));
    let n = net.mesh.num_vertices();
    let perm: Vec<usize> = (0..n).rev().collect();
    let pos: Vec<Point> = perm.iter().map(|&v| net.mesh.position(v)).collect();
    let mut inv = vec![0; n];
    for (new, &old) in perm.iter().enumerate() {
        inv[old] = new;
    }
    let faces: Vec<Vec<usize>> = net
        .mesh
        .faces()
        .map(|f| f.iter().map(|&v| inv[v as usize]).collect())
        .collect();
    let shuffled = PolyMesh::new(pos, &faces).unwrap();
    let t = classify(&shuffled).unwrap();
    for v in 0..n {
        assert_eq!(t[inv[v]], net.type2[v]);
    }
    // A type-2 vertex on the boundary is rejected.
    assert!(
        FourDirNet::new(
            fairsub::gallery::tri_grid(),
            vec![true; fairsub::gallery::tri_grid().num_vertices()]
        )
        .is_err()
    );
}

// ---------------------------------------------------------------------------------------------
// Patch complexes

use fairsub::surface::{ComplexOptions, Element, PatchComplex, Provenance};

fn complex(scheme: &str, m: &PolyMesh, rings: usize) -> PatchComplex {
    fairsub::surface::complex(scheme, m, ComplexOptions { rings, fill: true }, |_| {}).unwrap()
}

fn level_of(p: &Provenance) -> Option<usize> {
    match p {
        Provenance::Regular { .. } => Some(0),
        Provenance::Ring { ring, .. } => Some(*ring as usize),
        _ => None,
    }
}

fn patch_nets() -> Vec<(&'static str, PolyMesh)> {
    use fairsub::gallery::{self, CnetShape};
    vec![
        ("cnet-5", gallery::cnet(5, CnetShape::Convex, 3)),
        ("cnet-3", gallery::cnet(3, CnetShape::Saddle, 3)),
        ("prism-5", gallery::prism(5)),
        ("cube", gallery::cube()),
        ("tetrahedron", gallery::tetrahedron()),
        ("open-pipe", gallery::open_pipe()),
        ("torus-evs", gallery::torus_with_evs()),
        ("open-grid", gallery::open_grid()),
    ]
}

/// Every regular and ring patch of level `l` passes through limit points of the uniformly
/// refined net: its corners and the centre (level `l`), edge midpoints (level `l + 1`) and the
/// point `(1/2, 1/2)` (level `l + 2`).
#[test]
fn patches_are_exact_limits() {
    for (name, m) in patch_nets() {
        let rings = 2;
        let c = complex("nonbox", &m, rings);
        let mut net = FcvNet::barycentric(m.clone());
        let mut sets = Vec::new();
        for _ in 0..=rings + 2 {
            sets.push(NonBox::limit_stencils(&net).apply(&net.points()));
            net = NonBox::step(&net).unwrap().net;
        }
        let mut n = 0;
        for (p, prov) in c.patches.iter().zip(&c.provenance) {
            let Some(l) = level_of(prov) else { continue };
            for (u, v) in [
                (0.0, 0.0),
                (1.0, 0.0),
                (0.0, 1.0),
                (0.5, 0.0),
                (0.0, 0.5),
                (1.0, 0.5),
                (0.5, 0.5),
            ] {
                let q = p.eval(u, v);
                let d = sets[l + 2]
                    .iter()
                    .map(|s| geom::dist(*s, q))
                    .fold(f64::INFINITY, f64::min);
                assert!(
                    d < 1e-12,
                    "{name}: level {l} patch point ({u}, {v}) is {d} from the limit"
                );
                n += 1;
            }
        }
        assert!(n > 0, "{name}");
    }
}

/// Closed nets give closed complexes (every non-collapsed side is shared), all nets are C^0,
/// and regular and ring patches meet with continuous normals (the spline is C^1); the fill is
/// only C^0 to them.
#[test]
fn complexes_are_watertight_and_g1_outside_the_fill() {
    for (name, m) in patch_nets() {
        for scheme in ["nonbox", "nonbox-4dir"] {
            if scheme == "nonbox-4dir" && name != "cube" && name != "tetrahedron" {
                continue;
            }
            let c = complex(scheme, &m, 3);
            let rep = fairsub::analysis::continuity::check(&c);
            assert!(
                rep.all.c0 < 1e-12,
                "{scheme} {name}: C^0 gap {}",
                rep.all.c0
            );
            if m.boundary_loops().is_empty() {
                assert_eq!(rep.open_sides, 0, "{scheme} {name}: {:?}", rep.open);
            }
            for (kind, d) in &rep.by_kind {
                if !kind.contains("cap") {
                    assert!(d.g1 < 1e-8, "{scheme} {name} {kind}: normal jump {}", d.g1);
                }
            }
        }
    }
}

#[test]
fn ring_layout_at_an_isolated_extraordinary_vertex() {
    for k in [3, 5, 6] {
        let m = fairsub::gallery::cnet(k, fairsub::gallery::CnetShape::Convex, 3);
        let c = complex("nonbox", &m, 4);
        let mut per_ring = [0usize; 5];
        let mut caps = 0;
        for p in &c.provenance {
            match *p {
                Provenance::Ring {
                    element: Element::Vertex(0),
                    ring,
                    ..
                } => per_ring[ring as usize] += 1,
                Provenance::Cap {
                    element: Element::Vertex(0),
                    ..
                } => caps += 1,
                _ => {}
            }
        }
        // Three cells (twelve triangles) per sector and ring, one fill quad per sector.
        assert_eq!(&per_ring[1..], &[12 * k; 4], "k = {k}");
        assert_eq!(caps, k);
    }
    // An n-gon is an element of its own: its first ring is at level 1.
    let c = complex("nonbox", &fairsub::gallery::prism(5), 2);
    let caps = c
        .provenance
        .iter()
        .filter(|p| {
            matches!(
                p,
                Provenance::Cap {
                    element: Element::Face(_),
                    ..
                }
            )
        })
        .count();
    assert_eq!(caps, 2 * 5);
    // The two variants give the same complex.
    let a = complex("nonbox", &fairsub::gallery::cube(), 2);
    let b = complex("nonbox-4dir", &fairsub::gallery::cube(), 2);
    assert_eq!(a.len(), b.len());
    for (p, q) in a.patches.iter().zip(&b.patches) {
        for (x, y) in p.cps.iter().zip(&q.cps) {
            assert!(geom::dist(*x, *y) < 1e-12);
        }
    }
}

#[test]
fn gallery_fcv_scale_series_is_the_scaled_cube() {
    let all = fairsub::gallery::all();
    let s4 = fairsub::schemes::by_name("nonbox-4dir").unwrap();
    for (name, s) in [("0.5", 0.5), ("1", 1.0), ("1.5", 1.5)] {
        let (_, m) = all
            .iter()
            .find(|(n, _)| *n == format!("nonbox-cube-fcv-{name}"))
            .unwrap();
        let a = fairsub::schemes::refine_levels(s4.as_ref(), m, 2, |_| {}).unwrap();
        let b = NonBox::refine_levels(
            &FcvNet::scaled(fairsub::gallery::cube(), s).unwrap(),
            2,
            |_| {},
        )
        .unwrap();
        assert!(max_dist(a.positions(), &b.points()) < 1e-12, "scale {name}");
    }
}

#[test]
fn fcv_choice_for_the_cli() {
    let cube = fairsub::gallery::cube();
    let dir = std::env::temp_dir().join(format!("fairsub-nonbox-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("cube.fcv");
    std::fs::write(&path, "*\n*\n0 0 9\n*\n*\n*\n").unwrap();
    let net = choose_fcv_net(&cube, 0.5, Some(&path)).unwrap();
    assert_eq!(net.fcv[2], [0.0, 0.0, 9.0]);
    assert_eq!(net.fcv[0], geom::scale(cube.face_centroid(0), 0.5));
    // A layout mesh keeps its own FCVs.
    let lm = net.to_layout_mesh();
    let back = choose_fcv_net(&lm, 1.0, None).unwrap();
    assert_eq!(back.points(), net.points());
    // A missing file is an I/O error naming it.
    let e = choose_fcv_net(&cube, 1.0, Some(&dir.join("none.fcv")))
        .unwrap_err()
        .to_string();
    assert!(e.contains("none.fcv"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
    // Edge types of the four-directional net.
    let t = triangulate(&net);
    let n2 = (0..t.mesh.num_edges())
        .filter(|&e| t.is_type2_edge(e))
        .count();
    assert_eq!(n2, 24); // one per corner of every face
}

#[test]
fn notes_say_how_the_input_was_read() {
    use fairsub::schemes::nonbox::input_notes;
    assert!(input_notes(false, &fairsub::gallery::cube()).is_empty());
    let pipe = input_notes(false, &fairsub::gallery::open_pipe());
    assert!(
        pipe.iter().any(|n| n.contains("reconstruction")),
        "{pipe:?}"
    );
    let tet = input_notes(true, &fairsub::gallery::tetrahedron());
    assert!(tet[0].contains("not quasi-four-directional"), "{tet:?}");
    let fcv = input_notes(true, &fairsub::gallery::nonbox_cube_fcv(0.5));
    assert!(
        fcv[0].contains("6 type-2 vertices") && fcv[0].contains("type-2 vertices last"),
        "{fcv:?}"
    );
    let oct = input_notes(true, &fairsub::gallery::octahedron());
    assert!(oct[0].contains("admits 3 type assignments"), "{oct:?}");
    // Shuffled so that the FCVs are not last: the advice is given.
    let net = triangulate(&FcvNet::barycentric(fairsub::gallery::cube()));
    let n = net.mesh.num_vertices();
    let pos: Vec<Point> = (0..n).rev().map(|v| net.mesh.position(v)).collect();
    let faces: Vec<Vec<usize>> = net
        .mesh
        .faces()
        .map(|f| f.iter().map(|&v| n - 1 - v as usize).collect())
        .collect();
    let shuffled = PolyMesh::new(pos, &faces).unwrap();
    let t = classify(&shuffled).unwrap();
    assert!((0..n).all(|v| t[n - 1 - v] == net.type2[v]));
    let note = &input_notes(true, &shuffled)[0];
    assert!(
        note.contains("most type-2 vertices") && note.contains("--scheme nonbox"),
        "{note}"
    );
    let (_, notes) = fairsub::surface::complex_with_notes(
        "nonbox",
        &fairsub::gallery::open_pipe(),
        ComplexOptions {
            rings: 1,
            fill: true,
        },
        fairsub::surface::Fallback::default(),
        |_| {},
    )
    .unwrap();
    assert_eq!(notes.len(), 1);
}

// ---------------------------------------------------------------------------------------------
// The command line

fn fairsub_cli(args: &[&str]) -> (i32, String) {
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_fairsub"))
        .args(args)
        .output()
        .unwrap();
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

#[test]
fn cli_carries_fcvs_through_obj_files_and_writes_limit_meshes() {
    let dir = std::env::temp_dir().join(format!("fairsub-nonbox-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = |name: &str| dir.join(name).to_str().unwrap().to_string();
    // Two steps in one call equal one step applied twice through an OBJ file with FCVs.
    for (out, net, levels) in [
        ("one.obj", "gallery:cube".to_string(), "1"),
        ("two.obj", p("one.obj"), "1"),
        ("direct.obj", "gallery:cube".to_string(), "2"),
    ] {
        let args = [
            "subdivide",
            &net,
            "--scheme",
            "nonbox",
            "--fcv-scale",
            "1.5",
            "-l",
            levels,
            "-o",
            &p(out),
        ];
        let (code, err) = fairsub_cli(&args);
        assert_eq!(code, 0, "{err}");
        if out == "two.obj" {
            assert!(err.contains("--fcv-scale is ignored"), "{err}");
        }
    }
    let read = |name: &str| {
        let text = std::fs::read_to_string(dir.join(name)).unwrap();
        parse_fcv_obj(&text, &dir.join(name)).unwrap().0
    };
    let expect = NonBox::refine_levels(
        &FcvNet::scaled(fairsub::gallery::cube(), 1.5).unwrap(),
        2,
        |_| {},
    )
    .unwrap();
    for name in ["two.obj", "direct.obj"] {
        let got = read(name);
        assert_eq!(got.fcv.len(), 96);
        assert!(max_dist(&got.points(), &expect.points()) < 1e-12, "{name}");
    }
    // The limit mesh: triangles around the face centres, every point at its limit.
    let (code, err) = fairsub_cli(&[
        "subdivide",
        "gallery:cube",
        "--scheme",
        "nonbox",
        "--fcv-scale",
        "1.5",
        "-l",
        "2",
        "--limit",
        "-o",
        &p("limit.ply"),
    ]);
    assert_eq!(code, 0, "{err}");
    let lim = fairsub::io::read_mesh(&dir.join("limit.ply")).unwrap().mesh;
    let want =
        NonBox::limit_mesh(&FcvNet::scaled(fairsub::gallery::cube(), 1.5).unwrap(), 2).unwrap();
    assert_eq!((lim.num_vertices(), lim.num_faces()), (194, 384));
    assert!(max_dist(lim.positions(), want.positions()) < 1e-6);
    // OBJ limit output carries one unit normal per vertex, outward on the closed surface.
    let (code, err) = fairsub_cli(&[
        "subdivide",
        "gallery:cube",
        "--scheme",
        "nonbox",
        "-l",
        "2",
        "--limit",
        "-o",
        &p("limit.obj"),
    ]);
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(dir.join("limit.obj")).unwrap();
    let parse = |tag: &str| -> Vec<Point> {
        text.lines()
            .filter_map(|l| l.strip_prefix(tag))
            .map(|l| {
                let c: Vec<f64> = l.split_whitespace().map(|t| t.parse().unwrap()).collect();
                [c[0], c[1], c[2]]
            })
            .collect()
    };
    let (vs, ns) = (parse("v "), parse("vn "));
    assert_eq!((vs.len(), ns.len()), (194, 194));
    let want = NonBox::limit_mesh(&FcvNet::barycentric(fairsub::gallery::cube()), 2).unwrap();
    assert!(max_dist(&vs, want.positions()) < 1e-12);
    for (v, n) in vs.iter().zip(&ns) {
        assert!((geom::norm(*n) - 1.0).abs() < 1e-12);
        // The cube is symmetric about the origin: the normal leans outward along the position.
        assert!(geom::dot(*n, geom::normalize(*v)) > 0.9, "{v:?} {n:?}");
    }
    assert!(text.contains("f 1//1 "));
    // FCV options on another scheme, and a short FCV file, are clear errors.
    let (code, err) = fairsub_cli(&[
        "subdivide",
        "gallery:cube",
        "--scheme",
        "catmull-clark",
        "--fcv-scale",
        "2",
        "-o",
        &p("x.obj"),
    ]);
    assert_eq!(code, 1);
    assert!(err.contains("only the non-box schemes"), "{err}");
    std::fs::write(dir.join("short.fcv"), "*\n*\n").unwrap();
    let (code, err) = fairsub_cli(&[
        "subdivide",
        "gallery:cube",
        "--scheme",
        "nonbox",
        "--fcv-file",
        &p("short.fcv"),
        "-o",
        &p("x.obj"),
    ]);
    assert_eq!(code, 1);
    assert!(
        err.contains("short.fcv:2") && err.contains("6 faces"),
        "{err}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn cli_analyze_prints_the_published_numbers() {
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_fairsub"))
        .args(["analyze", "--scheme", "nonbox", "--valence", "6", "--json"])
        .output()
        .unwrap();
    assert!(o.status.success());
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let published = v["published"].as_array().unwrap();
    assert_eq!(published.len(), 8);
    let lambda = &published[0];
    assert!((lambda["computed"].as_f64().unwrap() - 0.625).abs() < 1e-12);
    for c in published {
        let q = c["quantity"].as_str().unwrap();
        let d = c["difference"].as_f64().unwrap();
        let allowed = if q.starts_with("sum of the printed") {
            0.125 + 1e-12
        } else {
            1e-12
        };
        assert!(d < allowed, "{q}: {d}");
    }
    assert_eq!(v["characteristic_map"]["injective"], true);
}

/// Boundary vertices with one face (corners) or two are regular: the c-net's only element is
/// its centre and the open grid has none; the corner cells are exact (`patches_are_exact_limits`).
#[test]
fn corners_and_two_face_boundary_vertices_need_no_rings() {
    use fairsub::surface::{Element, Provenance};
    let elements = |c: &PatchComplex| {
        let mut out: Vec<Element> = Vec::new();
        for p in &c.provenance {
            if let Provenance::Ring { element, .. } | Provenance::Cap { element, .. } = *p
                && !out.contains(&element)
            {
                out.push(element);
            }
        }
        out
    };
    let m = fairsub::gallery::cnet(5, fairsub::gallery::CnetShape::Convex, 3);
    let centre = (0..m.num_vertices())
        .find(|&v| !m.is_boundary_vertex(v) && m.vertex_faces(v).len() == 5)
        .unwrap();
    assert_eq!(
        elements(&complex("nonbox", &m, 2)),
        vec![Element::Vertex(centre as u32)]
    );
    let grid = fairsub::gallery::open_grid();
    let c = complex("nonbox", &grid, 2);
    assert!(elements(&c).is_empty());
    assert_eq!(c.len(), 4 * grid.num_faces());
}
