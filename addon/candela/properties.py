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
INTEGRATOR_NUMBERS = {"PATH": 0, "BDPT": 1, "MLT": 2, "PHOTON": 3, "IRRADIANCE_CACHE": 4}
INTEGRATOR_LABELS = {"PATH": "Path Tracing", "BDPT": "Bidirectional", "MLT": "Metropolis",
                     "PHOTON": "Photon Mapping", "IRRADIANCE_CACHE": "Irradiance Cache"}


def integrator_items():
    """Enum items from the native registry, so the UI never offers an integrator the build lacks."""
    items = []
    for i, (name, description) in enumerate(schema.integrators()):
        label = INTEGRATOR_LABELS.get(name, name.replace("_", " ").title())
        items.append((name, label, description or f"Render with the {label} integrator",
                      INTEGRATOR_NUMBERS.get(name, 100 + i)))
    return items


HEMISPHERE_SAMPLING = [
    ("UNIFORM", "Uniform", "Continue paths in uniformly distributed directions over the hemisphere. Teaching "
     "option: noisier than BSDF sampling at the same cost", 0),
    ("COSINE", "Cosine", "Continue paths cosine-weighted over the hemisphere", 1),
    ("BSDF", "BSDF", "Continue paths proportionally to the BSDF times the cosine (importance sampling)", 2),
]
LIGHT_SAMPLING = [
    ("BSDF_ONLY", "BSDF Only", "Direct light only where continuation rays hit emitters (point, spot and sun "
     "lights are still light-sampled: no ray can hit them). Teaching option: much noisier than Multiple "
     "Importance for small lights", 0),
    ("LIGHT_ONLY", "Light Only", "Direct light only by next-event estimation (shadow rays to sampled lights)", 1),
    ("MIS", "Multiple Importance", "Both, combined by multiple importance sampling", 2),
]
MIS_HEURISTICS = [
    ("BALANCE", "Balance", "Balance heuristic (Veach 1997, eq. 9.12)", 0),
    ("POWER", "Power", "Power heuristic with exponent 2 (Veach 1997, eq. 9.13)", 1),
]
LIGHT_PDFS = [
    ("AREA", "Area", "Sample points uniformly on the emitter's area. Teaching option: noisier than Solid "
     "Angle for nearby lights", 0),
    ("SOLID_ANGLE", "Solid Angle", "Sample directions uniformly in the solid angle the emitter covers "
     "(spherical triangles and rectangles), with area sampling for tiny and huge solid angles", 1),
]
LIGHT_SELECTIONS = [
    ("ALL", "All", "Estimate every light at every vertex (one shadow ray per light)", 0),
    ("UNIFORM", "Uniform", "Pick one light uniformly", 1),
    ("AREA", "Area", "Pick one light in proportion to its emitting area", 2),
    ("POWER", "Power", "Pick one light in proportion to its power", 3),
    ("TREE", "Light Tree", "Pick one light by a light hierarchy with bounds and orientation cones "
     "(favours nearby, facing, bright lights; scales to thousands of emitters)", 4),
    ("WARD", "Ward", "Pick lights in proportion to their maximum possible contribution at the point (Ward 1991)", 5),
]
RR_MODES = [
    ("OFF", "Off", "No Russian roulette: paths end at Max Bounces only", 0),
    ("THROUGHPUT", "Throughput", "Survival probability from the path throughput", 1),
    ("ALBEDO", "Albedo", "Survival probability from the surface's reflectance", 2),
    ("SQRT_THROUGHPUT", "Square Root Throughput",
     "Cycles' rule: on arrival at a vertex, continue with probability √(max throughput); "
     "paths live longer than with Throughput. Cycles' Min Light Bounces m matches Russian Roulette From m + 2", 3),
]


