//! Unit tests of stencils and stencil tables.

use super::*;

#[crate::unit::test]
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

#[crate::unit::test]
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

#[crate::unit::test]
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

#[crate::unit::test]
fn short_rows_merge_to_the_bits_of_the_stable_sort() {
    // rows of 2..100 terms over few sources with weights whose sums depend on their order:
    // the linear merge of short rows must give the stable sort's sums bit for bit
    let mut x = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = move || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        x
    };
    for len in 2..100usize {
        for _ in 0..20 {
            let sources = 1 + (next() % 16) as u32;
            let pairs: Vec<(u32, f64)> = (0..len)
                .map(|_| {
                    let w = (next() >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
                    let w = if next() % 7 == 0 {
                        0.0
                    } else {
                        w * 1e3f64.powi((next() % 5) as i32)
                    };
                    ((next() % u64::from(sources)) as u32 * 3, w)
                })
                .collect();
            let mut want = pairs.clone();
            want.sort_by_key(|e| e.0);
            let mut merged: Vec<(u32, f64)> = Vec::new();
            for (i, w) in want {
                match merged.last_mut() {
                    Some(last) if last.0 == i => last.1 += w,
                    _ => merged.push((i, w)),
                }
            }
            merged.retain(|e| e.1 != 0.0);
            let mut got = pairs;
            merge_pairs(&mut got);
            let bits =
                |v: &[(u32, f64)]| v.iter().map(|e| (e.0, e.1.to_bits())).collect::<Vec<_>>();
            assert_eq!(bits(&got), bits(&merged), "{len} terms");
        }
    }
}
