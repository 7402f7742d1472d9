"""Render passes through Blender: declared by update_render_passes, written by `blender -b … -F OPEN_EXR_MULTILAYER`
into a multilayer EXR and read back with their analytic values — a plane facing the camera 5 m away has Depth 5 and
its world-space normal, its object's pass index and its colour as albedo."""

import math
import os
import subprocess
import bpy
import numpy as np

import scenes

CANDELA_BLENDER = os.path.join(scenes.REPO, "bin", "candela-blender")

W, H = 24, 16


def plane_scene():
    """The camera at the origin looks along +Y (a rotated camera: the Normal pass is world space, not camera space) at
    a 4 m × 4 m plane at y = 5 facing it; the plane covers the middle of the frame, the rest is background."""
    scene = scenes.empty_scene(W, H)
    scene.candela.samples = 4
    scene.candela.max_bounces = 1
    plane = scenes.link(scene, bpy.data.objects.new("Plane", scenes.grid_mesh("Plane", 2.0)))
    plane.location = (0.0, 5.0, 0.0)
    plane.rotation_euler = (math.pi / 2, 0.0, 0.0)   # the XY plane turned to face −Y
    plane.pass_index = 7
    plane.data.materials.append(scenes.lambert_material("Colour", (0.2, 0.4, 0.6)))
    light = scenes.link(scene, bpy.data.objects.new("Point", bpy.data.lights.new("Point", 'POINT')))
    light.location = (0.0, 2.0, 1.0)
    light.data.energy = 100.0
    camera = scenes.add_camera(scene, location=(0.0, 0.0, 0.0), rotation=(math.pi / 2, 0.0, 0.0))
    camera.data.lens = 20.0   # the plane's ±2 m at 5 m spans tan 0.4; the frame spans ±0.9 × ±0.6
    layer = bpy.context.view_layer
    layer.use_pass_z = layer.use_pass_normal = layer.use_pass_object_index = True
    layer.candela.use_pass_albedo = True
    return scene


def render_multilayer(scene, path):
    scene.render.image_settings.file_format = 'OPEN_EXR_MULTILAYER'
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)
    from candela import native
    return native.require().read_exr_channels(path)


def render_command_line(scene, tmp_path):
    """Save the scene and render frame 1 as `bin/candela-blender -b file -F OPEN_EXR_MULTILAYER -f 1`."""
    blend = tmp_path / "passes.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(blend), check_existing=False)
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME", "VIRTUAL_ENV")}
    cmd = [CANDELA_BLENDER, "-b", str(blend), "-E", "CANDELA", "-o", str(tmp_path / "out_#"),
           "-F", "OPEN_EXR_MULTILAYER", "-f", "1"]
    proc = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    from candela import native
    return native.require().read_exr_channels(str(tmp_path / "out_1.exr"))


def test_depth_normal_index_and_albedo_reach_the_multilayer_exr(tmp_path):
    scene = plane_scene()
    channels = render_command_line(scene, tmp_path)
    layer = bpy.context.view_layer.name
    for name in ("Combined.R", "Depth.Z", "Normal.X", "Normal.Y", "Normal.Z", "IndexOB.X", "Albedo.R", "Albedo.G",
                 "Albedo.B"):
        assert f"{layer}.{name}" in channels, (name, sorted(channels))
    get = lambda name: channels[f"{layer}.{name}"]
    assert get("Depth.Z").shape == (H, W)
    # Pixels whose filter footprint (Blackman-Harris, 1.5 px) lies well inside the plane: the plane spans tan ±0.4 of
    # the camera's ±0.9 (horizontal fit, 36 mm sensor, 20 mm lens), i.e. columns 7–16 and rows 4–11 of 24 × 16.
    inside = (slice(6, 10), slice(9, 15))
    depth = get("Depth.Z")[inside]
    # z depth along the view axis = 5 for a plane perpendicular to it; float32 precision of the hit distance.
    assert np.allclose(depth, 5.0, rtol=1e-5), depth
    normal = np.stack([get("Normal.X"), get("Normal.Y"), get("Normal.Z")], axis=-1)[inside]
    assert np.allclose(normal, (0.0, -1.0, 0.0), atol=1e-5), normal   # world space, facing the camera
    assert np.all(get("IndexOB.X")[inside] == 7.0)
    albedo = np.stack([get("Albedo.R"), get("Albedo.G"), get("Albedo.B")], axis=-1)[inside]
    assert np.allclose(albedo, (0.2, 0.4, 0.6), atol=1e-6), albedo   # Lambert: the albedo is the colour
    # The corners see the background: Cycles' values.
    corners = (slice(0, 2), slice(0, 2))
    assert np.all(get("Depth.Z")[corners] == 1e10)
    assert np.all(get("IndexOB.X")[corners] == 0.0)
    for c in ("Normal.X", "Normal.Y", "Normal.Z", "Albedo.R"):
        assert np.all(get(c)[corners] == 0.0), c


