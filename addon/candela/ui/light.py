"""Light properties: type, colour, power and size (like CYCLES_LIGHT_PT_light); DATA_PT_spot/area are reused."""

import bpy

from .base import CandelaPanel


class CANDELA_LIGHT_PT_light(CandelaPanel, bpy.types.Panel):
    bl_context = "data"
    bl_label = "Light"

    @classmethod
    def poll(cls, context):
        return context.light is not None and super().poll(context)

    def draw(self, context):
        layout = self.layout
        light = context.light
        layout.row().prop(light, "type", expand=True)
        layout.use_property_split = True
        layout.use_property_decorate = False
        col = layout.column()
        col.prop(light, "color")
        col.prop(light, "energy")
        if light.type in {'POINT', 'SPOT'}:
            col.prop(light, "shadow_soft_size", text="Radius")
        elif light.type == 'SUN':
            col.prop(light, "angle")


classes = (CANDELA_LIGHT_PT_light,)
