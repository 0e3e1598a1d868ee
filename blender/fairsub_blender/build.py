"""From a Blender object and a recipe (the operator's settings as a dict) to fairsub's results,
through the package's public functions only (``fairsub.Net``, ``subdivide``, ``surface``,
``Surface.tessellation``): the refined net of ``levels`` steps, or the exact surface of
``rings`` rings. Nothing here changes the source object.

A recipe has the keys of :data:`RECIPE_KEYS`; ``options`` holds the scheme's own keyword
options (``{"split_ratio": "0.3"}``)."""

import fairsub
import numpy as np

from . import catalogue, convert

#: The keys of a recipe, with their defaults (Blender's modifier defaults where it has the
#: setting: boundary ``ALL`` = ``edge-only``, UV smooth "Keep Boundaries" = ``boundaries``).
RECIPE_KEYS = {
    "scheme": "catmull-clark",
    "levels": 1,
    "rings": 6,
    "density": 8,
    "fill": True,
    "boundary": "edge-only",
    "crease_method": "uniform",
    "fvar": "boundaries",
    "smooth_triangles": False,
    "use_creases": True,
    "use_uv": True,
    "limit": False,
    "use_modifiers": False,
    "options": {},
}


class SourceMesh:
    """The mesh of a source object as arrays (with its modifiers when the recipe asks), read
    once: :class:`convert.MeshArrays` plus the UV maps' corner values, by name."""

    def __init__(self, ob, recipe, depsgraph=None):
        if ob is None or ob.type != "MESH":
            raise ValueError("fairsub works on a mesh object: make one active")
        mesh, evaluated = ob.data, None
        if recipe["use_modifiers"] and depsgraph is not None:
            evaluated = ob.evaluated_get(depsgraph)
            mesh = evaluated.to_mesh()
        try:
            if len(mesh.polygons) == 0:
                raise ValueError(f"'{ob.name}' has no faces: fairsub subdivides polygon meshes")
            self.arrays = convert.MeshArrays(mesh)
            self.uv_names = [layer.name for layer in mesh.uv_layers]
            self.uvs = {
                n: convert.uv_map_values(mesh, n, self.arrays.corner_loops)
                for n in self.uv_names
            }
            self.materials = list(mesh.materials)
            nf = len(mesh.polygons)
            self.material_index = np.empty(nf, dtype=np.int32)
            mesh.polygons.foreach_get("material_index", self.material_index)
            self.sharp_face = np.empty(nf, dtype=bool)
            mesh.polygons.foreach_get("use_smooth", self.sharp_face)
            self.sharp_face = ~self.sharp_face
        finally:
            if evaluated is not None:
                evaluated.to_mesh_clear()
        self.name = ob.name

    def has_creases(self):
        """Whether the mesh has a nonzero edge or vertex crease."""
        a = self.arrays
        return any(c is not None and np.any(c != 0) for c in (a.edge_crease, a.vertex_crease))


def _feature_keywords(recipe):
    """The OpenSubdiv keyword options of the recipe that its scheme takes."""
    s = recipe["scheme"]
    kw = {}
    for key, option in (("boundary", "boundary"), ("crease_method", "crease-method")):
        if catalogue.takes(s, option):
            kw[key] = recipe[key]
    if catalogue.takes(s, "fvar") and recipe["levels"] > 0:
        kw["fvar"] = recipe["fvar"]
    if catalogue.takes(s, "smooth-triangles") and recipe["smooth_triangles"]:
        kw["smooth_triangles"] = True
    return kw


def net(src, recipe, uv_name=None, notes=None):
    """The fairsub net of a source mesh under a recipe (creases only for schemes that take
    OpenSubdiv's sharp features; a note says when they are left out), with the UV map
    ``uv_name`` as its face-varying channel; and the Blender vertex of every net vertex."""
    s = recipe["scheme"]
    features = catalogue.takes(s, "creases")
    use_creases = recipe["use_creases"] and features
    if recipe["use_creases"] and not features and src.has_creases() and notes is not None:
        notes.append(f"{s} has no rules for creases: the mesh's creases are left out")
    uv = src.uvs[uv_name] if uv_name is not None else None
    vertices, faces, kw, kept = convert.net_arguments(src.arrays, use_creases, uv)
    if not features:
        # vertices of loose edges are infinitely sharp only for OpenSubdiv's schemes
        kw.pop("corners", None)
    return fairsub.Net(vertices, faces, tolerant=features, **kw), kept


