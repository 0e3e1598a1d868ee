//! Adding a scheme takes one module and one registry row: a toy bilinear scheme, defined here
//! outside the crate, is registered and then offered by `fairsub schemes`, refines nets with
//! `subdivide --levels`, writes patches with `subdivide --rings` and is analysed by `analyze`,
//! without any change to fairsub itself.

use fairsub::bezier::BezierPatch;
use fairsub::bezier::complex::{PatchComplex, Provenance};
use fairsub::mesh::PolyMesh;
use fairsub::schemes::descriptor::{
    Capabilities, ComplexOptions, Descriptor, LocalRules, PatchRules, SchemeId, Spec, SurfaceOutput,
};
use fairsub::schemes::entry::About;
use fairsub::schemes::local::LocalMatrix;
use fairsub::schemes::registry::{Entry, register};
use fairsub::schemes::{CatmullClark, Refinement, Scheme};
use fairsub::stencil::{Stencil, StencilTable};
use fairsub::{Error, Result};

/// The toy scheme: bilinear subdivision of quad nets (vertex points stay, edge points are
/// midpoints, face points centroids); its limit is the piecewise bilinear net itself.
mod bilinear {
    use super::*;

    /// The rules, written once: the child points of a quad net in Catmull-Clark's child order
    /// (vertex points, edge points, face points).
    pub fn stencils(m: &PolyMesh) -> StencilTable {
        let mut t = StencilTable::with_capacity(
            m.num_vertices(),
            m.num_vertices() + m.num_edges() + m.num_faces(),
            4,
        );
        for v in 0..m.num_vertices() {
            let mut s = Stencil::new();
            s.add(v, 1.0);
            t.push(s);
        }
        for e in 0..m.num_edges() {
            let [a, b] = m.edge(e);
            let mut s = Stencil::new();
            s.add(a as usize, 0.5).add(b as usize, 0.5);
            t.push(s);
        }
        for f in 0..m.num_faces() {
            let face = m.face(f);
            let mut s = Stencil::new();
            for &v in face {
                s.add(v as usize, 1.0 / face.len() as f64);
            }
            t.push(s);
        }
        t
    }

    pub struct Bilinear;

    impl Scheme for Bilinear {
        fn name(&self) -> &'static str {
            ID.name()
        }

        fn refine(&self, mesh: &PolyMesh) -> Result<Refinement> {
            if let Some(f) = (0..mesh.num_faces()).find(|&f| mesh.face_size(f) != 4) {
                return Err(Error::UnsupportedFace {
                    face: f,
                    msg: format!("the bilinear toy refines quads; face {f} is not one"),
                });
            }
            let stencils = stencils(mesh);
            let (fs, corners) = CatmullClark::child_topology(mesh);
            let mesh = PolyMesh::from_refinement(stencils.apply(mesh.positions()), fs, corners)?;
            Ok(Refinement { mesh, stencils })
        }
    }

    /// Each quad is one bilinear patch.
    pub struct Patches;

    impl PatchRules for Patches {
        fn build(
            &self,
            mesh: &PolyMesh,
            _opts: ComplexOptions,
            _progress: &mut dyn FnMut(usize),
        ) -> Result<SurfaceOutput> {
            let mut c = PatchComplex::new();
            for f in 0..mesh.num_faces() {
                let q = mesh.face(f);
                let p = |k: usize| mesh.position(q[k] as usize);
                let patch = BezierPatch::new(1, 1, vec![p(0), p(3), p(1), p(2)]);
                c.push(patch, Provenance::Regular { face: f as u32 });
            }
            Ok(SurfaceOutput::plain(c))
        }
    }

    /// The local net of valence `n`: the centre, then per sector its edge and face neighbours;
    /// the matrix is read off [`stencils`] applied to the one-ring c-net.
    pub struct Local;

    impl LocalRules for Local {
        fn matrix(&self, n: usize) -> Result<LocalMatrix> {
            let net = fairsub::mesh::nets::cnet(n, fairsub::mesh::nets::CnetShape::Convex, 1);
            let t = stencils(&net);
            // Child rows: the centre's vertex point, then per sector the edge point of its
            // first edge and the face point of its face; sources: the centre, then per sector
            // the edge neighbour and the diagonal neighbour.
            let hs = net.outgoing_halfedges(0);
            let nv = net.num_vertices();
            let ne = net.num_edges();
            let mut rows = vec![0];
            let mut cols = vec![0];
            for &h in &hs {
                rows.push(nv + net.he_edge(h) as usize);
                rows.push(nv + ne + net.he_face(h) as usize);
                cols.push(net.he_to(h) as usize);
                cols.push(net.he_from(net.he_next(net.he_next(h))) as usize);
            }
            let sub = t
                .select_rows(&rows)
                .restrict_sources(&cols)
                .ok_or_else(|| Error::Unsupported("the one-ring is not invariant".into()))?;
            Ok(LocalMatrix {
                scheme: ID.name().into(),
                n,
                centre: 1,
                sector: 2,
                matrix: fairsub::schemes::local::dense(&sub),
            })
        }
    }

    pub struct Toy;

    impl Descriptor for Toy {
        fn capabilities(&self) -> Capabilities {
            Capabilities {
                refine: true,
                patches: true,
                eval: false,
            }
        }

        fn mesh_rules(&self, _: &Spec) -> Result<Option<Box<dyn Scheme>>> {
            Ok(Some(Box::new(Bilinear)))
        }

        fn patch_rules(&self, _: &Spec) -> Result<Option<Box<dyn PatchRules>>> {
            Ok(Some(Box::new(Patches)))
        }

        fn local_rules(&self, _: &Spec) -> Result<Option<Box<dyn LocalRules>>> {
            Ok(Some(Box::new(Local)))
        }
    }

    pub const ID: SchemeId = SchemeId::new("bilinear-toy");
    pub static DESCRIPTOR: Toy = Toy;
}

