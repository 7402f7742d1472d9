"""Cameras issue 20 found rendered wrongly: panoramic cameras (equirectangular, fisheye equidistant and equisolid)
against Cycles, stereoscopy (each eye through its own camera, into its own view) and a world-only scene."""

import math

import bpy
import numpy as np

import scenes
import texture_scenes as ts

EMISSION = 4.0


def panorama_scene(kind, width=96, height=48):
    """Emissive cubes in six directions around a camera at the origin (black world, no lights): a pixel is bright
    exactly where a cube is seen, whatever the integrator does beyond the camera ray."""
    scene = scenes.empty_scene(width, height)
    cam = scenes.add_camera(scene, location=(0.0, 0.0, 0.0), rotation=(math.pi / 2, 0.0, 0.0))   # looks along +Y
    cam.data.type = 'PANO'
    cam.data.cycles.panorama_type = kind
    cam.data.cycles.fisheye_fov = math.radians(200.0)
    cam.data.cycles.fisheye_lens = 8.0
    glow = scenes.emission_material("Glow", (1.0, 1.0, 1.0), EMISSION)
    for i, (location, size) in enumerate((((0, 6, 0), 1.5), ((-6, 1, 0), 1.2), ((6, 2, 1), 1.0), ((0, -6, 0), 1.5),
                                          ((1, 2, 6), 1.0), ((2, 5, -3), 0.8))):
        ob = scenes.link(scene, bpy.data.objects.new(f"Cube{i}", scenes.cube_mesh(f"Cube{i}", size)))
        ob.location = location
        ob.data.materials.append(glow)
    return scene


def bright(pixels):
    return pixels[..., :3].mean(axis=2) > 0.5 * EMISSION


def boundary(mask):
    """Pixels whose 3x3 neighbourhood is not all the same in `mask` (where coverage is partial)."""
    padded = np.pad(mask, 1, mode='edge')
    stack = [padded[1 + dy:padded.shape[0] - 1 + dy, 1 + dx:padded.shape[1] - 1 + dx]
             for dy in (-1, 0, 1) for dx in (-1, 0, 1)]
    return np.any(stack, axis=0) & ~np.all(stack, axis=0)


def check_like_cycles(scene, tmp_path, name):
    candela = ts.render(scene, 'CANDELA', 16, str(tmp_path / f"{name}_candela.exr"), max_bounces=0)
    cycles = ts.render(scene, 'CYCLES', 16, str(tmp_path / f"{name}_cycles.exr"), max_bounces=0)
    a, b = bright(candela), bright(cycles)
    assert b.sum() > 0.05 * b.size, "the scene must show cubes"
    # The same projection makes the masks differ only where a pixel is partly covered (noise and the filter then
    # decide): at most on boundary pixels of either mask. Any other projection moves whole cubes.
    wrong = (a != b) & ~(boundary(a) | boundary(b))
    assert not wrong.any(), f"{int(wrong.sum())} pixels differ from Cycles away from the cubes' edges"
    return candela, cycles


def test_equirectangular_matches_cycles(tmp_path):
    scene = panorama_scene('EQUIRECTANGULAR')
    candela, _ = check_like_cycles(scene, tmp_path, "equirect")
    # The cube behind the camera shows at the left and right edges, the one above at the top: a panorama, not a
    # perspective view.
    mask = bright(candela)
    assert mask[:, :4].any() and mask[:, -4:].any() and mask[-8:, :].any()


def test_fisheye_equidistant_matches_cycles(tmp_path):
    scene = panorama_scene('FISHEYE_EQUIDISTANT', 64, 64)
    candela, cycles = check_like_cycles(scene, tmp_path, "equidistant")
    # Outside the image circle: black in both.
    corner = np.zeros((64, 64), bool)
    yy, xx = np.mgrid[0:64, 0:64]
    corner[((xx + 0.5 - 32) ** 2 + (yy + 0.5 - 32) ** 2) > 34 ** 2] = True
    assert candela[corner][:, :3].max() == 0.0 and cycles[corner][:, :3].max() == 0.0


def test_fisheye_equisolid_matches_cycles(tmp_path):
    check_like_cycles(panorama_scene('FISHEYE_EQUISOLID', 80, 60), tmp_path, "equisolid")


