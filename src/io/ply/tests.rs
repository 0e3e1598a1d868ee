//! Unit tests of the PLY reader and writers.

use super::write::header_text;
use super::*;
use crate::io::Polygons;
use crate::io::testutil;
use ply_rs_bw::ply::{
    Addable, DefaultElement, ElementDef, Encoding, Ply, Property, PropertyDef, PropertyType,
    ScalarType,
};
use ply_rs_bw::writer::Writer;

fn read(bytes: &[u8]) -> Result<LoadedMesh> {
    read_ply_from(bytes, Path::new("t.ply"))
}

/// The whole message of a failed read.
fn msg(bytes: &[u8]) -> String {
    read(bytes).unwrap_err().to_string()
}

/// An ascii header of 3 float vertices and `nf` faces (lines 1..=9; payload from line 10).
fn ascii_head(nf: usize) -> String {
    format!(
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
         property float z\nelement face {nf}\nproperty list uchar int vertex_indices\nend_header\n"
    )
}

/// A binary little-endian file: 3 float vertices, one triangle with the given indices.
fn binary_triangle(indices: [i32; 3]) -> Vec<u8> {
    let mut b = b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n\
                  property float y\nproperty float z\nelement face 1\n\
                  property list uchar int vertex_indices\nend_header\n"
        .to_vec();
    for p in [[0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]] {
        for c in p {
            b.extend_from_slice(&c.to_le_bytes());
        }
    }
    b.push(3);
    for v in indices {
        b.extend_from_slice(&v.to_le_bytes());
    }
    b
}

/// A PLY built with ply-rs-bw's own writer: float coordinates, ushort-counted uint lists,
/// an extra element and extra properties.
fn crate_written(encoding: Encoding, double: bool) -> Vec<u8> {
    let mut ply = Ply::<DefaultElement>::new();
    ply.header.encoding = encoding;
    let mut v = ElementDef::new("vertex".to_string());
    let st = if double {
        ScalarType::Double
    } else {
        ScalarType::Float
    };
    for c in ["x", "y", "z"] {
        v.properties.add(PropertyDef::new(
            c.to_string(),
            PropertyType::Scalar(st.clone()),
        ));
    }
    v.properties.add(PropertyDef::new(
        "red".to_string(),
        PropertyType::Scalar(ScalarType::UChar),
    ));
    ply.header.elements.add(v);
    let mut f = ElementDef::new("face".to_string());
    f.properties.add(PropertyDef::new(
        "vertex_index".to_string(),
        PropertyType::List(ScalarType::UShort, ScalarType::UInt),
    ));
    ply.header.elements.add(f);
    let mut e = ElementDef::new("edge".to_string());
    e.properties.add(PropertyDef::new(
        "vertex1".to_string(),
        PropertyType::Scalar(ScalarType::Int),
    ));
    ply.header.elements.add(e);
    let pts = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.5],
        [0.0, 1.0, 0.0],
        [0.5, 2.0, 0.25],
    ];
    let verts: Vec<DefaultElement> = pts
        .iter()
        .map(|p| {
            let mut el = DefaultElement::new();
            for (k, c) in ["x", "y", "z"].into_iter().enumerate() {
                let prop = if double {
                    Property::Double(p[k])
                } else {
                    Property::Float(p[k] as f32)
                };
                el.insert(c.to_string(), prop);
            }
            el.insert("red".to_string(), Property::UChar(200));
            el
        })
        .collect();
    ply.payload.insert("vertex".to_string(), verts);
    let faces: Vec<DefaultElement> = [vec![0u32, 1, 2, 3], vec![3, 2, 4]]
        .into_iter()
        .map(|f| {
            let mut el = DefaultElement::new();
            el.insert("vertex_index".to_string(), Property::ListUInt(f));
            el
        })
        .collect();
    ply.payload.insert("face".to_string(), faces);
    let mut edge = DefaultElement::new();
    edge.insert("vertex1".to_string(), Property::Int(3));
    ply.payload.insert("edge".to_string(), vec![edge]);
    let mut buf = Vec::new();
    Writer::new().write_ply(&mut buf, &mut ply).unwrap();
    buf
}

