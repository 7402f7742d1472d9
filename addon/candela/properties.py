"""Candela's scene settings (`scene.candela`). Names equal the native params keys."""

import bpy
from bpy.props import BoolProperty, EnumProperty, FloatProperty, IntProperty, PointerProperty

from . import schema

# Stable enum numbers: saved .blend files store the number, so never renumber.
PIXEL_FILTERS = [
    ("BOX", "Box", "Box filter: every sample counts fully inside one pixel", 0),
    ("GAUSSIAN", "Gaussian", "Gaussian filter", 1),
    ("BLACKMAN_HARRIS", "Blackman-Harris", "Blackman-Harris filter, Cycles' default", 2),
]
SAMPLERS = [
    ("RANDOM", "Random", "Independent uniform random samples", 0),
    ("STRATIFIED", "Stratified (jittered)", "One jittered sample per stratum, strata shuffled per dimension", 1),
    ("NROOKS", "N-Rooks", "Latin hypercube: one sample per row and per column of every 2-D dimension", 2),
    ("HALTON", "Halton", "Halton sequence (prime bases), Owen-scrambled per pixel", 3),
    ("HAMMERSLEY", "Hammersley", "Hammersley point set for the sample count, Owen-scrambled per pixel", 4),
    ("SOBOL", "Sobol (Owen)", "Owen-scrambled, shuffled Sobol (0,2)-sequence per dimension pair", 5),
]
# Every integrator identifier the add-on knows, with its stable number (saved .blend files store the number, so
# never renumber). Numbers are reserved for the integrators the native registry does not have yet, so a file saved
# with one of them keeps its choice once it exists.
INTEGRATOR_NUMBERS = {"PATH": 0, "BDPT": 1, "MLT": 2, "PHOTON": 3, "IRRADIANCE_CACHE": 4, "LIGHT": 5,
                      "SURFACE_SAMPLING": 6, "SOURCE_SHOOTING": 7, "RECEIVER_GATHERING": 8, "SPPM": 9, "MMLT": 10,
                      "AUTO": 11}


def integrator_items():
    """Enum items from the native registry, so the UI never offers an integrator the build lacks."""
    items = []
    for i, (name, description, label) in enumerate(schema.integrators()):
        items.append((name, label, description or f"Render with the {label} integrator",
                      INTEGRATOR_NUMBERS.get(name, 100 + i)))
    return items


def integrator_settings():
    """{key: spec} of every integrator's own published settings (capabilities()["integrator_params"]); a key two
    integrators share (max_bounces, say) is one property, which must then be published alike by both."""
    settings = {}
    for specs in schema.integrator_params().values():
        for spec in specs:
            settings.setdefault(spec["key"], spec)
    return settings


def property_from_spec(spec):
    """The Blender property of one published setting: its label, description, default and range; an enum's items
    keep their published order as their numbers."""
    common = {"name": spec["label"], "description": spec["description"]}
    kind = spec["type"]
    if kind == "BOOL":
        return BoolProperty(default=bool(spec["default"]), **common)
    if kind == "INT":
        return IntProperty(default=int(spec["default"]), min=int(spec["min"]), max=int(spec["max"]),
                           soft_max=int(spec["soft_max"]), **common)
    if kind == "FLOAT":
        return FloatProperty(default=float(spec["default"]), min=float(spec["min"]), max=float(spec["max"]),
                             soft_max=float(spec["soft_max"]), **common)
    if kind == "ENUM":
        items = [(ident, label, description, i) for i, (ident, label, description) in enumerate(spec["items"])]
        return EnumProperty(items=items, default=spec["default"], **common)
    raise ValueError(f"published setting {spec['key']} has unknown type {kind}")


class CandelaRenderSettings(bpy.types.PropertyGroup):
    samples: IntProperty(name="Samples", description="Samples per pixel", default=64, min=1, soft_max=4096)
    seed: IntProperty(name="Seed", description="The image depends only on the seed, pixel and sample index",
                      default=0, min=0)
    use_animated_seed: BoolProperty(name="Animated Seed", description="Add the frame number to the seed",
                                    default=False)
    sampler: EnumProperty(name="Sampler", description="Pattern of the sample values drawn per pixel",
                          items=SAMPLERS, default="SOBOL")
    pixel_filter: EnumProperty(name="Pixel Filter", items=PIXEL_FILTERS, default="BLACKMAN_HARRIS")
    filter_width: FloatProperty(name="Filter Width", description="Pixel filter width in pixels", default=1.5,
                                min=0.01, soft_max=10.0, subtype='PIXEL')
    time_limit: FloatProperty(
        name="Time Limit", description="Stop rendering after this many seconds (after export and scene build), "
        "even if not all samples are done; 0 = no limit. Renders then differ between machines", default=0.0,
        min=0.0, soft_max=3600.0, subtype='TIME_ABSOLUTE', unit='TIME_ABSOLUTE')
    noise_threshold: FloatProperty(
        name="Image Noise Stop", description="Stop the whole render once the estimated relative error (RMSE / "
        "mean) of the whole image is below this, with a confidence margin; 0 = off. Checked from 16 samples per "
        "pixel on. Not Cycles' Noise Threshold, which is per-pixel adaptive sampling (typically 0.01): here 0.01 "
        "asks for 1 % error over the whole image, a long render", default=0.0, min=0.0, max=0.5,
        soft_max=0.1, precision=3, step=0.1)
    viewport_samples: IntProperty(
        name="Viewport Samples", description="Samples per pixel the Rendered viewport refines to; 0 = until the "
        "view changes", default=1024, min=0, soft_max=4096)
    viewport_start_resolution: IntProperty(
        name="Start Resolution", description="After a change the viewport first renders with at most this many "
        "pixels across (squared: in total), then doubles the resolution up to the full view, so moving the view "
        "shows an image at once", default=64, min=8, max=16384, subtype='PIXEL')
    # integrator and the integrators' own settings: added in register(), from the native module loaded by then


class CandelaViewLayerSettings(bpy.types.PropertyGroup):
    use_pass_albedo: BoolProperty(
        name="Albedo", description="Directional albedo (reflectance) of the first surface the camera sees, averaged "
        "over the pixel's samples (pass 'Albedo', for denoisers and compositing)", default=False)
    use_pass_noise: BoolProperty(
        name="Noise", description="Per-pixel estimated standard error of the pixel's luminance (pass 'Noise')",
        default=False)
    use_pass_ic_records: BoolProperty(
        name="IC Records", description="Irradiance Cache integrator: how many cache records each pixel's paths "
        "made (pass 'IC Records'), to see where the cache spends its work; 0 for the other integrators",
        default=False)


def register():
    items = integrator_items()
    CandelaRenderSettings.__annotations__["integrator"] = EnumProperty(
        name="Integrator", description="Light transport algorithm", items=items,
        default="PATH" if any(i[0] == "PATH" for i in items) else items[0][0])
    for key, spec in integrator_settings().items():
        CandelaRenderSettings.__annotations__[key] = property_from_spec(spec)
    bpy.utils.register_class(CandelaRenderSettings)
    bpy.types.Scene.candela = PointerProperty(type=CandelaRenderSettings, name="Candela Render Settings")
    bpy.utils.register_class(CandelaViewLayerSettings)
    bpy.types.ViewLayer.candela = PointerProperty(type=CandelaViewLayerSettings, name="Candela View Layer Settings")


def unregister():
    del bpy.types.ViewLayer.candela
    bpy.utils.unregister_class(CandelaViewLayerSettings)
    del bpy.types.Scene.candela
    bpy.utils.unregister_class(CandelaRenderSettings)
