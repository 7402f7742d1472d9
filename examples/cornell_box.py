"""The classic Cornell box, built from scratch for Candela and Cycles.

Run inside Blender:

    blender -b --factory-startup --python examples/cornell_box.py -- OUT.blend \
        [--engine CANDELA|CYCLES] [--size 512] [--samples 64] [--threads 0]

or import it from another script running inside Blender (benchmarks, parity tests):

    sys.path.insert(0, "<repo>/examples")
    import cornell_box
    scene = cornell_box.build_cornell_box(size=256, samples=64)
    cornell_box.configure_cycles(scene, samples=64, threads=2)

Geometry: the official Cornell data (graphics.cornell.edu/online/box/data.html), published in millimetres,
right-handed, y up, camera looking +z.  Converted to Blender (metres, Z up) by the proper rotation + offset

    X = (278 - x) / 1000,   Y = z / 1000,   Z = y / 1000

(det = +1, so face windings and normals keep their orientation).  The box is centred on X = 0, the camera sits
at (0, -0.8, 0.273) looking +Y, and the red wall (official x = 556) is on the LEFT of the image, the green wall
(x = 0) on the right, as in the published photographs.  Quads are triangulated 0-1-2, 0-2-3 explicitly (the
official left wall is non-planar by 3.2 mm, so the diagonal matters for parity between renderers).

Materials: Cycles node materials, Diffuse BSDF (roughness 0) with Bitterli's RGB reflectances; the light is an
emissive quad mesh (Emission shader, radiance (17, 12, 4) as in Bitterli's scene) lowered 0.5 mm below the
ceiling so that it is not coplanar with it.  World black, view transform Standard.
"""

import math
import os
import sys

import bpy

# ---------------------------------------------------------------------------------------------------------------
# Data
# ---------------------------------------------------------------------------------------------------------------

# Bitterli / Tungsten RGB reflectances (linear Rec.709).
RED = (0.63, 0.065, 0.05)
GREEN = (0.14, 0.45, 0.091)
WHITE = (0.725, 0.71, 0.68)
# Bitterli's light radiance Le = (17, 12, 4) = colour x strength.
LIGHT_RADIANCE = (17.0, 12.0, 4.0)

# Ceiling height (official y of the ceiling and of the light) and how far the light is lowered.
CEILING_Y_MM = 548.8
LIGHT_DROP_MM = 0.5

# Official camera: position (278, 273, -800) mm, looking +z, focal length 35 mm, film 25 x 25 mm.
CAMERA_POS_MM = (278.0, 273.0, -800.0)
LENS_MM = 35.0
SENSOR_MM = 25.0
FOV_DEG = math.degrees(2.0 * math.atan(0.5 * SENSOR_MM / LENS_MM))   # 39.3076

# Settings shared by both engines so that comparisons are fair.
DEFAULT_SIZE = 512
DEFAULT_SAMPLES = 64
MAX_BOUNCES = 12                     # Candela's default
# Blender's default pixel filter in both engines (Candela uses Cycles' meaning of the width: the
# Blackman-Harris window reaches 1.5 px each way at width 1.5).
PIXEL_FILTER = "BLACKMAN_HARRIS"
FILTER_WIDTH = 1.5
SEED = 0

