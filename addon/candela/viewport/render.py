"""One Rendered 3D viewport: its native ViewportSession, the scene sync, the view camera and the display.

Every CandelaRenderEngine that Blender creates for a viewport owns one ViewportRender; nothing is shared between
viewports or with final renders and previews. Blender calls view_update (scene changes) and view_draw (every
redraw) on the main thread; the native worker renders meanwhile, and a timer (20 Hz, main thread) asks Blender to
redraw a viewport when its session has a newer image or status. close() stops the worker; the engine's
__del__, unregistering the add-on (Blender does it when quitting) and the timer finding the engine freed (closing
the viewport, switching the engine, loading a file) all call it, so no thread outlives its viewport.
"""

import atexit
import time
import traceback
import types
import weakref

import bpy

from .. import native, schema
from ..export import ExportError, Warnings, export_scene
from ..params import integrator_params, to_native_params
from ..render_loop import log_entries
from ..unsupported import ignored_settings
from .display import Display
from .scene_sync import ImageCache, MeshCache, classify, instance_signature
from .view_camera import view_camera

UNLIMITED_SAMPLES = 1 << 24
TICK_S = 0.05
REDRAW_FAST_S, REDRAW_SLOW_S, FAST_PERIOD_S = 0.0, 0.25, 2.0   # redraw throttle: fast just after a restart
FIRST_IMAGE_WAIT_S = 0.05   # the longest a redraw after a view change waits for the new view's first image

# Stand-in for the scene camera's data when the scene has none (the view supplies the camera anyway).
_NO_CAMERA = types.SimpleNamespace(
    type='PERSP', sensor_fit='AUTO', sensor_width=36.0, sensor_height=24.0, lens=50.0, ortho_scale=6.0, shift_x=0.0,
    shift_y=0.0, clip_start=0.1, clip_end=1000.0, name="(none)", dof=types.SimpleNamespace(use_dof=False))

_live = weakref.WeakSet()   # open viewports, so unregister() and the timer can reach them (not render state)


def viewport_settings(scene, view_layer):
    """(native params of the viewport's renders, header notes): the final render's settings with the viewport's
    sample limit, no time limit or noise stop, no data passes, and an integrator the native registry marks as
    rendering in the viewport (capabilities()["viewport_integrators"]): the scene's chosen integrator where it can,
    else PATH with a note (in the header, and reported once as a warning). An integrator that cannot see through
    the view's camera (LIGHT in an orthographic view, LIGHT and BDPT through a panorama) falls back natively, with
    the session status's note."""
    camera = scene.camera if scene.camera is not None and scene.camera.type == 'CAMERA' else None
    try:
        params = to_native_params(scene, camera.data if camera is not None else _NO_CAMERA, argv=[],
                                  camera_object=camera)
    except ExportError:   # a panoramic scene camera without Cycles' settings: the view overrides the camera
        params = to_native_params(scene, _NO_CAMERA, argv=[])
    notes = []
    settings = scene.candela
    params["samples"] = settings.viewport_samples or UNLIMITED_SAMPLES
    params["time_limit"] = 0.0
    params["noise_threshold"] = 0.0
    params.pop("passes", None)
    if params["integrator"] not in schema.viewport_integrators():
        labels = {name: label for name, _, label in schema.integrators()}
        label = labels.get(params["integrator"], params["integrator"].replace("_", " ").title())
        notes.append(f"{label} does not render progressively: the viewport shows Path Tracing")
        for key in integrator_params(settings):
            params.pop(key, None)
        params.update(integrator_params(settings, "PATH"))
        params["integrator"] = "PATH"
    else:
        # PATH's own settings too (keys the chosen integrator does not read, which only a Session reports), for the
        # native fallback to PATH through a camera the chosen one cannot see through.
        for key, value in integrator_params(settings, "PATH").items():
            params.setdefault(key, value)
    return params, notes


