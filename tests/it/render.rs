//! Acceptance tests of the shape-interrogation renderer, asserted on the rendered buffers
//! (samples and pixels), never on golden images: a plane has zero curvature, a sphere-like
//! surface positive Gauss curvature, a cylinder straight parallel highlight lines; samples lie
//! exactly on the patches and on their pixel rays; closed surfaces leave no cracks; the output
//! is byte-for-byte deterministic; bad requests give errors that name the reason.

use fairsub::bezier::BezierPatch;
use fairsub::geom::{Point, add, dist, dot, scale, sub};
use fairsub::mesh::PolyMesh;
use fairsub::render::{self, Mode, RenderOptions, Scene, View};
use fairsub::surface::{ComplexOptions, Element, PatchComplex, Provenance};

fn cc(net: &PolyMesh, rings: usize) -> PatchComplex {
    fairsub::surface::complex(
        "catmull-clark",
        net,
        ComplexOptions { rings, fill: true },
        |_| {},
    )
    .unwrap()
}

fn opts(mode: Mode, size: usize, aa: usize) -> RenderOptions {
    RenderOptions {
        width: size,
        height: size,
        supersample: aa,
        mode,
        legend: false,
        ..RenderOptions::default()
    }
}

/// The default net's points moved into the plane `z = 0.3 x - 0.2 y + 1`.
fn tilted_plane_net() -> PolyMesh {
    let mut net = fairsub::gallery::default_net();
    let pos: Vec<Point> = net
        .positions()
        .iter()
        .map(|p| [p[0], p[1], 0.3 * p[0] - 0.2 * p[1] + 1.0])
        .collect();
    net.set_positions(pos);
    net
}

#[test]
fn a_plane_has_zero_curvature_at_every_covered_pixel() {
    // three rings: the coefficients of a patch carry rounding errors of the complex's
    // construction, which curvature divides by the patch's squared size (max |H| measured:
    // 1.0e-13 with 3 rings, 4.5e-13 with 4, 1.2e-12 with 6: the input's noise, not the
    // renderer's). The G^1 cap is the solution of a linear system (its fairness minimisation),
    // which adds its own rounding: max |H| on the cap measured 1.6e-10, so the bound is 1e-9.
    let net = tilted_plane_net();
    let scene = Scene::patches(cc(&net, 3), Some(net));
    for mode in [Mode::Gauss, Mode::Mean] {
        let mut o = opts(mode, 200, 1);
        o.view.elevation_deg = 75.0;
        let out = render::render(&scene, &o).unwrap();
        let covered: Vec<_> = out
            .frame
            .samples
            .iter()
            .filter(|s| s.is_covered())
            .collect();
        assert!(covered.len() > 10_000, "{} samples", covered.len());
        for s in &covered {
            assert!(s.gauss.abs() < 1e-9, "K = {}", s.gauss);
            assert!(s.mean.abs() < 1e-9, "H = {}", s.mean);
        }
        // the automatic range falls back to its floor and the plane is drawn white
        let r = out.range.unwrap();
        assert!(r < 1e-5, "range {r}");
        let c = out.image.get(100, 100).unwrap();
        assert!(c.iter().all(|&x| x > 190), "{c:?}");
    }
}

#[test]
fn a_sphere_like_surface_has_positive_gauss_curvature() {
    let net = fairsub::gallery::cube();
    let scene = Scene::patches(cc(&net, 4), Some(net));
    for (az, el) in [(-60.0, 40.0), (30.0, -20.0), (135.0, 70.0)] {
        let mut o = opts(Mode::Gauss, 160, 1);
        o.view.azimuth_deg = az;
        o.view.elevation_deg = el;
        let out = render::render(&scene, &o).unwrap();
        let mut n = 0;
        for s in out.frame.samples.iter().filter(|s| s.is_covered()) {
            assert!(s.gauss > 0.0, "K = {} at a covered sample", s.gauss);
            n += 1;
        }
        assert!(n > 5_000, "{n}");
        // and the picture is red where it is covered: the map of positive values
        let [lo, hi] = out.stats.gauss.unwrap();
        assert!(lo > 0.0 && hi > lo);
    }
}

