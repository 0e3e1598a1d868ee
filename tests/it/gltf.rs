//! glTF 2.0 output judged by the Khronos glTF-Validator (npm `gltf-validator`, run by Node):
//! refined nets with texture coordinates (`.glb`, `.gltf`), control nets, and tessellations of
//! exact surfaces with each kind of vertex colours give 0 errors and 0 warnings, and the
//! validator counts the triangles fairsub wrote.
//!
//! `FAIRSUB_GLTF_VALIDATOR` names the `node_modules` folder that holds `gltf-validator`
//! (`npm install gltf-validator`). Without it the test prints that it skipped, unless
//! `FAIRSUB_REQUIRE_GLTF` is set (CI sets both), then it fails.

use crate::common::{run_ok as fairsub, scratch, skip_slow};
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command;

fn validator() -> Option<PathBuf> {
    if skip_slow("gltf-validator") {
        return None;
    }
    match std::env::var_os("FAIRSUB_GLTF_VALIDATOR") {
        Some(p) => Some(PathBuf::from(p)),
        None if std::env::var_os("FAIRSUB_REQUIRE_GLTF").is_some() => {
            panic!("FAIRSUB_REQUIRE_GLTF is set but FAIRSUB_GLTF_VALIDATOR names no node_modules")
        }
        None => {
            eprintln!("skipped: set FAIRSUB_GLTF_VALIDATOR to a node_modules with gltf-validator");
            None
        }
    }
}

/// The validator's report of each file.
fn validate(modules: &Path, files: &[PathBuf]) -> Vec<Value> {
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/gltf/validate.js");
    let out = Command::new("node")
        .arg(script)
        .args(files)
        .env("NODE_PATH", modules)
        .output()
        .expect("node runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout)
        .lines()
        .map(|l| serde_json::from_str(l).expect("a JSON report"))
        .collect()
}

/// A 4 x 4 grid with texture coordinates (a seam down the middle) and a crease tag.
const GRID: &str = "\
v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 1\nv 2 1 0\nv 0 2 0\nv 1 2 0\nv 2 2 0.5\n\
vt 0 0\nvt 0.5 0\nvt 0 0.5\nvt 0.5 0.5\nvt 0 1\nvt 0.5 1\nvt 0.6 0\nvt 1 0\nvt 0.6 0.5\nvt 1 0.5\nvt 0.6 1\nvt 1 1\n\
f 1/1 2/2 5/4 4/3\nf 2/7 3/8 6/10 5/9\nf 4/3 5/4 8/6 7/5\nf 5/9 6/10 9/12 8/11\n\
t crease 2/1/0 1 4 2.0\n";

#[test]
fn slow_khronos_validator_finds_no_error_and_no_warning() {
    let Some(modules) = validator() else { return };
    let dir = scratch("gltf");
    let grid = dir.join("grid.obj");
    std::fs::write(&grid, GRID).unwrap();
    let p = |n: &str| dir.join(n);
    let s = |p: &Path| p.to_str().unwrap().to_string();
    // (arguments, file, triangles written)
    let jobs: Vec<(Vec<String>, PathBuf, u64)> = vec![
        (
            vec![
                s(&grid),
                "--scheme".into(),
                "catmull-clark".into(),
                "--levels".into(),
                "2".into(),
            ],
            p("refined.glb"),
            2 * 64,
        ),
        (
            vec![
                s(&grid),
                "--scheme".into(),
                "catmull-clark".into(),
                "--levels".into(),
                "2".into(),
            ],
            p("refined.gltf"),
            2 * 64,
        ),
        (
            vec![
                s(&grid),
                "--scheme".into(),
                "catmull-clark".into(),
                "--levels".into(),
                "0".into(),
            ],
            p("net.gltf"),
            2 * 4,
        ),
        (
            vec![
                "gallery:icosahedron".into(),
                "--scheme".into(),
                "loop".into(),
                "--levels".into(),
                "2".into(),
            ],
            p("loop.glb"),
            20 * 16,
        ),
    ];
    let mut files = Vec::new();
    let mut triangles = Vec::new();
    for (mut args, file, t) in jobs {
        args.insert(0, "subdivide".into());
        args.extend(["-o".into(), s(&file)]);
        let a: Vec<&str> = args.iter().map(String::as_str).collect();
        fairsub(&a);
        files.push(file);
        triangles.push(Some(t));
    }
    for colors in ["mean", "gauss", "provenance"] {
        let file = p(&format!("tess-{colors}.glb"));
        fairsub(&[
            "subdivide",
            "gallery:cube",
            "--scheme",
            "eg",
            "--rings",
            "2",
            "--tess",
            "4",
            "--vertex-colors",
            colors,
            "-o",
            &s(&file),
        ]);
        files.push(file);
        triangles.push(None);
    }
    let file = p("tess-guided.gltf");
    fairsub(&[
        "subdivide",
        "gallery:prism-5",
        "--scheme",
        "guided-bi5",
        "--rings",
        "2",
        "--tess",
        "3",
        "-o",
        &s(&file),
    ]);
    files.push(file);
    triangles.push(None);
    let reports = validate(&modules, &files);
    assert_eq!(reports.len(), files.len());
    for (r, t) in reports.iter().zip(&triangles) {
        eprintln!(
            "{}: {} errors, {} warnings, {} infos, {} hints {:?}",
            r["file"], r["errors"], r["warnings"], r["infos"], r["hints"], r["messages"]
        );
        assert_eq!(r["errors"], 0, "{r}");
        assert_eq!(r["warnings"], 0, "{r}");
        assert!(r["info"]["totalTriangleCount"].as_u64().unwrap() > 0, "{r}");
        if let Some(t) = t {
            assert_eq!(r["info"]["totalTriangleCount"], *t, "{r}");
        }
    }
    // the validator does find errors: a GLB cut short
    let bytes = std::fs::read(&files[0]).unwrap();
    let cut = p("cut.glb");
    std::fs::write(&cut, &bytes[..bytes.len() - 64]).unwrap();
    let r = &validate(&modules, &[cut])[0];
    assert!(r["errors"].as_u64().unwrap() > 0, "{r}");
    let _ = std::fs::remove_dir_all(dir);
}
