"""Per-node parity scenes: one input or texture node feeding an Emission shader (strength 1), so the picture is
the node's output itself and the comparison with Cycles isolates the node (no light transport, no lights, a black
world). Built inside Blender; tests/parity/parity.py --nodes renders them with both engines.

Geometry: PLANE, a 2 × 2 m grid (UVs 0..1) under a rotated, scaled, moved object transform, seen straight down by
an orthographic camera that it fills (object, generated and UV coordinates all differ from world ones); SPHERE, a
smooth UV sphere seen in perspective (normals and the view direction vary: Fresnel, Layer Weight, Geometry).
The *_LIT scenes light a white diffuse PLANE, SPHERE or LOWPOLY (the sphere with 16 × 8 faces) by a sun instead.

Each scene: NODE_SCENES[name] = (geometry, graph), graph(nt, coord) returning the socket fed to the Emission colour;
coord is a Texture Coordinate node. Values stay non-negative (emission is), so signed outputs go through
Vector Math ABSOLUTE or are chosen non-negative.
"""

import math

try:
    import bmesh
    import bpy
    from mathutils import Euler, Matrix, Vector
except ImportError:   # tests/parity/parity.py reads the scene lists outside Blender
    bpy = None


def node(nt, kind, props=None, **inputs):
    n = nt.nodes.new(kind)
    for key, value in (props or {}).items():
        setattr(n, key, value)
    for key, value in inputs.items():
        n.inputs[key.replace("_", " ")].default_value = value
    return n


def link(nt, socket, n, name):
    nt.links.new(socket, n.inputs[name])
    return n


def tex(kind, output="Fac", vector="Generated", props=None, **inputs):
    """A texture node fed by a Texture Coordinate output (None: its own default)."""
    def graph(nt, coord):
        n = node(nt, kind, props, **inputs)
        if vector is not None:
            nt.links.new(coord.outputs[vector], n.inputs["Vector"])
        return n.outputs[output]
    return graph


def absolute(graph):
    """|graph| per channel (Vector Math ABSOLUTE), for signed outputs."""
    def g(nt, coord):
        n = node(nt, "ShaderNodeVectorMath", {"operation": "ABSOLUTE"})
        nt.links.new(graph(nt, coord), n.inputs[0])
        return n.outputs["Vector"]
    return g


def scaled(graph, factor):
    def g(nt, coord):
        n = node(nt, "ShaderNodeVectorMath", {"operation": "SCALE"}, Scale=factor)
        nt.links.new(graph(nt, coord), n.inputs[0])
        return n.outputs["Vector"]
    return g


def floored_white_noise(output, dims="3D"):
    """White noise of ⌊7·generated⌋: exact integer-valued keys, so both engines hash the same bits (7, not 8: a
    plane's Generated z is ½, which Cycles interpolates to ½ − 1 ulp at some points: ⌊8·z⌋ would flip there)."""
    def g(nt, coord):
        s = node(nt, "ShaderNodeVectorMath", {"operation": "SCALE"}, Scale=7.0)
        nt.links.new(coord.outputs["Generated"], s.inputs[0])
        f = node(nt, "ShaderNodeVectorMath", {"operation": "FLOOR"})
        nt.links.new(s.outputs["Vector"], f.inputs[0])
        w = node(nt, "ShaderNodeTexWhiteNoise", {"noise_dimensions": dims}, W=3.0)
        nt.links.new(f.outputs["Vector"], w.inputs["Vector"])
        return w.outputs[output]
    return g


def coord_output(name, fn=abs):
    return absolute(lambda nt, coord: coord.outputs[name])


def geometry_output(name):
    def g(nt, coord):
        return node(nt, "ShaderNodeNewGeometry").outputs[name]
    return absolute(g) if name != "Backfacing" else g


def object_coords_of_empty(nt, coord):
    empty = bpy.data.objects.get("Frame")
    c = node(nt, "ShaderNodeTexCoord", {"object": empty})
    f = node(nt, "ShaderNodeVectorMath", {"operation": "FRACTION"})
    nt.links.new(c.outputs["Object"], f.inputs[0])
    return f.outputs["Vector"]


def camera_coords(nt, coord):
    m = node(nt, "ShaderNodeVectorMath", {"operation": "SCALE"}, Scale=0.25)
    nt.links.new(coord.outputs["Camera"], m.inputs[0])
    a = node(nt, "ShaderNodeVectorMath", {"operation": "ABSOLUTE"})
    nt.links.new(m.outputs["Vector"], a.inputs[0])
    return a.outputs["Vector"]


