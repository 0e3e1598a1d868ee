use super::*;

#[crate::unit::test]
fn quad_children_tile_the_cell() {
    // each child's centre lies in that child, and the child maps are orientation preserving
    for k in 0..4u8 {
        let m = Shape::Quad.child_map(k);
        let c = m.apply([0.5, 0.5]);
        assert_eq!(Shape::Quad.child_at(c), k);
        let det = m.e[0][0] * m.e[1][1] - m.e[1][0] * m.e[0][1];
        assert_eq!(det, 0.25);
        let back = m.invert(c);
        assert_eq!(back, [0.5, 0.5]);
    }
    // child 1: corner 1 of the parent, u toward corner 2
    let m = Shape::Quad.child_map(1);
    assert_eq!(m.apply([0.0, 0.0]), [1.0, 0.0]);
    assert_eq!(m.apply([1.0, 0.0]), [1.0, 0.5]);
    assert_eq!(m.apply([0.0, 1.0]), [0.5, 0.0]);
}

#[crate::unit::test]
fn triangle_children_tile_the_cell() {
    for k in 0..4u8 {
        let m = Shape::Triangle.child_map(k);
        let c = m.apply([1.0 / 3.0, 1.0 / 3.0]);
        assert_eq!(Shape::Triangle.child_at(c), k);
        let det = m.e[0][0] * m.e[1][1] - m.e[1][0] * m.e[0][1];
        assert_eq!(det, 0.25);
    }
    // the middle child: corners at the midpoints 0-1, 1-2, 2-0
    let m = Shape::Triangle.child_map(3);
    assert_eq!(m.apply([1.0, 0.0]), [0.5, 0.5]);
    assert_eq!(m.apply([0.0, 1.0]), [0.0, 0.5]);
}

#[crate::unit::test]
fn squares_are_the_frame_scaled() {
    for rot in 0..4u32 {
        let base = Domain::face(2, 4).child(1).rotated(rot);
        for level in 0..4u8 {
            let side = 1u32 << level;
            for i in 0..side {
                for j in 0..side {
                    let d = base.square(level, i, j);
                    assert_eq!(d.depth, 1 + level);
                    let h = 0.5f64.powi(i32::from(level));
                    let frame = base.patch_map();
                    for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.25, 0.625]] {
                        let want =
                            frame.apply([(f64::from(i) + p[0]) * h, (f64::from(j) + p[1]) * h]);
                        assert_eq!(d.patch_map().apply(p), want, "rot {rot} ({i}, {j})");
                    }
                }
            }
        }
    }
}

#[crate::unit::test]
fn domains_compose_child_maps() {
    let d = Domain::face(7, 4).child(2).child(1).rotated(3);
    assert_eq!(d.depth, 2);
    assert_eq!((d.step(1), d.step(2)), (2, 1));
    // child 2 then its child 1, patch origin at corner 3 of that cell
    let cell = Shape::Quad.child_map(2).compose(&Shape::Quad.child_map(1));
    let expect = cell.apply([0.0, 1.0]);
    assert_eq!(d.patch_map().apply([0.0, 0.0]), expect);
    let n = Domain::face(3, 5).child(4);
    assert_eq!((n.sub, n.depth), (4, 0));
    assert!(!Domain::UNTRACKED.is_tracked());
}
