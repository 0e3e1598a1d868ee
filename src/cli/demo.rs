//! `fairsub demo`: the main job on the embedded default net, no input file needed.
//!
//! Writes the net, its refinement by every scheme of the registry, and the exact surface of
//! every scheme with patch output (BezierView, IGES and a tessellated mesh) into one folder, and
//! prints what it wrote. The default net is a quad net; a scheme that takes triangles only
//! (Loop, sqrt(3), the modified butterfly) gets the same net with each quad cut along a diagonal
//! ([`triangulated`]), so every scheme of the registry is in the demo without naming one here.

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
    let tri_net = triangulated(&net)?;
    let reg = crate::schemes::registry();
    // The net a scheme is shown on: the default net, else its triangulation, else none.
    let net_for = |e: &crate::schemes::registry::Entry| {
        [&net, &tri_net]
            .into_iter()
            .find(|m| e.descriptor.check_input(m).is_ok())
    };
    if reg
        .entries()
        .iter()
        .any(|e| net_for(e).is_some_and(|m| std::ptr::eq(m, &tri_net)))
    {
        crate::io::write_mesh(&put("demo-net-triangles.obj"), &tri_net, MeshFormat::Obj)?;
        say!(
            "triangle schemes: the same net with each quad cut along a diagonal, {} faces",
            tri_net.num_faces()
        );
    }
    for e in reg.entries().iter().filter(|e| e.capabilities().refine) {
        let Some(net) = net_for(e) else { continue };
        let spec = crate::schemes::Spec::new(e.id);
        let m = super::subdivide::refine_with(
            super::subdivide::mesh_rules(&spec)?.as_ref(),
            net,
            3,
            false,
        )?;
        crate::io::write_mesh(
            &put(&format!("demo-{}-level3.obj", e.name)),
            &m,
            MeshFormat::Obj,
        )?;
    }
    for e in reg.entries().iter().filter(|e| e.capabilities().patches) {
        let Some(net) = net_for(e) else { continue };
        let c = super::subdivide::build_complex(&crate::schemes::Spec::new(e.id), net, 6, true)?;
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

/// `net` with every quad cut into two triangles along the diagonal from its first corner (other
/// faces kept as they are): the default net for the schemes that take triangles only.
fn triangulated(net: &crate::mesh::PolyMesh) -> Result<crate::mesh::PolyMesh> {
    let mut faces: Vec<Vec<usize>> = Vec::with_capacity(2 * net.num_faces());
    for f in 0..net.num_faces() {
        let c: Vec<usize> = net.face(f).iter().map(|&v| v as usize).collect();
        if c.len() == 4 {
            faces.push(vec![c[0], c[1], c[2]]);
            faces.push(vec![c[0], c[2], c[3]]);
        } else {
            faces.push(c);
        }
    }
    crate::mesh::PolyMesh::new(net.positions().to_vec(), &faces)
}
