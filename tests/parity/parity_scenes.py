"""The parity suite's scenes, built from scratch with Cycles nodes inside Blender (Candela and Cycles alike).

    sys.path[:0] = ["<repo>/examples", "<repo>/tests/parity"]
    import parity_scenes
    parity_scenes.build("area_disk", bpy.context.scene, size=128)

Every scene is one entry of SCENES: a builder that returns the image aspect.
The helpers of examples/scenes.py (materials, meshes, camera, world) and examples/cornell_box.py (the box, the
shared render settings) are reused; only what they lack is defined here.

Light scenes (docs/conventions.md §2 and §3): a white diffuse plane (albedo 1) 2 m below the light, with a small
white box casting a shadow (so the light's size shows in the penumbra), seen by an orthographic camera looking
straight down from 1.5 m — below the light, so the light itself is never in view and every pixel is the plane's
(or the box's) outgoing radiance E/π plus interreflections.
"""

import math

import bpy
from mathutils import Matrix

import cornell_box as cb
import node_scenes
import scenes as ex   # examples/scenes.py

WHITE = (1.0, 1.0, 1.0)
LIGHT_HEIGHT = 2.0


# ---------------------------------------------------------------------------------------------------------------
# Helpers examples/scenes.py does not have
# ---------------------------------------------------------------------------------------------------------------

def light(scene, name, kind, location, energy, rotation_deg=(0.0, 0.0, 0.0), scale=(1.0, 1.0, 1.0),
          color=(1.0, 1.0, 1.0), **props):
    """A Blender light of type `kind` ('POINT', 'SPOT', 'SUN', 'AREA') with data properties `props`
    (shadow_soft_size, spot_size, spot_blend, angle, shape, size, size_y)."""
    data = bpy.data.lights.new(name, kind)
    data.energy = energy
    data.color = color
    for key, value in props.items():
        setattr(data, key, value)
    ob = bpy.data.objects.new(name, data)
    ob.location = location
    ob.rotation_euler = tuple(math.radians(a) for a in rotation_deg)
    ob.scale = scale
    scene.collection.objects.link(ob)
    return ob


def principled(name, **inputs):
    """A Principled BSDF material; `inputs` by socket name with spaces as underscores (base_color=(r, g, b))."""
    def make(nt):
        n = nt.nodes.new("ShaderNodeBsdfPrincipled")
        for key, value in inputs.items():
            socket = n.inputs[key.replace("_", " ").title().replace("Ior", "IOR")]
            socket.default_value = (*value, 1.0) if isinstance(value, tuple) and len(value) == 3 else value
        return n
    return ex._material(name, make)


def ortho_camera(scene, location, ortho_scale):
    """An orthographic camera at `location` looking straight down (−Z), +Y up in the image."""
    cam = bpy.data.cameras.new("Camera")
    cam.type = "ORTHO"
    cam.ortho_scale = ortho_scale
    cam.sensor_fit = "AUTO"
    cam.clip_start, cam.clip_end = 0.01, 100.0
    ob = bpy.data.objects.new("Camera", cam)
    ob.location = location
    scene.collection.objects.link(ob)
    scene.camera = ob
    return ob


def environment_world(scene, rgb, strength, hdr_path=None):
    """World: a constant Background (rgb × strength), or an equirectangular Environment Texture (`hdr_path`)
    feeding the Background — the latter for when Candela reads environment textures."""
    if hdr_path is None:
        ex.world(scene, rgb, strength)
        return scene.world
    w = bpy.data.worlds.new("World")
    w.use_nodes = True
    nt = w.node_tree
    nt.nodes.clear()
    tex = nt.nodes.new("ShaderNodeTexEnvironment")
    tex.image = bpy.data.images.load(hdr_path, check_existing=True)
    bg = nt.nodes.new("ShaderNodeBackground")
    bg.inputs["Strength"].default_value = strength
    nt.links.new(tex.outputs["Color"], bg.inputs["Color"])
    nt.links.new(bg.outputs[0], nt.nodes.new("ShaderNodeOutputWorld").inputs["Surface"])
    scene.world = w
    return w


