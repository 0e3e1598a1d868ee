//! Non-box subdivision: the paper's Section 4 numbers, its Fig. 10 FCV-scale series, the cube and
//! tetrahedron of Fig. 11 and the open pipe of Fig. 9, written as refined nets with FCVs, limit
//! meshes and exact patch complexes.
//!
//! Run: `cargo run --release --example nonbox -- [OUT_DIR]` (default `nonbox-out`).

use fairsub::analysis::{certify, nonbox as anb};
use fairsub::io::fcv::write_fcv_obj;
use fairsub::schemes::nonbox::surface::nonbox_complex;
use fairsub::schemes::nonbox::{FcvNet, NonBox, a_k};
use fairsub::surface::ComplexOptions;
use std::path::PathBuf;

fn main() -> fairsub::Result<()> {
    let out = PathBuf::from(
        std::env::args()
            .nth(1)
            .unwrap_or_else(|| "nonbox-out".into()),
    );
    std::fs::create_dir_all(&out).map_err(|source| fairsub::Error::Io {
        path: out.clone(),
        source,
    })?;
    println!(
        "{:>3} {:>9} {:>14} {:>9} {:>12} {:>10}",
        "k", "a_k", "lambda", "mu/l^2", "|B - print|", "injective"
    );
    for k in 3..=12 {
        let lm = anb::local_matrix(k)?;
        let s = fairsub::analysis::spectrum(&lm.matrix);
        let dev = anb::published_comparisons(k)?
            .iter()
            .filter(|c| c.quantity.starts_with("max |Fourier block"))
            .map(|c| c.difference)
            .fold(0.0, f64::max);
        let (ring, lambda) = anb::characteristic_ring(k)?;
        let cert = certify::certify_ring(&ring, lambda);
        println!(
            "{k:>3} {:>9.6} {:>14.12} {:>9.5} {:>12.1e} {:>10}",
            a_k(k),
            s.lambda,
            s.mu_over_lambda_squared,
            dev,
            cert.injective
        );
    }
    let opts = ComplexOptions {
        rings: 4,
        fill: true,
    };
    let mut nets: Vec<(String, FcvNet)> = Vec::new();
    for s in [0.5, 1.0, 1.5] {
        nets.push((
            format!("cube-fcv-{s}"),
            FcvNet::scaled(fairsub::gallery::cube(), s)?,
        ));
    }
    nets.push((
        "tetrahedron".into(),
        FcvNet::barycentric(fairsub::gallery::tetrahedron()),
    ));
    nets.push((
        "open-pipe".into(),
        FcvNet::barycentric(fairsub::gallery::open_pipe()),
    ));
    for (name, net) in &nets {
        let fine = NonBox::refine_levels(net, 2, |_| {})?;
        write_fcv_obj(&out.join(format!("{name}-net2.obj")), &fine)?;
        let limit = NonBox::limit_mesh(net, 3)?;
        fairsub::io::write_mesh(
            &out.join(format!("{name}-limit3.ply")),
            &limit,
            fairsub::io::MeshFormat::PlyBinary,
        )?;
        let c = nonbox_complex(net, opts, |_| {})?;
        fairsub::io::write_bv(&out.join(format!("{name}.bv")), &c)?;
        println!(
            "{name}: {} patches, refined net and limit mesh written",
            c.len()
        );
    }
    println!("wrote {}", out.display());
    Ok(())
}
