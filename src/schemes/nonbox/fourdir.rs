//! The four-directional variant of non-box subdivision: quasi-four-directional triangle meshes.
//!
//! A quasi-four-directional mesh is a triangle mesh whose vertices are of two types such that
//! every triangle has exactly one type-2 vertex: the type-1 vertices and the type-1 edges
//! (joining two type-1 vertices) form a polygon mesh, each type-2 vertex is the FCV of the polygon
//! its fan of triangles covers. Triangulating a polygon mesh with FCVs (each `n`-gon fanned into
//! `n` triangles around its FCV, [`triangulate`]) gives one, and every one arises so
//! ([`FourDirNet::to_fcv_net`]).
//!
//! The paper's four stencils of the variant are the quad variant's four rules on that
//! correspondence: a type-1 E-vertex (on a type-1 edge) is the E-vertex, a type-2 E-vertex (on
//! the edge from a type-1 vertex `V0` to the type-2 vertex `FCV_0`) is the NFCV of corner `V0` of
//! `FCV_0`'s polygon, the type-1 V-vertex rule is the V-vertex rule (a type-1 vertex of valence
//! `2k` has `k` type-2 neighbours) and the type-2 V-vertex rule is the FCV rule. The 1-4 split
//! (the type-1 E-vertex joined to the type-2 vertex and to the two type-2 E-vertices) is the
//! triangulation of the refined quads around their FCVs. So [`NonBox4Dir`] refines by
//! converting to a [`FcvNet`], applying [`NonBox::step`]'s stencils and triangulating: one set of
//! rules, the same points and the same limit surface for both variants (tested, together with an
//! independent implementation of the four triangle stencils).
//!
//! # Finding the types
//!
//! A triangle mesh does not carry its types. Across an edge the types propagate (the far vertex
//! of the neighbouring triangle is type 2 exactly when the edge joins two type-1 vertices), so
//! each connected component has at most three consistent assignments, one per choice of the
//! type-2 vertex of a first triangle ([`classify`]); an assignment whose type-2 vertex lies on
//! the boundary is discarded (an FCV is inside its face). Among the rest fairsub takes the one
//! whose type-2 vertices are the last vertices of the mesh (the order [`triangulate`] and every
//! refinement write), otherwise the one with the most type-2 vertices (after one refinement
//! step the type-2 vertices are exactly those of valence 4). A regular four-directional grid
//! also admits two other assignments (type 2 at every other grid vertex): order the vertices
//! with the FCVs last to be unambiguous. A triangle mesh without any consistent assignment (the
//! tetrahedron, the icosahedron) is a polygon mesh of triangles and gets FCVs inserted.

use super::{FcvNet, NonBox, fcv_insertion, layout_vertex_count};
use crate::bezier::domain::FanTriangle;
use crate::error::{Error, Result};
use crate::mesh::PolyMesh;
use crate::schemes::options::ids;
use crate::schemes::{Refinement, Scheme};
use crate::stencil::{Stencil, StencilTable};

/// A quasi-four-directional triangle mesh with its vertex types.
#[derive(Debug, Clone)]
pub struct FourDirNet {
    /// The triangle mesh.
    pub mesh: PolyMesh,
    /// `type2[v]`: whether vertex `v` is of type 2 (an FCV).
    pub type2: Vec<bool>,
}

/// Triangulates a net with FCVs: vertices are the net's points (mesh vertices, then FCVs, so the
/// type-2 vertices are the last ones), face `f` with corners `c_0 .. c_(n-1)` becomes the
/// triangles `(c_i, c_(i+1), FCV_f)`, `i = 0 .. n - 1`, in face order.
pub fn triangulate(net: &FcvNet) -> FourDirNet {
    let m = &net.mesh;
    let nv = m.num_vertices();
    let mut face_start = vec![0u32];
    let mut corners = Vec::with_capacity(3 * m.num_halfedges());
    for f in 0..m.num_faces() {
        let c = m.face(f);
        for i in 0..c.len() {
            corners.extend_from_slice(&[c[i], c[(i + 1) % c.len()], (nv + f) as u32]);
            face_start.push(corners.len() as u32);
        }
    }
    // the polygons' vertices keep their numbers: their sharp features carry over by pairs
    let extras = net.mesh.extras().map(|ex| {
        let mut ex = ex.clone();
        if let crate::mesh::SharpEdges::ById(v) = &ex.sharp_edges {
            ex.sharp_edges = crate::mesh::SharpEdges::ByPair(
                v.iter().map(|&(e, s)| (m.edge(e as usize), s)).collect(),
            );
        }
        // triangle `h` stands on half-edge `h`
        ex.holes = super::holes::halfedge_holes(m);
        ex
    });
    let mesh = PolyMesh::from_refinement(net.points(), face_start, corners)
        .expect("the triangulation of a valid net is valid")
        .with_extras(extras);
    let mut type2 = vec![false; net.num_points()];
    for t in &mut type2[nv..] {
        *t = true;
    }
    FourDirNet { mesh, type2 }
}

