//! Walks around vertices and over quad grids: fans, rings, boundary loops, sector charts
//! and c-nets.

use super::{NONE, Outgoing, PolyMesh};

impl PolyMesh {
    /// The outgoing half-edges of `v` as an iterator (the one vertex-ring walker,
    /// [`Outgoing`]), counter-clockwise; for a boundary vertex starting at its boundary
    /// half-edge. Does not allocate.
    #[inline]
    pub fn outgoing(&self, v: usize) -> Outgoing<'_> {
        self.view().outgoing(v)
    }

    /// Outgoing half-edges of `v`, counter-clockwise; for a boundary vertex starting at its
    /// boundary half-edge. The last edge of a boundary vertex (the incoming boundary edge) has no
    /// outgoing half-edge and is not listed; see [`PolyMesh::vertex_neighbors`].
    pub fn outgoing_halfedges(&self, v: usize) -> Vec<u32> {
        self.outgoing(v).collect()
    }

    /// The outgoing half-edges of the interior vertex `h` starts at, counter-clockwise from `h`;
    /// `None` when the walk meets the boundary (the vertex is not interior).
    pub fn interior_ring_from(&self, h: u32) -> Option<Vec<u32>> {
        let hs: Vec<u32> = self.view().outgoing_from(h).collect();
        let closed = self.he_twin(self.he_prev(*hs.last()?)) == Some(h);
        closed.then_some(hs)
    }

    /// The two boundary neighbours of boundary vertex `v`: the end of its outgoing boundary
    /// half-edge and the start of its incoming one.
    pub fn boundary_neighbors(&self, v: usize) -> (u32, u32) {
        self.view().boundary_neighbors(v)
    }

    /// Whether `v` is a boundary vertex with a single incident face (valence 2): a corner.
    pub fn is_corner(&self, v: usize) -> bool {
        self.view().is_corner(v)
    }

    /// Faces around `v`, counter-clockwise (from the boundary for a boundary vertex).
    pub fn vertex_faces(&self, v: usize) -> Vec<u32> {
        self.outgoing_halfedges(v)
            .into_iter()
            .map(|h| self.he_face(h))
            .collect()
    }

    /// Edge neighbours of `v`, counter-clockwise (for a boundary vertex from one boundary
    /// neighbour to the other).
    pub fn vertex_neighbors(&self, v: usize) -> Vec<u32> {
        let hs = self.outgoing_halfedges(v);
        let mut out: Vec<u32> = hs.iter().map(|&h| self.he_to(h)).collect();
        if self.is_boundary_vertex(v) {
            let last = *hs.last().expect("a vertex has a half-edge");
            out.push(self.he_from(self.he_prev(last)));
        }
        out
    }

    /// Valence: the number of edges at `v`.
    pub fn valence(&self, v: usize) -> usize {
        let n = self.outgoing_halfedges(v).len();
        if self.is_boundary_vertex(v) { n + 1 } else { n }
    }

    /// The one-ring of `v`: every vertex of the faces around `v` except `v`, in
    /// counter-clockwise order, without repetition.
    pub fn one_ring(&self, v: usize) -> Vec<u32> {
        let mut out = Vec::new();
        // Linear in the size of the ring (a high-valence fan would be quadratic with
        // `Vec::contains`).
        let mut seen = std::collections::HashSet::new();
        for h in self.outgoing_halfedges(v) {
            let mut g = self.he_next(h);
            while self.he_from(g) != v as u32 {
                let w = self.he_from(g);
                if seen.insert(w) {
                    out.push(w);
                }
                g = self.he_next(g);
            }
        }
        out
    }

    /// The two-ring of `v`: vertices of faces around one-ring vertices that are neither `v` nor in
    /// its one-ring (sorted by index).
    pub fn two_ring(&self, v: usize) -> Vec<u32> {
        let ring1: std::collections::HashSet<u32> = self.one_ring(v).into_iter().collect();
        let mut out = Vec::new();
        for &w in &ring1 {
            for f in self.vertex_faces(w as usize) {
                for &x in self.face(f as usize) {
                    if x != v as u32 && !ring1.contains(&x) {
                        out.push(x);
                    }
                }
            }
        }
        out.sort_unstable();
        out.dedup();
        out
    }

    /// Boundary loops, each as the list of its vertices in the direction of the boundary
    /// half-edges (face on the left).
    pub fn boundary_loops(&self) -> Vec<Vec<u32>> {
        let nh = self.corners.len();
        let mut seen = vec![false; nh];
        let mut loops = Vec::new();
        for h0 in 0..nh as u32 {
            if self.topology().twin[h0 as usize] != NONE || seen[h0 as usize] {
                continue;
            }
            let mut lp = Vec::new();
            let mut h = h0;
            loop {
                seen[h as usize] = true;
                lp.push(self.he_from(h));
                // The next boundary half-edge starts where h ends: the boundary half-edge of that
                // vertex.
                h = self.topology().vert_he[self.he_to(h) as usize];
                if h == h0 || seen[h as usize] {
                    break;
                }
            }
            loops.push(lp);
        }
        loops
    }

    /// Whether every face is a quad.
    pub fn is_all_quads(&self) -> bool {
        (0..self.num_faces()).all(|f| self.face_size(f) == 4)
    }

    /// Whether every face is a triangle.
    pub fn is_all_triangles(&self) -> bool {
        (0..self.num_faces()).all(|f| self.face_size(f) == 3)
    }

    /// Whether `v` is regular in a quad mesh: interior of valence 4, boundary of valence 3, or a
    /// boundary corner of valence 2, with only quads around it.
    pub fn is_regular_quad_vertex(&self, v: usize) -> bool {
        // At most five outgoing half-edges are looked at, so the test costs O(1) also at a
        // vertex of high valence (callers ask it for every cell around such a vertex).
        let view = self.view();
        let mut n = 0;
        for h in view.outgoing(v) {
            n += 1;
            if n > 4 || self.face_size(view.face(h) as usize) != 4 {
                return false;
            }
        }
        if self.is_boundary_vertex(v) {
            // the incoming boundary edge has no outgoing half-edge
            n == 1 || n == 2
        } else {
            n == 4
        }
    }

    /// Extraordinary vertices of a quad-dominant net: vertices that are not
    /// [regular](Self::is_regular_quad_vertex).
    pub fn extraordinary_vertices(&self) -> Vec<usize> {
        (0..self.num_vertices())
            .filter(|&v| !self.is_regular_quad_vertex(v))
            .collect()
    }

    /// Extraordinary facets: faces that are not quads.
    pub fn extraordinary_faces(&self) -> Vec<usize> {
        (0..self.num_faces())
            .filter(|&f| self.face_size(f) != 4)
            .collect()
    }

    /// Half-edge from `a` to `b`, if the edge exists in that direction.
    pub fn find_halfedge(&self, a: usize, b: usize) -> Option<u32> {
        // Both rings are walked in step, so the cost is the smaller valence: asking a fan
        // centre of valence n for each of its n spokes stays linear in n. A half-edge b -> a
        // with a twin gives a -> b at once; one without a twin leaves the walk around a.
        let (bu, au) = (b as u32, a as u32);
        let (mut ra, mut rb) = (self.outgoing(a), self.outgoing(b));
        loop {
            let h = ra.next()?;
            if self.he_to(h) == bu {
                return Some(h);
            }
            if let Some(g) = rb.next().filter(|&g| self.he_to(g) == au) {
                if let Some(t) = self.he_twin(g) {
                    return Some(t);
                }
                return ra.find(|&h| self.he_to(h) == bu);
            }
        }
    }

    /// The cells of the quad grid walked by [`PolyMesh::sector_grid`]: `cells[i][j]` is the
    /// half-edge of cell `(i, j)` leaving its corner `(i, j)` in `+u` direction (its face is
    /// `he_face`), `0 <= i, j < size`.
    pub fn sector_cells(&self, h: u32, size: usize) -> Option<Vec<Vec<u32>>> {
        // cell[i][j] = the half-edge of cell (i, j) leaving its (i, j) corner in +u direction.
        let mut cell = vec![vec![NONE; size]; size];
        for i in 0..size {
            for j in 0..size {
                let c = if i == 0 && j == 0 {
                    h
                } else if j == 0 {
                    // Right neighbour of cell (i - 1, 0).
                    let left = cell[i - 1][0];
                    if self.face_size(self.he_face(left) as usize) != 4 {
                        return None;
                    }
                    self.he_next(self.he_twin(self.he_next(left))?)
                } else {
                    // Upper neighbour of cell (i, j - 1).
                    let below = cell[i][j - 1];
                    if self.face_size(self.he_face(below) as usize) != 4 {
                        return None;
                    }
                    self.he_twin(self.he_next(self.he_next(below)))?
                };
                if self.face_size(self.he_face(c) as usize) != 4 {
                    return None;
                }
                cell[i][j] = c;
            }
        }
        Some(cell)
    }

    /// Walks a quad grid starting at cell `(0, 0)` whose corner `(0, 0)` is the start of
    /// half-edge `h` and whose `+u` direction is `h`'s direction: returns `grid[i][j]`, the vertex
    /// at chart point `(i, j)` for `0 <= i, j <= size`, or `None` when a needed cell is missing or
    /// not a quad. The chart is oriented like the faces (`+v` is counter-clockwise from `+u`).
    pub fn sector_grid(&self, h: u32, size: usize) -> Option<Vec<Vec<u32>>> {
        let cell = self.sector_cells(h, size)?;
        let mut grid = vec![vec![NONE; size + 1]; size + 1];
        for i in 0..size {
            for j in 0..size {
                let c = cell[i][j];
                let n1 = self.he_next(c);
                let n2 = self.he_next(n1);
                let n3 = self.he_next(n2);
                grid[i][j] = self.he_from(c);
                grid[i + 1][j] = self.he_from(n1);
                grid[i + 1][j + 1] = self.he_from(n2);
                grid[i][j + 1] = self.he_from(n3);
            }
        }
        Some(grid)
    }

    /// The c-net of vertex `v` with `rings` rings of quads, in the canonical order of
    /// [`crate::mesh::nets::cnet`]: `v`, then for each sector `s` (counter-clockwise from
    /// [`PolyMesh::vertex_halfedge`]) the chart points `(i, j)`, `i = 1..=rings`,
    /// `j = 0..=rings`. `None` when `v` is on the boundary or the rings are not regular quads.
    pub fn cnet_indices(&self, v: usize, rings: usize) -> Option<Vec<u32>> {
        if self.is_boundary_vertex(v) {
            return None;
        }
        self.cnet_indices_from(self.vertex_halfedge(v), rings)
    }

    /// Like [`PolyMesh::cnet_indices`] with sector 0 starting at the outgoing half-edge `h` of
    /// an interior vertex.
    pub fn cnet_indices_from(&self, h: u32, rings: usize) -> Option<Vec<u32>> {
        let v = self.he_from(h);
        let mut out = vec![v];
        for h in self.interior_ring_from(h)? {
            let g = self.sector_grid(h, rings)?;
            for row in g.iter().skip(1) {
                out.extend_from_slice(row);
            }
        }
        Some(out)
    }
}
