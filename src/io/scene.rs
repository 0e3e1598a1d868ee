//! What the scene formats (USD, glTF) write of a mesh: polygons with vertex normals, texture
//! coordinates per face corner, named per-vertex values (curvature), per-vertex colours, and,
//! for a control net, its subdivision scheme and OpenSubdiv tags.
//!
//! [`SceneMesh`] gathers these once, from a refined net ([`SceneMesh::from_net`]) or from a
//! caller's arrays (a tessellation), so that both writers read the same data.

use super::Polygons;
use crate::error::Result;
use crate::geom::{Point, add, cross, norm, scale};
use crate::mesh::tags::SubdOptions;
use crate::mesh::{FaceVarying, PolyMesh, SharpEdges};

/// The OpenSubdiv scheme and tags of a control net, as USD's `UsdGeomMesh` holds them.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct NetTags {
    /// USD's `subdivisionScheme` token: `catmullClark`, `loop` or `bilinear`.
    pub scheme: &'static str,
    /// Sharp edges: end points and sharpness.
    pub creases: Vec<([u32; 2], f32)>,
    /// Sharp vertices and their sharpness.
    pub corners: Vec<(u32, f32)>,
    /// Hole faces.
    pub holes: Vec<u32>,
    /// The subdivision options the net asks for (written where set).
    pub options: SubdOptions,
}

/// A mesh for the scene writers (see the module notes).
#[derive(Debug, Clone, Default)]
pub struct SceneMesh {
    /// Vertex positions.
    pub positions: Vec<Point>,
    /// Face `f` has corners `corners[face_start[f]..face_start[f + 1]]`.
    pub face_start: Vec<u32>,
    /// Corner vertex indices.
    pub corners: Vec<u32>,
    /// Unit normals per vertex.
    pub normals: Option<Vec<Point>>,
    /// Texture coordinates per face corner.
    pub uv: Option<FaceVarying>,
    /// Named values per vertex (`gaussianCurvature`, `meanCurvature`).
    pub scalars: Vec<(String, Vec<f64>)>,
    /// Colours per vertex (linear RGB in `[0, 1]`).
    pub colors: Option<Vec<[f32; 3]>>,
    /// The scheme and tags, when the mesh is a control net to be subdivided by the reader.
    pub net: Option<NetTags>,
}

impl SceneMesh {
    /// A refined net (or a control net with `tags`): its polygons, texture coordinates and
    /// area-weighted vertex normals of its faces.
    pub fn from_net(m: &PolyMesh, tags: Option<NetTags>) -> SceneMesh {
        let mut s = SceneMesh {
            positions: m.positions().to_vec(),
            face_start: m.face_starts().to_vec(),
            corners: m.corners().to_vec(),
            uv: m.extras().and_then(|e| e.uv.clone()),
            net: tags,
            ..SceneMesh::default()
        };
        s.normals = Some(s.face_normals());
        s
    }

    /// The checked polygons (consistent arrays, finite coordinates).
    pub(crate) fn polygons(&self) -> Result<Polygons<'_>> {
        Polygons::new(&self.positions, &self.face_start, &self.corners)
    }

    /// Number of faces.
    pub fn num_faces(&self) -> usize {
        self.face_start.len().saturating_sub(1)
    }

    /// The corners of face `f`.
    pub fn face(&self, f: usize) -> &[u32] {
        &self.corners[self.face_start[f] as usize..self.face_start[f + 1] as usize]
    }

    /// Vertex normals: the normalised sum of the area vectors of the faces around each vertex
    /// (Newell's area vector of each polygon); `[0, 0, 1]` where that sum vanishes.
    pub fn face_normals(&self) -> Vec<Point> {
        let mut n = vec![[0.0; 3]; self.positions.len()];
        for f in 0..self.num_faces() {
            let face = self.face(f);
            let mut a = [0.0; 3];
            for (k, &v) in face.iter().enumerate() {
                let w = face[(k + 1) % face.len()];
                let (p, q) = (self.positions[v as usize], self.positions[w as usize]);
                a = add(a, cross(p, q));
            }
            for &v in face {
                n[v as usize] = add(n[v as usize], a);
            }
        }
        n.iter()
            .map(|&a| {
                let l = norm(a);
                if l > 0.0 && l.is_finite() {
                    scale(a, 1.0 / l)
                } else {
                    [0.0, 0.0, 1.0]
                }
            })
            .collect()
    }

    /// The faces as triangles (fans from each face's first corner), with the face-corner
    /// index of each triangle corner (for face-varying data).
    pub fn triangles(&self) -> Vec<[(u32, u32); 3]> {
        let mut t = Vec::with_capacity(self.corners.len());
        for f in 0..self.num_faces() {
            let s = self.face_start[f];
            let n = self.face_start[f + 1] - s;
            let c = |k: u32| (self.corners[(s + k) as usize], s + k);
            for k in 1..n.saturating_sub(1) {
                t.push([c(0), c(k), c(k + 1)]);
            }
        }
        t
    }

    /// The extent (`min`, `max`) of the positions.
    pub fn extent(&self) -> (Point, Point) {
        crate::geom::bounding_box(self.positions.iter().copied()).unwrap_or(([0.0; 3], [0.0; 3]))
    }
}

/// The scheme and tags of a control net for USD: the USD scheme token and the net's sharp
/// edges, vertices, holes and options (its extras).
pub fn net_tags(m: &PolyMesh, scheme: &'static str) -> NetTags {
    let mut t = NetTags {
        scheme,
        ..NetTags::default()
    };
    let Some(ex) = m.extras() else {
        return t;
    };
    t.creases = match &ex.sharp_edges {
        SharpEdges::ById(v) => v.iter().map(|&(e, s)| (m.edge(e as usize), s)).collect(),
        SharpEdges::ByPair(v) => v.clone(),
    };
    t.corners = ex.sharp_vertices.clone();
    t.holes = ex.holes.clone();
    t.options = ex.options;
    t
}
