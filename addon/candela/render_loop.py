"""One final render: export → native Session → poll loop feeding Blender's RenderResult.

`drive()` only needs an object with the RenderEngine methods it calls (begin_result, update_result, end_result,
test_break, update_progress, update_stats, report), so tests drive it with a fake engine.
"""

import time

from . import native
from .export import ExportError, Warnings, export_scene, name_objects, render_camera
from .export.camera import camera_to_world
from .export.motion import motion_arrays
from .params import animation_params, result_size, to_native_params
from .unsupported import ignored_settings

POLL_S = 0.05                # wait() timeout: test_break() polled at 20 Hz + native cancel (< 10 ms) keeps Esc under 100 ms
STATUS_INTERVAL_S = 1.0      # update_stats prints one line per call in -b: at most 1 Hz
DISPLAY_FIRST_S = 0.5        # first progressive refresh; then the interval doubles ...
DISPLAY_CAP_S = 4.0          # ... up to this in the UI
DISPLAY_CAP_BACKGROUND_S = 30.0   # nobody watches in -b: copying the image is wasted work

# Native statistics of the most recent final render in this process (session.stats() plus samples_done, phase,
# stop reason, noise estimate and the warnings reported), for scripts that drive bpy.ops.render.render() and want
# the engine's own numbers (make bench, make demo, tests). A published record, not render state: a final render
# replaces it as a whole when it ends (previews and the viewport never touch it), so a preview running beside a
# final render cannot change what the render reports.
last_render_stats = {}

