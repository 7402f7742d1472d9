"""Blender materials → the `materials` table (per material: fallback base colour and emitted radiance) and the
closure table (per material: the weighted BSDF closures of its Cycles node tree, docs/architecture.md).

The Cycles node tree is read directly (`get_output_node('CYCLES')`) the way Cycles evaluates it into a closure
list: Mix Shader scales its inputs' weights by (1 − fac) and fac, Add Shader concatenates, each BSDF node becomes
one weighted closure, Emission adds radiance, Principled's Alpha mixes with a Transparent closure. Inputs are
constants; a linked input (a texture, a math node) is not supported yet: its socket value is used, with one warning
per material naming the node. An unsupported shader node falls back to the material's viewport colour as a diffuse
closure, with one warning per material naming the node — never silently black. A Holdout node's weight goes to the
`material_holdout` table (alpha loses it where the camera sees the surface).
"""

import numpy as np

from .. import schema

DEFAULT_BASE = (0.8, 0.8, 0.8)   # no material at all: Blender's default grey


def _rgb(value):
    return tuple(float(c) for c in value[:3])


def _scaled(rgb, w):
    return tuple(c * k for c, k in zip(rgb, w))


class _Reader:
    """Walks one material's node tree into closures [(type, {column: value})] and emitted radiance."""

    def __init__(self, material, warnings):
        self.material, self.warnings = material, warnings
        self.closures, self.emission = [], (0.0, 0.0, 0.0)
        self.holdout = 0.0    # Holdout closure weight (Cycles: alpha loses it where the camera sees the surface)

    def value(self, node, name):
        socket = node.inputs[name]
        if socket.is_linked:
            src = socket.links[0].from_node
            self.warnings.add(f"Candela: material '{self.material.name}': input '{name}' of '{node.name}' is driven "
                              f"by '{src.name}' ({src.bl_idname}), which is not supported yet; using the input's "
                              "own value")
        return socket.default_value

    def rgb(self, node, name):
        return _rgb(self.value(node, name))

    def closure(self, kind, weight, **values):
        values.update(zip(("weight_r", "weight_g", "weight_b"), weight))
        self.closures.append((kind, values))

    def distribution(self, node, supported=("GGX", "BECKMANN")):
        d = getattr(node, "distribution", "GGX")
        if d == "SHARP":
            return 0, True
        if d not in supported:
            self.warnings.add(f"Candela: material '{self.material.name}': distribution {d} of '{node.name}' is "
                              "rendered as GGX")
            d = "GGX"
        return schema.DISTRIBUTIONS[d], False

    def walk(self, socket_from, weight):
        node = socket_from.node
        kind = node.bl_idname
        if max(weight) <= 0.0:
            return
        if kind == "ShaderNodeMixShader":
            fac = min(max(float(self.value(node, "Fac")), 0.0), 1.0)
            for inp, w in ((node.inputs[1], 1.0 - fac), (node.inputs[2], fac)):
                if inp.is_linked:
                    self.walk(inp.links[0].from_socket, tuple(c * w for c in weight))
        elif kind == "ShaderNodeAddShader":
            for inp in (node.inputs[0], node.inputs[1]):
                if inp.is_linked:
                    self.walk(inp.links[0].from_socket, weight)
        elif kind == "ShaderNodeBsdfDiffuse":
            self.closure("DIFFUSE", weight, **dict(zip(("color_r", "color_g", "color_b"), self.rgb(node, "Color"))),
                         roughness=float(self.value(node, "Roughness")))
        elif kind in ("ShaderNodeBsdfGlossy", "ShaderNodeBsdfAnisotropic"):
            d, sharp = self.distribution(node)
            extra = {"anisotropy": float(self.value(node, "Anisotropy"))} if "Anisotropy" in node.inputs else {}
            self.closure("GLOSSY", weight, **dict(zip(("color_r", "color_g", "color_b"), self.rgb(node, "Color"))),
                         roughness=0.0 if sharp else float(self.value(node, "Roughness")), distribution=d, **extra)
        elif kind in ("ShaderNodeBsdfGlass", "ShaderNodeBsdfRefraction"):
            d, sharp = self.distribution(node)
            self.closure("GLASS" if kind == "ShaderNodeBsdfGlass" else "REFRACTION", weight,
                         **dict(zip(("color_r", "color_g", "color_b"), self.rgb(node, "Color"))),
                         roughness=0.0 if sharp else float(self.value(node, "Roughness")),
                         ior=float(self.value(node, "IOR")), distribution=d)
        elif kind in ("ShaderNodeBsdfTranslucent", "ShaderNodeBsdfTransparent"):
            self.closure("TRANSLUCENT" if kind == "ShaderNodeBsdfTranslucent" else "TRANSPARENT", weight,
                         **dict(zip(("color_r", "color_g", "color_b"), self.rgb(node, "Color"))))
        elif kind == "ShaderNodeEmission":
            radiance = _scaled(self.rgb(node, "Color"), weight)
            strength = float(self.value(node, "Strength"))
            self.emission = tuple(e + c * strength for e, c in zip(self.emission, radiance))
        elif kind == "ShaderNodeBsdfPrincipled":
            self.principled(node, weight)
        elif kind == "ShaderNodeHoldout":
            self.holdout += sum(weight) / 3.0
        else:
            self.warnings.add(f"Candela: material '{self.material.name}': node '{node.name}' ({kind}) is not "
                              "supported yet; using the material's viewport colour there")
            self.closure("DIFFUSE", weight, **dict(zip(("color_r", "color_g", "color_b"),
                                                       _rgb(self.material.diffuse_color))))

    def principled(self, node, weight):
        alpha = min(max(float(self.value(node, "Alpha")), 0.0), 1.0)
        if alpha < 1.0:
            self.closure("TRANSPARENT", tuple(c * (1.0 - alpha) for c in weight), color_r=1.0, color_g=1.0, color_b=1.0)
            weight = tuple(c * alpha for c in weight)
        if float(self.value(node, "Subsurface")) > 0.0:
            self.warnings.add(f"Candela: material '{self.material.name}': subsurface scattering of '{node.name}' is "
                              "approximated by its diffuse colour")
        values = dict(zip(("color_r", "color_g", "color_b"), self.rgb(node, "Base Color")))
        values.update(zip(("subsurface_r", "subsurface_g", "subsurface_b"), self.rgb(node, "Subsurface Color")))
        for column, socket in (("subsurface", "Subsurface"), ("metallic", "Metallic"), ("specular", "Specular"),
                               ("specular_tint", "Specular Tint"), ("roughness", "Roughness"),
                               ("anisotropy", "Anisotropic"), ("sheen", "Sheen"), ("sheen_tint", "Sheen Tint"),
                               ("clearcoat", "Clearcoat"), ("clearcoat_roughness", "Clearcoat Roughness"),
                               ("ior", "IOR"), ("transmission", "Transmission"),
                               ("transmission_roughness", "Transmission Roughness")):
            values[column] = float(self.value(node, socket))
        self.closure("PRINCIPLED", weight, **values)
        radiance = _scaled(self.rgb(node, "Emission"), weight)
        strength = float(self.value(node, "Emission Strength"))
        self.emission = tuple(e + c * strength for e, c in zip(self.emission, radiance))


