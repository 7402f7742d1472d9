"""THE mapping from Blender settings to the native params dict (docs/architecture.md, "Params").

Inputs: `scene.candela` (properties.py), render resolution / percentage / border / pixel aspect / threads, the
camera's data, and command-line overrides. Nothing else builds params.
"""

import numpy as np

from . import cmdline, schema
from .export.common import ExportError
from .passes import native_pass_list

# The settings every integrator reads, sent always (the native side publishes them as common_params; a test checks
# that this list is that one).
COMMON_KEYS = ("samples", "seed", "sampler", "pixel_filter", "filter_width", "time_limit", "noise_threshold")


def setting_value(spec, value):
    """A property's value as the native side takes it, by the published type."""
    kind = spec["type"]
    if kind == "BOOL":
        return bool(value)
    if kind == "INT":
        return int(value)
    if kind == "FLOAT":
        return float(value)
    return str(value)


def integrator_params(settings, integrator=None):
    """The chosen integrator's own settings (and only its: another integrator's keys would be unknown to it), or
    those of `integrator` (the viewport's fallback to PATH)."""
    specs = schema.integrator_params().get(integrator or settings.integrator, [])
    return {spec["key"]: setting_value(spec, getattr(settings, spec["key"])) for spec in specs}


# Cycles' Film settings Candela shares (scene.cycles, as render.film_transparent is shared), with Cycles' defaults
# where the Cycles add-on is not there to hold them.
FILM_DEFAULTS = {"film_exposure": 1.0, "film_transparent_glass": False, "film_transparent_roughness": 0.1}


def film_params(scene):
    """Film > Exposure and Transparent Glass, read from Cycles' own properties (a scene set up for Cycles keeps them)."""
    cycles = getattr(scene, "cycles", None)
    out = {}
    for key, default in FILM_DEFAULTS.items():
        value = getattr(cycles, key, default) if cycles is not None else default
        out[key] = bool(value) if isinstance(default, bool) else float(value)
    return out


# Cycles' Light Paths properties → Candela's published settings of the same meaning (docs/light_paths.md).
CYCLES_LIGHT_PATHS = {"max_bounces": "max_bounces", "diffuse_bounces": "diffuse_bounces",
                      "glossy_bounces": "glossy_bounces", "transmission_bounces": "transmission_bounces",
                      "transparent_max_bounces": "transparent_bounces", "sample_clamp_direct": "clamp_direct",
                      "sample_clamp_indirect": "clamp_indirect", "blur_glossy": "filter_glossy",
                      "caustics_reflective": "caustics_reflective", "caustics_refractive": "caustics_refractive"}


def copy_cycles_light_paths(scene):
    """Sets scene.candela's Light Paths settings to the values scene.cycles holds; returns the keys copied."""
    cycles = getattr(scene, "cycles", None)
    copied = []
    if cycles is None:
        return copied
    for source, key in CYCLES_LIGHT_PATHS.items():
        if hasattr(cycles, source) and hasattr(scene.candela, key):
            setattr(scene.candela, key, type(getattr(scene.candela, key))(getattr(cycles, source)))
            copied.append(key)
    return copied


LIGHT_PATHS_PANELS = ("Max Bounces", "Clamping", "Caustics")


def unapplied_light_paths(settings):
    """The Light Paths settings (CYCLES_LIGHT_PATHS, Max Bounces aside) set away from their unbiased defaults that the
    chosen integrator does not apply: it does not publish them (a path started at a light has no camera-side bounce
    count, ray type or clamp), so its image is the full, unclamped solution. [(label, value), ...] in PATH's order."""
    published = schema.integrator_params()
    mine = {spec["key"] for spec in published.get(settings.integrator, [])}
    out = []
    for spec in published.get("PATH", []):
        key = spec["key"]
        if key == "max_bounces" or key not in CYCLES_LIGHT_PATHS.values() or key in mine:
            continue
        value = setting_value(spec, getattr(settings, key, spec["default"]))
        if value != setting_value(spec, spec["default"]):
            group = spec.get("group") or ""
            out.append((f"{group} > {spec['label']}" if group in LIGHT_PATHS_PANELS else spec["label"], value))
    return out


