"""The UI details issue 20 found in the GUI: spot and area shape in Candela's light panel, Simplify after Sampling,
the viewport's own sample limit, previews, one Shift+A list generated from the exporter's tables, the noise stop's own name, teaching options
marked as such and the sampling presets."""

from types import SimpleNamespace

import bpy
import nodeitems_utils

import scenes


class FakeLayout:
    """Records the properties a panel's draw() shows (background mode has no UI to draw into)."""

    def __init__(self, record=None):
        self.props = record if record is not None else []
        self.use_property_split = self.use_property_decorate = self.active = False

    def prop(self, owner, name, **kwargs):
        self.props.append(name)

    def column(self, **kwargs):
        return FakeLayout(self.props)

    row = column

    def separator(self, **kwargs):
        pass

    def label(self, **kwargs):
        pass

    def menu(self, *args, **kwargs):
        self.props.append(("menu", args[0]))


def drawn(panel_cls, context):
    panel = SimpleNamespace(layout=FakeLayout())
    panel_cls.draw(panel, context)
    return panel.layout.props


def light_context(kind, shape='SQUARE'):
    light = bpy.data.lights.new(f"L_{kind}", kind)
    if kind == 'AREA':
        light.shape = shape
    return SimpleNamespace(engine='CANDELA', light=light)


def test_spot_shape_is_drawn_under_candelas_light_panel():
    scenes.ensure_addon()
    spot = light_context('SPOT')
    assert bpy.types.CANDELA_LIGHT_PT_spot.bl_parent_id == "CANDELA_LIGHT_PT_light"
    assert bpy.types.CANDELA_LIGHT_PT_spot.poll(spot)
    assert not bpy.types.CANDELA_LIGHT_PT_spot.poll(light_context('POINT'))
    assert drawn(bpy.types.CANDELA_LIGHT_PT_spot, spot) == ["spot_size", "spot_blend", "show_cone"]
    # Blender's own spot panel hangs off EEVEE's light panel: not offered for Candela.
    assert "CANDELA" not in bpy.types.DATA_PT_spot.COMPAT_ENGINES


def test_area_shape_is_inside_the_light_panel_not_above_it():
    scenes.ensure_addon()
    square = drawn(bpy.types.CANDELA_LIGHT_PT_light, light_context('AREA', 'SQUARE'))
    assert square[-2:] == ["shape", "size"]
    rect = drawn(bpy.types.CANDELA_LIGHT_PT_light, light_context('AREA', 'RECTANGLE'))
    assert rect[-3:] == ["shape", "size", "size_y"]
    assert "CANDELA" not in bpy.types.DATA_PT_area.COMPAT_ENGINES


def test_simplify_comes_after_sampling():
    scenes.ensure_addon()
    from candela.ui import render
    names = [c.__name__ for c in render.classes]
    assert names.index("CANDELA_RENDER_PT_simplify") > names.index("CANDELA_RENDER_PT_sampling")
    for name in ("RENDER_PT_simplify", "RENDER_PT_simplify_viewport", "RENDER_PT_simplify_render"):
        assert "CANDELA" not in getattr(bpy.types, name).COMPAT_ENGINES, name
    body = drawn(bpy.types.CANDELA_RENDER_PT_simplify, SimpleNamespace(scene=bpy.context.scene))
    assert "simplify_subdivision" in body and "simplify_subdivision_render" in body


def test_viewport_samples_are_their_own_setting_in_the_sampling_panel():
    """The Rendered viewport's sample limit is its own value (as Cycles' Viewport samples), drawn in a Viewport
    sub-panel of Sampling with the start resolution and Blender's pixel size, and the viewport reads it (not the
    final render's samples)."""
    scenes.ensure_addon()
    from candela.viewport.render import viewport_settings
    panel = bpy.types.CANDELA_RENDER_PT_sampling_viewport
    assert panel.bl_parent_id == "CANDELA_RENDER_PT_sampling"
    scene = scenes.tiny_scene(samples=7)
    assert drawn(panel, SimpleNamespace(scene=scene)) == ["viewport_samples", "viewport_start_resolution",
                                                          "preview_pixel_size"]
    scene.candela.viewport_samples = 33
    assert viewport_settings(scene, bpy.context.view_layer)[0]["samples"] == 33
    assert scene.candela.samples == 7


def test_previews_and_material_preview_shading():
    scenes.ensure_addon()
    engine = bpy.types.RenderEngine.bl_rna_get_subclass_py("CANDELA")
    assert engine.bl_use_preview and engine.bl_use_eevee_viewport
    assert "CANDELA" in bpy.types.MATERIAL_PT_preview.COMPAT_ENGINES
    assert "CANDELA" in bpy.types.DATA_PT_preview.COMPAT_ENGINES
    ctx = SimpleNamespace(engine='CANDELA', world=bpy.data.worlds.new("W"))
    assert bpy.types.CANDELA_WORLD_PT_preview.poll(ctx)