def read_material(material, warnings):
    """{"base": rgb, "emission": rgb, "closures": [(type, values)]} for one material (None = no material).

    `base` is the diffuse colour the renderer uses when a material has no closures (no node tree)."""
    if material is None:
        return {"base": DEFAULT_BASE, "emission": (0.0, 0.0, 0.0), "closures": []}
    base = _rgb(material.diffuse_color)
    if not material.use_nodes or material.node_tree is None:
        return {"base": base, "emission": (0.0, 0.0, 0.0), "closures": []}   # legitimate: no warning
    output = material.node_tree.get_output_node('CYCLES')
    surface = output.inputs["Surface"] if output is not None else None
    if surface is None or not surface.is_linked:
        warnings.add(f"Candela: material '{material.name}' has no Cycles surface output; using its viewport colour")
        return {"base": base, "emission": (0.0, 0.0, 0.0), "closures": []}
    reader = _Reader(material, warnings)
    reader.walk(surface.links[0].from_socket, (1.0, 1.0, 1.0))
    # A material of pure emission (or all-black closures) must not fall back to the base colour: mark it black.
    return {"base": (0.0, 0.0, 0.0) if not reader.closures else base, "emission": reader.emission,
            "closures": reader.closures, "holdout": min(reader.holdout, 1.0)}


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
        if not self.rows:
            self.row_of(None)   # the schema wants at least one material
        columns = schema.material_columns()
        types = schema.material_types()
        table = []
        for m in self.rows:
            values = dict(zip(("base_r", "base_g", "base_b"), m["base"]))
            values.update(zip(("emission_r", "emission_g", "emission_b"), m["emission"]))
            table.append(schema.row(columns, values))
        closure_columns, closure_types = schema.closure_columns(), schema.closure_types()
        owners, kinds, params = [], [], []
        for index, m in enumerate(self.rows):
            for kind, values in m["closures"]:
                owners.append(index)
                kinds.append(closure_types[kind])
                params.append(schema.row(closure_columns, values))
        return {
            "material_type": np.full(len(self.rows), types["DIFFUSE"], np.uint32),
            "materials": np.array(table, np.float32).reshape(len(self.rows), len(columns)),
            "closure_material": np.array(owners, np.uint32),
            "closure_type": np.array(kinds, np.uint32),
            "closure_params": np.array(params, np.float32).reshape(len(owners), len(closure_columns)),
            "material_holdout": np.array([m.get("holdout", 0.0) for m in self.rows], np.float32),
        }