def map_range(interpolation, clamp=True, **inputs):
    def g(nt, coord):
        sep = node(nt, "ShaderNodeSeparateXYZ")
        nt.links.new(coord.outputs["Generated"], sep.inputs[0])
        m = node(nt, "ShaderNodeMapRange", {"interpolation_type": interpolation, "clamp": clamp}, **inputs)
        nt.links.new(sep.outputs["X"], m.inputs["Value"])
        return m.outputs["Result"]
    return g


def vector_math(operation, output="Vector", **inputs):
    def g(nt, coord):
        v = node(nt, "ShaderNodeVectorMath", {"operation": operation})
        for k, val in inputs.items():
            v.inputs[int(k[1:])].default_value = val
        nt.links.new(coord.outputs["Generated"], v.inputs[0])
        return v.outputs[output]
    return absolute(g) if output == "Vector" else g


def _blackbody(nt, temperature):
    b = node(nt, "ShaderNodeBlackbody")
    nt.links.new(temperature, b.inputs["Temperature"])
    return b.outputs["Color"]


def _wavelength(nt, value):
    w = node(nt, "ShaderNodeWavelength")
    nt.links.new(value, w.inputs["Wavelength"])
    return w.outputs["Color"]


def object_info_output(name):
    return lambda nt, coord: node(nt, "ShaderNodeObjectInfo").outputs[name]


def light_path_output(name):
    return lambda nt, coord: node(nt, "ShaderNodeLightPath").outputs[name]


def camera_only_world(nt, coord):
    """A Light Path trick: the camera sees a white world, everything else is lit by a blue one."""
    mix = node(nt, "ShaderNodeMixRGB", Color1=(0.1, 0.2, 0.8, 1.0), Color2=(1.0, 1.0, 1.0, 1.0))
    nt.links.new(node(nt, "ShaderNodeLightPath").outputs["Is Camera Ray"], mix.inputs["Fac"])
    return mix.outputs["Color"]


def hue_saturation(nt, coord):
    n = tex("ShaderNodeTexNoise", "Color", Scale=3.0)(nt, coord)
    h = node(nt, "ShaderNodeHueSaturation", Hue=0.3, Saturation=1.6, Value=1.2, Fac=0.8)
    nt.links.new(n, h.inputs["Color"])
    return h.outputs["Color"]


def bumped(height_graph, strength=1.0, distance=0.1, invert=False, then=None):
    """The Bump node's normal (|n| per channel) from a height graph; `then(nt, normal_socket)` may use it."""
    def g(nt, coord):
        b = node(nt, "ShaderNodeBump", {"invert": invert}, Strength=strength, Distance=distance)
        nt.links.new(height_graph(nt, coord), b.inputs["Height"])
        if then is not None:
            return then(nt, b.outputs["Normal"])
        a = node(nt, "ShaderNodeVectorMath", {"operation": "ABSOLUTE"})
        nt.links.new(b.outputs["Normal"], a.inputs[0])
        return a.outputs["Vector"]
    return g


def _sinx(nt, coord):
    sep = node(nt, "ShaderNodeSeparateXYZ")
    nt.links.new(coord.outputs["Object"], sep.inputs[0])
    m = node(nt, "ShaderNodeMath", {"operation": "MULTIPLY"})
    m.inputs[1].default_value = 20.0
    nt.links.new(sep.outputs["X"], m.inputs[0])
    s = node(nt, "ShaderNodeMath", {"operation": "SINE"})
    nt.links.new(m.outputs[0], s.inputs[0])
    return s.outputs[0]


def image_uv(nt, coord):
    """A smooth 16 × 16 float image (a sum of sines) read through UV coordinates, linear interpolation."""
    import numpy as np
    img = bpy.data.images.get("bump_image")
    if img is None:
        img = bpy.data.images.new("bump_image", 16, 16, float_buffer=True)
        y, x = np.mgrid[0:16, 0:16] / 16.0
        v = 0.5 + 0.25 * np.sin(2 * np.pi * x) * np.cos(4 * np.pi * y)
        px = np.ones((16, 16, 4), np.float32)
        px[..., 0] = px[..., 1] = px[..., 2] = v
        img.pixels.foreach_set(px.ravel())
        img.pack()
    t = node(nt, "ShaderNodeTexImage", {"image": img, "interpolation": "Cubic"})
    nt.links.new(coord.outputs["UV"], t.inputs["Vector"])
    return t.outputs["Color"]


def layer_weight_of(nt, normal):
    lw = node(nt, "ShaderNodeLayerWeight", Blend=0.4)
    nt.links.new(normal, lw.inputs["Normal"])
    return lw.outputs["Facing"]


def curves(kind, source, socket, edit):
    """A curves node fed by `source`, its curve mapping changed by edit(mapping)."""
    def g(nt, coord):
        c = node(nt, kind)
        edit(c.mapping)
        c.mapping.update()
        nt.links.new(source(nt, coord), c.inputs[socket])
        return c.outputs[0]
    return g


