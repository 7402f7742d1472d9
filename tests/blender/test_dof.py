"""Depth of field through Blender: the camera's DOF settings reach the native params as Cycles reads them, and a
defocused emitter renders with Cycles' brightness and Cycles' blur size."""

import math

import bpy
import numpy as np

import scenes

W = H = 64


def bokeh_scene(engine):
    """A 0.5 m emissive square 5 m in front of the camera, in focus at 2 m with f/0.08 (a 31 cm aperture radius):
    its image is the square convolved with a disk of radius a·|1/f − 1/z|·lens·W/sensor = 8.3 px (tests/native/
    dof_test.cpp). Black world, no lights: the image is exactly the emitter's, seen through the lens."""
    scene = scenes.empty_scene(W, H)
    square = scenes.link(scene, bpy.data.objects.new("Square", scenes.grid_mesh("Square", 0.25)))
    square.location = (0.0, 5.0, 0.0)
    square.rotation_euler = (math.pi / 2, 0.0, 0.0)
    square.data.materials.append(scenes.emission_material("Glow", (1.0, 1.0, 1.0), 1.0))
    camera = scenes.add_camera(scene, location=(0.0, 0.0, 0.0), rotation=(math.pi / 2, 0.0, 0.0))
    dof = camera.data.dof
    dof.use_dof, dof.focus_distance, dof.aperture_fstop = True, 2.0, 0.08
    scene.world = bpy.data.worlds.new("Black")
    scene.world.color = (0.0, 0.0, 0.0)
    scene.render.engine = engine
    if engine == 'CYCLES':
        c = scene.cycles
        c.device, c.samples, c.use_adaptive_sampling, c.use_denoising = 'CPU', 512, False, False
        c.max_bounces, c.pixel_filter_type, c.filter_width, c.seed = 0, 'BOX', 1.0, 3
    else:
        s = scene.candela
        s.samples, s.max_bounces, s.pixel_filter, s.filter_width, s.seed = 512, 0, 'BOX', 1.0, 3
    return scene


def render_luminance(scene, path):
    scene.render.image_settings.file_format = 'OPEN_EXR'
    bpy.ops.render.render()
    bpy.data.images["Render Result"].save_render(path)
    rgba = scenes.read_image_pixels(path)
    return rgba[..., :3] @ np.array([0.2126, 0.7152, 0.0722])


def flux_and_second_moment(lum):
    y, x = np.mgrid[0:lum.shape[0], 0:lum.shape[1]]
    r2 = (x + 0.5 - 0.5 * lum.shape[1]) ** 2 + (y + 0.5 - 0.5 * lum.shape[0]) ** 2
    return lum.sum(), (r2 * lum).sum() / lum.sum()


def test_defocused_emitter_matches_cycles(tmp_path):
    if not scenes.engine_available('CYCLES'):
        import pytest
        pytest.skip("Cycles is not available")
    cycles = render_luminance(bokeh_scene('CYCLES'), str(tmp_path / "cycles.exr"))
    candela = render_luminance(bokeh_scene('CANDELA'), str(tmp_path / "candela.exr"))
    flux_c, m2_c = flux_and_second_moment(cycles)
    flux_k, m2_k = flux_and_second_moment(candela)
    # Statistics: the square covers ~79 px², so each image sums ~79 × 512 ≈ 40,000 emitter hits; the flux's relative
    # standard error is at most 1/√40000 = 0.5 % per image (less with stratified samples), 0.7 % for the ratio, so
    # 2 % is about 3σ. The second moment (≈ 13 px² of the square + R²/2 = 35 px² of the disk) has a relative error of
    # about √(Var r² / hits) ≲ 1/√40000 ≈ 0.5 % per image; 3 % is > 4σ of the difference, while a 5 % error in the
    # aperture radius moves it by ~7 %.
    assert abs(flux_k / flux_c - 1.0) < 0.02, (flux_k, flux_c)
    assert abs(m2_k / m2_c - 1.0) < 0.03, (m2_k, m2_c)
    # The blur is real: in focus the same square has a second moment of ~13 px².
    assert m2_c > 40.0, m2_c


def test_dof_params_follow_the_camera():
    from candela.params import to_native_params
    scene = bokeh_scene('CANDELA')
    camera = scene.camera
    dof = camera.data.dof
    dof.aperture_blades, dof.aperture_rotation, dof.aperture_ratio = 6, 0.25, 1.5
    p = to_native_params(scene, camera.data, argv=["blender"], camera_object=camera)
    assert p["use_dof"] is True
    assert p["aperture_fstop"] == np.float32(0.08) and p["focus_distance"] == 2.0
    assert p["aperture_blades"] == 6 and abs(p["aperture_rotation"] - 0.25) < 1e-6 and p["aperture_ratio"] == 1.5
    # A focus object: its distance along the view axis (+Y here), not the straight-line distance.
    target = scenes.link(scene, bpy.data.objects.new("Target", None))
    target.location = (3.0, 4.0, -1.0)
    dof.focus_object = target
    bpy.context.view_layer.update()
    p = to_native_params(scene, camera.data, argv=["blender"], camera_object=camera)
    assert abs(p["focus_distance"] - 4.0) < 1e-5, p["focus_distance"]
    dof.use_dof = False
    assert to_native_params(scene, camera.data, argv=["blender"])["use_dof"] is False
