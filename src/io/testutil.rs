//! Fixtures shared by the unit tests of the readers and writers.

use super::{LoadedMesh, Polygons};
use crate::bezier::BezierPatch;
use crate::geom::Point;
use crate::surface::{Element, PatchComplex, Provenance};

/// Points that need every digit (and exponents, and a negative zero) to read back exactly.
pub const POINTS: [Point; 5] = [
    [0.1, -2.0 / 3.0, 1e-300],
    [1.0, 0.0, 12345.678901234567],
    [1.0, 1.0, -0.0],
    [0.0, 1.0, 3.0e20],
    [0.5, 2.0, -7.5],
];

/// A quad and a triangle over [`POINTS`].
pub fn polygons() -> Polygons<'static> {
    Polygons::new(&POINTS, &[0, 4, 7], &[0, 1, 2, 3, 3, 2, 4]).unwrap()
}

/// Asserts that a mesh read back is [`polygons`] exactly, without warnings.
pub fn assert_is_fixture(m: &LoadedMesh) {
    let bits = |p: &[Point]| -> Vec<u64> { p.iter().flatten().map(|x| x.to_bits()).collect() };
    assert_eq!(bits(m.mesh.positions()), bits(&POINTS));
    assert_eq!(m.mesh.num_faces(), 2);
    assert_eq!(m.mesh.face(0), &[0, 1, 2, 3]);
    assert_eq!(m.mesh.face(1), &[3, 2, 4]);
    assert!(m.warnings.is_empty(), "{:?}", m.warnings);
}

/// A patch of bi-degree `(du, dv)` whose coefficient `b[i][j]` (number `k` in storage order)
/// is `point(i, j, k)`.
pub fn patch(du: usize, dv: usize, point: impl Fn(usize, usize, usize) -> Point) -> BezierPatch {
    let cps = (0..(du + 1) * (dv + 1))
        .map(|k| point(k / (dv + 1), k % (dv + 1), k))
        .collect();
    BezierPatch::new(du, dv, cps)
}

/// A patch complex of regular patches (`None`: the next regular face) and ring / cap patches
/// of `element` (`Some((ring, sector))`, ring 0 meaning the cap).
pub fn complex(element: Element, items: Vec<(BezierPatch, Option<(u32, u32)>)>) -> PatchComplex {
    let mut c = PatchComplex::new();
    let mut face = 0;
    for (p, at) in items {
        let prov = match at {
            None => {
                face += 1;
                Provenance::Regular { face: face - 1 }
            }
            Some((0, sector)) => Provenance::Cap { element, sector },
            Some((ring, sector)) => Provenance::Ring {
                element,
                ring,
                sector,
            },
        };
        c.push(p, prov);
    }
    c
}

/// Checks the parse errors of a reader: each case is an input, the line the error must name
/// and parts its message must contain.
pub fn assert_parse_errors<T: std::fmt::Debug>(
    read: impl Fn(&str) -> crate::error::Result<T>,
    cases: &[(&str, usize, &[&str])],
) {
    for &(src, line, parts) in cases {
        match read(src) {
            Err(crate::error::Error::Parse { line: l, msg, .. }) => {
                assert_eq!(l, line, "{src:?}: {msg}");
                assert!(parts.iter().all(|p| msg.contains(p)), "{src:?}: {msg}");
            }
            other => panic!("{src:?}: expected a parse error, got {other:?}"),
        }
    }
}

/// The end of every message about invalid UTF-8 (see the `text` module).
pub const UTF8_RULE: &str = "fairsub reads text as UTF-8 and allows other bytes only in comments";

/// The text rule for a reader of bytes: `ok` (invalid bytes in comments only) reads, `bad`
/// fails with exactly `expected` followed by `: ` and [`UTF8_RULE`]. Returns what `ok` gave.
pub fn assert_text_rule<T: std::fmt::Debug>(
    read: impl Fn(&[u8]) -> crate::error::Result<T>,
    ok: &[u8],
    bad: &[u8],
    expected: &str,
) -> T {
    let e = read(bad).unwrap_err();
    assert_eq!(e.to_string(), format!("{expected}: {UTF8_RULE}"));
    read(ok).unwrap()
}
