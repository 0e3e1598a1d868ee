"""Blender meshes to fairsub nets and back, the way Blender's own Subdivision Surface modifier
hands a mesh to OpenSubdiv (read in Blender's source, `subdiv_converter_mesh.cc`, and written
here from that understanding):

- vertices that no face uses are left out, and the vertices of loose edges (edges no face uses)
  are infinitely sharp;
- an edge or vertex crease ``c`` (the float attributes ``crease_edge`` on edges and
  ``crease_vert`` on points) is the OpenSubdiv sharpness ``s = c * c * 10`` in single
  precision;
- loose vertices are kept where they are, and every loose edge is cut into ``2^levels``
  segments whose points lie on the uniform cubic B-spline through the edge's two vertices and
  one neighbour on each side (the other vertex of the only other edge at that vertex; where a
  vertex has no other edge or more than one, the edge is extended by its own length): so
  chains of loose edges come out smoothed, their inner vertices at ``(a + 4 v + b) / 6``, and
  a lone edge stays straight (:func:`loose_geometry`);
- a UV map becomes one face-varying channel: the corners around a vertex share a value when
  their UVs differ by less than 1e-4 in both coordinates from the first corner of the group
  (the corners taken in the reverse of their order, as Blender's list is built) and their faces
  have the same UV winding (the sign of the face's area in UV space); the shared value is the
  UV of the group's last corner.

Nothing here touches the scene: the functions read and build meshes from numpy arrays, and the
fairsub calls are the package's public ones (``fairsub.Net``, its ``face_arrays``, ``creases``,
``corners``, ``uv``)."""

import numpy as np

#: Blender's ``STD_UV_CONNECT_LIMIT``: UVs closer than this in both coordinates are one value.
UV_CONNECT_LIMIT = 1e-4
#: OpenSubdiv's infinite sharpness.
INFINITE = np.float32(10.0)


def crease_to_sharpness(crease):
    """OpenSubdiv sharpness of Blender crease values: ``c * c * 10`` in single precision, as
    Blender's modifier computes it (no clamp: a crease above 1 is infinitely sharp, as
    OpenSubdiv reads every sharpness from 10 up)."""
    c = np.asarray(crease, dtype=np.float32)
    return c * c * np.float32(10.0)


def sharpness_to_crease(sharpness):
    """The crease whose sharpness (by :func:`crease_to_sharpness`) is ``sharpness``: the
    single-precision square root of ``s / 10``, nudged by a unit in the last place where that
    lands on the same sharpness exactly; sharpness 10 and more (infinitely sharp) is crease 1."""
    s = np.minimum(np.asarray(sharpness, dtype=np.float32), INFINITE)
    s = np.maximum(s, np.float32(0.0))
    c = np.sqrt(s.astype(np.float64) / 10.0).astype(np.float32)
    for step in (np.float32(np.inf), np.float32(-np.inf)):
        miss = crease_to_sharpness(c) != s
        if not miss.any():
            break
        other = np.nextafter(c, step)
        hit = miss & (crease_to_sharpness(other) == s)
        c = np.where(hit, other, c)
    return c


def _float_attribute(mesh, name, domain, n):
    """A float attribute on ``domain`` as an array of ``n`` values, or None (missing, or on
    another domain or of another type: then the caller reports it)."""
    a = mesh.attributes.get(name)
    if a is None:
        return None
    if a.domain != domain or a.data_type not in ("FLOAT", "INT", "BOOLEAN", "INT8"):
        raise ValueError(
            f"the attribute '{name}' is {a.data_type} on {a.domain}; creases are read from a "
            f"FLOAT attribute on {domain}"
        )
    out = np.empty(n, dtype=np.float32 if a.data_type == "FLOAT" else np.int32)
    if a.data_type == "BOOLEAN":
        tmp = np.empty(n, dtype=bool)
        a.data.foreach_get("value", tmp)
        return tmp.astype(np.float32)
    a.data.foreach_get("value", out)
    return out.astype(np.float32)


