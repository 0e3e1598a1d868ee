use super::*;
use crate::bezier::BezierPatch;
use crate::geom::{add, cross, sub};
use crate::surface::{ComplexOptions, Provenance};

fn complex_of(patches: Vec<BezierPatch>) -> PatchComplex {
    let mut c = PatchComplex::new();
    for p in patches {
        c.push(p, Provenance::Unknown);
    }
    c
}

/// The parallelogram `origin + s e0 + t e1`, `s, t` in `[0, 1]`, as a bicubic patch whose
/// parameters are spaced unevenly: `s(u)` has the Bezier coefficients `0, 0.1, 0.9, 1`
/// (monotone, symmetric so that shared edges match either way), so the parametrisation is
/// not affine while the surface is the plane piece itself.
fn flat_patch(origin: Point, e0: Point, e1: Point) -> BezierPatch {
    let s = [0.0, 0.1, 0.9, 1.0];
    BezierPatch::from_fn(3, 3, |i, j| {
        add(
            origin,
            add(crate::geom::scale(e0, s[i]), crate::geom::scale(e1, s[j])),
        )
    })
}

/// The unit cube `[0, 1]^3` as six unevenly parametrised flat bicubic patches, outward.
fn cube() -> Vec<BezierPatch> {
    let (x, y, z) = ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]);
    let o = [0.0; 3];
    vec![
        flat_patch(o, y, x), // z = 0, normal -z
        flat_patch(z, x, y), // z = 1, normal +z
        flat_patch(o, x, z), // y = 0, normal -y
        flat_patch(y, z, x), // y = 1, normal +y
        flat_patch(o, z, y), // x = 0, normal -x
        flat_patch(x, y, z), // x = 1, normal +x
    ]
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * b.abs().max(1.0)
}

#[crate::unit::test]
fn a_cube_of_reparametrised_patches_has_its_closed_form_moments() {
    let m = measure(&complex_of(cube()), &MeasureOptions::default());
    assert!(m.closed, "{m:?}");
    assert_eq!((m.open_sides, m.orientation_conflicts), (0, 0));
    assert!(close(m.area, 6.0, 1e-14), "{}", m.area);
    let v = m.volume.expect("closed");
    assert!(v.outward);
    assert!(close(v.volume, 1.0, 1e-14), "{}", v.volume);
    for k in 0..3 {
        assert!(close(v.centroid[k], 0.5, 1e-14));
        assert!(close(m.area_centroid[k], 0.5, 1e-14));
        // solid: 1/6 on the diagonal; shell: 5/3 (two faces 1/6, four faces 1/3 each)
        assert!(close(v.inertia[k][k], 1.0 / 6.0, 1e-14), "{:?}", v.inertia);
        assert!(
            close(m.area_inertia[k][k], 5.0 / 3.0, 1e-14),
            "{:?}",
            m.area_inertia
        );
        for j in 0..3 {
            if j != k {
                assert!(v.inertia[k][j].abs() < 1e-15 && m.area_inertia[k][j].abs() < 1e-15);
            }
        }
    }
    assert!(m.closure < 1e-15);
}

#[crate::unit::test]
fn a_cube_turned_inside_out_reports_the_same_volume_inward() {
    let patches: Vec<BezierPatch> = cube().iter().map(|p| p.transposed()).collect();
    let m = measure(&complex_of(patches), &MeasureOptions::default());
    let v = m.volume.expect("closed");
    assert!(!v.outward && close(v.volume, 1.0, 1e-14));
    // one face flipped: the orientations disagree, no volume
    let mut patches = cube();
    patches[0] = patches[0].transposed();
    let m = measure(&complex_of(patches), &MeasureOptions::default());
    assert!(!m.closed && m.orientation_conflicts == 4 && m.volume.is_none());
    // one face missing: open, four open sides, the surface moments still reported
    let mut patches = cube();
    patches.pop();
    let m = measure(&complex_of(patches), &MeasureOptions::default());
    assert!(!m.closed && m.open_sides == 4 && m.volume.is_none());
    assert!(close(m.area, 5.0, 1e-14));
    assert!((m.closure - 1.0 / 5.0).abs() < 1e-14, "{}", m.closure);
}

