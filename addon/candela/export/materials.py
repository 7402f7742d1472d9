"""Blender materials → the `materials` table (per material: fallback base colour and emitted radiance), the
closure table (per material: the weighted BSDF closures of its Cycles node tree) and, where inputs are driven by
other nodes, one shader program per material with its input bindings (docs/architecture.md).

The Cycles node tree is read directly (`get_output_node('CYCLES')`) the way Cycles evaluates it into a closure
list: Mix Shader scales its inputs' weights by (1 − fac) and fac, Add Shader concatenates, each BSDF node becomes
one weighted closure, Emission adds radiance, Principled's Alpha mixes with a Transparent closure. Inputs come from
`shader_nodes.NodeCompiler`: a constant goes into the closure row, a varying value (a texture, a Math node on one)
is a register of the material's program bound to the closure column. Weights (a Mix Shader factor from a texture),
emission and the BSDFs' Normal input can vary too. An unsupported shader node falls back to the material's
viewport colour as a diffuse closure, with one warning per material naming the node — never silently black.
A Holdout node's weight (summed over the tree) goes to the `material_holdout` table when it is constant, else
(a Mix Shader factor from a texture) it is a register bound to the material's `HOLDOUT` input, evaluated at each
hit; alpha loses it where the camera sees the surface.
"""

import numpy as np

from .. import schema
from .shader_nodes import NodeCompiler, resolve
from .shader_tables import ShaderTables, const3, is_const

DEFAULT_BASE = (0.8, 0.8, 0.8)   # no material at all: Blender's default grey
# The shader nodes the closure walker understands (for Candela's Shift+A node categories and the docs).
SUPPORTED_SHADER_NODES = ("ShaderNodeAddShader", "ShaderNodeBsdfAnisotropic", "ShaderNodeBsdfDiffuse",
                          "ShaderNodeBsdfGlass", "ShaderNodeBsdfGlossy", "ShaderNodeBsdfPrincipled",
                          "ShaderNodeBsdfRefraction", "ShaderNodeBsdfTranslucent", "ShaderNodeBsdfTransparent",
                          "ShaderNodeEmission", "ShaderNodeHoldout", "ShaderNodeMixShader")
COLOR_GROUPS = ("weight", "color", "subsurface")   # closure values spread over the columns NAME_r, NAME_g, NAME_b
PLACEHOLDER = {"ior": 1.45}   # row value under a bound (varying) column; must pass the native row checks


def _rgb(value):
    return tuple(float(c) for c in value[:3])



def _holdout_value(weight):
    """The `material_holdout` number of a Holdout weight: the mean of its channels, at most 1 (a register: 0,
    the weight is bound to the material's HOLDOUT input instead)."""
    if not is_const(weight):
        return 0.0
    return min(sum(const3(weight)) / 3.0, 1.0)


