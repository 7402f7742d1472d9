"""Blender lights → rows of the `lights` table, in Blender's own quantities.

The native side converts W and W/m² to radiometry with Cycles 3.4's rules (docs/conventions.md §2), so nothing
here is unit conversion: strength = colour × energy (× the light's Emission node), geometry from the world matrix.
"""

import numpy as np

from .. import schema

SHAPES = {"SQUARE": 0, "RECTANGLE": 0, "DISK": 1, "ELLIPSE": 1}


def _node_factor(light, warnings):
    """Colour × strength of an Emission node feeding the light output (lights without nodes: 1)."""
    if not light.use_nodes or light.node_tree is None:
        return np.ones(3)
    output = light.node_tree.get_output_node('CYCLES')
    if output is None or not output.inputs["Surface"].is_linked:
        return np.ones(3)
    node = output.inputs["Surface"].links[0].from_node
    if node.bl_idname != "ShaderNodeEmission":
        warnings.add(f"Candela: light '{light.name}': node '{node.name}' ({node.bl_idname}) is not supported; "
                     f"ignoring the light's node tree")
        return np.ones(3)
    return np.array(node.inputs["Color"].default_value[:3]) * node.inputs["Strength"].default_value


def light_row(light, matrix, warnings, visible_camera=False):
    """(type name, {column: value}) for one light datablock under the world matrix `matrix` ((4, 4) ndarray).

    `visible_camera` is the object's Visibility > Camera flag (off by default for lights in 3.4, as Cycles
    honours: camera rays then pass through area lights)."""
    m = np.asarray(matrix, np.float64)
    strength = np.array(light.color[:3]) * light.energy * _node_factor(light, warnings)
    direction = -m[:3, 2]
    norm = np.linalg.norm(direction)
    direction = direction / norm if norm > 0 else np.array([0.0, 0.0, -1.0])
    values = {
        "strength_r": strength[0], "strength_g": strength[1], "strength_b": strength[2],
        "pos_x": m[0, 3], "pos_y": m[1, 3], "pos_z": m[2, 3],
        "dir_x": direction[0], "dir_y": direction[1], "dir_z": direction[2],
        "visible_camera": 1.0 if visible_camera else 0.0,
    }
    kind = light.type
    if kind in ("POINT", "SPOT"):
        values["radius"] = light.shadow_soft_size
    if kind == "SPOT":
        values["spot_size"] = light.spot_size
        values["spot_blend"] = light.spot_blend
    elif kind == "SUN":
        values["angle"] = light.angle
    elif kind == "AREA":
        size_x = light.size
        size_y = light.size_y if light.shape in ("RECTANGLE", "ELLIPSE") else light.size
        # Full extent along local X/Y in world space; the matrix columns carry the object scale (Cycles counts it).
        u, v = m[:3, 0] * size_x, m[:3, 1] * size_y
        values.update(u_x=u[0], u_y=u[1], u_z=u[2], v_x=v[0], v_y=v[1], v_z=v[2], shape=SHAPES[light.shape])
    return kind, values


class LightTable:
    def __init__(self, warnings):
        self.warnings = warnings
        self.types = []
        self.rows = []
        self.columns = schema.light_columns()
        self.type_ids = schema.light_types()

    def add(self, light, matrix, visible_camera=False):
        kind, values = light_row(light, matrix, self.warnings, visible_camera)
        if kind not in self.type_ids:
            self.warnings.add(f"Candela: light '{light.name}' of type {kind} is not supported; skipped")
            return
        self.types.append(self.type_ids[kind])
        self.rows.append(schema.row(self.columns, values))

    def arrays(self):
        return {
            "light_type": np.array(self.types, np.uint32),
            "lights": np.array(self.rows, np.float32).reshape(len(self.rows), len(self.columns)),
        }