def _edit_rgb(mapping):
    mapping.curves[3].points.new(0.4, 0.7)
    mapping.curves[0].points.new(0.5, 0.2)
    mapping.curves[2].points[1].location = (0.8, 0.9)   # the blue curve ends at x = 0.8: extrapolated past it


def _edit_vector(mapping):
    for k, c in enumerate(mapping.curves):
        c.points.new(0.1 * k, 0.3 + 0.2 * k)


def _edit_float(mapping):
    mapping.curves[0].points.new(0.3, 0.8)
    mapping.curves[0].points.new(0.7, 0.1)


def object_index(nt, coord):
    m = node(nt, "ShaderNodeMath", {"operation": "DIVIDE"})
    m.inputs[1].default_value = 5.0
    nt.links.new(node(nt, "ShaderNodeObjectInfo").outputs["Object Index"], m.inputs[0])
    return m.outputs[0]


def with_normal_input(kind, output, **inputs):
    def g(nt, coord):
        return node(nt, kind, **inputs).outputs[output]
    return g


def sky(sky_type, **props):
    """A world graph: the Sky Texture of `sky_type` (node properties `props`)."""
    def g(nt, coord):
        return node(nt, "ShaderNodeTexSky", {"sky_type": sky_type, **props}).outputs["Color"]
    return g


