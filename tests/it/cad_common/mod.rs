//! Helpers of the CAD face tests (`tests/it/cad_faces.rs`, `tests/it/cad_packed.rs`): gallery nets
//! and their patch complexes.

use fairsub::bezier::complex::PatchComplex;
use fairsub::mesh::PolyMesh;
use fairsub::schemes::registry;
use fairsub::surface::{ComplexOptions, build};

/// The gallery net `name`.
pub fn net(name: &str) -> PolyMesh {
    fairsub::gallery::all()
        .into_iter()
        .find(|(n, _)| n == name)
        .unwrap_or_else(|| panic!("no gallery net {name}"))
        .1
}

/// The complex of `scheme` on `mesh` with `rings` rings, filled.
pub fn complex(scheme: &str, mesh: &PolyMesh, rings: usize) -> PatchComplex {
    let spec = registry().lookup(scheme).unwrap();
    build(
        &spec,
        mesh,
        ComplexOptions { rings, fill: true },
        &mut |_| {},
    )
    .unwrap()
    .complex
}
