"""Scene dumps: `params.json` + one `NAME.npy` per array, rendered by `candela DUMP_DIR -o out.exr` without Blender.

Headless use (benchmarks, farms):
    blender -b scene.blend --addons candela --python-expr \
        "import bpy; bpy.ops.candela.export_dump(directory='/tmp/dump')"
"""

import json
import os

import bpy
import numpy as np
from bpy.props import StringProperty

from .export import ExportError, Warnings, export_scene, render_camera
from .params import to_native_params


def write_dump(directory, arrays, params):
    """Write a dump directory (created if needed); arrays are stored C-contiguous and little-endian."""
    os.makedirs(directory, exist_ok=True)
    with open(os.path.join(directory, "params.json"), "w", encoding="utf-8") as f:
        json.dump(params, f, indent=2, sort_keys=True)
        f.write("\n")
    for name, array in arrays.items():
        a = np.ascontiguousarray(array)
        if a.dtype.byteorder == ">":
            a = a.astype(a.dtype.newbyteorder("<"))
        np.save(os.path.join(directory, f"{name}.npy"), a, allow_pickle=False)


def export_dump(context, directory):
    """Export the current scene (evaluated viewport depsgraph) to `directory`; returns the warnings."""
    depsgraph = context.evaluated_depsgraph_get()
    scene = context.scene
    camera = render_camera(scene)
    warnings = Warnings()
    arrays = export_scene(depsgraph, camera, warnings=warnings)
    camera_eval = camera.evaluated_get(depsgraph)
    params = to_native_params(scene, camera_eval.data, camera_object=camera_eval, view_layer=context.view_layer)
    write_dump(bpy.path.abspath(directory), arrays, params)
    return warnings.messages


class CANDELA_OT_export_dump(bpy.types.Operator):
    """Write the scene as Candela arrays + params (a dump the command-line renderer can render)"""
    bl_idname = "candela.export_dump"
    bl_label = "Export Candela Dump"

    directory: StringProperty(name="Directory", subtype='DIR_PATH',
                              description="Directory receiving params.json and one .npy file per array")

    def execute(self, context):
        if not self.directory:
            self.report({'ERROR'}, "Candela: no dump directory given")
            return {'CANCELLED'}
        try:
            messages = export_dump(context, self.directory)
        except (ExportError, ValueError, OSError) as e:
            self.report({'ERROR'}, f"Candela: {e}")
            return {'CANCELLED'}
        for message in messages:
            self.report({'WARNING'}, message)
        self.report({'INFO'}, f"Candela: dump written to {self.directory}")
        return {'FINISHED'}

    def invoke(self, context, event):
        context.window_manager.fileselect_add(self)
        return {'RUNNING_MODAL'}


def register():
    bpy.utils.register_class(CANDELA_OT_export_dump)


def unregister():
    bpy.utils.unregister_class(CANDELA_OT_export_dump)
