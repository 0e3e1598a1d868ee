//! `fairsub demo`: the main job on the embedded default net, no input file needed.
//!
//! Writes the net, its refinements by every classic scheme that applies, and the exact
//! Catmull-Clark surface (BezierView, IGES and a tessellated mesh) into one folder, and prints
//! what it wrote.

use fairsub::Result;
use fairsub::io::{MeshFormat, OutputFormat};
use std::path::Path;

/// Runs `fairsub demo`.
pub fn run(out: &Path) -> Result<()> {
    std::fs::create_dir_all(out).map_err(|source| fairsub::Error::Io {
        path: out.to_path_buf(),
        source,
    })?;
    let net = fairsub::gallery::default_net();
    let mut written = Vec::new();
    let mut put = |name: &str| {
        let p = out.join(name);
        written.push(p.display().to_string());
        p
    };
    fairsub::io::write_mesh(&put("demo-net.obj"), &net, MeshFormat::Obj)?;
    println!(
        "default net: extended c-net of valence 5 (convex), {} vertices, {} faces",
        net.num_vertices(),
        net.num_faces()
    );
    for s in fairsub::schemes::catalog().iter().filter(|s| s.refine) {
        if s.name == "loop" && !net.is_all_triangles() {
            continue;
        }
        let m = super::subdivide::refine(s.name, &net, 3, false)?;
        fairsub::io::write_mesh(
            &put(&format!("demo-{}-level3.obj", s.name)),
            &m,
            MeshFormat::Obj,
        )?;
    }
    for s in fairsub::schemes::catalog().iter().filter(|s| s.rings) {
        if s.name == "loop" && !net.is_all_triangles() {
            continue;
        }
        let c = super::subdivide::build_complex(s.name, &net, 6, true)?;
        for (ext, fmt) in [
            ("bv", OutputFormat::Bv),
            ("igs", OutputFormat::Iges),
            ("ply", OutputFormat::Mesh(MeshFormat::PlyBinary)),
        ] {
            super::subdivide::write_complex(&c, fmt, &put(&format!("demo-{}.{ext}", s.name)), 8)?;
        }
        println!("{}: {} patches (6 rings + fill)", s.name, c.len());
    }
    super::render::demo_compare(&net, &put("demo-compare.png"))?;
    println!("wrote:");
    for w in &written {
        println!("  {w}");
    }
    Ok(())
}
