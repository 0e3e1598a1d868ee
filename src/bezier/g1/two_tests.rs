//! Caps of two sectors (a valence-2 vertex, the half-plane jet of
//! [`super::centre::half_plane_rows`]): certificates per degree and layout, and on random
//! compatible data C^0 and G^1 across both spokes and a normal that tends to `T0 x T1` at the
//! centre from every direction.

use super::tests::{Lcg, assert_spoke_g1, random_hole};
use super::*;
use crate::geom::{cross, dot, norm, normalize};

#[crate::unit::test]
fn two_sector_certificates() {
    let deg = Degrees {
        boundary: 3,
        cross: 3,
    };
    for layout in [Layout::Quad, Layout::Split(2), Layout::Split(3)] {
        let mut row = Vec::new();
        for d in 3..=7 {
            let m = CapMap::new(2, layout, deg, d, Centre::TangentPlane).unwrap();
            row.push(format!(
                "{d}: {:.1e} ({} free)",
                m.certificate, m.free_parameters
            ));
            // measured: 1e-3 and more below bi-5, 5.3e-12 and less from bi-5 on
            if d < 5 {
                assert!(
                    m.certificate > 1e-4,
                    "{layout:?} d {d}: {:e}",
                    m.certificate
                );
            } else {
                assert!(m.is_certified(), "{layout:?} d {d}: {:e}", m.certificate);
            }
        }
        eprintln!("{layout:?}: {}", row.join(", "));
        let low = lowest_certified_degree(2, layout, deg, Centre::Auto).unwrap();
        assert_eq!(low, 5, "{layout:?}");
    }
    // the data of Loop's kites have degree 4; the half-plane cap is for quad sectors only
    let tris = Degrees {
        boundary: 4,
        cross: 3,
    };
    assert!(CapMap::new(2, Layout::Triangle, tris, 5, Centre::TangentPlane).is_err());
}

#[crate::unit::test]
fn two_sectors_are_g1_on_both_spokes_and_at_the_centre() {
    let mut rng = Lcg(41);
    for d in [5, 6, 7] {
        let hole = random_hole(2, Fan::Closed, d, 1, 0.0, &mut rng);
        let cap = g1_cap_with(
            &hole,
            CapOptions {
                degree: Some(d),
                centre: Centre::Auto,
            },
        )
        .unwrap();
        assert!(cap.certificate < CERTIFIED, "d {d}: {:e}", cap.certificate);
        let p = &cap.patches;
        let size = hole.data().iter().map(|p| norm(*p)).fold(0.0, f64::max);
        let twice = [p[0].clone(), p[1].clone(), p[0].clone()];
        for k in 0..=10 {
            let u = k as f64 / 10.0;
            for s in 1..=2 {
                assert_spoke_g1(&twice, s, u, size, &format!("d {d}"));
            }
        }
        let nrm = normalize(cross(hole.tangents[0], hole.tangents[1]));
        for (s, patch) in p.iter().enumerate() {
            for eps in [1e-3, 1e-4, 1e-5] {
                for a in 0..=8 {
                    let t = a as f64 * std::f64::consts::FRAC_PI_2 / 8.0;
                    let dv = patch.derivatives(eps * t.cos(), eps * t.sin());
                    let ns = normalize(cross(dv.du, dv.dv));
                    let angle = norm(cross(ns, nrm));
                    assert!(
                        dot(ns, nrm) > 0.0 && angle < 1e3 * eps,
                        "d {d} sector {s} at {eps} angle {a}: {angle:e}"
                    );
                }
            }
        }
    }
}

/// A cone point of two sectors ([`Fan::Cone`], a corner tag on a valence-2 vertex): the
/// half-turn chart's weight is `w(0) = 2 cos(pi / 2) = 0`, and the cap is certified from bi-3
/// on (measured 1.7e-15 at bi-3, 1.5e-14 at bi-5).
#[crate::unit::test]
fn cones_of_two_sectors_are_certified() {
    let deg = Degrees {
        boundary: 3,
        cross: 3,
    };
    for d in 3..=6 {
        let m = CapMap::with_fan(2, Layout::Quad, deg, d, Centre::TangentPlane, Fan::Cone).unwrap();
        assert!(m.is_certified(), "d {d}: {:e}", m.certificate);
    }
    let low = lowest_certified_fan(2, Layout::Quad, deg, Centre::TangentPlane, Fan::Cone);
    assert_eq!(low.unwrap(), 3);
}