class MeshArrays:
    """A Blender mesh as numpy arrays: vertices (n, 3) float32, faces as sizes and corner
    vertices, edges (m, 2), the face of every edge count, and the creases."""

    def __init__(self, mesh):
        nv, nf = len(mesh.vertices), len(mesh.polygons)
        nl, ne = len(mesh.loops), len(mesh.edges)
        self.vertices = np.empty(nv * 3, dtype=np.float32)
        mesh.vertices.foreach_get("co", self.vertices)
        self.vertices = self.vertices.reshape(nv, 3)
        self.sizes = np.empty(nf, dtype=np.int32)
        mesh.polygons.foreach_get("loop_total", self.sizes)
        starts = np.empty(nf, dtype=np.int32)
        mesh.polygons.foreach_get("loop_start", starts)
        loop_verts = np.empty(nl, dtype=np.int32)
        mesh.loops.foreach_get("vertex_index", loop_verts)
        loop_edges = np.empty(nl, dtype=np.int32)
        mesh.loops.foreach_get("edge_index", loop_edges)
        # corners face after face (Blender keeps them so; the gather makes it certain)
        self.corner_loops = _ranges(starts, self.sizes)
        self.corners = loop_verts[self.corner_loops]
        self.edges = np.empty(ne * 2, dtype=np.int32)
        mesh.edges.foreach_get("vertices", self.edges)
        self.edges = self.edges.reshape(ne, 2)
        self.edge_faces = np.bincount(loop_edges, minlength=ne)
        self.edge_crease = _float_attribute(mesh, "crease_edge", "EDGE", ne)
        self.vertex_crease = _float_attribute(mesh, "crease_vert", "POINT", nv)
        self.face_of_corner = np.repeat(np.arange(nf), self.sizes)


def _ranges(starts, sizes):
    """The concatenation of ``range(start, start + size)`` for every face."""
    if len(sizes) == 0:
        return np.zeros(0, dtype=np.int64)
    offsets = np.repeat(starts - np.concatenate(([0], np.cumsum(sizes)[:-1])), sizes)
    return np.arange(int(sizes.sum())) + offsets


def uv_indexing(corner_verts, face_of_corner, sizes, uvs, limit=UV_CONNECT_LIMIT):
    """Face-varying values and one index per corner for a UV map (``uvs`` (corners, 2) in
    corner order), grouped as the module documentation says. Exactly equal UVs of a vertex
    are grouped at once; only vertices with several distinct UVs go through the greedy
    grouping (the seams)."""
    uvs = np.asarray(uvs, dtype=np.float32)
    limit = np.float32(limit)  # Blender compares in single precision
    n = len(corner_verts)
    # the UV winding of each face: the sign of its area in UV space
    nxt = np.arange(n) + 1
    ends = np.cumsum(sizes)
    nxt[ends - 1] = ends - sizes
    x, y = uvs[:, 0].astype(np.float64), uvs[:, 1].astype(np.float64)
    area = np.bincount(face_of_corner, weights=x * y[nxt] - x[nxt] * y, minlength=len(sizes))
    winding = (area > 0)[face_of_corner]
    key = np.stack([corner_verts, winding, uvs[:, 0].view(np.int32), uvs[:, 1].view(np.int32)], 1)
    _, first, group = np.unique(key, axis=0, return_index=True, return_inverse=True)
    group = group.reshape(-1)
    # vertices whose corners carry more than one distinct UV: group them as Blender does
    distinct = np.bincount(corner_verts[first], minlength=int(corner_verts.max()) + 1)
    seam = distinct[corner_verts] > 1
    if seam.any():
        group = group.copy()
        fresh = int(group.max()) + 1
        order = np.argsort(corner_verts[seam], kind="stable")
        seam_corners = np.flatnonzero(seam)[order]
        split = np.flatnonzero(np.diff(corner_verts[seam_corners])) + 1
        for cs in np.split(seam_corners, split):
            remaining = list(cs[::-1])  # Blender's list is built by prepending
            while remaining:
                head = remaining.pop(0)
                same = [
                    c
                    for c in remaining
                    if abs(uvs[c, 0] - uvs[head, 0]) < limit
                    and abs(uvs[c, 1] - uvs[head, 1]) < limit
                    and winding[c] == winding[head]
                ]
                for c in [head] + same:
                    group[c] = fresh
                remaining = [c for c in remaining if c not in same]
                fresh += 1
    _, index = np.unique(group, return_inverse=True)
    index = index.reshape(-1)
    values = np.zeros((int(index.max()) + 1 if n else 0, 2))
    values[index] = uvs  # the last corner of a group gives its value
    return values, index