def write_test_hdr(path, width=256, height=128):
    """A synthetic equirectangular sky (blue gradient, warm ground, one bright sun blob) saved as Radiance HDR."""
    import numpy as np
    v = (np.arange(height) + 0.5) / height                 # 0 = bottom row
    u = (np.arange(width) + 0.5) / width
    uu, vv = np.meshgrid(u, v)
    theta = (1.0 - vv) * math.pi                            # polar angle from +Z
    phi = (0.5 - uu) * 2.0 * math.pi                        # Cycles' equirectangular convention
    d = np.stack([np.sin(theta) * np.cos(phi), np.sin(theta) * np.sin(phi), np.cos(theta)], -1)
    up = np.clip(d[..., 2], 0.0, 1.0)[..., None]
    sky = (1.0 - up) * np.array([0.9, 0.95, 1.0]) + up * np.array([0.25, 0.45, 0.9])
    ground = np.array([0.35, 0.28, 0.2])
    rgb = np.where(d[..., 2:3] >= 0.0, sky, ground)
    sun = np.array([math.cos(math.radians(40)) * math.cos(math.radians(30)),
                    math.cos(math.radians(40)) * math.sin(math.radians(30)), math.sin(math.radians(40))])
    rgb = rgb + 200.0 * (d @ sun > math.cos(math.radians(3.0)))[..., None] * np.array([1.0, 0.9, 0.75])
    img = bpy.data.images.new("parity_sky", width, height, alpha=True, float_buffer=True)
    px = np.concatenate([rgb, np.ones((height, width, 1))], -1).astype(np.float32)
    img.pixels.foreach_set(px.ravel())
    img.filepath_raw = path
    img.file_format = "HDR"
    img.save()
    bpy.data.images.remove(img)
    return path


def write_sun_hdr(path, width=256, height=128, sun=160000.0):
    """An equirectangular sky of radiance ~1 (a mild gradient) with a 2 × 2-texel sun of `sun` at 40° elevation:
    the case of issue 22 (a very bright sun of a few texels in an HDR). Written as flat (uncompressed) Radiance
    RGBE by numpy: Blender's Image.save() of a generated float image lost the sun (the file's maximum was 4.9)."""
    import numpy as np
    v = (np.arange(height) + 0.5) / height                 # row 0 = bottom (Blender's pixel order)
    rgb = np.ones((height, width, 3)) * np.array([0.9, 1.0, 1.1])
    rgb *= (0.8 + 0.4 * v)[:, None, None]
    sy, sx = int(height * (0.5 + 40.0 / 180.0)), int(width * 0.3)
    rgb[sy:sy + 2, sx:sx + 2] = sun * np.array([1.0, 0.95, 0.85])
    top_down = rgb[::-1].reshape(-1, 3)
    m = top_down.max(axis=1)
    mant, exp = np.frexp(m)                                # m = mant·2^exp, mant in [0.5, 1)
    scale = np.where(m > 1e-32, mant * 256.0 / np.maximum(m, 1e-38), 0.0)
    rgbe = np.zeros((top_down.shape[0], 4), np.uint8)
    rgbe[:, :3] = np.clip(top_down * scale[:, None], 0, 255).astype(np.uint8)
    rgbe[:, 3] = np.where(m > 1e-32, exp + 128, 0).astype(np.uint8)
    with open(path, "wb") as f:
        f.write(f"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y {height} +X {width}\n".encode())
        f.write(rgbe.tobytes())
    return path


# ---------------------------------------------------------------------------------------------------------------
# Scenes
# ---------------------------------------------------------------------------------------------------------------

def _plane_and_blocker(scene):
    white = ex.diffuse("White", WHITE)
    ex.rectangle(scene, "Plane", white, Matrix.Diagonal((4.0, 4.0, 1.0, 1.0)))          # 8 × 8 m at z = 0
    ex.cube(scene, "Blocker", white, Matrix.Translation((0.7, -0.5, 0.55)) @ Matrix.Diagonal((0.25, 0.25, 0.25, 1)))
    ortho_camera(scene, (0.0, 0.0, 1.5), 5.0)
    ex.world(scene, (0.0, 0.0, 0.0), 0.0)
    return 1.0