def test_passes_off_by_default(tmp_path):
    scene = plane_scene()
    layer = bpy.context.view_layer
    layer.use_pass_z = layer.use_pass_normal = layer.use_pass_object_index = False
    layer.candela.use_pass_albedo = False
    channels = render_multilayer(scene, str(tmp_path / "plain.exr"))
    assert not any(".Depth." in c or ".Normal." in c or ".IndexOB." in c or ".Albedo." in c for c in channels)


def test_native_params_list_the_passes():
    from candela.params import to_native_params
    scene = plane_scene()
    params = to_native_params(scene, scene.camera.data, argv=["blender"], view_layer=bpy.context.view_layer)
    assert params["passes"].split(",") == ["Depth", "Normal", "Albedo", "IndexOB"]


def test_bdpt_strategy_images_reach_the_multilayer_exr_and_sum_to_the_image(tmp_path):
    """BDPT's Strategy Images: one RGB pass per (depth, s, t), weighted and unweighted, registered because the setting
    is on; with a one-pixel box filter the weighted ones sum to Combined (integrators/bdpt/strategy_images.h)."""
    scene = plane_scene()
    scene.candela.integrator = 'BDPT'
    scene.candela.bdpt_strategy_images = True
    scene.candela.bdpt_strategy_depth = 2
    scene.candela.max_bounces = 1          # paths of depth 0..2: all of them have images
    scene.candela.pixel_filter = 'BOX'
    scene.candela.filter_width = 1.0
    channels = render_command_line(scene, tmp_path)
    layer = bpy.context.view_layer.name
    from candela import schema
    names = schema.bdpt_strategy_passes(2)
    assert len(names) == 2 * (2 + 3 + 4) and "BDPT d1 s1 t2" in names and "BDPT d2 s3 t1 unweighted" in names
    for name in names:
        assert f"{layer}.{name}.R" in channels, (name, sorted(channels)[:20])
    for c in "RGB":
        combined = channels[f"{layer}.Combined.{c}"]
        total = sum(channels[f"{layer}.{n}.{c}"] for n in names if not n.endswith("unweighted"))
        assert combined.max() > 0.0
        np.testing.assert_allclose(total, combined, rtol=1e-3, atol=1e-5)


def test_ic_records_pass_marks_the_irradiance_caches_records(tmp_path):
    """The IC Records pass (View Layer › Passes › Candela) reaches the multilayer EXR: with the Irradiance Cache it
    counts the records the pixels' paths made (on the plane, none on the background), with PATH it is zero."""
    scene = plane_scene()
    layer = bpy.context.view_layer
    layer.use_pass_z = layer.use_pass_normal = layer.use_pass_object_index = False
    layer.candela.use_pass_albedo = False
    layer.candela.use_pass_ic_records = True
    from candela.params import to_native_params
    assert to_native_params(scene, scene.camera.data, argv=["blender"], view_layer=layer)["passes"] == "IC Records"
    scene.candela.integrator = "IRRADIANCE_CACHE"
    scene.candela.ic_gather_rays = 64
    channels = render_multilayer(scene, str(tmp_path / "ic.exr"))
    records = next(v for k, v in channels.items() if ".IC Records." in k)
    assert records.shape == (H, W) and records.sum() >= 1 and np.all(records >= 0)
    depth_free = np.isclose(records[0], 0.0).all() and np.isclose(records[-1], 0.0).all()   # background rows
    assert depth_free, records
    scene.candela.integrator = "PATH"
    channels = render_multilayer(scene, str(tmp_path / "path.exr"))
    assert np.all(next(v for k, v in channels.items() if ".IC Records." in k) == 0.0)
    layer.candela.use_pass_ic_records = False
