//! USD against Pixar's own `usd-core` (PyPI): files usd-core writes (usda, usdc, usdz, with
//! creases, corners, holes, boundary and face-varying options, the smooth triangle rule and an
//! indexed `st` primvar) refine exactly as the same nets written as OBJ with OpenSubdiv's tags;
//! files fairsub writes (control nets with their tags, refined nets, tessellations with
//! curvature primvars) open in a usd-core stage with the attributes fairsub meant, and every
//! validator `UsdValidation.ValidationRegistry().GetOrLoadAllValidators()` returns reports no
//! error on them.
//!
//! The peer is `tests/usd/usdcore.py` run by the Python named in `FAIRSUB_USD_PYTHON` (a
//! virtual environment with `pip install usd-core`). Without it the tests print that they
//! skipped, unless `FAIRSUB_REQUIRE_USD` is set (CI sets both), then they fail.

use crate::common::{run_ok as fairsub, scratch, skip_slow};
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command;

/// The Python with usd-core, or `None` (skip) when it is not configured and not required.
fn usd_python() -> Option<PathBuf> {
    if skip_slow("usd-core") {
        return None;
    }
    match std::env::var_os("FAIRSUB_USD_PYTHON") {
        Some(p) => Some(PathBuf::from(p)),
        None if std::env::var_os("FAIRSUB_REQUIRE_USD").is_some() => {
            panic!(
                "FAIRSUB_REQUIRE_USD is set but FAIRSUB_USD_PYTHON names no Python with usd-core"
            )
        }
        None => {
            eprintln!(
                "skipped: set FAIRSUB_USD_PYTHON to a Python with usd-core (pip install usd-core)"
            );
            None
        }
    }
}

fn peer(py: &Path, args: &[&str]) -> Value {
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/usd/usdcore.py");
    let out = Command::new(py)
        .arg(script)
        .args(args)
        .output()
        .expect("python runs");
    assert!(
        out.status.success(),
        "usdcore.py {args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("JSON from usdcore.py")
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

#[test]
fn slow_usd_core_files_refine_as_the_obj_with_tags() {
    let Some(py) = usd_python() else { return };
    let dir = scratch("read");
    peer(&py, &["make", s(&dir)]);
    for net in ["cube", "grid", "mixed"] {
        let refine = |src: &str, out: &str| {
            let (i, o) = (dir.join(src), dir.join(out));
            fairsub(&[
                "subdivide",
                s(&i),
                "--scheme",
                "catmull-clark",
                "--levels",
                "3",
                "-o",
                s(&o),
            ]);
            std::fs::read(o).unwrap()
        };
        let want = refine(&format!("{net}.obj"), &format!("{net}-obj.obj"));
        for ext in ["usda", "usdc", "usdz"] {
            let got = refine(&format!("{net}.{ext}"), &format!("{net}-{ext}.obj"));
            assert!(
                got == want,
                "{net}.{ext} refines differently from {net}.obj"
            );
        }
        // the tags matter: the same net without them refines differently
        let text = std::fs::read_to_string(dir.join(format!("{net}.obj"))).unwrap();
        let bare: String = text
            .lines()
            .filter(|l| !l.starts_with("t "))
            .map(|l| format!("{l}\n"))
            .collect();
        std::fs::write(dir.join(format!("{net}-bare.obj")), bare).unwrap();
        let plain = refine(&format!("{net}-bare.obj"), &format!("{net}-bare-out.obj"));
        assert!(plain != want, "{net}: the tags changed nothing");
    }
    // the grid's texture coordinates came through (seams and all): vt lines in the output
    let out = std::fs::read_to_string(dir.join("grid-usdz.obj")).unwrap();
    assert!(
        out.lines().filter(|l| l.starts_with("vt ")).count() > 800,
        "no texture coordinates"
    );
    let _ = std::fs::remove_dir_all(dir);
}

/// The attribute `name` of the inspected mesh.
fn attr<'a>(d: &'a Value, name: &str) -> &'a Value {
    &d["attributes"][name]["value"]
}

/// Asserts usd-core opened the file and its validators found no error; returns the report.
fn inspect_clean(py: &Path, file: &Path) -> Value {
    let d = peer(py, &["inspect", s(file)]);
    assert_eq!(d["opened"], true, "{}", file.display());
    assert!(d["validators"].as_u64().unwrap() >= 25, "{d}");
    assert_eq!(
        d["errors"],
        serde_json::json!([]),
        "{}: {}",
        file.display(),
        d["errors"]
    );
    assert_eq!(d["validTopology"][0], true, "{d}");
    d
}