def _light_scene(make_light):
    def build(scene, **_):
        aspect = _plane_and_blocker(scene)
        make_light(scene)
        return aspect
    return build


def build_emissive_quad_over_plane(scene, **_):
    aspect = _plane_and_blocker(scene)
    # A 1 × 1 m quad 2 m up, tilted 20°, strength 25 (≡ a 100 W 1 × 1 m area light, docs/conventions.md §2.5).
    ex.rectangle(scene, "Emitter", ex.emission("Emitter", (1.0, 0.9, 0.8), 25.0),
                 Matrix.Translation((-0.2, 0.1, LIGHT_HEIGHT)) @ Matrix.Rotation(math.radians(20.0), 4, "X")
                 @ Matrix.Diagonal((0.5, 0.5, 1.0, 1.0)))
    return aspect


def build_cornell_area_light(scene, size=128, **_):
    """The example Cornell box with its emissive quad replaced by an area light of the same radiance and size:
    P = 4·A·L (docs/conventions.md §2.4), pointing down."""
    cb.build_cornell_box(scene, size=size, engine="CYCLES")
    quad = scene.objects["Light"]
    verts = [quad.matrix_world @ v.co for v in quad.data.vertices]
    bpy.data.objects.remove(quad, do_unlink=True)
    centre = sum(verts, verts[0] * 0.0) / len(verts)
    size_x = (verts[0] - verts[3]).length    # official x extent (130 mm)
    size_y = (verts[0] - verts[1]).length    # official z extent (105 mm)
    strength = max(cb.LIGHT_RADIANCE)
    colour = tuple(c / strength for c in cb.LIGHT_RADIANCE)
    light(scene, "AreaLight", "AREA", centre, 4.0 * size_x * size_y * strength, color=colour,
          shape="RECTANGLE", size=size_x, size_y=size_y)    # default orientation: shines down (−Z)
    return 1.0


def build_cornell_emissive_quad(scene, size=128, **_):
    cb.build_cornell_box(scene, size=size, engine="CYCLES")
    return 1.0


def build_cornell_quad_near_ceiling(scene, size=128, **_):
    """The Cornell box with its emissive quad 10 mm below the ceiling instead of 0.5 mm: light fixtures close to
    a ceiling. Both faces of a mesh emitter emit, so the back face lights the ceiling above it and some of that
    light leaves the gap; the shading points there are 10 mm from the emitter, which makes shadow rays toward it
    sensitive to how they avoid hitting the emitter itself."""
    cb.build_cornell_box(scene, size=size, engine="CYCLES")
    scene.objects["Light"].location.z -= 0.0095
    return 1.0


def build_principled_spheres(scene, **_):
    """A row of Principled spheres (dielectric, metal, rough glass, clearcoat) on a grey floor, under an area
    light and a dim sky."""
    ex.rectangle(scene, "Floor", ex.diffuse("Floor", (0.5, 0.5, 0.5)), Matrix.Diagonal((6, 6, 1, 1)))
    ex.rectangle(scene, "Back", ex.diffuse("Back", (0.6, 0.55, 0.5)),
                 Matrix.Translation((0, 2.0, 2.0)) @ Matrix.Rotation(math.radians(90.0), 4, "X")
                 @ Matrix.Diagonal((6, 2, 1, 1)))
    spheres = [
        ("Dielectric", dict(base_color=(0.8, 0.15, 0.1), roughness=0.35, specular=0.5)),
        ("Metal", dict(base_color=(0.95, 0.7, 0.35), metallic=1.0, roughness=0.25)),
        ("RoughGlass", dict(base_color=(0.9, 0.95, 1.0), transmission=1.0, roughness=0.2, ior=1.45)),
        ("Clearcoat", dict(base_color=(0.1, 0.25, 0.7), roughness=0.6, clearcoat=1.0, clearcoat_roughness=0.05)),
    ]
    for i, (name, inputs) in enumerate(spheres):
        ex.sphere(scene, name, principled(name, **inputs), (-1.65 + 1.1 * i, 0.0, 0.5), 0.5)
    light(scene, "Key", "AREA", (1.0, -2.0, 3.5), 400.0, rotation_deg=(35.0, 0.0, 15.0), shape="RECTANGLE",
          size=2.0, size_y=1.0)
    ex.camera(scene, (0.0, -6.0, 1.6), (80.0, 0.0, 0.0), lens=42.0)
    ex.world(scene, (0.6, 0.7, 1.0), 0.2)
    return 2.0


