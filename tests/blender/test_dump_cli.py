"""A dump written by the add-on renders to the same image with the command-line renderer (same seed)."""

import os
import subprocess

import bpy
import numpy as np
import pytest

import scenes

CLI = os.path.join(scenes.REPO, "build", "bin", "candela")


@pytest.mark.skipif(not os.path.isfile(CLI), reason="the command-line renderer is not built")
def test_dump_renders_like_blender(tmp_path):
    scene = scenes.tiny_scene(width=32, height=24, samples=4)
    assert bpy.ops.candela.export_dump(directory=str(tmp_path / "dump")) == {'FINISHED'}
    proc = subprocess.run([CLI, str(tmp_path / "dump"), "-o", str(tmp_path / "cli.exr"), "-q"],
                          capture_output=True, text=True, timeout=60)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    scene.render.image_settings.file_format = 'OPEN_EXR'
    bpy.ops.render.render()
    bpy.data.images["Render Result"].save_render(str(tmp_path / "blender.exr"))
    a = scenes.read_image_pixels(str(tmp_path / "blender.exr"))
    b = scenes.read_image_pixels(str(tmp_path / "cli.exr"))
    assert a.shape == b.shape
    assert np.allclose(a, b, rtol=1e-4, atol=1e-5), np.abs(a - b).max()
