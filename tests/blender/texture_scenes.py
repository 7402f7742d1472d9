"""Scenes for the texture and environment tests (and for the parity suite): a textured plane under a sun and a
sphere lit by an HDR environment, built by script, plus rendering one scene with Cycles or Candela alike.

    scene = textured_plane_scene(tmp_dir)            # Image Texture (8-bit sRGB PNG) → Diffuse colour, sun
    scene = environment_scene(tmp_dir)               # equirectangular float EXR world, diffuse sphere
    pixels = render(scene, "CYCLES", samples, path)  # (H, W, 4) float32, linear
"""

import os

import bpy
import numpy as np

import scenes


def save_image(path, rgb, float_buffer=False, colorspace=None):
    """Writes an (H, W, 3) array (row 0 = bottom) to `path` (PNG 8-bit, or OpenEXR float) and loads it back."""
    h, w, _ = rgb.shape
    img = bpy.data.images.new(os.path.basename(path), w, h, alpha=False, float_buffer=float_buffer)
    px = np.ones((h, w, 4), np.float32)
    px[..., :3] = rgb
    img.pixels.foreach_set(px.ravel())
    if float_buffer:   # Image.save() would write display-encoded values into the EXR; save_render keeps them linear
        settings = bpy.context.scene.render.image_settings
        previous = settings.file_format
        settings.file_format = 'OPEN_EXR'
        img.save_render(path, scene=bpy.context.scene)
        settings.file_format = previous
    else:
        img.filepath_raw = path
        img.file_format = 'PNG'
        img.save()
    bpy.data.images.remove(img)
    loaded = bpy.data.images.load(path, check_existing=False)
    if colorspace is not None:
        loaded.colorspace_settings.name = colorspace
    return loaded


def checker(n=8, a=(0.9, 0.6, 0.2), b=(0.1, 0.2, 0.5)):
    """An n×n checker of two colours (8-bit sRGB-encoded values), bottom-left texel `b`."""
    y, x = np.mgrid[0:n, 0:n]
    odd = ((x + y) % 2 == 1)[..., None]
    return np.where(odd, np.array(a, np.float32), np.array(b, np.float32)).astype(np.float32)


def _diffuse_textured(name, image, interpolation='Closest'):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    nodes.remove(nodes["Principled BSDF"])
    diffuse = nodes.new("ShaderNodeBsdfDiffuse")
    tex = nodes.new("ShaderNodeTexImage")
    tex.image, tex.interpolation = image, interpolation
    links.new(tex.outputs["Color"], diffuse.inputs["Color"])
    links.new(diffuse.outputs["BSDF"], nodes["Material Output"].inputs["Surface"])
    return mat, tex


