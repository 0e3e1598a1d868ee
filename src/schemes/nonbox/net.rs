//! Nets with face control vertices ([`FcvNet`]): a quad net and one FCV per face, their layout
//! as one mesh (FCVs after the vertices), and the insertion of scaled barycentric FCVs.

use super::*;

/// A polygon mesh with one face control vertex (FCV) per face.
#[derive(Debug, Clone)]
pub struct FcvNet {
    /// The polygon mesh (its vertices are the type-1 points).
    pub mesh: PolyMesh,
    /// `fcv[f]` is the FCV of face `f`.
    pub fcv: Vec<Point>,
}

impl FcvNet {
    /// A net from a mesh and its FCVs. Errors when the count differs from the number of faces or
    /// a coordinate is not finite (naming the face).
    pub fn new(mesh: PolyMesh, fcv: Vec<Point>) -> Result<FcvNet> {
        if fcv.len() != mesh.num_faces() {
            return Err(Error::InvalidArgument(format!(
                "{} FCVs given for a net of {} faces: give exactly one FCV per face, in face order",
                fcv.len(),
                mesh.num_faces()
            )));
        }
        if let Some(f) = fcv.iter().position(|p| !p.iter().all(|c| c.is_finite())) {
            return Err(Error::InvalidArgument(format!(
                "the FCV of face {f} has a NaN or infinite coordinate"
            )));
        }
        Ok(FcvNet { mesh, fcv })
    }

    /// The net with the face barycentres (means of the corners) as FCVs, the paper's default.
    pub fn barycentric(mesh: PolyMesh) -> FcvNet {
        let fcv = (0..mesh.num_faces())
            .map(|f| mesh.face_centroid(f))
            .collect();
        FcvNet { mesh, fcv }
    }

    /// The net with `scale` times the face barycentres as FCVs, scaled about the origin (the
    /// paper's Fig. 10 takes 0.5, 1 and 1.5 on a cube centred at the origin). Errors for a
    /// non-finite scale.
    pub fn scaled(mesh: PolyMesh, scale: f64) -> Result<FcvNet> {
        if !scale.is_finite() {
            return Err(Error::InvalidArgument(format!(
                "FCV scale {scale} is not a finite number"
            )));
        }
        let mut net = FcvNet::barycentric(mesh);
        for p in &mut net.fcv {
            *p = geom::scale(*p, scale);
        }
        Ok(net)
    }

    /// Reads a net from a plain mesh: a [layout mesh](FcvNet::to_layout_mesh) gives its FCVs,
    /// any other mesh its face barycentres.
    pub fn from_mesh(mesh: &PolyMesh) -> FcvNet {
        match Self::from_layout_mesh(mesh) {
            Some(net) => net,
            None => FcvNet::barycentric(mesh.clone()),
        }
    }

    /// Splits a layout mesh (vertices, then one unused vertex per face) into mesh and FCVs;
    /// `None` when `mesh` does not have that layout.
    pub fn from_layout_mesh(mesh: &PolyMesh) -> Option<FcvNet> {
        let nv = layout_vertex_count(mesh)?;
        let pos = mesh.positions();
        let m = PolyMesh::from_refinement(
            pos[..nv].to_vec(),
            mesh.face_starts().to_vec(),
            mesh.corners().to_vec(),
        )
        .ok()?
        .with_extras(mesh.extras().cloned());
        Some(FcvNet {
            mesh: m,
            fcv: pos[nv..].to_vec(),
        })
    }

    /// The layout mesh of this net: the mesh's vertices, then the FCVs as extra vertices (one per
    /// face, in face order) that no face uses. See the module documentation.
    pub fn to_layout_mesh(&self) -> PolyMesh {
        PolyMesh::from_refinement(
            self.points(),
            self.mesh.face_starts().to_vec(),
            self.mesh.corners().to_vec(),
        )
        .expect("the faces of a valid net stay valid")
        .with_extras(self.mesh.extras().cloned())
    }

    /// Number of points: vertices plus FCVs.
    pub fn num_points(&self) -> usize {
        self.mesh.num_vertices() + self.fcv.len()
    }

    /// Point index of the FCV of face `f`.
    pub fn fcv_point(&self, f: usize) -> usize {
        self.mesh.num_vertices() + f
    }

    /// All points: vertex positions, then FCVs.
    pub fn points(&self) -> Vec<Point> {
        let mut p = self.mesh.positions().to_vec();
        p.extend_from_slice(&self.fcv);
        p
    }

    /// The same net with new point positions (vertices, then FCVs).
    ///
    /// # Panics
    /// Panics when the count differs (a programming error).
    pub fn with_points(&self, points: Vec<Point>) -> FcvNet {
        assert_eq!(
            points.len(),
            self.num_points(),
            "point count must not change"
        );
        let nv = self.mesh.num_vertices();
        let mut mesh = self.mesh.clone();
        mesh.set_positions(points[..nv].to_vec());
        FcvNet {
            mesh,
            fcv: points[nv..].to_vec(),
        }
    }
}

/// Number of face-using vertices when `mesh` is a layout mesh (see [`FcvNet::to_layout_mesh`]):
/// the last `num_faces` vertices are unused by every face and all others are used.
pub fn layout_vertex_count(mesh: &PolyMesh) -> Option<usize> {
    let (n, nf) = (mesh.num_vertices(), mesh.num_faces());
    let nv = n.checked_sub(nf)?;
    let mut used = vec![false; n];
    for &v in mesh.corners() {
        used[v as usize] = true;
    }
    (used[..nv].iter().all(|&u| u) && used[nv..].iter().all(|&u| !u)).then_some(nv)
}

/// The table that inserts FCVs `scale * barycentre` into a plain mesh: rows are the net's points
/// (vertices, then FCVs), sources the mesh's vertices.
pub fn fcv_insertion(mesh: &PolyMesh, scale: f64) -> StencilTable {
    let (nv, nf) = (mesh.num_vertices(), mesh.num_faces());
    let mut t = StencilTable::with_capacity(nv, nv + nf, 4);
    for v in 0..nv {
        t.push(Stencil::point(v));
    }
    for f in 0..nf {
        let face = mesh.face(f);
        let w = scale / face.len() as f64;
        t.push(Stencil::from_pairs(face.iter().map(|&v| (v as usize, w))));
    }
    t
}
