//! Unit tests of the IGES writer and reader.

use super::entity::{Bad, parse_real, split_params, surface_128};
use super::parse_iges;
use super::write::{iges_date, iges_real, iges_text};
use crate::bezier::BezierPatch;
use crate::error::Error;
use crate::io::testutil;
use crate::surface::{Element, PatchComplex, Provenance};
use std::path::Path;

fn patch(du: usize, dv: usize, seed: f64) -> BezierPatch {
    testutil::patch(du, dv, |i, j, k| {
        [
            i as f64 + seed / 7.0,
            -(j as f64) / 3.0 * 1e5,
            (seed * (k as f64 + 1.0)).sin() * 1e-9,
        ]
    })
}

/// Two regular patches, a ring-2 patch and a cap patch of face 3.
fn complex() -> PatchComplex {
    let items = vec![
        (patch(3, 3, 0.1), None),
        (patch(2, 5, 0.2), None),
        (patch(4, 4, 0.3), Some((2, 1))),
        (patch(3, 2, 0.4), Some((0, 0))),
    ];
    testutil::complex(Element::Face(3), items)
}

fn text() -> String {
    iges_text(&complex(), "out dir/model.igs", "20260102.030405").unwrap()
}

#[crate::unit::test]
fn reals_and_dates() {
    assert_eq!(iges_real(1.0), "1.0D0");
    assert_eq!(iges_real(-1.25e-3), "-1.25D-3");
    assert_eq!(iges_real(0.0), "0.0D0");
    assert_eq!(iges_real(1e300), "1.0D300");
    for x in [1.0 / 3.0, -2.0e-308, 12345.678, f64::MAX, 5e-324] {
        assert_eq!(parse_real(&iges_real(x)), Some(x));
    }
    assert_eq!(parse_real("1."), Some(1.0));
    assert_eq!(parse_real(" -.5E1 "), Some(-5.0));
    assert_eq!(iges_date(0), "19700101.000000");
    assert_eq!(iges_date(951_782_400), "20000229.000000");
    assert_eq!(iges_date(1_767_323_045), "20260102.030405");
}

#[crate::unit::test]
fn records_are_80_columns_with_sections_in_order() {
    let t = text();
    let lines: Vec<&str> = t.lines().collect();
    assert!(lines.iter().all(|l| l.len() == 80 && l.is_ascii()));
    let letters: String = lines.iter().map(|l| &l[72..73]).collect();
    let counts: Vec<usize> = "SGDPT"
        .chars()
        .map(|c| letters.matches(c).count())
        .collect();
    assert_eq!(counts[0], 2);
    assert_eq!(counts[2], 8); // two records per entity
    assert_eq!(counts[4], 1);
    let t_rec = lines.last().unwrap();
    assert_eq!(
        &t_rec[..32],
        format!("S{:07}G{:07}D{:07}P{:07}", 2, counts[1], 8, counts[3])
    );
    assert_eq!(&t_rec[72..], "T      1");
    // Global: delimiters, units, version 5.3, date, sanitized file name.
    let g: String = lines
        .iter()
        .filter(|l| &l[72..73] == "G")
        .map(|l| &l[..72])
        .collect();
    let params = split_params(&g, ',', ';').unwrap();
    assert_eq!(params.len(), 25);
    assert_eq!(params[0], ",");
    assert_eq!(params[1], ";");
    assert_eq!(params[2], "model");
    assert_eq!(params[3], "out_dir_model.igs");
    assert_eq!(params[13], "2");
    assert_eq!(params[14], "MM");
    assert_eq!(params[17], "20260102.030405");
    assert_eq!(params[22], "11");
    assert_eq!(params[23], "0");
    assert_eq!(parse_real(&params[19]), Some(5.0 / 3.0 * 1e5));
    // First directory entry: type 128, P pointer 1, status, label and subscript.
    let d1 = lines[2 + counts[1]];
    let d2 = lines[3 + counts[1]];
    assert_eq!(&d1[..16], "     128       1");
    assert_eq!(&d1[64..80], "00000000D      1");
    assert_eq!(&d2[..8], "     128");
    assert_eq!(&d2[56..72], " regular       1");
    let d4 = lines[5 + counts[1]];
    assert_eq!(&d4[56..72], " regular       2");
    let d6 = lines[7 + counts[1]];
    assert_eq!(&d6[56..72], "   ring2       1");
    // Parameter records: columns 65 blank, 66-72 DE pointer.
    let p1 = lines[2 + counts[1] + 8];
    assert!(
        p1.starts_with("128,3,3,3,3,0,0,1,0,0,0.0,0.0,0.0,0.0,1.0,1.0,1.0,1.0,"),
        "{p1}"
    );
    assert_eq!(&p1[64..80], "       1P      1");
}

