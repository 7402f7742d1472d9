"""View Layer tab: the render passes Candela can write (passes.py), drawn like Cycles' Passes > Data panel."""

import bpy

from .base import CandelaPanel


class CANDELA_VIEWLAYER_PT_passes(CandelaPanel, bpy.types.Panel):
    bl_context = "view_layer"
    bl_label = "Passes"

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        view_layer = context.view_layer
        col = layout.column(heading="Include", align=True)
        col.prop(view_layer, "use_pass_combined")
        col.prop(view_layer, "use_pass_z")
        col.prop(view_layer, "use_pass_normal")
        col.prop(view_layer.candela, "use_pass_albedo")
        col = layout.column(heading="Indexes", align=True)
        col.prop(view_layer, "use_pass_object_index")
        col = layout.column(heading="Candela", align=True)
        col.prop(view_layer.candela, "use_pass_noise")
        col.prop(view_layer.candela, "use_pass_ic_records")


classes = (CANDELA_VIEWLAYER_PT_passes,)
