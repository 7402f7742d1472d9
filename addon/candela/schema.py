"""Column layouts and type ids of the native array schema (docs/architecture.md).

The native module is the authority (`capabilities()`); the documented layout is the fallback so that export and
dumps also work without it (tests, dumps written on a machine without the build).
"""

from . import native

MATERIAL_COLUMNS = ("base_r", "base_g", "base_b", "emission_r", "emission_g", "emission_b")
LIGHT_COLUMNS = ("strength_r", "strength_g", "strength_b", "pos_x", "pos_y", "pos_z", "dir_x", "dir_y", "dir_z",
                 "u_x", "u_y", "u_z", "v_x", "v_y", "v_z", "radius", "spot_size", "spot_blend", "angle", "shape",
                 "visible_camera")
MATERIAL_TYPES = {"DIFFUSE": 0}
CLOSURE_COLUMNS = ("weight_r", "weight_g", "weight_b", "color_r", "color_g", "color_b", "roughness", "anisotropy",
                   "ior", "distribution", "metallic", "specular", "specular_tint", "sheen", "sheen_tint", "clearcoat",
                   "clearcoat_roughness", "transmission", "transmission_roughness", "subsurface", "subsurface_r",
                   "subsurface_g", "subsurface_b")
CLOSURE_TYPES = {"DIFFUSE": 0, "GLOSSY": 1, "GLASS": 2, "REFRACTION": 3, "TRANSLUCENT": 4, "TRANSPARENT": 5,
                 "PRINCIPLED": 6}
DISTRIBUTIONS = {"GGX": 0, "BECKMANN": 1}
LIGHT_TYPES = {"POINT": 0, "SPOT": 1, "SUN": 2, "AREA": 3}
INSTANCE_FLAGS = {"CAMERA": 1, "DIFFUSE": 2, "GLOSSY": 4, "TRANSMISSION": 8, "SHADOW": 16, "HOLDOUT": 32}
INTEGRATORS = ("PATH",)

# Shader programs (docs/architecture.md, "Shader programs"): every enumeration by its native name, in value order.
SHADER_ENUMS = {
    "shader_ops": ("CONST", "COORD", "IMAGE", "IMAGE_ALPHA", "MIX", "MATH", "RAMP", "RAMP_ALPHA", "LUMINANCE",
                   "AVERAGE", "COMBINE", "SEPARATE", "MAPPING", "NORMAL_MAP", "INVERT", "BRIGHT_CONTRAST", "TEX_NOISE",
                   "TEX_WHITE_NOISE", "TEX_MUSGRAVE", "TEX_VORONOI", "TEX_WAVE", "TEX_MAGIC", "TEX_CHECKER",
                   "TEX_GRADIENT", "TEX_BRICK", "VECTOR_MATH", "MAP_RANGE", "HUE_SATURATION", "LAYER_WEIGHT",
                   "FRESNEL", "BUMP", "ATTRIBUTE", "SKY", "CURVES", "BLACKBODY"),
    "coord_kinds": ("UV", "GENERATED", "OBJECT", "NORMAL", "WORLD_NORMAL", "INCOMING", "POSITION", "TRUE_NORMAL",
                    "BACKFACING", "REFLECTION", "OBJECT_LOCATION", "OBJECT_INDEX", "TANGENT"),
    "math_ops": ("ADD", "SUBTRACT", "MULTIPLY", "DIVIDE", "MULTIPLY_ADD", "POWER", "LOGARITHM", "SQRT",
                 "INVERSE_SQRT", "ABSOLUTE", "EXPONENT", "MINIMUM", "MAXIMUM", "LESS_THAN", "GREATER_THAN", "SIGN",
                 "COMPARE", "SMOOTH_MIN", "SMOOTH_MAX", "ROUND", "FLOOR", "CEIL", "TRUNC", "FRACT", "MODULO", "WRAP",
                 "SNAP", "PINGPONG", "SINE", "COSINE", "TANGENT", "ARCSINE", "ARCCOSINE", "ARCTANGENT", "ARCTAN2",
                 "SINH", "COSH", "TANH", "RADIANS", "DEGREES"),
    "mix_blends": ("MIX", "DARKEN", "MULTIPLY", "BURN", "LIGHTEN", "SCREEN", "DODGE", "ADD", "OVERLAY", "SOFT_LIGHT",
                   "LINEAR_LIGHT", "DIFFERENCE", "SUBTRACT", "DIVIDE", "HUE", "SATURATION", "VALUE", "COLOR"),
    "color_models": ("RGB", "HSV", "HSL"),
    "normal_map_spaces": ("TANGENT", "OBJECT", "WORLD", "BLENDER_OBJECT", "BLENDER_WORLD"),
    "image_projections": ("FLAT", "EQUIRECTANGULAR", "MIRROR_BALL"),
    "tex_interpolations": ("CLOSEST", "LINEAR", "CUBIC"),
    "tex_extensions": ("REPEAT", "EXTEND", "CLIP"),
    "tex_color_spaces": ("LINEAR", "SRGB"),
    "tex_storages": ("FLOAT", "BYTE"),
    "input_targets": ("CLOSURE", "EMISSION", "NORMAL", "WORLD", "HOLDOUT"),
    "musgrave_types": ("MULTIFRACTAL", "FBM", "HYBRID_MULTIFRACTAL", "RIDGED_MULTIFRACTAL", "HETERO_TERRAIN"),
    "voronoi_features": ("F1", "F2", "SMOOTH_F1", "DISTANCE_TO_EDGE", "N_SPHERE_RADIUS"),
    "voronoi_metrics": ("EUCLIDEAN", "MANHATTAN", "CHEBYCHEV", "MINKOWSKI"),
    "wave_types": ("BANDS", "RINGS"),
    "wave_profiles": ("SIN", "SAW", "TRI"),
    "gradient_types": ("LINEAR", "QUADRATIC", "EASING", "DIAGONAL", "SPHERICAL", "QUADRATIC_SPHERE", "RADIAL"),
    "vector_math_ops": ("ADD", "SUBTRACT", "MULTIPLY", "DIVIDE", "MULTIPLY_ADD", "CROSS_PRODUCT", "PROJECT", "REFLECT",
                        "REFRACT", "FACEFORWARD", "DOT_PRODUCT", "DISTANCE", "LENGTH", "SCALE", "NORMALIZE", "ABSOLUTE",
                        "MINIMUM", "MAXIMUM", "FLOOR", "CEIL", "FRACTION", "MODULO", "WRAP", "SNAP", "SINE", "COSINE",
                        "TANGENT"),
    "map_range_types": ("LINEAR", "STEPPED", "SMOOTHSTEP", "SMOOTHERSTEP"),
    "sky_models": ("PREETHAM", "NISHITA"),
}
RAMP_SIZE = 256   # entries per ColorRamp table


