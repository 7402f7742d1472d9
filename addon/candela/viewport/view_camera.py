"""The 3D view's own camera as native camera params, the way Cycles builds it (blender_camera_from_view):

- a free perspective view: the view's lens with Blender's 36 mm default sensor, clip start/end of the view, the
  viewplane zoomed ×2 (Blender's viewport convention);
- an orthographic view: ortho_scale = view distance · 36 / lens, rays from half the clip end behind the view
  (clip_start = −clip_end/2) to half in front;
- the camera view: the scene camera (or the view's local camera) with its lens, sensor, shift and depth of
  field, zoomed by Blender's camera-view zoom 2 / (√2 + zoom/50)² (×2) and panned by view_camera_offset; a
  panoramic camera instead maps the viewport to the part of the panorama inside the camera frame.

The matrix is the view's (view_matrix inverted: −Z forward, +Y up, as a camera object), in camera view the
camera's own (the same, without waiting for the view to be redrawn). Borders: the
camera view honours the render border (inside the camera frame), other views the view's own render region.
"""

import math

import numpy as np

from ..export.camera import camera_to_world
from ..params import camera_params, dof_params

DEFAULT_SENSOR = 36.0   # Blender's DEFAULT_SENSOR_WIDTH: what a free view's lens is measured against


class ViewCamera:
    """The native view params (`params`, a dict for ViewportSession.set_view), the camera → world matrix and
    notes for the header (settings the view cannot honour)."""

    def __init__(self, params, matrix, notes=()):
        self.params, self.matrix, self.notes = params, matrix, tuple(notes)

    def key(self):
        """Equality key: a view change is a change of any of these."""
        return (tuple(sorted(self.params.items())), self.matrix.tobytes())


def camera_view_zoom(view_camera_zoom):
    """Blender's camera-view zoom factor of the viewplane (Cycles' "magic zoom formula", ×2 as every view)."""
    return 2.0 * 2.0 / (math.sqrt(2.0) + view_camera_zoom / 50.0) ** 2


def viewplane(width, height, sensor_fit="AUTO", sensor_width=DEFAULT_SENSOR, sensor_height=24.0, lens=50.0,
              ortho=False, ortho_scale=6.0, zoom=1.0, offset=(0.0, 0.0), shift=(0.0, 0.0)):
    """(left, right, bottom, top) of the view in camera-space units (tan of the angle for perspective, scene
    units for orthographic): the native camera's viewplane times its field-of-view scale (scene/camera.cpp)."""
    horizontal = sensor_fit == "HORIZONTAL" or (sensor_fit == "AUTO" and width > height)
    sensor = sensor_height if sensor_fit == "VERTICAL" else sensor_width
    if horizontal:
        aspect = width / height
        xaspect, yaspect = aspect, 1.0
    else:
        aspect = height / width
        xaspect, yaspect = 1.0, aspect
    if ortho:
        xaspect = xaspect * ortho_scale / (aspect * 2.0)
        yaspect = yaspect * ortho_scale / (aspect * 2.0)
        aspect = ortho_scale / 2.0
    dx = 2.0 * (aspect * shift[0] + offset[0] * xaspect * 2.0)
    dy = 2.0 * (aspect * shift[1] + offset[1] * yaspect * 2.0)
    scale = 1.0 if ortho else (0.5 * sensor / lens) / aspect
    return tuple(scale * v for v in (-xaspect * zoom + dx, xaspect * zoom + dx, -yaspect * zoom + dy,
                                     yaspect * zoom + dy))


def camera_frame(region_size, render_size, cam, zoom, offset):
    """The camera frame (x0, y0, x1, y1) in region pixels of the camera view (what Blender draws as the camera's
    border): the render's viewplane placed in the region's."""
    common = dict(sensor_fit=cam.sensor_fit, sensor_width=cam.sensor_width, sensor_height=cam.sensor_height,
                  lens=cam.lens, ortho=cam.type == 'ORTHO', ortho_scale=cam.ortho_scale,
                  shift=(cam.shift_x, cam.shift_y))
    w, h = region_size
    view = viewplane(w, h, zoom=zoom, offset=offset, **common)
    frame = viewplane(render_size[0], render_size[1], **common)
    fx = lambda v: (v - view[0]) / (view[1] - view[0]) * w   # noqa: E731
    fy = lambda v: (v - view[2]) / (view[3] - view[2]) * h   # noqa: E731
    return fx(frame[0]), fy(frame[2]), fx(frame[1]), fy(frame[3])