/// The solid between the paraboloid `z = 1 - x^2 - y^2` and the plane `z = -2` over
/// `[-1, 1]^2`: top bi-quadratic, sides of bi-degree (2, 1), bottom bilinear, mixed degrees.
fn paraboloid_block() -> Vec<BezierPatch> {
    // x(u) = 2u - 1 (coefficients -1, 0, 1), x^2 has coefficients 1, -1, 1
    let lin = [-1.0, 0.0, 1.0];
    let sq = [1.0, -1.0, 1.0];
    let top = BezierPatch::from_fn(2, 2, |i, j| [lin[i], lin[j], 1.0 - sq[i] - sq[j]]);
    // the four sides, each x or y = +-1 with z from -1 up to the top's edge curve
    let side = |f: &dyn Fn(f64) -> [f64; 2], flip: bool| {
        let p = BezierPatch::from_fn(2, 1, |i, j| {
            let [a, b] = f(lin[i]);
            let top_z = 1.0 - sq[i] - 1.0;
            [a, b, if j == 0 { -2.0 } else { top_z }]
        });
        if flip { p.reversed_u() } else { p }
    };
    let sides = [
        side(&|t| [t, -1.0], false),
        side(&|t| [1.0, t], false),
        side(&|t| [t, 1.0], true),
        side(&|t| [-1.0, t], true),
    ];
    let bottom = BezierPatch::from_fn(1, 1, |i, j| {
        let (x, y) = (2.0 * j as f64 - 1.0, 2.0 * i as f64 - 1.0);
        [x, y, -2.0]
    });
    let mut out = vec![top, bottom];
    out.extend(sides);
    out
}

#[crate::unit::test]
fn the_paraboloid_block_has_its_closed_form_volume_and_centroid() {
    let m = measure(&complex_of(paraboloid_block()), &MeasureOptions::default());
    assert!(m.closed, "{m:?}");
    let v = m.volume.expect("closed");
    assert!(v.outward, "{v:?}");
    // V = int (f + 2) = int (3 - x^2 - y^2) = 28/3 with f = 1 - x^2 - y^2;
    // int_V z = int (f^2 - 4) / 2 = (52/45 - 16) / 2 = -334/45, so z_c = -167/210
    assert!(close(v.volume, 28.0 / 3.0, 1e-14), "{}", v.volume);
    assert!(v.centroid[0].abs() < 1e-14 && v.centroid[1].abs() < 1e-14);
    assert!(
        close(v.centroid[2], -167.0 / 210.0, 1e-14),
        "{:?}",
        v.centroid
    );
    assert_eq!(m.rules, vec![[1, 1, 3, 3], [2, 1, 5, 3], [2, 2, 5, 5]]);
}

/// Every closed surface's volume three ways: `int x N_x`, `int y N_y`, `int z N_z` agree only
/// when the surface is watertight; and against the moments' own `1/3 int X . N`.
fn volume_three_ways(c: &PatchComplex) -> [f64; 3] {
    let mut out = [0.0; 3];
    for p in &c.patches {
        let rule = Region::WHOLE.rule(exact_points(p.deg_u), exact_points(p.deg_v));
        quadrature::for_each_sample(p, &rule, |s, w| {
            for k in 0..3 {
                out[k] += w * s.p[k] * s.n[k];
            }
        });
    }
    out
}

fn gallery_complex(name: &str, scheme: &str, rings: usize) -> PatchComplex {
    let mesh = crate::gallery::all()
        .into_iter()
        .find(|(n, _)| n == name)
        .expect("gallery net")
        .1;
    crate::surface::complex(scheme, &mesh, ComplexOptions { rings, fill: true }, |_| {})
        .expect("complex")
}

#[crate::unit::test]
fn catmull_clark_surfaces_are_watertight_by_the_divergence_theorem() {
    for name in ["cube", "octahedron", "torus-evs"] {
        let c = gallery_complex(name, "catmull-clark", 4);
        let m = measure(&c, &MeasureOptions::default());
        assert!(m.closed, "{name}: {} open sides", m.open_sides);
        let v = m.volume.expect("closed").volume;
        for w in volume_three_ways(&c) {
            assert!(close(w.abs(), v, 1e-12), "{name}: {w} vs {v}");
        }
        assert!(m.closure < 1e-13, "{name}: closure {}", m.closure);
    }
}

/// A rotation (about an axis through no special point) and a translation.
fn rigid(p: Point) -> Point {
    let axis = crate::geom::normalize([1.0, 2.0, -0.5]);
    let (s, c) = 0.7f64.sin_cos();
    let k = axis;
    let kxp = cross(k, p);
    let kdp = dot(k, p);
    let r = add(
        add(crate::geom::scale(p, c), crate::geom::scale(kxp, s)),
        crate::geom::scale(k, kdp * (1.0 - c)),
    );
    add(r, [3.0, -1.5, 0.25])
}

