"""Depsgraph → dict of numpy arrays in the native schema (docs/architecture.md). Pure data: no bpy writes.

    arrays = export_scene(depsgraph, camera, test_break=engine.test_break, status=print, warnings=Warnings())

Returns None when `test_break()` turned True; raises ExportError for scenes that cannot be rendered. Pass a dict
as `names` to receive how each exported mesh and instance is named in messages (name_objects uses it).
"""

import re

import numpy as np

from .. import schema
from .camera import camera_to_world, render_camera
from .motion import instance_key
from .common import ExportError, Warnings
from .geometry import GeometryTable, random_from_id
from .lights import LightTable
from .materials import MaterialTable
from .mesh import read_mesh
from .shader_tables import ShaderTables
from .world import world_arrays

__all__ = ["export_scene", "render_camera", "name_objects", "ExportError", "Warnings"]

GEOMETRY_TYPES = {'MESH', 'CURVE', 'SURFACE', 'FONT', 'META'}
BREAK_EVERY = 1000   # instances between test_break()/status calls: cheap enough, and < 0.1 s apart in practice


def _hidden_for_render(inst):
    """A render depsgraph already drops hide_render objects; the viewport one (dump operator) does not."""
    owner = inst.parent if inst.is_instance and inst.parent is not None else inst.object
    return owner.original.hide_render


VISIBILITY = (("CAMERA", "visible_camera"), ("DIFFUSE", "visible_diffuse"), ("GLOSSY", "visible_glossy"),
              ("TRANSMISSION", "visible_transmission"), ("SHADOW", "visible_shadow"))


def object_flags(inst, view_layer, bits):
    """`instance_flags` of one instance, as Cycles syncs an object: ray visibility is the instance's AND its
    instancer's (Object > Visibility > Ray Visibility), holdout is the instancer's (or the object's own) holdout in
    this view layer (Object > Visibility > Holdout, or a holdout collection)."""
    owner = inst.parent if inst.is_instance and inst.parent is not None else inst.object
    obs = (inst.object, owner) if owner is not inst.object else (inst.object,)
    flags = 0
    for name, attr in VISIBILITY:
        if all(getattr(o, attr, True) for o in obs):
            flags |= bits[name]
    if _holdout(owner, view_layer):
        flags |= bits["HOLDOUT"]
    return flags


def _holdout(owner, view_layer):
    """The object's own holdout, or its collection's in `view_layer` (an original view layer: holdout_get on an
    evaluated object and view layer answers False in 3.4.1, even for an object marked holdout)."""
    if owner.is_holdout:
        return True
    if view_layer is None:
        return False
    try:
        return bool(owner.original.holdout_get(view_layer=view_layer))
    except (TypeError, RuntimeError, ReferenceError):
        return False


def _original_view_layer(depsgraph):
    layer = getattr(depsgraph, "view_layer", None)
    if layer is None:
        return None
    return depsgraph.scene.original.view_layers.get(layer.name)


def name_objects(message, names):
    """A native message names meshes and instances by index ("mesh 3", "instance 7"); name the Blender objects."""
    if not names:
        return message

    def replace(kind):
        def label(match):
            index = int(match.group(1))
            table = names.get(kind, [])
            return table[index] if index < len(table) else match.group(0)
        return label

    message = re.sub(r"\bmesh (\d+)\b", replace("mesh"), message)
    return re.sub(r"\binstance (\d+)\b", replace("instance"), message)


def export_scene(depsgraph, camera, test_break=None, status=None, warnings=None, names=None, mesh_reader=None,
                 camera_matrix=None, image_cache=None, motion=None):
    """Export the evaluated scene seen through `camera` (an original camera object, see render_camera), or from
    `camera_matrix` (a 4x4 camera → world matrix: the 3D view's) when `camera` is None. `mesh_reader`: how
    meshes are read (default export/mesh.py read_mesh; the viewport passes its cache's); `image_cache` a dict
    keeping loaded image texels across exports (the viewport's)."""
    warnings = warnings if warnings is not None else Warnings()
    scene = depsgraph.scene
    tables = ShaderTables(warnings, image_cache)
    materials = MaterialTable(warnings, tables)
    geometry = GeometryTable(materials, read=mesh_reader or read_mesh)
    lights = LightTable(warnings)
    bits = schema.instance_flags()
    view_layer = _original_view_layer(depsgraph)
    # Motion blur: `motion` (a dict, if given) gets each instance's key and motion steps, for export/motion.py's
    # motion_arrays, which samples the transforms over the shutter (it moves Blender's frame: the caller runs it).

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
            random = random_from_id(inst.random_id) if inst.is_instance else None
            geometry.add(ob, matrix, flags=object_flags(inst, view_layer, bits), pass_index=ob.pass_index,
                         random=random, motion_key=instance_key(inst) if motion is not None else None)

    world = world_arrays(scene.world, warnings, tables)
    if geometry.triangle_count == 0 and not lights.rows and not _world_emits(world):
        # Cycles renders black here; an error says why (every object hidden, an empty file) instead.
        raise ExportError(f"scene '{scene.name}' has nothing to render: no visible mesh triangles, no lights "
                          "and a black world")

    if names is not None:
        names.update(geometry.names())
    arrays = geometry.arrays()
    arrays.update(materials.arrays())
    arrays.update(lights.arrays())
    if camera is not None:
        camera_matrix = camera.original.evaluated_get(depsgraph).matrix_world
    arrays["camera_to_world"] = camera_to_world(camera_matrix)
    if motion is not None:
        motion["keys"] = geometry.instance_keys
        motion["steps"] = geometry.motion_steps
    arrays.update(world)
    arrays.update(tables.arrays())   # after every material and the world: the programs and their bindings
    return arrays


def _world_emits(world):
    """A world program (an HDRI, a texture) or a non-black constant colour."""
    color = world.get("world_color")
    return color is None or bool(np.any(np.asarray(color) > 0.0))
