"""Cycles input nodes → shader program operations (shader_tables.Program).

`NodeCompiler.input(socket)` returns the value feeding an input socket: a 3-tuple when nothing varies over the
surface (unlinked sockets, RGB / Value nodes, Math on constants) or a register of the program. Links are followed
through reroutes, muted nodes (their internal pass-through) and node groups. Socket types convert as Cycles
converts them: colour → value is Rec.709 luminance, vector → value the average of x, y, z, value → colour or vector
a broadcast.

Supported: Image Texture (flat projection), Environment Texture, the procedural textures (Noise, White Noise,
Voronoi, Musgrave, Wave, Magic, Checker, Brick, Gradient: `procedural_nodes.py`), Texture Coordinate (Generated,
Normal, UV, Object), UV Map, Mapping, Normal Map, Mix (colour, float, vector), MixRGB, Math, Vector Math, Map Range,
ColorRamp, RGB, Value, Invert, Gamma, Bright/Contrast, Hue/Saturation, RGB to BW, Separate/Combine Color, RGB, HSV
and XYZ, Clamp, Layer Weight, Fresnel. Any other node gives one
warning per material naming it, and the socket it feeds keeps its own value (as if unlinked), never black by
accident.
"""


import mathutils

from .procedural_nodes import ProceduralNodes
from .shader_tables import MISSING_COLOR, Program, Reg, const3, is_const

_INTERPOLATION = {"Closest": "CLOSEST", "Linear": "LINEAR", "Cubic": "CUBIC", "Smart": "CUBIC"}
_PASS_THROUGH = {"NodeReroute"}
RENDER_COLOR = "\x00render color"   # the Color Attribute node without a name: the mesh's default colour attribute


def _socket_default(socket):
    value = getattr(socket, "default_value", None)
    if value is None:
        return (0.0, 0.0, 0.0)
    return const3(value if isinstance(value, (int, float, bool)) else tuple(value))


def resolve(socket, ctx):
    """The output socket driving input `socket` in group context `ctx` (a tuple of group nodes, innermost
    last): (output socket or None, the last input socket on the way, its context). None means "unlinked": use
    that input socket's own value."""
    while True:
        links = [link for link in socket.links if not link.is_muted] if socket.is_linked else []
        if not links:
            return None, socket, ctx
        out = links[0].from_socket
        node = out.node
        if node.bl_idname in _PASS_THROUGH:
            socket = node.inputs[0]
            continue
        if node.mute:
            through = [il.from_socket for il in node.internal_links if il.to_socket == out]
            if not through:
                return None, socket, ctx
            socket = through[0]
            continue
        if node.bl_idname == "NodeGroupInput":
            if not ctx:
                return None, socket, ctx
            group = ctx[-1]
            match = [s for s in group.inputs if s.identifier == out.identifier]
            if not match:
                return None, socket, ctx
            socket, ctx = match[0], ctx[:-1]
            continue
        if node.bl_idname == "ShaderNodeGroup":
            tree = node.node_tree
            outputs = [n for n in tree.nodes if n.bl_idname == "NodeGroupOutput"] if tree is not None else []
            active = [n for n in outputs if n.is_active_output] or outputs
            match = [s for s in active[0].inputs if s.identifier == out.identifier] if active else []
            if not match:
                return None, socket, ctx
            socket, ctx = match[0], ctx + (node,)
            continue
        return out, socket, ctx


