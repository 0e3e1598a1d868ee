"""``bpy.ops.fairsub.subdivide``: the active mesh refined by a fairsub scheme (``levels`` >= 1)
or its exact surface tessellated (``levels=0``, ``rings``, ``density``), as a new object beside
the source, which is left as it was.

The refined mesh keeps the source's loose vertices and refines its loose edges as Blender's
modifier does (for OpenSubdiv's schemes; see :func:`convert.loose_geometry`). It carries the
source's UV maps (refined by OpenSubdiv's face-varying rules), its materials and flat/smooth
shading per face (for Catmull-Clark and Loop, whose child faces
follow their parent), and its creases refined: each edge and vertex gets the crease of its
refined sharpness (``sharpness_to_crease``), so that subdividing the result again, by fairsub or
by Blender's modifier, continues the same surface (Blender's modifier itself copies a parent's
crease to its children unchanged instead). Boundary edges get no crease (they are sharp
whatever their crease).

The exact surface carries its exact normals (custom normals), the exact Gauss and mean
curvature per vertex (float attributes ``fairsub_gauss``, ``fairsub_mean``), the patch of each
triangle (``fairsub_patch``) and the mean curvature as the colour attribute
``fairsub_curvature``. Both results remember their recipe in the custom property ``fairsub``
(JSON), which the shape tools read."""

import json

import bpy
import fairsub
import numpy as np

from . import build, catalogue, convert

BOUNDARY_ITEMS = [
    ("edge-only", "All (edge only)", "Blender's 'All': boundary edges are sharp, corners follow them"),
    ("edge-and-corner", "Keep Corners", "Blender's 'Keep Corners': corners of one face stay"),
    ("none", "None", "faces at the boundary are left out (OpenSubdiv's 'none')"),
]
FVAR_ITEMS = [
    (v, label, f"OpenSubdiv's face-varying interpolation '{v}' (Blender's UV Smooth '{label}')")
    for v, label in (
        ("none", "All"),
        ("corners-only", "Keep Corners"),
        ("corners-plus1", "Keep Corners, Junctions"),
        ("corners-plus2", "Keep Corners, Junctions, Concave"),
        ("boundaries", "Keep Boundaries"),
        ("all", "None"),
    )
]
CREASE_ITEMS = [
    ("uniform", "Uniform", "sharpness decreases by 1 per level (Blender's rule)"),
    ("chaikin", "Chaikin", "OpenSubdiv's Chaikin rule for semi-sharp creases"),
]


#: The names of the recipe properties (filled by :func:`recipe_properties`).
PROPERTY_NAMES = []


def recipe_properties():
    """The properties of a recipe (for the operator and the scene's settings), the scheme
    menu and the schemes' options from the package's catalogue."""
    p = bpy.props
    d = build.RECIPE_KEYS
    props = {
        "scheme": p.EnumProperty(
            name="Scheme", description="The subdivision scheme", items=catalogue.scheme_items()
        ),
        "levels": p.IntProperty(
            name="Levels",
            description="Refinement steps; 0 writes the exact surface (rings, density)",
            default=d["levels"], min=0, soft_max=6, max=10,
        ),
        "rings": p.IntProperty(
            name="Rings", description="Rings per extraordinary element of the exact surface",
            default=d["rings"], min=1, soft_max=10, max=20,
        ),
        "density": p.IntProperty(
            name="Density", description="Samples per patch edge of the exact surface's tessellation",
            default=d["density"], min=1, soft_max=32, max=128,
        ),
        "fill": p.BoolProperty(
            name="Fill", description="Close the hole inside the last ring with the scheme's cap",
            default=d["fill"],
        ),
        "boundary": p.EnumProperty(name="Boundary", items=BOUNDARY_ITEMS, default=d["boundary"]),
        "crease_method": p.EnumProperty(
            name="Creases", items=CREASE_ITEMS, default=d["crease_method"]
        ),
        "fvar": p.EnumProperty(
            name="UV Smooth", description="How UVs are interpolated", items=FVAR_ITEMS,
            default=d["fvar"],
        ),
        "smooth_triangles": p.BoolProperty(
            name="Smooth Triangles", description="OpenSubdiv's smooth triangle rule (Catmull-Clark)",
            default=d["smooth_triangles"],
        ),
        "use_creases": p.BoolProperty(
            name="Use Creases", description="Map the mesh's edge and vertex creases to sharpness",
            default=d["use_creases"],
        ),
        "use_uv": p.BoolProperty(name="UVs", description="Carry the UV maps", default=d["use_uv"]),
        "limit": p.BoolProperty(
            name="Limit Surface", description="Move the refined points to their limit positions",
            default=d["limit"],
        ),
        "use_modifiers": p.BoolProperty(
            name="Use Modifiers", description="Subdivide the mesh with its modifiers applied",
            default=d["use_modifiers"],
        ),
    }
    for o in catalogue.generic_options():
        props[catalogue.prop_name(o["name"])] = catalogue.make_property(p, o)
    PROPERTY_NAMES[:] = list(props)
    return props


