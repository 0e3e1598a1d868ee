//! Unit tests of stencils and stencil tables.

use super::*;

#[test]
fn apply_and_compose() {
    let mut a = StencilTable::new(3);
    a.push(Stencil::from_pairs([(0, 0.5), (1, 0.5)]));
    a.push(Stencil::from_pairs([(1, 0.5), (2, 0.5)]));
    let mut b = StencilTable::new(2);
    b.push(Stencil::from_pairs([(0, 0.5), (1, 0.5)]));
    let src = [[0.0, 0.0], [2.0, 4.0], [4.0, 0.0]];
    let ab = b.compose(&a);
    assert_eq!(ab.apply(&src), b.apply(&a.apply(&src)));
    assert_eq!(ab.apply(&src)[0], [2.0, 2.0]);
    assert_eq!(ab.max_affine_defect(), 0.0);
    let sub = a.restrict_sources(&[0, 1]).map(|t| t.num_rows());
    assert_eq!(sub, None);
    let s = Stencil::from_pairs([(2, 1.0), (0, 0.25), (2, -1.0), (0, 0.75)]);
    assert_eq!(s.entries(), &[(0, 1.0)]);
}

#[test]
fn packed_tables_share_weights_and_give_the_same_bits() {
    // Rows 0..n repeat one weight vector, except row 5 (its own weights).
    let n = 10_000;
    let mut t = StencilTable::new(n);
    for r in 0..n {
        let w = if r == 5 { 0.5 } else { 0.25 };
        t.push(Stencil::from_pairs([(r, w), ((r + 1) % n, 1.0 - w)]));
    }
    let p = PackedStencilTable::new(&t);
    // The wrap-around row sorts its sources the other way: a third weight vector.
    assert_eq!(p.num_stored_weights(), 6);
    let src: Vec<[f64; 2]> = (0..n).map(|i| [i as f64, (i * i) as f64 * 0.1]).collect();
    let mut a = vec![[0.0; 2]; n];
    let mut b = vec![[0.0; 2]; n];
    t.apply_into(&src, &mut a);
    p.apply_into(&src, &mut b);
    assert_eq!(a, b);
}

#[test]
fn parallel_apply_matches_serial() {
    let n = 10_000;
    let mut t = StencilTable::new(n);
    for r in 0..n {
        t.push(Stencil::from_pairs([(r, 0.25), ((r + 1) % n, 0.75)]));
    }
    let src: Vec<[f64; 1]> = (0..n).map(|i| [i as f64]).collect();
    let out = t.apply(&src);
    for (r, o) in out.iter().enumerate() {
        assert_eq!(o[0], 0.25 * r as f64 + 0.75 * ((r + 1) % n) as f64);
    }
}