class _Reader:
    """Walks one material's node tree into closures [(type, {name: value})], emission and a normal."""

    def __init__(self, material, warnings, tables):
        self.material, self.warnings = material, warnings
        self.owner = f"material '{material.name}'"
        self.nodes = NodeCompiler(tables, self.owner, warnings)
        self.nodes.material_index = getattr(material, "pass_index", 0)
        self.program = self.nodes.program
        self.closures, self.emission = [], (0.0, 0.0, 0.0)
        self.holdout = (0.0, 0.0, 0.0)   # Holdout closure weight, a constant or a register (Cycles: alpha loses it)
        self.normal, self._normal_from = None, None
        self.normal_from_displacement = False   # Cycles moves the smooth normal itself then: no bump shadowing

    def warn(self, message):
        self.warnings.add(f"Candela: {self.owner}: {message}")

    def value(self, node, name, ctx):
        """A scalar input: a constant float, or a register."""
        v = self.nodes.input(node.inputs[name], ctx)
        return v[0] if is_const(v) else v

    def rgb(self, node, name, ctx):
        return self.nodes.input(node.inputs[name], ctx)

    def closure(self, kind, weight, **values):
        values["weight"] = weight
        self.closures.append((kind, values))

    def add_emission(self, node, color_name, strength_name, weight, ctx):
        radiance = self.program.mul(self.rgb(node, color_name, ctx), self.value(node, strength_name, ctx))
        self.emission = self.program.add(self.emission, self.program.mul(radiance, weight))

    def take_normal(self, node, ctx, name="Normal"):
        """A linked Normal input (Normal Map, …) becomes the material's shading normal."""
        if name not in node.inputs or not node.inputs[name].is_linked:
            return
        out, _, _ = resolve(node.inputs[name], ctx)
        if out is None:
            return
        if self.normal is None:
            n = self.nodes.input(node.inputs[name], ctx)
            if not is_const(n):
                self.normal, self._normal_from = n, (out.node.as_pointer(), out.identifier)
        elif self._normal_from != (out.node.as_pointer(), out.identifier):
            self.warn(f"the closures use different Normal inputs; '{node.name}' uses the first one found")

    def displacement(self, output):
        """The Displacement output as a bump normal (Cycles' "bump only"; true displacement is not supported)."""
        socket = output.inputs.get("Displacement")
        if socket is None or not socket.is_linked:
            return
        # True displacement (a method other than Bump Only) is rendered as bump too: unsupported.py says so, once
        # per render with the settings Candela ignores.
        normal = self.nodes.displacement_bump(socket)
        if normal is None:
            return
        if self.normal is not None:
            self.warn("the Displacement output and a BSDF's Normal input both set the normal; using the BSDF's")
            return
        self.normal = normal
        self.normal_from_displacement = True

    def distribution(self, node, supported=("GGX", "BECKMANN")):
        d = getattr(node, "distribution", "GGX")
        if d == "SHARP":
            return 0, True
        if d not in supported:
            self.warn(f"distribution {d} of '{node.name}' is rendered as GGX")
            d = "GGX"
        return schema.DISTRIBUTIONS[d], False

    def walk(self, input_socket, weight, ctx=()):
        """Adds the closures feeding the shader input socket `input_socket`, scaled by `weight`."""
        out, _, ctx = resolve(input_socket, ctx)
        if out is None or (is_const(weight) and max(weight) <= 0.0):
            return
        node = out.node
        kind = node.bl_idname
        p = self.program
        if kind == "ShaderNodeMixShader":
            fac = p.clamp01(self.value(node, "Fac", ctx))
            self.walk(node.inputs[1], p.mul(weight, p.one_minus(fac)), ctx)
            self.walk(node.inputs[2], p.mul(weight, fac), ctx)
        elif kind == "ShaderNodeAddShader":
            self.walk(node.inputs[0], weight, ctx)
            self.walk(node.inputs[1], weight, ctx)
        elif kind == "ShaderNodeBsdfDiffuse":
            self.take_normal(node, ctx)
            self.closure("DIFFUSE", weight, color=self.rgb(node, "Color", ctx), roughness=self.value(node, "Roughness", ctx))
        elif kind in ("ShaderNodeBsdfGlossy", "ShaderNodeBsdfAnisotropic"):
            self.take_normal(node, ctx)
            d, sharp = self.distribution(node)
            extra = {"anisotropy": self.value(node, "Anisotropy", ctx)} if "Anisotropy" in node.inputs else {}
            self.closure("GLOSSY", weight, color=self.rgb(node, "Color", ctx),
                         roughness=0.0 if sharp else self.value(node, "Roughness", ctx), distribution=d, **extra)
        elif kind in ("ShaderNodeBsdfGlass", "ShaderNodeBsdfRefraction"):
            self.take_normal(node, ctx)
            d, sharp = self.distribution(node)
            self.closure("GLASS" if kind == "ShaderNodeBsdfGlass" else "REFRACTION", weight,
                         color=self.rgb(node, "Color", ctx), roughness=0.0 if sharp else self.value(node, "Roughness", ctx),
                         ior=self.value(node, "IOR", ctx), distribution=d)
        elif kind in ("ShaderNodeBsdfTranslucent", "ShaderNodeBsdfTransparent"):
            self.take_normal(node, ctx)
            self.closure("TRANSLUCENT" if kind == "ShaderNodeBsdfTranslucent" else "TRANSPARENT", weight,
                         color=self.rgb(node, "Color", ctx))
        elif kind == "ShaderNodeEmission":
            self.add_emission(node, "Color", "Strength", weight, ctx)
        elif kind == "ShaderNodeBsdfPrincipled":
            self.principled(node, weight, ctx)
        elif kind == "ShaderNodeHoldout":
            self.holdout = p.add(self.holdout, weight)
        else:
            self.warn(f"node '{node.name}' ({kind}) is not supported yet; using the material's viewport colour there")
            self.closure("DIFFUSE", weight, color=_rgb(self.material.diffuse_color))

    def principled(self, node, weight, ctx):
        p = self.program
        alpha = p.clamp01(self.value(node, "Alpha", ctx))
        if not is_const(alpha) or alpha[0] < 1.0:
            self.closure("TRANSPARENT", p.mul(weight, p.one_minus(alpha)), color=(1.0, 1.0, 1.0))
            weight = p.mul(weight, alpha)
        subsurface = self.value(node, "Subsurface", ctx)
        if not is_const(subsurface) or subsurface > 0.0:
            self.warn(f"subsurface scattering of '{node.name}' is approximated by its diffuse colour")
        self.take_normal(node, ctx)
        for name in ("Clearcoat Normal", "Tangent"):
            if name in node.inputs and node.inputs[name].is_linked:
                self.warn(f"input '{name}' of '{node.name}' is not supported yet and is ignored")
        values = {"color": self.rgb(node, "Base Color", ctx), "subsurface": self.rgb(node, "Subsurface Color", ctx)}
        for column, socket in (("subsurface", "Subsurface"), ("metallic", "Metallic"), ("specular", "Specular"),
                               ("specular_tint", "Specular Tint"), ("roughness", "Roughness"),
                               ("anisotropy", "Anisotropic"), ("sheen", "Sheen"), ("sheen_tint", "Sheen Tint"),
                               ("clearcoat", "Clearcoat"), ("clearcoat_roughness", "Clearcoat Roughness"),
                               ("ior", "IOR"), ("transmission", "Transmission"),
                               ("transmission_roughness", "Transmission Roughness")):
            values[column if column != "subsurface" else "subsurface_amount"] = self.value(node, socket, ctx)
        self.closure("PRINCIPLED", weight, **values)
        self.add_emission(node, "Emission", "Emission Strength", weight, ctx)


