"""Material inputs and the environment through the add-on: Image Texture (sRGB and Non-Color, missing files),
Normal Map, unsupported input nodes, an Environment Texture world, and brightness against Cycles 3.4."""

import math

import bpy
import mathutils
import numpy as np
import pytest

import scenes
import texture_scenes as ts
from candela import schema
from candela.export import Warnings, export_scene

SUN = 3.0   # W/m², straight down: a diffuse texel of albedo ρ shows ρ·3/π


def export(scene):
    warnings = Warnings()
    arrays = export_scene(bpy.context.evaluated_depsgraph_get(), scene.camera, warnings=warnings)
    return arrays, warnings.messages


def srgb_decode(c):
    c = np.asarray(c, np.float64)
    return np.where(c < 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def texel_of_pixels(scene, n=8):
    """For the textured plane seen from above: each pixel centre's checker texel (ix, iy) and whether the pixel's
    whole footprint lies inside that texel."""
    w, h = scene.render.resolution_x, scene.render.resolution_y
    half = 4.0 * 18.0 / scene.camera.data.lens          # half the view width at the plane (sensor 36 mm, AUTO fit)
    px = (np.arange(w) + 0.5) / w * 2 * half - half     # world x of pixel centres (image x → +X)
    py = (np.arange(h) + 0.5) / h * 2 * half - half     # world y (row 0 = bottom → −Y)
    u, v = (px + 2.0) / 4.0 * n, (py + 2.0) / 4.0 * n    # texel coordinates: the plane spans [−2, 2]² with UV 0..1
    margin = half / w * n / 4.0 * 1.01                  # half a pixel in texel units
    inside_x = np.abs(u - np.round(u)) > margin
    inside_y = np.abs(v - np.round(v)) > margin
    ix, iy = np.floor(u).astype(int), np.floor(v).astype(int)
    return ix[None, :], iy[:, None], inside_y[:, None] & inside_x[None, :]


def expected_plane(scene, texels, decode):
    ix, iy, inside = texel_of_pixels(scene)
    albedo = texels[iy, ix]                              # (H, W, 3)
    return (srgb_decode(albedo) if decode else albedo) * SUN / math.pi, inside


def test_supported_node_lists_name_real_node_types():
    from candela.export.materials import SUPPORTED_SHADER_NODES
    from candela.export.shader_nodes import SUPPORTED_INPUT_NODES
    assert "ShaderNodeTexImage" in SUPPORTED_INPUT_NODES and "ShaderNodeNormalMap" in SUPPORTED_INPUT_NODES
    for name in SUPPORTED_SHADER_NODES + SUPPORTED_INPUT_NODES:
        assert hasattr(bpy.types, name), name


def test_textured_plane_exports_an_image_program(tmp_path):
    scene = ts.textured_plane_scene(str(tmp_path))
    a, warnings = export(scene)
    assert warnings == []
    assert a["uvs"].shape == (2, 3, 2) and a["uvs"].min() == 0.0 and a["uvs"].max() == 1.0
    assert a["texture_info"].tolist() == [[0, 8, 8, schema.shader_enum("tex_color_spaces")["SRGB"],
                                           schema.shader_enum("tex_storages")["BYTE"]]]
    assert a["textures_u8"].shape == (64, 4) and "textures" not in a   # 8-bit texels stay 8-bit
    assert np.array_equal(a["textures_u8"][:, :3].reshape(8, 8, 3), np.rint(ts.checker() * 255).astype(np.uint8))
    cols = schema.closure_columns()
    targets = schema.shader_enum("input_targets")
    binding = a["input_bindings"][0]
    assert binding[0] == targets["CLOSURE"] and binding[2] == cols.index("color_r") and binding[3] == 3
    assert "tangents" not in a   # no normal map: no tangents exported


def test_textured_plane_renders_the_texture(tmp_path):
    """Direct sunlight on a diffuse plane: each pixel inside a texel is exactly that texel's decoded albedo·3/π."""
    scene = ts.textured_plane_scene(str(tmp_path))
    scene.candela.max_bounces = 0
    pixels = ts.render(scene, 'CANDELA', 4, str(tmp_path / "plane.exr"), max_bounces=0)
    stored = np.round(ts.checker() * 255.0) / 255.0      # what the 8-bit PNG holds
    want, inside = expected_plane(scene, stored, decode=True)
    got = pixels[..., :3]
    assert inside.sum() > 0.5 * inside.size
    # A delta sun and a constant albedo per texel: no noise at all inside a texel; float rounding only.
    assert np.allclose(got[inside], want[inside], rtol=1e-4, atol=1e-6)


def test_non_color_images_are_not_decoded(tmp_path):
    scene = ts.textured_plane_scene(
        str(tmp_path), image=lambda: ts.save_image(str(tmp_path / "data.png"), ts.checker(), colorspace='Non-Color'))
    a, _ = export(scene)
    assert a["texture_info"][0, 3] == schema.shader_enum("tex_color_spaces")["LINEAR"]
    pixels = ts.render(scene, 'CANDELA', 4, str(tmp_path / "plane.exr"), max_bounces=0)
    stored = np.round(ts.checker() * 255.0) / 255.0
    want, inside = expected_plane(scene, stored, decode=False)
    assert np.allclose(pixels[..., :3][inside], want[inside], rtol=1e-4, atol=1e-6)


def test_node_groups_reroutes_and_muted_nodes_are_followed(tmp_path):
    """The checker image inside a node group, through a reroute and a muted Invert node, renders as without."""
    reference = ts.render(ts.textured_plane_scene(str(tmp_path)), 'CANDELA', 4, str(tmp_path / "ref.exr"), 0)
    scene = ts.textured_plane_scene(str(tmp_path))
    mat = bpy.data.materials["Checker"]
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    tex = nodes["Image Texture"]
    group = bpy.data.node_groups.new("Wrap", 'ShaderNodeTree')
    group.inputs.new('NodeSocketColor', "Tint")
    group.outputs.new('NodeSocketColor', "Color")
    g_in, g_out = group.nodes.new("NodeGroupInput"), group.nodes.new("NodeGroupOutput")
    multiply = group.nodes.new("ShaderNodeMixRGB")
    multiply.blend_type, multiply.inputs["Fac"].default_value = 'MULTIPLY', 1.0
    group.links.new(g_in.outputs["Tint"], multiply.inputs["Color1"])
    multiply.inputs["Color2"].default_value = (1.0, 1.0, 1.0, 1.0)
    group.links.new(multiply.outputs["Color"], g_out.inputs["Color"])
    wrapper = nodes.new("ShaderNodeGroup")
    wrapper.node_tree = group
    reroute = nodes.new("NodeReroute")
    muted = nodes.new("ShaderNodeInvert")
    muted.mute = True
    links.new(tex.outputs["Color"], wrapper.inputs["Tint"])
    links.new(wrapper.outputs["Color"], reroute.inputs[0])
    links.new(reroute.outputs[0], muted.inputs["Color"])
    links.new(muted.outputs["Color"], nodes["Diffuse BSDF"].inputs["Color"])
    a, warnings = export(scene)
    assert warnings == [] and len(a["input_bindings"]) == 1
    pixels = ts.render(scene, 'CANDELA', 4, str(tmp_path / "group.exr"), 0)
    assert np.allclose(pixels, reference, rtol=1e-5, atol=1e-7)


def test_packed_images_need_no_file(tmp_path):
    def packed():
        image = ts.save_image(str(tmp_path / "packed.png"), ts.checker())
        image.pack()
        (tmp_path / "packed.png").unlink()
        return image

    scene = ts.textured_plane_scene(str(tmp_path), image=packed)
    a, warnings = export(scene)
    assert warnings == [] and a["textures_u8"].shape == (64, 4)
    pixels = ts.render(scene, 'CANDELA', 4, str(tmp_path / "packed.exr"), max_bounces=0)
    stored = np.round(ts.checker() * 255.0) / 255.0
    want, inside = expected_plane(scene, stored, decode=True)
    assert np.allclose(pixels[..., :3][inside], want[inside], rtol=1e-4, atol=1e-6)


def test_missing_image_warns_and_renders_magenta(tmp_path):
    def lost():
        image = bpy.data.images.new("Lost", 4, 4)
        image.source, image.filepath = 'FILE', str(tmp_path / "does_not_exist.png")
        return image

    scene = ts.textured_plane_scene(str(tmp_path), image=lost)
    a, warnings = export(scene)
    assert any("'Lost'" in m and "material 'Checker'" in m and "magenta" in m for m in warnings), warnings
    assert "texture_info" not in a   # nothing to sample: the input is the constant magenta
    pixels = ts.render(scene, 'CANDELA', 2, str(tmp_path / "lost.exr"), max_bounces=0)
    centre = pixels[8:-8, 8:-8, :3].reshape(-1, 3)
    assert np.allclose(centre, np.array([1.0, 0.0, 1.0]) * SUN / math.pi, rtol=1e-4, atol=1e-6)


def test_unsupported_input_node_warns_once_and_keeps_the_socket_value(tmp_path):
    scene = ts.textured_plane_scene(str(tmp_path))
    mat = bpy.data.materials["Checker"]
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    diffuse = nodes["Diffuse BSDF"]
    diffuse.inputs["Color"].default_value = (0.5, 0.5, 0.5, 1.0)
    density = nodes.new("ShaderNodeTexPointDensity")   # a node Candela does not read
    links.new(density.outputs["Color"], diffuse.inputs["Color"])
    links.new(density.outputs["Density"], diffuse.inputs["Roughness"])
    a, warnings = export(scene)
    noisy = [m for m in warnings if "Point Density" in m]
    assert len(noisy) == 1 and "material 'Checker'" in noisy[0], warnings
    cols = schema.closure_columns()
    assert np.allclose(a["closure_params"][0, cols.index("color_r"):cols.index("color_r") + 3], 0.5)


def test_flat_normal_map_changes_nothing_and_a_tilted_one_tilts(tmp_path):
    """A normal map of (0.5, 0.5, 1) renders the plane exactly as without; one tilted by 30° toward the UV tangent
    scales the sunlit radiance by cos 30°."""
    reference = ts.render(ts.textured_plane_scene(str(tmp_path)), 'CANDELA', 4, str(tmp_path / "ref.exr"), 0)
    for tilt in (0.0, math.radians(30.0)):
        scene = ts.textured_plane_scene(str(tmp_path))
        mat = bpy.data.materials["Checker"]
        nodes, links = mat.node_tree.nodes, mat.node_tree.links
        color = (0.5 + 0.5 * math.sin(tilt), 0.5, 0.5 + 0.5 * math.cos(tilt))
        rgb = np.broadcast_to(np.array(color, np.float32), (4, 4, 3)).copy()
        image = ts.save_image(str(tmp_path / f"normal{tilt:.2f}.exr"), rgb, float_buffer=True, colorspace='Non-Color')
        tex = nodes.new("ShaderNodeTexImage")
        tex.image = image
        normal_map = nodes.new("ShaderNodeNormalMap")
        links.new(tex.outputs["Color"], normal_map.inputs["Color"])
        links.new(normal_map.outputs["Normal"], nodes["Diffuse BSDF"].inputs["Normal"])
        a, warnings = export(scene)
        assert "tangents" in a and warnings == []
        assert np.allclose(a["tangents"][..., :3], (1.0, 0.0, 0.0), atol=1e-5)   # MikkTSpace: +X along u
        pixels = ts.render(scene, 'CANDELA', 4, str(tmp_path / f"n{tilt:.2f}.exr"), 0)
        assert np.allclose(pixels[..., :3], reference[..., :3] * math.cos(tilt), rtol=1e-4, atol=1e-6), tilt


def test_generated_coordinates_match_cycles(tmp_path):
    """The checker through Generated coordinates on an off-centre, scaled mesh: Blender's texture space (the
    mesh's bounds) decides where the texels land. Edge pixels of the checker differ between the engines' sample
    positions (per pixel up to ~0.05 at 64 samples); an 8 × 8-pixel block holds ≲ 16 edge pixels, so its mean
    differs by ≲ 0.5 % of its value from noise, while a misplaced texture space moves whole texels: 5 %."""
    def build():
        scene = ts.textured_plane_scene(str(tmp_path), 32, 32)
        ob = bpy.data.objects["Plane"]
        co = np.empty(len(ob.data.vertices) * 3, np.float32)
        ob.data.vertices.foreach_get("co", co)
        co = co.reshape(-1, 3) * (0.7, 1.0, 1.0) + (0.5, 0.3, 0.0)
        ob.data.vertices.foreach_set("co", co.ravel())
        ob.data.update()
        ob.scale, ob.location = (1.3, 1.0, 1.0), (-0.6, -0.3, 0.0)
        nodes, links = bpy.data.materials["Checker"].node_tree.nodes, bpy.data.materials["Checker"].node_tree.links
        links.new(nodes.new("ShaderNodeTexCoord").outputs["Generated"], nodes["Image Texture"].inputs["Vector"])
        return scene
    images = {e: ts.render(build(), e, 64, str(tmp_path / f"{e}.exr"), 0)[..., :3] for e in ('CYCLES', 'CANDELA')}
    blocks = {e: img.reshape(4, 8, 4, 8, 3).mean(axis=(1, 3)) for e, img in images.items()}
    assert np.allclose(blocks['CANDELA'], blocks['CYCLES'], rtol=0.05, atol=1e-3), blocks['CANDELA'] / blocks['CYCLES']


def test_tangent_space_normal_map_matches_cycles(tmp_path):
    """A 4 × 4 normal map of random tilts up to 30° in every direction (strength 0.8) on the checker plane, under a
    sun off the vertical. Where a pixel lies inside one texel of both images its radiance depends only on the
    shading normal n: Candela gives albedo·E/π·max(0, n·l) exactly (tangent, bitangent sign, green direction and
    strength blend as in Cycles), times the shadow-terminator term both engines apply to bumped diffuse closures
    (Chiang et al. 2019: g = (Ng·l)/((n·l)(Ng·n)), 1 for g ≥ 1, else g + g² − g³). Both are checked to float
    precision, so a change on either side shows."""
    rng = np.random.default_rng(3)
    theta, phi = rng.uniform(0.0, math.radians(30.0), (4, 4)), rng.uniform(0.0, 2.0 * math.pi, (4, 4))
    normals = np.stack([np.sin(theta) * np.cos(phi), np.sin(theta) * np.sin(phi), np.cos(theta)], axis=-1)
    sun_rotation = (0.4, 0.3, 0.0)

    def build():
        scene = ts.textured_plane_scene(str(tmp_path), 32, 32)
        nodes, links = bpy.data.materials["Checker"].node_tree.nodes, bpy.data.materials["Checker"].node_tree.links
        tex = nodes.new("ShaderNodeTexImage")
        tex.interpolation = 'Closest'
        tex.image = ts.save_image(str(tmp_path / "normals.exr"), (0.5 + 0.5 * normals).astype(np.float32),
                                  float_buffer=True, colorspace='Non-Color')
        normal_map = nodes.new("ShaderNodeNormalMap")
        normal_map.inputs["Strength"].default_value = 0.8
        links.new(tex.outputs["Color"], normal_map.inputs["Color"])
        links.new(normal_map.outputs["Normal"], nodes["Diffuse BSDF"].inputs["Normal"])
        bpy.data.objects["Sun"].rotation_euler = sun_rotation
        return scene
    images = {e: ts.render(build(), e, 16, str(tmp_path / f"{e}.exr"), 0)[..., :3] for e in ('CYCLES', 'CANDELA')}
    scene = build()
    ix, iy, inside = texel_of_pixels(scene)                  # checker texels (8 × 8); the normal map's are 4 × 4
    stored = bpy.data.images["normals.exr"]
    px = np.empty(16 * 4, np.float32)
    stored.pixels.foreach_get(px)
    n = 2.0 * px.reshape(4, 4, 4)[..., :3].astype(np.float64) - 1.0
    n /= np.linalg.norm(n, axis=-1, keepdims=True)
    ng = np.array([0.0, 0.0, 1.0])
    n = ng + (n - ng) * 0.8
    n /= np.linalg.norm(n, axis=-1, keepdims=True)
    light = np.array(mathutils.Euler(sun_rotation).to_matrix() @ mathutils.Vector((0.0, 0.0, 1.0)))
    albedo = srgb_decode(np.round(ts.checker() * 255.0) / 255.0)[iy, ix]
    n_pix = n[iy // 2, ix // 2]
    cos = np.maximum(n_pix @ light, 0.0)
    want = albedo * SUN / math.pi * cos[..., None]
    assert inside.sum() > 0.4 * inside.size
    g = (ng @ light) / ((n_pix @ light) * (n_pix @ ng))
    term = np.where(g >= 1.0, 1.0, np.where(g < 0.0, 0.0, g + g * g - g ** 3))
    assert (term[inside] < 0.999).any()   # the sun is low enough for the term to matter somewhere
    # Both engines apply the bump shadowing term (docs/light_paths.md, "Bump shadowing").
    assert np.allclose(images['CANDELA'][inside], (want * term[..., None])[inside], rtol=1e-4, atol=1e-6)
    assert np.allclose(images['CYCLES'][inside], (want * term[..., None])[inside], rtol=1e-3, atol=1e-6)


def test_environment_world_exports_a_program(tmp_path):
    scene = ts.environment_scene(str(tmp_path))
    a, warnings = export(scene)
    assert warnings == []
    assert "world_color" not in a
    targets = schema.shader_enum("input_targets")
    world = [b for b in a["input_bindings"] if b[0] == targets["WORLD"]]
    assert len(world) == 1
    assert a["texture_info"][0, 1:].tolist() == [64, 32, schema.shader_enum("tex_color_spaces")["LINEAR"],
                                                 schema.shader_enum("tex_storages")["FLOAT"]]


@pytest.mark.parametrize("name", ["textured_plane", "environment", "environment_rotated"])
def test_brightness_matches_cycles(tmp_path, name):
    """The parity requirement against Cycles 3.4: image mean within 2 %, 4 × 4 block means within 5 %. At these
    sample counts both renders' per-pixel noise is ≤ 3.5 % (Candela's estimate), so the noise of the image mean is
    < 0.15 % and of a block mean (≥ 48 pixels) < 0.5 %: 2 % and 5 % are far outside noise, a failure is a real
    difference. The rotated environment checks Blender's direction → (u, v) mapping through a Mapping node."""
    if name == "textured_plane":
        build, samples, bounces = ts.textured_plane_scene, 32, 0
    elif name == "environment":
        build, samples, bounces = (lambda d: ts.environment_scene(d, 32, 24)), 128, 4
    else:
        build, samples, bounces = (lambda d: ts.environment_scene(d, 32, 24, rotation=1.0)), 128, 4
    images = {}
    for engine in ('CYCLES', 'CANDELA'):
        images[engine] = ts.render(build(str(tmp_path)), engine, samples, str(tmp_path / f"{engine}.exr"), bounces)
    a, b = images['CANDELA'][..., :3].mean(-1), images['CYCLES'][..., :3].mean(-1)
    assert a.mean() == pytest.approx(b.mean(), rel=0.02), (a.mean(), b.mean())
    h, w = a.shape
    ba, bb = (x[: h // 4 * 4, : w // 4 * 4].reshape(4, h // 4, 4, w // 4).mean(axis=(1, 3)) for x in (a, b))
    lit = bb > 0.05 * bb.max()
    assert np.all(np.abs(ba - bb)[lit] <= 0.05 * bb[lit]), np.round(ba / bb, 3)
