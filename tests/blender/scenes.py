"""Helpers for the in-Blender tests: reset to an empty scene with Candela enabled, and tiny test scenes."""

import os

import addon_utils
import bpy
import numpy as np

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def engine_available(engine_id="CANDELA"):
    """Whether `engine_id` is in the (dynamic) render engine enum: RNA's static enum_items do not list add-ons."""
    render = bpy.context.scene.render
    previous = render.engine
    try:
        render.engine = engine_id
    except TypeError:   # "enum 'CANDELA' not found in (...)"
        return False
    render.engine = previous
    return True


def ensure_addon():
    if not engine_available():
        addon_utils.enable("candela", default_set=True)
    assert engine_available(), "the candela add-on could not be enabled"


def empty_scene(width=32, height=24):
    """A fresh empty file; the scene renders with Candela at width x height, 100 %."""
    bpy.ops.wm.read_homefile(use_empty=True)
    ensure_addon()
    scene = bpy.context.scene
    scene.render.engine = 'CANDELA'
    scene.render.resolution_x, scene.render.resolution_y = width, height
    scene.render.resolution_percentage = 100
    return scene


def link(scene, ob):
    scene.collection.objects.link(ob)
    return ob


def add_camera(scene, location=(0.0, -6.0, 2.0), rotation=(1.35, 0.0, 0.0)):
    cam = link(scene, bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera")))
    cam.location, cam.rotation_euler = location, rotation
    scene.camera = cam
    return cam


def grid_mesh(name, size=1.0):
    """A square of side 2*size in the XY plane (2 triangles)."""
    me = bpy.data.meshes.new(name)
    s = size
    me.from_pydata([(-s, -s, 0), (s, -s, 0), (s, s, 0), (-s, s, 0)], [], [(0, 1, 2, 3)])
    me.update()
    return me


def cube_mesh(name, size=0.5):
    me = bpy.data.meshes.new(name)
    s = size
    verts = [(x, y, z) for x in (-s, s) for y in (-s, s) for z in (-s, s)]
    faces = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    me.from_pydata(verts, [], faces)
    me.update()
    return me


def diffuse_material(name, color):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    bsdf = mat.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (*color, 1.0)
    return mat


def lambert_material(name, color):
    """A Diffuse BSDF (roughness 0: Lambert), whose albedo is exactly its colour: what the irradiance cache serves
    (it leaves Principled's diffuse, which is not Lambertian, to path tracing: docs/irradiance_cache.md)."""
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    nodes.remove(nodes["Principled BSDF"])
    diffuse = nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = (*color, 1.0)
    diffuse.inputs["Roughness"].default_value = 0.0
    links.new(diffuse.outputs["BSDF"], nodes["Material Output"].inputs["Surface"])
    return mat


def emission_material(name, color, strength):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    nodes.remove(nodes["Principled BSDF"])
    emission = nodes.new("ShaderNodeEmission")
    emission.inputs["Color"].default_value = (*color, 1.0)
    emission.inputs["Strength"].default_value = strength
    links.new(emission.outputs["Emission"], nodes["Material Output"].inputs["Surface"])
    return mat


def tiny_scene(width=32, height=24, samples=8, with_camera=True):
    """Ground plane + point light + emissive cube, seen by a camera: lit everywhere it matters."""
    scene = empty_scene(width, height)
    scene.candela.samples = samples
    plane = link(scene, bpy.data.objects.new("Plane", grid_mesh("Plane", 5.0)))
    plane.data.materials.append(diffuse_material("Grey", (0.8, 0.8, 0.8)))
    cube = link(scene, bpy.data.objects.new("Cube", cube_mesh("Cube")))
    cube.location = (0.0, 0.0, 0.5)
    cube.data.materials.append(emission_material("Glow", (1.0, 0.5, 0.2), 5.0))
    light = link(scene, bpy.data.objects.new("Point", bpy.data.lights.new("Point", 'POINT')))
    light.location = (1.0, -1.0, 3.0)
    light.data.energy = 500.0
    if with_camera:
        add_camera(scene)
    return scene


def read_image_pixels(path):
    """(H, W, 4) float32 pixels of an image file, via Blender's image loader."""
    image = bpy.data.images.load(path, check_existing=False)
    try:
        w, h = image.size
        pixels = np.empty(w * h * 4, np.float32)
        image.pixels.foreach_get(pixels)
        return pixels.reshape(h, w, 4)
    finally:
        bpy.data.images.remove(image)