# Cycles 3.4's default Light Paths (Render > Light Paths), which the *_cycles_defaults scenes render with; Candela
# takes them through the add-on's "Light Paths from Cycles" copy (addon/candela/params.py, docs/light_paths.md).
CYCLES_DEFAULT_LIGHT_PATHS = {"max_bounces": 12, "diffuse_bounces": 4, "glossy_bounces": 4, "transmission_bounces": 12,
                              "transparent_max_bounces": 8, "sample_clamp_direct": 0.0, "sample_clamp_indirect": 10.0,
                              "blur_glossy": 1.0, "caustics_reflective": True, "caustics_refractive": True}


def _open_room(scene, floor, back):
    ex.rectangle(scene, "Floor", floor, Matrix.Diagonal((6, 6, 1, 1)))
    ex.rectangle(scene, "Back", back, Matrix.Translation((0, 2.0, 2.0)) @ Matrix.Rotation(math.radians(90.0), 4, "X")
                 @ Matrix.Diagonal((6, 2, 1, 1)))
    light(scene, "Key", "AREA", (1.0, -2.0, 3.5), 400.0, rotation_deg=(35.0, 0.0, 15.0), shape="RECTANGLE",
          size=1.0, size_y=0.6)
    ex.camera(scene, (0.0, -6.0, 1.6), (80.0, 0.0, 0.0), lens=42.0)
    ex.world(scene, (0.6, 0.7, 1.0), 0.1)


def build_glossy_cycles_defaults(scene, **_):
    """Glossy spheres (sharp, medium, rough) in front of a glossy back wall on a diffuse floor, under a small area
    light, with Cycles' default Light Paths: glossy inter-reflections past 4 bounces are cut, sharp reflections seen
    after a diffuse bounce are blurred (Filter Glossy 1) and indirect light is clamped at 10."""
    _open_room(scene, ex.diffuse("Floor", (0.6, 0.6, 0.6)), ex.glossy("Back", (0.7, 0.7, 0.75), 0.15, "GGX"))
    for i, r in enumerate((0.02, 0.15, 0.4)):
        ex.sphere(scene, f"Glossy{i}", ex.glossy(f"Glossy{i}", (0.9, 0.8, 0.6), r, "GGX"), (-1.1 + 1.1 * i, 0.0, 0.5),
                  0.5)
    return 2.0


def build_glass_cycles_defaults(scene, **_):
    """A sharp glass sphere and a rough Principled glass sphere on a diffuse floor under a small area light, with
    Cycles' default Light Paths: the caustics on the floor come through Filter Glossy (sharp glass made rough after
    the diffuse bounce), transmission is cut after 12 and indirect light is clamped at 10."""
    _open_room(scene, ex.diffuse("Floor", (0.6, 0.6, 0.6)), ex.diffuse("Back", (0.6, 0.55, 0.5)))
    ex.sphere(scene, "Glass", ex.glass("Glass", 1.5), (-0.7, 0.0, 0.5), 0.5)
    ex.sphere(scene, "RoughGlass", principled("RoughGlass", base_color=(0.9, 0.95, 1.0), transmission=1.0,
                                              roughness=0.25, ior=1.45), (0.7, 0.0, 0.5), 0.5)
    return 2.0


