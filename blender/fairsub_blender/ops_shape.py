"""The shape tools, on the active object (a fairsub result, whose recipe and source they read
from its ``fairsub`` property, or any mesh, with the scene's fairsub settings):

- ``fairsub.measure``: the exact surface's area, volume and centroid (:mod:`measure`), kept
  on the object (``fairsub_measure``) and shown in the Shape panel;
- ``fairsub.highlight_lines``: the highlight-line material (:mod:`materials`);
- ``fairsub.curvature``: the exact Gauss or mean curvature of an exact-surface result as the
  colour attribute ``fairsub_curvature``, and a material that shows it;
- ``fairsub.render``: fairsub's own picture of the exact surface (``fairsub.render``: exact
  normals and curvature per pixel) as an image, to compare with Blender's render;
- ``fairsub.export``: the exact surface as IGES (B-spline surfaces for CAD), BezierView
  (``.bv``) or a tessellated OBJ / PLY (``Surface.write``)."""

import json

import bpy
import fairsub
import numpy as np
from bpy_extras.io_utils import ExportHelper
from mathutils import Vector

from . import build, materials, measure
from .ops_subdivide import recipe_of, set_curvature_colours


def exact_surface(context, ob):
    """The exact surface of the active object: (surface, recipe, notes). A fairsub result is
    rebuilt from its source with its own recipe (rings; levels set to 0); another mesh under
    the scene's fairsub settings."""
    info = ob.get("fairsub") if ob is not None else None
    if info:
        recipe = json.loads(info)
        name = recipe.pop("source")
        src_ob = bpy.data.objects.get(name)
        if src_ob is None:
            raise ValueError(f"the source object '{name}' of {ob.name} no longer exists")
    else:
        recipe, src_ob = recipe_of(context.scene.fairsub), ob
    recipe["levels"] = 0
    src = build.SourceMesh(src_ob, recipe, context.evaluated_depsgraph_get())
    s, notes = build.surface(src, recipe)
    return s, recipe, notes


class _OnMesh:
    """The shape tools run on an active mesh object in Object Mode."""

    @classmethod
    def poll(cls, context):
        ob = context.active_object
        return ob is not None and ob.type == "MESH" and ob.mode == "OBJECT"


class FAIRSUB_OT_measure(_OnMesh, bpy.types.Operator):
    """Area, volume and centroid of the exact surface (of a fairsub result, or of the active
    mesh under the fairsub settings)"""

    bl_idname = "fairsub.measure"
    bl_label = "Measure Exact Surface"

    def execute(self, context):
        ob = context.active_object
        try:
            s, recipe, _ = exact_surface(context, ob)
        except ValueError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        m = measure.measure(s)
        m.update(scheme=recipe["scheme"], rings=recipe["rings"])
        ob["fairsub_measure"] = json.dumps(m)
        text = f"area {m['area']:.9g}"
        if m["closed"]:
            c = m["centroid"]
            text += f", volume {m['volume']:.9g}, centroid ({c[0]:.6g}, {c[1]:.6g}, {c[2]:.6g})"
        else:
            text += " (open surface: no volume)"
        self.report({"INFO"}, f"{ob.name}: {text} (object space)")
        return {"FINISHED"}


class FAIRSUB_OT_highlight_lines(_OnMesh, bpy.types.Operator):
    """Show highlight lines on the active object (a material of parallel light lines above
    it: a break shows a jump of the normal, a kink one of the curvature)"""

    bl_idname = "fairsub.highlight_lines"
    bl_label = "Highlight Lines"
    bl_options = {"REGISTER", "UNDO"}

    stripes: bpy.props.FloatProperty(
        name="Stripes", description="Light lines across the object", default=materials.STRIPES,
        min=1.0, soft_max=60.0,
    )

    def execute(self, context):
        ob = context.active_object
        corners = np.array([ob.matrix_world @ Vector(c) for c in ob.bound_box])
        lo, hi = corners.min(axis=0), corners.max(axis=0)
        centre, radius = (lo + hi) / 2, float(np.linalg.norm(hi - lo) / 2) or 1.0
        toward, right = _viewer(context, centre)
        mat = materials.highlight_material(
            centre, radius * materials.STRIPES / self.stripes, toward, right
        )
        materials.assign(ob, mat)
        return {"FINISHED"}


