"""One final render: export → native Session → poll loop feeding Blender's RenderResult.

`drive()` only needs an object with the RenderEngine methods it calls (begin_result, update_result, end_result,
test_break, update_progress, update_stats, report), so tests drive it with a fake engine.
"""

import time

from . import native
from .export import ExportError, Warnings, export_scene, name_objects, render_camera
from .params import result_size, to_native_params

POLL_S = 0.05                # wait() timeout: test_break() polled at 20 Hz + native cancel (< 10 ms) keeps Esc under 100 ms
STATUS_INTERVAL_S = 1.0      # update_stats prints one line per call in -b: at most 1 Hz
DISPLAY_FIRST_S = 0.5        # first progressive refresh; then the interval doubles ...
DISPLAY_CAP_S = 4.0          # ... up to this in the UI
DISPLAY_CAP_BACKGROUND_S = 30.0   # nobody watches in -b: copying the image is wasted work

# Native statistics of the most recent render in this process (session.stats() plus samples_done, phase, stop
# reason, noise estimate and the warnings reported), for scripts that drive bpy.ops.render.render() and want the
# engine's own numbers (make bench, make demo, tests).
last_render_stats = {}
_warnings = []   # warnings reported during the current render


class Backoff:
    """`due(now)` is True at most once per interval; the interval grows by `factor` up to `cap`."""

    def __init__(self, first, factor, cap, now):
        self.interval, self.factor, self.cap = first, factor, cap
        self.next = now + first

    def due(self, now):
        if now < self.next:
            return False
        self.interval = min(self.interval * self.factor, self.cap)
        self.next = now + self.interval
        return True


def format_duration(seconds):
    seconds = max(0, int(round(seconds)))
    h, rem = divmod(seconds, 3600)
    m, s = divmod(rem, 60)
    return f"{h}:{m:02d}:{s:02d}" if h else f"{m:02d}:{s:02d}"


def format_count(n):
    """3200000 → "3.2 M", 41000 → "41 k", 512 → "512"."""
    n = float(n)
    for scale, suffix in ((1e9, " G"), (1e6, " M"), (1e3, " k")):
        if abs(n) >= scale:
            return f"{n / scale:.3g}{suffix}"
    return f"{int(n)}"


def status_line(integrator, progress):
    """"Path | Sample 37/256 | Elapsed 00:12 | Remaining 00:41", the phase while building, or the integrator's
    current stage with its own progress ("Photon | Tracing photons 3.2 M / 10 M | Elapsed 00:04"). When the native
    side names the method itself (AUTO's choice and reason, "Auto: BDPT — caustic paths ..."), that replaces the name."""
    name = integrator.replace("_", " ").title() if integrator != "BDPT" else "BDPT"
    name = progress.get("method") or name
    elapsed = float(progress.get("elapsed_s", 0.0))
    phase = progress.get("phase", "rendering")
    if phase == "building":
        return f"{name} | Building scene | Elapsed {format_duration(elapsed)}"
    stage = progress.get("stage") or ""
    if stage and phase == "rendering":
        stage_total = int(progress.get("stage_total", 0))
        what = (f"{stage} {format_count(progress.get('stage_done', 0))} / {format_count(stage_total)}" if stage_total
                else stage)
        return f"{name} | {what} | Elapsed {format_duration(elapsed)}"
    done, total = int(progress.get("samples_done", 0)), int(progress.get("samples_total", 0))
    unit = (progress.get("unit") or "sample").capitalize()
    fraction = float(progress.get("fraction", 0.0))
    line = f"{name} | {unit} {done}/{total} | Elapsed {format_duration(elapsed)}"
    error = progress.get("relative_error")
    if error is not None:
        line += f" | Noise {100.0 * error:.1f} %"
    stop = progress.get("stop_reason") or ""
    if stop and stop != "samples":
        line += f" | Stopped: {stop}"
    elif fraction > 0.0:
        line += f" | Remaining {format_duration(elapsed * (1.0 - fraction) / fraction)}"
    return line


def _result_passes(result):
    """The result's passes by name (Combined, plus those the view layer asks for: passes.py)."""
    return {render_pass.name: render_pass for render_pass in result.layers[0].passes}


def _copy_pass(session, passes, name, width, height):
    """Copy native pass `name` into the result; False while it does not exist (yet)."""
    render_pass = passes.get(name)
    if render_pass is None:
        return False
    buf = session.get_pass(name)
    if buf is None:
        return False
    if buf.shape != (width * height, render_pass.channels):
        raise RuntimeError(f"native {name} pass has shape {buf.shape}, expected ({width * height}, "
                           f"{render_pass.channels})")
    render_pass.rect.foreach_set(buf)   # must be a 2-D (N, channels) array in Blender 3.4 (a flat one crashes)
    return True