#[crate::unit::test]
fn moments_are_invariant_under_rigid_motion() {
    let c = gallery_complex("torus-evs", "catmull-clark", 3);
    let mut moved = c.clone();
    for p in &mut moved.patches {
        *p = p.map_points(rigid);
    }
    let (a, b) = (
        measure(&c, &MeasureOptions::default()),
        measure(&moved, &MeasureOptions::default()),
    );
    let (va, vb) = (a.volume.unwrap(), b.volume.unwrap());
    assert!(close(a.area, b.area, 1e-13), "{} {}", a.area, b.area);
    assert!(close(va.volume, vb.volume, 1e-13));
    let want = rigid(va.centroid);
    assert!(
        crate::geom::dist(want, vb.centroid) < 1e-12,
        "{want:?} {:?}",
        vb.centroid
    );
    assert!(crate::geom::dist(rigid(a.area_centroid), b.area_centroid) < 1e-12);
    for k in 0..3 {
        assert!(close(
            va.principal_moments[k],
            vb.principal_moments[k],
            1e-12
        ));
    }
}

/// Volume and area of a triangle mesh.
fn mesh_volume_area(t: &crate::surface::tessellate::Tessellation) -> (f64, f64) {
    let (mut v, mut a) = (0.0, 0.0);
    for tri in &t.triangles {
        let [p, q, r] = tri.map(|i| t.positions[i as usize]);
        v += dot(p, cross(q, r)) / 6.0;
        a += crate::geom::norm(cross(sub(q, p), sub(r, p))) / 2.0;
    }
    (v, a)
}

#[crate::unit::test]
fn the_gallery_cube_agrees_with_the_limit_of_its_tessellations() {
    let c = gallery_complex("cube", "catmull-clark", 4);
    let m = measure(&c, &MeasureOptions::default());
    let v = m.volume.unwrap().volume;
    let mut errs = Vec::new();
    let mut last = None;
    for n in [4, 8, 16, 32] {
        let (tv, ta) = mesh_volume_area(&crate::surface::tessellate::tessellate(&c, n));
        errs.push(((tv - v).abs() / v, (ta - m.area).abs() / m.area));
        // Richardson: the chord error is O(h^2), so (4 T(h/2) - T(h)) / 3 is O(h^4)
        if let Some((pv, pa)) = last {
            let (rv, ra): (f64, f64) = ((4.0 * tv - pv) / 3.0, (4.0 * ta - pa) / 3.0);
            if n == 32 {
                assert!((rv - v).abs() / v < 1e-6, "{rv} vs {v}");
                assert!((ra - m.area).abs() / m.area < 1e-6, "{ra} vs {}", m.area);
            }
        }
        last = Some((tv, ta));
    }
    // each halving of the tessellation's spacing divides the errors by about 4
    for w in errs.windows(2) {
        assert!(w[1].0 < w[0].0 / 3.5 && w[1].1 < w[0].1 / 3.5, "{errs:?}");
    }
}

#[crate::unit::test]
fn the_area_rule_converges_geometrically_to_the_adaptive_value() {
    let c = gallery_complex("torus-evs", "catmull-clark", 3);
    let m = measure(&c, &MeasureOptions::default());
    assert!(
        m.area_error < 1e-13 * m.area,
        "{} of {}",
        m.area_error,
        m.area
    );
    // the plain tensor rule of q points per direction on every patch, q = 2 .. 12
    let errs: Vec<f64> = (2..=12)
        .map(|q| {
            let a: f64 = c
                .patches
                .iter()
                .map(|p| {
                    let rule = Region::WHOLE.rule(q, q);
                    let mut s = 0.0;
                    quadrature::for_each_sample(p, &rule, |x, w| s += w * norm(x.n));
                    s
                })
                .sum();
            (a - m.area).abs() / m.area
        })
        .collect();
    assert!(errs[0] > 1e-6, "{errs:?}");
    assert!(errs[10] < 1e-13, "{errs:?}");
}

#[crate::unit::test]
fn face_areas_add_up_to_the_area() {
    for (name, scheme) in [
        ("cube", "catmull-clark"),
        ("octahedron", "loop"),
        ("icosahedron", "loop"),
        ("cube", "doo-sabin"),
        ("prism-5", "catmull-clark"),
    ] {
        let c = gallery_complex(name, scheme, 3);
        let faces = crate::gallery::all()
            .into_iter()
            .find(|(n, _)| n == name)
            .unwrap()
            .1
            .num_faces();
        let m = measure(&c, &MeasureOptions::default());
        let f = face_areas(&c, faces, AREA_TOLERANCE);
        let total: f64 = f.areas.iter().sum::<f64>() + f.unassigned;
        assert!(
            close(total, m.area, 1e-12),
            "{name} {scheme}: {total} vs {}",
            m.area
        );
        assert!(
            f.unassigned < 1e-12 * m.area,
            "{name} {scheme}: {}",
            f.unassigned
        );
        // symmetric nets: every face the same area
        let (lo, hi) = f
            .areas
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(a, b), &x| (a.min(x), b.max(x)));
        if name != "prism-5" {
            assert!(hi - lo < 1e-9 * hi, "{name} {scheme}: {lo} .. {hi}");
        }
    }
}