# name → (geometry, graph)
NODE_SCENES = {
    "node_noise_3d": ("PLANE", tex("ShaderNodeTexNoise", Scale=4.0, Detail=3.0, Roughness=0.6, Distortion=0.5)),
    "node_noise_color_3d": ("PLANE", tex("ShaderNodeTexNoise", "Color", Scale=3.0, Detail=2.5)),
    "node_noise_1d": ("PLANE", tex("ShaderNodeTexNoise", "Color", props={"noise_dimensions": "1D"}, W=0.7,
                                   Scale=2.0, Detail=1.5)),
    "node_noise_2d": ("PLANE", tex("ShaderNodeTexNoise", props={"noise_dimensions": "2D"}, Scale=6.0, Detail=4.0,
                                   Distortion=1.0)),
    "node_noise_4d": ("PLANE", tex("ShaderNodeTexNoise", "Color", props={"noise_dimensions": "4D"}, W=1.3,
                                   Scale=4.0, Detail=2.0, Distortion=0.3)),
    "node_white_noise": ("PLANE", floored_white_noise("Value")),
    "node_white_noise_color": ("PLANE", floored_white_noise("Color")),
    "node_white_noise_color_4d": ("PLANE", floored_white_noise("Color", "4D")),
    "node_voronoi_f1": ("PLANE", tex("ShaderNodeTexVoronoi", "Distance", Scale=6.0)),
    "node_voronoi_color": ("PLANE", tex("ShaderNodeTexVoronoi", "Color", Scale=6.0)),
    "node_voronoi_f2_manhattan": ("PLANE", tex("ShaderNodeTexVoronoi", "Distance",
                                               props={"feature": "F2", "distance": "MANHATTAN"}, Scale=5.0)),
    "node_voronoi_smooth_f1": ("PLANE", tex("ShaderNodeTexVoronoi", "Color", props={"feature": "SMOOTH_F1"},
                                            Scale=4.0, Smoothness=0.7)),
    "node_voronoi_edge": ("PLANE", tex("ShaderNodeTexVoronoi", "Distance", props={"feature": "DISTANCE_TO_EDGE"},
                                       Scale=5.0)),
    "node_voronoi_radius": ("PLANE", tex("ShaderNodeTexVoronoi", "Radius", props={"feature": "N_SPHERE_RADIUS"},
                                         Scale=5.0)),
    "node_voronoi_2d_chebychev": ("PLANE", tex("ShaderNodeTexVoronoi", "Color",
                                               props={"voronoi_dimensions": "2D", "distance": "CHEBYCHEV"}, Scale=7.0)),
    "node_voronoi_4d_minkowski": ("PLANE", tex("ShaderNodeTexVoronoi", "Distance",
                                               props={"voronoi_dimensions": "4D", "distance": "MINKOWSKI"}, W=0.4,
                                               Scale=4.0, Exponent=1.5)),
    "node_voronoi_1d_position": ("PLANE", tex("ShaderNodeTexVoronoi", "W", props={"voronoi_dimensions": "1D"},
                                              W=2.3, Scale=3.0)),
    "node_voronoi_position": ("PLANE", absolute(tex("ShaderNodeTexVoronoi", "Position", Scale=5.0,
                                                    Randomness=0.8))),
    "node_musgrave_fbm": ("PLANE", absolute(tex("ShaderNodeTexMusgrave", Scale=3.0, Detail=3.5))),
    "node_musgrave_multifractal": ("PLANE", tex("ShaderNodeTexMusgrave", props={"musgrave_type": "MULTIFRACTAL"},
                                                Scale=3.0, Detail=3.0)),
    "node_musgrave_hybrid": ("PLANE", absolute(tex("ShaderNodeTexMusgrave",
                                                   props={"musgrave_type": "HYBRID_MULTIFRACTAL"}, Scale=3.0,
                                                   Detail=4.0, Offset=0.6, Gain=1.2))),
    "node_musgrave_ridged": ("PLANE", tex("ShaderNodeTexMusgrave", props={"musgrave_type": "RIDGED_MULTIFRACTAL"},
                                          Scale=2.0, Detail=3.0, Offset=1.0, Gain=1.5)),
    "node_musgrave_hetero": ("PLANE", absolute(tex("ShaderNodeTexMusgrave", props={"musgrave_type": "HETERO_TERRAIN"},
                                                   Scale=3.0, Detail=2.5, Offset=0.5))),
    "node_musgrave_2d": ("PLANE", absolute(tex("ShaderNodeTexMusgrave", props={"musgrave_dimensions": "2D"},
                                               Scale=4.0, Detail=2.0))),
    "node_wave_bands": ("PLANE", tex("ShaderNodeTexWave", Scale=2.0, Distortion=2.0, Detail=2.0)),
    "node_wave_rings_saw": ("PLANE", tex("ShaderNodeTexWave", props={"wave_type": "RINGS", "wave_profile": "SAW"},
                                         Scale=1.5)),
    "node_wave_diagonal_tri": ("PLANE", tex("ShaderNodeTexWave", props={"bands_direction": "DIAGONAL",
                                                                        "wave_profile": "TRI"}, Scale=1.0,
                                            Phase_Offset=1.0)),
    "node_magic": ("PLANE", tex("ShaderNodeTexMagic", "Color", Scale=3.0, Distortion=1.5)),
    "node_magic_deep": ("PLANE", tex("ShaderNodeTexMagic", "Fac", props={"turbulence_depth": 6}, Scale=2.0)),
    "node_checker": ("PLANE", tex("ShaderNodeTexChecker", "Color", Scale=7.0)),
    "node_brick": ("PLANE", tex("ShaderNodeTexBrick", "Color", Scale=3.0, Mortar_Smooth=0.3, Bias=0.2)),
    "node_brick_fac": ("PLANE", tex("ShaderNodeTexBrick", "Fac", props={"offset": 0.3, "squash": 0.6,
                                                                        "squash_frequency": 3},
                                    Scale=4.0, Mortar_Size=0.05)),
    "node_gradient_linear": ("PLANE", tex("ShaderNodeTexGradient")),
    "node_gradient_easing": ("PLANE", tex("ShaderNodeTexGradient", props={"gradient_type": "EASING"})),
    "node_gradient_radial": ("PLANE", tex("ShaderNodeTexGradient", vector="Object",
                                          props={"gradient_type": "RADIAL"})),
    "node_gradient_sphere": ("PLANE", tex("ShaderNodeTexGradient", vector="Object",
                                          props={"gradient_type": "QUADRATIC_SPHERE"})),
    "node_gradient_diagonal": ("PLANE", tex("ShaderNodeTexGradient", props={"gradient_type": "DIAGONAL"})),
    "node_texcoord_generated": ("PLANE", coord_output("Generated")),
    "node_texcoord_uv": ("PLANE", coord_output("UV")),
    "node_texcoord_object": ("PLANE", coord_output("Object")),
    "node_texcoord_object_of_empty": ("PLANE", object_coords_of_empty),
    "node_texcoord_camera": ("PLANE", camera_coords),
    "node_texcoord_reflection": ("SPHERE", coord_output("Reflection")),
    "node_texcoord_normal": ("SPHERE", coord_output("Normal")),
    "node_geometry_position": ("PLANE", scaled(geometry_output("Position"), 0.5)),
    "node_geometry_normal": ("SPHERE", geometry_output("Normal")),
    "node_geometry_incoming": ("SPHERE", geometry_output("Incoming")),
    "node_geometry_tangent": ("SPHERE", geometry_output("Tangent")),
    "node_object_info_location": ("PLANE", absolute(lambda nt, c: node(nt, "ShaderNodeObjectInfo").outputs["Location"])),
    "node_layer_weight_fresnel": ("SPHERE", with_normal_input("ShaderNodeLayerWeight", "Fresnel", Blend=0.3)),
    "node_layer_weight_facing": ("SPHERE", with_normal_input("ShaderNodeLayerWeight", "Facing", Blend=0.7)),
    "node_fresnel": ("SPHERE", with_normal_input("ShaderNodeFresnel", "Fac", IOR=1.8)),
    "node_map_range_stepped": ("PLANE", map_range("STEPPED", To_Min=0.2, To_Max=0.9, Steps=5.0)),
    "node_map_range_smoother": ("PLANE", map_range("SMOOTHERSTEP", From_Min=0.8, From_Max=0.1)),
    "node_vector_math_cross": ("PLANE", vector_math("CROSS_PRODUCT", v1=(0.3, -0.5, 0.8))),
    "node_vector_math_distance": ("PLANE", vector_math("DISTANCE", "Value", v1=(0.5, 0.5, 0.5))),
    "node_vector_math_wrap": ("PLANE", vector_math("WRAP", v1=(0.3, 0.3, 0.3), v2=(0.0, 0.1, 0.0))),
    "node_hue_saturation": ("PLANE", hue_saturation),
    "node_blackbody": ("PLANE", lambda nt, c: _blackbody(nt, map_range("LINEAR", To_Min=1500.0, To_Max=12000.0)(nt, c))),
    # sin(20·x): its finite differences are secants over one pixel, so this checks Cycles' offsets and frame.
    "node_bump_sine": ("PLANE", bumped(lambda nt, c: _sinx(nt, c), distance=0.01)),
    "node_attribute_color": ("PLANE", lambda nt, c: node(nt, "ShaderNodeAttribute",
                                                         {"attribute_name": "Col"}).outputs["Color"]),
    "node_attribute_float": ("PLANE", lambda nt, c: node(nt, "ShaderNodeAttribute",
                                                         {"attribute_name": "weight"}).outputs["Fac"]),
    "node_attribute_alpha": ("PLANE", lambda nt, c: node(nt, "ShaderNodeAttribute",
                                                         {"attribute_name": "Col"}).outputs["Alpha"]),
    "node_color_attribute_default": ("PLANE", lambda nt, c: node(nt, "ShaderNodeVertexColor").outputs["Color"]),
    "node_uv_map_named": ("PLANE", lambda nt, c: node(nt, "ShaderNodeUVMap", {"uv_map": "Second"}).outputs["UV"]),
    "world_sky_preetham": ("SKY", sky("PREETHAM", turbidity=2.5, sun_direction=(0.3, -0.6, 0.45))),
    "world_sky_preetham_lit": ("SKY_LIT", sky("PREETHAM", turbidity=4.0, sun_direction=(-0.5, -0.5, 0.5))),
    "node_rgb_curves": ("PLANE", curves("ShaderNodeRGBCurve", tex("ShaderNodeTexNoise", "Color", Scale=3.0), "Color",
                                        _edit_rgb)),
    "node_vector_curves": ("PLANE", curves("ShaderNodeVectorCurve", lambda nt, c: c.outputs["Generated"], "Vector",
                                           _edit_vector)),
    "node_float_curve": ("PLANE", curves("ShaderNodeFloatCurve", tex("ShaderNodeTexNoise", Scale=2.0), "Value",
                                         _edit_float)),
    "node_object_info_index": ("PLANE", object_index),
    "node_object_info_color": ("PLANE", object_info_output("Color")),
    "node_object_info_alpha": ("PLANE", object_info_output("Alpha")),
    "node_object_info_random": ("PLANE", object_info_output("Random")),
    "node_texcoord_window": ("PLANE", coord_output("Window")),
    "node_wavelength": ("PLANE", lambda nt, c: _wavelength(nt, map_range("LINEAR", To_Min=380.0, To_Max=780.0)(nt, c))),
    "node_light_path_ray_length": ("SPHERE", scaled(light_path_output("Ray Length"), 0.2)),
    "world_light_path_camera": ("SKY_LIT", camera_only_world),
    "bump_plane_lit": ("PLANE_LIT", (tex("ShaderNodeTexNoise", Scale=3.0, Detail=2.0), False)),
    "displacement_plane_lit": ("PLANE_LIT", (tex("ShaderNodeTexWave", Scale=1.5, Distortion=1.0), True)),
    "node_bump_noise": ("PLANE", bumped(tex("ShaderNodeTexNoise", Scale=3.0, Detail=1.0), distance=0.2)),
    "node_bump_image_uv": ("PLANE", bumped(image_uv, strength=0.8, distance=0.05)),
    "node_bump_object_invert": ("PLANE", bumped(tex("ShaderNodeTexWave", vector="Object", Scale=1.0), distance=0.02,
                                                invert=True)),
    "node_bump_sphere": ("SPHERE", bumped(tex("ShaderNodeTexNoise", vector="Object", Scale=2.0, Detail=2.0),
                                          distance=0.3, then=layer_weight_of)),
    # A bump-mapped sphere under a sun: Cycles multiplies the BSDF of a bumped closure by Chiang et al.'s (2019)
    # bump shadowing term (1.06× Cycles without it; docs/light_paths.md, "Bump shadowing").
    "bump_sphere_lit": ("SPHERE_LIT", (tex("ShaderNodeTexVoronoi", "Distance", vector="Object", Scale=3.0), False)),
    # A smooth-shaded low-poly sphere (16 × 8 faces) under a sun, no bump: Cycles' shadow terminator geometry
    # offset (the object's default 0.1; docs/light_paths.md, "Shadow terminator offset").
    "terminator_sphere_lit": ("LOWPOLY_LIT", None),
}
# Not in the suite until they match: the Nishita sky from published spectral tables, not Cycles' own, measured at
# 1.26 (sky, 48 px), 0.98 with 13–64 % off per block (sun disc in view) and 1.054 (a ground lit by sky and sun)
# times Cycles' brightness. Run them with `parity.py --nodes --scenes world_sky_nishita,…`.
NODE_EXTRA_SCENES = {
    # The whole-render timing scene (procedural textures only): `parity.py --nodes --scenes procedural_heavy`.
    "procedural_heavy": ("PROCEDURAL_HEAVY", None),
    # Blackbody below 1500 K: Candela integrates Planck's law over the 20 nm CIE table, Cycles uses fitted curves;
    # 0.997 overall, green up to 2 % low and the (tiny) blue channel up to 12 % off near 800 K.
    "node_blackbody_low": ("PLANE", lambda nt, c: _blackbody(nt, map_range("LINEAR", To_Min=800.0, To_Max=2500.0)(nt, c))),
    "world_sky_nishita": ("SKY", sky("NISHITA", sun_elevation=math.radians(15.0), sun_rotation=math.radians(200.0),
                                     sun_disc=False)),
    "world_sky_nishita_disc": ("SKY", sky("NISHITA", sun_elevation=math.radians(12.0),
                                          sun_rotation=math.radians(170.0), sun_size=math.radians(3.0))),
    "world_sky_nishita_lit": ("SKY_LIT", sky("NISHITA", sun_elevation=math.radians(35.0),
                                             sun_rotation=math.radians(120.0))),
}
ALL_NODE_SCENES = {**NODE_SCENES, **NODE_EXTRA_SCENES}
# The quick mode of `make test` (parity.py --nodes --quick) renders them all: emission only, a few seconds each.
QUICK_NODE_SCENES = list(NODE_SCENES)


