"""Add-on preferences: shows whether the native module loaded, and why not."""

import sys

import bpy

from . import native, schema

# Set by __init__.register() when registering the full add-on failed for a reason other than the native module.
registration_error = None


class CandelaPreferences(bpy.types.AddonPreferences):
    bl_idname = __package__

    def draw(self, context):
        layout = self.layout
        col = layout.column()
        if native.module is not None and registration_error is None:
            caps = native.capabilities()
            col.label(text=f"Native module loaded (ABI {native.ABI_VERSION})", icon='CHECKMARK')
            col.label(text="Integrators: " + ", ".join(entry[0] for entry in schema.integrators()))
            return
        col.label(text="Candela cannot render:", icon='ERROR')
        for line in _wrap(registration_error or native.error or "unknown error", 90):
            col.label(text=line)
        col.label(text=f"Blender's Python: {sys.version.split()[0]}; expected native ABI {native.ABI_VERSION}, "
                       f"cpython-311-x86_64-linux-gnu")


def _wrap(text, width):
    words, line = text.split(), ""
    for word in words:
        if line and len(line) + 1 + len(word) > width:
            yield line
            line = word
        else:
            line = f"{line} {word}" if line else word
    if line:
        yield line


def register():
    bpy.utils.register_class(CandelaPreferences)


def unregister():
    bpy.utils.unregister_class(CandelaPreferences)
