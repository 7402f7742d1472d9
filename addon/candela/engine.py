"""The Candela RenderEngine: thin; the work happens in render_loop.py."""

import traceback

import bpy

from . import passes, render_loop, viewport
from .export import ExportError


class CandelaRenderEngine(bpy.types.RenderEngine):
    bl_idname = "CANDELA"
    bl_label = "Candela"
    bl_use_preview = True               # material, world and light thumbnails: small isolated renders
    bl_use_eevee_viewport = True        # Material Preview shading draws with EEVEE (the same Cycles nodes)
    bl_use_postprocess = True           # compositing and sequencer on the result
    bl_use_shading_nodes_custom = False  # keep Blender's Cycles shader editor (the default True hides it)

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self._viewport = None   # this engine's Rendered viewport (viewport/render.py), if it is one

    def __del__(self):
        # Can run twice and after the struct was freed (Blender 3.4: then even reading an attribute raises
        # ReferenceError). The viewport's timer closes it in that case anyway (viewport/render.py).
        try:
            viewport = self._viewport
            self._viewport = None
        except (AttributeError, ReferenceError):
            return
        if viewport is not None:
            try:
                viewport.close()
            except Exception:
                traceback.print_exc()

    def render(self, depsgraph):
        # Never let an exception escape: Blender 3.4 then saves an empty image (exit 0) or segfaults. An ERROR
        # report makes `blender -b … -f N` skip saving and exit 1, the right way to fail a farm task.
        try:
            render_loop.render_frame(self, depsgraph, background=bpy.app.background)
        except Exception as e:
            if not isinstance(e, ExportError):   # scene problems are the user's to fix: the message says it all
                traceback.print_exc()
            message = f"Candela: {e}"
            self.report({'ERROR'}, message)
            self.error_set(message)

    # ---- Rendered viewport shading: errors go to the viewport's header (update_stats), never out of here ----

    def view_update(self, context, depsgraph):
        try:
            if self._viewport is None or self._viewport.closed:
                self._viewport = viewport.ViewportRender(self)
            self._viewport.update(context, depsgraph)
        except Exception as e:
            self._viewport_failed(e)

    def view_draw(self, context, depsgraph):
        try:
            if self._viewport is None or self._viewport.closed:   # no update yet, or closed after an error
                self._viewport = viewport.ViewportRender(self)
                self._viewport.update(context, depsgraph)
            self._viewport.draw(context, depsgraph)
            self.update_memory_stats(memory_used=self._viewport.memory_mb(), memory_peak=self._viewport.memory_mb())
        except Exception as e:
            self._viewport_failed(e)

    def _viewport_failed(self, e):
        if not isinstance(e, (ExportError, ValueError, ReferenceError)):
            traceback.print_exc()   # a bug: the console gets the traceback, the header the message
        try:
            self.update_stats("", f"Candela: {e}")
        except ReferenceError:
            pass

    def update_render_passes(self, scene=None, renderlayer=None):
        self.register_pass(scene, renderlayer, "Combined", 4, "RGBA", 'COLOR')
        for p in passes.enabled_passes(renderlayer) + passes.strategy_passes(scene):
            self.register_pass(scene, renderlayer, p.name, p.channels, p.chan_id, p.pass_type)


def register():
    bpy.utils.register_class(CandelaRenderEngine)


def unregister():
    viewport.close_all()   # no viewport thread outlives the add-on (Blender unregisters add-ons when quitting)
    bpy.utils.unregister_class(CandelaRenderEngine)