class CandelaRenderSettings(bpy.types.PropertyGroup):
    samples: IntProperty(name="Samples", description="Samples per pixel", default=64, min=1, soft_max=4096)
    max_bounces: IntProperty(name="Max Bounces", description="Maximum path length; 0 = direct light only",
                             default=12, min=0, max=1024)
    rr_start_bounce: IntProperty(name="Russian Roulette From", description="Russian roulette from this bounce on",
                                 default=3, min=0, max=1024)
    seed: IntProperty(name="Seed", description="The image depends only on the seed, pixel and sample index",
                      default=0, min=0)
    use_animated_seed: BoolProperty(name="Animated Seed", description="Add the frame number to the seed",
                                    default=False)
    sampler: EnumProperty(name="Sampler", description="Pattern of the sample values drawn per pixel",
                          items=SAMPLERS, default="SOBOL")
    pixel_filter: EnumProperty(name="Pixel Filter", items=PIXEL_FILTERS, default="BLACKMAN_HARRIS")
    filter_width: FloatProperty(name="Filter Width", description="Pixel filter width in pixels", default=1.5,
                                min=0.01, soft_max=10.0, subtype='PIXEL')
    hemisphere_sampling: EnumProperty(name="Hemisphere Sampling", items=HEMISPHERE_SAMPLING, default="BSDF",
                                      description="How continuation directions are drawn (delta lobes always "
                                      "use the BSDF)")
    light_sampling: EnumProperty(name="Light Sampling", items=LIGHT_SAMPLING, default="MIS",
                                 description="Which estimators of direct light are used")
    mis_heuristic: EnumProperty(name="MIS Heuristic", items=MIS_HEURISTICS, default="POWER")
    light_pdf: EnumProperty(name="Light PDF", items=LIGHT_PDFS, default="SOLID_ANGLE",
                            description="How a point on an area light or emissive triangle is chosen")
    light_selection: EnumProperty(name="Light Selection", items=LIGHT_SELECTIONS, default="TREE",
                                  description="How next-event estimation chooses among many lights")
    ward_threshold: FloatProperty(name="Ward Threshold", description="Light Selection WARD: shadow-test lights in "
                                  "order of their largest possible contribution until the untested lights could add "
                                  "at most this fraction of the light found; the rest is estimated by one sampled "
                                  "light (unbiased). 0 tests every light", default=0.05, min=0.0, soft_max=1.0)
    light_samples: IntProperty(name="Light Samples", description="Shadow rays per path vertex (stratified)",
                               default=1, min=1, max=256)
    branching_factor: IntProperty(name="Branching Factor", description="Continuation rays at the first surface "
                                  "(stochastic ray tracing); 1 is path tracing", default=1, min=1, max=256)
    rr_mode: EnumProperty(name="Russian Roulette", items=RR_MODES, default="THROUGHPUT")
    clamp_indirect: FloatProperty(name="Clamp Indirect", description="Clamp the brightest component of indirect "
                                  "light contributions to this value; 0 = off. Biased: it removes fireflies by "
                                  "removing energy", default=0.0, min=0.0, soft_max=100.0)
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
    # integrator: added in register(), its items come from the native module loaded by then


class CandelaViewLayerSettings(bpy.types.PropertyGroup):
    use_pass_albedo: BoolProperty(
        name="Albedo", description="Directional albedo (reflectance) of the first surface the camera sees, averaged "
        "over the pixel's samples (pass 'Albedo', for denoisers and compositing)", default=False)
    use_pass_noise: BoolProperty(
        name="Noise", description="Per-pixel estimated standard error of the pixel's luminance (pass 'Noise')",
        default=False)


def register():
    items = integrator_items()
    CandelaRenderSettings.__annotations__["integrator"] = EnumProperty(
        name="Integrator", description="Light transport algorithm", items=items,
        default="PATH" if any(i[0] == "PATH" for i in items) else items[0][0])
    bpy.utils.register_class(CandelaRenderSettings)
    bpy.types.Scene.candela = PointerProperty(type=CandelaRenderSettings, name="Candela Render Settings")
    bpy.utils.register_class(CandelaViewLayerSettings)
    bpy.types.ViewLayer.candela = PointerProperty(type=CandelaViewLayerSettings, name="Candela View Layer Settings")


def unregister():
    del bpy.types.ViewLayer.candela
    bpy.utils.unregister_class(CandelaViewLayerSettings)
    del bpy.types.Scene.candela
    bpy.utils.unregister_class(CandelaRenderSettings)