def _viewer(context, centre):
    """The unit direction from ``centre`` to the viewer and the viewer's right vector: the
    scene camera's, else the 3D view's, else Blender's front view (looking along +y)."""
    cam = context.scene.camera
    if cam is not None:
        rot = cam.matrix_world.to_3x3()
        toward = np.array(cam.matrix_world.translation) - centre
        n = np.linalg.norm(toward)
        if n > 0:
            return toward / n, np.array(rot.col[0])
    rv = getattr(context, "region_data", None)
    if rv is not None and hasattr(rv, "view_rotation"):
        rot = rv.view_rotation.to_matrix()
        return np.array(rot.col[2]), np.array(rot.col[0])
    return np.array([0.0, -1.0, 0.0]), np.array([1.0, 0.0, 0.0])


class FAIRSUB_OT_curvature(_OnMesh, bpy.types.Operator):
    """Colour an exact-surface result by its exact curvature (blue negative, white 0, red
    positive, as fairsub's renderer)"""

    bl_idname = "fairsub.curvature"
    bl_label = "Curvature Colours"
    bl_options = {"REGISTER", "UNDO"}

    kind: bpy.props.EnumProperty(
        name="Curvature",
        items=[("mean", "Mean", "mean curvature H"), ("gauss", "Gauss", "Gauss curvature K")],
    )
    range: bpy.props.FloatProperty(
        name="Range", description="Colour range +-range (0: the 98th percentile of |value|)",
        default=0.0, min=0.0,
    )

    def execute(self, context):
        ob = context.active_object
        attr = ob.data.attributes.get(f"fairsub_{self.kind}")
        if attr is None:
            self.report(
                {"ERROR"},
                f"{ob.name} has no exact curvature: make the exact surface (fairsub Subdivide "
                "with levels 0)",
            )
            return {"CANCELLED"}
        values = np.empty(len(attr.data), dtype=np.float32)
        attr.data.foreach_get("value", values)
        r = set_curvature_colours(ob.data, values.astype(np.float64), self.range or None)
        ob["fairsub_curvature"] = json.dumps({"kind": self.kind, "range": r})
        materials.assign(ob, materials.curvature_material())
        self.report({"INFO"}, f"{self.kind} curvature, range +-{r:g}")
        return {"FINISHED"}


RENDER_MODES = [
    (m, m.capitalize(), f"fairsub render --mode {m}")
    for m in ("highlight", "reflection", "isophote", "mean", "gauss", "shaded", "provenance")
]


class FAIRSUB_OT_render(_OnMesh, bpy.types.Operator):
    """fairsub's own picture of the exact surface (exact normals and curvature per pixel), as
    an image to compare with Blender's render"""

    bl_idname = "fairsub.render"
    bl_label = "fairsub Picture"

    mode: bpy.props.EnumProperty(name="Mode", items=RENDER_MODES)
    width: bpy.props.IntProperty(name="Width", default=640, min=16, max=4096)
    height: bpy.props.IntProperty(name="Height", default=480, min=16, max=4096)

    def execute(self, context):
        ob = context.active_object
        try:
            s, _, _ = exact_surface(context, ob)
            pixels = fairsub.render(s, self.mode, size=(self.width, self.height))
        except ValueError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        name = f"fairsub {ob.name} {self.mode}"
        img = bpy.data.images.get(name)
        if img is not None and tuple(img.size) != (self.width, self.height):
            bpy.data.images.remove(img)
            img = None
        img = img or bpy.data.images.new(name, self.width, self.height)
        rgba = np.ones((self.height, self.width, 4), dtype=np.float32)
        rgba[..., :3] = pixels[::-1] / 255.0  # Blender's rows run bottom to top
        img.pixels.foreach_set(rgba.reshape(-1))
        img.update()
        self.report({"INFO"}, f"image '{name}'")
        return {"FINISHED"}


class FAIRSUB_OT_export(_OnMesh, bpy.types.Operator, ExportHelper):
    """Write the exact surface: IGES (.igs, B-spline surfaces for CAD), BezierView (.bv), or a
    tessellated mesh (.obj, .ply)"""

    bl_idname = "fairsub.export"
    bl_label = "Export Exact Surface"

    filename_ext = ".igs"
    filter_glob: bpy.props.StringProperty(default="*.igs;*.iges;*.bv;*.obj;*.ply", options={"HIDDEN"})
    density: bpy.props.IntProperty(
        name="Density", description="Samples per patch edge of a tessellated mesh", default=8,
        min=1, max=128,
    )

    def execute(self, context):
        try:
            s, _, _ = exact_surface(context, context.active_object)
            s.write(self.filepath, tess=self.density)
        except ValueError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        self.report({"INFO"}, f"wrote {len(s)} patches to {self.filepath}")
        return {"FINISHED"}