/// The vertex types of a triangle mesh: the chosen consistent assignment (see the
/// [module](self) documentation); an error names a face that is not a triangle or a triangle
/// where every choice conflicts.
pub fn classify(mesh: &PolyMesh) -> Result<Vec<bool>> {
    classify_counted(mesh).map(|(t, _)| t)
}

/// Like [`classify`], also returning the largest number of consistent assignments found in a
/// connected component (1 when the types are unambiguous).
pub fn classify_counted(mesh: &PolyMesh) -> Result<(Vec<bool>, usize)> {
    if let Some(f) = (0..mesh.num_faces()).find(|&f| mesh.face_size(f) != 3) {
        return Err(Error::Unsupported(format!(
            "face {f} has {} corners: a quasi-four-directional mesh has only triangles (use \
             --scheme {} for polygon meshes)",
            mesh.face_size(f),
            ids::NONBOX
        )));
    }
    let nf = mesh.num_faces();
    let nv = mesh.num_vertices();
    let mut types: Vec<Option<bool>> = vec![None; nv];
    let mut visited = vec![false; nf];
    let mut most = 0;
    for seed in 0..nf {
        if visited[seed] {
            continue;
        }
        // Try the three choices of the seed triangle's type-2 vertex.
        let mut options: Vec<Assignment> = Vec::new();
        for k in 0..3 {
            if let Some(opt) = propagate(mesh, seed, k) {
                options.push(opt);
            }
        }
        if options.is_empty() {
            return Err(Error::Unsupported(format!(
                "the triangles around face {seed} admit no vertex types (every triangle needs \
                 exactly one type-2 vertex, inside the mesh): not quasi-four-directional"
            )));
        }
        most = most.max(options.len());
        let trailing = |o: &Assignment| {
            let max1 = o.1.iter().filter(|x| !x.1).map(|x| x.0).max();
            let min2 = o.1.iter().filter(|x| x.1).map(|x| x.0).min();
            matches!((max1, min2), (Some(a), Some(b)) if a < b)
        };
        let count2 = |o: &Assignment| o.1.iter().filter(|x| x.1).count();
        let best = options
            .iter()
            .enumerate()
            .max_by_key(|(i, o)| (trailing(o), count2(o), usize::MAX - i))
            .map(|(i, _)| i)
            .expect("non-empty");
        let (faces, assigned) = &options[best];
        for &f in faces {
            visited[f] = true;
        }
        for &(v, t) in assigned {
            types[v] = Some(t);
        }
    }
    Ok((
        types.into_iter().map(|t| t.unwrap_or(false)).collect(),
        most,
    ))
}

/// A consistent type assignment of one connected component: its faces and its
/// `(vertex, is type 2)` pairs.
type Assignment = (Vec<usize>, Vec<(usize, bool)>);

/// Propagates the types over the component of `seed` with corner `k` of `seed` as its type-2
/// vertex; `None` on a conflict or a type-2 boundary vertex.
fn propagate(mesh: &PolyMesh, seed: usize, k: usize) -> Option<Assignment> {
    let mut ty: std::collections::HashMap<usize, bool> = std::collections::HashMap::new();
    let c = mesh.face(seed);
    for (i, &v) in c.iter().enumerate() {
        ty.insert(v as usize, i == k);
    }
    let mut seen = std::collections::HashSet::new();
    seen.insert(seed);
    let mut queue = vec![seed];
    let mut faces = Vec::new();
    while let Some(f) = queue.pop() {
        faces.push(f);
        let c = mesh.face(f);
        if c.iter().filter(|&&v| ty[&(v as usize)]).count() != 1 {
            return None;
        }
        let h0 = mesh.face_halfedge(f);
        for h in h0..h0 + 3 {
            let Some(t) = mesh.he_twin(h) else { continue };
            let g = mesh.he_face(t) as usize;
            let (a, b) = (mesh.he_from(h) as usize, mesh.he_to(h) as usize);
            let far = mesh.he_from(mesh.he_prev(t)) as usize;
            let want = !ty[&a] && !ty[&b];
            match ty.get(&far) {
                Some(&x) if x != want => return None,
                _ => {
                    ty.insert(far, want);
                }
            }
            if seen.insert(g) {
                queue.push(g);
            }
        }
    }
    let mut assigned: Vec<(usize, bool)> = ty.into_iter().collect();
    assigned.sort_unstable();
    if assigned
        .iter()
        .any(|&(v, t)| t && mesh.is_boundary_vertex(v))
    {
        return None;
    }
    faces.sort_unstable();
    Some((faces, assigned))
}

