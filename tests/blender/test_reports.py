"""What a render tells the user: settings Candela ignores (once per render, by name), the latest warning in the
status line while the render runs and in the render window's header after it, Candela's own memory figure; and renders and previews keep their reports apart."""

import bpy

import scenes
from fake_engine import FakeEngine


class RecordingEngine(FakeEngine):
    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.memory = []

    def update_memory_stats(self, memory_used=0.0, memory_peak=0.0):
        self.memory.append((memory_used, memory_peak))


class PreviewEngine(RecordingEngine):
    is_preview = True


def render(engine=None):
    from candela import render_loop
    engine = engine or RecordingEngine()
    render_loop.render_frame(engine, bpy.context.evaluated_depsgraph_get(), background=True)
    return engine


def warnings_of(engine):
    return [m for kind, m in engine.reports if kind == {'WARNING'}]


def add_linked_output(material, socket_name):
    nodes, links = material.node_tree.nodes, material.node_tree.links
    source = nodes.new("ShaderNodeVolumePrincipled" if socket_name == "Volume" else "ShaderNodeDisplacement")
    out = source.outputs[0]
    links.new(out, nodes["Material Output"].inputs[socket_name])


def test_ignored_settings_are_named_once_per_render():
    scene = scenes.tiny_scene(width=16, height=12, samples=1)
    scene.render.use_motion_blur = True
    scene.cycles.rolling_shutter_type = 'TOP'   # motion blur renders; its rolling shutter does not
    layer = bpy.context.view_layer
    layer.material_override = bpy.data.materials["Grey"]
    layer.use_pass_mist = layer.use_pass_diffuse_color = layer.use_pass_emit = True
    add_linked_output(bpy.data.materials["Grey"], "Volume")
    add_linked_output(bpy.data.materials["Grey"], "Displacement")
    bpy.data.materials["Grey"].cycles.displacement_method = 'BOTH'   # true displacement, which Candela does not do
    hair = bpy.data.objects["Plane"].modifiers.new("Hair", 'PARTICLE_SYSTEM')
    hair.particle_system.settings.type = 'HAIR'
    volume = scenes.link(scene, bpy.data.objects.new("Smoke", bpy.data.volumes.new("Smoke")))
    assert volume.type == 'VOLUME'
    warnings = warnings_of(render())
    expected = ["Rolling Shutter", "Material Override 'Grey'", "Mist pass", "Diffuse Color pass", "Emit pass",
                "material 'Grey': the Volume output", "material 'Grey': the Displacement output's true displacement",
                "hair particle system 'Hair'", "object 'Smoke' is a volume"]
    for text in expected:
        matching = [w for w in warnings if text in w]
        assert len(matching) == 1, (text, warnings)


def test_bump_through_the_displacement_output_is_rendered_and_not_reported():
    """Candela renders the Displacement output as bump mapping (Cycles' Bump Only, the default method): no warning;
    only true displacement is reported, once."""
    scenes.tiny_scene(width=16, height=12, samples=1)
    material = bpy.data.materials["Grey"]
    add_linked_output(material, "Displacement")
    assert material.cycles.displacement_method == 'BUMP'
    assert not [w for w in warnings_of(render()) if "isplacement" in w]
    material.cycles.displacement_method = 'DISPLACEMENT'
    reported = [w for w in warnings_of(render()) if "isplacement" in w]
    assert len(reported) == 1 and "Displacement Only" in reported[0] and "bump mapping only" in reported[0], reported


def test_a_plain_scene_has_no_such_warnings():
    scenes.tiny_scene(width=16, height=12, samples=1)
    assert warnings_of(render()) == []


def test_latest_warning_stays_in_the_status_line_and_memory_is_candelas():
    scene = scenes.tiny_scene(width=16, height=12, samples=1)
    scene.render.use_motion_blur = True
    scene.cycles.rolling_shutter_type = 'TOP'
    bpy.context.view_layer.use_pass_mist = True
    engine = render()
    final = engine.stats[-1]
    assert "Sample 1/1" in final and "Mist pass" in final and "(+1 more in the Info editor)" in final
    assert engine.memory and engine.memory[-1][0] > 0.0   # scene + film, in MB


def test_latest_warning_stays_in_the_header_after_the_render():
    """Blender's summary line after a render ends with the render result's message (error_set): the latest
    warning; a render without warnings, a preview and a background render (no window) set none."""
    from candela import render_loop
    scene = scenes.tiny_scene(width=16, height=12, samples=1)
    clean = RecordingEngine()
    render_loop.render_frame(clean, bpy.context.evaluated_depsgraph_get(), background=False)
    assert clean.error is None
    scene.render.use_motion_blur = True           # motion blur renders; its rolling shutter is reported
    scene.cycles.rolling_shutter_type = 'TOP'
    bpy.context.view_layer.use_pass_mist = True
    engine = RecordingEngine()
    render_loop.render_frame(engine, bpy.context.evaluated_depsgraph_get(), background=False)
    latest = warnings_of(engine)[-1]
    assert engine.error == latest + " (+1 more in the Info editor)", (engine.error, warnings_of(engine))
    assert render().error is None   # background=True
    preview = PreviewEngine()
    render_loop.render_frame(preview, bpy.context.evaluated_depsgraph_get(), background=False)
    assert preview.error is None


def test_previews_are_cheap_and_never_touch_the_final_render_record():
    from candela import render_loop
    scene = scenes.tiny_scene(width=16, height=12, samples=3)
    render()
    final_record = render_loop.last_render_stats
    assert final_record["samples_done"] == 3
    scene.render.use_motion_blur = True   # a preview's scene is Blender's own: no ignored-settings warnings
    preview = render(PreviewEngine())
    assert render_loop.last_render_stats is final_record   # untouched by the preview
    assert warnings_of(preview) == []
    assert any("Sample 32/32" in s for s in preview.stats), preview.stats   # PREVIEW_PARAMS


def test_each_render_has_its_own_warnings():
    scene = scenes.tiny_scene(width=16, height=12, samples=1)
    scene.render.use_motion_blur = True
    scene.cycles.rolling_shutter_type = 'TOP'
    first = render()
    scene.render.use_motion_blur = False
    second = render()
    from candela import render_loop
    assert any("Rolling Shutter" in w for w in warnings_of(first))
    assert render_loop.last_render_stats["warnings"] == [] and warnings_of(second) == []