PREVIEW_PARAMS = {"samples": 32, "max_bounces": 8, "integrator": "PATH", "time_limit": 0.0, "noise_threshold": 0.0}


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
    current stage with its own progress ("Photon | Tracing photons 3.2 M / 10 M | Elapsed 00:04", or in percent:
    "Irradiance Cache | Irradiance cache 41 % | 1234 records | Elapsed 00:04"); the integrator's note (its record
    count) stays in the line while it renders. When the native side names the method itself (AUTO's choice and
    reason, "Auto: BDPT — caustic paths ..."), that replaces the name."""
    name = integrator.replace("_", " ").title() if integrator not in ("BDPT", "SPPM") else integrator
    name = progress.get("method") or name
    elapsed = float(progress.get("elapsed_s", 0.0))
    phase = progress.get("phase", "rendering")
    if phase == "building":
        return f"{name} | Building scene | Elapsed {format_duration(elapsed)}"
    stage = progress.get("stage") or ""
    note = progress.get("note") or ""      # the integrator's status beside its progress ("1234 records")
    note_part = f" | {note}" if note else ""
    if stage and phase == "rendering":
        stage_total = int(progress.get("stage_total", 0))
        stage_done = int(progress.get("stage_done", 0))
        if stage_total and progress.get("stage_percent"):
            what = f"{stage} {int(100 * stage_done / stage_total)} %"
        elif stage_total:
            what = f"{stage} {format_count(stage_done)} / {format_count(stage_total)}"
        else:
            what = stage
        return f"{name} | {what}{note_part} | Elapsed {format_duration(elapsed)}"
    done, total = int(progress.get("samples_done", 0)), int(progress.get("samples_total", 0))
    unit = (progress.get("unit") or "sample").capitalize()
    fraction = float(progress.get("fraction", 0.0))
    line = f"{name} | {unit} {done}/{total}{note_part} | Elapsed {format_duration(elapsed)}"
    error = progress.get("relative_error")
    if error is not None:
        line += f" | Noise {100.0 * error:.1f} %"
    elif progress.get("noise_unavailable"):  # SPPM: its two half-images share photons, so no honest estimate
        line += " | Noise n/a"
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


class RenderRecord:
    """What one render (a final render of one view layer, or a preview) reports: its own, never shared."""

    def __init__(self, publish=True):
        self.warnings = []
        self.info = []      # Info-level log lines (log_entries)
        self.publish = publish   # final renders publish last_render_stats; previews do not


def _warn(engine, message, record):
    if message in record.warnings:
        return
    record.warnings.append(message)
    engine.report({'WARNING'}, message)


def log_entries(session):
    """[(level, message), ...] of what the native side logged since the last call: level "INFO" for what the
    renderer did (what the scene lets it skip, AUTO's analysis and choice, cache sizes), "WARNING" for what may make
    the image differ from what the user expects (core/message_log.h). Stand-ins without levels log warnings."""
    take = getattr(session, "take_log_entries", None)
    if take is None:
        return [("WARNING", message) for message in session.take_log()]
    return [(str(level), str(message)) for level, message in take()]


def _forward_log(engine, session, record):
    for level, message in log_entries(session):
        if level == "INFO":
            record.info.append(message)
            engine.report({'INFO'}, f"Candela: {message}")
        else:
            _warn(engine, f"Candela: {message}", record)


def with_latest_warning(line, record):
    """The status line with the latest warning after it, in every status update: the image editor's header and
    the terminal show it while the render runs, where the Info editor is usually not open. (When the render ends,
    Blender replaces the line with its own frame/time/memory summary: keep_latest_warning.)"""
    if not record.warnings:
        return line
    latest = record.warnings[-1]
    more = len(record.warnings) - 1
    return f"{line} | {latest}" + (f" (+{more} more in the Info editor)" if more else "")


def _memory_stats(engine, session):
    """Candela's own memory in the header (Blender otherwise shows another engine's figure from earlier)."""
    try:
        stats = session.stats()
        film = session.width * session.height * float(native.capabilities().get("film_bytes_per_pixel", 0.0))
        mb = (float(stats.get("scene_bytes", 0)) + film) / (1024.0 * 1024.0)
        engine.update_memory_stats(memory_used=mb, memory_peak=mb)
    except (AttributeError, TypeError):   # stand-in engines in tests
        pass


def drive(engine, session, layer="", integrator="PATH", background=False, clock=time.monotonic, out=print,
          names=None, record=None, view=""):
    """Poll a started session until it finishes or `engine.test_break()`; always ends the result.

    Returns the final `session.progress()`; raises RuntimeError if the native render failed (after the partial
    image was handed to Blender), naming objects by `names` (export_scene's) where the message names a mesh.
    `record` collects this render's warnings; `view` is the multiview view the result is for ("" = mono).
    """
    record = record if record is not None else RenderRecord()
    width, height = session.width, session.height
    result = engine.begin_result(0, 0, width, height, layer=layer, view=view)
    joined = False
    try:
        passes = _result_passes(result)
        start = clock()
        display = Backoff(DISPLAY_FIRST_S, 2.0, DISPLAY_CAP_BACKGROUND_S if background else DISPLAY_CAP_S, start)
        status = Backoff(STATUS_INTERVAL_S, 1.0, STATUS_INTERVAL_S, start)
        shown = False
        while not session.wait(POLL_S):
            if engine.test_break():
                session.cancel()
                break
            now = clock()
            progress = session.progress()
            engine.update_progress(float(progress.get("fraction", 0.0)))
            if status.due(now):
                engine.update_stats("", with_latest_warning(status_line(integrator, progress), record))
                _forward_log(engine, session, record)
                _memory_stats(engine, session)
            # The first pass is shown as soon as it is done (first pixels after F12), then at growing intervals.
            first = not background and not shown and int(progress.get("samples_done", 0)) >= 1
            if (first or display.due(now)) and _copy_pass(session, passes, "Combined", width, height):
                engine.update_result(result)
                shown = True
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
    _forward_log(engine, session, record)
    _memory_stats(engine, session)
    if record.publish:
        global last_render_stats
        last_render_stats = dict(session.stats(), samples_done=progress.get("samples_done"),
                                 phase=progress.get("phase"), stop_reason=progress.get("stop_reason"),
                                 relative_error=progress.get("relative_error"), warnings=list(record.warnings),
                                 info=list(record.info), method=progress.get("method"))
    if session.error:
        raise RuntimeError(name_objects(session.error, names))
    engine.update_progress(1.0)
    engine.update_stats("", with_latest_warning(status_line(integrator, progress), record))
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
    elif progress.get("noise_unavailable"):
        what += ", noise estimate n/a"
    line = f"Candela: rendered {width}x{height}, {what} in {seconds:.2f} s ({rate:.1f} samples/s)"
    stages = stats.get("stages") or []
    if stages:  # the pre-passes inside that time (photon shooting, the irradiance cache, MLT's bootstrap ...)
        line += "; of which " + ", ".join(
            f"{st['name'].lower()} {float(st['seconds']):.2f} s" + (f" ({st['runs']}×)" if st["runs"] > 1 else "")
            for st in stages)
    return line


def result_views(engine, width, height, layer):
    """The view names Blender expects results for: ["left", "right"] for stereo 3D, [""] for mono."""
    if not hasattr(engine, "active_view_set"):   # stand-in engines in tests
        return [""]
    probe = engine.begin_result(0, 0, width, height, layer=layer)
    try:
        names = [v.name for v in getattr(probe, "views", ())]
    finally:
        engine.end_result(probe, cancel=True, do_merge_results=False)
    return names if len(names) > 1 else [""]


def view_camera(engine, camera_eval, view):
    """(camera → world matrix, shift_x) of the camera for one multiview view, as Blender computes each eye (its
    interocular offset, convergence and shift); the object's own for mono."""
    if not view or not hasattr(engine, "camera_model_matrix"):
        return camera_eval.matrix_world, None
    engine.active_view_set(view)
    spherical = engine.use_spherical_stereo(camera_eval)
    return engine.camera_model_matrix(camera_eval, use_spherical_stereo=spherical), \
        float(engine.camera_shift_x(camera_eval, use_spherical_stereo=spherical))


def render_frame(engine, depsgraph, background=False):
    """The whole final render (or material/world/light preview) of one view layer (engine.render forwards here):
    every multiview view of it, each through its own camera."""
    nat = native.require()
    scene = depsgraph.scene
    preview = bool(getattr(engine, "is_preview", False))
    record = RenderRecord(publish=not preview)
    layer = depsgraph.view_layer.name
    camera = render_camera(scene, engine.camera_override)
    width, height = result_size(scene.render)
    warnings = Warnings()
    names = {}
    motion = {} if scene.render.use_motion_blur and not preview else None
    arrays = export_scene(depsgraph, camera, test_break=engine.test_break,
                          status=lambda text: engine.update_stats("", text), warnings=warnings, names=names,
                          motion=motion)
    if arrays is not None and motion is not None and hasattr(engine, "frame_set"):
        engine.update_stats("", "Exporting motion")
        arrays.update(motion_arrays(engine, depsgraph, camera.original if camera is not None else None,
                                    motion["keys"], motion["steps"], arrays["instance_transform"]))
    if not preview:   # a preview's tiny scene is Blender's: its settings are not the user's to fix
        for message in ignored_settings(depsgraph, camera):
            warnings.add(message)
    for message in warnings.messages:
        _warn(engine, message, record)
    if arrays is None:
        # Cancelled while exporting: still hand Blender a (blank) result, never none at all.
        engine.end_result(engine.begin_result(0, 0, width, height, layer=layer))
        return None
    camera_eval = camera.original.evaluated_get(depsgraph)
    params = to_native_params(scene, camera_eval.data, camera_object=camera_eval, view_layer=depsgraph.view_layer)
    params.update(animation_params(scene.candela, bool(getattr(engine, "is_animation", False)) and not preview))
    if preview:
        params.update(PREVIEW_PARAMS)
        params.pop("passes", None)
    views = result_views(engine, width, height, layer)
    progress = None
    for i, view in enumerate(views):
        matrix, shift_x = view_camera(engine, camera_eval, view)
        view_arrays = arrays if not view else dict(arrays, camera_to_world=camera_to_world(matrix))
        view_params = params if shift_x is None else dict(params, shift_x=shift_x)
        engine.update_stats("", "Building scene")
        try:
            # Validates everything and refuses a scene or film that cannot fit in memory, before building anything.
            session = nat.Session(view_arrays, view_params)
        except ValueError as e:
            raise ExportError(name_objects(str(e), names)) from None
        del view_arrays
        if i == len(views) - 1:
            del arrays   # the session holds its own copy: do not keep two while the BVH is built
        if (session.width, session.height) != (width, height):
            raise RuntimeError(f"native film is {session.width}x{session.height}, Blender expects {width}x{height}")
        session.start()
        progress = drive(engine, session, layer=layer, integrator=view_params["integrator"], background=background,
                         names=names, record=record, view=view)
        if engine.test_break():
            break
    if record.warnings and not background and not preview:
        keep_latest_warning(engine, record)
    return progress


def keep_latest_warning(engine, record):
    """After the render Blender replaces the status line with its own summary (frame, time, memory), which ends
    with the render result's message when it has one (what engine.error_set sets, where Cycles' messages show):
    the latest warning goes there, so it stays in the render window's header after the render."""
    more = len(record.warnings) - 1
    engine.error_set(record.warnings[-1] + (f" (+{more} more in the Info editor)" if more else ""))