# name -> (material, list of quads in official mm coordinates, y up)
SURFACES = {
    "Floor": ("White", [
        [(552.8, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 559.2), (549.6, 0.0, 559.2)],
    ]),
    "Ceiling": ("White", [
        [(556.0, 548.8, 0.0), (556.0, 548.8, 559.2), (0.0, 548.8, 559.2), (0.0, 548.8, 0.0)],
    ]),
    "BackWall": ("White", [
        [(549.6, 0.0, 559.2), (0.0, 0.0, 559.2), (0.0, 548.8, 559.2), (556.0, 548.8, 559.2)],
    ]),
    "RightWall": ("Green", [
        [(0.0, 0.0, 559.2), (0.0, 0.0, 0.0), (0.0, 548.8, 0.0), (0.0, 548.8, 559.2)],
    ]),
    "LeftWall": ("Red", [
        [(552.8, 0.0, 0.0), (549.6, 0.0, 559.2), (556.0, 548.8, 559.2), (556.0, 548.8, 0.0)],
    ]),
    "ShortBlock": ("White", [
        [(130.0, 165.0, 65.0), (82.0, 165.0, 225.0), (240.0, 165.0, 272.0), (290.0, 165.0, 114.0)],
        [(290.0, 0.0, 114.0), (290.0, 165.0, 114.0), (240.0, 165.0, 272.0), (240.0, 0.0, 272.0)],
        [(130.0, 0.0, 65.0), (130.0, 165.0, 65.0), (290.0, 165.0, 114.0), (290.0, 0.0, 114.0)],
        [(82.0, 0.0, 225.0), (82.0, 165.0, 225.0), (130.0, 165.0, 65.0), (130.0, 0.0, 65.0)],
        [(240.0, 0.0, 272.0), (240.0, 165.0, 272.0), (82.0, 165.0, 225.0), (82.0, 0.0, 225.0)],
    ]),
    "TallBlock": ("White", [
        [(423.0, 330.0, 247.0), (265.0, 330.0, 296.0), (314.0, 330.0, 456.0), (472.0, 330.0, 406.0)],
        [(423.0, 0.0, 247.0), (423.0, 330.0, 247.0), (472.0, 330.0, 406.0), (472.0, 0.0, 406.0)],
        [(472.0, 0.0, 406.0), (472.0, 330.0, 406.0), (314.0, 330.0, 456.0), (314.0, 0.0, 456.0)],
        [(314.0, 0.0, 456.0), (314.0, 330.0, 456.0), (265.0, 330.0, 296.0), (265.0, 0.0, 296.0)],
        [(265.0, 0.0, 296.0), (265.0, 330.0, 296.0), (423.0, 330.0, 247.0), (423.0, 0.0, 247.0)],
    ]),
    # 130 x 105 mm, official y = 548.8 (coplanar with the ceiling): lowered by LIGHT_DROP_MM.  The official
    # winding gives a -y normal, i.e. the light faces down into the box (both sides of a mesh emitter emit in
    # Cycles and Candela, so this only matters for tidiness).
    "Light": ("Light", [
        [(343.0, CEILING_Y_MM - LIGHT_DROP_MM, 227.0), (343.0, CEILING_Y_MM - LIGHT_DROP_MM, 332.0),
         (213.0, CEILING_Y_MM - LIGHT_DROP_MM, 332.0), (213.0, CEILING_Y_MM - LIGHT_DROP_MM, 227.0)],
    ]),
}


def to_blender(p_mm):
    """Official Cornell coordinates (mm, y up, camera looking +z) -> Blender metres, Z up, camera looking +Y."""
    x, y, z = p_mm
    return ((278.0 - x) * 1e-3, z * 1e-3, y * 1e-3)


# ---------------------------------------------------------------------------------------------------------------
# Scene construction
# ---------------------------------------------------------------------------------------------------------------

def _set(obj, name, value):
    """Set obj.name = value if the property exists; return True on success."""
    if obj is None or not hasattr(obj, name):
        return False
    try:
        setattr(obj, name, value)
        return True
    except (TypeError, ValueError, AttributeError):
        return False


def clear_scene(scene):
    for ob in list(scene.objects):
        bpy.data.objects.remove(ob, do_unlink=True)
    for coll in (bpy.data.meshes, bpy.data.materials, bpy.data.cameras, bpy.data.lights):
        for block in list(coll):
            if block.users == 0:
                coll.remove(block)


def _diffuse_material(name, rgb):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    mat.diffuse_color = (*rgb, 1.0)                 # viewport colour
    nt = mat.node_tree
    nt.nodes.clear()
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    out.target = "ALL"
    out.location = (300, 0)
    bsdf = nt.nodes.new("ShaderNodeBsdfDiffuse")
    bsdf.inputs["Color"].default_value = (*rgb, 1.0)
    bsdf.inputs["Roughness"].default_value = 0.0
    nt.links.new(bsdf.outputs["BSDF"], out.inputs["Surface"])
    return mat


def _emission_material(name, radiance):
    strength = max(radiance)
    colour = tuple(c / strength for c in radiance)
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    mat.diffuse_color = (*colour, 1.0)
    nt = mat.node_tree
    nt.nodes.clear()
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    out.target = "ALL"
    out.location = (300, 0)
    em = nt.nodes.new("ShaderNodeEmission")
    em.inputs["Color"].default_value = (*colour, 1.0)
    em.inputs["Strength"].default_value = strength
    nt.links.new(em.outputs["Emission"], out.inputs["Surface"])
    return mat


