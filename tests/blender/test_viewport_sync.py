"""The viewport's scene and view sync without a display (Blender -b): what depsgraph updates re-export, that a
transform-only edit reads no mesh and rebuilds no mesh BVH, and that the view's camera (free perspective,
orthographic, camera view with zoom and border) renders what the equivalent camera renders.

The viewport renders from the same sampler stream as a final render (pixel, sample index, seed), so an image of
the same camera, size and samples differs from the final render only by float rounding (the viewport instances
every mesh, the final render flattens single-use meshes): the comparisons allow only that."""

import math
import time
from types import SimpleNamespace

import bpy
import numpy as np

import scenes
from candela import native
from candela.export import export_scene
from candela.params import to_native_params
from candela.viewport import scene_sync
from candela.viewport.render import viewport_settings
from candela.viewport.view_camera import view_camera


def update(block, geometry=False, transform=False, shading=False):
    return SimpleNamespace(id=block, is_updated_geometry=geometry, is_updated_transform=transform,
                           is_updated_shading=shading)


def test_classify_updates():
    scene = scenes.tiny_scene()
    cube, plane = bpy.data.objects["Cube"], bpy.data.objects["Plane"]
    moved = scene_sync.classify([update(cube, transform=True)])
    assert moved.export and not moved.geometry and not moved.scene
    edited = scene_sync.classify([update(cube, geometry=True, transform=True), update(plane.data)])
    assert edited.export and edited.geometry == {"Cube", "Plane"}
    selected = scene_sync.classify([update(cube)])   # selection only: no flags
    assert not selected.export
    settings = scene_sync.classify([update(scene)])
    assert settings.scene and not settings.export
    assert scene_sync.classify([update(bpy.data.materials["Grey"], shading=True)]).export


def test_integrators_without_progressive_rendering_fall_back_to_path(monkeypatch):
    from candela.viewport import render
    scene = scenes.tiny_scene()
    settings, notes = viewport_settings(scene, bpy.context.view_layer)
    assert settings["integrator"] == "PATH" and notes == []
    assert settings["time_limit"] == 0.0 and settings["noise_threshold"] == 0.0 and "passes" not in settings
    scene.candela.viewport_samples = 0
    assert viewport_settings(scene, bpy.context.view_layer)[0]["samples"] == render.UNLIMITED_SAMPLES
    from candela import schema
    assert {"PATH", "LIGHT", "BDPT"} <= set(schema.viewport_integrators())   # the registry's viewport flag
    scene.candela.integrator = "LIGHT"
    settings, notes = viewport_settings(scene, bpy.context.view_layer)
    assert settings["integrator"] == "LIGHT" and notes == []
    assert "light_selection" in settings   # PATH's settings as well, for the native fallback through the view's camera
    monkeypatch.setattr(schema, "viewport_integrators", lambda: ("PATH",))   # LIGHT as if it were not progressive
    scene.candela.max_bounces = 3
    settings, notes = viewport_settings(scene, bpy.context.view_layer)
    assert settings["integrator"] == "PATH" and "Light Tracing does not render progressively" in notes[0]
    assert settings["max_bounces"] == 3 and "branching_factor" in settings   # PATH's own settings, not LIGHT's


def wait_done(session, timeout=60.0):
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        status = session.status()
        if status["phase"] in ("done", "failed"):
            return status
        time.sleep(0.01)
    raise AssertionError(f"the viewport session did not finish: {session.status()}")