def _grid(name, size=2.0, cuts=8):
    bm = bmesh.new()
    bm.loops.layers.uv.new("UVMap")   # create_grid fills an existing UV layer
    bmesh.ops.create_grid(bm, x_segments=cuts, y_segments=cuts, size=size / 2.0, calc_uvs=True)
    me = bpy.data.meshes.new(name)
    bm.to_mesh(me)
    bm.free()
    _add_attributes(me)
    return me


def _add_attributes(me):
    """Mesh attributes for the Attribute, Color Attribute and UV Map scenes: "Col" (float colours per corner),
    "Bytes" (8-bit colours per vertex, the default colour attribute), "weight" (a float per vertex), "Second" (a
    second UV map, rotated and scaled)."""
    import numpy as np
    rng = np.random.default_rng(5)
    nl, nv = len(me.loops), len(me.vertices)
    col = me.color_attributes.new("Col", "FLOAT_COLOR", "CORNER")
    col.data.foreach_set("color", rng.uniform(0.05, 1.0, (nl, 4)).astype(np.float32).ravel())
    byte = me.color_attributes.new("Bytes", "BYTE_COLOR", "POINT")
    byte.data.foreach_set("color", rng.uniform(0.05, 1.0, (nv, 4)).astype(np.float32).ravel())
    me.color_attributes.render_color_index = me.color_attributes.find("Bytes")
    weight = me.attributes.new("weight", "FLOAT", "POINT")
    co = np.empty(3 * nv, np.float32)
    me.vertices.foreach_get("co", co)
    co = co.reshape(nv, 3)
    weight.data.foreach_set("value", (0.5 + 0.4 * np.sin(3.0 * co[:, 0]) * np.cos(2.0 * co[:, 1])).astype(np.float32))
    second = me.uv_layers.new(name="Second")
    uv = np.empty(2 * nl, np.float32)
    me.uv_layers["UVMap"].data.foreach_get("uv", uv)
    uv = uv.reshape(nl, 2)
    second.data.foreach_set("uv", np.stack([0.8 * uv[:, 1] + 0.1, 1.5 * uv[:, 0]], 1).astype(np.float32).ravel())
    me.uv_layers["UVMap"].active_render = True


