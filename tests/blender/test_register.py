"""The add-on registers and unregisters cleanly, twice in a row."""

import addon_utils
import bpy

from scenes import empty_scene, engine_available, ensure_addon


def test_engine_is_registered():
    ensure_addon()
    assert engine_available()
    assert hasattr(bpy.types.Scene, "candela")
    assert hasattr(bpy.types, "CANDELA_RENDER_PT_sampling")


def test_register_unregister_twice():
    ensure_addon()
    for _ in range(2):
        addon_utils.disable("candela", default_set=True)
        assert not engine_available()
        assert not hasattr(bpy.types.Scene, "candela")
        assert "CANDELA" not in bpy.types.RENDER_PT_format.COMPAT_ENGINES
        addon_utils.enable("candela", default_set=True)
        assert engine_available()
        assert hasattr(bpy.types.Scene, "candela")
        assert "CANDELA" in bpy.types.RENDER_PT_format.COMPAT_ENGINES
        assert "CANDELA" not in bpy.types.DATA_PT_light.COMPAT_ENGINES   # replaced by Candela's light panel


def test_native_module_loaded():
    import candela.native as native
    ensure_addon()
    assert native.module is not None, native.error
    assert native.module.ABI_VERSION == native.ABI_VERSION


def test_properties_defaults():
    settings = empty_scene().candela
    assert settings.samples == 64
    assert settings.max_bounces == 12
    assert settings.rr_start_bounce == 3
    assert settings.seed == 0
    assert settings.pixel_filter == 'BLACKMAN_HARRIS'
    assert abs(settings.filter_width - 1.5) < 1e-6
    assert settings.integrator == 'PATH'
