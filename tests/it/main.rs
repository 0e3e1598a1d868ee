//! The integration tests, one module per topic, linked into one test binary (issue 51: one
//! link instead of one per file). `cargo test --release --test it -- NAME::` runs one topic;
//! `tests/consolidate.sh` moved the former `tests/NAME.rs` files here (and moves new ones).
//!
//! Tests named `slow_*` run a peer program or a client (OpenSubdiv, OpenCASCADE, CGAL and
//! OpenMesh, usd-core, the Khronos glTF-Validator, headless Chromium): `cargo test --release --
//! --list` shows them, `FAIRSUB_SKIP_SLOW=1` skips them on a laptop, and CI (`.ci/run`) never
//! does. Each says when it skipped (`-- --nocapture`). Helpers shared by the modules are in
//! `common`.

mod common;

mod acceptance_sweep;
mod analysis;
mod analysis_valences;
mod architecture;
mod batch;
mod batch_memory;
mod bi2;
mod boundary_caps;
mod bv_kinds;
mod cad_faces;
mod cad_packed;
mod classic_patches;
mod classic_schemes;
mod cli;
mod cone_caps;
mod continuity;
mod corner_caps;
mod crease_caps;
mod dart_caps;
mod derive;
mod derived_rules;
mod dual_boundary;
mod eg;
mod eval;
mod eval_caps;
mod eval_dual;
mod eval_limit_rings;
mod eval_nonbox;
mod eval_polar;
mod eval_rest;
mod eval_sharp_caps;
mod eval_ternary;
mod evalmore;
mod foldover_val2;
mod foundation;
mod fourier_analysis;
mod fuzz;
mod fvar;
mod g1cap;
mod g1cap_schemes;
mod gltf;
mod golden;
mod guided;
mod harden;
mod io;
mod loop_boundary_caps;
mod measure_rational;
mod nonbox;
mod nonbox_holes;
mod osd_peer;
mod patch_table;
mod patch_table_tracked;
mod peer_sqrt3_butterfly;
mod perf;
mod ply_data;
mod prepare;
mod prepare_holes;
mod prepare_models;
mod prepare_tagged;
mod project;
mod qas;
mod render;
mod render_api;
mod semisharp_rings;
mod sharp_bi2_nonbox;
mod sharp_caps;
mod sharp_dual;
mod sharp_loop_patches;
mod sharp_patches;
mod sqrt3_butterfly;
mod step_peer;
mod usd;
mod viewer;
mod viewer_host;
mod wedge_caps;

// Helpers shared by several modules (tests/consolidate.sh).
#[allow(dead_code)]
#[path = "cad_common/mod.rs"]
mod cad_common;
#[allow(dead_code)]
#[path = "eval"]
mod eval_helpers {
    #[path = "cli.rs"]
    pub mod cli;
    #[path = "faces.rs"]
    pub mod faces;
    #[path = "open_caps.rs"]
    pub mod open_caps;
    #[path = "ratios.rs"]
    pub mod ratios;
    #[path = "support.rs"]
    pub mod support;
}
#[allow(dead_code)]
#[path = "sharp"]
mod sharp_helpers {
    #[path = "support.rs"]
    pub mod support;
}
#[allow(dead_code)]
#[path = "viewer"]
mod viewer_helpers {
    #[path = "server.rs"]
    pub mod server;
}
// End of the shared helpers.
mod compare_refine_only;
mod public_api;
mod reference_pages;
