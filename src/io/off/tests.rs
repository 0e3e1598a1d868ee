//! Unit tests of the OFF reader and writer.

use super::*;
use crate::io::testutil;

fn read(s: &str) -> Result<LoadedMesh> {
    read_off_from(s.as_bytes(), Path::new("t.off"))
}

#[crate::unit::test]
fn reads_off_with_comments_and_ngons() {
    let src = "OFF # header\n# a comment\n\n5 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0.5 2 0.25\n\
               4 0 1 2 3\n3 3 2 4\n";
    let m = read(src).unwrap();
    assert_eq!(m.mesh.num_faces(), 2);
    assert_eq!(m.mesh.face(0), &[0, 1, 2, 3]);
    assert_eq!(m.mesh.face(1), &[3, 2, 4]);
    assert_eq!(m.mesh.position(4), [0.5, 2.0, 0.25]);
    assert!(m.warnings.is_empty(), "{:?}", m.warnings);
}

#[crate::unit::test]
fn reads_coff_noff_and_counts_on_header_line() {
    let src =
        "COFF 3 1 3\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n0 1 0 0 0 255 255\n3 0 1 2 10 20 30\n";
    let m = read(src).unwrap();
    assert_eq!(m.mesh.position(1), [1.0, 0.0, 0.0]);
    assert_eq!(m.mesh.face(0), &[0, 1, 2]);
    let src = "NOFF\n3 1 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n";
    let m = read(src).unwrap();
    assert_eq!(m.mesh.position(2), [0.0, 1.0, 0.0]);
    let m = read("3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 2 0 1\n").unwrap();
    assert_eq!(m.mesh.face(0), &[2, 0, 1]);
    assert_eq!(m.warnings.len(), 1);
    assert!(m.warnings[0].contains("no 'OFF' header"));
}

#[crate::unit::test]
fn errors_name_lines() {
    testutil::assert_parse_errors(
        read,
        &[
            (
                "OFF\n3 1 0\n0 0 0\n1 0 zz\n0 1 0\n3 0 1 2\n",
                4,
                &["'zz'", "vertex 1"],
            ),
            (
                "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n",
                6,
                &["vertex 3", "3 vertices"],
            ),
            (
                "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n",
                6,
                &["announces 4 corners but lists 3"],
            ),
            // The end of the file is at its last line (1 for an empty file), never line 0.
            (
                "OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n\n",
                6,
                &["file ends after 3 of 4 vertices"],
            ),
            (
                "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
                6,
                &["file ends after 1 of 2 faces"],
            ),
            ("", 1, &["empty file: expected an 'OFF' header"]),
            ("# only a comment\nOFF\n", 2, &["expected the counts line"]),
            ("OFF\n3 x 0\n", 2, &["face count 'x'"]),
            ("PLY\n", 1, &["'PLY'"]),
            (
                "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n",
                6,
                &["2 corners"],
            ),
            // A huge count in a tiny file fails cleanly (and allocates nothing big).
            (
                "OFF\n4000000000 4000000000 0\n0 0 0\n",
                3,
                &["file ends after 1 of 4000000000 vertices"],
            ),
            // Validation error mapped to the face line.
            (
                "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 2 3\n",
                8,
                &["inconsistent orientation"],
            ),
        ],
    );
    assert!(matches!(read("4OFF\n"), Err(Error::Unsupported(_))));
    assert!(matches!(read("OFF BINARY\n"), Err(Error::Unsupported(_))));
}

#[crate::unit::test]
fn invalid_utf8_is_an_error_outside_comments_only() {
    let m = testutil::assert_text_rule(
        |b| read_off_from(b, Path::new("t.off")),
        b"OFF # \xe9\n3 1 0\n0 0 0 # caf\xe9\n1 0 0\n0 1 0\n3 0 1 2\n",
        b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 \xe90\n3 0 1 2\n",
        "t.off:5: invalid UTF-8 at column 5 (byte 0xE9)",
    );
    assert_eq!(m.mesh.num_faces(), 1);
}
