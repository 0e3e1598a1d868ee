//! Helpers shared by the evaluation tests (`tests/eval.rs`, `tests/eval_caps.rs`): gallery nets,
//! deterministic random numbers and a temporary directory per test process.

use fairsub::mesh::PolyMesh;

/// The gallery net `name`.
pub fn gallery(name: &str) -> PolyMesh {
    fairsub::gallery::all()
        .into_iter()
        .find(|(n, _)| n == name)
        .unwrap_or_else(|| panic!("gallery net {name}"))
        .1
}

/// Deterministic points in `[0, 1)`.
pub struct Lcg(pub u64);
impl Lcg {
    /// The next number.
    pub fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A path `name` in a temporary directory of this test process (`prefix` names the test).
pub fn tmp(prefix: &str, name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("{prefix}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir.join(name)
}
