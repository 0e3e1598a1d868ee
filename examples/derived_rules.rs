//! The full report on fairsub's derived EG and QAS+ rules (issue 15): the deviation of the
//! derived tables from every printed one, the spectra side by side with the published numbers,
//! the injectivity certificates, the constructions explored, and the cost of one derivation.
//!
//! Run: `cargo run --release --example derived_rules`. With `nets DIR N... ` it instead writes
//! the extended c-nets of the given valences in all four gallery shapes as OBJ files into `DIR`
//! (the gallery stops at 10; `docs/make-derived-images.sh` draws valences 12 and 16).

use fairsub::analysis::{self, LocalMatrix, certify};
use fairsub::schemes::eg::derive::{self as egd, EgDeriveOptions, Fit, Join, compare};
use fairsub::schemes::eg::{Eg, EgRules, facts as egfacts};
use fairsub::schemes::qas::derive as qd;
use fairsub::schemes::qas::{Qas, QasRules, facts as qfacts};
use nalgebra::DMatrix;
use std::time::Instant;

fn dense(t: &fairsub::stencil::StencilTable) -> DMatrix<f64> {
    DMatrix::from_row_slice(t.num_rows(), t.num_sources(), &t.to_dense())
}

fn eg_spectrum(r: &EgRules) -> (f64, f64, f64) {
    let lm = LocalMatrix {
        scheme: "eg-derived".into(),
        n: r.n,
        centre: 1,
        sector: 12,
        matrix: dense(&Eg::with_rules(r.clone()).step().unwrap().step),
    };
    let s = analysis::spectrum(&lm.matrix);
    let (pts, lambda) = lm.characteristic_points().unwrap();
    let ring = Eg::with_rules(r.clone()).step().unwrap().ring.apply(&pts);
    let patches: Vec<_> = (0..3 * r.n)
        .map(|k| {
            fairsub::bezier::BezierPatch::new(4, 4, ring[25 * k..25 * k + 25].to_vec()).transposed()
        })
        .collect();
    let cert = certify::certify_ring(&patches, lambda);
    let jac = if cert.injective {
        cert.jacobian_min_coefficient
    } else {
        f64::NAN
    };
    (s.lambda, s.mu_over_lambda_squared, jac)
}

fn rho_md(r: &QasRules) -> f64 {
    let a = dense(&Qas::with_rules(r.clone()).step(0.5).unwrap().step);
    let nd = 12 * r.n;
    let md = a.view((1, 1), (nd, nd)).into_owned();
    analysis::eigenvalues(&md)
        .iter()
        .map(|z| z.norm())
        .fold(0.0, f64::max)
}