fn check_five(m: &LoadedMesh) {
    assert_eq!(m.mesh.num_vertices(), 5);
    assert_eq!(m.mesh.face(0), &[0, 1, 2, 3]);
    assert_eq!(m.mesh.face(1), &[3, 2, 4]);
    assert_eq!(m.mesh.position(2), [1.0, 1.0, 0.5]);
    assert_eq!(m.mesh.position(4), [0.5, 2.0, 0.25]);
    assert_eq!(m.warnings, vec!["ignored PLY elements: edge".to_string()]);
}

#[crate::unit::test]
fn reads_all_encodings_written_by_ply_rs() {
    for enc in [
        Encoding::Ascii,
        Encoding::BinaryLittleEndian,
        Encoding::BinaryBigEndian,
    ] {
        for double in [false, true] {
            let bytes = crate_written(enc, double);
            let m = read(&bytes).unwrap_or_else(|e| panic!("{enc:?} {double}: {e}"));
            check_five(&m);
        }
    }
}

#[crate::unit::test]
fn reads_hand_written_big_endian_with_int_coordinates() {
    let mut b = b"ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty short x\n\
                  property int y\nproperty uchar z\nelement face 1\n\
                  property list uchar short vertex_indices\nend_header\n"
        .to_vec();
    for (x, y, z) in [(-1i16, 0i32, 7u8), (1, 0, 7), (0, 2, 9)] {
        b.extend_from_slice(&x.to_be_bytes());
        b.extend_from_slice(&y.to_be_bytes());
        b.push(z);
    }
    b.push(3);
    for v in [0i16, 1, 2] {
        b.extend_from_slice(&v.to_be_bytes());
    }
    let m = read(&b).unwrap();
    assert_eq!(
        m.mesh.positions(),
        &[[-1.0, 0.0, 7.0], [1.0, 0.0, 7.0], [0.0, 2.0, 9.0]]
    );
    assert_eq!(m.mesh.face(0), &[0, 1, 2]);
}

#[crate::unit::test]
fn missing_elements_and_properties_are_named_at_their_header_line() {
    let m = msg(b"ply\nformat ascii 1.0\nelement point 1\nproperty float x\nend_header\n1\n");
    assert_eq!(
        m,
        "t.ply:5: no 'vertex' element in the PLY header (elements: 'point')"
    );
    let m = msg(
        b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n1 2\n",
    );
    assert_eq!(m, "t.ply:3: element 'vertex' has no property 'z'");
    let m = msg(
        b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n1 2 3\n",
    );
    assert!(m.starts_with("t.ply:7: no 'face' element"), "{m}");
    let m = msg(
        b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nelement face 0\nproperty list uchar int idx\nend_header\n1 2 3\n",
    );
    assert_eq!(
        m,
        "t.ply:7: element 'face' has neither a 'vertex_indices' nor a 'vertex_index' list property"
    );
    let m = msg(
        b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nelement face 0\nproperty list uchar float vertex_indices\nend_header\n1 2 3\n",
    );
    assert!(
        m.starts_with("t.ply:7: ") && m.contains("list of integers"),
        "{m}"
    );
    let m = msg(format!("{}0 0 0\n1 0 0\n0 1 0\n", ascii_head(0)).as_bytes());
    assert_eq!(
        m,
        "t.ply:7: the 'face' element is empty (3 vertices); fairsub needs a polygon mesh"
    );
}

