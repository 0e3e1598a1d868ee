"""The picture of the Blender guide page (docs/images/blender-suzanne.png), rendered headless
with Blender as a Python module and Cycles on the CPU: Suzanne's exact Catmull-Clark surface
(fairsub Subdivide, levels 0) twice, with fairsub's highlight lines (left) and its exact mean
curvature as colours over +-6 (right).

    python blender/examples/render_picture.py docs/images/blender-suzanne.png [--samples 32]
"""

import argparse
import math
import pathlib
import sys

import bpy

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1]))
import fairsub_blender  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("--samples", type=int, default=32)
    ap.add_argument("--size", default="720x336")
    a = ap.parse_args()
    w, h = (int(x) for x in a.size.split("x"))
    bpy.ops.wm.read_factory_settings(use_empty=True)
    fairsub_blender.register()
    try:
        scene = bpy.context.scene
        cam = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
        scene.collection.objects.link(cam)
        cam.location = (0, -8.0, 0.35)
        cam.rotation_euler = (math.radians(88), 0, 0)
        cam.data.lens = 50
        scene.camera = cam
        for x, tool in ((-1.5, "highlight"), (1.5, "mean")):
            bpy.ops.mesh.primitive_monkey_add(location=(x, 0, 0), rotation=(0, 0, math.radians(-20 if x < 0 else 20)))
            bpy.ops.fairsub.subdivide(scheme="catmull-clark", levels=0, rings=4, density=6)
            if tool == "highlight":
                bpy.ops.fairsub.highlight_lines(stripes=10)
            else:
                bpy.ops.fairsub.curvature(kind="mean", range=6.0)
        for ob in list(scene.objects):
            if ob.type == "MESH" and "fairsub" not in ob:
                bpy.data.objects.remove(ob)
        world = bpy.data.worlds.new("world")
        world.color = (0.9, 0.9, 0.9)
        scene.world = world
        scene.render.engine = "CYCLES"
        scene.cycles.device = "CPU"
        scene.cycles.samples = a.samples
        scene.cycles.use_denoising = True
        scene.render.resolution_x, scene.render.resolution_y = w, h
        scene.render.resolution_percentage = 100
        scene.render.image_settings.file_format = "PNG"
        scene.render.image_settings.color_mode = "RGB"
        scene.view_settings.view_transform = "Standard"
        scene.render.filepath = str(pathlib.Path(a.out).resolve())
        bpy.ops.render.render(write_still=True)
        print(scene.render.filepath)
    finally:
        fairsub_blender.unregister()


if __name__ == "__main__":
    main()