#[crate::unit::test]
fn roundtrip_is_exact() {
    let c = complex();
    let back = parse_iges(&text(), Path::new("m.igs")).unwrap();
    assert_eq!(back.patches, c.patches);
    assert!(back.provenance.iter().all(|p| *p == Provenance::Unknown));
    // Spot-check the u-fastest order of control points against the parameter records.
    let t = text();
    let p_data: String = t
        .lines()
        .filter(|l| &l[72..73] == "P")
        .take_while(|l| l[65..72].trim() == "1")
        .map(|l| &l[..64])
        .collect();
    let params = split_params(&p_data, ',', ';').unwrap();
    // 10 header values, 8 + 8 knots, 16 weights, then X(0,0) Y(0,0) Z(0,0) X(1,0)...
    let first_pt = 10 + 16 + 16;
    let b10 = c.patches[0].cp(1, 0);
    assert_eq!(parse_real(&params[first_pt + 3]), Some(b10[0]));
    assert_eq!(parse_real(&params[first_pt + 4]), Some(b10[1]));
    assert_eq!(params.len(), first_pt + 48 + 4);
}

#[crate::unit::test]
fn degree_zero_is_raised_exactly() {
    let mut c = PatchComplex::new();
    c.push(
        BezierPatch::new(
            0,
            2,
            vec![[1.0, 2.0, 3.0], [4.0, 5.0, 6.0], [7.0, 8.0, 9.0]],
        ),
        Provenance::Unknown,
    );
    let back = parse_iges(
        &iges_text(&c, "z.igs", "20000101.000000").unwrap(),
        Path::new("z.igs"),
    )
    .unwrap();
    let p = &back.patches[0];
    assert_eq!((p.deg_u, p.deg_v), (1, 2));
    for j in 0..3 {
        assert_eq!(p.cp(0, j), c.patches[0].cp(0, j));
        assert_eq!(p.cp(1, j), c.patches[0].cp(0, j));
    }
}

#[crate::unit::test]
fn empty_complex_is_a_valid_file() {
    let t = iges_text(&PatchComplex::new(), "e.igs", "20000101.000000").unwrap();
    assert!(parse_iges(&t, Path::new("e.igs")).unwrap().is_empty());
    assert!(
        t.lines()
            .last()
            .unwrap()
            .starts_with("S0000002G0000002D0000000P0000000"),
        "{t}"
    );
}

/// The error of the test file after `f` changed its records.
fn corrupt(f: fn(&mut Vec<String>)) -> Error {
    let mut lines: Vec<String> = text().lines().map(String::from).collect();
    f(&mut lines);
    let s = lines.join("\n") + "\n";
    parse_iges(&s, Path::new("bad.igs")).unwrap_err()
}

/// Record `k` (0-based) of the D section.
fn d_record(lines: &mut [String], k: usize) -> &mut String {
    let first = lines.iter().position(|l| &l[72..73] == "D").unwrap();
    &mut lines[first + k]
}

/// Adds `by` to the parameter record count of the first directory entry.
fn shift_count(lines: &mut [String], by: i64) {
    let r = d_record(lines, 1);
    let n: i64 = r[24..32].trim().parse().unwrap();
    r.replace_range(24..32, &format!("{:>8}", n + by));
}