def net_arguments(a, use_creases=True, uv=None):
    """The arguments of ``fairsub.Net`` for mesh arrays ``a``: (vertices, faces, keywords,
    kept), with unused vertices left out (``kept`` lists the Blender vertex of every net
    vertex), loose edges' vertices infinitely sharp, creases as sharpness when
    ``use_creases``, and ``uv`` (a UV map's corner values, in face corner order) as a
    face-varying channel."""
    nv = len(a.vertices)
    used = np.zeros(nv, dtype=bool)
    used[a.corners] = True
    kept = np.flatnonzero(used)
    new_of_old = np.full(nv, -1, dtype=np.int64)
    new_of_old[kept] = np.arange(len(kept))
    kw = {}
    face_edges = a.edge_faces > 0
    if use_creases and a.edge_crease is not None:
        s = crease_to_sharpness(a.edge_crease)
        pick = face_edges & (s > 0)
        if pick.any():
            kw["creases"] = (new_of_old[a.edges[pick]], s[pick])
    vs = np.zeros(nv, dtype=np.float32)
    if use_creases and a.vertex_crease is not None:
        vs = crease_to_sharpness(a.vertex_crease)
    loose = a.edges[~face_edges].reshape(-1)
    vs[loose] = INFINITE
    pick = used & (vs > 0)
    if pick.any():
        kw["corners"] = (new_of_old[np.flatnonzero(pick)], vs[pick])
    if uv is not None:
        kw["uv"] = uv_indexing(a.corners, a.face_of_corner, a.sizes, uv)
    faces = (a.sizes.astype(np.int64), new_of_old[a.corners])
    return a.vertices[kept].astype(np.float64), faces, kw, kept


def _bspline_weights(u):
    """The uniform cubic B-spline's four weights at ``u`` in [0, 1] (u, 4)."""
    u = np.asarray(u, dtype=np.float64)[:, None]
    return np.hstack(
        [(1 - u) ** 3, 3 * u**3 - 6 * u**2 + 4, -3 * u**3 + 3 * u**2 + 3 * u + 1, u**3]
    ) / 6.0


def loose_geometry(a, levels, surface_index, base):
    """The loose vertices and loose edges of mesh arrays ``a`` as Blender's modifier refines
    them ``levels`` times (see the module documentation), for a result whose first ``base``
    vertices are the refined surface: ``surface_index`` gives the result vertex of every
    source vertex that a face uses (-1 for the others, the loose ones). Returns the new points
    (k, 3), to append after the surface's vertices, and the result's loose edges (m, 2)."""
    nv = len(a.vertices)
    loose_edges = a.edges[a.edge_faces == 0]
    loose_verts = np.flatnonzero(surface_index < 0)
    index = surface_index.copy()
    index[loose_verts] = base + np.arange(len(loose_verts))
    pos = a.vertices.astype(np.float64)
    moved = pos[loose_verts]
    if len(loose_edges) == 0:
        return moved, np.zeros((0, 2), dtype=np.int64)
    # a vertex of two edges: its two partners (the first and the last edge written)
    degree = np.bincount(a.edges.reshape(-1), minlength=nv)
    ends, partner = a.edges.reshape(-1), a.edges[:, ::-1].reshape(-1)
    last = np.full(nv, -1, dtype=np.int64)
    last[ends] = partner
    first = np.full(nv, -1, dtype=np.int64)
    first[ends[::-1]] = partner[::-1]

    def outer(v, w):
        # the point beyond v on the edge (v, w): the other edge's vertex, or the edge extended
        n = np.where(last[v] == w, first[v], last[v])
        n = np.where(degree[v] == 2, n, -1)
        return np.where((n >= 0)[:, None], pos[np.maximum(n, 0)], 2 * pos[v] - pos[w])

    v0, v1 = loose_edges[:, 0], loose_edges[:, 1]
    ctrl = np.stack([outer(v0, v1), pos[v0], pos[v1], outer(v1, v0)], axis=1)  # (m, 4, 3)
    # the loose vertices of the edges at their B-spline position (u = 0 and 1)
    for u, v in ((0.0, v0), (1.0, v1)):
        free = surface_index[v] < 0
        moved[index[v[free]] - base] = np.einsum("j,mjc->mc", _bspline_weights([u])[0], ctrl[free])
    segments = 2**levels
    inner = _bspline_weights(np.arange(1, segments) / segments)  # (segments - 1, 4)
    inner_points = np.einsum("sj,mjc->msc", inner, ctrl).reshape(-1, 3)
    start = base + len(loose_verts)
    chain = np.empty((len(loose_edges), segments + 1), dtype=np.int64)
    chain[:, 0] = index[v0]
    chain[:, -1] = index[v1]
    chain[:, 1:-1] = start + np.arange(len(inner_points)).reshape(len(loose_edges), segments - 1)
    edges = np.stack([chain[:, :-1], chain[:, 1:]], axis=2).reshape(-1, 2)
    return np.vstack([moved, inner_points]), edges


