"""Loose vertices and loose edges (no face uses them) next to a surface: Blender's modifier
keeps the vertices and cuts every loose edge into 2^levels segments on a cubic B-spline through
its neighbours (a chain of loose edges comes out smoothed, a lone edge straight, an edge that
meets the surface or more than one other edge is extended by itself). The operator's result
has the same vertices (each within ``TOL`` of one of Blender's), the same faces, and the same
loose edges through that matching."""

import bmesh
import numpy as np
import pytest

from conftest import BOUNDARIES, TOL, bpy, faces, matching, modifier_mesh, size


def scene():
    """Blender's cube with a lone loose edge, a chain of three, a star of three edges at one
    vertex (one of them continuing into a second edge), an edge from a cube corner, an edge
    between two cube vertices across a face, and a loose vertex."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.mesh.primitive_cube_add()
    ob = bpy.context.active_object
    bm = bmesh.new()
    bm.from_mesh(ob.data)
    bm.verts.ensure_lookup_table()
    cube = {tuple(round(c) for c in v.co): v for v in bm.verts}

    def polyline(*points):
        vs = [p if isinstance(p, bmesh.types.BMVert) else bm.verts.new(p) for p in points]
        for a, b in zip(vs, vs[1:]):
            bm.edges.new([a, b])
        return vs

    polyline((3, 0, 0), (4, 0.5, 0))
    polyline((0, 3, 0), (1, 4, 0), (2, 3, 1), (3, 4, 0.5))
    centre = bm.verts.new((-3, -3, 0))
    polyline(centre, (-4, -3, 1))
    polyline(centre, (-3, -4, -1), (-2, -5, -1))
    polyline(centre, (-2, -2, 0.5))
    polyline(cube[(1, 1, 1)], (2, 2.5, 2))
    polyline(cube[(-1, -1, -1)], cube[(1, 1, -1)])
    bm.verts.new((5, 5, 5))
    bm.to_mesh(ob.data)
    bm.free()
    return ob


def loose_edges(me):
    """The loose edges of a mesh as vertex pairs (m, 2)."""
    le = np.empty(len(me.loops), dtype=np.int32)
    me.loops.foreach_get("edge_index", le)
    ev = np.empty(len(me.edges) * 2, dtype=np.int32)
    me.edges.foreach_get("vertices", ev)
    ev = ev.reshape(-1, 2)
    return ev[np.bincount(le, minlength=len(me.edges)) == 0]


@pytest.mark.parametrize("boundary", list(BOUNDARIES))
@pytest.mark.parametrize("levels", [1, 2, 3])
def test_loose_geometry_equals_blenders_modifier(boundary, levels):
    ob = scene()
    ref = modifier_mesh(ob, levels, boundary)
    bpy.ops.fairsub.subdivide(scheme="catmull-clark", levels=levels, boundary=BOUNDARIES[boundary])
    res = bpy.context.active_object.data
    assert (len(res.vertices), len(res.edges), len(res.polygons)) == (
        len(ref.vertices), len(ref.edges), len(ref.polygons)
    )
    idx, dist = matching(ref, res)
    assert dist.max() <= TOL * size(ob.data), dist.max()
    assert len(set(idx)) == len(idx)
    ref_loose = {tuple(sorted(e)) for e in idx[loose_edges(ref)]}
    res_loose = {tuple(sorted(e)) for e in loose_edges(res)}
    assert len(ref_loose) == 10 * 2**levels and ref_loose == res_loose
    assert sorted(map(sorted, (idx[list(f)] for f in faces(ref)[0]))) == sorted(
        map(sorted, faces(res)[0])
    )
