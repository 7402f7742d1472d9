"""Object ray visibility and holdout through Blender (Cycles 3.4's rules): an object invisible to the camera still
casts its shadow, one invisible to shadows casts none, and a holdout (object or Holdout shader) punches alpha."""

import math

import bpy
import numpy as np

import scenes

N = 32   # pixels; the orthographic camera sees 8 m × 8 m of ground: 4 px per metre, x = 0 at column 16


def shadow_scene():
    """A white ground lit by a sun tilted 45° toward +X, seen from straight above (orthographic). A dark cube floats
    at z ∈ [1, 2] over the origin: its image covers x ∈ [−0.5, 0.5] (columns 14–17), its shadow lands at
    x ∈ [0.5, 2.5] (columns 18–25), apart from it."""
    scene = scenes.empty_scene(N, N)
    scene.candela.samples = 8
    scene.candela.max_bounces = 1
    scene.candela.pixel_filter = 'BOX'
    scene.candela.filter_width = 1.0
    ground = scenes.link(scene, bpy.data.objects.new("Ground", scenes.grid_mesh("Ground", 10.0)))
    ground.data.materials.append(scenes.diffuse_material("White", (0.8, 0.8, 0.8)))
    cube = scenes.link(scene, bpy.data.objects.new("Cube", scenes.cube_mesh("Cube", 0.5)))
    cube.location = (0.0, 0.0, 1.5)
    cube.data.materials.append(scenes.diffuse_material("Dark", (0.1, 0.1, 0.1)))
    sun = scenes.link(scene, bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", 'SUN')))
    sun.rotation_euler = (0.0, -math.pi / 4, 0.0)   # shines along (sin 45°, 0, −cos 45°)
    sun.data.energy = 3.0
    sun.data.angle = 0.0
    camera = scenes.add_camera(scene, location=(0.0, 0.0, 10.0), rotation=(0.0, 0.0, 0.0))
    camera.data.type = 'ORTHO'
    camera.data.ortho_scale = 8.0
    return scene, cube


CUBE = (slice(15, 17), slice(15, 17))      # rows, columns well inside the cube's image
SHADOW = (slice(14, 18), slice(20, 24))    # well inside its shadow (x ∈ [1, 2])
LIT = 0.8 * 3.0 * math.cos(math.pi / 4) / math.pi   # the sunlit white ground's radiance: 0.54


def render(scene, path):
    scene.render.image_settings.file_format = 'OPEN_EXR'
    bpy.ops.render.render()
    bpy.data.images["Render Result"].save_render(path)
    return scenes.read_image_pixels(path)


def lum(rgba, region):
    return float((rgba[..., :3] @ np.array([0.2126, 0.7152, 0.0722]))[region].mean())


def test_camera_invisible_object_still_casts_its_shadow(tmp_path):
    scene, cube = shadow_scene()
    normal = render(scene, str(tmp_path / "normal.exr"))
    # The direct sun is deterministic per sample; only the one indirect bounce is noisy (a few % of LIT), hence
    # the generous bounds below, which still separate shadow (≲ 0.1·LIT) from light (≈ LIT).
    assert lum(normal, SHADOW) < 0.2 * LIT and lum(normal, CUBE) < 0.3 * LIT
    cube.visible_camera = False
    hidden = render(scene, str(tmp_path / "hidden.exr"))
    assert abs(lum(hidden, CUBE) / LIT - 1.0) < 0.15, lum(hidden, CUBE)   # the camera sees the lit ground through it
    assert lum(hidden, SHADOW) < 0.2 * LIT, lum(hidden, SHADOW)          # and the shadow stays


def test_shadow_invisible_object_casts_no_shadow(tmp_path):
    scene, cube = shadow_scene()
    cube.visible_shadow = False
    rgba = render(scene, str(tmp_path / "noshadow.exr"))
    assert abs(lum(rgba, SHADOW) / LIT - 1.0) < 0.15, lum(rgba, SHADOW)   # lit like the open ground
    assert lum(rgba, CUBE) < 0.3 * LIT, lum(rgba, CUBE)                   # the dark cube is still seen


def test_holdout_object_and_holdout_shader_punch_alpha(tmp_path):
    scene, cube = shadow_scene()
    scene.render.film_transparent = True
    cube.is_holdout = True
    rgba = render(scene, str(tmp_path / "holdout.exr"))
    assert np.all(rgba[CUBE][..., 3] == 0.0) and np.all(rgba[CUBE][..., :3] == 0.0)
    assert np.all(rgba[SHADOW][..., 3] == 1.0)   # the ground is opaque
    cube.is_holdout = False
    # The Holdout shader mixed half-and-half with the dark diffuse: alpha 0.5 over the cube.
    mat = cube.data.materials[0]
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    holdout, mix = nodes.new("ShaderNodeHoldout"), nodes.new("ShaderNodeMixShader")
    mix.inputs["Fac"].default_value = 0.5
    links.new(nodes["Principled BSDF"].outputs["BSDF"], mix.inputs[1])
    links.new(holdout.outputs["Holdout"], mix.inputs[2])
    links.new(mix.outputs["Shader"], nodes["Material Output"].inputs["Surface"])
    rgba = render(scene, str(tmp_path / "holdout_shader.exr"))
    assert np.allclose(rgba[CUBE][..., 3], 0.5, atol=1e-6), rgba[CUBE][..., 3]
    # A varying Mix factor is evaluated per hit: Fac = clamp(x + 0.5) with x the cube's object coordinate (its
    # top face spans x ∈ [−0.5, 0.5]); a pixel covering x ∈ [a, a + 0.25] (box filter: samples stay inside it)
    # averages alpha = 1 − Fac to 1 − (a + 0.125 + 0.5): 0.625 over column 15 (x ∈ [−0.25, 0]), 0.375 over column
    # 16 (measured 0.620–0.630 and 0.369–0.381). Before, any varying holdout weight counted as a full holdout.
    coord, sep, add = nodes.new("ShaderNodeTexCoord"), nodes.new("ShaderNodeSeparateXYZ"), nodes.new("ShaderNodeMath")
    add.operation, add.use_clamp = 'ADD', True
    add.inputs[1].default_value = 0.5
    links.new(coord.outputs["Object"], sep.inputs["Vector"])
    links.new(sep.outputs["X"], add.inputs[0])
    links.new(add.outputs["Value"], mix.inputs["Fac"])
    rgba = render(scene, str(tmp_path / "holdout_textured.exr"))
    alpha = rgba[CUBE][..., 3]
    # The pixel mean is exact only in expectation: 8 samples of a linear ramp spanning 0.25 in Fac have a
    # standard deviation of at most 0.25/√12/√8 = 0.026 (independent samples; Sobol's are better); 5σ ≈ 0.13.
    assert np.allclose(alpha[:, 0], 0.625, atol=0.13) and np.allclose(alpha[:, 1], 0.375, atol=0.13), alpha


def test_export_writes_flags_and_pass_index():
    from candela import schema
    from candela.export import export_scene
    scene, cube = shadow_scene()
    cube.visible_glossy = False
    cube.is_holdout = True
    cube.pass_index = 4
    depsgraph = bpy.context.evaluated_depsgraph_get()
    arrays = export_scene(depsgraph, scene.camera)
    bits = schema.instance_flags()
    flags = {int(m): (int(f), int(i)) for m, f, i in zip(arrays["instance_mesh"], arrays["instance_flags"],
                                                          arrays["instance_pass_index"])}
    assert len(flags) == 2
    ground_flags, cube_flags = sorted(flags.values(), key=lambda v: v[1])
    everything = bits["CAMERA"] | bits["DIFFUSE"] | bits["GLOSSY"] | bits["TRANSMISSION"] | bits["SHADOW"]
    assert ground_flags == (everything, 0)
    assert cube_flags == ((everything & ~bits["GLOSSY"]) | bits["HOLDOUT"], 4)


def test_collection_holdout_marks_its_objects():
    from candela import schema
    from candela.export import export_scene
    scene, cube = shadow_scene()
    matte = bpy.data.collections.new("Matte")
    scene.collection.children.link(matte)
    scene.collection.objects.unlink(cube)
    matte.objects.link(cube)
    bpy.context.view_layer.layer_collection.children["Matte"].holdout = True
    arrays = export_scene(bpy.context.evaluated_depsgraph_get(), scene.camera)
    holdout = schema.instance_flags()["HOLDOUT"]
    assert sorted(bool(f & holdout) for f in arrays["instance_flags"]) == [False, True]