/// The parabolic cylinder `z = (1 - y^2) / 2`, `|x| <= 1.5`: a bi-degree (2, 1) patch with `u`
/// across the rulings and `v` along the axis `x`.
fn cylinder() -> BezierPatch {
    let profile = [[-1.0, 0.0], [0.0, 1.0], [1.0, 0.0]];
    BezierPatch::from_fn(2, 1, |i, j| {
        [
            if j == 0 { -1.5 } else { 1.5 },
            profile[i][0],
            profile[i][1],
        ]
    })
}

/// A dome: the same profile in both directions (curved highlight lines).
fn dome() -> BezierPatch {
    let h = [0.0, 1.0, 0.0];
    BezierPatch::from_fn(2, 2, |i, j| {
        [-1.5 + 1.5 * j as f64, -1.0 + i as f64, 0.5 * (h[i] + h[j])]
    })
}

/// Where the grey level crosses the middle between the dark and light stripe colours, per
/// column: sub-pixel row positions of all crossings, for columns in the middle 60% of the
/// covered width.
fn stripe_edges(img: &render::Image) -> Vec<(f64, Vec<f64>)> {
    let grey = |x: usize, y: usize| {
        let c = img.get(x, y).unwrap();
        (c[0] as f64 + c[1] as f64 + c[2] as f64) / 3.0
    };
    let covered = |x: usize, y: usize| img.get(x, y).unwrap() != render::BACKGROUND;
    let xs: Vec<usize> = (0..img.width)
        .filter(|&x| (0..img.height).any(|y| covered(x, y)))
        .collect();
    let (x0, x1) = (xs[0], xs[xs.len() - 1]);
    let span = x1 - x0;
    let mut out = Vec::new();
    for x in x0 + span / 5..=x1 - span / 5 {
        let ys: Vec<usize> = (0..img.height).filter(|&y| covered(x, y)).collect();
        // stay two pixels away from the surface's own boundary
        let (ya, yb) = (ys[0] + 2, ys[ys.len() - 1] - 2);
        let mid = 128.0;
        let mut cross_at = Vec::new();
        for y in ya..yb {
            let (g0, g1) = (grey(x, y), grey(x, y + 1));
            if (g0 - mid) * (g1 - mid) < 0.0 {
                cross_at.push(y as f64 + 0.5 + (mid - g0) / (g1 - g0));
            }
        }
        out.push((x as f64 + 0.5, cross_at));
    }
    out
}

/// Least-squares line `y = a + b x`; returns `(a, b, max residual)`.
fn fit_line(pts: &[(f64, f64)]) -> (f64, f64, f64) {
    let n = pts.len() as f64;
    let (sx, sy) = pts
        .iter()
        .fold((0.0, 0.0), |(a, b), &(x, y)| (a + x, b + y));
    let (mx, my) = (sx / n, sy / n);
    let sxx: f64 = pts.iter().map(|&(x, _)| (x - mx) * (x - mx)).sum();
    let sxy: f64 = pts.iter().map(|&(x, y)| (x - mx) * (y - my)).sum();
    let b = sxy / sxx;
    let a = my - b * mx;
    let res = pts
        .iter()
        .map(|&(x, y)| (y - a - b * x).abs())
        .fold(0.0, f64::max);
    (a, b, res)
}

