//! EG and QAS+ with derived rules on whole meshes (issue 15): one extraordinary vertex of each
//! valence 3..16 and meshes with several, C^2 between the bi-3 surroundings and all rings, no
//! Catmull-Clark fallback where a construction covers the valence, curvature per ring; the
//! distance between the surfaces of the printed and the derived rules; and the reports
//! (`analyze --json`, `info`, `schemes`) that name the rules used.

use fairsub::analysis::{continuity, curvature};
use fairsub::bezier::complex::{PatchComplex, Provenance};
use fairsub::gallery::{self, CnetShape};
use fairsub::mesh::{Element, PolyMesh};
use fairsub::schemes::descriptor::{Fallback, RulesChoice, Spec};
use fairsub::schemes::registry;
use fairsub::surface::ComplexOptions;
use std::f64::consts::PI;

fn spec(name: &str, rules: RulesChoice, fallback: Fallback) -> Spec {
    let mut s = registry().lookup(name).unwrap();
    s.params.rules = rules;
    s.params.fallback = fallback;
    s
}

fn build(
    name: &str,
    net: &PolyMesh,
    rules: RulesChoice,
    rings: usize,
    fill: bool,
) -> fairsub::host::SurfaceOutput {
    fairsub::surface::build(
        &spec(name, rules, Fallback::Error),
        net,
        ComplexOptions { rings, fill },
        &mut |_| {},
    )
    .unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// C^0 everywhere, C^1 and C^2 across every join that involves no cap (the bi-3 surroundings,
/// ring to ring, and inside rings).
fn assert_c2(label: &str, c: &PatchComplex) {
    let r = continuity::check(c);
    let scale = r.size.max(1.0);
    // Where the complex has regular patches, their joins to the first rings are measured too
    // (drum-7 has none: after its Catmull-Clark step every face lies in some element's rings).
    let has_regular = c
        .provenance
        .iter()
        .any(|p| matches!(p, Provenance::Regular { .. }));
    assert_eq!(
        r.by_kind.contains_key("regular|ring1"),
        has_regular,
        "{label}"
    );
    for (kind, d) in &r.by_kind {
        assert!(d.c0 < 1e-12 * scale, "{label} {kind}: C0 {}", d.c0);
        if !kind.contains("cap") {
            assert!(d.c1 < 1e-10 * scale, "{label} {kind}: C1 {}", d.c1);
            assert!(d.c2 < 1e-9 * scale, "{label} {kind}: C2 {}", d.c2);
        }
    }
}

/// The largest |K| on ring `ring` of element 0.
fn kmax(c: &[curvature::ElementCurvature], ring: u32) -> f64 {
    let r = c[0].rings.iter().find(|r| r.ring == ring).unwrap();
    r.gauss_min.abs().max(r.gauss_max.abs())
}

/// The note a derived cap gets, if any.
fn derived_note(notes: &[String], label: &str) -> bool {
    notes.iter().any(|n| n.contains(label))
}

/// What the spectrum of a scheme's local matrix at valence `n` predicts for the curvature of its
/// rings. Ring k is lambda^k chi plus the mu-components (the quadratic part) plus smaller ones,
/// so (up to the nonlinearity of K) the Gauss curvature of ring k is `P g^k + T r^k + ...`:
/// `g = mu_i mu_j / lambda^4` for the mu-cluster (eigenvalue moduli within 2% of lambda^2; the
/// rotationally symmetric and the n-fold saddle mode may differ) and `r = nu / lambda^2` for the
/// largest modulus `nu` below the cluster.
struct Prediction {
    lambda: f64,
    /// Transient ratio nu / lambda^2.
    r: f64,
    /// Smallest and largest (mu_i mu_j) / lambda^4 over the cluster.
    g: (f64, f64),
}

fn prediction(scheme: &str, n: usize) -> Prediction {
    let lm = fairsub::analysis::local::local_matrix(scheme, n).unwrap();
    let mut m: Vec<f64> = fairsub::linalg::eigenvalues(&lm.matrix)
        .iter()
        .map(|z| z.norm())
        .collect();
    m.sort_by(|a, b| b.total_cmp(a));
    let lambda = m[1];
    let l2 = lambda * lambda;
    let cluster: Vec<f64> = m
        .iter()
        .map(|x| x / l2)
        .filter(|x| (x - 1.0).abs() < 0.02)
        .collect();
    let r = m.iter().map(|x| x / l2).find(|x| *x < 0.98).unwrap();
    let (lo, hi) = cluster
        .iter()
        .fold((f64::MAX, 0.0f64), |(lo, hi), x| (lo.min(*x), hi.max(*x)));
    Prediction {
        lambda,
        r,
        g: (lo * lo, hi * hi),
    }
}

/// Curvature bounded, and what that can mean. No rule in use has mu = lambda^2 exactly except
/// QAS+ (1/4 = (1/2)^2, Section 5); EG's mu / lambda^2 is 1.00015 .. 1.05815 in the paper and
/// 0.9972 .. 1.0006 for the derived rules (tests/it/derive.rs). So K on ring k tends to `P g^k`
/// with g a hair from 1: it goes to 0 (g < 1) or to infinity (g > 1) so slowly that over all
/// rings double precision can represent (lambda^k > 1e-16) it changes by at most
/// `g_hi^k_f` (at most 1.072, at n = 7, where the saddle mode has g = 1.0012). "Bounded" is asserted
/// as: (1) past the first rings the increments of |K| per ring contract geometrically at the
/// spectrum's ratio r (plus the drift (g - 1) K that the cluster makes, also predicted), so
/// (2) the transient's remaining sum after the last ring, a geometric series bounded from the
/// measured last increment, is small, and (3) the limit estimate times the drift to the f64
/// floor stays within 6 times ring 1's curvature (the largest is 5.7, the derived EG n = 16
/// saddle: a large but decaying transient at r = 0.727). The derived EG n = 7 saddle that
/// grew 5.3% on ring 6 is this transient: r = 0.620 there, and its increments go 0.054, 0.048,
/// 0.035, 0.024, 0.015, 0.0095, 0.006, ... down to the drift 0.0012 K = 4e-4 by ring 15.
#[test]
fn one_vertex_of_each_valence_3_to_16_is_c2_with_bounded_curvature() {
    println!(
        "scheme     n  shape   r      g_hi     rings  |K| ring 1  ring R    last incr  limit est  drift to 1e-16"
    );
    for n in (3..=16).filter(|&n| n != 4) {
        for scheme in ["eg", "qas-plus"] {
            let pr = prediction(scheme, n);
            assert!(
                pr.r < 0.75 && pr.g.0 > 0.985 && pr.g.1 < 1.0015,
                "{scheme} {n}"
            );
            // Rings while lambda^R >= 1e-5 (smaller rings make K from second differences of
            // 1e-10-sized patches, where rounding shows), at most 16.
            let rings = ((1e-5f64.ln() / pr.lambda.ln()) as usize).min(16);
            for shape in [CnetShape::Convex, CnetShape::Saddle] {
                let net = gallery::cnet(n, shape, 3);
                let o = build(scheme, &net, RulesChoice::Printed, rings, true);
                let label = format!("{scheme} n={n} {shape:?}");
                assert!(o.fell_back.is_empty(), "{label}: fell back");
                let derived = format!("{scheme} (derived rules, n = {n})");
                let expect_derived = match scheme {
                    "eg" => !matches!(n, 3..=5),
                    _ => n >= 8,
                };
                assert_eq!(
                    derived_note(&o.notes, &derived),
                    expect_derived,
                    "{label}: {:?}",
                    o.notes
                );
                assert!(
                    o.notes.iter().all(|m| !m.contains("Catmull-Clark")),
                    "{label}: {:?}",
                    o.notes
                );
                if scheme == "qas-plus" && n == 3 {
                    assert!(derived_note(&o.notes, "eg rules there"), "{:?}", o.notes);
                }
                assert_c2(&label, &o.complex);
                let c = curvature::ring_curvature(&o.complex);
                let k: Vec<f64> = (1..=rings as u32).map(|r| kmax(&c, r)).collect();
                let d: Vec<f64> = k.windows(2).map(|w| w[1] - w[0]).collect();
                // The drift the cluster allows on ring j: (g - 1) K_j for g in the cluster's
                // range, with 50% margin; and a floor for rounding.
                let drift =
                    |j: usize| 1.5 * (pr.g.1 - 1.0).abs().max((1.0 - pr.g.0).abs()) * k[j] + 1e-7;
                // (1) Over the last W rings the increments beyond the drift shrink at least by
                // (r + 0.12)^W of the largest one at the window's start.
                const W: usize = 5;
                let q = pr.r + 0.12;
                let last = d.len() - 1;
                let start = d[last - W].abs().max(d[last - W - 1].abs());
                let excess = (d[last].abs() - drift(last + 1)).max(0.0);
                assert!(
                    excess <= q.powi(W as i32) * start,
                    "{label}: last increment {:.3e} (drift {:.3e}) vs {:.3e} at ring {}, r = {:.3}",
                    d[last],
                    drift(last + 1),
                    start,
                    last + 1 - W,
                    pr.r
                );
                // (2) What the transient can still add after ring R: at most the geometric
                // series of the last increment at ratio q, under 15% of K_R.
                let kr = k[rings - 1];
                let tail = d[last].abs() * q / (1.0 - q);
                assert!(tail < 0.15 * kr, "{label}: tail {tail:.3e} of {kr:.3e}");
                // (3) Limit estimate times the drift down to the f64 floor, against ring 1.
                let kf = 1e-16f64.ln() / pr.lambda.ln();
                let drift_f = pr.g.1.max(1.0).powf(kf - rings as f64);
                let bound = (kr + tail) * drift_f;
                assert!(drift_f < 1.1, "{label}: drift {drift_f}");
                assert!(
                    bound < 6.0 * k[0],
                    "{label}: {bound:.3e} vs ring 1 {:.3e}",
                    k[0]
                );
                println!(
                    "{scheme:9} {n:2}  {:7} {:.3}  {:.5}  {rings:2}     {:.3e}   {kr:.3e}  {:+.2e}  {:.3e}  x{drift_f:.4}",
                    shape.name(),
                    pr.r,
                    pr.g.1,
                    k[0],
                    d[last],
                    kr + tail,
                );
            }
        }
    }
}

/// A closed net with an `n`-gon on top and a `2n`-gon at the bottom, joined by `n` quads and
/// `n` triangles: after the Catmull-Clark step of the caps, extraordinary vertices of valence
/// `n`, `2n` and `3n` of valence 3.
fn drum(n: usize) -> PolyMesh {
    let mut pos = Vec::new();
    for j in 0..2 * n {
        let a = PI * j as f64 / n as f64;
        pos.push([1.2 * a.cos(), 1.2 * a.sin(), -0.8]);
    }
    for i in 0..n {
        let a = PI * (2 * i) as f64 / n as f64 + 0.5 * PI / n as f64;
        pos.push([0.8 * a.cos(), 0.8 * a.sin(), 0.8 + 0.1 * (i % 2) as f64]);
    }
    let b = |j: usize| j % (2 * n);
    let t = |i: usize| 2 * n + i % n;
    let mut faces: Vec<Vec<usize>> = vec![(0..2 * n).rev().collect(), (0..n).map(t).collect()];
    for i in 0..n {
        faces.push(vec![b(2 * i), b(2 * i + 1), t(i)]);
        faces.push(vec![b(2 * i + 1), b(2 * i + 2), t(i + 1), t(i)]);
    }
    PolyMesh::new(pos, &faces).unwrap()
}

#[test]
fn meshes_with_several_extraordinary_vertices_are_c2_without_fallback() {
    // Valences of the extraordinary vertices after the Catmull-Clark step of the n-gons.
    let nets = [
        ("prism-6", gallery::prism(6), vec![3, 6]),
        ("prism-8", gallery::prism(8), vec![3, 8]),
        ("drum-7", drum(7), vec![3, 7, 14]),
        ("drum-8", drum(8), vec![3, 8, 16]),
        ("torus-evs", gallery::torus_with_evs(), vec![3, 5]),
    ];
    for (name, net, valences) in nets {
        for scheme in ["eg", "qas-plus"] {
            let o = build(scheme, &net, RulesChoice::Printed, 4, true);
            let label = format!("{scheme} {name}");
            assert!(o.fell_back.is_empty(), "{label}");
            let printed: &[usize] = if scheme == "eg" { &[3, 5] } else { &[5, 6, 7] };
            for &n in &valences {
                let l = format!("{scheme} (derived rules, n = {n})");
                let expect = !(printed.contains(&n) || scheme == "qas-plus" && n == 3);
                assert_eq!(
                    derived_note(&o.notes, &l),
                    expect,
                    "{label} n={n}: {:?}",
                    o.notes
                );
            }
            let r = continuity::check(&o.complex);
            assert_eq!(r.open_sides, 0, "{label}");
            assert_c2(&label, &o.complex);
            let k = curvature::ring_curvature(&o.complex);
            assert!(k.len() >= 2, "{label}: {} capped elements", k.len());
            println!(
                "{label}: {} capped elements, {} patches, notes: {}",
                k.len(),
                o.complex.len(),
                o.notes.len()
            );
        }
    }
}

#[test]
fn only_valences_above_16_fall_back() {
    let net = gallery::cnet(17, CnetShape::Convex, 3);
    for scheme in ["eg", "qas-plus", "qas-plus-bi3", "qas-0.4"] {
        let o = fairsub::surface::build(
            &spec(scheme, RulesChoice::Printed, Fallback::CatmullClark),
            &net,
            ComplexOptions {
                rings: 2,
                fill: true,
            },
            &mut |_| {},
        )
        .unwrap();
        assert_eq!(o.fell_back, vec![(Element::Vertex(0), 17)], "{scheme}");
        let e = fairsub::surface::build(
            &spec(scheme, RulesChoice::Derived, Fallback::Error),
            &net,
            ComplexOptions {
                rings: 2,
                fill: true,
            },
            &mut |_| {},
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("vertex 0 has valence 17") && e.contains("3..=16"),
            "{scheme}: {e}"
        );
    }
}

#[test]
fn derived_rules_can_be_chosen_where_printed_ones_exist() {
    for (scheme, n) in [("eg", 3), ("eg", 5), ("qas-plus", 5), ("qas-plus", 7)] {
        let net = gallery::cnet(n, CnetShape::Saddle, 3);
        let p = build(scheme, &net, RulesChoice::Printed, 3, true);
        assert!(p.notes.is_empty(), "{scheme} {n}: {:?}", p.notes);
        let d = build(scheme, &net, RulesChoice::Derived, 3, true);
        let l = format!("{scheme} (derived rules, n = {n}), chosen by --rules derived");
        assert!(derived_note(&d.notes, &l), "{:?}", d.notes);
        // The name suffix means the same.
        let s = registry().lookup(&format!("{scheme}-derived")).unwrap();
        assert_eq!(s.params.rules, RulesChoice::Derived);
        assert_c2(&format!("{scheme}-derived {n}"), &d.complex);
    }
}

/// Max distance between corresponding points of two complexes of the same layout, sampled on a
/// 9 x 9 grid per patch, and the largest control-point difference (an upper bound of the
/// distance, by the convex-hull property).
fn distance(a: &PatchComplex, b: &PatchComplex) -> (f64, f64) {
    assert_eq!(a.len(), b.len());
    let (mut sampled, mut bound) = (0.0f64, 0.0f64);
    for (p, q) in a.patches.iter().zip(&b.patches) {
        for (x, y) in p.cps.iter().zip(&q.cps) {
            bound = bound.max(fairsub::geom::dist(*x, *y));
        }
        for i in 0..=8 {
            for j in 0..=8 {
                let (u, v) = (i as f64 / 8.0, j as f64 / 8.0);
                sampled = sampled.max(fairsub::geom::dist(p.eval(u, v), q.eval(u, v)));
            }
        }
    }
    (sampled, bound)
}

/// Measured distances between the surfaces of the printed and the derived rules, relative to
/// the net's bounding-box diagonal (6 rings and the fill), by scheme, valence and shape.
const DISTANCES: [(&str, usize, &str, f64); 20] = [
    ("eg", 3, "convex", 1.368e-4),
    ("eg", 3, "saddle", 1.134e-4),
    ("eg", 3, "planar", 1.454e-4),
    ("eg", 3, "raised", 2.375e-4),
    ("eg", 5, "convex", 2.349e-5),
    ("eg", 5, "saddle", 2.575e-5),
    ("eg", 5, "planar", 2.439e-5),
    ("eg", 5, "raised", 8.484e-5),
    ("qas-plus", 5, "convex", 4.988e-5),
    ("qas-plus", 5, "saddle", 4.876e-5),
    ("qas-plus", 5, "planar", 1.838e-4),
    ("qas-plus", 5, "raised", 6.533e-5),
    ("qas-plus", 6, "convex", 2.806e-5),
    ("qas-plus", 6, "saddle", 5.238e-5),
    ("qas-plus", 6, "planar", 7.582e-5),
    ("qas-plus", 6, "raised", 4.231e-5),
    ("qas-plus", 7, "convex", 4.752e-5),
    ("qas-plus", 7, "saddle", 5.820e-5),
    ("qas-plus", 7, "planar", 1.226e-4),
    ("qas-plus", 7, "raised", 5.465e-5),
];

#[test]
fn distance_between_printed_and_derived_surfaces() {
    println!("scheme     n  shape   sampled / diagonal   control-point bound / diagonal");
    for (scheme, n, shape, measured) in DISTANCES {
        let s = CnetShape::ALL
            .into_iter()
            .find(|s| s.name() == shape)
            .unwrap();
        let net = gallery::cnet(n, s, 3);
        let (lo, hi) = net.bounding_box();
        let diag = fairsub::geom::dist(lo, hi);
        let p = build(scheme, &net, RulesChoice::Printed, 6, true).complex;
        let d = build(scheme, &net, RulesChoice::Derived, 6, true).complex;
        let (sampled, bound) = distance(&p, &d);
        let (rel, relb) = (sampled / diag, bound / diag);
        println!("{scheme:9} {n:2}  {shape:7} {rel:.3e}            {relb:.3e}");
        assert!(rel > 0.0 && rel <= relb + 1e-15, "{scheme} {n} {shape}");
        assert!(
            (rel - measured).abs() <= 0.002 * measured,
            "{scheme} {n} {shape}: {rel:.4e}, measured {measured:.4e}"
        );
    }
}

/// Runs a command in-process and returns its report.
fn command(words: &[&str]) -> String {
    let (r, out) = fairsub::cli::capture(|| {
        fairsub::cli::run_words(std::iter::once("fairsub").chain(words.iter().copied()))
    });
    r.unwrap_or_else(|e| panic!("{words:?}: {e}"));
    out
}

fn analyze_json(scheme: &str, n: usize, rules: &str) -> serde_json::Value {
    let n = n.to_string();
    let out = command(&[
        "analyze", "--scheme", scheme, "-n", &n, "--json", "--rules", rules,
    ]);
    serde_json::from_str(&out).unwrap()
}

/// The published entries whose quantity contains `what`: (published, computed).
fn published(v: &serde_json::Value, what: &str) -> Vec<(f64, f64)> {
    v["published"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|p| p["quantity"].as_str().unwrap().contains(what))
        .map(|p| {
            let (a, b) = (
                p["published"].as_f64().unwrap(),
                p["computed"].as_f64().unwrap(),
            );
            assert!((p["difference"].as_f64().unwrap() - (a - b).abs()).abs() < 1e-15);
            (a, b)
        })
        .collect()
}

#[test]
fn analyze_reports_every_printed_number_beside_the_computed_one() {
    // EG: mu / lambda^2 of Section 6 for the printed (3, 5) and the derived rules (3, 5..10).
    for (n, p) in fairsub::schemes::eg::facts::MU_OVER_LAMBDA2 {
        for rules in ["printed", "derived"] {
            let v = analyze_json("eg", n, rules);
            let origin = if rules == "derived" || !matches!(n, 3 | 5) {
                "derived"
            } else {
                "printed"
            };
            assert_eq!(v["rules"]["origin"], origin, "n={n}");
            let printed = published(
                &v,
                "mu / lambda^2 (Section 6 table, printed to 5 decimals), printed rules",
            );
            let derived = published(
                &v,
                "mu / lambda^2 (Section 6 table, printed to 5 decimals), derived rules",
            );
            assert_eq!(printed.len(), usize::from(matches!(n, 3 | 5)), "n={n}");
            assert_eq!(derived.len(), 1, "n={n}");
            for (a, b) in printed.iter().chain(&derived) {
                assert_eq!(*a, p);
                assert!((0.99..=1.06).contains(b), "n={n}: {b}");
            }
            if let Some((_, b)) = printed.first() {
                assert!((b - p).abs() < 1e-5, "n={n}: printed rules give {b}");
            }
            // Derived: Catmull-Clark's lambda; printed: within Section 6's 1e-3 of it.
            let lam = published(&v, "lambda: Catmull-Clark's");
            let tol = if origin == "derived" { 1e-9 } else { 1e-3 };
            assert!((lam[0].0 - lam[0].1).abs() < tol, "n={n}: {lam:?}");
            // The deviation table of the derived rules at this valence.
            let tables = v["derivation"]["tables"].as_array().unwrap();
            assert_eq!(tables.len(), 5, "n={n}");
            for t in tables {
                assert!(t["max_e5"].as_f64().unwrap() > t["median_e5"].as_f64().unwrap());
            }
        }
    }
    // QAS+: rho(M_d) of the printed tables (5, 6, 7) and the bound of Section 5 (5..10), for
    // the printed and the derived tables; the T_8 deviation at 8.
    for n in 5..=10 {
        let v = analyze_json("qas-plus", n, "printed");
        let bound = published(&v, "bound on the spectral radius of M_d");
        assert_eq!(bound.len(), if n <= 7 { 2 } else { 1 }, "n={n}");
        for (a, b) in &bound {
            assert_eq!(*a, 0.13621);
            assert!(b < a, "n={n}: rho {b}");
        }
        let of_printed = published(&v, "of the printed tables");
        if let Some(p) = fairsub::schemes::qas::facts::rho_md_of_printed(n) {
            assert_eq!(of_printed.len(), 2, "n={n}");
            let printed = published(&v, "printed tables (in use)");
            assert!(printed.iter().all(|(a, b)| a != &0.13621 || b < a));
            assert!(
                of_printed
                    .iter()
                    .any(|(a, b)| *a == p && (a - b).abs() < 1e-6)
            );
        } else {
            assert!(of_printed.is_empty());
        }
        let tables: Vec<String> = v["derivation"]["tables"]
            .as_array()
            .unwrap()
            .iter()
            .map(|t| t["table"].as_str().unwrap().to_string())
            .collect();
        match n {
            5..=7 => assert_eq!(tables.len(), 7, "n={n}: {tables:?}"),
            8 => assert_eq!(tables, vec!["T_8".to_string()]),
            _ => assert!(tables.is_empty()),
        }
    }
    // Valences without printed rules are analysed with the derived ones; above 16 an error.
    let v = analyze_json("qas-plus", 12, "printed");
    assert_eq!(v["scheme"], "qas-plus (derived rules, n = 12)");
    assert!(v["qas"]["m_d_spectral_radius"].as_f64().unwrap() < 0.25);
    assert!(v["characteristic_map"]["injective"].as_bool().unwrap());
    let v = analyze_json("eg", 16, "printed");
    assert_eq!(v["scheme"], "eg (derived rules, n = 16)");
    assert!(v["characteristic_map"]["injective"].as_bool().unwrap());
    let (r, _) = fairsub::cli::capture(|| {
        fairsub::cli::run_words(["fairsub", "analyze", "--scheme", "eg", "-n", "17"])
    });
    assert!(r.unwrap_err().to_string().contains("3..=16"));
}

#[test]
fn info_and_schemes_name_the_rules_per_valence() {
    let out = command(&["info", "gallery:cnet-7-convex", "--json"]);
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let eg = &v["rules_by_valence"]["eg"][0];
    assert_eq!(eg["valence"], 7);
    assert_eq!(eg["origin"], "derived");
    assert_eq!(eg["rules"], "eg (derived rules, n = 7)");
    assert_eq!(v["rules_by_valence"]["qas-plus"][0]["origin"], "printed");
    let text = command(&["schemes"]);
    assert!(
        text.contains("rules:      3 printed, 4 regular, 5 printed, 6..16 derived"),
        "{text}"
    );
    assert!(text.contains("17+ Catmull-Clark rings and fill"), "{text}");
    assert!(text.contains("--rules derived: 3 derived"), "{text}");
    let json: serde_json::Value = serde_json::from_str(&command(&["schemes", "--json"])).unwrap();
    let qas = json
        .as_array()
        .unwrap()
        .iter()
        .find(|r| r["name"] == "qas-plus")
        .unwrap();
    let ranges = qas["rules_by_valence"].as_array().unwrap();
    let origins: Vec<&str> = ranges
        .iter()
        .map(|r| r["origin"].as_str().unwrap())
        .collect();
    assert_eq!(
        origins,
        ["borrowed", "regular", "printed", "derived", "fallback"]
    );
    assert_eq!(ranges[3]["from"], 8);
    assert_eq!(ranges[3]["to"], 16);
    assert!(ranges[4]["to"].is_null());
}

#[test]
fn check_command_reports_c2_joins_and_curvature_per_ring_with_derived_rules() {
    let nets = [
        ("eg", "gallery:cnet-7-saddle".to_string(), 7),
        ("qas-plus", "gallery:cnet-8-convex".to_string(), 8),
        (
            "eg",
            concat!(env!("CARGO_MANIFEST_DIR"), "/docs/nets/cnet-16-saddle.obj").to_string(),
            16,
        ),
        (
            "qas-plus",
            concat!(env!("CARGO_MANIFEST_DIR"), "/docs/nets/cnet-12-saddle.obj").to_string(),
            12,
        ),
    ];
    for (scheme, net, n) in nets {
        let out = command(&["check", &net, "--scheme", scheme, "--rings", "4", "--json"]);
        let v: serde_json::Value = serde_json::from_str(&out).unwrap();
        let label = format!("{scheme} n={n}");
        let derived = format!("{scheme} (derived rules, n = {n})");
        assert!(
            v["notes"]
                .as_array()
                .unwrap()
                .iter()
                .any(|m| m.as_str().unwrap().contains(&derived)),
            "{label}: {}",
            v["notes"]
        );
        let c = &v["continuity"];
        let size = c["size"].as_f64().unwrap().max(1.0);
        let kinds = c["by_kind"].as_object().unwrap();
        assert!(kinds.contains_key("regular|ring1") && kinds.contains_key("ring3|ring4"));
        for (kind, d) in kinds {
            assert!(d["c0"].as_f64().unwrap() < 1e-12 * size, "{label} {kind}");
            if !kind.contains("cap") {
                assert!(d["c1"].as_f64().unwrap() < 1e-10 * size, "{label} {kind}");
                assert!(d["c2"].as_f64().unwrap() < 1e-9 * size, "{label} {kind}");
            }
        }
        // The per-ring curvature ranges are the library's.
        let mesh = fairsub::cli::load_net(&net).unwrap().mesh;
        let lib =
            curvature::ring_curvature(&build(scheme, &mesh, RulesChoice::Printed, 4, true).complex);
        let rings = v["curvature"][0]["rings"].as_array().unwrap();
        for r in 1..=4u32 {
            let j = rings.iter().find(|x| x["ring"] == r).unwrap();
            let (lo, hi) = (
                j["gauss_min"].as_f64().unwrap(),
                j["gauss_max"].as_f64().unwrap(),
            );
            let l = lib[0].rings.iter().find(|x| x.ring == r).unwrap();
            assert!(
                (lo - l.gauss_min).abs() < 1e-12 && (hi - l.gauss_max).abs() < 1e-12,
                "{label} ring {r}"
            );
        }
    }
}
