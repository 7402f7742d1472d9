"""Render-tab panels: Sampling, the chosen integrator's settings (sub-panels generated from the settings the native
registry publishes: one per group, "Light Paths" and "Light Sampling" for PATH) after its Viewport sub-panel, Film,
Simplify (after Sampling, as in Cycles)."""

import bpy

from .. import schema
from .base import CandelaPanel


class CANDELA_RENDER_PT_sampling(CandelaPanel, bpy.types.Panel):
    bl_context = "render"
    bl_label = "Sampling"

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        settings = context.scene.candela
        col = layout.column()
        col.prop(settings, "integrator")
        col.prop(settings, "samples")
        col.prop(settings, "noise_threshold")
        col.prop(settings, "time_limit")
        col.prop(settings, "sampler")
        row = col.row(align=True)
        row.prop(settings, "seed")
        row.prop(settings, "use_animated_seed", text="", icon='TIME')
        if getattr(context.scene, "cycles", None) is not None and hasattr(settings, "diffuse_bounces"):
            col.operator("candela.copy_cycles_light_paths", icon='IMPORT')


class CANDELA_OT_copy_cycles_light_paths(bpy.types.Operator):
    """Set Candela's bounce limits, clamps, Filter Glossy and caustics switches to this scene's Cycles values"""
    bl_idname = "candela.copy_cycles_light_paths"
    bl_label = "Light Paths from Cycles"
    bl_options = {'REGISTER', 'UNDO'}

    def execute(self, context):
        from ..params import copy_cycles_light_paths
        copied = copy_cycles_light_paths(context.scene)
        self.report({'INFO'}, f"Candela: copied {len(copied)} Light Paths settings from Cycles")
        return {'FINISHED'}


class CANDELA_RENDER_PT_sampling_viewport(CandelaPanel, bpy.types.Panel):
    bl_context = "render"
    bl_label = "Viewport"
    bl_parent_id = "CANDELA_RENDER_PT_sampling"

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        settings = context.scene.candela
        col = layout.column()
        col.prop(settings, "viewport_samples", text="Samples")
        col.prop(settings, "viewport_start_resolution")
        col.prop(context.scene.render, "preview_pixel_size", text="Pixel Size")


class CANDELA_RENDER_PT_film(CandelaPanel, bpy.types.Panel):
    bl_context = "render"
    bl_label = "Film"
    bl_options = {'DEFAULT_CLOSED'}

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        settings = context.scene.candela
        col = layout.column()
        col.prop(settings, "pixel_filter")
        sub = col.column()
        sub.active = settings.pixel_filter != 'BOX'
        sub.prop(settings, "filter_width", text="Width")
        col.prop(context.scene.render, "film_transparent", text="Transparent")
        cycles = getattr(context.scene, "cycles", None)
        if cycles is not None:   # Cycles' own Film settings, shared with it (addon/candela/params.py)
            sub = col.column()
            sub.active = context.scene.render.film_transparent
            sub.prop(cycles, "film_transparent_glass", text="Transparent Glass")
            sub2 = sub.column()
            sub2.active = cycles.film_transparent_glass
            sub2.prop(cycles, "film_transparent_roughness", text="Roughness Threshold")
            col.prop(cycles, "film_exposure", text="Exposure")


class CANDELA_RENDER_PT_simplify(CandelaPanel, bpy.types.Panel):
    """Blender's Simplify settings (subdivision and child particles are applied by Blender's evaluation, which
    Candela renders), drawn after Sampling like Cycles' (Blender's own panel would come first: ui/compat.py)."""
    bl_context = "render"
    bl_label = "Simplify"
    bl_options = {'DEFAULT_CLOSED'}

    def draw_header(self, context):
        self.layout.prop(context.scene.render, "use_simplify", text="")

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        rd = context.scene.render
        layout.active = rd.use_simplify
        col = layout.column(heading="Viewport")
        col.prop(rd, "simplify_subdivision", text="Max Subdivision")
        col.prop(rd, "simplify_child_particles", text="Child Particles")
        col = layout.column(heading="Render")
        col.prop(rd, "simplify_subdivision_render", text="Max Subdivision")
        col.prop(rd, "simplify_child_particles_render", text="Child Particles")


def condition_holds(settings, condition):
    """A published setting's `active_if`: "KEY==ID", "KEY!=ID" or "KEY>N" (empty: always)."""
    if not condition:
        return True
    for op in ("==", "!=", ">"):
        if op in condition:
            key, value = condition.split(op, 1)
            current = getattr(settings, key.strip(), None)
            if op == "==":
                return str(current) == value.strip()
            if op == "!=":
                return str(current) != value.strip()
            return current is not None and float(current) > float(value)
    return True


def settings_groups(specs):
    """[(group, [spec, ...]), ...] in the order the groups first appear."""
    groups = []
    for spec in specs:
        group = spec.get("group") or ""
        for name, members in groups:
            if name == group:
                members.append(spec)
                break
        else:
            groups.append((group, [spec]))
    return groups


def make_settings_panel(integrator, label, index, group, specs):
    """A sub-panel of Sampling drawing one group of an integrator's settings, shown while it is the chosen one."""
    keys = tuple(spec["key"] for spec in specs)
    conditions = {spec["key"]: spec.get("active_if", "") for spec in specs}

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        settings = context.scene.candela
        col = layout.column()
        for key in keys:
            if not hasattr(settings, key):
                continue
            row = col.row()
            row.active = condition_holds(settings, conditions[key])
            row.prop(settings, key)

    def poll(cls, context):
        return CandelaPanel.poll.__func__(cls, context) and context.scene.candela.integrator == integrator

    return type(f"CANDELA_RENDER_PT_{integrator.lower()}_{index}", (CandelaPanel, bpy.types.Panel), {
        "bl_context": "render", "bl_label": group or label, "bl_parent_id": "CANDELA_RENDER_PT_sampling",
        "bl_options": {'DEFAULT_CLOSED'}, "draw": draw, "poll": classmethod(poll)})


def settings_panels():
    panels = []
    labels = {name: label for name, _, label in schema.integrators()}
    for integrator, specs in schema.integrator_params().items():
        for index, (group, members) in enumerate(settings_groups(specs)):
            panels.append(make_settings_panel(integrator, labels.get(integrator, integrator), index, group, members))
    return tuple(panels)


classes = ((CANDELA_RENDER_PT_sampling, CANDELA_RENDER_PT_sampling_viewport, CANDELA_OT_copy_cycles_light_paths) +
           settings_panels() + (CANDELA_RENDER_PT_film, CANDELA_RENDER_PT_simplify))
