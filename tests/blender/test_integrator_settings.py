"""Each integrator's settings come from what the native registry publishes (core/param_spec.h): the add-on builds a
property per published setting, sends only the chosen integrator's keys, draws them in the integrator's own
sub-panels, and keeps stable enum numbers for saved .blend files."""

import bpy
import pytest

from scenes import empty_scene, ensure_addon, tiny_scene


def _modules():
    ensure_addon()
    from candela import native, params, properties, schema
    from candela.ui import render as ui_render
    return native, params, properties, schema, ui_render


def test_every_published_setting_is_a_property_with_its_default_range_and_items():
    _, _, _, schema, _ = _modules()
    rna = bpy.types.Scene.bl_rna.properties["candela"].fixed_type.properties
    for integrator, specs in schema.integrator_params().items():
        for spec in specs:
            prop = rna[spec["key"]]
            assert prop.name == spec["label"] and prop.description == spec["description"], spec["key"]
            if spec["type"] == "ENUM":
                assert [item.identifier for item in prop.enum_items] == [i[0] for i in spec["items"]]
                assert [item.value for item in prop.enum_items] == list(range(len(spec["items"])))  # stable numbers
                assert prop.default == spec["default"]
            elif spec["type"] in ("INT", "FLOAT"):
                assert prop.default == pytest.approx(spec["default"]), spec["key"]
                assert prop.hard_min == pytest.approx(spec["min"]) and prop.hard_max == pytest.approx(spec["max"])


def test_a_key_two_integrators_share_is_published_alike():
    _, _, _, schema, _ = _modules()
    seen = {}
    for integrator, specs in schema.integrator_params().items():
        for spec in specs:
            if spec["key"] in seen:
                assert spec == seen[spec["key"]], f"{integrator} publishes {spec['key']} differently"
            seen[spec["key"]] = spec


def test_the_common_settings_are_the_published_common_params():
    _, params, _, schema, _ = _modules()
    published = {spec["key"]: spec for spec in schema.common_params()}
    assert set(params.COMMON_KEYS) <= set(published)
    rna = bpy.types.Scene.bl_rna.properties["candela"].fixed_type.properties
    for key in params.COMMON_KEYS:
        spec = published[key]
        prop = rna[key]
        if spec["type"] == "ENUM":
            assert [item.identifier for item in prop.enum_items] == [i[0] for i in spec["items"]], key
        else:
            assert prop.default == pytest.approx(spec["default"]), key


def test_stable_numbers_are_reserved_for_every_planned_integrator():
    _, _, properties, schema, _ = _modules()
    numbers = properties.INTEGRATOR_NUMBERS
    for name in ("PATH", "LIGHT", "BDPT", "SURFACE_SAMPLING", "SOURCE_SHOOTING", "RECEIVER_GATHERING", "PHOTON",
                 "SPPM", "IRRADIANCE_CACHE", "MLT", "MMLT", "AUTO"):
        assert name in numbers
    assert len(set(numbers.values())) == len(numbers)
    for name, _, _ in schema.integrators():
        assert name in numbers, f"registry integrator {name} has no stable number"
    assert numbers["PATH"] == 0 and numbers["BDPT"] == 1 and numbers["MLT"] == 2   # as saved files have them


def test_auto_is_in_the_integrator_menu_with_its_stable_number_and_only_common_keys():
    _, params, properties, schema, _ = _modules()
    assert "AUTO" in [name for name, _, _ in schema.integrators()]
    rna = bpy.types.Scene.bl_rna.properties["candela"].fixed_type.properties
    items = {item.identifier: item.value for item in rna["integrator"].enum_items}
    assert items["AUTO"] == properties.INTEGRATOR_NUMBERS["AUTO"]
    # AUTO has no settings of its own: the chosen integrator's main settings come from AUTO's settings table (native
    # auto_policy.cpp), the rest stay at their defaults
    assert schema.integrator_params()["AUTO"] == []
    scene = tiny_scene(width=8, height=6, samples=1)
    scene.candela.integrator = "AUTO"
    sent = params.to_native_params(scene, scene.camera.data)
    assert sent["integrator"] == "AUTO"
    assert "light_selection" not in sent   # else AUTO would keep it, not choose PATH's light selection


