"""F12 through Blender: a tiny scene renders finite, non-black pixels."""

import os

import bpy
import numpy as np

import scenes


def render_to_exr(scene, path):
    scene.render.image_settings.file_format = 'OPEN_EXR'
    bpy.ops.render.render()
    bpy.data.images["Render Result"].save_render(path)
    return scenes.read_image_pixels(path)


def test_render_tiny_scene(tmp_path):
    scene = scenes.tiny_scene(width=32, height=24, samples=8)
    pixels = render_to_exr(scene, str(tmp_path / "tiny.exr"))
    assert pixels.shape == (24, 32, 4)
    rgb = pixels[..., :3]
    assert np.all(np.isfinite(rgb))
    assert rgb.max() > 0.0
    assert rgb.mean() > 1e-3, rgb.mean()   # plane lit by a 500 W light + an emissive cube: clearly not black


def test_render_border_result_size(tmp_path):
    scene = scenes.tiny_scene(width=40, height=30, samples=2)
    r = scene.render
    r.use_border, r.use_crop_to_border = True, True
    r.border_min_x, r.border_max_x, r.border_min_y, r.border_max_y = 0.25, 0.75, 0.0, 0.5
    pixels = render_to_exr(scene, str(tmp_path / "border.exr"))
    assert pixels.shape == (15, 20, 4)
    assert np.all(np.isfinite(pixels))


def test_noise_pass_and_noise_threshold(tmp_path):
    """The Noise pass reaches the render result (multilayer EXR), and a noise threshold ends the render early."""
    import sys

    scene = scenes.tiny_scene(width=32, height=24, samples=100000)
    scene.candela.noise_threshold = 0.05
    bpy.context.view_layer.candela.use_pass_noise = True
    scene.render.image_settings.file_format = 'OPEN_EXR_MULTILAYER'
    path = str(tmp_path / "noise.exr")
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)
    stats = sys.modules["candela.render_loop"].last_render_stats
    assert stats["phase"] == "done" and stats["stop_reason"] == "noise threshold"
    assert 16 <= stats["samples_done"] < 100000
    # The EXR header lists the channels: the Noise pass is written beside Combined.
    with open(path, "rb") as f:
        header = f.read(8192)
    assert b"Noise.X" in header, "the Noise pass is missing from the multilayer EXR"
    assert b"Combined.R" in header
