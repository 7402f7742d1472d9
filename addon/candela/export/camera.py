"""The render camera: which object, and its scale-free camera → world matrix."""

import numpy as np

from .common import ExportError


def render_camera(scene, camera_override=None):
    """`engine.camera_override or scene.camera` (the original object), or an ExportError naming the scene."""
    camera = camera_override or scene.camera
    if camera is None:
        raise ExportError(f"scene '{scene.name}' has no camera")
    if camera.type != 'CAMERA':
        raise ExportError(f"scene '{scene.name}': the active camera '{camera.name}' is not a camera object")
    return camera


def camera_to_world(matrix_world):
    """(4, 4) float32 with the rotation columns normalised: the native camera wants a rigid transform.

    The camera looks down −Z with +Y up, exactly Blender's camera object convention, so no axis flip here.
    """
    m = np.array(matrix_world, np.float64)
    for axis in range(3):
        n = np.linalg.norm(m[:3, axis])
        if n > 0:
            m[:3, axis] /= n
    return m.astype(np.float32)