def test_auto_is_told_of_an_animation_render_and_no_other_integrator_is():
    _, params, _, _, _ = _modules()
    scene = tiny_scene(width=8, height=6, samples=1)
    scene.candela.integrator = "AUTO"
    assert params.animation_params(scene.candela, True) == {"animation": True}
    assert params.animation_params(scene.candela, False) == {}   # a still, whatever the scene's frame range
    scene.candela.integrator = "PATH"
    assert params.animation_params(scene.candela, True) == {}


def test_only_the_chosen_integrators_keys_are_sent():
    _, params, _, schema, _ = _modules()
    scene = tiny_scene(width=8, height=6, samples=1)
    camera = scene.camera
    all_keys = {spec["key"] for specs in schema.integrator_params().values() for spec in specs}
    for integrator, specs in schema.integrator_params().items():
        scene.candela.integrator = integrator
        sent = params.to_native_params(scene, camera.data)
        mine = {spec["key"] for spec in specs}
        assert mine <= set(sent)
        assert not (all_keys - mine) & set(sent), f"{integrator} would receive another integrator's keys"


def test_the_chosen_integrator_has_its_sub_panels():
    _, _, _, schema, ui_render = _modules()
    labels = {cls.bl_label for cls in ui_render.classes if getattr(cls, "bl_parent_id", "") == "CANDELA_RENDER_PT_sampling"}
    groups = {spec["group"] for spec in schema.integrator_params()["PATH"] if spec["group"]}
    assert groups == {"Light Paths", "Max Bounces", "Clamping", "Caustics", "Light Sampling"} and groups <= labels
    assert ui_render.condition_holds(empty_scene().candela, "rr_mode!=OFF")
    assert not ui_render.condition_holds(empty_scene().candela, "light_selection==WARD")


def test_a_setting_outside_its_range_fails_with_its_name():
    native, params, _, _, _ = _modules()
    from candela.export import export_scene, render_camera
    scene = tiny_scene(width=8, height=6, samples=1)
    depsgraph = bpy.context.evaluated_depsgraph_get()
    arrays = export_scene(depsgraph, render_camera(scene))
    sent = params.to_native_params(scene, scene.camera.data)
    sent["max_bounces"] = 5000
    with pytest.raises(ValueError, match="max_bounces"):
        native.require().Session(arrays, sent)


def test_the_metropolis_integrators_publish_their_settings_under_their_saved_numbers():
    _, _, properties, schema, ui_render = _modules()
    items = {item[0]: item[3] for item in properties.integrator_items()}
    assert items["MLT"] == 2 and items["MMLT"] == 10
    labels = {cls.bl_label for cls in ui_render.classes if getattr(cls, "bl_parent_id", "") == "CANDELA_RENDER_PT_sampling"}
    for name in ("MLT", "MMLT"):
        specs = {spec["key"]: spec for spec in schema.integrator_params()[name]}
        assert {"max_bounces", "bdpt_mis", "mlt_large_step", "mlt_sigma", "mlt_bootstrap", "mlt_chains"} <= set(specs)
        assert specs["mlt_large_step"]["default"] == pytest.approx(0.3)
        assert specs["mlt_large_step"]["min"] == 0.0 and specs["mlt_large_step"]["max"] == 1.0
        assert specs["mlt_chains"]["min"] == 2
        assert "Metropolis" in labels


def test_light_paths_settings_an_integrator_does_not_apply_are_named_in_one_warning():
    ensure_addon()
    from candela import unsupported
    scene = tiny_scene(width=8, height=6, samples=1)
    settings = scene.candela
    settings.integrator = "BDPT"
    assert unsupported.light_paths_messages(settings) == []       # the unbiased defaults: nothing to say
    settings.clamp_indirect = 10.0
    settings.glossy_bounces = 4
    settings.filter_glossy = 1.0
    (message,) = unsupported.light_paths_messages(settings)
    assert message.startswith("Candela: BDPT does not apply")
    for part in ("Max Bounces > Glossy 4", "Clamping > Indirect Light 10", "Filter Glossy 1"):
        assert part in message, message
    settings.integrator = "PATH"                                 # PATH applies them: no warning
    assert unsupported.light_paths_messages(settings) == []
    settings.integrator = "IRRADIANCE_CACHE"
    from candela import schema
    published = {spec["key"] for spec in schema.integrator_params()["IRRADIANCE_CACHE"]}
    assert bool(unsupported.light_paths_messages(settings)) == (not {"clamp_indirect", "glossy_bounces",
                                                                      "filter_glossy"} <= published)