def build_environment(scene, hdr_path=None, **_):
    """Lit by the world only: a constant colour (or, with `hdr_path`, an equirectangular environment)."""
    ex.rectangle(scene, "Floor", ex.diffuse("Floor", (0.7, 0.7, 0.7)), Matrix.Diagonal((5, 5, 1, 1)))
    ex.sphere(scene, "Diffuse", ex.diffuse("Diffuse", (0.8, 0.4, 0.2)), (-0.9, 0.0, 0.5), 0.5)
    ex.sphere(scene, "Glossy", ex.glossy("Glossy", (0.8, 0.8, 0.8), 0.3, "GGX"), (0.3, 0.3, 0.5), 0.5)
    ex.cube(scene, "Box", ex.diffuse("Box", (0.3, 0.5, 0.3)),
            Matrix.Translation((1.3, -0.4, 0.3)) @ Matrix.Rotation(math.radians(25.0), 4, "Z")
            @ Matrix.Diagonal((0.3, 0.3, 0.3, 1)))
    ex.camera(scene, (0.0, -5.0, 2.2), (72.0, 0.0, 0.0), lens=40.0)
    environment_world(scene, (0.8, 0.9, 1.0), 1.0, hdr_path)
    return 1.5


def build_environment_hdr(scene, out_dir=".", **kw):
    import os
    path = os.path.join(out_dir, "parity_sky.hdr")
    if not os.path.exists(path):
        write_test_hdr(path)
    return build_environment(scene, hdr_path=path, **kw)


def _sun_hdr_scene(interpolation):
    """A diffuse floor and sphere lit only by write_sun_hdr's sky through an Environment Texture with
    `interpolation` (Linear is Blender's default): the per-sample variance test of issue 22
    (tests/parity/env_variance.py)."""
    def build(scene, out_dir=".", **_):
        import os
        path = os.path.join(out_dir, "sun_sky.hdr")
        if not os.path.exists(path):
            write_sun_hdr(path)
        ex.rectangle(scene, "Floor", ex.diffuse("Floor", (0.7, 0.7, 0.7)), Matrix.Diagonal((5, 5, 1, 1)))
        ex.sphere(scene, "Diffuse", ex.diffuse("Diffuse", (0.8, 0.4, 0.2)), (0.0, 0.0, 0.6), 0.6)
        ex.camera(scene, (0.0, -5.0, 2.2), (72.0, 0.0, 0.0), lens=40.0)
        world = environment_world(scene, (1.0, 1.0, 1.0), 1.0, path)
        for node in world.node_tree.nodes:
            if node.bl_idname == "ShaderNodeTexEnvironment":
                node.interpolation = interpolation
        return 1.5
    return build


def _linear_keys(ob, path, frames_values):
    """Keyframes of `ob`'s property `path` (frame → value), linearly interpolated (no easing)."""
    for frame, value in frames_values:
        setattr(ob, path, value)
        ob.keyframe_insert(path, frame=frame)
    for fc in ob.animation_data.action.fcurves:
        for kp in fc.keyframe_points:
            kp.interpolation = "LINEAR"


def _motion_room(scene, back=(0.5, 0.55, 0.6)):
    """A floor and back wall under an area light, lit also by a dim world: the motion scenes' stage."""
    ex.rectangle(scene, "Floor", ex.diffuse("Floor", (0.6, 0.6, 0.6)), Matrix.Diagonal((6, 6, 1, 1)))
    ex.rectangle(scene, "Back", ex.diffuse("Back", back),
                 Matrix.Translation((0, 2.0, 2.0)) @ Matrix.Rotation(math.radians(90.0), 4, "X")
                 @ Matrix.Diagonal((6, 2, 1, 1)))
    light(scene, "Key", "AREA", (1.0, -2.0, 3.5), 400.0, rotation_deg=(35.0, 0.0, 15.0), shape="RECTANGLE",
          size=1.0, size_y=0.6)
    ex.world(scene, (0.6, 0.7, 1.0), 0.2)


