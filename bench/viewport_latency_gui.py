"""Blender side of `make viewport-latency` (bench/viewport_latency.py starts it under Xvfb on one scene and engine).

What the user sees is read from the Xvfb framebuffer file (a few milliseconds per look, the same for every
engine, no engine instrumentation), polled on every pass of Blender's event loop:

- view change → first image: the 3D view (Rendered shading, a free perspective view framed like the scene's
  camera) is left to render, then orbited by 4°; the time until the view first shows an image of the new view
  (first_new: a coarse or noisy first image counts, the old image does not). Trials alternate the orbit's
  direction.
- F12 → first pixels: the render in a full-screen image editor; the time from invoking the render until the
  screen first shows pixels of it (first_new from the blank result to the finished render).
- the same view change in Solid shading ("redraw_floor"): the time Blender itself needs to show a new frame of
  the scene here, with no render engine involved.

Writes {"view_change": [s, ...], "f12": [...], "redraw_floor": [...], "engine_first_image": [...]} to
$CANDELA_GUI_DIR/latency.json (engine_first_image: Candela's worker, from taking the view change to its first
image, without Blender's redraw).
"""

import json
import math
import os
import sys
import time

import bpy
import numpy as np
from mathutils import Quaternion, Vector

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPO, "tests", "blender"))
import gui_steps as G  # noqa: E402

ENGINE = os.environ["CANDELA_LATENCY_ENGINE"]
VIEW_TRIALS = int(os.environ.get("CANDELA_LATENCY_VIEW_TRIALS", "5"))
F12_TRIALS = int(os.environ.get("CANDELA_LATENCY_F12_TRIALS", "3"))
SETTLE_S = float(os.environ.get("CANDELA_LATENCY_SETTLE_S", "3.0"))


def grab(region=None):
    """The screen (or a region of it), grey, every second pixel: enough to tell images apart."""
    screen = G.framebuffer()
    if region is not None:
        window = bpy.context.window_manager.windows[0]
        screen = G.region_pixels(screen, region, window.height)
    else:
        screen = screen.astype(np.float32) / 255.0
    return screen[::2, ::2].mean(axis=2)


def distance(a, b):
    return float(np.abs(a - b).mean())


def record(frames, region, until):
    """Append (time, frame) on every event-loop pass until `until(t)` says stop."""
    while True:
        t = time.perf_counter()
        frames.append((t, grab(region)))
        if until(t):
            return
        yield 0.0


def first_new(frames, t0, before, after):
    """Seconds from t0 to the first frame that left `before` (by at least half of `after`'s distance from it)
    and is closer to `after` than to `before`: a first, coarse or noisy, image of the new state counts, the old
    image does not."""
    moved = distance(after, before)
    for t, frame in frames:
        if t >= t0 and distance(frame, before) > 0.5 * moved and distance(frame, after) < distance(frame, before):
            return t - t0
    return None


def view_trials(region, rv3d, results, key="view_change"):
    for i in range(VIEW_TRIALS):
        old = grab(region)
        frames = []
        axis = Quaternion((0.0, 0.0, 1.0), math.radians(4.0 if i % 2 == 0 else -4.0))
        rv3d.view_rotation = axis @ rv3d.view_rotation
        t0 = time.perf_counter()
        yield from record(frames, region, lambda t: t - t0 > SETTLE_S)
        settled = frames[-1][1]
        latency = first_new(frames, t0, old, settled)
        results[key].append(latency)
        if key == "view_change" and G.viewports():   # Candela's own part: the worker's first image
            results["engine_first_image"].append(G.viewports()[0].session.status()["seconds_to_first_image"])
        G.note(f"{ENGINE} {key} {i + 1}: {latency if latency is None else round(1000 * latency)} ms")


def f12_trials(window, results):
    bpy.context.preferences.view.render_display_type = 'SCREEN'
    for i in range(F12_TRIALS):
        frames = []
        with bpy.context.temp_override(window=window):
            t0 = time.perf_counter()
            bpy.ops.render.render('INVOKE_DEFAULT')
        started = time.perf_counter()
        yield from record(frames, None, lambda t: t - started > 1.0 and not bpy.app.is_job_running('RENDER'))
        yield 0.5
        final = grab()
        blank = max((f for _, f in frames), key=lambda f: distance(f, final))   # before any pixel arrived
        latency = first_new(frames, t0, blank, final)
        results["f12"].append(latency)
        G.note(f"{ENGINE} F12 {i + 1}: {latency if latency is None else round(1000 * latency)} ms")
        with bpy.context.temp_override(window=bpy.context.window_manager.windows[0]):
            bpy.ops.screen.back_to_previous()
        yield 1.0


def steps():
    window, area, region, space = G.view3d()
    scene = bpy.context.scene
    scene.render.engine = ENGINE
    rv3d = space.region_3d
    space.overlay.show_overlays = False
    # A free perspective view framed like the scene's camera (the view's lens matches the camera's field of view
    # on Blender's 36 mm viewport sensor at zoom 2).
    cam = scene.camera
    rv3d.view_perspective = 'PERSP'
    rv3d.view_rotation = cam.matrix_world.to_quaternion()
    forward = cam.matrix_world.to_3x3() @ Vector((0.0, 0.0, -1.0))
    rv3d.view_distance = 8.0
    rv3d.view_location = cam.matrix_world.translation + 8.0 * forward.normalized()
    space.lens = cam.data.lens * 36.0 / cam.data.sensor_width * 2.0
    results = {"engine": ENGINE, "view_change": [], "f12": [], "redraw_floor": [], "engine_first_image": [],
               "load_average": os.getloadavg()[0]}
    space.shading.type = 'SOLID'
    yield 3.0
    yield from view_trials(region, rv3d, results, key="redraw_floor")
    space.shading.type = 'RENDERED'
    yield SETTLE_S + 5.0   # scene sync and BVH build, then the first images
    yield from view_trials(region, rv3d, results)
    space.shading.type = 'SOLID'   # the viewport must not compete with the final render
    yield 1.0
    yield from f12_trials(window, results)
    with open(os.path.join(G.WORK, "latency.json"), "w") as f:
        json.dump(results, f)
    G.check("measured", all(v is not None for v in results["view_change"] + results["f12"] + results["redraw_floor"]),
            results)


G.run(steps)
