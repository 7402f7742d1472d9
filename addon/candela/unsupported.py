"""Blender settings a scene uses that Candela does not render: one warning per render each, naming the setting or
the object, material or view layer, so nothing is dropped without a word.

Checked: motion blur's rolling shutter, a view layer's Material Override, render passes Candela does not write (every use_pass_*
beyond Combined, Depth, Normal and Object Index, plus Cycles' own), shader AOVs and light groups, volumes (Volume
objects, a material's or the world's Volume output), true displacement (a material's Displacement output with
the Displacement Only or Displacement and Bump method: Candela renders the output as bump mapping, Cycles' Bump Only,
which is not reported), hair (hair particle systems and Curves objects), stereo for panoramic cameras
and depth of field through a panorama.
"""

import bpy

from .export.shader_nodes import resolve
from .params import unapplied_light_paths

# Blender's pass toggles Candela writes (passes.py); every other use_pass_* of the view layer is reported.
PRODUCED = {"use_pass_combined", "use_pass_z", "use_pass_normal", "use_pass_object_index",
            "use_pass_cryptomatte_accurate"}   # "accurate" is an option of cryptomatte, not a pass
CYCLES_PASSES = ("use_pass_volume_direct", "use_pass_volume_indirect", "use_pass_shadow_catcher",
                 "denoising_store_passes")


def _label(prop_owner, identifier):
    prop = prop_owner.bl_rna.properties.get(identifier)
    name = prop.name if prop is not None else identifier
    return name


def pass_messages(view_layer):
    out = []
    for prop in view_layer.bl_rna.properties:
        ident = prop.identifier
        if ident.startswith("use_pass_") and ident not in PRODUCED and getattr(view_layer, ident, False):
            out.append(f"Candela: view layer '{view_layer.name}': the {prop.name} pass is not produced (Candela "
                       "writes Combined, Depth, Normal, Albedo, Object Index and Noise)")
    cycles = getattr(view_layer, "cycles", None)
    if cycles is not None:
        for ident in CYCLES_PASSES:
            if getattr(cycles, ident, False):
                out.append(f"Candela: view layer '{view_layer.name}': the {_label(cycles, ident)} pass (Cycles) is "
                           "not produced")
    if len(getattr(view_layer, "aovs", ())):
        out.append(f"Candela: view layer '{view_layer.name}': shader AOVs are not produced")
    if len(getattr(view_layer, "lightgroups", ())):
        out.append(f"Candela: view layer '{view_layer.name}': light groups are not produced")
    return out


def _linked(tree, kind, socket):
    """Whether the active Cycles output of `kind` has its `socket` input driven by a node."""
    if tree is None:
        return False
    output = tree.get_output_node('CYCLES')
    if output is None or output.bl_idname != kind or socket not in output.inputs:
        return False
    out, _, _ = resolve(output.inputs[socket], ())
    return out is not None


def material_messages(material):
    out = []
    tree = material.node_tree if material.use_nodes else None
    if _linked(tree, "ShaderNodeOutputMaterial", "Volume"):
        out.append(f"Candela: material '{material.name}': the Volume output is ignored (no volume rendering)")
    # The original's setting: an evaluated copy keeps the value of its last evaluation, older than an edit the
    # depsgraph has not seen yet.
    method = displacement_method(getattr(material, "original", None) or material)
    if method != "BUMP" and _linked(tree, "ShaderNodeOutputMaterial", "Displacement"):
        label = {"DISPLACEMENT": "Displacement Only", "BOTH": "Displacement and Bump"}.get(method, method)
        out.append(f"Candela: material '{material.name}': the Displacement output's true displacement (method "
                   f"{label}) is not rendered: the surface does not move, the output is rendered as bump mapping only")
    return out


def displacement_method(material):
    """Cycles' displacement method of a material ('BUMP', 'DISPLACEMENT' or 'BOTH'; Blender 3.4 keeps it in the
    Cycles add-on's settings, later versions on the material); 'BUMP' where neither has one."""
    method = getattr(material, "displacement_method", None)
    if method is None:
        method = getattr(getattr(material, "cycles", None), "displacement_method", "BUMP")
    return method


def world_messages(world):
    if world is not None and world.use_nodes and _linked(world.node_tree, "ShaderNodeOutputWorld", "Volume"):
        return [f"Candela: world '{world.name}': the Volume output is ignored (no volume rendering)"]
    return []


def object_messages(ob):
    out = []
    if ob.type == 'VOLUME':
        out.append(f"Candela: object '{ob.name}' is a volume: volumes are not rendered")
    elif ob.type == 'CURVES':
        out.append(f"Candela: object '{ob.name}' is hair (Curves): hair is not rendered")
    for psys in getattr(ob, "particle_systems", ()):
        settings = psys.settings
        if settings is not None and settings.type == 'HAIR' and settings.render_type == 'PATH':
            out.append(f"Candela: object '{ob.name}': hair particle system '{psys.name}' is not rendered")
    return out


def camera_messages(camera, scene):
    out = []
    data = camera.data
    if data.type == 'PANO' and data.dof.use_dof:
        out.append(f"Candela: camera '{camera.name}': depth of field is not rendered through a panoramic camera")
    if data.type == 'PANO' and scene.render.use_multiview:
        out.append(f"Candela: camera '{camera.name}': stereo of a panoramic camera renders each eye from an offset "
                   "position (no spherical stereo)")
    return out


def _shown(value):
    if isinstance(value, bool):
        return "on" if value else "off"
    return f"{value:g}" if isinstance(value, float) else str(value)


def light_paths_messages(settings):
    """One warning when Light Paths settings (e.g. copied from Cycles) are set that the chosen integrator does not
    apply: without it the image would silently be brighter than PATH's or Cycles' with the same settings."""
    unapplied = unapplied_light_paths(settings)
    if not unapplied:
        return []
    listed = ", ".join(f"{label} {_shown(value)}" for label, value in unapplied)
    return [f"Candela: {settings.integrator} does not apply the path tracer's Light Paths settings {listed}: its "
            "image is the full solution without these limits and clamps (PATH applies them)"]


def ignored_settings(depsgraph, camera=None):
    """The messages for the evaluated scene of `depsgraph` (camera: the render camera, if any)."""
    scene = depsgraph.scene
    out = []
    if scene.render.use_motion_blur:
        # Camera and object motion are rendered (export/motion.py); these parts of Cycles' motion blur are not.
        if getattr(getattr(scene, "cycles", None), "rolling_shutter_type", "NONE") != "NONE":
            out.append("Candela: Motion Blur > Rolling Shutter is not rendered: every row sees the whole shutter")
    layer = scene.original.view_layers.get(depsgraph.view_layer.name) if depsgraph.view_layer else None
    if layer is not None:
        if layer.material_override is not None:
            out.append(f"Candela: view layer '{layer.name}': Material Override '{layer.material_override.name}' is "
                       "ignored; objects render with their own materials")
        out += pass_messages(layer)
    for block in depsgraph.ids:
        if isinstance(block, bpy.types.Material):
            out += material_messages(block)
        elif isinstance(block, bpy.types.Object):
            out += object_messages(block)
    out += world_messages(scene.world)
    out += light_paths_messages(scene.candela)
    if camera is not None:
        out += camera_messages(camera, scene)
    return out
