"""Meshes a modeller makes that are not closed manifolds of consistent winding: three faces on
one edge, two fans meeting at one vertex, faces flipped against their neighbours, one filled
n-gon, triangle-fan caps. The operator's Catmull-Clark equals Blender's modifier on them as on
the primitives: the same counts, every point within ``TOL``, the same faces."""

import bmesh
import pytest

from conftest import BOUNDARIES, TOL, bpy, canonical, faces, matching, modifier_mesh, size


def three_faces_on_an_edge(bm):
    v = [bm.verts.new(p) for p in [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1)]]
    bm.faces.new([v[0], v[1], v[2]])
    bm.faces.new([v[1], v[0], v[3]])
    bm.faces.new([v[0], v[1], v[4]])


def bowtie(bm):
    v = [bm.verts.new(p) for p in [(0, 0, 0), (1, 0, 0), (1, 1, 0), (-1, 0, 0), (-1, -1, 0)]]
    bm.faces.new([v[0], v[1], v[2]])
    bm.faces.new([v[0], v[3], v[4]])


def flipped(bm):
    bmesh.ops.create_grid(bm, x_segments=3, y_segments=3, size=1)
    bm.faces.ensure_lookup_table()
    bmesh.ops.reverse_faces(bm, faces=[bm.faces[0], bm.faces[4]])


def ngon(bm):
    bmesh.ops.create_circle(bm, cap_ends=True, segments=9, radius=1)


def fan_cone(bm):
    bmesh.ops.create_cone(
        bm, cap_ends=True, cap_tris=True, segments=7, radius1=1, radius2=0.3, depth=2
    )


MESHES = {f.__name__: f for f in (three_faces_on_an_edge, bowtie, flipped, ngon, fan_cone)}


@pytest.mark.parametrize("boundary", list(BOUNDARIES))
@pytest.mark.parametrize("levels", [1, 2])
@pytest.mark.parametrize("name", list(MESHES))
def test_odd_meshes_equal_blenders_modifier(empty, name, levels, boundary):
    me = bpy.data.meshes.new(name)
    ob = bpy.data.objects.new(name, me)
    bpy.context.collection.objects.link(ob)
    bpy.context.view_layer.objects.active = ob
    bm = bmesh.new()
    MESHES[name](bm)
    bm.to_mesh(me)
    bm.free()
    ref = modifier_mesh(ob, levels, boundary)
    bpy.ops.fairsub.subdivide(scheme="catmull-clark", levels=levels, boundary=BOUNDARIES[boundary])
    res = bpy.context.active_object.data
    assert (len(res.vertices), len(res.polygons)) == (len(ref.vertices), len(ref.polygons))
    idx, dist = matching(ref, res)
    assert dist.max() <= TOL * size(me), dist.max()
    assert len(set(idx)) == len(idx)
    assert {canonical(tuple(idx[list(f)])) for f in faces(ref)[0]} == {
        canonical(f) for f in faces(res)[0]
    }
