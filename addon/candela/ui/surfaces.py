"""Material and world Surface panels drawing the Cycles node tree Candela reads (EEVEE's read the EEVEE output)."""

import bpy

from .base import CandelaPanel


def _draw_output(layout, id_data, fallback_prop):
    if not id_data.use_nodes or id_data.node_tree is None:
        layout.prop(id_data, "use_nodes", icon='NODETREE')
        layout.use_property_split = True
        layout.prop(id_data, fallback_prop)
        return
    tree = id_data.node_tree
    output = tree.get_output_node('CYCLES')
    if output is None:
        layout.label(text="No output node")
        return
    layout.template_node_view(tree, output, output.inputs["Surface"])


class CANDELA_MATERIAL_PT_surface(CandelaPanel, bpy.types.Panel):
    bl_context = "material"
    bl_label = "Surface"

    @classmethod
    def poll(cls, context):
        return context.material is not None and super().poll(context)

    def draw(self, context):
        _draw_output(self.layout, context.material, "diffuse_color")


class CANDELA_WORLD_PT_surface(CandelaPanel, bpy.types.Panel):
    bl_context = "world"
    bl_label = "Surface"

    @classmethod
    def poll(cls, context):
        return context.world is not None and super().poll(context)

    def draw(self, context):
        _draw_output(self.layout, context.world, "color")


class CANDELA_WORLD_PT_preview(CandelaPanel, bpy.types.Panel):
    """The world preview Candela renders (bl_use_preview); Blender has no engine-agnostic world preview panel."""
    bl_context = "world"
    bl_label = "Preview"
    bl_options = {'DEFAULT_CLOSED'}

    @classmethod
    def poll(cls, context):
        return context.world is not None and super().poll(context)

    def draw(self, context):
        self.layout.template_preview(context.world)


classes = (CANDELA_WORLD_PT_preview, CANDELA_MATERIAL_PT_surface, CANDELA_WORLD_PT_surface)