/// Writes `cnet-N-SHAPE.obj` for the valences given after `nets DIR`.
fn write_nets(args: &[String]) {
    let dir = std::path::Path::new(&args[0]);
    std::fs::create_dir_all(dir).unwrap();
    for n in &args[1..] {
        let n: usize = n.parse().expect("a valence");
        for shape in fairsub::gallery::CnetShape::ALL {
            let net = fairsub::gallery::cnet(n, shape, 3);
            let path = dir.join(format!("cnet-{n}-{}.obj", shape.name()));
            fairsub::io::write_mesh(&path, &net, fairsub::io::MeshFormat::Obj).unwrap();
        }
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.first().map(String::as_str) == Some("nets") {
        return write_nets(&args[1..]);
    }
    println!(
        "# Derived EG rules ({})\n",
        compare::describe(&EgDeriveOptions::default())
    );
    println!(
        "n   time(ms)  lambda-lambda_CC  mu/l^2 derived  published  chi injective (min Jacobian coef.)"
    );
    for n in 3..=16 {
        let t = Instant::now();
        let r = egd::derive_rules(n, &EgDeriveOptions::default()).unwrap();
        let ms = t.elapsed().as_secs_f64() * 1e3;
        let (l, ratio, jac) = eg_spectrum(&r);
        let pubr = egfacts::mu_over_lambda2(n)
            .map(|x| format!("{x:.5}"))
            .unwrap_or_else(|| "-".into());
        println!(
            "{n:<3} {ms:8.1}  {:15.1e}  {ratio:14.5}  {pubr:>9}  {}",
            l - analysis::catmull_clark_lambda(n),
            if jac.is_nan() {
                "NO".to_string()
            } else {
                format!("yes ({jac:.3e})")
            }
        );
    }
    println!("\n## Deviation from the printed arrays (units of 1e-5)\n");
    for n in 3..=10 {
        if n == 4 {
            continue;
        }
        let c = compare::eg_comparison(n).unwrap();
        println!("n = {n}: max {:.0}, median {:.1}", c.max_e5, c.median_e5);
        for t in &c.tables {
            let closest = t
                .closest_row
                .map(|(r, d)| format!(", closest derived row r = {r} ({d:.0})"))
                .unwrap_or_default();
            println!(
                "  {:8} rows {:?}: max {:6.0} median {:6.1}{closest}{}",
                t.table,
                t.rows.iter().map(|x| x.0).collect::<Vec<_>>(),
                t.max_e5,
                t.median_e5,
                t.note
                    .as_ref()
                    .map(|s| format!("  [{s}]"))
                    .unwrap_or_default()
            );
        }
        if !c.a0_e5.is_empty() {
            println!(
                "  a0 (11 22 21 12 31 32): {:?}",
                c.a0_e5.iter().map(|x| x.round()).collect::<Vec<_>>()
            );
        }
    }
    println!("\n## EG constructions explored (n = 3 | n = 5: max / median, 1e-5; mu/lambda^2)\n");
    for fit in [Fit::AllEstimates, Fit::JoinedNodes] {
        for join in [Join::RayAverage, Join::MeanOfAll] {
            for fairness in [3, 4, 5] {
                for plane in [false, true] {
                    let o = EgDeriveOptions {
                        fit,
                        join,
                        fairness,
                        plane,
                    };
                    let mut line = format!(
                        "{fit:?} {join:?} F_{fairness} {:5}",
                        if plane { "plane" } else { "uv" }
                    );
                    for n in [3, 5] {
                        let r = egd::derive_rules(n, &o).unwrap();
                        let c = compare::compare_rules(&r, "");
                        let (_, ratio, _) = eg_spectrum(&r);
                        line += &format!(" | {:6.0} / {:5.1}  {ratio:.5}", c.max_e5, c.median_e5);
                    }
                    println!("{line}");
                }
            }
        }
    }

    println!("\n# Derived QAS+ tables ({})\n", qd::compare::DESCRIPTION);
    println!("n   time(ms)  rho(M_d) derived  printed   bound     Section 3 chi injective");
    for n in 3..=16 {
        let t = Instant::now();
        let r = qd::derive_tables(n, 4).unwrap();
        let ms = t.elapsed().as_secs_f64() * 1e3;
        let rho = rho_md(&r);
        let printed = QasRules::new(n)
            .ok()
            .map(|p| format!("{:.6}", rho_md(&p)))
            .unwrap_or_else(|| "-".into());
        let bound = if qfacts::BOUND_VALENCES.contains(&n) {
            format!("{}", qfacts::RHO_MD_BOUND)
        } else {
            "(1/4)".into()
        };
        let (ring, _) = qd::chi::derived_chi_ring(n).unwrap();
        let cert = certify::certify_ring(&ring, 0.5);
        println!(
            "{n:<3} {ms:8.2}  {rho:16.6}  {printed:>8}  {bound:>8}  {}",
            cert.injective
        );
    }
    println!("\n## Deviation from the printed tables (units of 1e-5)\n");
    for n in 5..=8 {
        let c = qd::compare::qas_comparison(n).unwrap();
        println!(
            "n = {n}: K max {:.0} median {:.1}; T max {:.0} median {:.1}",
            c.k_max_e5, c.k_median_e5, c.t_max_e5, c.t_median_e5
        );
        for t in &c.tables {
            println!(
                "  {:8}: max {:6.0} median {:6.1}",
                t.table, t.max_e5, t.median_e5
            );
        }
    }
    println!(
        "\n## QAS+ fairness orders explored (K max / median, T max / median; rho(M_d)) at n = 5, 6, 7\n"
    );
    for k in [3, 4, 5] {
        let mut line = format!("F_{k}");
        for n in 5..=7 {
            let r = qd::derive_tables(n, k).unwrap();
            let c = qd::compare::compare_tables(&r, "");
            line += &format!(
                " | {:5.0}/{:5.1} {:6.0}/{:6.1} {:.6}",
                c.k_max_e5,
                c.k_median_e5,
                c.t_max_e5,
                c.t_median_e5,
                rho_md(&r)
            );
        }
        println!("{line}");
    }
    println!("\n## Section 3 chi: derived z3, z4, z6 against Appendix B\n");
    for (n, b) in fairsub::schemes::qas::chi::APPENDIX_B {
        let (z, _) = qd::chi::derived_z(n).unwrap();
        let dev = [3, 4, 6]
            .iter()
            .zip(b)
            .map(|(&i, x)| (z[i] - x).abs())
            .fold(0.0, f64::max);
        println!(
            "n = {n}: z3 {:.10} z4 {:.10} z6 {:.10}  max |derived - Appendix B| {dev:.1e}",
            z[3], z[4], z[6]
        );
    }
}
