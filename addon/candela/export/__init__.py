"""Depsgraph → dict of numpy arrays in the native schema (docs/architecture.md). Pure data: no bpy writes.

    arrays = export_scene(depsgraph, camera, test_break=engine.test_break, status=print, warnings=Warnings())

Returns None when `test_break()` turned True; raises ExportError for scenes that cannot be rendered.
"""

import numpy as np

from .camera import camera_to_world, render_camera
from .common import ExportError, Warnings
from .geometry import GeometryTable
from .lights import LightTable
from .materials import MaterialTable
from .world import world_color

__all__ = ["export_scene", "render_camera", "ExportError", "Warnings"]

GEOMETRY_TYPES = {'MESH', 'CURVE', 'SURFACE', 'FONT', 'META'}
BREAK_EVERY = 1000   # instances between test_break()/status calls: cheap enough, and < 0.1 s apart in practice


def _hidden_for_render(inst):
    """A render depsgraph already drops hide_render objects; the viewport one (dump operator) does not."""
    owner = inst.parent if inst.is_instance and inst.parent is not None else inst.object
    return owner.original.hide_render


def export_scene(depsgraph, camera, test_break=None, status=None, warnings=None):
    """Export the evaluated scene seen through `camera` (an original camera object, see render_camera)."""
    warnings = warnings if warnings is not None else Warnings()
    scene = depsgraph.scene
    materials = MaterialTable(warnings)
    geometry = GeometryTable(materials)
    lights = LightTable(warnings)

    for i, inst in enumerate(depsgraph.object_instances):
        if i % BREAK_EVERY == BREAK_EVERY - 1:
            if test_break is not None and test_break():
                return None
            if status is not None:
                status(f"Exporting objects ({i + 1})")
        ob = inst.object
        if ob.type not in GEOMETRY_TYPES and ob.type != 'LIGHT':
            continue
        # inst.matrix_world is a transient view into the iterator: copy it before doing anything else.
        matrix = np.array(inst.matrix_world, np.float32)
        if _hidden_for_render(inst):
            continue
        if ob.type == 'LIGHT':
            lights.add(ob.data, matrix, visible_camera=ob.visible_camera)
        elif inst.show_self:
            geometry.add(ob, matrix)

    if geometry.triangle_count == 0:
        raise ExportError(f"scene '{scene.name}' has nothing to render: no visible mesh triangles")

    arrays = geometry.arrays()
    arrays.update(materials.arrays())
    arrays.update(lights.arrays())
    arrays["camera_to_world"] = camera_to_world(camera.original.evaluated_get(depsgraph).matrix_world)
    arrays["world_color"] = world_color(scene.world, warnings)
    return arrays
