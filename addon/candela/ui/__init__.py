"""Candela's UI: own panels plus Blender's reusable ones."""

import bpy

from . import compat, light, render, surfaces, view_layer

classes = render.classes + light.classes + surfaces.classes + view_layer.classes


def register():
    for cls in classes:
        bpy.utils.register_class(cls)
    compat.register()


def unregister():
    compat.unregister()
    for cls in reversed(classes):
        bpy.utils.unregister_class(cls)
