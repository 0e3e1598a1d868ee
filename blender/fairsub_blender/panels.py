"""The sidebar tab "fairsub" of the 3D viewport: the Subdivide panel (the scene's settings,
``scene.fairsub``, and the button that runs ``fairsub.subdivide`` with them) and the Shape
panel (measure, highlight lines, curvature, fairsub's picture, export)."""

import json

import bpy

from . import ops_subdivide
from .ops_subdivide import draw_recipe


class FairsubSettings(bpy.types.PropertyGroup):
    """The Subdivide panel's settings (the operator's properties, kept with the scene); the
    annotations are filled from the catalogue when the add-on registers."""


class _Sidebar:
    """The 3D viewport's sidebar, tab fairsub."""

    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "fairsub"


class FAIRSUB_PT_subdivide(_Sidebar, bpy.types.Panel):
    bl_label = "Subdivide"
    bl_idname = "FAIRSUB_PT_subdivide"

    def draw(self, context):
        settings = context.scene.fairsub
        draw_recipe(self.layout, settings)
        op = self.layout.operator("fairsub.subdivide", icon="MOD_SUBSURF")
        for key in ops_subdivide.PROPERTY_NAMES:
            setattr(op, key, getattr(settings, key))


class FAIRSUB_PT_shape(_Sidebar, bpy.types.Panel):
    bl_label = "Shape"
    bl_idname = "FAIRSUB_PT_shape"

    def draw(self, context):
        layout = self.layout
        ob = context.active_object
        layout.operator("fairsub.highlight_lines", icon="LIGHT_AREA")
        row = layout.row(align=True)
        row.operator("fairsub.curvature", text="Mean").kind = "mean"
        row.operator("fairsub.curvature", text="Gauss").kind = "gauss"
        layout.operator("fairsub.measure", icon="DRIVER_DISTANCE")
        info = ob.get("fairsub_measure") if ob is not None else None
        if info:
            m = json.loads(info)
            box = layout.box()
            box.label(text=f"{m['scheme']}, {m['rings']} rings, {m['patches']} patches")
            box.label(text=f"Area: {m['area']:.9g}")
            if m["closed"]:
                c = m["centroid"]
                box.label(text=f"Volume: {m['volume']:.9g}")
                box.label(text=f"Centroid: {c[0]:.6g}, {c[1]:.6g}, {c[2]:.6g}")
            else:
                box.label(text="Open surface: no volume")
        layout.operator("fairsub.render", icon="IMAGE_DATA")
        layout.operator("fairsub.export", icon="EXPORT")
