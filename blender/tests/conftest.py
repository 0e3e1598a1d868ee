"""Shared pieces of the Blender add-on's tests, run headless with Blender as a Python module
(``pip install bpy`` of Blender 4.5, with the fairsub wheel in the same environment):

    FAIRSUB_REQUIRE_BLENDER=1 python -m pytest -q blender/tests

Without ``bpy`` the tests skip, unless ``FAIRSUB_REQUIRE_BLENDER=1`` (CI sets it) makes that a
failure. The primitives are Blender's own, made in each test with ``bpy.ops``; Blender's
Subdivision Surface modifier is the peer."""

import os
import pathlib
import sys

import numpy as np
import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]

try:
    import bpy
except ImportError:  # pragma: no cover - depends on the environment
    if os.environ.get("FAIRSUB_REQUIRE_BLENDER") == "1":
        raise
    pytest.skip("Blender as a Python module (bpy) is not installed", allow_module_level=True)

from mathutils.kdtree import KDTree  # noqa: E402  (bpy first)

sys.path.insert(0, str(REPO / "blender"))
import fairsub_blender  # noqa: E402

#: Blender's primitives, made as the tests need them (Blender's default sizes).
PRIMITIVES = {
    "cube": lambda: bpy.ops.mesh.primitive_cube_add(),
    "uv_sphere": lambda: bpy.ops.mesh.primitive_uv_sphere_add(),
    "cylinder": lambda: bpy.ops.mesh.primitive_cylinder_add(),
    "open_cylinder": lambda: bpy.ops.mesh.primitive_cylinder_add(end_fill_type="NOTHING"),
    "cone": lambda: bpy.ops.mesh.primitive_cone_add(),
    "grid": lambda: bpy.ops.mesh.primitive_grid_add(),
    "plane": lambda: bpy.ops.mesh.primitive_plane_add(),
    "torus": lambda: bpy.ops.mesh.primitive_torus_add(),
    "ico_sphere": lambda: bpy.ops.mesh.primitive_ico_sphere_add(),
    "suzanne": lambda: bpy.ops.mesh.primitive_monkey_add(),
}

#: Blender's boundary options and fairsub's names for them.
BOUNDARIES = {"ALL": "edge-only", "PRESERVE_CORNERS": "edge-and-corner"}

#: Blender's UV smooth options and OpenSubdiv's face-varying interpolation they select.
UV_SMOOTH = {
    "NONE": "all",
    "PRESERVE_CORNERS": "corners-only",
    "PRESERVE_CORNERS_AND_JUNCTIONS": "corners-plus1",
    "PRESERVE_CORNERS_JUNCTIONS_AND_CONCAVE": "corners-plus2",
    "PRESERVE_BOUNDARIES": "boundaries",
    "SMOOTH_ALL": "none",
}

#: The agreement asked of fairsub and Blender's modifier, relative to the object's size (the
#: largest distance of a source vertex from the origin, at least 1). Blender refines in single
#: precision: on its cylinder at level 3 (32-gon caps) it is 1.25e-6 away from OpenSubdiv's own
#: refinement in double (which fairsub equals to 1e-7) and 1.31e-6 from it in single
#: precision, while the cylinder reaches 1.41 from the origin.
TOL = 1e-6


@pytest.fixture(scope="session", autouse=True)
def addon():
    """The add-on, registered as ``fairsub_blender.register()`` for the whole session."""
    fairsub_blender.register()
    yield fairsub_blender
    fairsub_blender.unregister()


@pytest.fixture()
def empty():
    """An empty scene (factory settings), for each test."""
    bpy.ops.wm.read_factory_settings(use_empty=True)


def primitive(name):
    """A new primitive, active."""
    PRIMITIVES[name]()
    return bpy.context.active_object


def positions(mesh):
    """Vertex positions (n, 3) float64."""
    v = np.empty(len(mesh.vertices) * 3, dtype=np.float32)
    mesh.vertices.foreach_get("co", v)
    return v.reshape(-1, 3).astype(np.float64)


def faces(mesh):
    """Faces as tuples of vertex indices."""
    sizes = np.empty(len(mesh.polygons), dtype=np.int32)
    mesh.polygons.foreach_get("loop_total", sizes)
    starts = np.empty(len(mesh.polygons), dtype=np.int32)
    mesh.polygons.foreach_get("loop_start", starts)
    lv = np.empty(len(mesh.loops), dtype=np.int32)
    mesh.loops.foreach_get("vertex_index", lv)
    return [tuple(lv[s : s + n]) for s, n in zip(starts, sizes)], starts


def modifier_mesh(ob, levels, boundary="ALL", uv_smooth="PRESERVE_BOUNDARIES", limit=False):
    """Blender's Subdivision Surface modifier's result on ``ob`` (Catmull-Clark, creases used),
    as a new mesh; the modifier is removed again."""
    m = ob.modifiers.new("fairsub peer", "SUBSURF")
    m.levels = levels
    m.use_limit_surface = limit
    m.boundary_smooth = boundary
    m.uv_smooth = uv_smooth
    m.use_creases = True
    depsgraph = bpy.context.evaluated_depsgraph_get()
    me = bpy.data.meshes.new_from_object(ob.evaluated_get(depsgraph))
    ob.modifiers.remove(m)
    return me


def size(mesh):
    """The largest distance of a vertex from the origin, at least 1."""
    return max(1.0, float(np.linalg.norm(positions(mesh), axis=1).max()))


def matching(a, b):
    """Each vertex of mesh ``a`` matched to the nearest of mesh ``b``: (indices into b,
    distances)."""
    pa, pb = positions(a), positions(b)
    kd = KDTree(len(pb))
    for i, p in enumerate(pb):
        kd.insert(p, i)
    kd.balance()
    found = [kd.find(p) for p in pa]
    return np.array([f[1] for f in found]), np.array([f[2] for f in found])


def canonical(face):
    """A face as the rotation of its vertex cycle that starts at its smallest vertex."""
    k = int(np.argmin(face))
    return tuple(face[k:]) + tuple(face[:k])


def attribute_values(a):
    """The values of an attribute as a flat float array."""
    key = {"FLOAT_VECTOR": "vector", "FLOAT2": "vector", "FLOAT_COLOR": "color",
           "BYTE_COLOR": "color", "INT32_2D": "value", "QUATERNION": "value",
           "FLOAT4X4": "value"}.get(a.data_type, "value")
    width = {"FLOAT_VECTOR": 3, "FLOAT2": 2, "FLOAT_COLOR": 4, "BYTE_COLOR": 4,
             "INT32_2D": 2, "QUATERNION": 4, "FLOAT4X4": 16}.get(a.data_type, 1)
    out = np.empty(len(a.data) * width, dtype=np.float64)
    try:
        a.data.foreach_get(key, out)
    except (TypeError, AttributeError):
        out = np.array([float(getattr(d, key)) for d in a.data])
    return out


def snapshot(ob):
    """Everything a test promises to leave alone on a source object: transform, vertices,
    faces, every attribute (creases, UVs, ...), modifiers and materials."""
    me = ob.data
    return {
        "name": ob.name,
        "matrix": [tuple(r) for r in ob.matrix_world],
        "positions": positions(me).tolist(),
        "faces": faces(me)[0],
        "attributes": {
            (a.name, a.domain, a.data_type): attribute_values(a).tolist() for a in me.attributes
        },
        "modifiers": [m.name for m in ob.modifiers],
        "materials": [m.name if m else None for m in me.materials],
    }
