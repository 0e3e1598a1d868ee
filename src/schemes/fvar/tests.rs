//! Hand-computed face-varying refinements.