def shader_context(engine, shader_type):
    space = SimpleNamespace(type='NODE_EDITOR', tree_type='ShaderNodeTree', shader_type=shader_type, edit_tree=None)
    return SimpleNamespace(engine=engine, space_data=space)


def visible_categories(context):
    """(category name, node types) of every registered shader category Shift+A shows in `context`."""
    out = []
    for cats in nodeitems_utils._node_categories.values():
        for cat in cats[0]:
            if cat.poll(context):
                out.append((cat.name, [i.nodetype for i in cat.items(context) if hasattr(i, "nodetype")]))
    return out


def test_shift_a_lists_each_category_once():
    scenes.ensure_addon()
    for shader_type in ('OBJECT', 'WORLD'):
        names = [name for name, _ in visible_categories(shader_context('CANDELA', shader_type))]
        assert len(names) == len(set(names)), names
        assert "Shader" in names and "Converter" in names
    # Other engines keep Blender's own menu, without Candela's.
    cycles = [name for name, _ in visible_categories(shader_context('CYCLES', 'OBJECT'))]
    assert len(cycles) == len(set(cycles)) and "Shader" in cycles


def test_shift_a_lists_what_the_exporter_supports():
    scenes.ensure_addon()
    from candela.export.materials import SUPPORTED_SHADER_NODES
    from candela.export.shader_nodes import SUPPORTED_INPUT_NODES
    material = [n for _, nodes in visible_categories(shader_context('CANDELA', 'OBJECT')) for n in nodes]
    world = [n for _, nodes in visible_categories(shader_context('CANDELA', 'WORLD')) for n in nodes]
    for node in ("ShaderNodeMapping", "ShaderNodeInvert", "ShaderNodeCombineColor", "ShaderNodeSeparateColor",
                 "ShaderNodeCombineXYZ", "ShaderNodeSeparateXYZ", "ShaderNodeClamp", "ShaderNodeRGB",
                 "ShaderNodeBsdfPrincipled", "ShaderNodeHoldout", "ShaderNodeOutputMaterial"):
        assert node in material, node
    assert "ShaderNodeBackground" in world and "ShaderNodeTexEnvironment" in world
    assert "ShaderNodeBackground" not in material and "ShaderNodeBsdfPrincipled" not in world
    # Nothing the exporter cannot read is offered; everything offered is offered once per list.
    supported = set(SUPPORTED_SHADER_NODES) | set(SUPPORTED_INPUT_NODES) | {
        "ShaderNodeOutputMaterial", "ShaderNodeOutputWorld", "ShaderNodeBackground", "NodeFrame", "NodeReroute"}
    assert set(material) <= supported, set(material) - supported
    # main's procedural textures and Bump are offered now that the exporter reads them; volumes and hair are not.
    assert "ShaderNodeTexNoise" in material and "ShaderNodeBump" in material
    assert "ShaderNodeVolumePrincipled" not in material and "ShaderNodeBsdfHair" not in material
    counts = {}
    for n in material:
        counts[n] = counts.get(n, 0) + 1
    assert all(c == 1 or n == "ShaderNodeMix" for n, c in counts.items()), counts   # Mix: Color and Converter


def test_noise_stop_has_its_own_name():
    scenes.ensure_addon()
    prop = bpy.types.Scene.bl_rna.properties["candela"].fixed_type.bl_rna.properties["noise_threshold"]
    assert prop.name != "Noise Threshold"
    assert "whole image" in prop.description and "Cycles" in prop.description and "per-pixel" in prop.description


def test_teaching_options_are_marked_and_not_defaults():
    scenes.ensure_addon()
    props = bpy.types.Scene.bl_rna.properties["candela"].fixed_type.bl_rna.properties
    for prop, item in (("hemisphere_sampling", "UNIFORM"), ("light_sampling", "BSDF_ONLY"), ("light_pdf", "AREA")):
        assert "Teaching option" in props[prop].enum_items[item].description, (prop, item)
        assert props[prop].default != item


def test_presets_apply_and_name_real_settings():
    scene = scenes.empty_scene()
    from candela.ui import presets
    assert [v[0] for v in presets.PRESETS.values()] == ["Preview", "Final", "Course: compare samplers"]
    for name in presets.PRESETS:
        bpy.ops.candela.sampling_preset(preset=name)
        for key, value in presets.PRESETS[name][2].items():
            got = getattr(scene.candela, key)
            assert (abs(got - value) < 1e-6) if isinstance(value, float) else got == value, (name, key)
    assert scene.candela.sampler == 'RANDOM' and bpy.context.view_layer.candela.use_pass_noise
    bpy.ops.candela.sampling_preset(preset='FINAL')
    assert scene.candela.hemisphere_sampling == 'BSDF' and scene.candela.light_sampling == 'MIS'
