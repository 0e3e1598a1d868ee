//! Builds the exact Catmull-Clark surface of a gallery net and writes it three ways.
//!
//! Run: `cargo run --release --example catmull_clark_surface [OUT_DIR]`

use fairsub::gallery::{self, CnetShape};
use fairsub::io::{self, MeshFormat};
use fairsub::schemes::{CatmullClark, Scheme};
use fairsub::surface::{ComplexOptions, complex, tessellate::tessellate};

fn main() -> fairsub::Result<()> {
    let dir = std::path::PathBuf::from(
        std::env::args()
            .nth(1)
            .unwrap_or_else(|| "example-out".into()),
    );
    std::fs::create_dir_all(&dir).map_err(|source| fairsub::Error::Io {
        path: dir.clone(),
        source,
    })?;
    // A saddle-shaped extended c-net of valence 6.
    let net = gallery::cnet(6, CnetShape::Saddle, 3);
    // Two refinement steps of the control net.
    let mut fine = net.clone();
    for _ in 0..2 {
        fine = CatmullClark.refine(&fine)?.mesh;
    }
    io::write_mesh(&dir.join("saddle6-level2.obj"), &fine, MeshFormat::Obj)?;
    // The exact surface: bi-3 patches, 5 rings around the extraordinary vertex, and the fill.
    let surface = complex(
        "catmull-clark",
        &net,
        ComplexOptions {
            rings: 5,
            fill: true,
        },
        |_| {},
    )?;
    io::write_bv(&dir.join("saddle6.bv"), &surface)?;
    io::write_iges(&dir.join("saddle6.igs"), &surface)?;
    let t = tessellate(&surface, 6);
    let (pos, fs, corners) = t.to_polygons();
    io::write_polygons(
        &dir.join("saddle6-tess.ply"),
        &pos,
        &fs,
        &corners,
        MeshFormat::PlyBinary,
    )?;
    println!(
        "{} patches; tessellation {} vertices, {} triangles; written to {}",
        surface.len(),
        t.num_vertices(),
        t.num_triangles(),
        dir.display()
    );
    Ok(())
}
