//! Unit tests of the shading modes.

use super::*;

#[crate::unit::test]
fn diverging_map_is_blue_white_red() {
    let b = diverging(-1.0);
    let w = diverging(0.0);
    let r = diverging(1.0);
    assert!(b[2] > b[0] && r[0] > r[2]);
    assert!(w.iter().all(|&x| x > 0.95));
    assert_eq!(diverging(5.0), r);
    assert_eq!(diverging(f64::NAN), w);
}

#[crate::unit::test]
fn highlight_parameter_matches_plane_intersection() {
    let cam = Camera::look_at([0.3, -4.0, 2.0], [0.0; 3], [0.0, 0.0, 1.0], 30.0, 100, 100);
    let region = Region {
        centre: [0.0; 3],
        radius: 1.0,
    };
    let l = Lights::new(&cam, &region, &ShadeOptions::default());
    let p = [0.2, 0.1, -0.3];
    let n = normalize([0.1, -0.5, 0.8]);
    let c = l.stripe_param(Mode::Highlight, p, n, n).unwrap();
    // intersect the normal line with the plane, take the coordinate across the lines
    let s = dot(sub(l.plane_point, p), l.plane_normal) / dot(n, l.plane_normal);
    let q = add(p, scale(n, s));
    let c2 = dot(sub(q, l.plane_point), l.across) / l.periods.highlight;
    assert!((c - c2).abs() < 1e-12, "{c} {c2}");
    // and the normal line meets the light line with that parameter
    let a = add(l.plane_point, scale(l.across, c * l.periods.highlight));
    let m = cross(n, l.line_dir);
    assert!(dot(sub(a, p), m).abs() < 1e-12);
}

#[crate::unit::test]
fn segments_clip_to_the_image() {
    let (p, q) = clip_segment([-100.0, 5.0], [200.0, 5.0], 50.0, 50.0).unwrap();
    assert_eq!((p[0], q[0]), (-1.0, 51.0));
    assert!(clip_segment([-100.0, -5.0], [200.0, -5.0], 50.0, 50.0).is_none());
}
