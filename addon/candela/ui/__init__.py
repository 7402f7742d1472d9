"""Candela's UI: own panels plus Blender's reusable ones."""

import bpy

from . import compat, light, node_categories, presets, render, surfaces, view_layer, visibility

classes = (render.classes + light.classes + surfaces.classes + view_layer.classes + visibility.classes +
           presets.classes)


def register():
    for cls in classes:
        bpy.utils.register_class(cls)
    compat.register()
    node_categories.register()
    presets.register()


def unregister():
    presets.unregister()
    node_categories.unregister()
    compat.unregister()
    for cls in reversed(classes):
        bpy.utils.unregister_class(cls)
