//! Unit tests of the OBJ reader and writer.

use super::statement::parse_i64;
use super::*;
use crate::io::testutil;

fn read(s: &str) -> Result<LoadedMesh> {
    read_obj_from(s.as_bytes(), Path::new("t.obj"))
}

#[crate::unit::test]
fn reads_ngons_slash_forms_and_negative_indices() {
    let src = "# a quad and a pentagon sharing an edge\n\
               mtllib x.mtl\n\
               o thing\n\
               v 0 0 0\n\
               v 1 0 0 1.0\n\
               v 1 1 0 0.5 0.5 0.5\n\
               v 0 1 0\n\
               vt 0 0\n\
               vn 0 0 1\n\
               f 1/1 2/1/1 3//1 4\n\
               v 2 0 0\n\
               v 2.5 0.5 0\n\
               v 2 1 0\n\
               g g1\n\
               s off\n\
               usemtl m\n\
               f -6 -3 -2 -1 -5   # relative: 2 5 6 7 3 (1-based)\n";
    let m = read(src).unwrap();
    assert_eq!(m.mesh.num_vertices(), 7);
    assert_eq!(m.mesh.num_faces(), 2);
    assert_eq!(m.mesh.face(0), &[0, 1, 2, 3]);
    assert_eq!(m.mesh.face(1), &[1, 4, 5, 6, 2]);
    assert_eq!(m.mesh.position(5), [2.5, 0.5, 0.0]);
    assert_eq!(m.mesh.position(1), [1.0, 0.0, 0.0]);
    // The vt is read; the faces mix corners with and without vt indices, so they are dropped.
    assert_eq!(m.warnings.len(), 2, "{:?}", m.warnings);
    assert!(
        m.warnings[0].contains("texture coordinates ignored"),
        "{:?}",
        m.warnings
    );
    let w = &m.warnings[1];
    for part in [
        "1 'vn'",
        "1 'g'",
        "1 'o'",
        "1 's'",
        "1 'usemtl'",
        "1 'mtllib'",
    ] {
        assert!(w.contains(part), "{w}");
    }
}

#[crate::unit::test]
fn line_continuation_and_crlf() {
    let src = "v 0 0 0\r\nv 1 \\\r\n 0 0\r\nv 0 1 0\r\nf 1 2 \\\n3\r\nf 1 2 x\n";
    // Physical lines count: the bad face is on line 7.
    testutil::assert_parse_errors(read, &[(src, 7, &["'x'"])]);
    let m = read("v 0 0 0\r\nv 1 \\\r\n 0 0\r\nv 0 1 0\r\nf 1 2 \\\n3\r\n").unwrap();
    assert_eq!(m.mesh.position(1), [1.0, 0.0, 0.0]);
    assert_eq!(m.mesh.face(0), &[0, 1, 2]);
}

#[crate::unit::test]
fn dropped_vertex_is_reported() {
    let m = read("v 0 0 0\nv 9 9 9\nv 1 0 0\nv 0 1 0\nf 1 3 4\n").unwrap();
    assert_eq!(m.mesh.num_vertices(), 3);
    assert_eq!(m.mesh.position(1), [1.0, 0.0, 0.0]);
    assert_eq!(m.warnings.len(), 1);
    assert!(
        m.warnings[0].contains("1 vertices are used by no face"),
        "{}",
        m.warnings[0]
    );
    assert!(
        m.warnings[0].contains("vertex 1 on line 2"),
        "{}",
        m.warnings[0]
    );
}

#[crate::unit::test]
fn errors_name_lines() {
    testutil::assert_parse_errors(
        read,
        &[
            (
                "v 0 0 0\nv 1 0 0\nv 0 1.x 0\n",
                3,
                &["'1.x'", "y coordinate"],
            ),
            ("v 0 0 0\nv 1 0\n", 2, &["2 coordinates"]),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 0\n", 5, &["index 0"]),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\nf 1 2 3\n",
                5,
                &["vertex 9", "only 3 vertices"],
            ),
            ("v 0 0 0\nv 1 0 0\nf 1 -3 2\n", 3, &["-3"]),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", 4, &["2 vertices"]),
            // Errors about the whole file are at its last line (1 for an empty file), never 0.
            (
                "v 0 0 0\n# end\n",
                2,
                &["no faces ('f' lines) found (1 vertices read); fairsub needs a polygon mesh"],
            ),
            ("", 1, &["no faces"]),
        ],
    );
}

#[crate::unit::test]
fn invalid_utf8_is_an_error_outside_comments_only() {
    let ok = b"v 0 0 0\nv 1 0 0\nv 0 1 0\n# caf\xe9 \xff\nf 1 2 3 # \xe9\n";
    // The same byte in a coordinate: an error naming line and column, not a replaced character.
    let bad = b"v 0 0 0\nv 1 \xe9 0\nv 0 1 0\nf 1 2 3\n";
    let m = testutil::assert_text_rule(
        |b| read_obj_from(b, Path::new("t.obj")),
        ok,
        bad,
        "t.obj:2: invalid UTF-8 at column 5 (byte 0xE9)",
    );
    assert_eq!(m.mesh.num_faces(), 1);
}

#[crate::unit::test]
fn mesh_validation_errors_point_at_the_face_line() {
    testutil::assert_parse_errors(
        read,
        &[
            // Third face repeats a vertex.
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n# c\nf 1 1 2\n",
                8,
                &["face 2 uses vertex 0 more than once"],
            ),
            // Second face uses edge 1->2 in the same direction as the first.
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 3 4\n",
                6,
                &["inconsistent orientation"],
            ),
            // A NaN coordinate names the vertex line.
            ("v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", 2, &["vertex 1"]),
        ],
    );
}

#[crate::unit::test]
fn lines_across_buffer_ends_and_unicode_whitespace() {
    // A tiny reader buffer splits most lines; continuations, CRLF and comments survive.
    let src = "# x\nv 0 0 0\r\nv 1 0 0 # c\nv 0 \\\n1 0\nvt 1 1\nvt 2 2\nf 1 2 3\n";
    let m = read_obj_from(
        std::io::BufReader::with_capacity(5, src.as_bytes()),
        Path::new("b"),
    )
    .unwrap();
    assert_eq!(
        m.mesh.positions(),
        &[[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
    );
    // vt lines are read (no face uses them here): no warning.
    assert!(m.warnings.is_empty(), "{:?}", m.warnings);
    // Non-ASCII lines split on Unicode whitespace (no-break space), as `split_whitespace`.
    let m = read("v 0\u{a0}0 0\nv 1 0 0\nv 0 1 0\nf 1 2\u{2003}3\n").unwrap();
    assert_eq!(m.mesh.face(0), &[0, 1, 2]);
    let src = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 \u{e9}3\n";
    testutil::assert_parse_errors(read, &[(src, 4, &["'\u{e9}3'"])]);
    // Integer forms accepted like `str::parse::<i64>`.
    assert_eq!(parse_i64(b"+12"), Some(12));
    assert_eq!(parse_i64(b"-9223372036854775808"), Some(i64::MIN));
    assert_eq!(parse_i64(b"9223372036854775808"), None);
    assert_eq!(parse_i64(b"-"), None);
    assert_eq!(parse_i64(b"1x"), None);
}
