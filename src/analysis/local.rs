//! Local subdivision matrices and characteristic rings of schemes by name: each scheme's own
//! local analysis (in its folder under [`crate::schemes`], from its own stencils), looked up in
//! the registry.

use crate::bezier::BezierPatch;
use crate::error::Result;
use crate::schemes::local::LocalMatrix;
use crate::schemes::registry;

pub use crate::mesh::nets::loop_net;
pub use crate::schemes::catmull_clark::local::local_matrix as catmull_clark;
pub use crate::schemes::doo_sabin::local::local_matrix as doo_sabin_facet;
pub use crate::schemes::eg::local::local_matrix as eg;
pub use crate::schemes::guided::local::{
    lambda as guided_lambda, local_matrix as guided, table5 as guided_table5,
};
pub use crate::schemes::loop_subdivision::local::local_matrix as loop_one_ring;
pub use crate::schemes::qas::local::{
    QasFacts, facts as qas_facts, facts_bi3 as qas_bi3_facts, local_matrix as qas,
    local_matrix_bi3 as qas_bi3,
};

/// The local rules of a named scheme (with the parameters its name's suffixes set).
fn rules(scheme: &str) -> Result<Box<dyn crate::schemes::descriptor::LocalRules>> {
    super::report::local_rules(&registry().lookup(scheme)?)
}

/// The local matrix of a scheme by name.
pub fn local_matrix(scheme: &str, n: usize) -> Result<LocalMatrix> {
    rules(scheme)?.matrix(n)
}

/// The characteristic ring of a scheme at valence `n`: the planar patches of one ring built from
/// the characteristic-map control points on the local net by the scheme's own patch code, and
/// lambda.
pub fn characteristic_ring(scheme: &str, n: usize) -> Result<(Vec<BezierPatch>, f64)> {
    rules(scheme)?.characteristic_ring(n)
}
