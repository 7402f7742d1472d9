"""Drawing the viewport image with Blender's gpu module.

The native image is scene-linear RGBA, rows bottom to top, of a level's film (a coarse level has fewer pixels
than the view). It becomes a float texture stretched over the part of the view it covers; the draw manager's
viewport buffer is scene-linear and Blender applies the view transform, look, exposure and gamma when it shows
it, so colour-management edits never restart the render (bind_display_space_shader binds the image shader the
engine API expects).
"""

import gpu
import numpy as np
from gpu_extras.presets import draw_texture_2d


class Display:
    """The newest uploaded image: its texture and where it goes in the view."""

    def __init__(self):
        self.texture = None
        self.version = 0
        self.meta = None      # the image dict without its pixels
        self.uploads = 0

    def upload(self, image):
        """Replace the texture with a native ViewportSession.image() dict."""
        pixels = image.pop("pixels")
        height, width = pixels.shape[:2]
        # gpu.types.Buffer copies from an array of matching shape in one block (element by element otherwise).
        flat = np.ascontiguousarray(pixels, np.float32).reshape(height, width * 4)
        buffer = gpu.types.Buffer('FLOAT', [height, width * 4], flat)
        self.texture = gpu.types.GPUTexture((width, height), format='RGBA32F', data=buffer)
        self.version = image["version"]
        self.meta = image
        self.uploads += 1

    def draw(self, engine, scene, width, height):
        """Draw into the view of width × height pixels; False if there is nothing to draw yet."""
        if self.texture is None:
            return False
        m = self.meta
        sx, sy = width / m["frame_width"], height / m["frame_height"]
        gpu.state.blend_set('ALPHA_PREMULT')
        engine.bind_display_space_shader(scene)
        draw_texture_2d(self.texture, (m["x0"] * sx, m["y0"] * sy), m["width"] * sx, m["height"] * sy)
        engine.unbind_display_space_shader()
        gpu.state.blend_set('NONE')
        return True

    def free(self):
        self.texture = None
        self.meta = None