def _border(x0, y0, x1, y1, width, height):
    """A border window clamped to the view, in whole pixels (every pixel it covers, up to float rounding of its
    edges); None when it is empty."""
    eps = 1e-4
    bx0, by0 = max(0, int(math.floor(x0 + eps))), max(0, int(math.floor(y0 + eps)))
    bx1, by1 = min(width, int(math.ceil(x1 - eps))), min(height, int(math.ceil(y1 - eps)))
    return (bx0, by0, bx1, by1) if bx1 > bx0 and by1 > by0 else None


def view_camera(scene, depsgraph, space, rv3d, width, height, render_size):
    """The ViewCamera of one 3D view of `width` × `height` pixels; `render_size` is the render's frame (for the
    camera frame in camera view)."""
    notes = []
    matrix = None
    params = {"width": int(width), "height": int(height), "pixel_aspect_x": 1.0, "pixel_aspect_y": 1.0,
              "use_dof": False, "view_zoom": 2.0, "view_offset_x": 0.0, "view_offset_y": 0.0}
    crop = None
    camera = None
    if rv3d.view_perspective == 'CAMERA':
        camera = space.camera if space.use_local_camera and space.camera is not None else scene.camera
        if camera is not None and camera.type != 'CAMERA':
            camera = None
    if camera is not None:
        cam_eval = camera.evaluated_get(depsgraph)
        cam = cam_eval.data
        matrix = camera_to_world(cam_eval.matrix_world)   # what the camera view shows (its view matrix is this)
        params.update(camera_params(cam))
        params.update(dof_params(cam, cam_eval))
        zoom = camera_view_zoom(rv3d.view_camera_zoom)
        # The native camera's pan (Cycles' viewplane offset, dx = 4·offset·xaspect): Blender's camera view
        # moves the frame by 2·view_camera_offset of the unzoomed viewplane's extent, i.e. offset =
        # view_camera_offset (checked against Blender's own projection in tests/blender/gui_viewport.py).
        offset = (float(rv3d.view_camera_offset[0]), float(rv3d.view_camera_offset[1]))
        frame = camera_frame((width, height), render_size, cam, zoom, offset)
        if cam.type == 'PANO':
            # The viewport shows the part of the panorama inside the camera frame (Cycles' pano_viewplane).
            fw, fh = frame[2] - frame[0], frame[3] - frame[1]
            params.update(pano_left=-frame[0] / fw, pano_right=(width - frame[0]) / fw,
                          pano_bottom=-frame[1] / fh, pano_top=(height - frame[1]) / fh, view_zoom=1.0)
        else:
            params.update(view_zoom=zoom, view_offset_x=offset[0], view_offset_y=offset[1])
        render = scene.render
        if render.use_border:
            fw, fh = frame[2] - frame[0], frame[3] - frame[1]
            crop = _border(frame[0] + render.border_min_x * fw, frame[1] + render.border_min_y * fh,
                           frame[0] + render.border_max_x * fw, frame[1] + render.border_max_y * fh, width, height)
    elif rv3d.view_perspective == 'ORTHO' or not rv3d.is_perspective:
        far = 0.5 * space.clip_end
        params.update(camera_type="ORTHO", sensor_fit="AUTO", sensor_width=DEFAULT_SENSOR, lens=space.lens,
                      ortho_scale=rv3d.view_distance * DEFAULT_SENSOR / space.lens, clip_start=-far, clip_end=far,
                      shift_x=0.0, shift_y=0.0)
    else:
        params.update(camera_type="PERSP", sensor_fit="AUTO", sensor_width=DEFAULT_SENSOR, lens=space.lens,
                      clip_start=space.clip_start, clip_end=space.clip_end, shift_x=0.0, shift_y=0.0)
    if camera is None and space.use_render_border:
        crop = _border(space.render_border_min_x * width, space.render_border_min_y * height,
                       space.render_border_max_x * width, space.render_border_max_y * height, width, height)
    if crop is not None:
        params.update(crop_x0=crop[0], crop_y0=crop[1], crop_x1=crop[2], crop_y1=crop[3])
    if matrix is None:
        matrix = camera_to_world(rv3d.view_matrix.inverted())
    params = {k: (float(v) if isinstance(v, (float, np.floating)) else v) for k, v in params.items()}
    return ViewCamera(params, np.ascontiguousarray(matrix, np.float32), notes)