def _mesh_object(scene, name, quads_mm, material):
    verts = []
    faces = []
    for quad in quads_mm:
        base = len(verts)
        verts.extend(to_blender(p) for p in quad)
        # Explicit triangulation 0-1-2, 0-2-3 (the official convention).
        faces.append((base + 0, base + 1, base + 2))
        faces.append((base + 0, base + 2, base + 3))
    me = bpy.data.meshes.new(name)
    me.from_pydata(verts, [], faces)
    me.materials.append(material)
    for poly in me.polygons:
        poly.use_smooth = False
    me.validate()
    me.update()
    ob = bpy.data.objects.new(name, me)
    scene.collection.objects.link(ob)
    return ob


def _camera(scene):
    cam = bpy.data.cameras.new("Camera")
    cam.type = "PERSP"
    cam.lens_unit = "MILLIMETERS"
    cam.lens = LENS_MM
    cam.sensor_width = SENSOR_MM
    cam.sensor_height = SENSOR_MM
    cam.sensor_fit = "AUTO"             # square image: the 25 mm sensor spans the width (FOV 39.3076 deg)
    cam.clip_start = 0.01
    cam.clip_end = 100.0
    cam.shift_x = cam.shift_y = 0.0
    ob = bpy.data.objects.new("Camera", cam)
    ob.location = to_blender(CAMERA_POS_MM)
    # A Blender camera looks down its local -Z with +Y up; rotating +90 deg about X makes it look +Y with Z up,
    # i.e. the official direction (0, 0, 1) with up (0, 1, 0).
    ob.rotation_mode = "XYZ"
    ob.rotation_euler = (math.radians(90.0), 0.0, 0.0)
    scene.collection.objects.link(ob)
    scene.camera = ob
    return ob


def _world(scene):
    world = bpy.data.worlds.get("CornellWorld") or bpy.data.worlds.new("CornellWorld")
    world.color = (0.0, 0.0, 0.0)
    world.use_nodes = True
    nt = world.node_tree
    nt.nodes.clear()
    out = nt.nodes.new("ShaderNodeOutputWorld")
    bg = nt.nodes.new("ShaderNodeBackground")
    bg.inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    bg.inputs["Strength"].default_value = 0.0
    nt.links.new(bg.outputs["Background"], out.inputs["Surface"])
    scene.world = world
    return world


def engine_available(name, scene=None):
    """True when a render engine with this bl_idname is registered (e.g. the Candela add-on is enabled).

    Checked by trying to select it (the engine enum is dynamic), then restoring the previous engine.
    """
    scene = scene or bpy.context.scene
    if scene is None:
        return False
    before = scene.render.engine
    try:
        scene.render.engine = name
    except TypeError:
        return False
    ok = scene.render.engine == name
    scene.render.engine = before
    return ok


def configure_render(scene, size=DEFAULT_SIZE, threads=0):
    """Resolution, colour management and thread count shared by both engines."""
    r = scene.render
    r.resolution_x = size
    r.resolution_y = size
    r.resolution_percentage = 100
    r.pixel_aspect_x = r.pixel_aspect_y = 1.0
    r.use_border = False
    r.film_transparent = False
    r.use_motion_blur = False
    if threads and threads > 0:
        r.threads_mode = "FIXED"
        r.threads = int(threads)
    else:
        r.threads_mode = "AUTO"
    vs = scene.view_settings
    scene.display_settings.display_device = "sRGB"
    vs.view_transform = "Standard"
    vs.look = "None"
    vs.exposure = 0.0
    vs.gamma = 1.0
    vs.use_curve_mapping = False


def configure_cycles(scene, samples=DEFAULT_SAMPLES, threads=None):
    """Cycles settings for a fair comparison: CPU, fixed sample count, no denoising/adaptivity/clamping,
    the same filter and bounce limits as Candela."""
    if not hasattr(scene, "cycles"):
        return False
    c = scene.cycles
    c.device = "CPU"
    c.samples = int(samples)
    c.use_denoising = False
    _set(c, "use_preview_denoising", False)
    c.use_adaptive_sampling = False
    _set(c, "time_limit", 0.0)
    c.sample_clamp_direct = 0.0
    c.sample_clamp_indirect = 0.0
    c.seed = SEED
    c.use_animated_seed = False
    c.pixel_filter_type = PIXEL_FILTER
    c.filter_width = FILTER_WIDTH
    c.max_bounces = MAX_BOUNCES
    c.diffuse_bounces = MAX_BOUNCES
    c.glossy_bounces = MAX_BOUNCES
    c.transmission_bounces = MAX_BOUNCES
    c.transparent_max_bounces = MAX_BOUNCES
    c.volume_bounces = 0
    c.min_light_bounces = 0
    c.min_transparent_bounces = 0
    _set(c, "caustics_reflective", True)
    _set(c, "caustics_refractive", True)
    _set(c, "blur_glossy", 0.0)
    _set(scene.render, "film_exposure", 1.0)
    _set(c, "film_exposure", 1.0)
    if threads is not None and threads > 0:
        scene.render.threads_mode = "FIXED"
        scene.render.threads = int(threads)
    return True