def recipe_of(props):
    """The recipe (a dict, see :mod:`build`) of an operator's or the scene's properties."""
    r = {k: getattr(props, k) for k in build.RECIPE_KEYS if k != "options"}
    opts = catalogue.option_keywords(props, r["scheme"])
    for o in catalogue.options(r["scheme"]):
        key = o["name"].replace("-", "_")
        if o["file"] and key in opts:
            opts[key] = bpy.path.abspath(opts[key])
    r["options"] = opts
    return r


def _place(context, src_ob, mesh, suffix):
    """A new object for ``mesh`` in the source's collections, at the source's transform,
    selected and active."""
    ob = bpy.data.objects.new(f"{src_ob.name} {suffix}", mesh)
    collections = list(src_ob.users_collection) or [context.collection]
    for c in collections:
        c.objects.link(ob)
    ob.matrix_world = src_ob.matrix_world.copy()
    for other in context.selected_objects:
        other.select_set(False)
    ob.select_set(True)
    context.view_layer.objects.active = ob
    return ob


def _refined_object(context, src_ob, src, recipe, r):
    """The Blender object of a refined net (see the module documentation)."""
    me = convert.build_mesh(
        bpy.data, f"{src_ob.data.name} {recipe['scheme']}", r["vertices"], r["sizes"], r["corners"],
        r["loose_edges"],
    )
    for name, (values, idx) in r["uv"].items():
        layer = me.uv_layers.new(name=name)
        layer.uv.foreach_set("vector", np.ascontiguousarray(values[idx], dtype=np.float32).ravel())
    if recipe["use_creases"] and catalogue.takes(recipe["scheme"], "creases"):
        _refined_creases(me, r)
    for m in src.materials:
        me.materials.append(m)
    if r["parent"] is not None:
        me.polygons.foreach_set("material_index", src.material_index[r["parent"]])
        me.polygons.foreach_set("use_smooth", ~src.sharp_face[r["parent"]])
    else:
        me.shade_smooth()
    me.update()
    return me


def _refined_creases(me, r):
    """The refined sharpness as ``crease_edge`` and ``crease_vert`` (boundary edges left at 0)."""
    edges, s = r["creases"]
    ne = len(me.edges)
    crease = np.zeros(ne, dtype=np.float32)
    if len(s):
        idx = convert.edge_index(me, edges)
        ok = idx >= 0
        crease[idx[ok]] = convert.sharpness_to_crease(s[ok])
        faces_of_edge = np.zeros(ne, dtype=np.int64)
        loop_edges = np.empty(len(me.loops), dtype=np.int32)
        me.loops.foreach_get("edge_index", loop_edges)
        faces_of_edge += np.bincount(loop_edges, minlength=ne)
        crease[faces_of_edge == 1] = 0.0
    if crease.any():
        convert.set_float_attribute(me, "crease_edge", "EDGE", crease)
    verts, vs = r["corners_sharp"]
    if len(vs):
        vc = np.zeros(len(me.vertices), dtype=np.float32)
        vc[verts] = convert.sharpness_to_crease(vs)
        convert.set_float_attribute(me, "crease_vert", "POINT", vc)


