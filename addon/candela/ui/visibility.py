"""Object tab: Ray Visibility under Visibility (Blender's panel already draws Holdout), like Cycles' sub-panel."""

import bpy

from .base import CandelaPanel


class CANDELA_OBJECT_PT_visibility_ray_visibility(CandelaPanel, bpy.types.Panel):
    bl_context = "object"
    bl_label = "Ray Visibility"
    bl_parent_id = "OBJECT_PT_visibility"

    @classmethod
    def poll(cls, context):
        ob = context.object
        return ob is not None and ob.type in {'MESH', 'CURVE', 'SURFACE', 'FONT', 'META'} and super().poll(context)

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        ob = context.object
        col = layout.column(heading="Ray Visibility", align=True)
        col.prop(ob, "visible_camera", text="Camera", toggle=False)
        col.prop(ob, "visible_diffuse", text="Diffuse", toggle=False)
        col.prop(ob, "visible_glossy", text="Glossy", toggle=False)
        col.prop(ob, "visible_transmission", text="Transmission", toggle=False)
        col.prop(ob, "visible_shadow", text="Shadow", toggle=False)


classes = (CANDELA_OBJECT_PT_visibility_ray_visibility,)
