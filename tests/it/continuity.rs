//! Continuity certificates on Catmull-Clark complexes and on a deliberately broken file.

use fairsub::analysis::continuity;
use fairsub::gallery::{self, CnetShape};
use fairsub::surface::{ComplexOptions, complex};

/// Catmull-Clark complexes are C^2 across every shared boundary between regular patches and
/// rings (every ring comes from regular sub-nets); the fill is C^0 to the rings.
#[test]
fn catmull_clark_complexes_are_c2_rings_included() {
    let nets = [
        ("cnet-3-convex", gallery::cnet(3, CnetShape::Convex, 3)),
        ("cnet-5-saddle", gallery::cnet(5, CnetShape::Saddle, 3)),
        (
            "cnet-8-planar",
            gallery::cnet(8, CnetShape::PlanarSectors, 3),
        ),
        ("cube", gallery::cube()),
        ("torus", gallery::torus_with_evs()),
        ("prism-5", gallery::prism(5)),
        ("open-pipe", gallery::open_pipe()),
    ];
    for (name, net) in nets {
        let c = complex(
            "catmull-clark",
            &net,
            ComplexOptions {
                rings: 4,
                fill: true,
            },
            |_| {},
        )
        .unwrap();
        let r = continuity::check(&c);
        let scale = r.size.max(1.0);
        for (kind, d) in &r.by_kind {
            assert!(d.c0 < 1e-12 * scale, "{name} {kind}: C0 {}", d.c0);
            if !kind.contains("cap") {
                assert!(d.c1 < 1e-10 * scale, "{name} {kind}: C1 {}", d.c1);
                assert!(d.c2 < 1e-9 * scale, "{name} {kind}: C2 {}", d.c2);
                assert!(d.g1 < 1e-9, "{name} {kind}: G1 {}", d.g1);
            }
        }
        // Closed nets give closed complexes: no open side.
        if net.boundary_loops().is_empty() {
            assert_eq!(r.open_sides, 0, "{name}");
        }
        // Joins between consecutive rings were measured.
        let between_rings = r.by_kind.keys().any(|k| {
            let parts: Vec<&str> = k.split('|').collect();
            parts.len() == 2
                && parts[0].starts_with("ring")
                && parts[1].starts_with("ring")
                && parts[0] != parts[1]
        });
        let has_evs = !net.extraordinary_vertices().is_empty() || !net.is_all_quads();
        assert_eq!(between_rings, has_evs, "{name}: {:?}", r.by_kind.keys());
    }
}

/// A file with one coefficient moved is reported at that place.
#[test]
fn a_broken_file_is_reported_where_it_is_broken() {
    let net = gallery::cnet(5, CnetShape::Convex, 3);
    let mut c = complex(
        "catmull-clark",
        &net,
        ComplexOptions {
            rings: 2,
            fill: false,
        },
        |_| {},
    )
    .unwrap();
    // Move the corner coefficient b[3][3] of a ring-2 patch by 0.01 along z.
    let k = c
        .provenance
        .iter()
        .position(|p| matches!(p, fairsub::surface::Provenance::Ring { ring: 2, .. }))
        .unwrap();
    let moved = c.patches[k].cp(3, 3);
    c.patches[k].cp_mut(3, 3)[2] += 0.01;
    let r = continuity::check(&c);
    // The corner no longer matches: either the side no longer coincides (an open side more) or a
    // defect of about 0.01 sits at the moved point.
    let clean = continuity::check(
        &complex(
            "catmull-clark",
            &net,
            ComplexOptions {
                rings: 2,
                fill: false,
            },
            |_| {},
        )
        .unwrap(),
    );
    assert!(r.open_sides > clean.open_sides || r.all.c0 > 1e-3);
    // The broken patch's sides at the moved corner are reported open, next to the moved point.
    let near: Vec<_> = r.open.iter().filter(|o| o.patch == k).collect();
    assert_eq!(
        near.len(),
        2,
        "open sides {:?}",
        r.open.iter().map(|o| o.patch).collect::<Vec<_>>()
    );
    for o in near {
        assert!(fairsub::geom::dist(o.midpoint, moved) < 0.5);
    }
}