/// The one registry row.
fn register_toy() {
    let _ = register(Entry::new(
        bilinear::ID,
        &["toy"],
        About {
            family: "a toy: bilinear subdivision",
            input: "quad nets",
            patches: "one bilinear patch per quad",
            smoothness: "C^0",
            valences: "all",
            status: "test only",
        },
        &bilinear::DESCRIPTOR,
    ));
}

fn run(words: &[&str]) -> (Result<()>, String) {
    let mut all = vec!["fairsub"];
    all.extend_from_slice(words);
    fairsub::cli::capture(|| fairsub::cli::run_words(all))
}

#[test]
fn a_toy_scheme_appears_everywhere_after_one_registry_row() {
    register_toy();
    // A second registration of the same name is refused.
    assert!(
        register(Entry::new(
            bilinear::ID,
            &[],
            fairsub::schemes::registry().entry(bilinear::ID).about,
            &bilinear::DESCRIPTOR,
        ))
        .is_err()
    );
    let (r, out) = run(&["schemes", "--json"]);
    r.unwrap();
    let cat: serde_json::Value = serde_json::from_str(&out).unwrap();
    let row = cat
        .as_array()
        .unwrap()
        .iter()
        .find(|s| s["name"] == "bilinear-toy")
        .expect("listed");
    assert_eq!(row["refine"], true);
    assert_eq!(row["rings"], true);

    let dir = std::env::temp_dir().join(format!("fairsub-toy-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let obj = dir.join("cube2.obj");
    let (r, _) = run(&[
        "subdivide",
        "gallery:cube",
        "--scheme",
        "toy",
        "--levels",
        "2",
        "-o",
        obj.to_str().unwrap(),
    ]);
    r.unwrap();
    let m = fairsub::io::read_mesh(&obj).unwrap().mesh;
    assert_eq!(m.num_faces(), 6 * 16);
    // Bilinear: every refined point lies on a face plane of the cube.
    let (lo, hi) = fairsub::gallery::cube().bounding_box();
    assert!(
        m.positions().iter().all(|p| {
            (0..3).any(|d| (p[d] - lo[d]).abs() < 1e-12 || (p[d] - hi[d]).abs() < 1e-12)
        })
    );

    let bv = dir.join("cube.bv");
    let (r, _) = run(&[
        "subdivide",
        "gallery:cube",
        "--scheme",
        "bilinear-toy",
        "--rings",
        "1",
        "-o",
        bv.to_str().unwrap(),
    ]);
    r.unwrap();
    assert_eq!(fairsub::io::read_bv(&bv).unwrap().patches.len(), 6);

    let (r, out) = run(&[
        "analyze",
        "--scheme",
        "bilinear-toy",
        "--valence",
        "5",
        "--json",
    ]);
    r.unwrap();
    let a: serde_json::Value = serde_json::from_str(&out).unwrap();
    let lambda = a["spectrum"]["lambda"].as_f64().unwrap();
    let dominant = a["spectrum"]["dominant"].as_f64().unwrap();
    assert!(
        (dominant - 1.0).abs() < 1e-12 && (lambda - 0.5).abs() < 1e-12,
        "{a}"
    );
    assert_eq!(a["matrix_size"], 11);
    std::fs::remove_dir_all(&dir).unwrap();
}
