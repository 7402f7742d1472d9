"""Headless renders through bin/candela-blender: failures exit non-zero without an output file; success saves it."""

import os
import shutil
import subprocess

import bpy

import scenes

CANDELA_BLENDER = os.path.join(scenes.REPO, "bin", "candela-blender")


def _save(scene, path):
    scene.render.image_settings.file_format = 'OPEN_EXR'
    bpy.ops.wm.save_as_mainfile(filepath=str(path), check_existing=False)


def _render(blend, out_dir, *extra, scripts_dir=None):
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME", "VIRTUAL_ENV")}
    if scripts_dir is not None:
        env["CANDELA_SCRIPTS_DIR"] = str(scripts_dir)
    cmd = [CANDELA_BLENDER, "-b", str(blend), "-E", "CANDELA", "-o", str(out_dir / "out_#"), "-f", "1", *extra]
    return subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=120)


def test_missing_camera_fails(tmp_path):
    scene = scenes.tiny_scene(with_camera=False, samples=2)
    _save(scene, tmp_path / "nocam.blend")
    proc = _render(tmp_path / "nocam.blend", tmp_path)
    output = proc.stdout + proc.stderr
    assert proc.returncode != 0, output
    assert "no camera" in output, output     # Blender itself refuses before calling the engine
    assert not any(p.name.startswith("out_") for p in tmp_path.iterdir()), list(tmp_path.iterdir())


def test_engine_error_fails(tmp_path):
    """An error raised inside Candela's render() (nothing to render) → ERROR report → exit 1, no file, no crash."""
    scene = scenes.empty_scene()
    scenes.add_camera(scene)
    _save(scene, tmp_path / "empty.blend")
    proc = _render(tmp_path / "empty.blend", tmp_path)
    output = proc.stdout + proc.stderr
    assert proc.returncode == 1, output      # 1, not a segfault (139)
    assert "nothing to render" in output, output
    assert not any(p.name.startswith("out_") for p in tmp_path.iterdir()), list(tmp_path.iterdir())


def test_render_with_camera_succeeds(tmp_path):
    scene = scenes.tiny_scene(samples=64)
    _save(scene, tmp_path / "ok.blend")
    proc = _render(tmp_path / "ok.blend", tmp_path, "--", "--candela-samples", "2")
    output = proc.stdout + proc.stderr
    assert proc.returncode == 0, output
    assert (tmp_path / "out_1.exr").is_file(), output
    assert "Candela: rendered 32x24, 2 samples" in output, output


def test_summary_names_the_pre_pass_and_its_time(tmp_path):
    """The last line says how much of the render time a pre-pass took (here the irradiance cache's)."""
    scene = scenes.tiny_scene(samples=2)
    scene.candela.integrator = "IRRADIANCE_CACHE"
    _save(scene, tmp_path / "ic.blend")
    proc = _render(tmp_path / "ic.blend", tmp_path)
    output = proc.stdout + proc.stderr
    assert proc.returncode == 0, output
    assert "Candela: rendered 32x24, 2 samples" in output and "; of which irradiance cache " in output, output


def test_missing_native_module_reports_error(tmp_path):
    """Without the .so the add-on still registers; rendering fails loudly and explains why."""
    import candela
    staged = tmp_path / "scripts" / "addons" / "candela"
    shutil.copytree(os.path.dirname(candela.__file__), staged,
                    ignore=shutil.ignore_patterns("_native*", "__pycache__"))
    scene = scenes.tiny_scene(samples=2)
    _save(scene, tmp_path / "ok.blend")
    proc = _render(tmp_path / "ok.blend", tmp_path, scripts_dir=tmp_path / "scripts")
    output = proc.stdout + proc.stderr
    assert proc.returncode == 1, output
    assert "cannot import candela._native" in output, output
    assert not any(p.name.startswith("out_") for p in tmp_path.iterdir())
