//! Hand-computed face-varying refinements: two unit quads side by side whose shared edge is a
//! seam (each face its own UV island), one Catmull-Clark step.

use crate::mesh::tags::{BoundaryInterpolation, FvarInterpolation, SubdOptions};
use crate::mesh::{Extras, FaceVarying, PolyMesh};
use crate::schemes::Scheme;
use crate::schemes::catmull_clark::Configured;

/// Vertices 0 (0,0), 1 (1,0), 2 (2,0), 3 (0,1), 4 (1,1), 5 (2,1); faces (0 1 4 3), (1 2 5 4);
/// UVs: face 0 the unit square, face 1 the square shifted to u = 2..3.
fn strip() -> PolyMesh {
    let p = |x: f64, y: f64| [x, y, 0.0];
    let positions = vec![
        p(0., 0.),
        p(1., 0.),
        p(2., 0.),
        p(0., 1.),
        p(1., 1.),
        p(2., 1.),
    ];
    let mut m = PolyMesh::from_flat(positions, vec![0, 4, 8], vec![0, 1, 4, 3, 1, 2, 5, 4])
        .expect("a valid strip");
    let uv = FaceVarying {
        values: vec![
            [0., 0.],
            [1., 0.],
            [1., 1.],
            [0., 1.],
            [2., 0.],
            [3., 0.],
            [3., 1.],
            [2., 1.],
        ],
        corners: (0..8).collect(),
        names: ["u".into(), "v".into()],
        classes: Vec::new(),
    };
    m.set_extras(Some(Extras {
        uv: Some(uv),
        ..Extras::default()
    }));
    m
}

/// The UV of child vertex `c` in the child faces of parent face `f` (child face `h` is the quad
/// at parent corner `h`, so parent face 0 has child faces 0..4).
fn uv_at(fvar: FvarInterpolation, boundary: BoundaryInterpolation, c: u32, f: usize) -> [f64; 2] {
    let scheme = Configured {
        options: SubdOptions {
            fvar: Some(fvar),
            boundary: Some(boundary),
            ..SubdOptions::default()
        },
    };
    let child = crate::schemes::refine_levels(&scheme, &strip(), 1, |_| {}).unwrap();
    assert!(scheme.face_varying().is_some());
    let uv = child
        .extras()
        .and_then(|e| e.uv.as_ref())
        .expect("refined UVs");
    let k = (0..child.corners().len())
        .find(|&i| child.corners()[i] == c && i / 4 / 4 == f)
        .expect("the child corner");
    uv.values[uv.corners[k] as usize]
}

#[crate::unit::test]
fn seam_values_follow_the_option() {
    use BoundaryInterpolation::{EdgeAndCorner, EdgeOnly};
    use FvarInterpolation::*;
    // Vertex 1 in face 0: an fvar boundary value with one face. `none`: the crease rule along
    // its island's boundary, 3/4 (1,0) + 1/8 ((1,1) + (0,0)); every other option keeps it.
    assert_eq!(uv_at(None, EdgeAndCorner, 1, 0), [0.875, 0.125]);
    assert_eq!(uv_at(CornersOnly, EdgeAndCorner, 1, 0), [1.0, 0.0]);
    assert_eq!(uv_at(Boundaries, EdgeAndCorner, 1, 0), [1.0, 0.0]);
    // Its sibling in face 1: 3/4 (2,0) + 1/8 ((3,0) + (2,1)).
    assert_eq!(uv_at(None, EdgeAndCorner, 1, 1), [2.125, 0.125]);
    // The geometric corner 0: stays under edge-and-corner; under edge-only it follows the crease
    // rule with `none`, 3/4 (0,0) + 1/8 ((1,0) + (0,1)), and stays with corners-only (a smooth
    // geometric corner made an fvar corner).
    assert_eq!(uv_at(None, EdgeAndCorner, 0, 0), [0.0, 0.0]);
    assert_eq!(uv_at(None, EdgeOnly, 0, 0), [0.125, 0.125]);
    assert_eq!(uv_at(CornersOnly, EdgeOnly, 0, 0), [0.0, 0.0]);
    // The seam's edge point (child vertex 6 + edge) and the face point (child vertex 6 + 7 + f)
    // on each side: midpoints and centroids.
    let mesh = strip();
    let e = mesh.find_edge(1, 4).expect("the seam edge") + 6;
    assert_eq!(uv_at(None, EdgeAndCorner, e, 0), [1.0, 0.5]);
    assert_eq!(uv_at(None, EdgeAndCorner, e, 1), [2.0, 0.5]);
    assert_eq!(uv_at(All, EdgeAndCorner, 6 + 7 + 1, 1), [2.5, 0.5]);
}