def textured_plane_scene(directory, width=48, height=48, image=None):
    """A 4 × 4 m plane (UVs 0..1) seen from 4 m above, its Diffuse colour from an 8×8 checker image (or
    `image()`, called after the scene reset), lit by a 3 W/m² sun straight down: direct light only, so every
    pixel is albedo·3/π."""
    scene = scenes.empty_scene(width, height)
    scenes.add_camera(scene, location=(0.0, 0.0, 4.0), rotation=(0.0, 0.0, 0.0))
    scene.camera.data.lens = 50.0 * 1.3   # the plane fills the frame
    plane = scenes.link(scene, bpy.data.objects.new("Plane", scenes.grid_mesh("Plane", 2.0)))
    layer = plane.data.uv_layers.new(name="UVMap")
    layer.data.foreach_set("uv", np.array([(0, 0), (1, 0), (1, 1), (0, 1)], np.float32).ravel())
    image = image() if image is not None else save_image(os.path.join(directory, "checker.png"), checker())
    mat, _ = _diffuse_textured("Checker", image)
    plane.data.materials.append(mat)
    sun = scenes.link(scene, bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", 'SUN')))
    sun.data.energy, sun.data.angle = 3.0, 0.0
    scene.world = None
    return scene


def sky_image(w=64, h=32):
    """A float environment: a bright warm sun patch, a blue gradient sky whose red varies around the horizon (so
    that a mirrored or shifted u shows), and a dark ground (row 0 = down)."""
    v = (np.arange(h) + 0.5) / h
    u = (np.arange(w) + 0.5) / w
    sky = np.zeros((h, w, 3), np.float32)
    sky[...] = np.stack([0.2 + 0.5 * v, 0.3 + 0.6 * v, 0.6 + 0.8 * v], axis=-1)[:, None, :]
    sky[..., 0] *= (0.3 + 1.4 * u)[None, :]
    sky[: h // 2] *= 0.1
    sky[h * 3 // 4: h * 3 // 4 + 2, w * 5 // 8: w * 5 // 8 + 2] = (40.0, 35.0, 25.0)
    return sky


def environment_scene(directory, width=48, height=32, strength=1.5, rotation=None):
    """A diffuse sphere (albedo 0.7) on no ground, lit by an equirectangular float EXR world of strength 1.5,
    seen together with the background. With `rotation` (radians about Z) the world's Generated coordinates go
    through a Mapping node first, the usual way to turn an HDRI."""
    scene = scenes.empty_scene(width, height)
    scenes.add_camera(scene, location=(0.0, -5.0, 0.0), rotation=(np.pi / 2, 0.0, 0.0))
    bpy.ops.mesh.primitive_uv_sphere_add(segments=64, ring_count=32, radius=1.0)
    sphere = bpy.context.active_object
    bpy.ops.object.shade_smooth()
    sphere.data.materials.append(scenes.diffuse_material("Grey", (0.7, 0.7, 0.7)))
    mat = sphere.data.materials[0]
    bsdf = mat.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Specular"].default_value = 0.0
    bsdf.inputs["Roughness"].default_value = 1.0
    world = bpy.data.worlds.new("Sky")
    scene.world = world
    world.use_nodes = True
    nodes, links = world.node_tree.nodes, world.node_tree.links
    env = nodes.new("ShaderNodeTexEnvironment")
    env.image = save_image(os.path.join(directory, "sky.exr"), sky_image(), float_buffer=True)
    links.new(env.outputs["Color"], nodes["Background"].inputs["Color"])
    nodes["Background"].inputs["Strength"].default_value = strength
    if rotation is not None:
        mapping = nodes.new("ShaderNodeMapping")
        mapping.inputs["Rotation"].default_value = (0.0, 0.0, rotation)
        links.new(nodes.new("ShaderNodeTexCoord").outputs["Generated"], mapping.inputs["Vector"])
        links.new(mapping.outputs["Vector"], env.inputs["Vector"])
    return scene


def render(scene, engine, samples, path, max_bounces=4, read=True):
    """Renders `scene` with `engine` (CYCLES: CPU, no denoising, no adaptive sampling, no clamping, box filter;
    CANDELA: box filter) to an EXR at `path`; returns its (H, W, 4) linear pixels (None with read=False: a stereo
    render writes path_L.exr and path_R.exr instead)."""
    scene.render.engine = engine
    scene.render.image_settings.file_format = 'OPEN_EXR'
    scene.render.image_settings.color_depth = '32'   # full floats: half floats would round the comparisons
    scene.render.filepath = path
    if engine == 'CYCLES':
        c = scene.cycles
        c.device, c.samples, c.use_denoising, c.use_adaptive_sampling = 'CPU', samples, False, False
        c.sample_clamp_direct = c.sample_clamp_indirect = 0.0
        c.pixel_filter_type, c.filter_width = 'BOX', 1.0
        c.max_bounces = c.diffuse_bounces = c.glossy_bounces = c.transmission_bounces = max_bounces
        c.seed = 1
    else:
        c = scene.candela
        c.samples, c.pixel_filter, c.filter_width, c.max_bounces = samples, 'BOX', 1.0, max_bounces
    bpy.ops.render.render(write_still=True)
    return scenes.read_image_pixels(path) if read else None


# ---- node semantics: an emission plane whose colour is a node chain over its UVs -------------------------------

MATH_OPS = ("ADD", "SUBTRACT", "MULTIPLY", "DIVIDE", "MULTIPLY_ADD", "POWER", "LOGARITHM", "SQRT", "INVERSE_SQRT",
            "ABSOLUTE", "EXPONENT", "MINIMUM", "MAXIMUM", "LESS_THAN", "GREATER_THAN", "SIGN", "COMPARE",
            "SMOOTH_MIN", "SMOOTH_MAX", "ROUND", "FLOOR", "CEIL", "TRUNC", "FRACT", "MODULO", "WRAP", "SNAP",
            "PINGPONG", "SINE", "COSINE", "TANGENT", "ARCSINE", "ARCCOSINE", "ARCTANGENT", "ARCTAN2", "SINH", "COSH",
            "TANH", "RADIANS", "DEGREES")
MIX_BLENDS = ("MIX", "DARKEN", "MULTIPLY", "BURN", "LIGHTEN", "SCREEN", "DODGE", "ADD", "OVERLAY", "SOFT_LIGHT",
              "LINEAR_LIGHT", "DIFFERENCE", "SUBTRACT", "DIVIDE", "HUE", "SATURATION", "VALUE", "COLOR")


def node_scene(kind, size=32):
    """An orthographic view of a plane filling the frame whose Emission colour is `kind` applied to its UVs:
    "math_OP" (Math node on 4u − 2 and v, then Absolute), "mix_BLEND" (colour Mix of (u, v, 0.4) and a constant
    by factor v), "ramp" (an eased ColorRamp of u), "hsv" (Combine HSV → Separate HSL → Combine RGB), "misc"
    (Mapping → Gamma → Bright/Contrast → Invert)."""
    scene = scenes.empty_scene(size, size)
    scenes.add_camera(scene, location=(0.0, 0.0, 4.0), rotation=(0.0, 0.0, 0.0))
    scene.camera.data.type, scene.camera.data.ortho_scale = 'ORTHO', 4.0
    plane = scenes.link(scene, bpy.data.objects.new("Plane", scenes.grid_mesh("Plane", 2.0)))
    layer = plane.data.uv_layers.new(name="UVMap")
    layer.data.foreach_set("uv", np.array([(0, 0), (1, 0), (1, 1), (0, 1)], np.float32).ravel())
    mat = bpy.data.materials.new("Nodes")
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    nodes.remove(nodes["Principled BSDF"])
    emission = nodes.new("ShaderNodeEmission")
    links.new(emission.outputs[0], nodes["Material Output"].inputs["Surface"])
    separate = nodes.new("ShaderNodeSeparateXYZ")
    links.new(nodes.new("ShaderNodeTexCoord").outputs["UV"], separate.inputs[0])
    u, v = separate.outputs[0], separate.outputs[1]

    def uv_color(z):
        combine = nodes.new("ShaderNodeCombineXYZ")
        links.new(u, combine.inputs[0])
        links.new(v, combine.inputs[1])
        combine.inputs[2].default_value = z
        return combine.outputs[0]

    if kind.startswith("math_"):
        scale = nodes.new("ShaderNodeMath")
        scale.operation = 'MULTIPLY_ADD'
        links.new(u, scale.inputs[0])
        scale.inputs[1].default_value, scale.inputs[2].default_value = 4.0, -2.0
        node = nodes.new("ShaderNodeMath")
        node.operation = kind[5:]
        links.new(scale.outputs[0], node.inputs[0])
        links.new(v, node.inputs[1])
        node.inputs[2].default_value = 0.3
        absolute = nodes.new("ShaderNodeMath")
        absolute.operation = 'ABSOLUTE'
        links.new(node.outputs[0], absolute.inputs[0])
        out = absolute.outputs[0]
    elif kind.startswith("mix_"):
        node = nodes.new("ShaderNodeMix")
        node.data_type, node.blend_type = 'RGBA', kind[4:]
        sockets = {s.identifier: s for s in node.inputs}
        links.new(uv_color(0.4), sockets["A_Color"])
        sockets["B_Color"].default_value = (0.8, 0.3, 0.6, 1.0)
        links.new(v, sockets["Factor_Float"])
        out = {s.identifier: s for s in node.outputs}["Result_Color"]
    elif kind == "ramp":
        node = nodes.new("ShaderNodeValToRGB")
        links.new(u, node.inputs[0])
        node.color_ramp.elements[0].color = (0.1, 0.8, 0.2, 1.0)
        node.color_ramp.elements.new(0.4).color = (0.9, 0.1, 0.3, 1.0)
        node.color_ramp.interpolation = 'EASE'
        out = node.outputs[0]
    elif kind == "hsv":
        hsv = nodes.new("ShaderNodeCombineColor")
        hsv.mode = 'HSV'
        links.new(u, hsv.inputs[0])
        links.new(v, hsv.inputs[1])
        hsv.inputs[2].default_value = 0.8
        hsl = nodes.new("ShaderNodeSeparateColor")
        hsl.mode = 'HSL'
        links.new(hsv.outputs[0], hsl.inputs[0])
        rgb = nodes.new("ShaderNodeCombineColor")
        links.new(hsl.outputs[0], rgb.inputs[1])
        links.new(hsl.outputs[2], rgb.inputs[0])
        links.new(hsv.outputs[0], rgb.inputs[2])
        out = rgb.outputs[0]
    elif kind == "misc":
        mapping = nodes.new("ShaderNodeMapping")
        mapping.inputs["Rotation"].default_value = (0.0, 0.0, 0.5)
        mapping.inputs["Scale"].default_value = (2.0, 1.0, 1.0)
        mapping.inputs["Location"].default_value = (0.1, 0.2, 0.0)
        links.new(uv_color(0.5), mapping.inputs[0])
        gamma = nodes.new("ShaderNodeGamma")
        gamma.inputs[1].default_value = 2.2
        links.new(mapping.outputs[0], gamma.inputs[0])
        bc = nodes.new("ShaderNodeBrightContrast")
        bc.inputs[1].default_value, bc.inputs[2].default_value = 0.1, 0.3
        links.new(gamma.outputs[0], bc.inputs[0])
        invert = nodes.new("ShaderNodeInvert")
        invert.inputs[0].default_value = 0.3
        links.new(bc.outputs[0], invert.inputs[1])
        out = invert.outputs[0]
    else:
        raise ValueError(kind)
    links.new(out, emission.inputs["Color"])
    plane.data.materials.append(mat)
    scene.world = None
    return scene
