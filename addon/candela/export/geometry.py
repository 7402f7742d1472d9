"""Mesh instances → the shared-mesh part of the schema (positions … instance_transform).

Meshes are deduplicated within one export by the evaluated data pointer plus the object's material slots, so 1,000
linked duplicates or particle instances become one mesh and 1,000 instances. The pointer is only meaningful during
this one depsgraph walk: never keep it.
"""

import numpy as np

from .common import ExportError
from .mesh import read_mesh


class GeometryTable:
    def __init__(self, materials):
        self.materials = materials
        self.meshes = []            # (MeshData, tri_material uint32)
        self._by_key = {}           # dedup key → mesh index, or -1 for objects without faces
        self.instance_mesh = []
        self.transforms = []

    def _key(self, ob, slots):
        # Modified objects get their own evaluated mesh, so their pointer is distinct; linked duplicates share one.
        # Non-mesh geometry (curves, text, metaballs) is converted per evaluated object.
        data_ptr = ob.data.as_pointer() if ob.type == 'MESH' and ob.data is not None else ob.as_pointer()
        return data_ptr, tuple(m.as_pointer() if m is not None else 0 for m in slots)

    def add(self, ob, matrix):
        """Add one instance of the evaluated object `ob` with object → world `matrix` ((4, 4) float32)."""
        # Blender keeps an infinite scale as a huge finite matrix: treat anything beyond 1e30 as not finite.
        if not np.isfinite(matrix).all() or np.abs(matrix).max() > 1e30:
            raise ExportError(f"object '{ob.name}' has a non-finite transform (NaN or Inf in its location, "
                              "rotation or scale)")
        slots = tuple(slot.material for slot in ob.material_slots)
        key = self._key(ob, slots)
        index = self._by_key.get(key)
        if index is None:
            index = self._by_key[key] = self._add_mesh(ob, slots)
        if index >= 0:
            self.instance_mesh.append(index)
            self.transforms.append(matrix)

    def _add_mesh(self, ob, slots):
        data = read_mesh(ob)
        if data is None:
            return -1
        rows = np.array([self.materials.row_of(m) for m in slots] or [self.materials.row_of(None)], np.uint32)
        # Out-of-range indices (slots removed after assignment) clamp to the last slot, as Blender draws them.
        tri_material = rows[np.clip(data.material_index, 0, len(rows) - 1)]
        self.meshes.append((data, tri_material))
        return len(self.meshes) - 1

    @property
    def triangle_count(self):
        return sum(len(d.triangles) for d, _ in self.meshes)

    def arrays(self):
        datas = [d for d, _ in self.meshes]
        vertex_counts = np.array([len(d.positions) for d in datas], np.int64)
        tri_counts = np.array([len(d.triangles) for d in datas], np.int64)
        vertex_base = np.concatenate([[0], np.cumsum(vertex_counts)[:-1]]).astype(np.uint32)
        # One mesh (the common big-mesh case) is handed over without copies.
        triangles = [d.triangles if vertex_base[i] == 0 else d.triangles + vertex_base[i] for i, d in enumerate(datas)]
        # Per-vertex normals when every mesh has them (the common case: 12 bytes a vertex instead of 36 a
        # triangle), else per-corner normals for all.
        if all(d.normals is None for d in datas):
            normals = {"vertex_normals": _joined([d.vertex_normals for d in datas], np.float32)}
        else:
            normals = {"normals": _joined([d.corner_normals() for d in datas], np.float32)}
        return {
            **normals,
            "positions": _joined([d.positions for d in datas], np.float32),
            "triangles": _joined(triangles, np.uint32),
            "tri_smooth": _joined([d.smooth for d in datas], np.uint8),
            "tri_material": _joined([m for _, m in self.meshes], np.uint32),
            "mesh_tri_start": np.concatenate([[0], np.cumsum(tri_counts)]).astype(np.uint32),
            "instance_mesh": np.array(self.instance_mesh, np.uint32),
            "instance_transform": np.array(self.transforms, np.float32).reshape(-1, 4, 4),
        }


def _joined(parts, dtype):
    """The parts concatenated as one C-contiguous array of `dtype` (no copy for a single part of that type)."""
    if len(parts) == 1:
        return np.ascontiguousarray(parts[0], dtype)
    return np.ascontiguousarray(np.concatenate(parts), dtype)