def test_transform_only_edit_reads_no_mesh_and_builds_no_bvh():
    scene = scenes.tiny_scene(width=32, height=24)
    cache = scene_sync.MeshCache()
    session = native.module.ViewportSession(2)
    try:
        def sync():
            depsgraph = bpy.context.evaluated_depsgraph_get()
            arrays = export_scene(depsgraph, scene.camera, mesh_reader=cache.read)
            cache.end_export()
            settings, _ = viewport_settings(scene, depsgraph.view_layer)
            settings["samples"] = 4
            session.update_scene(arrays, settings)
            view = view_camera(scene, depsgraph, SPACE, camera_view(), 32, 24, (32, 24))
            session.set_view(dict(view.params, pixel_size=1, start_resolution=4096), view.matrix)
            return wait_done(session)

        first = sync()
        assert cache.reads == 2 and first["bvh_built"] == 2 and first["bvh_reused"] == 0
        before = session.image(0)["pixels"].copy()
        bpy.data.objects["Cube"].location.x += 0.7          # transform only
        bpy.data.lights["Point"].energy *= 2.0               # and a light
        second = sync()
        assert cache.reads == 2, "a transform-only edit read a mesh again"
        assert second["bvh_built"] == 2 and second["bvh_reused"] == 2, second
        assert not np.allclose(session.image(0)["pixels"], before), "the edit did not change the image"
        bpy.data.objects["Cube"].data.vertices[1].co.z += 0.3   # geometry (a top corner): that mesh only
        cache.invalidate({"Cube"})
        third = sync()
        assert cache.reads == 3 and third["bvh_built"] == 3 and third["bvh_reused"] == 3, third
    finally:
        session.stop()


def test_images_are_read_once_across_exports(tmp_path):
    import texture_scenes as ts
    scene = ts.textured_plane_scene(str(tmp_path))
    reads = []   # images read from Blender (each read is stored in the cache)

    class Counting(scene_sync.ImageCache):
        def __setitem__(self, key, value):
            reads.append(key[0])
            super().__setitem__(key, value)

    images = Counting()

    def export():
        arrays = export_scene(bpy.context.evaluated_depsgraph_get(), scene.camera, image_cache=images)
        images.end_export()
        return arrays

    first = export()
    assert len(reads) == 1
    bpy.data.objects["Plane"].location.x += 0.1   # a transform edit: the texels come from the cache
    second = export()
    assert len(reads) == 1 and np.array_equal(first["textures_u8"], second["textures_u8"])
    image = bpy.data.images[reads[0]]
    changes = scene_sync.classify([update(image)])
    assert changes.export and changes.images == {image.name}
    images.invalidate(changes.images)              # an edited image is read again
    export()
    assert len(reads) == 2


SPACE = SimpleNamespace(camera=None, use_local_camera=False, use_render_border=False, lens=50.0, clip_start=0.01,
                        clip_end=1000.0, render_border_min_x=0.0, render_border_min_y=0.0, render_border_max_x=1.0,
                        render_border_max_y=1.0)
ZOOM_ONE = 50.0 * (2.0 - math.sqrt(2.0))   # Blender's camera-view zoom at which the frame fills the view


def camera_view(zoom=ZOOM_ONE, offset=(0.0, 0.0)):
    return SimpleNamespace(view_perspective='CAMERA', is_perspective=True, view_camera_zoom=zoom,
                           view_camera_offset=offset, view_distance=10.0, view_matrix=None)


def free_view(camera_object, perspective='PERSP', distance=10.0):
    bpy.context.view_layer.update()   # the object's matrix_world is evaluated by the depsgraph
    return SimpleNamespace(view_perspective=perspective, is_perspective=perspective == 'PERSP', view_camera_zoom=0.0,
                           view_camera_offset=(0.0, 0.0), view_distance=distance,
                           view_matrix=camera_object.matrix_world.inverted())


def viewport_image(scene, space, rv3d, width, height, samples=8):
    depsgraph = bpy.context.evaluated_depsgraph_get()
    render = scene.render
    view = view_camera(scene, depsgraph, space, rv3d, width, height, (render.resolution_x, render.resolution_y))
    settings, _ = viewport_settings(scene, depsgraph.view_layer)
    settings.update(samples=samples, pixel_filter="BOX", filter_width=1.0)
    arrays = export_scene(depsgraph, scene.camera)
    session = native.module.ViewportSession(2)
    try:
        session.update_scene(arrays, settings)
        session.set_view(dict(view.params, pixel_size=1, start_resolution=1 << 14), view.matrix)
        wait_done(session)
        image = session.image(0)
    finally:
        session.stop()
    return image


