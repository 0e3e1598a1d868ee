"""The sidebar panels' draw functions, run headless on a recording layout (Blender draws
panels only with a window): every property they show exists on what they show it from, the
Subdivide panel's button carries the scene's settings, and the Shape panel shows the measured
area, volume and centroid of the active result."""

import json

import pytest

from conftest import bpy, primitive
from fairsub_blender import panels


class Recorder:
    """A stand-in for ``UILayout`` that records what a panel draws."""

    def __init__(self, log):
        self.log = log

    def prop(self, data, key, **kw):
        assert hasattr(data, key), f"the panel shows '{key}', which {data!r} lacks"
        self.log.append(("prop", key))

    def label(self, text="", **kw):
        self.log.append(("label", text))

    def operator(self, idname, **kw):
        category, name = idname.split(".")
        assert name in dir(getattr(bpy.ops, category)), f"no operator {idname}"
        op = type("Properties", (), {})()
        self.log.append(("operator", idname, op))
        return op

    def row(self, **kw):
        return self

    column = box = row


def draw(panel):
    log = []
    panel.draw(type("Panel", (), {"layout": Recorder(log)})(), bpy.context)
    return log


@pytest.mark.parametrize("scheme", ["catmull-clark", "loop", "eg", "tps-adjustable"])
@pytest.mark.parametrize("levels", [0, 2])
def test_the_subdivide_panel_draws_its_settings(empty, scheme, levels):
    s = bpy.context.scene.fairsub
    s.scheme, s.levels, s.rings = scheme, levels, 3
    log = draw(panels.FAIRSUB_PT_subdivide)
    shown = [e[1] for e in log if e[0] == "prop"]
    assert shown[:2] == ["scheme", "levels"]
    assert ("rings" in shown) == (levels == 0)
    ops = [e for e in log if e[0] == "operator"]
    assert [e[1] for e in ops] == ["fairsub.subdivide"]
    button = ops[0][2]
    assert (button.scheme, button.levels, button.rings) == (scheme, levels, 3)


def test_the_shape_panel_shows_the_measured_surface(empty):
    primitive("cube")
    bpy.ops.fairsub.subdivide(scheme="catmull-clark", levels=0, rings=3, density=2)
    log = draw(panels.FAIRSUB_PT_shape)
    assert [e[1] for e in log if e[0] == "operator"] == [
        "fairsub.highlight_lines", "fairsub.curvature", "fairsub.curvature", "fairsub.measure",
        "fairsub.render", "fairsub.export",
    ]
    assert sorted(e[2].kind for e in log if e[0] == "operator" and e[1] == "fairsub.curvature") == [
        "gauss", "mean"
    ]
    assert not [e for e in log if e[0] == "label"]  # nothing measured yet
    assert bpy.ops.fairsub.measure() == {"FINISHED"}
    m = json.loads(bpy.context.active_object["fairsub_measure"])
    labels = [e[1] for e in draw(panels.FAIRSUB_PT_shape) if e[0] == "label"]
    c = m["centroid"]
    assert labels == [
        f"catmull-clark, 3 rings, {m['patches']} patches",
        f"Area: {m['area']:.9g}",
        f"Volume: {m['volume']:.9g}",
        f"Centroid: {c[0]:.6g}, {c[1]:.6g}, {c[2]:.6g}",
    ]
    # the cube's exact surface is symmetric about the origin, and smaller than the cube
    assert max(abs(x) for x in c) < 1e-9 and 0 < m["volume"] < 8