#[crate::unit::test]
fn corrupted_files_are_rejected_with_clear_messages() {
    type Mutation = fn(&mut Vec<String>);
    let cases: [(Mutation, &[&str]); 12] = [
        // 81 columns.
        (|l| l[3].push(' '), &["bad.igs:4:", "81 columns"]),
        // Bad parameter pointer in the second entry (records 3, 4 of D).
        (
            |l| d_record(l, 2).replace_range(8..16, "     999"),
            &["directory entry 3", "pointer 999"],
        ),
        // Pointer inside the P section but to another entity's records.
        (
            |l| d_record(l, 2).replace_range(8..16, "       1"),
            &["names directory entry 1", "directory entry 3"],
        ),
        // Wrong parameter record counts.
        (|l| shift_count(l, 1), &["names directory entry 3"]),
        (|l| shift_count(l, -1), &["belongs to no directory entry"]),
        // Wrong count in the terminate record.
        (
            |l| l.last_mut().unwrap().replace_range(16..24, "D0000009"),
            &["terminate record field 3", "8 D records"],
        ),
        // Sequence numbers must be consecutive.
        (
            |l| d_record(l, 3).replace_range(73..80, "      7"),
            &["sequence number '7'", "expected 4"],
        ),
        // Sections out of order.
        (|l| l.swap(0, 2), &["order S, G, D, P, T"]),
        // Mismatched entity types in a directory entry pair.
        (
            |l| d_record(l, 1).replace_range(0..8, "     126"),
            &["entity type 128 in its first record but 126 in its second"],
        ),
        // A garbled number in the parameter data.
        (
            |l| {
                let i = l.iter().position(|l| &l[72..73] == "P").unwrap();
                l[i].replace_range(0..6, "128,x,");
            },
            &["K1 is 'x"],
        ),
        // Missing terminate record.
        (
            |l| {
                l.pop();
            },
            &["Terminate"],
        ),
        // A non-ASCII character (a U+FFFD from an invalid byte) names its record.
        (
            |l| l[5].replace_range(10..11, "\u{fffd}"),
            &["bad.igs:6: non-ASCII"],
        ),
    ];
    for (k, (mutate, parts)) in cases.into_iter().enumerate() {
        let e = corrupt(mutate).to_string();
        assert!(parts.iter().all(|p| e.contains(p)), "case {k}: {e}");
    }
}

fn params(s: &str) -> Vec<String> {
    split_params(s, ',', ';').unwrap()
}

#[crate::unit::test]
fn entity_128_conversion_rules() {
    // A bilinear patch: X(i,j) with i fastest.
    let ok = "128,1,1,1,1,0,0,1,0,0,0.,0.,1.,1.,0.,0.,1.,1.,1.,1.,1.,1.,\
              0.,0.,0.,1.,0.,0.,0.,1.,0.,1.,1.,1.,0.,1.,0.,1.;";
    let p = match surface_128(&params(ok)) {
        Ok(p) => p,
        Err(_) => panic!("valid entity rejected"),
    };
    assert_eq!(p.cp(1, 0), [1.0, 0.0, 0.0]);
    assert_eq!(p.cp(0, 1), [0.0, 1.0, 0.0]);
    assert_eq!(p.cp(1, 1), [1.0, 1.0, 1.0]);
    // Equal weights other than 1 and knots on [2, 5] are fine.
    let ok2 = ok
        .replace("1.,1.,1.,1.,0.,0.,0.,1.", "3.,3.,3.,3.,0.,0.,0.,1.")
        .replace("0.,0.,1.,1.,0.,0.,1.,1.,", "2.,2.,5.,5.,0.,0.,1.,1.,")
        .replace("0.,1.,0.,1.;", "2.,5.,0.,1.;");
    assert!(surface_128(&params(&ok2)).is_ok());
    let unsupported = |s: &str| matches!(surface_128(&params(s)), Err(Bad::Unsupported(_)));
    // Rational weights.
    assert!(unsupported(
        &ok.replace("1.,1.,1.,1.,0.,0.,0.,1.", "2.,1.,1.,1.,0.,0.,0.,1.")
    ));
    // Partial parameter range.
    assert!(unsupported(&ok.replace("0.,1.,0.,1.;", "0.,0.5,0.,1.;")));
    // Several spans: K1 = 2, M1 = 1.
    assert!(unsupported(&ok.replacen("128,1,", "128,2,", 1)));
    // Unclamped knots.
    assert!(unsupported(&ok.replace(
        "0.,0.,1.,1.,0.,0.,1.,1.,",
        "0.,0.5,1.,1.,0.,0.,1.,1.,"
    )));
    // Too few parameters.
    assert!(matches!(
        surface_128(&params("128,1,1,1,1,0,0,1,0,0,0.;")),
        Err(Bad::Parse(_))
    ));
}

#[crate::unit::test]
fn other_entity_types_are_unsupported() {
    let t = text().replace("     128", "     126");
    let e = parse_iges(&t, Path::new("o.igs")).unwrap_err();
    assert!(
        matches!(e, Error::Unsupported(_)) && e.to_string().contains("entity type 126"),
        "{e}"
    );
}