/// Fits a line to each stripe edge (edges matched across columns by their order); returns
/// `(slope, max residual)` per edge, using only columns with the most common edge count, and
/// the fraction of columns that have that count.
fn stripe_lines(img: &render::Image) -> (Vec<(f64, f64)>, f64) {
    let cols = stripe_edges(img);
    let mut counts = std::collections::BTreeMap::new();
    for (_, e) in &cols {
        *counts.entry(e.len()).or_insert(0usize) += 1;
    }
    let (&k, &ncols) = counts.iter().max_by_key(|&(_, &c)| c).unwrap();
    let lines = (0..k)
        .map(|e| {
            let pts: Vec<(f64, f64)> = cols
                .iter()
                .filter(|(_, c)| c.len() == k)
                .map(|(x, c)| (*x, c[e]))
                .collect();
            let (_, b, res) = fit_line(&pts);
            (b, res)
        })
        .collect();
    (lines, ncols as f64 / cols.len() as f64)
}

fn single_patch_scene(p: BezierPatch) -> Scene {
    let mut c = PatchComplex::new();
    c.push(p, Provenance::Unknown);
    Scene::patches(c, None)
}

fn cylinder_view() -> RenderOptions {
    let mut o = opts(Mode::Highlight, 300, 1);
    o.view = View {
        azimuth_deg: -90.0,
        elevation_deg: 55.0,
        ..View::default()
    };
    o
}

#[test]
fn a_cylinder_gives_straight_parallel_highlight_lines() {
    let out = render::render(&single_patch_scene(cylinder()), &cylinder_view()).unwrap();
    let (lines, consistent) = stripe_lines(&out.image);
    assert_eq!(consistent, 1.0, "every column crosses the same stripes");
    assert!(lines.len() >= 6, "only {} stripe edges", lines.len());
    for &(slope, res) in &lines {
        assert!(res < 0.25, "stripe edge deviates {res} px from its line");
        // light lines along the axis, which is the image's horizontal: horizontal stripes
        assert!(slope.abs() < 2e-3, "slope {slope}");
    }
    let s0 = lines[0].0;
    assert!(lines.iter().all(|&(s, _)| (s - s0).abs() < 2e-3));
}

#[test]
fn a_dome_gives_curved_highlight_lines_under_the_same_test() {
    let out = render::render(&single_patch_scene(dome()), &cylinder_view()).unwrap();
    let (lines, _) = stripe_lines(&out.image);
    assert!(!lines.is_empty());
    let worst = lines.iter().map(|&(_, r)| r).fold(0.0, f64::max);
    assert!(worst > 2.0, "a dome's stripes fit lines to {worst} px");
}

#[test]
fn samples_lie_on_their_patch_and_on_their_pixel_ray() {
    let net = fairsub::gallery::default_net();
    let c = cc(&net, 8);
    let scene = Scene::patches(c.clone(), Some(net));
    let o = opts(Mode::Shaded, 120, 2);
    let out = render::render(&scene, &o).unwrap();
    let f = &out.frame;
    assert!(
        f.exact as f64 > 0.999 * f.covered() as f64,
        "{} of {}",
        f.exact,
        f.covered()
    );
    let cam = out.camera.scaled(f.supersample);
    let mut checked = 0;
    for y in (0..f.height).step_by(7) {
        for x in (0..f.width).step_by(5) {
            let s = f.get(x, y);
            if !s.is_covered() {
                continue;
            }
            let p = f.position(s);
            let patch = &c.patches[s.prim as usize];
            let q = patch.eval(s.uv[0] as f64, s.uv[1] as f64);
            // f32 storage: parameters to 6e-8, positions to 1e-7 relative
            assert!(dist(p, q) < 1e-5, "{p:?} vs {q:?}");
            let dir = cam.ray(x as f64 + 0.5, y as f64 + 0.5);
            let w = sub(p, cam.eye);
            let off = sub(w, scale(dir, dot(w, dir)));
            let pixel = dot(w, dir) / cam.focal();
            assert!(
                fairsub::geom::norm(off) < 1e-3 * pixel + 1e-6,
                "sample off its ray by {} (pixel {pixel})",
                fairsub::geom::norm(off)
            );
            // the stored normal is the patch normal there
            let n = patch.normal(s.uv[0] as f64, s.uv[1] as f64);
            assert!(dist(s.normal(), n) < 1e-4);
            checked += 1;
        }
    }
    assert!(checked > 100);
}