def configure_candela(scene, samples=DEFAULT_SAMPLES, threads=None):
    """Candela settings matching configure_cycles (only properties the add-on actually has are set)."""
    props = getattr(scene, "candela", None)
    if props is None:
        return False
    _set(props, "samples", int(samples))
    _set(props, "max_bounces", MAX_BOUNCES)
    _set(props, "seed", SEED)
    _set(props, "use_animated_seed", False)
    _set(props, "integrator", "PATH")
    _set(props, "pixel_filter", PIXEL_FILTER)
    _set(props, "filter_width", FILTER_WIDTH)
    if threads is not None and threads > 0:
        scene.render.threads_mode = "FIXED"
        scene.render.threads = int(threads)
    return True


def set_engine(scene, engine=None):
    """engine None: CANDELA when the add-on is enabled, else CYCLES. Returns the engine set."""
    wanted = engine or ("CANDELA" if engine_available("CANDELA") else "CYCLES")
    try:
        scene.render.engine = wanted
    except TypeError:
        print(f"cornell_box: render engine {wanted!r} is not available; keeping {scene.render.engine!r}",
              file=sys.stderr)
    return scene.render.engine


def build_cornell_box(scene=None, size=DEFAULT_SIZE, samples=DEFAULT_SAMPLES, engine=None, threads=0,
                      clear=True):
    """Build the Cornell box in `scene` (default: the context scene) and configure both engines.

    Returns the scene.  Objects: Floor, Ceiling, BackWall, LeftWall (red), RightWall (green), ShortBlock,
    TallBlock, Light (emissive quad), Camera.
    """
    scene = scene or bpy.context.scene
    if clear:
        clear_scene(scene)
    mats = {
        "White": _diffuse_material("White", WHITE),
        "Red": _diffuse_material("Red", RED),
        "Green": _diffuse_material("Green", GREEN),
        "Light": _emission_material("Light", LIGHT_RADIANCE),
    }
    for name, (mat, quads) in SURFACES.items():
        _mesh_object(scene, name, quads, mats[mat])
    _camera(scene)
    _world(scene)
    scene.frame_set(1)
    configure_render(scene, size=size, threads=threads)
    configure_cycles(scene, samples=samples, threads=threads)
    configure_candela(scene, samples=samples, threads=threads)
    set_engine(scene, engine)
    return scene


# ---------------------------------------------------------------------------------------------------------------
# Command line
# ---------------------------------------------------------------------------------------------------------------

def _script_args(argv=None):
    argv = sys.argv if argv is None else argv
    return argv[argv.index("--") + 1:] if "--" in argv else []


def main(argv=None):
    import argparse
    ap = argparse.ArgumentParser(prog="cornell_box.py",
                                 description="Build the Cornell box and save it to a .blend file.")
    ap.add_argument("out", help="output .blend path")
    ap.add_argument("--engine", default=None, help="CANDELA or CYCLES (default: CANDELA if enabled, else CYCLES)")
    ap.add_argument("--size", type=int, default=DEFAULT_SIZE, help="square resolution (default 512)")
    ap.add_argument("--samples", type=int, default=DEFAULT_SAMPLES, help="samples per pixel (default 64)")
    ap.add_argument("--threads", type=int, default=0, help="render threads (0 = automatic)")
    args = ap.parse_args(_script_args(argv))

    engine = args.engine.upper() if args.engine else None
    if engine and not engine_available(engine):
        print(f"cornell_box: engine {engine} not available (is the add-on enabled?); "
              f"the scene will use {'CYCLES'}", file=sys.stderr)
        engine = "CYCLES"
    scene = build_cornell_box(size=args.size, samples=args.samples, engine=engine, threads=args.threads)
    out = os.path.abspath(args.out)
    os.makedirs(os.path.dirname(out), exist_ok=True)
    bpy.ops.wm.save_as_mainfile(filepath=out, check_existing=False, compress=False)
    print(f"cornell_box: saved {out} (engine {scene.render.engine}, {args.size}x{args.size}, "
          f"{args.samples} spp, FOV {FOV_DEG:.4f} deg)")


if __name__ == "__main__":
    main()
