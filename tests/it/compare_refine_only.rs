//! `fairsub compare` takes schemes without exact patches (sqrt(3), modified butterfly) from
//! the registry's capabilities: they are drawn as their net refined 4 times beside the schemes
//! with patches, and a mode that needs patches is refused naming the scheme.

use std::process::Command;

fn fairsub(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_fairsub"))
        .args(args)
        .output()
        .expect("fairsub runs")
}

#[test]
fn refinement_only_schemes_are_compared_as_refined_nets() {
    let dir = crate::common::scratch("compare-ro");
    let png = dir.join("c.png");
    let out = fairsub(&[
        "compare",
        "gallery:icosahedron",
        "--schemes",
        "sqrt3,butterfly,loop",
        "--modes",
        "shaded,highlight",
        "--size",
        "64x64",
        "--json",
        "-o",
        png.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let schemes = report["schemes"].as_array().unwrap();
    let patches: Vec<(String, u64)> = schemes
        .iter()
        .map(|s| {
            (
                s["scheme"].as_str().unwrap().to_string(),
                s["patches"].as_u64().unwrap(),
            )
        })
        .collect();
    assert_eq!(patches[0], ("sqrt3".to_string(), 0));
    assert_eq!(patches[1], ("butterfly".to_string(), 0));
    assert_eq!(patches[2].0, "loop");
    assert!(patches[2].1 >= 20, "{patches:?}");
    // the panel holds 3 x 2 cells of 64 x 64 pixels (with labels around them)
    let bytes = std::fs::read(&png).unwrap();
    assert!(bytes.starts_with(b"\x89PNG"));
    let (w, h) = (
        u32::from_be_bytes(bytes[16..20].try_into().unwrap()),
        u32::from_be_bytes(bytes[20..24].try_into().unwrap()),
    );
    assert!(
        w >= 2 * 64 && h >= 2 * 64 && w * h >= 6 * 64 * 64,
        "{w} x {h}"
    );

    // curvature needs patches: refused, naming the scheme
    let out = fairsub(&[
        "compare",
        "gallery:icosahedron",
        "--schemes",
        "sqrt3",
        "--modes",
        "mean",
        "-o",
        png.to_str().unwrap(),
    ]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("sqrt3") && err.contains("needs exact patches"),
        "{err}"
    );
    std::fs::remove_dir_all(&dir).ok();
}
