"""One evaluated object → triangle arrays, through public RNA + foreach_get only (no per-vertex Python).

Raw struct reads break with every Blender mesh-layout change (3.4, 3.5, 3.6); foreach_get does not.

Speed (`make bench` times 1 M triangles): foreach_get is fast on the mesh's own arrays (vertex co, loop
vertex_index, polygon loop_start/loop_total/use_smooth/normals, vertex normals) but slow on `loop_triangles` (a
getter per item: ~0.2 s per property per million triangles). So meshes made of triangles and quads are
triangulated here with numpy exactly as the evaluated mesh's loop triangles are (a quad splits along its 0–2
diagonal, or along 1–3 when it folds over that diagonal seen along its normal; tests/blender/test_export.py
compares with `loop_triangles` on random meshes); meshes with n-gons use `loop_triangles`. Split normals are computed only when they can differ from
the vertex normals (auto smooth or custom normals); otherwise `calc_normals_split` would give smooth corners
their vertex normals, so the vertex normals are sent as they are (`vertex_normals`, 12 bytes a vertex instead of
36 a triangle) and flat faces use their geometric normal in the renderer anyway.
"""

from dataclasses import dataclass

import numpy as np

from .common import ExportError


@dataclass
class MeshData:
    positions: np.ndarray       # (V, 3) float32, object space
    triangles: np.ndarray       # (T, 3) uint32, local vertex indices
    normals: np.ndarray         # (T, 3, 3) float32 split normals per corner, or None: use vertex_normals
    smooth: np.ndarray          # (T,) uint8
    material_index: np.ndarray  # (T,) int32 slot index
    uvs: np.ndarray = None      # (T, 3, 2) float32 render UV map per corner (textured materials only)
    tangents: np.ndarray = None  # (T, 3, 4) float32 UV tangent xyz + bitangent sign per corner (normal maps only)
    texspace: np.ndarray = None  # (6,) float32 texture-space location and size (Generated coordinates)
    vertex_normals: np.ndarray = None   # (V, 3) float32, when the split normals are the vertex normals
    attributes: dict = None     # name → (T, 3, 4) float32 per-corner values of the attributes its materials read

    def corner_normals(self):
        """(T, 3, 3) per-corner normals whichever way they were read."""
        return self.normals if self.normals is not None else np.take(self.vertex_normals, self.triangles, axis=0)


def _get(collection, prop, n, dtype, width=1):
    out = np.empty(n * width, dtype)
    collection.foreach_get(prop, out)
    return out.reshape(n, width) if width > 1 else out


def _triangulate_tris_and_quads(me, positions, loop_vertex):
    """(triangles (T, 3) vertex indices, loops (T, 3) corner indices, polygon of each triangle (T,)) for a
    mesh whose faces all have 3 or 4 corners, in the order and with the diagonals of Blender's loop triangles;
    None if it has n-gons."""
    npoly = len(me.polygons)
    start = _get(me.polygons, "loop_start", npoly, np.int32)
    total = _get(me.polygons, "loop_total", npoly, np.int32)
    if npoly == 0 or total.min() < 3 or total.max() > 4:
        return None
    quad = total == 4
    all_quads = bool(quad.all())
    q = start if all_quads else start[quad]
    i0, i1, i2, i3 = (loop_vertex[q + c] for c in range(4))
    # Blender splits a quad along 1–3 instead of 0–2 when, seen along the face normal n, corner 3 is not on the
    # left of the 0→2 diagonal or corner 1 not on its right: with t = (p2 − p0) × n, flip when
    # p3·t ≥ p0·t or p1·t ≤ p0·t (BLI `is_quad_flip_v3_first_third_fast_with_normal`, which the evaluated
    # mesh's loop triangles — what Cycles reads — use; folded quads are the only ones it changes).
    p0, p1, p2, p3 = (np.take(positions, i, axis=0) for i in (i0, i1, i2, i3))  # np.take: 2× fancy indexing
    normal = _get(me.polygon_normals, "vector", npoly, np.float32, 3)
    tangent = np.cross(p2 - p0, normal if all_quads else normal[quad])
    dot = lambda a, b: np.einsum("ij,ij->i", a, b)  # noqa: E731
    d0 = dot(p0, tangent)
    flip = (dot(p3, tangent) >= d0) | (dot(p1, tangent) <= d0)
    # Straight split (0,1,2), (0,2,3); folded split (0,1,3), (1,2,3) — Blender's order for each. Corner k of a
    # triangle is written as the offset (0–3) of its loop within the quad, so vertices and loops share it.
    k = np.empty((len(q), 2, 3), np.int32)
    k[:, 0, 0], k[:, 0, 1], k[:, 0, 2] = 0, 1, np.where(flip, 3, 2)
    k[:, 1, 0], k[:, 1, 1], k[:, 1, 2] = np.where(flip, 1, 0), 2, 3
    quad_loops = (q[:, None, None] + k).reshape(-1, 3)
    if all_quads:
        return loop_vertex[quad_loops], quad_loops, np.repeat(np.arange(npoly, dtype=np.int32), 2)
    per_poly = np.where(quad, 2, 1)
    poly_of_tri = np.repeat(np.arange(npoly, dtype=np.int32), per_poly)
    first = np.concatenate([[0], np.cumsum(per_poly)[:-1]])   # each polygon's first triangle
    loops = np.empty((len(poly_of_tri), 3), np.int32)
    t = start[~quad]
    loops[first[~quad]] = t[:, None] + np.arange(3, dtype=np.int32)
    fq = first[quad]
    loops[fq], loops[fq + 1] = quad_loops[0::2], quad_loops[1::2]
    return loop_vertex[loops], loops, poly_of_tri