impl FourDirNet {
    /// A four-directional net from a triangle mesh with explicit types. Errors (naming the
    /// triangle) unless every triangle has exactly one type-2 vertex and no type-2 vertex is on
    /// the boundary.
    pub fn new(mesh: PolyMesh, type2: Vec<bool>) -> Result<FourDirNet> {
        if type2.len() != mesh.num_vertices() {
            return Err(Error::InvalidArgument(format!(
                "{} vertex types given for a mesh of {} vertices",
                type2.len(),
                mesh.num_vertices()
            )));
        }
        for f in 0..mesh.num_faces() {
            let c = mesh.face(f);
            if c.len() != 3 {
                return Err(Error::Unsupported(format!(
                    "face {f} has {} corners: a quasi-four-directional mesh has only triangles",
                    c.len()
                )));
            }
            let n2 = c.iter().filter(|&&v| type2[v as usize]).count();
            if n2 != 1 {
                return Err(Error::InvalidArgument(format!(
                    "triangle {f} has {n2} type-2 vertices; each triangle needs exactly one"
                )));
            }
        }
        if let Some(v) = (0..mesh.num_vertices()).find(|&v| type2[v] && mesh.is_boundary_vertex(v))
        {
            return Err(Error::InvalidArgument(format!(
                "type-2 vertex {v} lies on the boundary: an FCV must be inside its face"
            )));
        }
        Ok(FourDirNet { mesh, type2 })
    }

    /// Whether edge `e` is of type 2 (joins a type-1 and a type-2 vertex); type-1 edges join two
    /// type-1 vertices and are the edges of the polygon mesh.
    pub fn is_type2_edge(&self, e: usize) -> bool {
        let [a, b] = self.mesh.edge(e);
        self.type2[a as usize] || self.type2[b as usize]
    }

    /// The types found by [`classify`].
    pub fn classified(mesh: PolyMesh) -> Result<FourDirNet> {
        let t = classify(&mesh)?;
        FourDirNet::new(mesh, t)
    }

    /// The half-edges from type-2 vertex `v` to its polygon's corners, in the polygon's corner
    /// order: counter-clockwise, starting in the triangle of lowest index (so a net
    /// triangulated by [`triangulate`] gets its own corner order back). The triangle of the
    /// `i`-th is the polygon's `(corner i, corner i + 1, FCV)`.
    fn polygon_halfedges(&self, v: usize) -> Vec<u32> {
        let m = &self.mesh;
        let hs = m.outgoing_halfedges(v);
        let first = (0..hs.len()).min_by_key(|&i| m.he_face(hs[i])).unwrap_or(0);
        (0..hs.len()).map(|i| hs[(first + i) % hs.len()]).collect()
    }

    /// Each triangle as the fan triangle of its polygon in [`FourDirNet::to_fcv_net`]'s net
    /// (polygon `p` is the `p`-th type-2 vertex's): the domain of the triangles when the
    /// complex is built on that net (`crate::bezier::domain`'s `fan` module).
    pub fn fan_triangles(&self) -> Vec<FanTriangle> {
        let m = &self.mesh;
        let mut out = vec![
            FanTriangle {
                host: u32::MAX,
                sides: 0,
                edge: 0,
                rot: 0,
            };
            m.num_faces()
        ];
        let type2 = (0..m.num_vertices()).filter(|&v| self.type2[v]);
        for (p, v) in type2.enumerate() {
            let hs = self.polygon_halfedges(v);
            for (i, &h) in hs.iter().enumerate() {
                let t = m.he_face(h) as usize;
                let corner = m.he_to(h);
                let rot = m.face(t).iter().position(|&w| w == corner).unwrap_or(0);
                out[t] = FanTriangle {
                    host: p as u32,
                    sides: hs.len() as u32,
                    edge: i as u32,
                    rot: rot as u8,
                };
            }
        }
        out
    }

