"""Motion blur export (addon/candela/export/motion.py, docs/light_paths.md "Motion blur"): the shutter's sample
times for each Position as Cycles 3.4 places them, the instances' and camera's transforms sampled there, the frame
restored afterwards, and a render of a moving scene through the whole add-on."""

import bpy
import numpy as np

import scenes
from fake_engine import FakeEngine


def moving_scene(position="CENTER", steps=1, camera_moves=False):
    scene = scenes.tiny_scene(width=16, height=12, samples=2)
    slider = scenes.link(scene, bpy.data.objects.new("Slider", scenes.cube_mesh("Slider", 0.3)))
    slider.data.materials.append(scenes.diffuse_material("Red", (0.8, 0.2, 0.2)))
    for frame in (0, 10):   # x = frame / 2, linear
        slider.location = (frame / 2.0, 1.0, 0.3)
        slider.keyframe_insert("location", frame=frame)
    for kp in slider.animation_data.action.fcurves[0].keyframe_points:
        kp.interpolation = "LINEAR"
    slider.cycles.motion_steps = steps
    if camera_moves:
        cam = scene.camera
        for frame, z in ((0, 2.0), (10, 4.0)):
            cam.location = (0.0, -6.0, z)
            cam.keyframe_insert("location", frame=frame)
        for fc in cam.animation_data.action.fcurves:
            for kp in fc.keyframe_points:
                kp.interpolation = "LINEAR"
    scene.frame_set(4)
    scene.render.use_motion_blur = True
    scene.render.motion_blur_shutter = 0.5
    scene.cycles.motion_blur_position = position
    return scene


def export_with_motion(scene):
    from candela.export import export_scene, render_camera
    from candela.export.motion import motion_arrays
    depsgraph = bpy.context.evaluated_depsgraph_get()
    motion = {}
    names = {}
    camera = render_camera(scene)
    arrays = export_scene(depsgraph, camera, names=names, motion=motion)
    engine = FakeEngine()
    arrays.update(motion_arrays(engine, depsgraph, camera, motion["keys"], motion["steps"],
                                arrays["instance_transform"]))
    return arrays, names, engine


def test_shutter_offsets_follow_cycles_position():
    from candela.export.motion import shutter_offsets
    scene = moving_scene()
    for position, expected in (("CENTER", [-0.25, 0.0, 0.25]), ("START", [0.0, 0.25, 0.5]),
                               ("END", [-0.5, -0.25, 0.0])):
        scene.cycles.motion_blur_position = position
        assert np.allclose(shutter_offsets(scene, 3), expected), position


def test_objects_are_sampled_over_the_shutter_and_the_frame_is_restored():
    for position, steps, xs in (("CENTER", 1, [1.875, 2.0, 2.125]), ("START", 1, [2.0, 2.125, 2.25]),
                                ("CENTER", 2, [1.875, 1.9375, 2.0, 2.0625, 2.125])):
        scene = moving_scene(position, steps)
        arrays, names, engine = export_with_motion(scene)
        motion = arrays["instance_motion"]
        slider = names["instance"].index("object 'Slider'")
        assert motion.shape == (len(arrays["instance_mesh"]), len(xs), 4, 4)
        assert np.allclose(motion[slider, :, 0, 3], xs, atol=1e-5), (position, motion[slider, :, 0, 3])
        for i in range(len(motion)):   # the others stay still: their exported transform at every step
            if i != slider:
                assert np.array_equal(motion[i], np.repeat(arrays["instance_transform"][i][None], len(xs), 0))
        assert scene.frame_current == 4 and scene.frame_subframe == 0.0
        assert engine.frames[-1] == (4, 0.0)
        assert "camera_motion" not in arrays   # the camera does not move


def test_unticked_objects_and_motion_blur_off_stay_still():
    scene = moving_scene()
    bpy.data.objects["Slider"].cycles.use_motion_blur = False
    bpy.data.objects["Camera"].cycles.use_motion_blur = False
    arrays, _, _ = export_with_motion(scene)
    assert "instance_motion" not in arrays and "camera_motion" not in arrays
    scene.render.use_motion_blur = False
    bpy.data.objects["Slider"].cycles.use_motion_blur = True
    arrays, _, engine = export_with_motion(scene)
    assert "instance_motion" not in arrays and not getattr(engine, "frames", [])


def test_camera_motion_is_sampled():
    scene = moving_scene(camera_moves=True)
    arrays, _, _ = export_with_motion(scene)
    cam = arrays["camera_motion"]
    assert cam.shape == (3, 4, 4)
    # z = 2 + frame / 5 at frames 3.75, 4, 4.25.
    assert np.allclose(cam[:, 2, 3], [2.75, 2.8, 2.85], atol=1e-5), cam[:, 2, 3]


def test_a_moving_scene_renders_without_warnings():
    from candela import render_loop
    moving_scene(camera_moves=True)
    engine = FakeEngine()
    render_loop.render_frame(engine, bpy.context.evaluated_depsgraph_get(), background=True)
    warnings = [m for kind, m in engine.reports if kind == {'WARNING'}]
    errors = [m for kind, m in engine.reports if kind == {'ERROR'}]
    assert errors == [] and warnings == [], (errors, warnings)
    assert engine.result.layers[0].passes[0].rect.data is not None
    assert engine.frames[-1] == (4, 0.0)