def _finite(normals):
    """Degenerate faces can give non-finite normals: zero means "use the geometric normal" to the renderer."""
    if not np.isfinite(normals).all():
        normals = np.where(np.isfinite(normals), normals, np.float32(0.0))
    return normals


def _render_uv_layer(me):
    layers = me.uv_layers
    for layer in layers:
        if layer.active_render:
            return layer
    return layers.active


def _attribute(me, name, loops, triangles, poly_of_tri):
    """(T, 3, 4) per-corner values of mesh attribute `name`: a UV map (u, v, 0, 1), a colour attribute (linear
    RGBA), a float (v, v, v, 1) or a vector attribute (x, y, z, 1), on any domain; 0 where the mesh has none (Cycles
    reads a missing attribute as 0)."""
    from .shader_nodes import RENDER_COLOR
    n = len(loops)
    out = np.zeros((n, 3, 4), np.float32)
    nloops = len(me.loops)
    if name == RENDER_COLOR:
        colors = me.color_attributes
        index = getattr(colors, "render_color_index", -1)
        if not len(colors):
            return out
        name = colors[index].name if 0 <= index < len(colors) else colors[0].name
    if name in me.uv_layers:
        uv = _get(me.uv_layers[name].data, "uv", nloops, np.float32, 2)
        out[..., :2] = np.take(uv, loops, axis=0)
        out[..., 3] = 1.0
        return out
    attr = me.attributes.get(name)
    if attr is None:
        return out
    count = len(attr.data)
    if attr.data_type in ("FLOAT_COLOR", "BYTE_COLOR"):
        values = _get(attr.data, "color", count, np.float32, 4)
    elif attr.data_type in ("FLOAT_VECTOR", "FLOAT2"):
        width = 3 if attr.data_type == "FLOAT_VECTOR" else 2
        values = np.zeros((count, 4), np.float32)
        values[:, :width] = _get(attr.data, "vector", count, np.float32, width)
        values[:, 3] = 1.0
    elif attr.data_type in ("FLOAT", "INT", "BOOLEAN", "INT8"):
        prop = "value"
        raw = _get(attr.data, prop, count, np.float32 if attr.data_type == "FLOAT" else
                   (bool if attr.data_type == "BOOLEAN" else np.int32))
        values = np.ones((count, 4), np.float32)
        values[:, :3] = raw.astype(np.float32)[:, None]
    else:
        return out
    values = np.nan_to_num(values, nan=0.0, posinf=0.0, neginf=0.0)
    if attr.domain == "POINT":
        out[:] = np.take(values, triangles.astype(np.int64), axis=0)
    elif attr.domain == "CORNER":
        out[:] = np.take(values, loops, axis=0)
    elif attr.domain == "FACE":
        out[:] = np.take(values, poly_of_tri, axis=0)[:, None, :]
    return out


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


