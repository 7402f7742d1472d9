"""Sampling presets in the Sampling panel: artist defaults and a course setup, one click each.

- Preview: a quick, clean look (few samples and bounces, every variance-reduction technique on).
- Final: Candela's production defaults (BSDF and light sampling with MIS, the light tree, Sobol).
- Course: compare samplers: a fixed, noisy setup for comparing the samplers side by side (16 samples, a box filter,
  no stopping rule, the Noise pass on): change only the Sampler between renders.

Research switches that make renders worse (uniform hemisphere sampling, BSDF-only light sampling, the area light
pdf) stay available in their panels and say so in their tooltips; no preset turns them on.
"""

import bpy
from bpy.props import EnumProperty

# Scene settings (scene.candela) per preset; keys are property names.
PRODUCTION = {"sampler": "SOBOL", "hemisphere_sampling": "BSDF", "light_sampling": "MIS", "mis_heuristic": "POWER",
              "light_pdf": "SOLID_ANGLE", "light_selection": "TREE", "light_samples": 1, "branching_factor": 1,
              "noise_threshold": 0.0, "time_limit": 0.0, "pixel_filter": "BLACKMAN_HARRIS", "filter_width": 1.5,
              "clamp_indirect": 0.0}
PRESETS = {
    "PREVIEW": ("Preview", "Quick look: 16 samples, 4 bounces, every variance-reduction technique on",
                dict(PRODUCTION, samples=16, max_bounces=4, rr_mode="THROUGHPUT", rr_start_bounce=2,
                     viewport_samples=64)),
    "FINAL": ("Final", "Candela's production defaults: 256 samples, 12 bounces, MIS, light tree, Sobol",
              dict(PRODUCTION, samples=256, max_bounces=12, rr_mode="THROUGHPUT", rr_start_bounce=3,
                   viewport_samples=1024)),
    "COURSE_SAMPLERS": ("Course: compare samplers", "16 samples, box filter, fixed seed, no stopping rule, Noise "
                        "pass on: render once per Sampler and compare the noise",
                        dict(PRODUCTION, samples=16, max_bounces=4, rr_mode="OFF", rr_start_bounce=3,
                             sampler="RANDOM", seed=0, use_animated_seed=False, pixel_filter="BOX",
                             filter_width=1.0)),
}
VIEW_LAYER = {"COURSE_SAMPLERS": {"use_pass_noise": True}}   # view_layer.candela settings


def apply_preset(scene, view_layer, name):
    """Set the preset's values (unknown keys raise: the table must follow properties.py)."""
    settings = scene.candela
    for key, value in PRESETS[name][2].items():
        if not hasattr(settings, key):
            raise AttributeError(f"preset {name}: scene.candela has no setting '{key}'")
        setattr(settings, key, value)
    if view_layer is not None:
        for key, value in VIEW_LAYER.get(name, {}).items():
            setattr(view_layer.candela, key, value)


class CANDELA_OT_sampling_preset(bpy.types.Operator):
    """Apply a Candela sampling preset"""
    bl_idname = "candela.sampling_preset"
    bl_label = "Apply Sampling Preset"
    bl_options = {'REGISTER', 'UNDO'}

    preset: EnumProperty(name="Preset", items=[(k, v[0], v[1]) for k, v in PRESETS.items()])

    def execute(self, context):
        apply_preset(context.scene, context.view_layer, self.preset)
        return {'FINISHED'}


class CANDELA_MT_sampling_presets(bpy.types.Menu):
    bl_label = "Sampling Presets"

    def draw(self, context):
        for key, (label, _, _) in PRESETS.items():
            self.layout.operator(CANDELA_OT_sampling_preset.bl_idname, text=label).preset = key


def draw_presets(panel, context):
    """Prepended to the Sampling panel (an added draw function: the panel's own body is untouched)."""
    panel.layout.menu(CANDELA_MT_sampling_presets.__name__, text="Presets", icon='PRESET')


classes = (CANDELA_OT_sampling_preset, CANDELA_MT_sampling_presets)


def register():
    bpy.types.CANDELA_RENDER_PT_sampling.prepend(draw_presets)


def unregister():
    bpy.types.CANDELA_RENDER_PT_sampling.remove(draw_presets)