def final_image(scene, samples=8):
    depsgraph = bpy.context.evaluated_depsgraph_get()
    cam = scene.camera.evaluated_get(depsgraph)
    params = to_native_params(scene, cam.data, camera_object=cam, argv=[])
    params.update(samples=samples, pixel_filter="BOX", filter_width=1.0)
    s = native.module.Session(export_scene(depsgraph, scene.camera), params)
    s.start()
    s.join()
    assert s.error is None
    return s.get_pass("Combined").reshape(s.height, s.width, 4)


def assert_same_render(a, b):
    """Equal up to float rounding of the instanced vs flattened meshes: a few edge pixels may see another surface."""
    assert a.shape == b.shape
    close = np.isclose(a, b, rtol=1e-3, atol=1e-4).all(axis=2)
    assert close.mean() > 0.99, f"only {100 * close.mean():.1f} % of the pixels agree"


def test_camera_view_renders_what_the_camera_renders():
    scene = scenes.tiny_scene(width=40, height=30)
    image = viewport_image(scene, SPACE, camera_view(), 40, 30)
    assert (image["frame_width"], image["frame_height"], image["width"]) == (40, 30, 40)
    assert_same_render(image["pixels"], final_image(scene))


def test_camera_view_honours_zoom_offset_and_border():
    """A view twice the frame's size at zoom 1/2 (the frame fills its centre), panned, with a render border: the
    border part of the frame is exactly the final render's border window."""
    scene = scenes.tiny_scene(width=40, height=30)
    r = scene.render
    r.use_border, r.border_min_x, r.border_max_x, r.border_min_y, r.border_max_y = True, 0.25, 0.75, 0.2, 0.6
    # Blender's camera-view zoom 0: the viewplane is scaled by 2·2/(√2)² = 2, so the 40x30 frame covers 40x30
    # pixels of an 80x60 view, centred. A pan of view_camera_offset 0.25 moves the viewplane by 4·0.25·xaspect,
    # a quarter of its width (and height): the frame moves to the view's corner, where its pixels are the view's
    # pixels (and draw the same samples).
    image = viewport_image(scene, SPACE, camera_view(0.0, (0.25, 0.25)), 80, 60)
    final = final_image(scene)
    # The frame spans x ∈ [0, 40), y ∈ [0, 30) of the view; the border is x ∈ [10, 30), y ∈ [6, 18).
    assert (image["x0"], image["y0"], image["width"], image["height"]) == (10, 6, 20, 12), image
    assert_same_render(image["pixels"], final)


def test_free_perspective_view_is_the_camera_at_half_the_lens():
    """A free view of lens L on Blender's 36 mm sensor, zoomed ×2, sees what a camera of lens L/2 sees."""
    scene = scenes.tiny_scene(width=40, height=30)
    cam = scene.camera
    cam.data.lens, cam.data.sensor_width, cam.data.sensor_fit = 25.0, 36.0, 'AUTO'
    space = SimpleNamespace(**dict(vars(SPACE), lens=50.0, clip_start=cam.data.clip_start, clip_end=cam.data.clip_end))
    image = viewport_image(scene, space, free_view(cam), 40, 30)
    assert_same_render(image["pixels"], final_image(scene))


def test_orthographic_view_is_the_orthographic_camera():
    scene = scenes.tiny_scene(width=40, height=30)
    cam = scene.camera
    cam.data.type, cam.data.ortho_scale = 'ORTHO', 2.0 * 10.0 * 36.0 / 50.0   # view distance · 36 / lens, ×2
    image = viewport_image(scene, SPACE, free_view(cam, 'ORTHO', distance=10.0), 40, 30)
    assert_same_render(image["pixels"], final_image(scene))