def test_unsupported_panorama_is_refused_by_name(tmp_path):
    from fake_engine import FakeEngine
    from candela import render_loop
    from candela.export import ExportError
    scene = panorama_scene('MIRRORBALL', 16, 16)
    try:
        render_loop.render_frame(FakeEngine(), bpy.context.evaluated_depsgraph_get())
    except ExportError as e:
        assert "MIRRORBALL" in str(e) and "'Camera'" in str(e)
    else:
        raise AssertionError("a mirror-ball panorama rendered without a word")


def render_stereo(scene, engine, path):
    from candela import native   # Blender's loader sees these EXRs as stereo images: read them directly
    ts.render(scene, engine, 8, path, read=False)   # writes path_L.exr and path_R.exr
    return native.module.read_exr(path + "_L.exr"), native.module.read_exr(path + "_R.exr")


def test_stereo_renders_each_eye_through_its_camera(tmp_path):
    """Both eyes see the scene through Blender's per-eye camera (interocular offset, off-axis convergence and
    shift), in the named views: the emissive cube sits where Cycles puts it in each eye."""
    scene = scenes.tiny_scene(width=64, height=40, samples=8)
    r = scene.render
    r.use_multiview, r.views_format = True, 'STEREO_3D'
    scene.camera.data.stereo.interocular_distance = 0.4
    r.image_settings.views_format = 'INDIVIDUAL'

    def cube_x(pixels):   # the emissive cube's centre column (it is far brighter than the lit plane)
        glow = pixels[..., 0] > 3.0
        assert glow.sum() > 4, "the cube must be seen"
        return np.nonzero(glow)[1].mean()

    left, right = render_stereo(scene, 'CANDELA', str(tmp_path / "candela"))
    cl, cr = render_stereo(scene, 'CYCLES', str(tmp_path / "cycles"))
    assert left[..., :3].mean() > 1e-3 and right[..., :3].mean() > 1e-3   # no blank eye
    assert abs(cube_x(left) - cube_x(right)) > 2.0                       # no mono eye: the views differ
    # Same place as Cycles in each eye: within half a pixel (the centroid of a shape several pixels wide).
    assert abs(cube_x(left) - cube_x(cl)) < 0.5 and abs(cube_x(right) - cube_x(cr)) < 0.5


def test_world_only_scene_renders_the_sky(tmp_path):
    scene = scenes.empty_scene(16, 12)
    scenes.add_camera(scene)
    world = bpy.data.worlds.new("Sky")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.2, 0.4, 0.8, 1.0)
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 1.5
    scene.world = world
    pixels = ts.render(scene, 'CANDELA', 2, str(tmp_path / "sky.exr"))
    assert np.allclose(pixels[..., :3], (0.3, 0.6, 1.2), rtol=1e-5)


def test_every_integrator_renders_a_panorama_like_path_or_refuses_it_by_name():
    """Issue 20: a panoramic camera works in every integrator that connects to the camera, or is refused there by
    name, never rendered as another projection. The scene's background is exactly black (black world, no lights,
    no bounces), so any light outside PATH's cubes (away from their partly covered edge pixels) means another
    projection, whatever the integrator's noise; and the cubes behind and above the camera must show."""
    from fake_engine import FakeEngine
    from candela import render_loop, schema
    from candela.export import ExportError
    scene = panorama_scene('EQUIRECTANGULAR', 64, 32)
    scene.candela.samples, scene.candela.max_bounces = 8, 0

    def render(integrator):
        scene.candela.integrator = integrator
        engine = FakeEngine()
        render_loop.render_frame(engine, bpy.context.evaluated_depsgraph_get(), background=True)
        return engine.image().reshape(32, 64, 4)

    path = bright(render("PATH"))
    allowed = path | boundary(path)
    assert path[:, :3].any() and path[:, -3:].any() and path[-6:, :].any()   # behind (both edges) and above
    refused, rendered = [], []
    for name, _, label in schema.integrators():
        if name == "PATH":
            continue
        try:
            lit = render(name)[..., :3].max(axis=2) > 0.0
        except ExportError as e:
            message = str(e)
            assert f"integrator {name}" in message and "panoramic camera (Equirectangular)" in message, message
            refused.append(name)
            continue
        stray = lit & ~allowed
        assert not stray.any(), f"{label}: {int(stray.sum())} lit pixels where PATH's panorama shows nothing"
        assert lit[:, :3].any() and lit[:, -3:].any() and lit[-6:, :].any(), f"{label}: not the panorama"
        rendered.append(name)
    assert {"LIGHT", "BDPT"} <= set(refused), (refused, rendered)
