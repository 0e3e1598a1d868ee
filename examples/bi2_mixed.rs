//! A mixed bi-2 net in the spirit of the bi-2 paper's Fig. 15: regular bi-2 regions, PGS
//! (binary) rings at two pentagons and TPS (ternary) rings at ten valence-3 vertices, in one
//! surface. Writes the net and its exact surface, and prints the continuity certificate per
//! kind of join.
//!
//! Run: `cargo run --release --example bi2_mixed [OUT_DIR]`, then for instance
//! `fairsub render OUT_DIR/bi2-mixed-net.obj --scheme bi2-mixed --mode provenance -o p.png`.

use fairsub::analysis::continuity;
use fairsub::io::{self, MeshFormat};
use fairsub::schemes::bi2::mixed::{Bi2Element, elements, fig15_like_net};
use fairsub::surface::{ComplexOptions, complex};

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
    // Two ternary splits of the pentagonal prism separate its elements.
    let net = fig15_like_net(5)?;
    let els = elements(&net);
    let count = |f: fn(&Bi2Element) -> bool| els.iter().filter(|e| f(e)).count();
    println!(
        "net: {} faces; {} PGS facets, {} TPS vertices, {} poles",
        net.num_faces(),
        count(|e| matches!(e, Bi2Element::Facet(_))),
        count(|e| matches!(e, Bi2Element::Vertex(_))),
        count(|e| matches!(e, Bi2Element::Pole(_))),
    );
    io::write_mesh(&dir.join("bi2-mixed-net.obj"), &net, MeshFormat::Obj)?;
    // Regular bi-2 patches of the input net, 4 rings per element, each hole filled.
    let surface = complex(
        "bi2-mixed",
        &net,
        ComplexOptions {
            rings: 4,
            fill: true,
        },
        |_| {},
    )?;
    io::write_bv(&dir.join("bi2-mixed.bv"), &surface)?;
    println!("surface: {} patches", surface.len());
    // C^0 over all joins; C^1 per kind (regular|ring1 is where binary or ternary rings meet
    // the shared regular patches). The fill's spokes (cap|cap) are C^0 by design.
    let plain = continuity::check(&surface);
    println!(
        "C0 {:.1e} over {} shared pieces, {} open sides",
        plain.all.c0, plain.all.pieces, plain.open_sides
    );
    for (kind, d) in fairsub::analysis::scaled::continuity_up_to_scaling(&surface).by_kind {
        println!(
            "  {kind:<16} {:>5} pieces  C1 (relative) {:.1e}  G1 {:.1e} rad",
            d.pieces, d.c1_relative, d.g1
        );
    }
    Ok(())
}