def exact_object_mesh(name, t, materials=()):
    """The Blender mesh of an exact surface's tessellation ``t`` (see the module
    documentation)."""
    tri = t["triangles"]
    me = convert.build_mesh(
        bpy.data, name, t["vertices"], np.full(len(tri), 3), tri.reshape(-1)
    )
    me.shade_smooth()
    convert.set_float_attribute(me, "fairsub_gauss", "POINT", t["gauss"])
    convert.set_float_attribute(me, "fairsub_mean", "POINT", t["mean"])
    patch = me.attributes.new("fairsub_patch", "INT", "FACE")
    patch.data.foreach_set("value", t["triangle_patch"].astype(np.int32))
    set_curvature_colours(me, t["mean"])
    me.normals_split_custom_set_from_vertices(np.ascontiguousarray(t["normals"], dtype=np.float32))
    for m in materials:
        me.materials.append(m)
    me.update()
    return me


def set_curvature_colours(me, values, range_=None):
    """The colour attribute ``fairsub_curvature``: ``values`` per vertex in fairsub's
    curvature colours (``fairsub.curvature_colours``); returns the range used."""
    colours, r = fairsub.curvature_colours(values, range_)
    rgba = np.ones((len(colours), 4), dtype=np.float32)
    rgba[:, :3] = colours
    attr = me.color_attributes.get("fairsub_curvature")
    if attr is None:
        attr = me.color_attributes.new("fairsub_curvature", "FLOAT_COLOR", "POINT")
    attr.data.foreach_set("color", rgba.reshape(-1))
    me.color_attributes.active_color = attr
    me.color_attributes.render_color_index = me.color_attributes.active_color_index
    return r


def report_notes(op, notes, shown=3):
    """fairsub's notes (fallbacks, derived rules) as warnings: the first few, then a count;
    all of them on the console."""
    for n in notes:
        print(f"fairsub: {n}")
    for n in notes[:shown]:
        op.report({"WARNING"}, n)
    if len(notes) > shown:
        op.report({"WARNING"}, f"... and {len(notes) - shown} more notes (see the console)")


class FAIRSUB_OT_subdivide(bpy.types.Operator):
    """Subdivide the active mesh with a fairsub scheme into a new object (the source is left
    as it was)"""

    bl_idname = "fairsub.subdivide"
    bl_label = "fairsub Subdivide"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        ob = context.active_object
        return ob is not None and ob.type == "MESH" and ob.mode == "OBJECT"

    def draw(self, context):
        draw_recipe(self.layout, self)

    def execute(self, context):
        src_ob = context.active_object
        recipe = recipe_of(self)
        try:
            src = build.SourceMesh(src_ob, recipe, context.evaluated_depsgraph_get())
            if recipe["levels"] > 0:
                r = build.refine(src, recipe)
                me = _refined_object(context, src_ob, src, recipe, r)
                notes = r["notes"]
                suffix = f"{recipe['scheme']} x{recipe['levels']}"
            else:
                s, t, notes = build.exact(src, recipe)
                me = exact_object_mesh(f"{src_ob.data.name} {recipe['scheme']}", t, src.materials)
                suffix = f"{recipe['scheme']} exact"
        except ValueError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        ob = _place(context, src_ob, me, suffix)
        ob["fairsub"] = json.dumps(dict(recipe, source=src_ob.name))
        report_notes(self, notes)
        self.report(
            {"INFO"}, f"{ob.name}: {len(me.vertices)} vertices, {len(me.polygons)} faces"
        )
        return {"FINISHED"}


def draw_recipe(layout, props):
    """The settings of a recipe, showing only what its scheme takes."""
    s = props.scheme
    row = catalogue.scheme(s)
    layout.prop(props, "scheme")
    layout.prop(props, "levels")
    if props.levels == 0:
        col = layout.column(align=True)
        col.prop(props, "rings")
        col.prop(props, "density")
        col.prop(props, "fill")
    elif not row["refine"]:
        layout.label(text=f"{s}: exact surface only (levels 0)", icon="INFO")
    for key, option in (
        ("boundary", "boundary"),
        ("crease_method", "crease-method"),
        ("smooth_triangles", "smooth-triangles"),
    ):
        if catalogue.takes(s, option):
            layout.prop(props, key)
    if catalogue.takes(s, "creases"):
        layout.prop(props, "use_creases")
    if catalogue.takes(s, "fvar") and props.levels > 0:
        layout.prop(props, "use_uv")
        layout.prop(props, "fvar")
    if props.levels > 0:
        layout.prop(props, "limit")
    layout.prop(props, "use_modifiers")
    for o in catalogue.options(s):
        if o["name"] not in catalogue.OWN:
            layout.prop(props, catalogue.prop_name(o["name"]))