    /// The polygon mesh with FCVs of this net, and for each of its points (vertices, then FCVs)
    /// the vertex of this triangle mesh it is.
    pub fn to_fcv_net(&self) -> Result<(FcvNet, Vec<usize>)> {
        let m = &self.mesh;
        let mut new_of_old = vec![usize::MAX; m.num_vertices()];
        let mut type1 = Vec::new();
        for (v, slot) in new_of_old.iter_mut().enumerate() {
            if !self.type2[v] {
                *slot = type1.len();
                type1.push(v);
            }
        }
        let mut faces: Vec<Vec<usize>> = Vec::new();
        let mut fcv = Vec::new();
        let mut fcv_vertex = Vec::new();
        for v in (0..m.num_vertices()).filter(|&v| self.type2[v]) {
            faces.push(
                self.polygon_halfedges(v)
                    .iter()
                    .map(|&h| new_of_old[m.he_to(h) as usize])
                    .collect(),
            );
            fcv.push(m.position(v));
            fcv_vertex.push(v);
        }
        let pos = type1.iter().map(|&v| m.position(v)).collect();
        let poly = PolyMesh::new(pos, &faces).map_err(|e| {
            Error::Unsupported(format!(
                "the type-1 polygons of the triangle mesh do not form a valid net ({e})"
            ))
        })?;
        let poly = match m.extras() {
            Some(ex) => poly.with_extras(Some(polygon_extras(m, ex, &new_of_old)?)),
            None => poly,
        };
        let net = FcvNet::new(poly, fcv)?;
        let mut map = type1;
        map.extend(fcv_vertex);
        Ok((net, map))
    }
}

/// The sharp features of a four-directional triangle mesh on its polygon net (type-1 vertices
/// renumbered by `new_of_old`): creases must join two type-1 vertices (the polygons' edges),
/// corners be type-1 vertices.
fn polygon_extras(
    m: &PolyMesh,
    ex: &crate::mesh::Extras,
    new_of_old: &[usize],
) -> Result<crate::mesh::Extras> {
    let map = |v: u32, what: &str| -> Result<u32> {
        match new_of_old[v as usize] {
            usize::MAX => Err(Error::Unsupported(format!(
                "{what} at vertex {v}, a face centre (type-2 vertex) of the four-directional \
                 mesh; its sharp features must lie on the polygons' edges and corners"
            ))),
            n => Ok(n as u32),
        }
    };
    let pairs: Vec<([u32; 2], f32)> = match &ex.sharp_edges {
        crate::mesh::SharpEdges::ById(v) => {
            v.iter().map(|&(e, s)| (m.edge(e as usize), s)).collect()
        }
        crate::mesh::SharpEdges::ByPair(v) => v.clone(),
    };
    let mut out = ex.clone();
    out.sharp_edges = crate::mesh::SharpEdges::ByPair(
        pairs
            .into_iter()
            .map(|([a, b], s)| Ok(([map(a, "a crease")?, map(b, "a crease")?], s)))
            .collect::<Result<_>>()?,
    );
    out.sharp_vertices = ex
        .sharp_vertices
        .iter()
        .map(|&(v, s)| Ok((map(v, "a corner")?, s)))
        .collect::<Result<_>>()?;
    out.sharp_vertices.sort_unstable_by_key(|p| p.0);
    Ok(out)
}

/// Reads the four-directional net a plain mesh stands for: a layout mesh (triangulated with its
/// FCVs), a triangle mesh with a consistent type assignment, or else any polygon mesh with its
/// barycentres as FCVs (triangulated). Returns the net and, for the last case, the table that
/// computes its points from the mesh's vertices.
pub(crate) fn four_dir_of(mesh: &PolyMesh) -> Result<(FourDirNet, Option<StencilTable>)> {
    if layout_vertex_count(mesh).is_some()
        && let Some(net) = FcvNet::from_layout_mesh(mesh)
    {
        return Ok((triangulate(&net), None));
    }
    if mesh.is_all_triangles()
        && let Ok(net) = FourDirNet::classified(mesh.clone())
    {
        return Ok((net, None));
    }
    let net = FcvNet::barycentric(mesh.clone());
    Ok((triangulate(&net), Some(fcv_insertion(mesh, 1.0))))
}

/// Whether the type-2 vertices are exactly the last vertices.
fn trailing_type2(t: &[bool]) -> bool {
    t.iter().skip_while(|&&x| !x).all(|&x| x)
}

