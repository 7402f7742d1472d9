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
    uvs: np.ndarray = None      # (T, 3, 2) float32 render UV map per corner (textured materials only)
    tangents: np.ndarray = None  # (T, 3, 4) float32 UV tangent xyz + bitangent sign per corner (normal maps only)
    texspace: np.ndarray = None  # (6,) float32 texture-space location and size (Generated coordinates)


def _render_uv_layer(me):
    layers = me.uv_layers
    for layer in layers:
        if layer.active_render:
            return layer
    return layers.active


def _tangents(me, ob, layer, loops, uvs, positions, triangles, warnings):
    """Per-corner MikkTSpace tangents and bitangent signs (Blender's, as Cycles uses them); for meshes whose
    faces MikkTSpace cannot take (n-gons) one tangent per triangle from its UV gradient, with a warning."""
    try:
        me.calc_tangents(uvmap=layer.name)
        t = np.empty((len(me.loops), 3), np.float32)
        me.loops.foreach_get("tangent", t.ravel())
        sign = np.empty(len(me.loops), np.float32)
        me.loops.foreach_get("bitangent_sign", sign)
        return np.concatenate([t[loops], sign[loops][..., None]], axis=2).astype(np.float32)
    except RuntimeError:
        warnings.add(f"Candela: object '{ob.name}': tangents for its normal map are computed per triangle (the mesh "
                     "has faces with more than four corners)")
    p = positions[triangles]                       # (T, 3, 3)
    e1, e2 = p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]
    d1, d2 = uvs[:, 1] - uvs[:, 0], uvs[:, 2] - uvs[:, 0]
    det = d1[:, 0] * d2[:, 1] - d2[:, 0] * d1[:, 1]
    safe = np.where(np.abs(det) > 1e-20, det, 1.0)
    tangent = (e1 * d2[:, 1:2] - e2 * d1[:, 1:2]) / safe[:, None]
    bitangent = (e2 * d1[:, 0:1] - e1 * d2[:, 0:1]) / safe[:, None]
    normal = np.cross(e1, e2)
    sign = np.where(np.einsum("ij,ij->i", np.cross(normal, tangent), bitangent) < 0.0, -1.0, 1.0)
    out = np.zeros((len(triangles), 3, 4), np.float32)
    out[:, :, :3] = np.where(np.abs(det)[:, None] > 1e-20, tangent, 0.0)[:, None, :]
    out[:, :, 3] = sign[:, None]
    return out


def read_mesh(ob, uses=frozenset(), warnings=None):
    """Triangulated, modifier-applied geometry of the evaluated object `ob`, or None when it has no faces.
    `uses` ("UV", "TANGENT", "GENERATED") names what its textured materials read."""
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
        data = MeshData(positions, triangles.astype(np.uint32), normals, smooth.astype(np.uint8), material_index)
        layer = _render_uv_layer(me) if uses & {"UV", "TANGENT"} else None
        if layer is not None:
            loops = np.empty((nt, 3), np.int32)
            tris.foreach_get("loops", loops.ravel())
            uv = np.empty((len(me.loops), 2), np.float32)
            layer.data.foreach_get("uv", uv.ravel())
            data.uvs = np.ascontiguousarray(uv[loops])
            if "TANGENT" in uses:
                data.tangents = _tangents(me, ob, layer, loops, data.uvs, positions, triangles, warnings)
        if "GENERATED" in uses:
            data.texspace = np.array([*me.texspace_location, *me.texspace_size], np.float32)
        return data
    finally:
        ob.to_mesh_clear()