#[test]
fn closed_surfaces_render_without_cracks() {
    // a cube's Catmull-Clark complex has T-junctions between every two rings
    let net = fairsub::gallery::cube();
    let scene = Scene::patches(cc(&net, 5), Some(net));
    for (az, el) in [(-60.0, 40.0), (10.0, 5.0), (100.0, -45.0)] {
        let mut o = opts(Mode::Shaded, 300, 1);
        o.view.azimuth_deg = az;
        o.view.elevation_deg = el;
        let out = render::render(&scene, &o).unwrap();
        let f = &out.frame;
        let mut holes = 0;
        for y in 1..f.height - 1 {
            for x in 1..f.width - 1 {
                if !f.get(x, y).is_covered()
                    && [(x - 1, y), (x + 1, y), (x, y - 1), (x, y + 1)]
                        .iter()
                        .all(|&(a, b)| f.get(a, b).is_covered())
                {
                    holes += 1;
                }
            }
        }
        assert_eq!(holes, 0, "view ({az}, {el})");
    }
}

#[test]
fn output_is_deterministic_whatever_the_thread_count() {
    let net = fairsub::gallery::default_net();
    let scene = Scene::patches(cc(&net, 6), Some(net));
    let mut o = opts(Mode::Highlight, 160, 2);
    o.overlays.patches = true;
    o.overlays.net = true;
    let run = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| render::render(&scene, &o).unwrap().image.to_png().unwrap())
    };
    let a = run(1);
    assert_eq!(a, run(1));
    assert_eq!(a, run(3));
    let mut m = o.clone();
    m.mode = Mode::Mean;
    m.legend = true;
    let b = render::render(&scene, &m).unwrap().image.to_png().unwrap();
    assert_eq!(
        b,
        render::render(&scene, &m).unwrap().image.to_png().unwrap()
    );
}

#[test]
fn provenance_colours_alternate_by_ring() {
    let net = fairsub::gallery::default_net();
    let c = cc(&net, 6);
    let scene = Scene::patches(c.clone(), Some(net));
    let mut o = opts(Mode::Provenance, 200, 1);
    o.view.zoom_rings = Some((1, 7));
    o.view.elevation_deg = 90.0;
    let out = render::render(&scene, &o).unwrap();
    // every covered pixel has the hue of its patch's group
    let hue = |p: &Provenance| render::shade::provenance_colour(p);
    let mut seen = std::collections::BTreeSet::new();
    for y in 0..out.frame.height {
        for x in 0..out.frame.width {
            let s = out.frame.get(x, y);
            if !s.is_covered() {
                continue;
            }
            let prov = c.provenance[s.prim as usize];
            let base = hue(&prov);
            let px = out.image.get(x, y).unwrap().map(|v| v as f64 / 255.0);
            // shading scales the colour: the channel ratios stay (up to the highlight)
            let dominant = |c: [f64; 3]| (0..3).max_by(|&a, &b| c[a].total_cmp(&c[b])).unwrap();
            if px.iter().all(|&v| v < 0.97) {
                assert_eq!(dominant(px), dominant(base), "{prov:?} at ({x}, {y})");
            }
            seen.insert(prov.group_name());
        }
    }
    for g in ["ring1", "ring2", "ring3", "cap"] {
        assert!(seen.contains(g), "{g} not visible: {seen:?}");
    }
    // odd and even rings differ
    let r1 = hue(&Provenance::Ring {
        element: Element::Vertex(0),
        ring: 1,
        sector: 0,
    });
    let r2 = hue(&Provenance::Ring {
        element: Element::Vertex(0),
        ring: 2,
        sector: 0,
    });
    assert_ne!(r1, r2);
}