def build_moving_cube(scene, **_):
    """Motion blur of an object (Shutter 0.5, Position Center, Motion Steps 1: three samples): a light 1 m cube in
    front of a dark wall, sliding 4 m and turning 90° per frame (linear keys at frames 0 and 2), so over the shutter
    around frame 1 it sweeps 2 m and 45°, its shadow blurring with it."""
    _motion_room(scene, back=(0.05, 0.05, 0.06))
    cube = ex.cube(scene, "Cube", ex.diffuse("Cube", (0.9, 0.8, 0.7)),
                   Matrix.Translation((0.0, 0.0, 0.5)) @ Matrix.Diagonal((0.5, 0.5, 0.5, 1)))
    _linear_keys(cube, "location", [(0, (-4.0, 0.0, 0.5)), (2, (4.0, 0.0, 0.5))])
    _linear_keys(cube, "rotation_euler", [(0, (0.0, 0.0, 0.0)), (2, (0.0, 0.0, math.radians(180.0)))])
    ex.camera(scene, (0.0, -6.0, 1.6), (80.0, 0.0, 0.0), lens=42.0)
    scene.frame_set(1)
    return 2.0


def build_camera_pan(scene, **_):
    """Motion blur of the camera (Shutter 0.5, Position Start: the frame opens the shutter): still spheres and a
    box seen by a camera panning 20° per frame (linear keys at frames 0 and 2), so 10° over the shutter from
    frame 1."""
    _motion_room(scene)
    ex.sphere(scene, "Diffuse", ex.diffuse("Diffuse", (0.8, 0.4, 0.2)), (-0.9, 0.0, 0.5), 0.5)
    ex.sphere(scene, "Glossy", ex.glossy("Glossy", (0.8, 0.8, 0.8), 0.3, "GGX"), (0.3, 0.3, 0.5), 0.5)
    ex.cube(scene, "Box", ex.diffuse("Box", (0.3, 0.5, 0.3)),
            Matrix.Translation((1.3, -0.4, 0.3)) @ Matrix.Rotation(math.radians(25.0), 4, "Z")
            @ Matrix.Diagonal((0.3, 0.3, 0.3, 1)))
    cam = ex.camera(scene, (0.0, -5.0, 2.2), (72.0, 0.0, 0.0), lens=40.0)
    _linear_keys(cam, "rotation_euler", [(0, tuple(math.radians(a) for a in (72.0, 0.0, 20.0))),
                                         (2, tuple(math.radians(a) for a in (72.0, 0.0, -20.0)))])
    scene.frame_set(1)
    return 1.5


# Motion blur scenes: Render Properties > Motion Blur on (after configure_render, which turns it off), with Cycles'
# shutter position.
MOTION_SCENES = {"moving_cube": "CENTER", "camera_pan": "START"}


def _lights():
    h = LIGHT_HEIGHT
    return {
        # 1000 W point light, as in the table of docs/conventions.md §3.
        "point": lambda s: light(s, "Point", "POINT", (0.0, 0.0, h), 1000.0, shadow_soft_size=0.0),
        "point_radius": lambda s: light(s, "Point", "POINT", (0.3, 0.2, h), 1000.0, shadow_soft_size=0.5),
        "spot_blend": lambda s: light(s, "Spot", "SPOT", (0.0, 0.2, h), 1000.0, rotation_deg=(12.0, 0.0, 0.0),
                                      spot_size=math.radians(80.0), spot_blend=0.4, shadow_soft_size=0.1),
        "sun_angle": lambda s: light(s, "Sun", "SUN", (0.0, 0.0, h), 3.0, rotation_deg=(30.0, 0.0, 20.0),
                                     angle=math.radians(15.0)),
        "area_square": lambda s: light(s, "Area", "AREA", (0.0, 0.0, h), 100.0, rotation_deg=(20.0, 0.0, 0.0),
                                       shape="SQUARE", size=1.0),
        # Rectangle and ellipse under a non-uniform object scale: Cycles counts the scale in the area.
        "area_rect": lambda s: light(s, "Area", "AREA", (0.2, 0.0, h), 100.0, rotation_deg=(15.0, 0.0, 30.0),
                                     scale=(1.2, 0.8, 1.0), shape="RECTANGLE", size=1.5, size_y=0.5),
        "area_disk": lambda s: light(s, "Area", "AREA", (0.0, 0.0, h), 100.0, shape="DISK", size=1.0),
        "area_ellipse": lambda s: light(s, "Area", "AREA", (-0.2, 0.1, h), 100.0, rotation_deg=(0.0, 10.0, 45.0),
                                        scale=(1.3, 1.0, 1.0), shape="ELLIPSE", size=1.4, size_y=0.6),
    }


