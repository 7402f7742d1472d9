"""Blender materials → rows of the `materials` table (DIFFUSE: base colour + emitted radiance).

The Cycles node tree is read directly (`get_output_node('CYCLES')`). Each supported shader node has one reader in
SHADER_READERS; anything else falls back to the viewport colour (`material.diffuse_color`) with one warning per
material naming the node. A later version grows the table (Glossy, Glass, Mix Shader, textures, ...).
"""

from .. import schema

DEFAULT_BASE = (0.8, 0.8, 0.8)   # no material at all: Blender's default grey


def _rgb(value):
    return tuple(float(c) for c in value[:3])


def _input(node, name, warnings, material):
    """An input's constant value; a linked input is not supported yet → its default value with a warning."""
    socket = node.inputs[name]
    if socket.is_linked:
        src = socket.links[0].from_node
        warnings.add(f"Candela: material '{material.name}': input '{name}' of '{node.name}' is driven by "
                     f"'{src.name}' ({src.bl_idname}), which is not supported yet; using the input's own value")
    return socket.default_value


def _diffuse(node, material, warnings):
    return {"base": _rgb(_input(node, "Color", warnings, material))}


def _principled(node, material, warnings):
    emission = _rgb(_input(node, "Emission", warnings, material))
    strength = float(_input(node, "Emission Strength", warnings, material))
    return {"base": _rgb(_input(node, "Base Color", warnings, material)),
            "emission": tuple(c * strength for c in emission)}


def _emission(node, material, warnings):
    color = _rgb(_input(node, "Color", warnings, material))
    strength = float(_input(node, "Strength", warnings, material))
    return {"base": (0.0, 0.0, 0.0), "emission": tuple(c * strength for c in color)}


# node.bl_idname → reader(node, material, warnings) -> {"base": rgb, "emission": rgb}
SHADER_READERS = {
    "ShaderNodeBsdfDiffuse": _diffuse,
    "ShaderNodeBsdfPrincipled": _principled,
    "ShaderNodeEmission": _emission,
}


def _fallback(material):
    return {"base": _rgb(material.diffuse_color)}


def read_material(material, warnings):
    """{"type": "DIFFUSE", "base": rgb, "emission": rgb} for one material (None = no material)."""
    if material is None:
        shader = {"base": DEFAULT_BASE}
    elif not material.use_nodes or material.node_tree is None:
        shader = _fallback(material)   # a legitimate non-node material: no warning
    else:
        output = material.node_tree.get_output_node('CYCLES')
        surface = output.inputs["Surface"] if output is not None else None
        if surface is None or not surface.is_linked:
            warnings.add(f"Candela: material '{material.name}' has no Cycles surface output; "
                         f"using its viewport colour")
            shader = _fallback(material)
        else:
            node = surface.links[0].from_node
            reader = SHADER_READERS.get(node.bl_idname)
            if reader is None:
                warnings.add(f"Candela: material '{material.name}': node '{node.name}' ({node.bl_idname}) is not "
                             f"supported yet; using the material's viewport colour")
                shader = _fallback(material)
            else:
                shader = reader(node, material, warnings)
    return {"type": "DIFFUSE", "base": shader["base"], "emission": shader.get("emission", (0.0, 0.0, 0.0))}


class MaterialTable:
    """Assigns one row per distinct material (None included) within one export."""

    def __init__(self, warnings):
        self.warnings = warnings
        self.rows = []        # dicts from read_material
        self._index = {}      # material pointer (0 for None) → row

    def row_of(self, material):
        key = material.as_pointer() if material is not None else 0
        row = self._index.get(key)
        if row is None:
            row = self._index[key] = len(self.rows)
            self.rows.append(read_material(material, self.warnings))
        return row

    def arrays(self):
        import numpy as np
        if not self.rows:
            self.row_of(None)   # the schema wants at least one material
        columns = schema.material_columns()
        types = schema.material_types()
        table = []
        for m in self.rows:
            values = dict(zip(("base_r", "base_g", "base_b"), m["base"]))
            values.update(zip(("emission_r", "emission_g", "emission_b"), m["emission"]))
            table.append(schema.row(columns, values))
        return {
            "material_type": np.array([types[m["type"]] for m in self.rows], np.uint32),
            "materials": np.array(table, np.float32).reshape(len(self.rows), len(columns)),
        }