#[test]
fn focus_and_zoom_frame_the_inner_rings() {
    let net = fairsub::gallery::default_net();
    let c = cc(&net, 8);
    let scene = Scene::patches(c.clone(), Some(net));
    let limit = render::camera::focus_point(&c, Element::Vertex(0)).unwrap();
    // the Catmull-Clark limit point of the centre: (n^2 e + 4 sum edge + sum face) / (n (n + 5))
    let m = fairsub::gallery::default_net();
    let n = m.valence(0) as f64;
    let mut sum = scale(m.position(0), n * n);
    for v in m.vertex_neighbors(0) {
        sum = add(sum, scale(m.position(v as usize), 4.0));
    }
    for f in m.vertex_faces(0) {
        let face = m.face(f as usize);
        let k = face.iter().position(|&v| v == 0).unwrap();
        sum = add(sum, m.position(face[(k + 2) % 4] as usize));
    }
    let exact = scale(sum, 1.0 / (n * (n + 5.0)));
    assert!(dist(limit, exact) < 1e-9, "{limit:?} vs {exact:?}");

    let mut o = opts(Mode::Shaded, 100, 1);
    o.view.focus = Some(Element::Vertex(0));
    let whole = render::render(&scene, &o).unwrap();
    assert!(dist(whole.camera.target, limit) < 1e-12);
    o.view.zoom_rings = Some((5, 8));
    let zoomed = render::render(&scene, &o).unwrap();
    assert!(dist(zoomed.camera.target, limit) < 1e-12);
    // rings 5..8 are about 2^-4 of the surface's size
    let ratio = zoomed.region.radius / whole.region.radius;
    assert!(ratio > 0.01 && ratio < 0.2, "{ratio}");
    // the centre pixel sees the cap or the innermost rings
    let s = zoomed.frame.get(50, 50);
    match c.provenance[s.prim as usize] {
        Provenance::Cap { .. } => {}
        Provenance::Ring { ring, .. } => assert!(ring >= 5, "ring {ring}"),
        p => panic!("{p:?}"),
    }
}

#[test]
fn bad_requests_name_the_reason() {
    let net = fairsub::gallery::default_net();
    let scene = Scene::patches(cc(&net, 3), Some(net.clone()));
    let err = |o: &RenderOptions| render::render(&scene, o).unwrap_err().to_string();
    let mut o = opts(Mode::Shaded, 64, 1);
    o.view.focus = Some(Element::Vertex(999));
    assert!(
        err(&o).contains("vertex 999 is out of range"),
        "{}",
        err(&o)
    );
    o.view.focus = Some(Element::Vertex(3));
    assert!(err(&o).contains("no patches of vertex 3"), "{}", err(&o));
    o.view.focus = Some(Element::Vertex(0));
    o.view.zoom_rings = Some((5, 6));
    assert!(err(&o).contains("no patches in rings 5..6"), "{}", err(&o));
    let mut o = opts(Mode::Shaded, 64, 1);
    o.width = 0;
    assert!(err(&o).contains("bad --size 0x64"), "{}", err(&o));
    let mut o = opts(Mode::Gauss, 64, 1);
    o.shade.range = Some(-1.0);
    assert!(err(&o).contains("bad --range"));
    // curvature needs patches
    let mesh = Scene::mesh(&net);
    let e = render::render(&mesh, &opts(Mode::Mean, 64, 1))
        .unwrap_err()
        .to_string();
    assert!(e.contains("needs exact patches"), "{e}");
    // a plain mesh renders shaded and with highlight lines
    let out = render::render(&mesh, &opts(Mode::Highlight, 64, 1)).unwrap();
    assert!(out.stats.covered > 500);
    // a non-finite surface is an error, not a panic
    let mut c = PatchComplex::new();
    c.push(
        BezierPatch::from_fn(1, 1, |i, j| [i as f64, j as f64, f64::NAN]),
        Provenance::Unknown,
    );
    let e = render::render(&Scene::patches(c, None), &opts(Mode::Shaded, 64, 1))
        .unwrap_err()
        .to_string();
    assert!(e.contains("non-finite"), "{e}");
}