/// How [`NonBox4Dir`] reads `mesh`, in one sentence for the user.
pub fn describe_input(mesh: &PolyMesh) -> String {
    if let Some(nv) = layout_vertex_count(mesh) {
        return format!(
            "{}: polygon net with {} FCVs (layout mesh), triangulated around them",
            ids::NONBOX_4DIR,
            mesh.num_vertices() - nv
        );
    }
    if mesh.is_all_triangles() {
        let typed =
            classify_counted(mesh).and_then(|(t, n)| FourDirNet::new(mesh.clone(), t).map(|_| n));
        return match (classify(mesh), typed) {
            (Ok(t), Ok(n)) => format!(
                "{}: read as a quasi-four-directional mesh with {} type-2 vertices \
                 (FCVs){}",
                ids::NONBOX_4DIR,
                t.iter().filter(|&&x| x).count(),
                if n == 1 {
                    String::new()
                } else if trailing_type2(&t) {
                    format!(
                        "; the topology admits {n} type assignments, fairsub took the one with \
                         the type-2 vertices last"
                    )
                } else {
                    format!(
                        "; the topology admits {n} type assignments, fairsub took the one with \
                         the most type-2 vertices (give the FCVs as the last vertices to fix \
                         them, or use --scheme {} to treat the triangles as polygons)",
                        ids::NONBOX
                    )
                }
            ),
            (Err(e), _) | (_, Err(e)) => format!(
                "{}: not quasi-four-directional ({e}); the triangles are polygons with \
                 their barycentres as FCVs",
                ids::NONBOX_4DIR
            ),
        };
    }
    format!(
        "{}: polygon net with its face barycentres as FCVs, triangulated around them",
        ids::NONBOX_4DIR
    )
}

/// Re-indexes a table whose rows and sources are points of an [`FcvNet`] to the vertices of the
/// four-directional mesh: `map[p]` is the vertex of point `p`.
fn remap_sources(t: &StencilTable, map: &[usize], n: usize) -> StencilTable {
    let mut out = StencilTable::with_capacity(n, t.num_rows(), 8);
    for r in 0..t.num_rows() {
        let (idx, w) = t.row(r);
        out.push(Stencil::from_pairs(
            idx.iter().zip(w).map(|(&i, &w)| (map[i as usize], w)),
        ));
    }
    out
}

/// The four-directional variant as a [`Scheme`]: input a quasi-four-directional triangle mesh
/// (types found by [`classify`]), a layout mesh, or any polygon mesh (FCVs = barycentres);
/// output the refined quasi-four-directional triangle mesh (type-1 vertices first, then the
/// type-2 vertices).
#[derive(Debug, Clone, Copy, Default)]
pub struct NonBox4Dir;

impl NonBox4Dir {
    /// One step of a four-directional net: the child net and the table from this net's vertices
    /// to the child's.
    pub fn step(net: &FourDirNet) -> Result<(FourDirNet, StencilTable)> {
        let (fcv, map) = net.to_fcv_net()?;
        let step = NonBox::step(&fcv)?;
        let child = triangulate(&step.net);
        let st = remap_sources(&step.stencils, &map, net.mesh.num_vertices());
        Ok((child, st))
    }

    /// Limit-position stencils of every vertex of a four-directional net (over its vertices).
    pub fn limit_stencils(net: &FourDirNet) -> Result<StencilTable> {
        let (fcv, map) = net.to_fcv_net()?;
        let lim = NonBox::limit_stencils(&fcv);
        let n = net.mesh.num_vertices();
        let mut rows = vec![0usize; n];
        for (p, &v) in map.iter().enumerate() {
            rows[v] = p;
        }
        Ok(remap_sources(&lim.select_rows(&rows), &map, n))
    }
}

impl Scheme for NonBox4Dir {
    fn step_size(&self, s: &crate::schemes::growth::NetSize) -> crate::schemes::growth::NetSize {
        crate::schemes::growth::four_directional(s)
    }

    fn fcv_layout(&self) -> crate::schemes::FcvLayout {
        crate::schemes::FcvLayout::Triangles
    }

    fn input_notes(&self, mesh: &PolyMesh) -> Vec<String> {
        super::input_notes(true, mesh)
    }

    fn name(&self) -> &'static str {
        crate::schemes::options::ids::NONBOX_4DIR.name()
    }

    fn refine(&self, mesh: &PolyMesh) -> Result<Refinement> {
        let (net, insertion) = four_dir_of(mesh)?;
        let (child, st) = Self::step(&net)?;
        let stencils = match insertion {
            Some(ins) => st.compose(&ins),
            None => st,
        };
        let positions = stencils.apply(mesh.positions());
        let mut m = child.mesh;
        m.set_positions(positions);
        Ok(Refinement { mesh: m, stencils })
    }

    fn limit_stencils(&self, mesh: &PolyMesh) -> Result<StencilTable> {
        let (net, insertion) = four_dir_of(mesh)?;
        let lim = Self::limit_stencils(&net)?;
        Ok(match insertion {
            Some(ins) => lim
                .select_rows(&(0..mesh.num_vertices()).collect::<Vec<_>>())
                .compose(&ins),
            None => lim,
        })
    }
}