# name → builder(scene, size=..., out_dir=...) returning the image aspect (width / height). tests/parity/parity.py
# lists the same names (it runs outside Blender) and which of them the quick mode of `make test` renders.
SCENES = {name: _light_scene(make) for name, make in _lights().items()}
SCENES.update({
    "emissive_quad": build_emissive_quad_over_plane,
    "cornell_area_light": build_cornell_area_light,
    "cornell_emissive_quad": build_cornell_emissive_quad,
    "cornell_quad_near_ceiling": build_cornell_quad_near_ceiling,
    "principled_spheres": build_principled_spheres,
    "environment": build_environment,
    "glossy_cycles_defaults": build_glossy_cycles_defaults,
    "glass_cycles_defaults": build_glass_cycles_defaults,
    "moving_cube": build_moving_cube,
    "camera_pan": build_camera_pan,
})
# Not in the default list until Candela reads Environment Texture nodes (issue #3, h-textures): run it with
# `--scenes environment_hdr`, then add it to parity.py's ALL_SCENES.
EXTRA_SCENES = {"environment_hdr": build_environment_hdr,
                "sun_hdr_linear": _sun_hdr_scene("Linear"), "sun_hdr_closest": _sun_hdr_scene("Closest")}
# Per-node scenes (tests/parity/node_scenes.py): run by `parity.py --nodes`.
NODE_SCENES = {name: (lambda n: lambda scene, size=128, out_dir=".": node_scenes.build_node_scene(
    n, scene, size=size, out_dir=out_dir))(name) for name in node_scenes.ALL_NODE_SCENES}
BY_NAME = {**SCENES, **EXTRA_SCENES, **NODE_SCENES}


def build(name, scene=None, size=128, threads=0, out_dir="."):
    """Build parity scene `name` into `scene` (default: the context scene), `size` pixels wide, and apply the
    shared render settings (examples/cornell_box.py: same bounces, seed, colour management on both engines)."""
    scene = scene or bpy.context.scene
    if name not in BY_NAME:
        raise KeyError(f"unknown parity scene '{name}' (known: {', '.join(BY_NAME)})")
    cb.clear_scene(scene)
    for coll in (bpy.data.worlds, bpy.data.images):
        for block in list(coll):
            if block.users == 0:
                coll.remove(block)
    aspect = BY_NAME[name](scene, size=size, out_dir=out_dir)
    cb.configure_render(scene, size=size, threads=threads)
    scene.render.resolution_y = max(1, round(size / aspect))
    cb.configure_cycles(scene, threads=threads)
    cb.configure_candela(scene, threads=threads)
    if name in MOTION_SCENES:
        scene.render.use_motion_blur = True
        scene.render.motion_blur_shutter = 0.5
        scene.cycles.motion_blur_position = MOTION_SCENES[name]
    if name.endswith("_cycles_defaults"):
        for key, value in CYCLES_DEFAULT_LIGHT_PATHS.items():
            setattr(scene.cycles, key, value)
    # Candela's Light Paths settings follow Cycles' for every scene: the suite renders all scenes in one Blender
    # scene, so values copied for a *_cycles_defaults scene would otherwise stay for the scenes after it.
    if hasattr(scene, "candela"):
        from candela.params import copy_cycles_light_paths
        copy_cycles_light_paths(scene)
    return scene
