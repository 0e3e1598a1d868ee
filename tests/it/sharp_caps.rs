//! G^1 caps at extraordinary vertices with semi-sharp features (OpenSubdiv's tags), under
//! Catmull-Clark and Loop: the adaptive loop refines such a vertex until its sharpness is
//! spent (as OpenSubdiv's adaptive isolation does) and then caps it as a plain vertex. Until
//! 2026-12-04 these holes kept the C^0 Hermite fill: `check` at 3 rings measured 0.60 rad
//! between the fill's pieces on `cc_pole7_crease` and 0.12 rad on `loop_chain_chaikin`; the
//! regular vertices of a semi-sharp chain were filled at `rings + 2` levels before their
//! sharpness was spent (`cc_chain_chaikin_tag`: 3.3e-2 rad at 1 to 3 rings).
//!
//! Tests, at 1, 2 and 3 rings and under both crease methods: every ring and regular patch is
//! exact against the limit points of uniform refinement (`check_net`), no fill patch is left
//! (every cap patch belongs to a G^1 cap), every join is G^1 below 1e-8 rad, and every cap's
//! centre is a limit point of the uniformly refined net.

use crate::sharp_helpers::support;

use fairsub::bezier::complex::PatchComplex;
use fairsub::host::ComplexOptions;
use fairsub::mesh::PolyMesh;
use fairsub::mesh::tags::{CreaseMethod, SubdOptions};
use fairsub::schemes::Scheme;
use fairsub::schemes::{catmull_clark, loop_subdivision};
use support::{
    check_net, file_options, fill_patches, limit_points, nearest, osd, quad_samples,
    triangle_samples,
};

/// A complex, the scheme that refines the net and the scheme's parameter samples.
type Built = (PatchComplex, Box<dyn Scheme>, fn(usize) -> Vec<(f64, f64)>);

/// Checks `name` under one scheme (`cc`: Catmull-Clark, else Loop) with both crease methods;
/// at least `min_caps` G^1 caps; no open side on the closed Catmull-Clark nets.
fn semi_sharp_vertices_are_capped(name: &str, cc: bool, min_caps: usize) {
    let closed = cc && name != "cc_chain_chaikin_tag";
    let m: PolyMesh = osd(name);
    for method in [CreaseMethod::Uniform, CreaseMethod::Chaikin] {
        let subd = SubdOptions {
            crease_method: Some(method),
            ..file_options(&m)
        };
        for rings in [1, 2, 3] {
            let what = format!("{name}, {method:?}, {rings} rings");
            let opts = ComplexOptions { rings, fill: true };
            let (c, scheme, samples): Built = if cc {
                let c = catmull_clark::surface::catmull_clark_complex_with(&m, opts, subd, |_| {});
                let s = catmull_clark::Configured { options: subd };
                (c.expect(&what), Box::new(s), quad_samples)
            } else {
                let c = loop_subdivision::surface::loop_complex_with(&m, opts, subd, |_| {});
                let s = loop_subdivision::Configured { options: subd };
                (c.expect(&what), Box::new(s), triangle_samples)
            };
            let r = check_net(&what, &m, &c, scheme.as_ref(), samples, closed, false);
            assert!(c.caps.len() >= min_caps, "{what}: {} caps", c.caps.len());
            assert_eq!(fill_patches(&c), 0, "{what}: fill patches left");
            assert_eq!(r.sharp.pieces, 0, "{what}: no infinitely sharp edge");
            assert!(
                r.all.g1 < 1e-8,
                "{what}: G^1 {:e} at {:?}",
                r.all.g1,
                r.all.g1_at
            );
            // every centre is the limit point of its vertex (a vertex of the deepest level)
            let pts = limit_points(scheme.as_ref(), &m, support_levels(&c));
            for s in &c.caps {
                let d = nearest(&pts, s.hole.centre);
                assert!(
                    d < 1e-12,
                    "{what}: centre {:?} {d:e} off the limit",
                    s.hole.centre
                );
            }
        }
    }
}

/// The deepest level of the complex's rings: every cap's centre is a vertex of it.
fn support_levels(c: &PatchComplex) -> usize {
    c.provenance
        .iter()
        .filter_map(support::level_of)
        .max()
        .unwrap_or(0)
}

#[test]
fn catmull_clark_caps_semi_sharp_pole_and_chain() {
    semi_sharp_vertices_are_capped("cc_pole7_crease", true, 2);
    // valence 4 everywhere: once spent, the chain's vertices are regular (no cap, no fill)
    semi_sharp_vertices_are_capped("cc_chain_chaikin", true, 0);
    // an open grid whose chain's vertices are regular but marked while their edges are
    // semi-sharp: refined until spent, then regular patches (3.3e-2 rad in the fill before)
    semi_sharp_vertices_are_capped("cc_chain_chaikin_tag", true, 0);
}

#[test]
fn loop_caps_the_semi_sharp_chain() {
    semi_sharp_vertices_are_capped("loop_chain_chaikin", false, 2);
}