def _cap(key, fallback):
    value = native.capabilities().get(key)
    return value if value else fallback


def material_columns():
    return tuple(_cap("material_columns", MATERIAL_COLUMNS))


def closure_columns():
    return tuple(_cap("closure_columns", CLOSURE_COLUMNS))


def closure_types():
    return dict(_cap("closure_types", CLOSURE_TYPES))


def light_columns():
    return tuple(_cap("light_columns", LIGHT_COLUMNS))


def material_types():
    return dict(_cap("material_types", MATERIAL_TYPES))


def light_types():
    return dict(_cap("light_types", LIGHT_TYPES))


def instance_flags():
    """Bits of the `instance_flags` array: the ray types an object is visible to, and holdout."""
    return dict(_cap("instance_flags", INSTANCE_FLAGS))


def shader_enum(key):
    """{name: value} of one shader-program enumeration (SHADER_ENUMS keys)."""
    return dict(_cap(key, {name: i for i, name in enumerate(SHADER_ENUMS[key])}))


def bdpt_strategy_passes(depth):
    """BDPT's strategy-image pass names for strategy depths 0..depth (native/integrators/bdpt/strategy_images.h)."""
    table = native.capabilities().get("bdpt_strategy_passes") or {}
    return tuple(str(n) for n in table.get(int(depth), ()))


def integrators():
    """((name, description, label), ...) of the native registry (names only in the fallback)."""
    result = []
    for entry in _cap("integrators", INTEGRATORS):
        if isinstance(entry, str):
            entry = (entry,)
        name = str(entry[0])
        description = str(entry[1]) if len(entry) > 1 else ""
        label = str(entry[2]) if len(entry) > 2 else name.replace("_", " ").title()
        result.append((name, description, label))
    return tuple(result)


def integrator_params():
    """{integrator: [published setting spec, ...]} (core/param_spec.h): each integrator's own settings, in the
    order its panels draw them; {} without the native module."""
    return {str(name): list(specs) for name, specs in _cap("integrator_params", {}).items()}


def common_params():
    """The settings every integrator reads (samples, seed, sampler, filter, transparency, stopping rules)."""
    return list(_cap("common_params", []))


def row(columns, values):
    """One table row in `columns` order from a {column: value} dict; columns the add-on does not know stay 0."""
    return [float(values.get(c, 0.0)) for c in columns]
