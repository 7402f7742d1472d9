"""Render-tab panels: Sampling, Light Paths, Film."""

import bpy

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


class CANDELA_RENDER_PT_light_paths(CandelaPanel, bpy.types.Panel):
    bl_context = "render"
    bl_label = "Light Paths"
    bl_options = {'DEFAULT_CLOSED'}

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        settings = context.scene.candela
        col = layout.column()
        col.prop(settings, "max_bounces")
        col.prop(settings, "rr_mode")
        sub = col.column()
        sub.active = settings.rr_mode != 'OFF'
        sub.prop(settings, "rr_start_bounce")
        col.prop(settings, "branching_factor")
        col.prop(settings, "hemisphere_sampling")
        col.prop(settings, "clamp_indirect")


class CANDELA_RENDER_PT_light_sampling(CandelaPanel, bpy.types.Panel):
    bl_context = "render"
    bl_label = "Light Sampling"
    bl_options = {'DEFAULT_CLOSED'}

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        settings = context.scene.candela
        col = layout.column()
        col.prop(settings, "light_sampling")
        sub = col.column()
        sub.active = settings.light_sampling == 'MIS'
        sub.prop(settings, "mis_heuristic")
        col.prop(settings, "light_selection")
        sub = col.column()
        sub.active = settings.light_selection == 'WARD'
        sub.prop(settings, "ward_threshold")
        col.prop(settings, "light_pdf")
        col.prop(settings, "light_samples")


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


classes = (CANDELA_RENDER_PT_sampling, CANDELA_RENDER_PT_sampling_viewport, CANDELA_RENDER_PT_light_paths, CANDELA_RENDER_PT_light_sampling,
           CANDELA_RENDER_PT_film, CANDELA_RENDER_PT_simplify)
