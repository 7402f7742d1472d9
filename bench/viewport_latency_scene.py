"""Builds one scene of the viewport latency benchmark in `blender -b` and saves it (args after `--`: NAME PATH).

NAME: an example scene (examples/scenes.py: cornell_box, soft_shadow, veach_mis, glossy, many_lights) or
"million": a smooth 1,000,000-triangle wavy grid under a sun, with a small cube on it. Rendered at 640 pixels wide
with 16 samples by both engines (F12), the viewports at 64 samples, start resolution 64, pixel size 1."""

import math
import os
import sys

import bpy

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPO, "examples"))
sys.path.insert(0, os.path.join(REPO, "bench"))

name, path = sys.argv[sys.argv.index("--") + 1:][:2]
bpy.ops.wm.read_homefile(use_empty=True)
scene = bpy.context.scene
if name == "million":
    import cornell_box as cb
    import export_bench
    import scenes
    grid = bpy.data.objects.new("Grid", export_bench.grid_mesh(1_000_000))
    scene.collection.objects.link(grid)
    grid.data.materials.append(scenes.diffuse("Ground", (0.6, 0.6, 0.55)))
    cube = scenes.cube(scene, "Box", scenes.diffuse("Red", (0.8, 0.1, 0.1)), None)
    cube.location = (0.0, 0.0, 1.0)
    scenes.camera(scene, (0.0, -16.0, 8.0), (65.0, 0.0, 0.0))
    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
    sun.rotation_euler = (math.radians(35), 0.0, math.radians(20))
    sun.data.energy = 3.0
    scene.collection.objects.link(sun)
    scenes.world(scene, (0.4, 0.5, 0.7), 0.3)
    cb.configure_render(scene, size=640)
    scene.render.resolution_y = 360
    cb.configure_cycles(scene, samples=16)
    cb.configure_candela(scene, samples=16)
else:
    import scenes
    scenes.build(name, scene, size=640, samples=16)
scene.render.preview_pixel_size = '1'
scene.candela.viewport_samples = 64
scene.candela.viewport_start_resolution = 64
scene.cycles.preview_samples = 64
scene.cycles.preview_start_resolution = 64
scene.cycles.use_preview_denoising = False
scene.cycles.use_preview_adaptive_sampling = False
bpy.ops.wm.save_as_mainfile(filepath=path)
