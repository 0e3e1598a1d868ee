//! Tests of PGS's parameters and DS-net labels.

use super::*;

#[crate::unit::test]
fn regular_parameters_are_bi2() {
    let p = PgsParams::new(4).unwrap();
    assert_eq!(p.mu, 1.0);
    assert!((p.lambda - 0.5).abs() < 1e-15);
    assert!((p.w1 - 0.5).abs() < 1e-15 && (p.w2 - 0.125).abs() < 1e-15);
    assert!((p.alpha - 0.5).abs() < 1e-15);
    assert!(PgsParams::new(2).is_err());
}

#[crate::unit::test]
fn ds_net_labels() {
    for n in [3, 5, 8] {
        let m = ds_net(n, |_, _| 0.0).unwrap();
        let net = Pgs::facet_net(&m, 0).expect("the DS-net's facet has a DS-net");
        for s in 0..n {
            assert_eq!(net.a[s] as usize, ds_net_index(s, 0, 0));
            assert_eq!(net.b[s] as usize, ds_net_index(s, 1, 0), "b_{s}");
            assert_eq!(net.d[s] as usize, ds_net_index(s, 0, 1), "d_{s}");
        }
        // Chart walks across sectors.
        assert_eq!(ds_net_chart(n, 1, -1, 3), Some(ds_net_index(2, 1, 0)));
        assert_eq!(ds_net_chart(n, 1, 3, -1), Some(ds_net_index(0, 0, 1)));
        assert_eq!(ds_net_chart(n, 0, -1, -1), None);
    }
}

#[crate::unit::test]
fn face_corners_equal_the_corner_stencils() {
    // A facet with a DS-net (rule (4)) and one without (the outer ring's faces: Doo-Sabin).
    for n in [3, 5, 8, 40] {
        let m = ds_net(n, |x, y| 0.3 * (2.0 * x).sin() * y + 0.1 * x * x).unwrap();
        for f in 0..m.num_faces() {
            let fc = Pgs::face_corners(&m, f);
            let h0 = m.face_halfedge(f);
            for (i, p) in fc.points.iter().enumerate() {
                let st = Pgs::corner_stencil(&m, h0 + i as u32);
                let q = st.apply(m.positions());
                for k in 0..3 {
                    assert!((p[k] - q[k]).abs() < 1e-14, "n {n} face {f} corner {i}");
                }
                assert!(st.entries().iter().all(|(x, _)| fc.reads.contains(x)));
            }
        }
    }
}
