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
INTEGRATORS = ("PATH",)


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


def integrators():
    """((name, description), ...): the native registry lists names or (name, description) pairs."""
    result = []
    for entry in _cap("integrators", INTEGRATORS):
        if isinstance(entry, str):
            result.append((entry, ""))
        else:
            result.append((str(entry[0]), str(entry[1]) if len(entry) > 1 else ""))
    return tuple(result)


def row(columns, values):
    """One table row in `columns` order from a {column: value} dict; columns the add-on does not know stay 0."""
    return [float(values.get(c, 0.0)) for c in columns]
