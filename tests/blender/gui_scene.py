"""The GUI tests' scene (run in `blender -b`, saved to the path after `--`): a grey floor, a red cube at the
origin, a small emissive marker, a sun, a camera, Candela as the engine with a quick viewport (16 samples, pixel
size 2). Saved with the factory UI, so the GUI opens it without a splash screen."""

import math
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import scenes  # noqa: E402

path = sys.argv[sys.argv.index("--") + 1]
scene = scenes.empty_scene(640, 360)
floor = scenes.link(scene, bpy.data.objects.new("Floor", scenes.grid_mesh("Floor", 6.0)))
floor.data.materials.append(scenes.diffuse_material("Grey", (0.6, 0.6, 0.6)))
cube = scenes.link(scene, bpy.data.objects.new("Cube", scenes.cube_mesh("Cube", 1.0)))
cube.location = (0.0, 0.0, 1.0)
cube.data.materials.append(scenes.diffuse_material("Red", (0.8, 0.05, 0.05)))
marker = scenes.link(scene, bpy.data.objects.new("Marker", scenes.cube_mesh("Marker", 0.15)))
marker.location = (2.5, -1.5, 0.4)
marker.data.materials.append(scenes.emission_material("Glow", (1.0, 1.0, 1.0), 40.0))
sun = scenes.link(scene, bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", 'SUN')))
sun.rotation_euler = (math.radians(40), math.radians(10), math.radians(30))
sun.data.energy = 3.0
world = bpy.data.worlds.new("World")
world.color = (0.05, 0.05, 0.05)
scene.world = world
scenes.add_camera(scene, location=(7.0, -7.0, 5.0), rotation=(math.radians(63), 0.0, math.radians(45)))
scene.candela.viewport_samples = 16
scene.render.preview_pixel_size = '2'
bpy.ops.wm.save_as_mainfile(filepath=path)
