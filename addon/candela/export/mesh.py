"""One evaluated object → triangle arrays, through public RNA + foreach_get only (no per-vertex Python).

Raw struct reads break with every Blender mesh-layout change (3.4, 3.5, 3.6); foreach_get does not.
"""

from dataclasses import dataclass

import numpy as np

from .common import ExportError


@dataclass
class MeshData:
    positions: np.ndarray       # (V, 3) float32, object space
    triangles: np.ndarray       # (T, 3) uint32, local vertex indices
    normals: np.ndarray         # (T, 3, 3) float32 split normals per corner
    smooth: np.ndarray          # (T,) uint8
    material_index: np.ndarray  # (T,) int32 slot index


def read_mesh(ob):
    """Triangulated, modifier-applied geometry of the evaluated object `ob`, or None when it has no faces."""
    me = ob.to_mesh()
    try:
        if me is None:
            return None
        me.calc_loop_triangles()
        nt, nv = len(me.loop_triangles), len(me.vertices)
        if nt == 0:
            return None
        # Split normals honour auto smooth, custom normals and sharp edges the way Cycles sees them.
        me.calc_normals_split()
        tris = me.loop_triangles
        positions = np.empty((nv, 3), np.float32)
        me.vertices.foreach_get("co", positions.ravel())
        bad = ~np.isfinite(positions).all(axis=1)
        if bad.any():
            raise ExportError(f"object '{ob.name}': {int(bad.sum())} vertices have non-finite (NaN or Inf) "
                              f"coordinates, the first is vertex {int(np.argmax(bad))}")
        triangles = np.empty((nt, 3), np.int32)
        tris.foreach_get("vertices", triangles.ravel())
        normals = np.empty((nt, 3, 3), np.float32)
        tris.foreach_get("split_normals", normals.ravel())
        # Degenerate faces can give non-finite normals: zero means "use the geometric normal" to the renderer.
        normals[~np.isfinite(normals)] = 0.0
        smooth = np.empty(nt, bool)
        tris.foreach_get("use_smooth", smooth)
        material_index = np.empty(nt, np.int32)
        tris.foreach_get("material_index", material_index)
        return MeshData(positions, triangles.astype(np.uint32), normals, smooth.astype(np.uint8), material_index)
    finally:
        ob.to_mesh_clear()