def _camera(scene, location, rotation_deg, ortho_scale=None, lens=50.0):
    cam = bpy.data.cameras.new("Camera")
    if ortho_scale is not None:
        cam.type, cam.ortho_scale = "ORTHO", ortho_scale
    cam.lens, cam.clip_start, cam.clip_end = lens, 0.01, 100.0
    ob = bpy.data.objects.new("Camera", cam)
    ob.location = location
    ob.rotation_euler = tuple(math.radians(a) for a in rotation_deg)
    scene.collection.objects.link(ob)
    scene.camera = ob
    return ob


def _emission_material(name, graph):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nt = mat.node_tree
    nt.nodes.clear()
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    em = nt.nodes.new("ShaderNodeEmission")
    em.inputs["Strength"].default_value = 1.0
    coord = nt.nodes.new("ShaderNodeTexCoord")
    nt.links.new(graph(nt, coord), em.inputs["Color"])
    nt.links.new(em.outputs[0], out.inputs["Surface"])
    return mat


def _sky_world(scene, graph):
    w = bpy.data.worlds.new("Sky")
    w.use_nodes = True
    nt = w.node_tree
    nt.nodes.clear()
    bg = nt.nodes.new("ShaderNodeBackground")
    nt.links.new(graph(nt, None), bg.inputs["Color"])
    nt.links.new(bg.outputs[0], nt.nodes.new("ShaderNodeOutputWorld").inputs["Surface"])
    scene.world = w