#[test]
fn slow_fairsub_files_open_in_usd_core_and_pass_every_validator() {
    let Some(py) = usd_python() else { return };
    let dir = scratch("write");
    peer(&py, &["make", s(&dir)]);
    let grid = dir.join("grid.obj");
    // the control net with its tags, as text and as a package
    for ext in ["usda", "usdz"] {
        let out = dir.join(format!("net.{ext}"));
        fairsub(&[
            "subdivide",
            s(&grid),
            "--scheme",
            "catmull-clark",
            "--levels",
            "0",
            "-o",
            s(&out),
        ]);
        let d = inspect_clean(&py, &out);
        assert_eq!(attr(&d, "subdivisionScheme"), "catmullClark");
        assert_eq!(
            d["attributes"]["subdivisionScheme"]["variability"],
            "Sdf.VariabilityUniform"
        );
        assert_eq!(attr(&d, "points").as_array().unwrap().len(), 20);
        assert_eq!(attr(&d, "faceVertexCounts").as_array().unwrap().len(), 12);
        // the OBJ's tags: crease 6-7-8 at 1.5 (two edges), corner 12 at 2, hole 10, edge-only
        let mut pairs: Vec<[i64; 2]> = attr(&d, "creaseIndices")
            .as_array()
            .unwrap()
            .chunks(2)
            .map(|c| {
                let (a, b) = (c[0].as_i64().unwrap(), c[1].as_i64().unwrap());
                [a.min(b), a.max(b)]
            })
            .collect();
        pairs.sort();
        assert_eq!(pairs, [[6, 7], [7, 8]]);
        assert_eq!(attr(&d, "creaseLengths"), &serde_json::json!([2, 2]));
        assert_eq!(
            attr(&d, "creaseSharpnesses"),
            &serde_json::json!([1.5, 1.5])
        );
        assert_eq!(attr(&d, "cornerIndices"), &serde_json::json!([12]));
        assert_eq!(attr(&d, "cornerSharpnesses"), &serde_json::json!([2.0]));
        assert_eq!(attr(&d, "holeIndices"), &serde_json::json!([10]));
        assert_eq!(attr(&d, "interpolateBoundary"), "edgeOnly");
        assert_eq!(attr(&d, "faceVaryingLinearInterpolation"), "cornersPlus1");
        assert_eq!(d["primvars"]["st"]["interpolation"], "faceVarying");
        assert_eq!(d["primvars"]["st"]["indexed"], true);
        assert_eq!(d["primvars"]["st"]["flattened"], 48);
        assert_eq!(d["normalsInterpolation"], "vertex");
        // and fairsub reads its own file back to the same refinement as the OBJ
        let a = dir.join(format!("back-{ext}.obj"));
        let b = dir.join("back-obj.obj");
        fairsub(&[
            "subdivide",
            s(&out),
            "--scheme",
            "catmull-clark",
            "--levels",
            "2",
            "-o",
            s(&a),
        ]);
        fairsub(&[
            "subdivide",
            s(&grid),
            "--scheme",
            "catmull-clark",
            "--levels",
            "2",
            "-o",
            s(&b),
        ]);
        assert!(
            std::fs::read(a).unwrap() == std::fs::read(b).unwrap(),
            "{ext} round trip"
        );
    }
    // a refined net: polygons as they are, with the refined texture coordinates
    let out = dir.join("refined.usd");
    fairsub(&[
        "subdivide",
        s(&grid),
        "--scheme",
        "catmull-clark",
        "--levels",
        "2",
        "-o",
        s(&out),
    ]);
    let d = inspect_clean(&py, &out);
    assert_eq!(attr(&d, "subdivisionScheme"), "none");
    assert_eq!(
        attr(&d, "faceVertexCounts").as_array().unwrap().len(),
        11 * 16
    );
    assert_eq!(d["primvars"]["st"]["flattened"], 11 * 16 * 4);
    assert!(d["attributes"].get("creaseIndices").is_none());
    // a tessellation of the exact surface with curvature primvars and colours (Loop, EG)
    for (net, scheme, colors) in [
        ("gallery:cube", "eg", "gauss"),
        ("gallery:octahedron", "loop", "provenance"),
    ] {
        let out = dir.join(format!("tess-{scheme}.usdz"));
        let log = fairsub(&[
            "subdivide",
            net,
            "--scheme",
            scheme,
            "--rings",
            "2",
            "--tess",
            "4",
            "--vertex-colors",
            colors,
            "-o",
            s(&out),
        ]);
        assert!(log.contains("wrote the tessellation"), "{log}");
        let d = inspect_clean(&py, &out);
        let n = attr(&d, "points").as_array().unwrap().len();
        assert!(n > 100, "{n}");
        for pv in ["gaussianCurvature", "meanCurvature", "displayColor"] {
            assert_eq!(d["primvars"][pv]["interpolation"], "vertex", "{pv}");
            assert_eq!(d["primvars"][pv]["flattened"], n, "{pv}");
        }
        assert_eq!(attr(&d, "normals").as_array().unwrap().len(), n);
        assert!(
            attr(&d, "faceVertexCounts")
                .as_array()
                .unwrap()
                .iter()
                .all(|c| c == 3)
        );
    }
    // the validators do find errors: a layer without defaultPrim, upAxis or metersPerUnit
    let bad = dir.join("bad.usda");
    std::fs::write(&bad, "#usda 1.0\n\ndef Mesh \"m\"\n{\n    point3f[] points = [(0, 0, 0), (1, 0, 0), (0, 1, 0)]\n    int[] faceVertexCounts = [3]\n    int[] faceVertexIndices = [0, 1, 2]\n}\n").unwrap();
    let d = peer(&py, &["inspect", s(&bad)]);
    assert!(!d["errors"].as_array().unwrap().is_empty(), "{d}");
    let _ = std::fs::remove_dir_all(dir);
}
