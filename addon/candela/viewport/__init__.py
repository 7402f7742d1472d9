"""Rendered shading in the 3D viewport (render.py), with the view's own camera (view_camera.py), scene updates
from depsgraph.updates (scene_sync.py) and drawing through Blender's gpu module (display.py)."""

from .render import ViewportRender, close_all, live_count

__all__ = ["ViewportRender", "close_all", "live_count"]