def _lit_material(name, height_graph, displacement):
    """A white Diffuse BSDF whose normal is bumped by height_graph: through a Bump node into its Normal, or (with
    `displacement`) through a Displacement node into the Material Output (Cycles' "bump only")."""
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nt = mat.node_tree
    nt.nodes.clear()
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    diffuse = node(nt, "ShaderNodeBsdfDiffuse", Color=(0.8, 0.8, 0.8, 1.0))
    nt.links.new(diffuse.outputs[0], out.inputs["Surface"])
    if height_graph is None:   # no bump: the plain diffuse surface
        return mat
    coord = nt.nodes.new("ShaderNodeTexCoord")
    if displacement:
        d = node(nt, "ShaderNodeDisplacement", Midlevel=0.5, Scale=0.15)
        nt.links.new(height_graph(nt, coord), d.inputs["Height"])
        nt.links.new(d.outputs[0], out.inputs["Displacement"])
        mat.cycles.displacement_method = "BUMP"
    else:
        b = node(nt, "ShaderNodeBump", Strength=0.9, Distance=0.3)
        nt.links.new(height_graph(nt, coord), b.inputs["Height"])
        nt.links.new(b.outputs["Normal"], diffuse.inputs["Normal"])
    return mat


def _procedural_heavy_material(name):
    """A material made only of procedural textures, as real files use them: a Diffuse colour mixing Noise (detail 6,
    distortion) and Voronoi colours by a Musgrave ridge mask, bumped by detailed Noise, lit by a sun. The timing
    scene of docs/textures.md ("Cost")."""
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nt = mat.node_tree
    nt.nodes.clear()
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    coord = nt.nodes.new("ShaderNodeTexCoord")
    diffuse = node(nt, "ShaderNodeBsdfDiffuse")
    noise = tex("ShaderNodeTexNoise", "Color", Scale=4.0, Detail=6.0, Distortion=0.4)(nt, coord)
    cells = tex("ShaderNodeTexVoronoi", "Color", Scale=8.0)(nt, coord)
    mask = tex("ShaderNodeTexMusgrave", props={"musgrave_type": "RIDGED_MULTIFRACTAL"}, Scale=3.0, Detail=4.0,
               Offset=1.0, Gain=1.5)(nt, coord)
    mix = node(nt, "ShaderNodeMixRGB")
    nt.links.new(mask, mix.inputs["Fac"])
    nt.links.new(noise, mix.inputs["Color1"])
    nt.links.new(cells, mix.inputs["Color2"])
    nt.links.new(mix.outputs["Color"], diffuse.inputs["Color"])
    bump = node(nt, "ShaderNodeBump", Strength=0.5, Distance=0.05)
    nt.links.new(tex("ShaderNodeTexNoise", Scale=12.0, Detail=5.0)(nt, coord), bump.inputs["Height"])
    nt.links.new(bump.outputs["Normal"], diffuse.inputs["Normal"])
    nt.links.new(diffuse.outputs[0], out.inputs["Surface"])
    return mat