#[test]
fn compare_shares_camera_and_range() {
    let net = fairsub::gallery::default_net();
    let a = Scene::patches(cc(&net, 4), Some(net.clone()));
    let b = Scene::patches(cc(&net, 7), Some(net.clone()));
    let modes = [Mode::Highlight, Mode::Mean];
    let o = opts(Mode::Shaded, 120, 1);
    let panel = render::compare(
        &[
            ("four".to_string(), a.clone()),
            ("seven".to_string(), b.clone()),
        ],
        &modes,
        &RenderOptions {
            legend: true,
            ..o.clone()
        },
    )
    .unwrap();
    assert_eq!(panel.ranges.len(), 1);
    assert_eq!(panel.stats.len(), 2);
    // the shared range is the automatic range over both frames together
    let fa = render::raster::rasterize(&a, &panel.camera, 1).unwrap();
    let fb = render::raster::rasterize(&b, &panel.camera, 1).unwrap();
    let r = render::auto_range(&[&fa, &fb], Mode::Mean, 0.98, panel.region.radius);
    assert_eq!(panel.ranges[0], (Mode::Mean, r));
    // 2 rows x 2 columns of 120 px cells, plus labels and one legend row
    assert!(panel.image.width > 240 && panel.image.width < 300);
    assert!(panel.image.height > 240 + 30 && panel.image.height < 360);
    // a cell of the panel equals the single picture with the panel's camera, lights and range
    let mut single = o.clone();
    single.mode = Mode::Highlight;
    let mut lights = render::Lights::new(&panel.camera, &panel.region, &single.shade);
    let period = lights.fit_period(Mode::Highlight, &[&fa, &fb]);
    assert_eq!(panel.periods, vec![(Mode::Highlight, period)]);
    let cell = render::shade::shade(
        &b,
        &fb,
        &panel.camera,
        &lights,
        Mode::Highlight,
        None,
        single.overlays,
    )
    .unwrap();
    let (x0, y0) = find_cell(&panel.image, &cell);
    assert!(x0 > 0 && y0 > 120, "second row, first column: ({x0}, {y0})");
}

/// Position of `cell` inside `img` (exhaustive search).
fn find_cell(img: &render::Image, cell: &render::Image) -> (usize, usize) {
    for y in 0..=img.height - cell.height {
        for x in 0..=img.width - cell.width {
            let same = (0..cell.height).all(|r| {
                let a = 3 * ((y + r) * img.width + x);
                let b = 3 * r * cell.width;
                img.data[a..a + 3 * cell.width] == cell.data[b..b + 3 * cell.width]
            });
            if same {
                return (x, y);
            }
        }
    }
    panic!("cell not found in the panel");
}

#[test]
fn per_ring_curvature_ranges() {
    let net = fairsub::gallery::default_net();
    let c = cc(&net, 5);
    let groups = render::stats::curvature_by_group(&c, 4);
    let names: Vec<&str> = groups.iter().map(|g| g.group.as_str()).collect();
    assert_eq!(
        names,
        [
            "regular", "ring1", "ring2", "ring3", "ring4", "ring5", "cap"
        ]
    );
    assert_eq!(groups.iter().map(|g| g.patches).sum::<usize>(), c.len());
    for g in &groups[1..6] {
        assert_eq!(g.patches, 15, "3n patches per ring");
        assert_eq!(g.element, Some(Element::Vertex(0)));
    }
    // the convex c-net: positive Gauss curvature around the extraordinary point
    for g in &groups[1..] {
        let [lo, hi] = g.gauss.unwrap();
        assert!(lo > 0.0 && hi >= lo, "{}: {lo} {hi}", g.group);
    }
    // a plane: zero everywhere
    let plane = cc(&tilted_plane_net(), 3);
    for g in render::stats::curvature_by_group(&plane, 4) {
        let [lo, hi] = g.mean.unwrap();
        // 1e-12 on the rings; the cap's linear solve adds rounding (measured 1.6e-10)
        let tol = if g.group == "cap" { 1e-9 } else { 1e-12 };
        assert!(lo.abs() < tol && hi.abs() < tol, "{}: {lo} {hi}", g.group);
    }
}

