"""The procedural textures and the converter/input nodes that compile to one native operation each
(docs/textures.md): Noise, White Noise, Musgrave, Voronoi, Wave, Magic, Checker, Gradient, Brick, Vector Math,
Map Range, Hue/Saturation, Layer Weight and Fresnel. A mix-in of shader_nodes.NodeCompiler (it provides `input`,
`coord`, `program`, `tables`).

Scalar sockets travel packed three to a register, (x, y, z) = three sockets, as the native operations read them
(texture/shader_program.h); an unlinked socket is a constant, so a pack of constants costs nothing.
"""

from .shader_tables import const3, is_const

_DIMS = {"1D": 1, "2D": 2, "3D": 3, "4D": 4}


class ProceduralNodes:

    def pack(self, *values):
        """Up to three scalar socket values (constants or registers) as one register (x, y, z)."""
        values = list(values) + [0.0] * (3 - len(values))
        if all(is_const(v) for v in values):
            return tuple(const3(v)[0] for v in values)
        return self.program.op("COMBINE", *values, i=(self.tables.enum("color_models")["RGB"],))

    def scalar(self, node, name, ctx):
        return self.input(node.inputs[name], ctx)

    def tex_vector(self, node, ctx):
        """The Vector socket, or Generated coordinates when it is unlinked (Cycles' texture default)."""
        socket = node.inputs["Vector"]
        return self.input(socket, ctx) if socket.is_linked else self.coord("GENERATED")

    def normal_input(self, node, ctx, name="Normal"):
        """A Normal socket, or the shading normal when it is unlinked."""
        socket = node.inputs[name]
        return self.input(socket, ctx) if socket.is_linked else self.coord("WORLD_NORMAL")

    def _enum(self, key, value, node, fallback):
        table = self.tables.enum(key)
        if value not in table:
            self.warn(f"{key[:-1].replace('_', ' ')} {value} of '{node.name}' is not supported; using {fallback}")
            value = fallback
        return table[value]

    # ---- procedural textures ------------------------------------------------------------------------------------

    def _ShaderNodeTexNoise(self, node, out, ctx):
        s = lambda n: self.scalar(node, n, ctx)   # noqa: E731
        return self.program.op("TEX_NOISE", self.tex_vector(node, ctx), self.pack(s("W"), s("Scale"), s("Detail")),
                               self.pack(s("Roughness"), s("Distortion")),
                               i=(_DIMS[node.noise_dimensions], int(out.identifier == "Color")))

    def _ShaderNodeTexWhiteNoise(self, node, out, ctx):
        # Cycles' White Noise reads the position when its Vector is unlinked.
        socket = node.inputs["Vector"]
        vector = self.input(socket, ctx) if socket.is_linked else self.coord("POSITION")
        return self.program.op("TEX_WHITE_NOISE", vector, self.pack(self.scalar(node, "W", ctx)),
                               i=(_DIMS[node.noise_dimensions], int(out.identifier == "Color")))

    def _ShaderNodeTexMusgrave(self, node, out, ctx):
        s = lambda n: self.scalar(node, n, ctx)   # noqa: E731
        gain = self.program.reg(s("Gain"))
        return self.program.op("TEX_MUSGRAVE", self.tex_vector(node, ctx), self.pack(s("W"), s("Scale"), s("Detail")),
                               self.pack(s("Dimension"), s("Lacunarity"), s("Offset")),
                               i=(gain.index, _DIMS[node.musgrave_dimensions],
                                  self._enum("musgrave_types", node.musgrave_type, node, "FBM")))

    def _ShaderNodeTexVoronoi(self, node, out, ctx):
        s = lambda n: self.scalar(node, n, ctx)   # noqa: E731
        output = ["Distance", "Color", "Position", "W", "Radius"].index(out.identifier)
        return self.program.op("TEX_VORONOI", self.tex_vector(node, ctx),
                               self.pack(s("W"), s("Scale"), s("Smoothness")), self.pack(s("Exponent"), s("Randomness")),
                               i=(_DIMS[node.voronoi_dimensions],
                                  self._enum("voronoi_features", node.feature, node, "F1"),
                                  self._enum("voronoi_metrics", node.distance, node, "EUCLIDEAN"), output))

    def _ShaderNodeTexWave(self, node, out, ctx):
        s = lambda n: self.scalar(node, n, ctx)   # noqa: E731
        if node.wave_type == "BANDS":
            direction = ["X", "Y", "Z", "DIAGONAL"].index(node.bands_direction)
        else:
            direction = ["X", "Y", "Z", "SPHERICAL"].index(node.rings_direction)
        return self.program.op("TEX_WAVE", self.tex_vector(node, ctx),
                               self.pack(s("Scale"), s("Distortion"), s("Detail")),
                               self.pack(s("Detail Scale"), s("Detail Roughness"), s("Phase Offset")),
                               i=(self.tables.enum("wave_types")[node.wave_type], direction,
                                  self.tables.enum("wave_profiles")[node.wave_profile]))

    def _ShaderNodeTexMagic(self, node, out, ctx):
        return self.program.op("TEX_MAGIC", self.tex_vector(node, ctx),
                               self.pack(self.scalar(node, "Scale", ctx), self.scalar(node, "Distortion", ctx)),
                               i=(max(0, min(int(node.turbulence_depth), 10)), int(out.identifier == "Fac")))

    def _ShaderNodeTexChecker(self, node, out, ctx):
        scale = self.program.reg(self.scalar(node, "Scale", ctx))
        return self.program.op("TEX_CHECKER", self.tex_vector(node, ctx), self.input(node.inputs["Color1"], ctx),
                               self.input(node.inputs["Color2"], ctx), i=(scale.index, int(out.identifier == "Fac")))

    def _ShaderNodeTexGradient(self, node, out, ctx):
        return self.program.op("TEX_GRADIENT", self.tex_vector(node, ctx),
                               i=(self.tables.enum("gradient_types")[node.gradient_type],))

    def _ShaderNodeTexBrick(self, node, out, ctx):
        s = lambda n: self.scalar(node, n, ctx)   # noqa: E731
        mortar = self.program.reg(self.input(node.inputs["Mortar"], ctx))
        sizes = self.program.reg(self.pack(s("Scale"), s("Mortar Size"), s("Mortar Smooth")))
        shape = self.program.reg(self.pack(s("Bias"), s("Brick Width"), s("Row Height")))
        offset = self.tables.add_consts([node.offset, node.offset_frequency, node.squash, node.squash_frequency,
                                         float(out.identifier == "Fac")])
        return self.program.op("TEX_BRICK", self.tex_vector(node, ctx), self.input(node.inputs["Color1"], ctx),
                               self.input(node.inputs["Color2"], ctx),
                               i=(mortar.index, sizes.index, shape.index, offset))

    # ---- converters and inputs ----------------------------------------------------------------------------------

    def _ShaderNodeVectorMath(self, node, out, ctx):
        ops = self.tables.enum("vector_math_ops")
        if node.operation not in ops:
            self.unsupported(node, f"operation {node.operation} is not supported yet")
            return None
        a, b = self.input(node.inputs[0], ctx), self.input(node.inputs[1], ctx)
        third = node.inputs[3] if node.operation in ("SCALE", "REFRACT") else node.inputs[2]
        return self.program.op("VECTOR_MATH", a, b, self.input(third, ctx),
                               i=(ops[node.operation], int(out.identifier == "Value")))

    def _ShaderNodeMapRange(self, node, out, ctx):
        if node.data_type == "FLOAT_VECTOR":
            names = ("Vector", "From_Min_FLOAT3", "From_Max_FLOAT3", "To_Min_FLOAT3", "To_Max_FLOAT3", "Steps_FLOAT3")
        else:
            names = ("Value", "From Min", "From Max", "To Min", "To Max", "Steps")
        v = [self.input(node.inputs[n], ctx) for n in names]
        regs = [self.program.reg(x) for x in v[3:]]
        kind = self.tables.enum("map_range_types")[node.interpolation_type]
        clamp = node.clamp and node.interpolation_type in ("LINEAR", "STEPPED")
        return self.program.op("MAP_RANGE", v[0], v[1], v[2],
                               i=(regs[0].index, regs[1].index, regs[2].index, kind | (int(clamp) << 8)))

    def _ShaderNodeHueSaturation(self, node, out, ctx):
        s = lambda n: self.scalar(node, n, ctx)   # noqa: E731
        return self.program.op("HUE_SATURATION", self.input(node.inputs["Color"], ctx),
                               self.pack(s("Hue"), s("Saturation"), s("Value")), s("Fac"))

    def _ShaderNodeLayerWeight(self, node, out, ctx):
        return self.program.op("LAYER_WEIGHT", self.normal_input(node, ctx), self.scalar(node, "Blend", ctx),
                               i=(int(out.identifier == "Facing"),))

    def _ShaderNodeFresnel(self, node, out, ctx):
        return self.program.op("FRESNEL", self.normal_input(node, ctx), self.scalar(node, "IOR", ctx))

    def _ShaderNodeBump(self, node, out, ctx):
        normal = self.normal_input(node, ctx)
        height = node.inputs["Height"]
        if not height.is_linked:
            return normal
        heights = self.at_offsets(lambda: self.input(height, ctx))
        return self.bump(heights, self.scalar(node, "Strength", ctx), self.scalar(node, "Distance", ctx), normal,
                         node.invert)

    def displacement_bump(self, socket, ctx=()):
        """The shading normal of a material's Displacement output in Cycles' "bump only" mode: the Displacement
        node's (height − midlevel)·scale as a bump height of distance 1 (object scale not applied); None if
        nothing varies or the producer is not a Displacement node."""
        from .shader_nodes import resolve
        out, _, ctx = resolve(socket, ctx)
        if out is None:
            return None
        node = out.node
        if node.bl_idname != "ShaderNodeDisplacement":
            self.unsupported(node, "feeds the Displacement output directly (only a Displacement node is read)")
            return None
        p = self.program

        def height():
            h = self.scalar(node, "Height", ctx)
            return p.mul(p.math("SUBTRACT", h, self.scalar(node, "Midlevel", ctx)), self.scalar(node, "Scale", ctx))
        normal = self.normal_input(node, ctx)
        result = self.bump(self.at_offsets(height), 1.0, 1.0, normal)
        return None if result is normal else result

    # ---- curves -------------------------------------------------------------------------------------------------

    def _curves(self, node, fac, value, rgb):
        """Cycles bakes the curves over the widest x range of their points (RAMP_SIZE samples); RGB Curves apply the
        combined curve (C) before each channel's, as Blender's curve mapping does."""
        from .. import schema
        mapping = node.mapping
        mapping.initialize()
        curves = list(mapping.curves)
        used = curves[:4] if rgb else curves[:3]
        min_x = min(c.points[0].location[0] for c in used)
        max_x = max(c.points[-1].location[0] for c in used)
        n = schema.RAMP_SIZE
        rows = []
        for i in range(n):
            t = min_x + i / (n - 1) * (max_x - min_x)
            if rgb:
                t = mapping.evaluate(curves[3], t)
            rows.append([mapping.evaluate(curves[k], t) for k in range(3)])
        index = self.tables.curve_table(rows)
        offset = self.tables.add_consts([min_x, max_x - min_x])
        return self.program.op("CURVES", fac, value, i=(index, offset, 0))

    def _ShaderNodeRGBCurve(self, node, out, ctx):
        return self._curves(node, self.scalar(node, "Fac", ctx), self.input(node.inputs["Color"], ctx), True)

    def _ShaderNodeVectorCurve(self, node, out, ctx):
        return self._curves(node, self.scalar(node, "Fac", ctx), self.input(node.inputs["Vector"], ctx), False)

    def _ShaderNodeFloatCurve(self, node, out, ctx):
        from .. import schema
        mapping = node.mapping
        mapping.initialize()
        curve = mapping.curves[0]
        min_x, max_x = curve.points[0].location[0], curve.points[-1].location[0]
        n = schema.RAMP_SIZE
        rows = [[mapping.evaluate(curve, min_x + i / (n - 1) * (max_x - min_x))] * 3 for i in range(n)]
        index = self.tables.curve_table(rows)
        offset = self.tables.add_consts([min_x, max_x - min_x])
        return self.program.op("CURVES", self.scalar(node, "Factor", ctx), self.scalar(node, "Value", ctx),
                               i=(index, offset, 1))

    # ---- sky ----------------------------------------------------------------------------------------------------

    def _ShaderNodeTexSky(self, node, out, ctx):
        from . import sky
        if node.sky_type not in ("PREETHAM", "NISHITA"):
            self.unsupported(node, f"sky type {node.sky_type} is not supported yet")
            return None
        socket = node.inputs["Vector"]
        vector = self.input(socket, ctx) if socket.is_linked else self.coord("GENERATED")
        if node.sky_type == "PREETHAM":
            state = sky.preetham_state(tuple(node.sun_direction), node.turbidity)
        else:
            self.warn(f"Nishita sky '{node.name}' uses published spectral tables, not Cycles' own: expect its "
                      "brightness and colour within about 15 % of Cycles'")
            state = [node.sun_elevation, node.sun_rotation, node.altitude, node.air_density, node.dust_density,
                     node.ozone_density, float(node.sun_disc), node.sun_size, node.sun_intensity]
        return self.program.op("SKY", vector, i=(self.tables.add_consts(state),
                                                 self.tables.enum("sky_models")[node.sky_type]))

    def _ShaderNodeBlackbody(self, node, out, ctx):
        return self.program.op("BLACKBODY", self.scalar(node, "Temperature", ctx))

    def _ShaderNodeWavelength(self, node, out, ctx):
        return self.program.op("WAVELENGTH", self.scalar(node, "Wavelength", ctx))