#[crate::unit::test]
fn header_errors_name_their_line() {
    assert_eq!(
        msg(b"PLY file\n"),
        "t.ply:1: not a PLY file: the first line is 'PLY file', not 'ply'"
    );
    assert_eq!(
        msg(b""),
        "t.ply:1: empty file: expected the PLY header ('ply' on the first line)"
    );
    assert_eq!(
        msg(b"ply\nformat ascii 1.0\nelement vertex 3\n"),
        "t.ply:3: file ends in the PLY header: no 'end_header' line"
    );
    let m = msg(b"ply\nformat ascii 1.0\nelemnt vertex 3\nend_header\n");
    assert!(
        m.starts_with("t.ply:3: PLY header: ") && m.ends_with(": 'elemnt vertex 3'"),
        "{m}"
    );
    let m = msg(b"ply\nelement vertex 3\nend_header\n");
    assert!(m.starts_with("t.ply:3: PLY header: "), "{m}");
}

#[crate::unit::test]
fn ascii_errors_name_line_element_and_property() {
    let head = ascii_head(2);
    // Lines 10..12 vertices, 13..14 faces.
    let m = msg(format!("{head}0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 5\n").as_bytes());
    assert_eq!(
        m,
        "t.ply:14: face 1 refers to vertex 5, but the file has 3 vertices (indices 0..2)"
    );
    let m = msg(format!("{head}0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2\n").as_bytes());
    assert!(
        m.starts_with("t.ply:14: invalid mesh: ") && m.contains("inconsistent orientation"),
        "{m}"
    );
    let cases = [
        (
            "0 0 0\n1 zz 0\n",
            "t.ply:11: vertex 1: property 'y' is 'zz', not of type float",
        ),
        (
            "0 0 0\n1 0\n",
            "t.ply:11: vertex 1: the line ends before property 'z' (float)",
        ),
        (
            "0 0 0\n1 0 0 7\n",
            "t.ply:11: vertex 1: the line has 1 more value than the properties of element 'vertex' take",
        ),
        (
            "0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n",
            "t.ply:13: face 0: list 'vertex_indices' announces 4 entries but the line has 3",
        ),
        (
            "0 0 0\n1 0 0\n0 1 0\n3 0 1 2.5\n",
            "t.ply:13: face 0: property 'vertex_indices' is '2.5', not of type int",
        ),
        (
            "0 0 0\n1 0 0\n0 1 0\n-3 0 1 2\n",
            "t.ply:13: face 0: property 'vertex_indices' is '-3', not of type uchar",
        ),
        (
            "0 0 0\n1 0 0\n0 1 0\n2 0 1\n",
            "t.ply:13: face 0 has 2 corners; a face needs at least 3",
        ),
        (
            "0 0 0\n1 0 0\n",
            "t.ply:11: file ends after 2 of the 3 'vertex' elements the header announces",
        ),
        (
            "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
            "t.ply:13: file ends after 1 of the 2 'face' elements the header announces",
        ),
    ];
    for (body, want) in cases {
        assert_eq!(msg(format!("{head}{body}").as_bytes()), want, "{body:?}");
    }
}

#[crate::unit::test]
fn invalid_utf8_only_in_comments() {
    let head = ascii_head(1);
    let body = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    // A Latin-1 byte in a comment (and in obj_info) is fine.
    let with_comment = head.replacen(
        "format ascii 1.0\n",
        "format ascii 1.0\ncomment caf\u{1}\nobj_info \u{1}\n",
        1,
    );
    let mut b = with_comment.into_bytes();
    for x in b.iter_mut().filter(|x| **x == 1) {
        *x = 0xE9;
    }
    b.extend_from_slice(body.as_bytes());
    assert_eq!(read(&b).unwrap().mesh.num_faces(), 1);
    // Elsewhere in the header, or in the ascii payload: an error at its line and column.
    let mut b = head
        .replacen("element face", "element f\u{1}ce", 1)
        .into_bytes();
    let k = b.iter().position(|&x| x == 1).unwrap();
    b[k] = 0xE9;
    b.extend_from_slice(body.as_bytes());
    assert_eq!(
        msg(&b),
        "t.ply:7: invalid UTF-8 at column 10 (byte 0xE9): fairsub reads text as UTF-8 and allows \
         other bytes only in comments"
    );
    let mut b = format!("{head}0 0 0\n1 0 \u{1}\n0 1 0\n3 0 1 2\n").into_bytes();
    let k = b.iter().position(|&x| x == 1).unwrap();
    b[k] = 0xFF;
    assert!(msg(&b).starts_with("t.ply:11: invalid UTF-8 at column 5 (byte 0xFF)"));
}

