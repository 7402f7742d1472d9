"""Reuse Blender's engine-agnostic panels by adding 'CANDELA' to their COMPAT_ENGINES (Cycles' get_panels()).

Every panel declaring 'BLENDER_RENDER' compatibility qualifies, minus EXCLUDE (replaced by Candela's own panels or
meaningless for Candela), plus EXTRA (EEVEE panels that are right for Candela too).
"""

import bpy

ENGINE = "CANDELA"
EXCLUDE = {
    "DATA_PT_light",            # type selector only: CANDELA_LIGHT_PT_light draws type + colour + power
    "DATA_PT_spot",             # hangs off EEVEE's light panel: CANDELA_LIGHT_PT_spot draws it under Candela's
    "DATA_PT_area",             # registered before Candela's light panel, so drawn above it: drawn inside it instead
    "RENDER_PT_freestyle",      # no Freestyle support
    "MATERIAL_PT_freestyle_line",
}
# Simplify (and its sub-panels) is registered before Candela's Sampling panel and would be drawn above it:
# CANDELA_RENDER_PT_simplify draws the same settings after Sampling.
EXCLUDE_PREFIXES = ("VIEWLAYER_PT_freestyle", "DATA_PT_lightprobe", "DATA_PT_context_lightprobe", "RENDER_PT_simplify")
EXTRA = ("EEVEE_MATERIAL_PT_context_material",   # the material slot list
         "MATERIAL_PT_preview",                  # the material preview (Candela renders it: bl_use_preview)
         "DATA_PT_camera_dof", "DATA_PT_camera_dof_aperture")   # depth of field: focus, f-stop, blades, ratio

_added = []   # panels we changed, so unregister undoes exactly that

# Many panels inherit one COMPAT_ENGINES set object from a shared base class, so adding to it in place would also
# enable the excluded panels sharing it. Each changed panel gets its own new set instead (in place edits by other
# engines registered later still reach it, since they walk every panel as well).


def _panels():
    for name in dir(bpy.types):
        panel = getattr(bpy.types, name, None)
        engines = getattr(panel, "COMPAT_ENGINES", None)
        if not isinstance(engines, set):
            continue
        if name in EXTRA or ("BLENDER_RENDER" in engines and name not in EXCLUDE
                             and not name.startswith(EXCLUDE_PREFIXES)):
            yield panel


def register():
    for panel in list(_panels()):
        if ENGINE not in panel.COMPAT_ENGINES:
            panel.COMPAT_ENGINES = panel.COMPAT_ENGINES | {ENGINE}
            _added.append(panel)


def unregister():
    for panel in _added:
        panel.COMPAT_ENGINES = panel.COMPAT_ENGINES - {ENGINE}
    _added.clear()
