//! USD round trips through fairsub's own writer and reader (usd-core's view of the same files
//! is `tests/it/usd.rs`).

use super::*;
use crate::io::scene::{SceneMesh, net_tags};
use crate::mesh::tags::{CornerTag, CreaseTag, FvarInterpolation, HoleTag, Tags};

/// A 3 x 3 grid of quads with a crease, a corner, a hole and texture coordinates.
fn grid() -> crate::mesh::PolyMesh {
    let mut pos = Vec::new();
    for j in 0..4 {
        for i in 0..4 {
            pos.push([i as f64, j as f64, 0.1 * (i * j) as f64]);
        }
    }
    let faces: Vec<Vec<usize>> = (0..3)
        .flat_map(|j| {
            (0..3).map(move |i| vec![4 * j + i, 4 * j + i + 1, 4 * j + i + 5, 4 * j + i + 4])
        })
        .collect();
    let m = crate::mesh::PolyMesh::new(pos, &faces).unwrap();
    let mut tags = Tags::default();
    tags.creases.push(CreaseTag {
        a: 5,
        b: 6,
        sharpness: 2.5,
        line: 1,
    });
    tags.corners.push(CornerTag {
        vertex: 10,
        sharpness: 4.0,
        line: 1,
    });
    tags.holes.push(HoleTag { face: 8, line: 1 });
    tags.options.fvar = Some(FvarInterpolation::CornersPlus2);
    let mut m = m.with_tags(&tags, std::path::Path::new("grid")).unwrap();
    let mut ex = m.take_extras().unwrap_or_default();
    ex.uv = Some(crate::mesh::FaceVarying {
        values: (0..16)
            .map(|k| [(k % 4) as f64 / 3.0, (k / 4) as f64 / 3.0])
            .collect(),
        corners: m.corners().to_vec(),
        names: ["s".into(), "t".into()],
        classes: Vec::new(),
    });
    m.set_extras(Some(ex));
    m
}

#[crate::unit::test]
fn control_nets_round_trip_in_every_encoding() {
    let net = grid();
    let dir = std::env::temp_dir().join(format!("fairsub-usd-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (ext, flavor) in [
        ("usda", UsdFlavor::Usda),
        ("usd", UsdFlavor::Usda),
        ("usdz", UsdFlavor::Usdz),
    ] {
        let path = dir.join(format!("grid.{ext}"));
        write_usd(
            &path,
            &SceneMesh::from_net(&net, Some(net_tags(&net, "catmullClark"))),
            flavor,
        )
        .unwrap();
        let back = read_usd_with(&path, false).unwrap();
        assert!(back.warnings.is_empty(), "{ext}: {:?}", back.warnings);
        let m = back.mesh;
        assert_eq!(m.corners(), net.corners(), "{ext}");
        for (a, b) in m.positions().iter().zip(net.positions()) {
            for c in 0..3 {
                assert_eq!(a[c], b[c] as f32 as f64, "{ext}");
            }
        }
        let (x, y) = (m.extras().unwrap(), net.extras().unwrap());
        assert_eq!(x.sharp_edges, y.sharp_edges, "{ext}");
        assert_eq!(x.sharp_vertices, y.sharp_vertices, "{ext}");
        assert_eq!(x.holes, y.holes, "{ext}");
        assert_eq!(
            x.options.fvar,
            Some(FvarInterpolation::CornersPlus2),
            "{ext}"
        );
        let (u, v) = (x.uv.as_ref().unwrap(), y.uv.as_ref().unwrap());
        assert_eq!(u.corners, v.corners, "{ext}");
        assert_eq!(u.values.len(), v.values.len(), "{ext}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[crate::unit::test]
fn bad_files_name_the_attribute() {
    let dir = std::env::temp_dir().join(format!("fairsub-usd-bad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("bad.usda");
    let body = |counts: &str, idx: &str| {
        format!(
            "#usda 1.0\n\ndef Mesh \"m\"\n{{\n    point3f[] points = [(0, 0, 0), (1, 0, 0), (0, 1, 0)]\n    int[] faceVertexCounts = [{counts}]\n    int[] faceVertexIndices = [{idx}]\n}}\n"
        )
    };
    for (counts, idx, want) in [
        ("2", "0, 1", "faceVertexCounts: face 0 has 2 corners"),
        (
            "3",
            "0, 1, 7",
            "faceVertexIndices: index 2 is 7, but the mesh has 3 points",
        ),
        (
            "3",
            "0, 1, 2, 0",
            "4 indices, but faceVertexCounts add up to 3",
        ),
    ] {
        std::fs::write(&path, body(counts, idx)).unwrap();
        let e = read_usd_with(&path, false).unwrap_err().to_string();
        assert!(
            e.contains("bad.usda") && e.contains("/m.") && e.contains(want),
            "{e}"
        );
    }
    std::fs::write(&path, "#usda 1.0\ndef Xform \"x\" {}\n").unwrap();
    let e = read_usd_with(&path, false).unwrap_err().to_string();
    assert!(e.contains("no Mesh prim"), "{e}");
    std::fs::write(&path, "not usd at all").unwrap();
    assert!(read_usd_with(&path, false).is_err());
    std::fs::remove_dir_all(&dir).unwrap();
}