def build_node_scene(name, scene, size=128, out_dir="."):
    geometry, graph = ALL_NODE_SCENES[name]
    if geometry == "PROCEDURAL_HEAVY":
        build_node_scene_geometry(name, scene, "PLANE", _procedural_heavy_material(name))
        sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
        sun.data.energy, sun.data.angle = 3.0, 0.0
        sun.rotation_euler = (math.radians(30.0), 0.0, math.radians(30.0))
        scene.collection.objects.link(sun)
        return 1.0
    if geometry == "LOWPOLY_LIT":
        build_node_scene_geometry(name, scene, "LOWPOLY", _lit_material(name, None, False))
        sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
        sun.data.energy, sun.data.angle = 3.0, 0.0
        sun.rotation_euler = (math.radians(70.0), 0.0, math.radians(60.0))   # a terminator across the view
        scene.collection.objects.link(sun)
        return 1.0
    if geometry in ("PLANE_LIT", "SPHERE_LIT"):
        # Bump mapping as it is used: a bumped diffuse surface under a sun (direct light only on a lone object).
        height, displacement = graph
        base = "PLANE" if geometry == "PLANE_LIT" else "SPHERE"
        build_node_scene_geometry(name, scene, base, _lit_material(name, height, displacement))
        sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
        sun.data.energy, sun.data.angle = 3.0, 0.0
        sun.rotation_euler = (math.radians(40.0), 0.0, math.radians(30.0))
        scene.collection.objects.link(sun)
        return 1.0
    scene.world = None
    if geometry in ("SKY", "SKY_LIT"):
        # The world alone, seen by a wide camera looking 30° above the horizon toward −Y (the Sky Texture's
        # azimuth 0 is +Y); SKY_LIT adds a white diffuse ground that the sky lights (the importance-sampled world).
        _sky_world(scene, graph)
        _camera(scene, (0.0, 0.0, 1.0), (100.0 if geometry == "SKY" else 75.0, 0.0, 180.0), lens=14.0)
        if geometry == "SKY_LIT":
            me = _grid(name, size=40.0, cuts=1)
            mat = bpy.data.materials.new(name)
            mat.use_nodes = True
            mat.node_tree.nodes["Principled BSDF"].inputs["Roughness"].default_value = 1.0
            mat.node_tree.nodes["Principled BSDF"].inputs["Specular"].default_value = 0.0
            me.materials.append(mat)
            scene.collection.objects.link(bpy.data.objects.new(name, me))
        else:   # Candela renders nothing without triangles: a small plane behind the camera
            ob = bpy.data.objects.new(name, _grid(name, size=0.1, cuts=1))
            ob.location = (0.0, 10.0, 1.0)
            scene.collection.objects.link(ob)
        return 1.0
    # Another object's space for Texture Coordinate > Object with an object.
    frame = bpy.data.objects.new("Frame", None)
    frame.matrix_world = Matrix.LocRotScale(Vector((0.3, -0.1, 0.2)), Euler((0.2, 0.1, 0.7)), Vector((0.5, 0.7, 0.6)))
    scene.collection.objects.link(frame)
    build_node_scene_geometry(name, scene, geometry, _emission_material(name, graph))
    return 1.0


def build_node_scene_geometry(name, scene, geometry, mat):
    """The PLANE or SPHERE of the module docstring with its camera, material `mat`."""
    scene.world = None
    if geometry == "PLANE":
        me = _grid(name)
        ob = bpy.data.objects.new(name, me)
        ob.matrix_world = Matrix.LocRotScale(Vector((0.15, -0.1, 0.05)), Euler((0.0, 0.0, math.radians(20.0))),
                                             Vector((1.3, 1.1, 1.0)))
        _camera(scene, (0.1, -0.1, 3.0), (0.0, 0.0, 0.0), ortho_scale=1.7)
    else:
        bm = bmesh.new()
        lowpoly = geometry == "LOWPOLY"
        bmesh.ops.create_uvsphere(bm, u_segments=16 if lowpoly else 64, v_segments=8 if lowpoly else 32, radius=1.0)
        me = bpy.data.meshes.new(name)
        bm.to_mesh(me)
        bm.free()
        for poly in me.polygons:
            poly.use_smooth = True
        ob = bpy.data.objects.new(name, me)
        ob.matrix_world = Matrix.LocRotScale(Vector((0.0, 0.0, 0.0)), Euler((0.3, 0.0, 0.5)), Vector((1.0, 1.0, 1.0)))
        _camera(scene, (0.0, -4.5, 0.6), (82.0, 0.0, 0.0), lens=60.0)
    me.materials.append(mat)
    ob.pass_index = 3
    ob.color = (0.9, 0.45, 0.2, 0.6)   # Object Info > Color and Alpha
    scene.collection.objects.link(ob)