def _warn(engine, message):
    _warnings.append(message)
    engine.report({'WARNING'}, message)


def _forward_log(engine, session):
    for entry in session.take_log():
        message = entry[-1] if isinstance(entry, (tuple, list)) else entry
        _warn(engine, f"Candela: {message}")


def drive(engine, session, layer="", integrator="PATH", background=False, clock=time.monotonic, out=print,
          names=None):
    """Poll a started session until it finishes or `engine.test_break()`; always ends the result.

    Returns the final `session.progress()`; raises RuntimeError if the native render failed (after the partial
    image was handed to Blender), naming objects by `names` (export_scene's) where the message names a mesh.
    """
    width, height = session.width, session.height
    result = engine.begin_result(0, 0, width, height, layer=layer)
    joined = False
    try:
        passes = _result_passes(result)
        start = clock()
        display = Backoff(DISPLAY_FIRST_S, 2.0, DISPLAY_CAP_BACKGROUND_S if background else DISPLAY_CAP_S, start)
        status = Backoff(STATUS_INTERVAL_S, 1.0, STATUS_INTERVAL_S, start)
        while not session.wait(POLL_S):
            if engine.test_break():
                session.cancel()
                break
            now = clock()
            progress = session.progress()
            engine.update_progress(float(progress.get("fraction", 0.0)))
            if status.due(now):
                engine.update_stats("", status_line(integrator, progress))
                _forward_log(engine, session)
            if display.due(now) and _copy_pass(session, passes, "Combined", width, height):
                engine.update_result(result)
        session.join()
        joined = True
        # Final (or, after a cancel, partial) image and the other passes: end_result hands them to Blender.
        for name in passes:
            _copy_pass(session, passes, name, width, height)
    finally:
        if not joined:          # an exception in the loop: stop the workers before the result goes away
            session.cancel()
            session.join()
        engine.end_result(result)

    progress = session.progress()
    last_render_stats.clear()
    _forward_log(engine, session)
    last_render_stats.update(session.stats(), samples_done=progress.get("samples_done"), phase=progress.get("phase"),
                             stop_reason=progress.get("stop_reason"), relative_error=progress.get("relative_error"),
                             warnings=list(_warnings))
    if session.error:
        raise RuntimeError(name_objects(session.error, names))
    engine.update_progress(1.0)
    engine.update_stats("", status_line(integrator, progress))
    out(summary_line(session, progress, width, height))
    return progress


def summary_line(session, progress, width, height):
    stats = session.stats()
    seconds = float(stats.get("render_seconds", progress.get("elapsed_s", 0.0)))
    done, total = int(progress.get("samples_done", 0)), int(progress.get("samples_total", 0))
    rate = float(stats.get("samples_per_second", 0.0))
    stop = progress.get("stop_reason") or ""
    what = f"{done} samples" if stop in ("", "samples") else f"{done} of {total} samples (stopped: {stop})"
    error = progress.get("relative_error")
    if error is not None:
        what += f", estimated noise {100.0 * error:.2f} %"
    return f"Candela: rendered {width}x{height}, {what} in {seconds:.2f} s ({rate:.1f} samples/s)"


def render_frame(engine, depsgraph, background=False):
    """The whole final render of one view layer (engine.render forwards here)."""
    nat = native.require()
    scene = depsgraph.scene
    layer = depsgraph.view_layer.name
    camera = render_camera(scene, engine.camera_override)
    width, height = result_size(scene.render)
    warnings = Warnings()
    names = {}
    arrays = export_scene(depsgraph, camera, test_break=engine.test_break,
                          status=lambda text: engine.update_stats("", text), warnings=warnings, names=names)
    _warnings.clear()
    for message in warnings.messages:
        _warn(engine, message)
    if arrays is None:
        # Cancelled while exporting: still hand Blender a (blank) result, never none at all.
        engine.end_result(engine.begin_result(0, 0, width, height, layer=layer))
        return None
    camera_eval = camera.original.evaluated_get(depsgraph)
    params = to_native_params(scene, camera_eval.data, camera_object=camera_eval, view_layer=depsgraph.view_layer)
    engine.update_stats("", "Building scene")
    try:
        # Validates everything and refuses a scene or film that cannot fit in memory, before building anything.
        session = nat.Session(arrays, params)
    except ValueError as e:
        raise ExportError(name_objects(str(e), names)) from None
    del arrays   # the session holds its own copy: do not keep two while the BVH is built
    if (session.width, session.height) != (width, height):
        raise RuntimeError(f"native film is {session.width}x{session.height}, Blender expects {width}x{height}")
    session.start()
    return drive(engine, session, layer=layer, integrator=params["integrator"], background=background, names=names)