def _check(recipe):
    s = catalogue.scheme(recipe["scheme"])
    if recipe["levels"] > 0 and not s["refine"]:
        raise ValueError(
            f"{s['name']} has no control net of its own to refine: set levels to 0 and choose "
            f"rings (its exact surface)"
        )
    if recipe["levels"] == 0 and not s["rings"]:
        raise ValueError(f"{s['name']} has no exact surface: give levels")


def refine(src, recipe):
    """The refined net of ``recipe["levels"]`` steps: a dict of ``vertices`` (n, 3),
    ``sizes``, ``corners`` (the faces), ``uv`` (name -> (values, indices)), ``creases``,
    ``corners_sharp`` (the refined sharpness, as ``fairsub.Net`` gives it), ``parent`` (the
    source face of every face, when known), ``loose_edges`` (the mesh's loose edges refined as
    Blender's modifier refines them, for OpenSubdiv's schemes; their points and the loose
    vertices follow the surface's in ``vertices``) and ``notes``."""
    _check(recipe)
    notes = []
    uv_names = src.uv_names if recipe["use_uv"] and catalogue.takes(recipe["scheme"], "fvar") else []
    if recipe["use_uv"] and src.uv_names and not uv_names:
        notes.append(f"{recipe['scheme']} does not carry UVs: the result has none")
    kw = dict(_feature_keywords(recipe), **recipe["options"])
    first = uv_names[0] if uv_names else None
    n, _ = net(src, recipe, first, notes)
    out = fairsub.subdivide(n, recipe["scheme"], levels=recipe["levels"], limit=recipe["limit"], **kw)
    if isinstance(out, tuple):  # a non-box limit mesh with its exact normals
        out = out[0]
    sizes, corners = out.face_arrays
    uv = {}
    if first is not None and out.uv is not None:
        uv[first] = out.uv
    for name in uv_names[1:]:
        # the same refinement for the next UV channel: only its values are kept
        m, _ = net(src, recipe, name)
        other = fairsub.subdivide(m, recipe["scheme"], levels=recipe["levels"], limit=recipe["limit"], **kw)
        if other.uv is not None:
            uv[name] = other.uv
    vertices, loose_edges = out.vertices, None
    if catalogue.takes(recipe["scheme"], "creases"):
        vertices, loose_edges = _with_loose_geometry(src.arrays, recipe["levels"], vertices)
    return {
        "vertices": vertices,
        "loose_edges": loose_edges,
        "sizes": sizes,
        "corners": corners,
        "uv": uv,
        "creases": out.creases,
        "corners_sharp": out.corners,
        "parent": convert.parent_faces(
            src.arrays.sizes, recipe["scheme"], recipe["levels"], len(sizes)
        ),
        "notes": notes,
    }


def _with_loose_geometry(a, levels, vertices):
    """The refined surface's vertices followed by the mesh's loose vertices and the points of
    its refined loose edges (``convert.loose_geometry``), and those edges (None when the mesh
    has no loose geometry)."""
    used = np.zeros(len(a.vertices), dtype=bool)
    used[a.corners] = True
    loose = a.edges[a.edge_faces == 0]
    if used.all() and len(loose) == 0:
        return vertices, None
    surface_index = np.where(used, 0, -1)
    # a loose edge's vertex on the surface is infinitely sharp: its refined vertex is where it
    # was, found by position
    for v in np.unique(loose[used[loose]]):
        d = np.abs(vertices - a.vertices[v].astype(np.float64)).max(axis=1)
        surface_index[v] = int(np.argmin(d))
    points, edges = convert.loose_geometry(a, levels, surface_index, len(vertices))
    return np.vstack([vertices, points]), edges


def surface(src, recipe):
    """The exact surface (``fairsub.Surface``) of ``recipe["rings"]`` rings, and notes."""
    notes = []
    n, _ = net(src, recipe, None, notes)
    kw = dict(_feature_keywords(recipe), **recipe["options"])
    s = fairsub.surface(n, recipe["scheme"], rings=recipe["rings"], fill=recipe["fill"], **kw)
    return s, notes + list(s.notes)


def exact(src, recipe):
    """The exact surface tessellated at ``recipe["density"]`` samples per patch edge: the
    surface, its ``Surface.tessellation`` dict, and notes."""
    _check(dict(recipe, levels=0))
    s, notes = surface(src, recipe)
    return s, s.tessellation(recipe["density"]), notes
