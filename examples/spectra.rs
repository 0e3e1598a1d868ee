//! Prints the subdominant eigenvalue of Catmull-Clark for valences 3..10, computed from the
//! scheme's own stencils, beside the closed form, with the characteristic-map certificate.
//!
//! Run: `cargo run --release --example spectra`

use fairsub::analysis::{self, certify, local};

fn main() -> fairsub::Result<()> {
    println!(
        "{:>3} {:>16} {:>16} {:>10} {:>10}",
        "n", "lambda", "closed form", "mu/l^2", "injective"
    );
    for n in 3..=10 {
        let lm = local::catmull_clark(n)?;
        let s = analysis::spectrum(&lm.matrix);
        let (ring, lambda) = local::characteristic_ring("catmull-clark", n)?;
        let cert = certify::certify_ring(&ring, lambda);
        println!(
            "{n:>3} {:>16.12} {:>16.12} {:>10.5} {:>10}",
            s.lambda,
            analysis::catmull_clark_lambda(n),
            s.mu_over_lambda_squared,
            cert.injective
        );
    }
    Ok(())
}