class NodeCompiler(ProceduralNodes):
    """Compiles the input sockets of one material (or the world) into one Program."""

    def __init__(self, tables, owner, warnings, world=False):
        self.tables, self.owner, self.warnings, self.world = tables, owner, warnings, world
        self.program = Program(tables)
        self.uses = set()     # "UV", "TANGENT", "GENERATED": what the meshes must export
        self._memo = {}
        self.offset = 0       # 1, 2 while compiling a Bump height at its offset points (COORD offsets)
        self.material_index = 0   # the material's pass index (Object Info > Material Index)

    def warn(self, message):
        self.warnings.add(f"Candela: {self.owner}: {message}")

    def unsupported(self, node, what=None):
        self.warn(f"node '{node.name}' ({node.bl_idname}) {what or 'is not supported yet'}; the input it feeds keeps "
                  "its own value")

    # ---- sockets ------------------------------------------------------------------------------------------------

    def input(self, socket, ctx=()):
        """The value feeding an input socket, converted to that socket's type."""
        out, last, last_ctx = resolve(socket, ctx)
        if out is None:
            return self.convert(_socket_default(last), last.type, socket.type)
        value = self.output(out, last_ctx)
        if value is None:   # unsupported producer: the socket's own value
            return _socket_default(socket)
        return self.convert(value, out.type, socket.type)

    def convert(self, value, from_type, to_type):
        if from_type == to_type or to_type not in ("VALUE", "INT", "BOOLEAN"):
            return value   # colour ↔ vector are the same three numbers; value → colour/vector is the broadcast
        if from_type == "RGBA":
            if is_const(value):
                r, g, b = value
                return (0.2126 * r + 0.7152 * g + 0.0722 * b,) * 3
            return self.program.op("LUMINANCE", value)
        if from_type == "VECTOR":
            if is_const(value):
                return (sum(value) / 3.0,) * 3
            return self.program.op("AVERAGE", value)
        return value

    def output(self, out, ctx):
        node = out.node
        key = (node.as_pointer(), out.identifier, tuple(g.as_pointer() for g in ctx), self.offset)
        if key not in self._memo:
            handler = getattr(self, "_" + node.bl_idname, None)
            if handler is None:
                self.unsupported(node)
                self._memo[key] = None
            else:
                self._memo[key] = handler(node, out, ctx)
        return self._memo[key]

    def coord(self, kind):
        if kind == "UV":
            self.uses.add("UV")
        elif kind in ("GENERATED", "OBJECT", "TANGENT") and not self.world:
            self.uses.add("GENERATED")
        moves = kind in ("UV", "GENERATED", "OBJECT", "POSITION")
        return self.program.op("COORD", i=(self.tables.enum("coord_kinds")[kind], self.offset if moves else 0))

    def at_offsets(self, compile_value):
        """compile_value() at the shading point and at Bump's two offset points: three values."""
        saved = self.offset
        values = []
        for offset in (0, 1, 2):
            self.offset = offset
            values.append(compile_value())
        self.offset = saved
        return values

    def bump(self, heights, strength, distance, normal, invert=False):
        """Cycles' Bump from heights at the point and its two offsets (BUMP); the normal itself if the height
        does not vary."""
        if all(is_const(h) for h in heights):
            return normal
        params = self.program.reg(self.pack(strength, distance))
        normal = self.program.reg(normal)
        return self.program.op("BUMP", *heights, i=(params.index, normal.index, int(invert)))

    # ---- textures -----------------------------------------------------------------------------------------------

    def _image_lookup(self, node, out, ctx, projection, default_coord):
        image = node.image
        index = self.tables.image(image, self.owner) if image is not None else None
        if index is None:
            if image is None:
                self.warn(f"image node '{node.name}' has no image; rendering it magenta, as Cycles does")
            return (1.0, 1.0, 1.0) if out.identifier == "Alpha" else MISSING_COLOR
        vector = node.inputs["Vector"]
        co = self.input(vector, ctx) if vector.is_linked else self.coord(default_coord)
        interpolation = _INTERPOLATION.get(node.interpolation, "LINEAR")
        extension = getattr(node, "extension", "REPEAT")
        if extension not in self.tables.enum("tex_extensions"):
            self.warn(f"extension {extension} of '{node.name}' is rendered as REPEAT")
            extension = "REPEAT"
        enums = self.tables
        return self.program.op("IMAGE_ALPHA" if out.identifier == "Alpha" else "IMAGE", co,
                               i=(index, enums.enum("tex_interpolations")[interpolation],
                                  enums.enum("tex_extensions")[extension],
                                  enums.enum("image_projections")[projection]))

    def _ShaderNodeTexImage(self, node, out, ctx):
        if node.projection != "FLAT":
            self.warn(f"projection {node.projection} of '{node.name}' is rendered as FLAT")
        return self._image_lookup(node, out, ctx, "FLAT", "UV")

    def _ShaderNodeTexEnvironment(self, node, out, ctx):
        projection = "MIRROR_BALL" if node.projection == "MIRROR_BALL" else "EQUIRECTANGULAR"
        return self._image_lookup(node, out, ctx, projection, "GENERATED")

    def _ShaderNodeTexCoord(self, node, out, ctx):
        if out.identifier == "Object" and getattr(node, "object", None) is not None and not self.world:
            # Another object's space: its inverse world matrix applied to the world position.
            return self.affine(node.object.matrix_world.inverted(), self.coord("POSITION"))
        if out.identifier == "Camera" and not self.world:
            camera = self.camera()
            if camera is None:
                self.unsupported(node, "output 'Camera' needs a scene camera")
                return None
            # Cycles' camera space looks down +Z (Blender's camera looks down −Z).
            flip = mathutils.Matrix.Diagonal((1.0, 1.0, -1.0, 1.0))
            return self.affine(flip @ camera.matrix_world.normalized().inverted(), self.coord("POSITION"))
        if out.identifier == "Window" and self.world:
            self.unsupported(node, "output 'Window' is not supported in the world yet")
            return None
        kind = {"Generated": "GENERATED", "Normal": "NORMAL", "UV": "UV", "Object": "OBJECT",
                "Reflection": "REFLECTION", "Window": "WINDOW"}.get(out.identifier)
        if kind is None:
            self.unsupported(node, f"output '{out.name}' is not supported yet")
            return None
        return self.coord(kind)

    def _ShaderNodeNewGeometry(self, node, out, ctx):
        kind = {"Position": "POSITION", "Normal": "WORLD_NORMAL", "True Normal": "TRUE_NORMAL",
                "Incoming": "INCOMING", "Backfacing": "BACKFACING", "Tangent": "TANGENT"}.get(out.identifier)
        if kind is None:
            self.unsupported(node, f"output '{out.name}' is not supported yet")
            return None
        return self.coord(kind)

    def _ShaderNodeObjectInfo(self, node, out, ctx):
        if self.world:
            return (0.0, 0.0, 0.0)
        if out.identifier == "Material Index":
            return (float(self.material_index),) * 3
        kind = {"Location": "OBJECT_LOCATION", "Object Index": "OBJECT_INDEX", "Color": "OBJECT_COLOR",
                "Alpha": "OBJECT_ALPHA", "Random": "OBJECT_RANDOM"}.get(out.identifier)
        if kind is None:
            self.unsupported(node, f"output '{out.name}' is not supported yet")
            return None
        return self.coord(kind)

    # The Light Path node: its outputs by the Cycles 3.4 names (docs/light_paths.md).
    _LIGHT_PATH = {"Is Camera Ray": "IS_CAMERA_RAY", "Is Shadow Ray": "IS_SHADOW_RAY",
                   "Is Diffuse Ray": "IS_DIFFUSE_RAY", "Is Glossy Ray": "IS_GLOSSY_RAY",
                   "Is Singular Ray": "IS_SINGULAR_RAY", "Is Reflection Ray": "IS_REFLECTION_RAY",
                   "Is Transmission Ray": "IS_TRANSMISSION_RAY", "Ray Length": "RAY_LENGTH",
                   "Ray Depth": "RAY_DEPTH", "Diffuse Depth": "DIFFUSE_DEPTH", "Glossy Depth": "GLOSSY_DEPTH",
                   "Transparent Depth": "TRANSPARENT_DEPTH", "Transmission Depth": "TRANSMISSION_DEPTH"}

    def _ShaderNodeLightPath(self, node, out, ctx):
        kind = self._LIGHT_PATH.get(out.identifier)
        if kind is None:   # Is Volume Scatter Ray: Candela has no volumes, so no ray is one
            return (0.0, 0.0, 0.0)
        return self.coord(kind)

    def camera(self):
        import bpy
        return bpy.context.scene.camera

    def affine(self, matrix, vector):
        """A 4×4 matrix applied to a point (the MAPPING operation with its rows)."""
        rows = [matrix[r][c] for r in range(3) for c in range(4)]
        return self.program.op("MAPPING", vector, i=(self.tables.add_consts(rows), 0))

    def _ShaderNodeUVMap(self, node, out, ctx):
        if node.uv_map and not self.world:
            return self.attribute(node.uv_map, "Vector")
        return self.coord("UV")

    def attribute(self, name, output):
        """A mesh attribute (a colour attribute, a UV map, a float or vector attribute) by name, exported per corner
        for the meshes whose materials read it; RENDER_COLOR is the mesh's default colour attribute."""
        if self.world:
            return (0.0, 0.0, 0.0)
        self.uses.add(("ATTRIBUTE", name))
        which = {"Fac": 1, "Alpha": 2}.get(output, 0)
        return self.program.op("ATTRIBUTE", i=(self.tables.attribute_slot(name), which))

    def _ShaderNodeAttribute(self, node, out, ctx):
        if node.attribute_type != "GEOMETRY":
            self.unsupported(node, f"reads a {node.attribute_type.lower()} attribute, which is not supported yet")
            return None
        return self.attribute(node.attribute_name, out.identifier)

    def _ShaderNodeVertexColor(self, node, out, ctx):
        return self.attribute(node.layer_name or RENDER_COLOR, out.identifier)

    def _ShaderNodeMapping(self, node, out, ctx):
        for name in ("Location", "Rotation", "Scale"):
            if name in node.inputs and node.inputs[name].is_linked:
                self.warn(f"input '{name}' of Mapping node '{node.name}' is driven by another node, which is not "
                          "supported yet; using its own value")
        vector = self.input(node.inputs["Vector"], ctx)
        loc = mathutils.Vector(node.inputs["Location"].default_value) if "Location" in node.inputs else mathutils.Vector()
        rot = mathutils.Euler(node.inputs["Rotation"].default_value, 'XYZ').to_matrix()
        scale = mathutils.Vector(node.inputs["Scale"].default_value)
        kind = node.vector_type
        inv = mathutils.Vector([1.0 / s if s != 0.0 else 0.0 for s in scale])
        if kind == "TEXTURE":   # the inverse of POINT: S⁻¹·Rᵀ·(v − loc)
            m = mathutils.Matrix.Diagonal(inv) @ rot.transposed()
            t = -(m @ loc)
        elif kind == "NORMAL":   # R·S⁻¹, normalised
            m = rot @ mathutils.Matrix.Diagonal(inv)
            t = mathutils.Vector()
        else:   # POINT: R·S·v + loc; VECTOR: no translation
            m = rot @ mathutils.Matrix.Diagonal(scale)
            t = loc if kind == "POINT" else mathutils.Vector()
        rows = [v for r in range(3) for v in (m[r][0], m[r][1], m[r][2], t[r])]
        if is_const(vector) and kind != "NORMAL":
            v = mathutils.Vector(vector)
            return tuple(m @ v + t)
        offset = self.tables.add_consts(rows)
        return self.program.op("MAPPING", vector, i=(offset, int(kind == "NORMAL")))

    def _ShaderNodeNormalMap(self, node, out, ctx):
        color = self.input(node.inputs["Color"], ctx)
        strength = self.input(node.inputs["Strength"], ctx)
        if node.space == "TANGENT":
            self.uses.update(("UV", "TANGENT"))
            if node.uv_map:
                self.warn(f"Normal Map node '{node.name}' names the UV map '{node.uv_map}'; Candela uses the mesh's "
                          "render UV map's tangents")
        return self.program.op("NORMAL_MAP", color, strength,
                               i=(self.tables.enum("normal_map_spaces")[node.space],))

    # ---- colour and math ----------------------------------------------------------------------------------------

    def _mix(self, blend, fac, a, b, clamp_factor, clamp_result, per_channel=False):
        enums = self.tables.enum("mix_blends")
        if blend not in enums:
            self.warn(f"blend mode {blend} is not supported; using MIX")
            blend = "MIX"
        return self.program.op("MIX", fac, a, b, i=(enums[blend], int(clamp_factor), int(clamp_result),
                                                    int(per_channel)))

    def _ShaderNodeMix(self, node, out, ctx):
        enabled = {s.identifier: s for s in node.inputs if s.enabled}
        suffix = {"FLOAT": "Float", "VECTOR": "Vector", "RGBA": "Color"}[node.data_type]
        per_channel = node.data_type == "VECTOR" and node.factor_mode == "NON_UNIFORM"
        fac = self.input(enabled["Factor_Vector" if per_channel else "Factor_Float"], ctx)
        a = self.input(enabled["A_" + suffix], ctx)
        b = self.input(enabled["B_" + suffix], ctx)
        blend = node.blend_type if node.data_type == "RGBA" else "MIX"
        clamp_result = node.clamp_result if node.data_type == "RGBA" else False
        return self._mix(blend, fac, a, b, node.clamp_factor, clamp_result, per_channel)

    def _ShaderNodeMixRGB(self, node, out, ctx):
        return self._mix(node.blend_type, self.input(node.inputs["Fac"], ctx), self.input(node.inputs["Color1"], ctx),
                         self.input(node.inputs["Color2"], ctx), True, node.use_clamp)

    def _ShaderNodeMath(self, node, out, ctx):
        ops = self.tables.enum("math_ops")
        if node.operation not in ops:
            self.unsupported(node, f"operation {node.operation} is not supported yet")
            return None
        a, b, c = (self.input(s, ctx) for s in node.inputs[:3])
        return self.program.op("MATH", a, b, c, i=(ops[node.operation], int(node.use_clamp)))

    def _ShaderNodeValToRGB(self, node, out, ctx):
        index = self.tables.ramp(node.color_ramp)
        interpolate = int(node.color_ramp.interpolation != "CONSTANT")
        return self.program.op("RAMP_ALPHA" if out.identifier == "Alpha" else "RAMP", self.input(node.inputs["Fac"], ctx),
                               i=(index, interpolate))

    def _ShaderNodeRGB(self, node, out, ctx):
        return const3(tuple(out.default_value))

    def _ShaderNodeValue(self, node, out, ctx):
        return const3(out.default_value)

    def _ShaderNodeInvert(self, node, out, ctx):
        return self.program.op("INVERT", self.input(node.inputs["Fac"], ctx), self.input(node.inputs["Color"], ctx))

    def _ShaderNodeGamma(self, node, out, ctx):
        return self.program.math("POWER", self.input(node.inputs["Color"], ctx), self.input(node.inputs["Gamma"], ctx))

    def _ShaderNodeBrightContrast(self, node, out, ctx):
        return self.program.op("BRIGHT_CONTRAST", *(self.input(node.inputs[n], ctx) for n in ("Color", "Bright", "Contrast")))

    def _ShaderNodeRGBToBW(self, node, out, ctx):
        return self.convert(self.input(node.inputs["Color"], ctx), "RGBA", "VALUE")

    def _separate(self, value, model, channel):
        if is_const(value) and model == "RGB":
            return (value[channel],) * 3
        return self.program.op("SEPARATE", value, i=(self.tables.enum("color_models")[model], channel))

    def _combine(self, values, model):
        if all(is_const(v) for v in values) and model == "RGB":
            return tuple(v[0] for v in values)
        return self.program.op("COMBINE", *values, i=(self.tables.enum("color_models")[model],))

    def _ShaderNodeSeparateColor(self, node, out, ctx):
        channel = [s.identifier for s in node.outputs].index(out.identifier)
        return self._separate(self.input(node.inputs[0], ctx), node.mode, channel)

    def _ShaderNodeCombineColor(self, node, out, ctx):
        return self._combine([self.input(s, ctx) for s in node.inputs[:3]], node.mode)

    def _ShaderNodeSeparateRGB(self, node, out, ctx):
        return self._separate(self.input(node.inputs[0], ctx), "RGB", [s.identifier for s in node.outputs].index(out.identifier))

    def _ShaderNodeCombineRGB(self, node, out, ctx):
        return self._combine([self.input(s, ctx) for s in node.inputs[:3]], "RGB")

    def _ShaderNodeSeparateHSV(self, node, out, ctx):
        return self._separate(self.input(node.inputs[0], ctx), "HSV", [s.identifier for s in node.outputs].index(out.identifier))

    def _ShaderNodeCombineHSV(self, node, out, ctx):
        return self._combine([self.input(s, ctx) for s in node.inputs[:3]], "HSV")

    _ShaderNodeSeparateXYZ = _ShaderNodeSeparateRGB
    _ShaderNodeCombineXYZ = _ShaderNodeCombineRGB

    def _ShaderNodeClamp(self, node, out, ctx):
        v, lo, hi = (self.input(node.inputs[n], ctx) for n in ("Value", "Min", "Max"))
        if node.clamp_type == "RANGE":   # either order of the bounds
            lo, hi = self.program.math("MINIMUM", lo, hi), self.program.math("MAXIMUM", lo, hi)
        return self.program.math("MINIMUM", self.program.math("MAXIMUM", v, lo), hi)


# The input nodes the compiler understands (for Candela's Shift+A node categories and the docs).
SUPPORTED_INPUT_NODES = tuple(sorted(name[1:] for name in dir(NodeCompiler) if name.startswith("_ShaderNode")))
