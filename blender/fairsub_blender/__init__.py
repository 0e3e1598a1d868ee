"""fairsub for Blender: subdivision surfaces of high shape quality on the active mesh.

``bpy.ops.fairsub.subdivide(scheme=..., levels=..., rings=..., boundary=...)`` refines the
active mesh with any fairsub scheme (``levels`` >= 1) or writes its exact surface (``levels=0``
with ``rings``, tessellated at ``density``), as a new object; Blender's edge and vertex creases
become OpenSubdiv sharpness as Blender's own Subdivision Surface modifier maps them, and the UV
maps are carried. The Shape panel measures the exact surface (area, volume, centroid), shows
highlight lines and curvature, renders fairsub's own pictures and exports IGES.

The add-on is built on the fairsub Python package's public functions only (``fairsub.Net``,
``schemes``, ``scheme_options``, ``subdivide``, ``surface``, ``render``,
``curvature_colours``); the package comes with the extension as a bundled wheel (see
``docs/guide/src/blender.md``), or from the Python environment when the add-on is imported as
the module ``fairsub_blender`` (headless, with Blender as a Python module).
"""

import atexit

import bpy

from . import ops_shape, ops_subdivide, panels

_classes = [
    ops_subdivide.FAIRSUB_OT_subdivide,
    ops_shape.FAIRSUB_OT_measure,
    ops_shape.FAIRSUB_OT_highlight_lines,
    ops_shape.FAIRSUB_OT_curvature,
    ops_shape.FAIRSUB_OT_render,
    ops_shape.FAIRSUB_OT_export,
    panels.FairsubSettings,
    panels.FAIRSUB_PT_subdivide,
    panels.FAIRSUB_PT_shape,
]


def _menu(self, context):
    self.layout.operator(ops_subdivide.FAIRSUB_OT_subdivide.bl_idname, icon="MOD_SUBSURF")


def register():
    """Registers the operators, the scene settings (``scene.fairsub``), the sidebar panels and
    an entry in the Object menu. The scheme menu and the schemes' options are read from the
    fairsub package here."""
    props = ops_subdivide.recipe_properties()
    ops_subdivide.FAIRSUB_OT_subdivide.__annotations__ = dict(props)
    panels.FairsubSettings.__annotations__ = dict(ops_subdivide.recipe_properties())
    for c in _classes:
        bpy.utils.register_class(c)
    bpy.types.Scene.fairsub = bpy.props.PointerProperty(type=panels.FairsubSettings)
    bpy.types.VIEW3D_MT_object.append(_menu)
    # Blender as a Python module (bpy 4.5) hangs at interpreter exit while classes are still
    # registered; Blender itself unregisters add-ons before it exits, which also drops this.
    atexit.register(unregister)


def unregister():
    """Undoes :func:`register`."""
    atexit.unregister(unregister)
    bpy.types.VIEW3D_MT_object.remove(_menu)
    del bpy.types.Scene.fairsub
    for c in reversed(_classes):
        bpy.utils.unregister_class(c)