def read_material(material, warnings, tables=None):
    """{"base": rgb, "emission": rgb or register, "closures": [(type, values)], "normal", "program", "uses"} for one
    material (None = no material). `base` is the diffuse colour the renderer uses when a material has no closures."""
    empty = {"base": DEFAULT_BASE, "emission": (0.0, 0.0, 0.0), "closures": [], "normal": None, "program": None,
             "uses": frozenset()}
    if material is None:
        return empty
    base = _rgb(material.diffuse_color)
    if not material.use_nodes or material.node_tree is None:
        return dict(empty, base=base)   # legitimate: no warning
    output = material.node_tree.get_output_node('CYCLES')
    surface = output.inputs["Surface"] if output is not None else None
    if surface is None or not surface.is_linked:
        warnings.add(f"Candela: material '{material.name}' has no Cycles surface output; using its viewport colour")
        return dict(empty, base=base)
    tables = tables if tables is not None else ShaderTables(warnings)
    reader = _Reader(material, warnings, tables)
    reader.walk(surface, (1.0, 1.0, 1.0))
    reader.displacement(output)
    program = tables.add_program(reader.program)
    # A material of pure emission (or all-black closures) must not fall back to the base colour: mark it black.
    return {"base": (0.0, 0.0, 0.0) if not reader.closures else base, "emission": reader.emission,
            "closures": reader.closures, "holdout": reader.holdout, "normal": reader.normal,
            "normal_from_displacement": reader.normal_from_displacement,
            "program": program, "uses": frozenset(reader.nodes.uses)}


class MaterialTable:
    """Assigns one row per distinct material (None included) within one export."""

    def __init__(self, warnings, tables=None):
        self.warnings = warnings
        self.tables = tables if tables is not None else ShaderTables(warnings)
        self.rows = []        # dicts from read_material
        self._index = {}      # material pointer (0 for None) → row

    def row_of(self, material):
        key = material.as_pointer() if material is not None else 0
        row = self._index.get(key)
        if row is None:
            row = self._index[key] = len(self.rows)
            self.rows.append(read_material(material, self.warnings, self.tables))
        return row

    def uses(self, row):
        """What the meshes of material `row` must export for its program ("UV", "TANGENT", "GENERATED")."""
        return self.rows[row]["uses"]

    def arrays(self):
        if not self.rows:
            self.row_of(None)   # the schema wants at least one material
        columns = schema.material_columns()
        types = schema.material_types()
        closure_columns, closure_types = schema.closure_columns(), schema.closure_types()
        column_index = {c: i for i, c in enumerate(closure_columns)}
        table, owners, kinds, params = [], [], [], []
        for index, m in enumerate(self.rows):
            emission = m["emission"]
            values = dict(zip(("base_r", "base_g", "base_b"), m["base"]))
            if is_const(emission):
                values.update(zip(("emission_r", "emission_g", "emission_b"), const3(emission)))
            else:
                self.tables.bind("EMISSION", index, 0, 3, m["program"], emission)
            table.append(schema.row(columns, values))
            if m["normal"] is not None:
                # Column 1 marks a normal from the Displacement output (docs/architecture.md, input_bindings).
                self.tables.bind("NORMAL", index, int(m.get("normal_from_displacement", False)), 3, m["program"],
                                 m["normal"])
            if not is_const(m.get("holdout", 0.0)):
                self.tables.bind("HOLDOUT", index, 0, 3, m["program"], m["holdout"])
            for kind, closure_values in m["closures"]:
                closure = len(owners)
                row = {}
                for name, value in closure_values.items():
                    if name == "subsurface_amount":
                        name = "subsurface"
                        group = False
                    else:
                        group = name in COLOR_GROUPS
                    first = name + "_r" if group else name
                    if is_const(value):
                        if group:
                            row.update(zip((name + "_r", name + "_g", name + "_b"), const3(value)))
                        else:
                            row[name] = value[0] if isinstance(value, tuple) else float(value)
                    elif first in column_index:
                        self.tables.bind("CLOSURE", closure, column_index[first], 3 if group else 1, m["program"], value)
                        if not group:
                            row[name] = PLACEHOLDER.get(name, 0.0)
                owners.append(index)
                kinds.append(closure_types[kind])
                params.append(schema.row(closure_columns, row))
        return {
            "material_type": np.full(len(self.rows), types["DIFFUSE"], np.uint32),
            "materials": np.array(table, np.float32).reshape(len(self.rows), len(columns)),
            "closure_material": np.array(owners, np.uint32),
            "closure_type": np.array(kinds, np.uint32),
            "closure_params": np.array(params, np.float32).reshape(len(owners), len(closure_columns)),
            "material_holdout": np.array([_holdout_value(m.get("holdout", 0.0)) for m in self.rows], np.float32),
        }
