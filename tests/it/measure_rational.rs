//! `fairsub measure` on rational patches: the closed circular cylinder of radius 1 and height
//! 1 built exactly from rational quadratic arcs (four side patches, four collapsed sectors per
//! disc) has the closed-form volume `pi`, area `4 pi`, centroid `(0, 0, 1/2)` and solid
//! inertia `Izz = pi / 2`, `Ixx = Iyy = pi / 3` (`m (3 r^2 + h^2) / 12`). The integrands are
//! rational, so these are reached by the adaptive rule; polynomial patches with the same
//! control points are a different surface (volume 10/3), which the second test shows.

use fairsub::analysis::moments::{MeasureOptions, measure};
use fairsub::bezier::BezierPatch;
use fairsub::geom::Point;
use fairsub::surface::{PatchComplex, Provenance};
use std::f64::consts::{FRAC_1_SQRT_2, PI};

/// The quarter arc `k` (angles `k pi / 2 .. (k + 1) pi / 2`) of the unit circle at height `z`:
/// its three control points and weights `1, 1/sqrt(2), 1`.
fn arc(k: usize, z: f64) -> [Point; 3] {
    let a0 = k as f64 * PI / 2.0;
    let a1 = a0 + PI / 2.0;
    let (c0, s0, c1, s1) = (a0.cos(), a0.sin(), a1.cos(), a1.sin());
    [[c0, s0, z], [c0 + c1, s0 + s1, z], [c1, s1, z]]
}

const W: [f64; 3] = [1.0, FRAC_1_SQRT_2, 1.0];

/// A bi-degree (2, 1) patch from `f(i, j)`, rational with the arc's weights along `u` (or
/// polynomial).
fn patch(rational: bool, f: impl Fn(usize, usize) -> Point) -> BezierPatch {
    let mut p = BezierPatch::from_fn(2, 1, f);
    if rational {
        p.weights = Some((0..3).flat_map(|i| [W[i], W[i]]).collect());
    }
    p
}

/// The closed cylinder's twelve patches, normals outward.
fn cylinder(rational: bool) -> Vec<BezierPatch> {
    let mut out = Vec::new();
    for k in 0..4 {
        let (lo, hi) = (arc(k, 0.0), arc(k, 1.0));
        // side: u along the arc (counter-clockwise), v up: X_u x X_v outward
        out.push(patch(rational, |i, j| if j == 0 { lo[i] } else { hi[i] }));
        // bottom: v from the centre to the arc, counter-clockwise: normal -z
        out.push(patch(
            rational,
            |i, j| if j == 0 { [0.0; 3] } else { lo[i] },
        ));
        // top: the arc clockwise: normal +z
        out.push(patch(rational, |i, j| {
            if j == 0 { [0.0, 0.0, 1.0] } else { hi[2 - i] }
        }));
    }
    out
}

fn complex(patches: Vec<BezierPatch>) -> PatchComplex {
    let mut c = PatchComplex::new();
    for p in patches {
        c.push(p, Provenance::Unknown);
    }
    c
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * b.abs().max(1.0)
}

#[test]
fn the_rational_cylinder_has_its_closed_form_moments() {
    let m = measure(&complex(cylinder(true)), &MeasureOptions::default());
    assert!(m.closed, "{m:?}");
    assert_eq!(m.rational, 12);
    assert!(close(m.area, 4.0 * PI, 1e-13), "{}", m.area);
    let v = m.volume.expect("closed");
    assert!(v.outward);
    assert!(close(v.volume, PI, 1e-13), "{}", v.volume);
    assert!(v.centroid[0].abs() < 1e-13 && v.centroid[1].abs() < 1e-13);
    assert!(close(v.centroid[2], 0.5, 1e-13), "{:?}", v.centroid);
    assert!(close(v.inertia[2][2], PI / 2.0, 1e-12), "{:?}", v.inertia);
    for k in 0..2 {
        assert!(close(v.inertia[k][k], PI / 3.0, 1e-12), "{:?}", v.inertia);
    }
    // the shell's centroid: the side's at height 1/2, the discs' at 0 and 1
    assert!(
        close(m.area_centroid[2], 0.5, 1e-13),
        "{:?}",
        m.area_centroid
    );
    assert!(m.closure < 1e-13, "{}", m.closure);
}

#[test]
fn the_same_control_points_without_weights_are_a_different_solid() {
    let m = measure(&complex(cylinder(false)), &MeasureOptions::default());
    assert_eq!(m.rational, 0);
    let v = m.volume.expect("closed");
    // the polynomial quadratic arc bulges beyond the circle (its middle control point
    // pulls harder): the volume is 10/3, not pi
    assert!((v.volume - 10.0 / 3.0).abs() < 1e-13, "{}", v.volume);
}

/// The cylinder as a BezierView file: type 8 patches, homogeneous points `w x, w y, w z, w`.
fn bv_text() -> String {
    let mut s = String::new();
    for p in cylinder(true) {
        s.push_str(&format!("8\n{} {}\n", p.deg_u, p.deg_v));
        let w = p.weights.as_ref().expect("rational");
        for (q, w) in p.cps.iter().zip(w) {
            s.push_str(&format!(
                "{:.17e} {:.17e} {:.17e} {:.17e}\n",
                w * q[0],
                w * q[1],
                w * q[2],
                w
            ));
        }
    }
    s
}

#[test]
fn measure_reads_the_rational_patches_of_a_bv_file() {
    let dir = std::env::temp_dir().join(format!("fairsub-measure-rational-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join("cylinder.bv");
    std::fs::write(&path, bv_text()).expect("written");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_fairsub"))
        .args(["measure", path.to_str().expect("utf-8"), "--json"])
        .output()
        .expect("runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let j: serde_json::Value = serde_json::from_slice(&out.stdout).expect("json");
    let m = &j;
    assert_eq!(m["rational"].as_u64(), Some(12), "{j}");
    let volume = m["volume"]["volume"].as_f64().expect("a volume");
    assert!(close(volume, PI, 1e-13), "{volume}");
    assert!(close(m["area"].as_f64().expect("area"), 4.0 * PI, 1e-13));
    let _ = std::fs::remove_dir_all(&dir);
}