def _evaluated_mesh(ob, need_copy=False):
    """(mesh, owned): an unmodified mesh object's own evaluated mesh when it can be read as is (Cycles reads it too),
    else a temporary copy from to_mesh() (modifiers, curves, text, edit mode, auto smooth) the caller clears."""
    if (not need_copy and ob.type == 'MESH' and ob.data is not None and len(ob.modifiers) == 0
            and not ob.data.is_editmode and not ob.data.use_auto_smooth):
        return ob.data, False
    return ob.to_mesh(), True


def read_mesh(ob, uses=frozenset(), warnings=None):
    """Triangulated, modifier-applied geometry of the evaluated object `ob`, or None when it has no faces.
    `uses` ("UV", "TANGENT", "GENERATED") names what its textured materials read."""
    me, owned = _evaluated_mesh(ob, need_copy="TANGENT" in uses)
    try:
        if me is None or len(me.polygons) == 0:
            return None
        nv, nloops, npoly = len(me.vertices), len(me.loops), len(me.polygons)
        positions = _get(me.vertices, "co", nv, np.float32, 3)
        if not np.isfinite(positions).all():
            bad = ~np.isfinite(positions).all(axis=1)
            raise ExportError(f"object '{ob.name}': {int(bad.sum())} vertices have non-finite (NaN or Inf) "
                              f"coordinates, the first is vertex {int(np.argmax(bad))}")
        loop_vertex = _get(me.loops, "vertex_index", nloops, np.int32)
        fast = _triangulate_tris_and_quads(me, positions, loop_vertex)
        if fast is not None:
            triangles, loops, poly_of_tri = fast
        else:
            me.calc_loop_triangles()
            nt = len(me.loop_triangles)
            if nt == 0:
                return None
            loops = _get(me.loop_triangles, "loops", nt, np.int32, 3)
            poly_of_tri = _get(me.loop_triangles, "polygon_index", nt, np.int32)
            triangles = loop_vertex[loops]
        smooth = _get(me.polygons, "use_smooth", npoly, bool)[poly_of_tri]
        if len(me.materials) > 1:
            material_index = _get(me.polygons, "material_index", npoly, np.int32)[poly_of_tri]
        else:   # one slot or none: every index draws slot 0 (geometry.py clamps), no need to read them
            material_index = np.zeros(len(poly_of_tri), np.int32)
        triangles = triangles.view(np.uint32)
        if me.use_auto_smooth or me.has_custom_normals:
            # Split normals honour auto smooth, custom normals and sharp edges the way Cycles sees them.
            me.calc_normals_split()
            corner = _get(me.loops, "normal", nloops, np.float32, 3)
            data = MeshData(positions, triangles, np.take(_finite(corner), loops, axis=0), smooth.view(np.uint8),
                            material_index)
        else:
            # Otherwise smooth corners have the vertex normals (flat faces use their geometric normal natively).
            vertex_normals = _finite(_get(me.vertex_normals, "vector", nv, np.float32, 3))
            data = MeshData(positions, triangles, None, smooth.view(np.uint8), material_index,
                            vertex_normals=vertex_normals)
        # Texture attributes, only for meshes whose materials read them.
        layer = _render_uv_layer(me) if uses & {"UV", "TANGENT"} else None
        if layer is not None:
            uv = _get(layer.data, "uv", nloops, np.float32, 2)
            data.uvs = np.ascontiguousarray(np.take(uv, loops, axis=0))
            if "TANGENT" in uses:
                data.tangents = _tangents(me, ob, layer, loops, data.uvs, positions, triangles, warnings)
        if "GENERATED" in uses:
            data.texspace = np.array([*me.texspace_location, *me.texspace_size], np.float32)
        names = [u[1] for u in uses if isinstance(u, tuple) and u[0] == "ATTRIBUTE"]
        if names:
            data.attributes = {name: _attribute(me, name, loops, triangles, poly_of_tri) for name in names}
        return data
    finally:
        if owned:
            ob.to_mesh_clear()
