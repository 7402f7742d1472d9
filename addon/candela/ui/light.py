"""Light properties: type, colour, power, size and shape (like CYCLES_LIGHT_PT_light), and the spot's cone.

Blender's DATA_PT_area would be drawn above this panel (it is registered first) and DATA_PT_spot hangs off EEVEE's
light panel, so Candela draws both itself (ui/compat.py excludes them).
"""

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
        elif light.type == 'AREA':
            col.separator()
            col.prop(light, "shape", text="Shape")
            sub = col.column(align=True)
            if light.shape in {'SQUARE', 'DISK'}:
                sub.prop(light, "size")
            else:
                sub.prop(light, "size", text="Size X")
                sub.prop(light, "size_y", text="Y")


class CANDELA_LIGHT_PT_spot(CandelaPanel, bpy.types.Panel):
    bl_context = "data"
    bl_label = "Spot Shape"
    bl_parent_id = "CANDELA_LIGHT_PT_light"

    @classmethod
    def poll(cls, context):
        return context.light is not None and context.light.type == 'SPOT' and super().poll(context)

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        light = context.light
        col = layout.column()
        col.prop(light, "spot_size", text="Size")
        col.prop(light, "spot_blend", text="Blend", slider=True)
        col.prop(light, "show_cone")


classes = (CANDELA_LIGHT_PT_light, CANDELA_LIGHT_PT_spot)
