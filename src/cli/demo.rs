//! `fairsub demo`: the main job on the embedded default net, no input file needed.
//!
//! Writes the net, its refinements by every classic scheme that applies, and the exact
//! Catmull-Clark surface (BezierView, IGES and a tessellated mesh) into one folder, and prints
//! what it wrote.

use crate::error::Result;
use crate::io::{MeshFormat, OutputFormat};
use std::path::Path;

/// Runs `fairsub demo`.
pub fn run(out: &Path) -> Result<()> {
    std::fs::create_dir_all(out).map_err(|source| crate::Error::Io {
        path: out.to_path_buf(),
        source,
    })?;
    let net = crate::gallery::default_net();
    let mut written = Vec::new();
    let mut put = |name: &str| {
        let p = out.join(name);
        written.push(p.display().to_string());
        p
    };
    crate::io::write_mesh(&put("demo-net.obj"), &net, MeshFormat::Obj)?;
    say!(
        "default net: extended c-net of valence 5 (convex), {} vertices, {} faces",
        net.num_vertices(),
        net.num_faces()
    );
    let reg = crate::schemes::registry();
    let takes_net = |e: &&crate::schemes::registry::Entry| e.descriptor.check_input(&net).is_ok();
    for e in reg
        .entries()
        .iter()
        .filter(|e| e.capabilities().refine)
        .filter(takes_net)
    {
        let spec = crate::schemes::Spec::new(e.id);
        let m = super::subdivide::refine_with(
            super::subdivide::mesh_rules(&spec)?.as_ref(),
            &net,
            3,
            false,
        )?;
        crate::io::write_mesh(
            &put(&format!("demo-{}-level3.obj", e.name)),
            &m,
            MeshFormat::Obj,
        )?;
    }
    for e in reg
        .entries()
        .iter()
        .filter(|e| e.capabilities().patches)
        .filter(takes_net)
    {
        let c = super::subdivide::build_complex(&crate::schemes::Spec::new(e.id), &net, 6, true)?;
        for (ext, fmt) in [
            ("bv", OutputFormat::Bv),
            ("igs", OutputFormat::Iges),
            ("ply", OutputFormat::Mesh(MeshFormat::PlyBinary)),
        ] {
            super::subdivide::write_complex(&c, fmt, &put(&format!("demo-{}.{ext}", e.name)), 8)?;
        }
        say!("{}: {} patches (6 rings + fill)", e.name, c.len());
    }
    super::render::demo_compare(&net, &put("demo-compare.png"))?;
    say!("wrote:");
    for w in &written {
        say!("  {w}");
    }
    Ok(())
}