def frame_size(render):
    """Full frame in pixels with the resolution percentage applied (Blender's integer arithmetic)."""
    return (render.resolution_x * render.resolution_percentage // 100,
            render.resolution_y * render.resolution_percentage // 100)


def crop_window(render):
    """(x0, y0, x1, y1) border window in pixels, y from the bottom, x1/y1 exclusive; the full frame without border."""
    width, height = frame_size(render)
    if not render.use_border:
        return 0, 0, width, height
    x0, x1 = int(render.border_min_x * width), int(render.border_max_x * width)
    y0, y1 = int(render.border_min_y * height), int(render.border_max_y * height)
    if x1 <= x0 or y1 <= y0:
        raise ValueError(f"the render border is empty ({x1 - x0}x{y1 - y0} pixels)")
    return x0, y0, x1, y1


def result_size(render):
    """Size of the RenderResult Blender expects from the engine: the border window (docs/conventions.md §1)."""
    x0, y0, x1, y1 = crop_window(render)
    return x1 - x0, y1 - y0


# The panoramic projections the native camera renders (scene/camera.h); Blender 3.4 keeps a camera's panorama
# settings in the Cycles add-on's properties (camera.data.cycles).
PANORAMA_TYPES = ("EQUIRECTANGULAR", "FISHEYE_EQUIDISTANT", "FISHEYE_EQUISOLID")


class CameraError(ExportError, ValueError):
    """A camera setting Candela cannot render; the message names the camera and the setting."""


def panorama_params(camera_data):
    """The panorama keys of a PANO camera (Cycles' settings), or CameraError naming what is missing."""
    settings = getattr(camera_data, "cycles", None)
    if settings is None:
        raise CameraError(f"camera '{camera_data.name}' is panoramic, but Blender 3.4 keeps panorama settings in "
                          "the Cycles add-on, which is disabled: enable Cycles (Edit > Preferences > Add-ons)")
    kind = settings.panorama_type
    if kind not in PANORAMA_TYPES:
        raise CameraError(f"camera '{camera_data.name}': panorama type {kind} is not supported (Candela renders "
                          "Equirectangular, Fisheye Equidistant and Fisheye Equisolid)")
    return {"panorama_type": kind, "fisheye_fov": float(settings.fisheye_fov),
            "fisheye_lens": float(settings.fisheye_lens), "latitude_min": float(settings.latitude_min),
            "latitude_max": float(settings.latitude_max), "longitude_min": float(settings.longitude_min),
            "longitude_max": float(settings.longitude_max)}


def camera_params(camera_data):
    cam = camera_data
    params = {
        "camera_type": {"ORTHO": "ORTHO", "PANO": "PANO"}.get(cam.type, "PERSP"),
        "sensor_fit": cam.sensor_fit,
        "sensor_width": float(cam.sensor_width),
        "sensor_height": float(cam.sensor_height),
        "lens": float(cam.lens),
        "ortho_scale": float(cam.ortho_scale),
        "shift_x": float(cam.shift_x),
        "shift_y": float(cam.shift_y),
        "clip_start": float(cam.clip_start),
        "clip_end": float(cam.clip_end),
    }
    if cam.type == 'PANO':
        params.update(panorama_params(cam))
    return params


def focus_object_distance(camera_matrix, focus_object, subtarget=""):
    """Cycles' focus distance for a focus object: its origin's (or the bone's head's) distance along the camera's view
    axis, |dot(view_dir, target − camera)|."""
    m = np.array(camera_matrix, np.float64)
    view = -m[:3, 2] / max(np.linalg.norm(m[:3, 2]), 1e-30)   # the camera looks down its −Z axis
    target = np.array(focus_object.matrix_world, np.float64)
    if subtarget and focus_object.type == 'ARMATURE' and focus_object.pose is not None:
        bone = focus_object.pose.bones.get(subtarget)
        if bone is not None:
            target = target @ np.array(bone.matrix, np.float64)
    return float(abs(np.dot(view, target[:3, 3] - m[:3, 3])))


def dof_params(camera_data, camera_object=None):
    """Depth of field as Blender's camera holds it (Camera > Depth of Field); the native side turns the f-stop into
    Cycles' aperture radius. `camera_object` (evaluated) is needed for a focus object."""
    dof = camera_data.dof
    if not dof.use_dof:
        return {"use_dof": False}
    focus = float(dof.focus_distance)
    if dof.focus_object is not None and camera_object is not None:
        focus = focus_object_distance(camera_object.matrix_world, dof.focus_object, dof.focus_subtarget)
    return {
        "use_dof": True,
        "focus_distance": focus,
        "aperture_fstop": float(dof.aperture_fstop),
        "aperture_blades": int(dof.aperture_blades),
        "aperture_rotation": float(dof.aperture_rotation),
        "aperture_ratio": float(dof.aperture_ratio),
    }


def animation_params(settings, is_animation):
    """AUTO's "animation" param (docs/auto.md, "Animation"): true for a frame of an animation render (Blender's
    RenderEngine.is_animation), so AUTO chooses no integrator whose image flickers from frame to frame. Not the
    scene's frame range: Blender's default scene spans frames 1-250, and a still of it is a still. Only AUTO reads
    it (another integrator would report it as an unused setting)."""
    return {"animation": True} if settings.integrator == "AUTO" and is_animation else {}


def to_native_params(scene, camera_data, argv=None, camera_object=None, view_layer=None):
    """The params dict for `_native.Session` (argv: for tests; default sys.argv). `camera_object` (the evaluated
    camera) resolves a depth-of-field focus object; `view_layer` gives the render passes to write."""
    settings = scene.candela
    render = scene.render
    width, height = frame_size(render)
    x0, y0, x1, y1 = crop_window(render)
    params = {
        "integrator": settings.integrator,
        "samples": settings.samples,
        "time_limit": float(settings.time_limit),
        "noise_threshold": float(settings.noise_threshold),
        "seed": settings.seed,
        "sampler": settings.sampler,
        "pixel_filter": settings.pixel_filter,
        "filter_width": float(settings.filter_width),
        # render.threads honours `-t N` and the Fixed/Auto-detect setting.
        "threads": int(render.threads),
        "width": width, "height": height,
        "crop_x0": x0, "crop_y0": y0, "crop_x1": x1, "crop_y1": y1,
        "pixel_aspect_x": float(render.pixel_aspect_x),
        "pixel_aspect_y": float(render.pixel_aspect_y),
        # Combined alpha 0 where the background is seen directly (premultiplied RGBA), like Cycles.
        "film_transparent": bool(render.film_transparent),
    }
    params.update(film_params(scene))
    params.update(integrator_params(settings))
    params.update(camera_params(camera_data))
    params.update(dof_params(camera_data, camera_object))
    if view_layer is not None:
        params["passes"] = native_pass_list(view_layer, scene)
    params.update(cmdline.overrides(argv))
    if settings.use_animated_seed:
        # Deterministic per frame on every farm worker (never wall-clock based).
        params["seed"] = params["seed"] + scene.frame_current
    return params