#[test]
fn bv_groups_give_back_the_provenance() {
    let net = fairsub::gallery::default_net();
    let c = cc(&net, 3);
    let text = fairsub::io::bv_to_string(&c).unwrap();
    let file = fairsub::io::parse_bv(&text, std::path::Path::new("t.bv")).unwrap();
    let back = render::complex_from_bv(&file);
    assert_eq!(back.len(), c.len());
    for (a, b) in c.provenance.iter().zip(&back.provenance) {
        assert_eq!(a.group_name(), b.group_name());
    }
    // zooming works on the recovered rings; focusing on an input vertex does not
    let scene = Scene::patches(back, None);
    let mut o = opts(Mode::Provenance, 64, 1);
    o.view.zoom_rings = Some((2, 3));
    assert!(render::render(&scene, &o).is_ok());
    o.view.focus = Some(Element::Vertex(0));
    let e = render::render(&scene, &o).unwrap_err().to_string();
    assert!(e.contains("no patches of vertex 0"), "{e}");
}

/// Reflection lines of a plane mirror: the view directions whose reflections lie in one plane
/// through the light-line direction form a plane through the eye, so the lines are straight.
#[test]
fn a_plane_mirror_gives_straight_reflection_lines() {
    let flat = BezierPatch::from_fn(1, 1, |i, j| {
        [-1.5 + 3.0 * j as f64, -1.0 + 2.0 * i as f64, 0.0]
    });
    let mut o = cylinder_view();
    o.mode = Mode::Reflection;
    o.shade.stripes = 10.0;
    let out = render::render(&single_patch_scene(flat), &o).unwrap();
    let (lines, consistent) = stripe_lines(&out.image);
    // an edge may run into the margin kept from the patch's own boundary in a few columns
    assert!(consistent > 0.9, "{consistent}");
    assert!(lines.len() >= 4, "{} edges", lines.len());
    for &(slope, res) in &lines {
        assert!(
            res < 0.25 && slope.abs() < 2e-3,
            "slope {slope}, residual {res}"
        );
    }
}

#[test]
fn the_cli_writes_pictures_and_json_and_reports_missing_patch_output() {
    let exe = env!("CARGO_BIN_EXE_fairsub");
    let dir = std::env::temp_dir().join(format!("fairsub-render-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let png = dir.join("h.png");
    let out = std::process::Command::new(exe)
        .args([
            "render",
            "gallery:cnet-5-convex",
            "-s",
            "catmull-clark",
            "-r",
            "4",
        ])
        .args([
            "-m",
            "mean",
            "--size",
            "96x80",
            "--zoom-rings",
            "2..5",
            "--json",
            "-o",
        ])
        .arg(&png)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let j: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(j["mode"], "mean");
    assert!(j["range"]["value"].as_f64().unwrap() > 0.0);
    assert_eq!(j["groups"][1]["group"], "ring1");
    let bytes = std::fs::read(&png).unwrap();
    assert_eq!(&bytes[1..4], b"PNG");

    let panel = dir.join("p.png");
    let out = std::process::Command::new(exe)
        .args([
            "compare",
            "gallery:cnet-5-convex",
            "--schemes",
            "catmull-clark,loop",
        ])
        .args(["--size", "64x64", "-o"])
        .arg(&panel)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let e = String::from_utf8_lossy(&out.stderr);
    assert!(e.contains("Loop patches need a triangle net"), "{e}");
    assert!(!panel.exists(), "nothing written after an error");

    let out = std::process::Command::new(exe)
        .args(["render", "gallery:cube", "-m", "wavy", "-o"])
        .arg(&png)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("unknown mode 'wavy'"));
    let _ = std::fs::remove_dir_all(&dir);
}
