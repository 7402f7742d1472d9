"""View Layer tab: the render passes Candela can write."""

import bpy

from .base import CandelaPanel


class CANDELA_VIEWLAYER_PT_passes(CandelaPanel, bpy.types.Panel):
    bl_context = "view_layer"
    bl_label = "Passes"

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        col = layout.column(heading="Include", align=True)
        col.prop(context.view_layer.candela, "use_pass_noise")


classes = (CANDELA_VIEWLAYER_PT_passes,)
