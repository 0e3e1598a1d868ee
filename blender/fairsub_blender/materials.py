"""The shape tools' materials, as shader node trees (Cycles and EEVEE):

- *highlight lines* (Beier and Chen 1994), defined as fairsub's renderer defines them
  (``render --mode highlight``, ``src/render/shade.rs``): a family of parallel light lines
  ``a + c e + t d`` in a plane between the viewer and the object (normal ``m = d x e`` toward
  the viewer, two bounding radii in front of the object's centre), ``d`` the viewer's right
  vector and ``e`` its up vector. The normal line ``p + s n`` of a surface point meets the light
  line with parameter ``c = (p - a) . (n x d) / (n . m)``; a dark band is drawn where
  ``frac(c / spacing) < width``. The lines are fixed in the world when the material is made
  (from the scene camera, else the 3D view, else the front view), like the light bars of a
  studio: a break in a line shows a discontinuity of the normal, a kink one of the curvature.
  Where the normal turns away from the plane (``|n . m|`` below 0.25) the bands fade out, as
  they crowd beyond what pixels can show (the renderer filters them instead). The spacing
  (twice the radius over 12 stripes, as the renderer starts from), width and plane point are
  nodes to edit.
- *curvature*: the colour attribute ``fairsub_curvature`` (fairsub's diverging colours), shown
  through an Attribute node."""

import bpy

HIGHLIGHT = "fairsub highlight lines"
CURVATURE = "fairsub curvature"
STRIPES = 12.0
WIDTH = 0.35


def _value(nodes, label, value, location):
    n = nodes.new("ShaderNodeValue")
    n.label = label
    n.outputs[0].default_value = value
    n.location = location
    return n


def _op(nodes, kind, operation, location):
    n = nodes.new(kind)
    n.operation = operation
    n.location = location
    return n


def _output(mat, colour_socket, x):
    """Colour -> half diffuse, half emission -> material output."""
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    diffuse = nodes.new("ShaderNodeBsdfDiffuse")
    emission = nodes.new("ShaderNodeEmission")
    mix = nodes.new("ShaderNodeMixShader")
    out = nodes.new("ShaderNodeOutputMaterial")
    diffuse.location, emission.location = (x, 120), (x, -60)
    mix.location, out.location = (x + 220, 40), (x + 420, 40)
    mix.inputs[0].default_value = 0.5
    links.new(colour_socket, diffuse.inputs["Color"])
    links.new(colour_socket, emission.inputs["Color"])
    links.new(diffuse.outputs[0], mix.inputs[1])
    links.new(emission.outputs[0], mix.inputs[2])
    links.new(mix.outputs[0], out.inputs["Surface"])


def _socket(sockets, identifier):
    """The socket with this identifier (the Mix node has an ``A`` per data type)."""
    return next(s for s in sockets if s.identifier == identifier)


def _new_material(name):
    mat = bpy.data.materials.get(name) or bpy.data.materials.new(name)
    mat.use_nodes = True
    mat.node_tree.nodes.clear()
    return mat


def highlight_material(centre, radius, toward, right, name=HIGHLIGHT):
    """The highlight-line material for an object of bounding-sphere ``centre`` (world) and
    ``radius``, seen from the unit direction ``toward`` (from the object to the viewer) with
    the unit ``right`` vector (see the module documentation); made anew each call."""
    import numpy as np

    m = np.asarray(toward, dtype=float)
    d = np.asarray(right, dtype=float)
    d = d - (d @ m) * m
    d /= np.linalg.norm(d)
    mat = _new_material(name)
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    geo = nodes.new("ShaderNodeNewGeometry")
    geo.location = (-1000, 0)
    spacing = _value(nodes, "spacing", 2.0 * radius / STRIPES, (-600, -300))
    width = _value(nodes, "width", WIDTH, (-200, -300))
    plane = nodes.new("ShaderNodeCombineXYZ")
    plane.label = "light plane point"
    plane.location = (-800, -250)
    for i, x in enumerate(np.asarray(centre) + 2.0 * radius * m):
        plane.inputs[i].default_value = float(x)
    pa = _op(nodes, "ShaderNodeVectorMath", "SUBTRACT", (-600, 0))
    links.new(geo.outputs["Position"], pa.inputs[0])
    links.new(plane.outputs[0], pa.inputs[1])
    nd = _op(nodes, "ShaderNodeVectorMath", "CROSS_PRODUCT", (-600, 200))
    links.new(geo.outputs["Normal"], nd.inputs[0])
    nd.inputs[1].default_value = tuple(d)  # d: the light lines' direction
    num = _op(nodes, "ShaderNodeVectorMath", "DOT_PRODUCT", (-400, 100))
    links.new(pa.outputs[0], num.inputs[0])
    links.new(nd.outputs[0], num.inputs[1])
    den = _op(nodes, "ShaderNodeVectorMath", "DOT_PRODUCT", (-400, -100))
    links.new(geo.outputs["Normal"], den.inputs[0])
    den.inputs[1].default_value = tuple(m)  # the light plane's normal, toward the viewer
    c = _op(nodes, "ShaderNodeMath", "DIVIDE", (-200, 100))
    links.new(num.outputs["Value"], c.inputs[0])
    links.new(den.outputs["Value"], c.inputs[1])
    t = _op(nodes, "ShaderNodeMath", "DIVIDE", (0, 100))
    links.new(c.outputs[0], t.inputs[0])
    links.new(spacing.outputs[0], t.inputs[1])
    frac = _op(nodes, "ShaderNodeMath", "FRACT", (200, 100))
    links.new(t.outputs[0], frac.inputs[0])
    dark = _op(nodes, "ShaderNodeMath", "LESS_THAN", (400, 100))
    links.new(frac.outputs[0], dark.inputs[0])
    links.new(width.outputs[0], dark.inputs[1])
    # fade where the normal turns away from the plane
    grazing = _op(nodes, "ShaderNodeMath", "ABSOLUTE", (-200, -100))
    links.new(den.outputs["Value"], grazing.inputs[0])
    fade = nodes.new("ShaderNodeMapRange")
    fade.location = (0, -100)
    fade.inputs["From Min"].default_value = 0.1
    fade.inputs["From Max"].default_value = 0.25
    links.new(grazing.outputs[0], fade.inputs["Value"])
    band = _op(nodes, "ShaderNodeMath", "MULTIPLY", (400, -50))
    links.new(dark.outputs[0], band.inputs[0])
    links.new(fade.outputs["Result"], band.inputs[1])
    mix = nodes.new("ShaderNodeMix")
    mix.data_type = "RGBA"
    mix.location = (600, 100)
    links.new(band.outputs[0], _socket(mix.inputs, "Factor_Float"))
    _socket(mix.inputs, "A_Color").default_value = (0.92, 0.92, 0.95, 1.0)
    _socket(mix.inputs, "B_Color").default_value = (0.06, 0.06, 0.09, 1.0)
    _output(mat, _socket(mix.outputs, "Result_Color"), 800)
    return mat


def curvature_material(name=CURVATURE):
    """The material that shows the colour attribute ``fairsub_curvature``."""
    mat = _new_material(name)
    attr = mat.node_tree.nodes.new("ShaderNodeAttribute")
    attr.attribute_type = "GEOMETRY"
    attr.attribute_name = "fairsub_curvature"
    attr.location = (-200, 0)
    _output(mat, attr.outputs["Color"], 0)
    return mat


def assign(ob, mat):
    """``mat`` as the object's only material (every face shows it)."""
    ob.data.materials.clear()
    ob.data.materials.append(mat)
    ob.data.polygons.foreach_set("material_index", [0] * len(ob.data.polygons))