def uv_map_values(mesh, name, corner_loops):
    """The corner UVs of the UV map ``name`` in face corner order (corners, 2)."""
    layer = mesh.uv_layers[name]
    out = np.empty(len(mesh.loops) * 2, dtype=np.float32)
    layer.uv.foreach_get("vector", out)
    return out.reshape(-1, 2)[corner_loops]


def parent_faces(sizes, scheme, levels, refined_faces):
    """The input face of every refined face of Catmull-Clark (an n-gon's n children, then four
    per quad) or Loop (four per triangle) refinement, whose children follow their parent in
    order; None for other schemes or when the counts do not add up (holes removed)."""
    if scheme not in ("catmull-clark", "loop") or levels < 1:
        return None
    parent = np.arange(len(sizes))
    first = sizes if scheme == "catmull-clark" else np.full(len(sizes), 4)
    parent = np.repeat(parent, first)
    for _ in range(levels - 1):
        parent = np.repeat(parent, 4)
    return parent if len(parent) == refined_faces else None


def build_mesh(bpy_data, name, vertices, sizes, corners, loose_edges=None):
    """A new Blender mesh from vertices (n, 3) and faces as sizes and corner vertices; the
    faces' edges are made by Blender (``update(calc_edges=True)``), after ``loose_edges``
    (m, 2) when given."""
    me = bpy_data.meshes.new(name)
    me.vertices.add(len(vertices))
    me.vertices.foreach_set("co", np.ascontiguousarray(vertices, dtype=np.float32).reshape(-1))
    if loose_edges is not None and len(loose_edges):
        me.edges.add(len(loose_edges))
        me.edges.foreach_set("vertices", np.ascontiguousarray(loose_edges, dtype=np.int32).reshape(-1))
    me.loops.add(len(corners))
    me.loops.foreach_set("vertex_index", np.ascontiguousarray(corners, dtype=np.int32))
    me.polygons.add(len(sizes))
    starts = np.concatenate(([0], np.cumsum(sizes)[:-1])).astype(np.int32)
    me.polygons.foreach_set("loop_start", starts)
    me.update(calc_edges=True)
    return me


def edge_index(mesh, pairs):
    """The index of the mesh edge between each vertex pair (m, 2); -1 where there is none."""
    ne = len(mesh.edges)
    ev = np.empty(ne * 2, dtype=np.int64)
    mesh.edges.foreach_get("vertices", ev)
    ev = ev.reshape(ne, 2)
    big = int(max(ev.max(initial=0), np.max(pairs, initial=0))) + 1
    keys = np.sort(ev, axis=1) @ np.array([big, 1])
    order = np.argsort(keys)
    want = np.sort(np.asarray(pairs, dtype=np.int64), axis=1) @ np.array([big, 1])
    pos = np.searchsorted(keys[order], want)
    pos = np.minimum(pos, ne - 1)
    found = keys[order][pos] == want
    return np.where(found, order[pos], -1)


def set_float_attribute(mesh, name, domain, values):
    """Sets (creating it when missing) the float attribute ``name`` on ``domain``."""
    a = mesh.attributes.get(name) or mesh.attributes.new(name, "FLOAT", domain)
    a.data.foreach_set("value", np.ascontiguousarray(values, dtype=np.float32))
