//! Analysis of subdivision schemes: local subdivision matrices, spectra, Fourier blocks,
//! eigenvectors, limit and tangent stencils, characteristic maps and their certificates.
//!
//! Every matrix here is assembled by applying a scheme's own refinement stencils to its local
//! net ([`local`]), never from a second copy of the rules, so the analysis proves properties of
//! exactly the code that builds surfaces. Local nets are ordered `centre points`, then sector
//! after sector with the same number of points each, which makes the discrete Fourier blocks of
//! rotationally symmetric schemes directly available.

pub mod certify;
pub mod continuity;
pub mod curvature;
pub mod local;
pub mod moments;
pub mod report;
pub mod scaled;

pub use crate::linalg::{C64, complex_eigenvalues, eigenvalues, null_space, poly_from_roots};
pub use crate::schemes::bi2::local as bi2;
pub use crate::schemes::catmull_clark::catmull_clark_lambda;
pub use crate::schemes::local::{
    Eigenvalue, FourierBlock, LocalMatrix, Spectrum, group_eigenvalues, spectrum,
};
pub use crate::schemes::nonbox::local as nonbox;
