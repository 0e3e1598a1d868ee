//! What OpenSubdiv's `Sdc` shares across schemes, written once here and used by every scheme
//! that takes sharp features: the crease and corner rules (sharpness, the vertex rules smooth /
//! dart / crease / corner, the subdivision of sharpness, the rule plans that Catmull-Clark's and
//! Loop's kernels apply, and the sharp features of the adaptive levels; `crease`), the limit
//! masks at darts ([`dart`]) and the face-varying topology and rules ([`fvar`]).
//!
//! The schemes differ only in their smooth masks: Catmull-Clark, Loop, the dual schemes and
//! non-box read the plans of this wing and write their own masks. Nothing here imports a scheme
//! family.

pub(crate) mod crease;
pub mod dart;
pub mod fvar;
