"""The Candela RenderEngine: thin; the work happens in render_loop.py."""

import traceback

import bpy

from . import passes, render_loop
from .export import ExportError


class CandelaRenderEngine(bpy.types.RenderEngine):
    bl_idname = "CANDELA"
    bl_label = "Candela"
    bl_use_preview = False              # material previews: later (they need cheap, isolated sessions)
    bl_use_postprocess = True           # compositing and sequencer on the result
    bl_use_shading_nodes_custom = False  # keep Blender's Cycles shader editor (the default True hides it)

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

    def update_render_passes(self, scene=None, renderlayer=None):
        self.register_pass(scene, renderlayer, "Combined", 4, "RGBA", 'COLOR')
        for p in passes.enabled_passes(renderlayer) + passes.strategy_passes(scene):
            self.register_pass(scene, renderlayer, p.name, p.channels, p.chan_id, p.pass_type)


def register():
    bpy.utils.register_class(CandelaRenderEngine)


def unregister():
    bpy.utils.unregister_class(CandelaRenderEngine)