#[crate::unit::test]
fn binary_errors_name_the_file_and_the_element() {
    let m = msg(&binary_triangle([0, -1, 2]));
    assert_eq!(
        m,
        "t.ply: face 0 (counted from 0) refers to vertex -1, but the file has 3 vertices (indices 0..2)"
    );
    // Truncated inside the face, and inside the vertices.
    let b = binary_triangle([0, 1, 2]);
    assert_eq!(
        msg(&b[..b.len() - 3]),
        "t.ply: binary 'face' data ends after 0 of the 1 elements the header announces (the file \
         is truncated)"
    );
    assert_eq!(
        msg(&b[..b.len() - 13 - 6]),
        "t.ply: binary 'vertex' data ends after 2 of the 3 elements the header announces (the \
         file is truncated)"
    );
    // A mesh error without a line names the file.
    let mut two = binary_triangle([0, 1, 2]);
    two.extend_from_within(two.len() - 13..);
    let k = two.windows(7).position(|w| w == b"face 1\n").unwrap();
    two[k + 5] = b'2';
    let m = msg(&two);
    assert!(
        m.starts_with("t.ply: invalid mesh: faces 0 and 1 both use edge")
            && m.ends_with("(faces and vertices counted from 0 in file order)"),
        "{m}"
    );
    // A negative list count of a signed count type.
    let mut b = binary_triangle([0, 1, 2]);
    let k = b.windows(11).position(|w| w == b"list uchar ").unwrap();
    b.splice(k + 5..k + 10, b"char".iter().copied());
    let n = b.len();
    b[n - 13] = 0xFF;
    let m = msg(&b);
    assert!(
        m.starts_with(
            "t.ply: binary 'face' element 0 (counted from 0): List length cannot be negative"
        ),
        "{m}"
    );
}

#[crate::unit::test]
fn binary_writer_layout() {
    let p = testutil::polygons();
    let mut buf = Vec::new();
    write_ply_binary_to(&mut buf, &p).unwrap();
    // header + 5 * 24 bytes + (1 + 16) + (1 + 12)
    let header = header_text(&p, "binary_little_endian");
    assert!(header.contains("property list uchar int vertex_indices"));
    assert_eq!(buf.len(), header.len() + 5 * 24 + 17 + 13);
    assert!(buf.starts_with(header.as_bytes()));
}

#[crate::unit::test]
fn parallel_binary_writer_equals_a_plain_encoding() {
    // Enough vertices and faces for many jobs and batches; mixed face sizes.
    let n = 300_000;
    let pos: Vec<[f64; 3]> = (0..n)
        .map(|i| [i as f64, (i as f64).sqrt(), -(i as f64) / 7.0])
        .collect();
    let mut fs = vec![0u32];
    let mut corners = Vec::new();
    let mut v = 0u32;
    while (v as usize) + 5 < n {
        let k = 3 + (v % 3);
        corners.extend(v..v + k);
        fs.push(corners.len() as u32);
        v += 2;
    }
    let p = Polygons::new(&pos, &fs, &corners).unwrap();
    let mut fast = Vec::new();
    write_ply_binary_to(&mut fast, &p).unwrap();
    let mut plain = header_text(&p, "binary_little_endian").into_bytes();
    for q in &pos {
        for c in q {
            plain.extend_from_slice(&c.to_le_bytes());
        }
    }
    for f in 0..p.num_faces() {
        plain.push(p.face(f).len() as u8);
        for &v in p.face(f) {
            plain.extend_from_slice(&v.to_le_bytes());
        }
    }
    assert!(fast == plain, "encodings differ");
}
