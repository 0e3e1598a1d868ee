//! `fairsub subdivide -o OUT.usda|.usd|.usdz|.glb|.gltf`: refined nets, control nets with
//! their tags, and tessellations of the exact surface with normals, curvature and colours, in
//! the scene formats.

use crate::error::{Error, Result};
use crate::io::scene::{NetTags, SceneMesh, net_tags};
use crate::io::{SceneFormat, gltf, usd};
use crate::mesh::PolyMesh;
use crate::schemes::Spec;
use crate::surface::PatchComplex;
use std::path::Path;

/// What `--vertex-colors` colours the vertices of a tessellation by (glTF `COLOR_0`, USD
/// `primvars:displayColor`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum VertexColors {
    /// Mean curvature, on the diverging map over a symmetric range (98th percentile of |H|).
    Mean,
    /// Gaussian curvature, likewise.
    Gauss,
    /// The patch's provenance: regular, ring parity, cap (the renderer's palette).
    Provenance,
}

/// Writes a scene mesh in its format.
fn write(path: &Path, m: &SceneMesh, f: SceneFormat) -> Result<()> {
    match f {
        SceneFormat::Usd(u) => usd::write_usd(path, m, u),
        SceneFormat::Gltf(g) => gltf::write_gltf(path, m, g),
    }
}

/// The USD scheme token of a scheme whose nets USD subdivides itself (OpenSubdiv's schemes).
fn usd_scheme(spec: &Spec) -> Option<&'static str> {
    use crate::schemes::options::ids;
    if spec.id == ids::CATMULL_CLARK {
        Some("catmullClark")
    } else if spec.id == ids::LOOP {
        // USD's token for Loop's scheme is the registry's name
        Some(ids::LOOP.name())
    } else {
        None
    }
}

/// Writes a net: the control net itself (`--levels 0`) with its scheme and tags where USD
/// has the scheme, or a refined net as polygons (`subdivisionScheme = "none"`).
pub fn write_net(
    path: &Path,
    net: &PolyMesh,
    control: Option<&Spec>,
    f: SceneFormat,
) -> Result<()> {
    let tags: Option<NetTags> = match control.map(|s| (s, usd_scheme(s))) {
        Some((_, Some(token))) => Some(net_tags(net, token)),
        Some((s, None)) => {
            eprintln!(
                "note: {}: USD and glTF have no {} subdivision: the control net is written as \
                 polygons",
                path.display(),
                s.name()
            );
            None
        }
        None => None,
    };
    if let (SceneFormat::Gltf(_), Some(t)) = (f, &tags)
        && (!t.creases.is_empty() || !t.corners.is_empty() || !t.holes.is_empty())
    {
        eprintln!(
            "warning: {}: glTF has no subdivision tags: the net's creases, corners and holes are \
             not written (write .usda to keep them)",
            path.display()
        );
    }
    write(path, &SceneMesh::from_net(net, tags), f)
}

/// Writes the tessellation of a complex (`tess` samples per patch edge) with vertex normals,
/// Gaussian and mean curvature per vertex, and colours on request.
pub fn write_complex(
    path: &Path,
    c: &PatchComplex,
    tess: usize,
    colors: Option<VertexColors>,
    f: SceneFormat,
) -> Result<()> {
    super::super::limits::check_tessellation(c, tess)?;
    let t = crate::surface::tessellate::tessellate(c, tess);
    if t.triangles.is_empty() {
        return Err(Error::InvalidArgument(format!(
            "{}: the tessellation has no triangles",
            path.display()
        )));
    }
    let curv: Vec<crate::bezier::Curvature> = (0..t.num_vertices())
        .map(|v| {
            let [u, w] = t.uv[v];
            c.patches[t.patch_of_vertex[v] as usize].curvatures(u, w)
        })
        .collect();
    let finite = |x: f64| if x.is_finite() { x } else { 0.0 };
    let gauss: Vec<f64> = curv.iter().map(|k| finite(k.gauss)).collect();
    let mean: Vec<f64> = curv.iter().map(|k| finite(k.mean)).collect();
    let (positions, face_start, corners) = t.to_polygons();
    let colors = colors.map(|k| match k {
        VertexColors::Mean => diverging_colors(&mean),
        VertexColors::Gauss => diverging_colors(&gauss),
        VertexColors::Provenance => t
            .patch_of_vertex
            .iter()
            .map(|&p| {
                rgb(crate::render::shade::provenance_colour(
                    &c.provenance[p as usize],
                ))
            })
            .collect(),
    });
    let m = SceneMesh {
        positions,
        face_start,
        corners,
        normals: Some(t.normals.clone()),
        uv: None,
        scalars: vec![
            ("gaussianCurvature".into(), gauss),
            ("meanCurvature".into(), mean),
        ],
        colors,
        net: None,
    };
    write(path, &m, f)
}

fn rgb(c: [f64; 3]) -> [f32; 3] {
    c.map(|x| x.clamp(0.0, 1.0) as f32)
}

/// Values on the diverging map over the symmetric range of their 98th percentile of `|x|`.
fn diverging_colors(v: &[f64]) -> Vec<[f32; 3]> {
    let mut a: Vec<f64> = v.iter().map(|x| x.abs()).collect();
    a.sort_by(f64::total_cmp);
    let r = a
        .get(((a.len().saturating_sub(1)) as f64 * 0.98).round() as usize)
        .copied()
        .filter(|&r| r > 0.0)
        .unwrap_or(1.0);
    v.iter()
        .map(|&x| rgb(crate::render::shade::diverging(x / r)))
        .collect()
}