class ViewportRender:
    def __init__(self, engine):
        self.engine = engine
        self.session = native.require().ViewportSession(0)
        self.meshes = MeshCache()
        self.images = ImageCache()
        self.display = Display()
        self.settings = None
        self.settings_notes = []
        self.signature = None
        self.view_key = None
        self.view_notes = ()
        self.error = None          # the add-on's own (export) error; the session reports its own
        self.warnings = []
        self.header = ""
        self.redraw_after = 0.0
        self.restart_time = time.monotonic()
        self.closed = False
        self.exports = 0
        self.pixel_size = 1        # of the finest level (Blender's viewport pixel size)
        _live.add(self)
        _ensure_timer()

    # ---- Blender's callbacks (main thread) -------------------------------------------------------------------

    def update(self, context, depsgraph):
        """view_update: export what changed (or restart for new settings)."""
        if self.closed:
            return
        scene = depsgraph.scene
        changes = classify(depsgraph.updates)
        settings, notes = viewport_settings(scene, depsgraph.view_layer)
        self.settings_notes = notes
        for note in notes:   # a fallback to PATH: reported once (printed, and the latest warning in the header)
            self._warn(f"Candela: {note}")
        first = self.exports == 0
        signature = instance_signature(depsgraph) if (first or changes.scene or changes.export) else self.signature
        if first or changes.export or signature != self.signature or self.error is not None:
            self.meshes.invalidate(changes.geometry)
            self.images.invalidate(changes.images)
            self.signature = signature
            self._export(depsgraph, context, settings)
        elif settings != self.settings:
            self.session.update_settings(settings)
            self._restarted()
        self.settings = settings

    def draw(self, context, depsgraph):
        """view_draw: follow the view, upload a newer image, draw, update the header."""
        if self.closed:
            return
        region, space, rv3d = context.region, context.space_data, context.region_data
        scene = depsgraph.scene
        render = scene.render
        render_size = (max(1, render.resolution_x * render.resolution_percentage // 100) * render.pixel_aspect_x,
                       max(1, render.resolution_y * render.resolution_percentage // 100) * render.pixel_aspect_y)
        try:
            view = view_camera(scene, depsgraph, space, rv3d, region.width, region.height, render_size)
            view.params["pixel_size"] = self.pixel_size = int(self.engine.get_preview_pixel_size(scene))
            view.params["start_resolution"] = int(scene.candela.viewport_start_resolution)
            key = view.key()
            if key != self.view_key:
                request = self.session.set_view(view.params, view.matrix)
                self.view_key, self.view_notes = key, view.notes
                self._restarted()
                self._wait_for_first_image(request)
        except (ExportError, ValueError) as e:
            self.view_key = None
            self._set_header(f"Candela: {e}")
            return
        image = self.session.image(self.display.version)
        if image is not None:
            self.display.upload(image)
        self.display.draw(self.engine, scene, region.width, region.height)
        self._set_header(self._status_text())

    # ---- the timer (main thread) -----------------------------------------------------------------------------

    def tick(self, now):
        """Ask Blender to redraw when something new is to be shown; close if Blender freed the engine."""
        if self.closed:
            return
        try:
            self.engine.is_preview   # raises ReferenceError once Blender freed the engine (even if idle)
            for level, message in log_entries(self.session):
                if level != "INFO":   # what the renderer did stays out of the viewport's header
                    self._warn(f"Candela: {message}")
            note = self.session.status().get("note")
            if note:   # the native fallback to PATH for this view's camera: reported once, like the settings'
                self._warn(f"Candela: {note}")
            fresh = self.session.image_version() != self.display.version
            if (fresh and now >= self.redraw_after) or self._status_text() != self.header:
                self.engine.tag_redraw()
                fast = now - self.restart_time < FAST_PERIOD_S
                self.redraw_after = now + (REDRAW_FAST_S if fast else REDRAW_SLOW_S)
        except ReferenceError:   # the engine is gone: its viewport was closed or changed
            self.close()

    # ---- helpers ---------------------------------------------------------------------------------------------

    def _export(self, depsgraph, context, settings):
        warnings = Warnings()
        matrix = context.region_data.view_matrix.inverted() if context.region_data is not None else None
        try:
            camera = None if matrix is not None else depsgraph.scene.camera
            arrays = export_scene(depsgraph, camera, warnings=warnings, mesh_reader=self.meshes.read,
                                  camera_matrix=matrix, image_cache=self.images)
            self.images.end_export()
            for message in ignored_settings(depsgraph):
                warnings.add(message)
            self.meshes.end_export()
            self.session.update_scene(arrays, settings)
            self.error = None
        except (ExportError, ValueError) as e:
            self.error = str(e)
        self.exports += 1
        for message in warnings.messages:
            self._warn(message)
        self._restarted()

    def _wait_for_first_image(self, request):
        """After a view change, wait a moment for the new view's coarsest image, so this redraw shows it instead
        of the old view (which would need another redraw: a few hundred milliseconds with software OpenGL). The
        coarsest level has about start_resolution² pixels and one sample: milliseconds; the wait is capped."""
        end = time.monotonic() + FIRST_IMAGE_WAIT_S
        while self.session.image_request() < request and time.monotonic() < end:
            time.sleep(0.001)

    def _warn(self, message):
        if message not in self.warnings:
            self.warnings.append(message)
            print(message)

    def _restarted(self):
        self.restart_time = time.monotonic()
        self.redraw_after = 0.0

    def _status_text(self):
        status = self.session.status()
        notes = list(self.settings_notes) + list(self.view_notes)
        if status.get("note"):
            notes.append(status["note"])
        error = self.error or status.get("error")
        if error:
            return f"Candela: {error}"
        phase = status["phase"]
        if phase == "building":
            text = "Building scene"
        elif phase == "pending":
            text = "Updating"
        elif phase in ("rendering", "done"):
            total = status["samples_total"]
            done = status["samples_done"] if status["pixel_size"] <= 1 or phase == "done" else 0
            if status["pixel_size"] > 1 and phase != "done" and total <= 1:
                text = "Rendering coarse preview"
            else:
                text = f"Sample {done}/{'∞' if total >= UNLIMITED_SAMPLES else total}"
            if phase == "done":
                text += " | Done"
        else:
            text = "Waiting"
        if self.warnings:
            text += f" | {self.warnings[-1]}"
            notes = [n for n in notes if f"Candela: {n}" != self.warnings[-1]]   # not twice
        return " | ".join([text] + notes)

    def _set_header(self, text):
        if text != self.header:
            self.header = text
            try:
                self.engine.update_stats("", text)
            except ReferenceError:
                self.close()

    def memory_mb(self):
        status = self.session.status()
        return (status["scene_bytes"] + status["film_bytes"]) / 1e6

    def close(self):
        if self.closed:
            return
        self.closed = True
        try:
            self.session.stop()
        finally:
            self.display.free()
            self.meshes.clear()
            self.images.clear()
            _live.discard(self)
            self.engine = None


def _tick():
    now = time.monotonic()
    for vp in list(_live):
        try:
            vp.tick(now)
        except Exception:
            traceback.print_exc()
            vp.close()
    return TICK_S if len(_live) else None


def _ensure_timer():
    if not bpy.app.timers.is_registered(_tick):
        bpy.app.timers.register(_tick, first_interval=TICK_S, persistent=True)


def _stop_threads_at_exit():
    """Last resort when Python shuts down: stop the native workers only (no GPU call: the context may be gone).
    Normally Blender has unregistered the add-on (close_all) before."""
    for vp in list(_live):
        try:
            vp.session.stop()
        except Exception:
            pass


atexit.register(_stop_threads_at_exit)


def close_all():
    """Stop every open viewport (unregister, quitting Blender)."""
    for vp in list(_live):
        vp.close()
    if bpy.app.timers.is_registered(_tick):
        bpy.app.timers.unregister(_tick)


def live_count():
    """Open viewports (tests)."""
    return len(_live)
