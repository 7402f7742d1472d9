"""Mesh instances → the shared-mesh part of the schema (positions … instance_transform).

Meshes are deduplicated within one export by the evaluated data pointer plus the object's material slots, so 1,000
linked duplicates or particle instances become one mesh and 1,000 instances. The pointer is only meaningful during
this one depsgraph walk: never keep it.
"""

import numpy as np

from .common import ExportError
from .mesh import read_mesh
from .motion import object_steps


class GeometryTable:
    def __init__(self, materials, read=read_mesh):
        """`read(ob, uses, warnings)` reads one evaluated object's triangles (export/mesh.py read_mesh; the
        viewport passes its cache's reader)."""
        self.materials = materials
        self.read = read
        self.meshes = []            # (MeshData, tri_material uint32)
        self._by_key = {}           # dedup key → mesh index, or -1 for objects without faces
        self.instance_mesh = []
        self.transforms = []
        self.flags = []             # per instance: `instance_flags` bits (ray visibility, holdout)
        self.pass_indices = []      # per instance: the object's pass index (IndexOB)
        self.colors = []            # per instance: Object Info > Color and Alpha (the object's colour)
        self.randoms = []           # per instance: Object Info > Random
        self.terminators = []       # per instance: Cycles' shadow terminator geometry offset
        self.mesh_objects = []      # per mesh: names of the objects drawing it (for messages)
        self.instance_objects = []  # per instance: its object's name
        self.instance_keys = []     # per instance: export/motion.py instance_key (motion blur finds it again)
        self.motion_steps = []      # per instance: its motion samples (export/motion.py object_steps; 0 = still)

    def _key(self, ob, slots):
        # Modified objects get their own evaluated mesh, so their pointer is distinct; linked duplicates share one.
        # Non-mesh geometry (curves, text, metaballs) is converted per evaluated object.
        data_ptr = ob.data.as_pointer() if ob.type == 'MESH' and ob.data is not None else ob.as_pointer()
        return data_ptr, tuple(m.as_pointer() if m is not None else 0 for m in slots)

    def add(self, ob, matrix, flags=0x1F, pass_index=0, random=None, motion_key=None):
        """Add one instance of the evaluated object `ob` with object → world `matrix` ((4, 4) float32), its
        `instance_flags` bits (default: visible to every ray, no holdout), pass index and Object Info > Random
        (default: Cycles' hash of the object's name); `motion_key`: what identifies the instance at other
        subframes (export/motion.py instance_key), kept for motion blur."""
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
            self.flags.append(flags)
            self.pass_indices.append(pass_index)
            self.colors.append(tuple(getattr(ob, "color", (1.0, 1.0, 1.0, 1.0))))
            self.randoms.append(object_random(ob.name) if random is None else random)
            cycles = getattr(ob, "cycles", None)
            self.terminators.append(float(getattr(cycles, "shadow_terminator_geometry_offset", 0.1)))
            self.instance_objects.append(ob.name)
            self.instance_keys.append(motion_key)
            self.motion_steps.append(object_steps(ob))
            if len(self.mesh_objects[index]) < 4:
                self.mesh_objects[index].append(ob.name)

    def _add_mesh(self, ob, slots):
        rows = np.array([self.materials.row_of(m) for m in slots] or [self.materials.row_of(None)], np.uint32)
        uses = frozenset().union(*(self.materials.uses(int(r)) for r in rows))
        data = self.read(ob, uses, self.materials.warnings)
        if data is None:
            return -1
        # Out-of-range indices (slots removed after assignment) clamp to the last slot, as Blender draws them.
        tri_material = rows[np.clip(data.material_index, 0, len(rows) - 1)]
        self.meshes.append((data, tri_material))
        self.mesh_objects.append([])
        return len(self.meshes) - 1

    def names(self):
        """How messages name mesh i and instance i: {"mesh": [...], "instance": [...]} (see name_objects)."""
        def mesh_label(objects):
            if len(objects) == 1:
                return f"object '{objects[0]}'"
            return f"the mesh of objects {', '.join(repr(o) for o in objects[:3])}{' …' if len(objects) > 3 else ''}"
        return {"mesh": [mesh_label(o) for o in self.mesh_objects],
                "instance": [f"object '{o}'" for o in self.instance_objects]}

    @property
    def triangle_count(self):
        return sum(len(d.triangles) for d, _ in self.meshes)

    def arrays(self):
        if not self.meshes:   # a world-only scene: no triangles at all
            return {"positions": np.zeros((0, 3), np.float32), "triangles": np.zeros((0, 3), np.uint32),
                    "tri_material": np.zeros(0, np.uint32), "mesh_tri_start": np.zeros(1, np.uint32),
                    "instance_mesh": np.zeros(0, np.uint32), "instance_transform": np.zeros((0, 4, 4), np.float32)}
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
        optional = {}
        # Texture attributes only when some textured material reads them; other meshes' rows stay 0.
        if any(d.uvs is not None for d in datas):
            optional["uvs"] = np.concatenate([d.uvs if d.uvs is not None else np.zeros((len(d.triangles), 3, 2), np.float32)
                                              for d in datas])
        if any(d.tangents is not None for d in datas):
            optional["tangents"] = np.concatenate(
                [d.tangents if d.tangents is not None else np.zeros((len(d.triangles), 3, 4), np.float32) for d in datas])
        names = self.materials.tables.attribute_names
        if names and any(d.attributes for d in datas):
            per_mesh = []
            for d in datas:
                block = np.zeros((len(d.triangles), 3, 4 * len(names)), np.float32)
                for slot, name in enumerate(names):
                    if d.attributes and name in d.attributes:
                        block[..., 4 * slot:4 * slot + 4] = d.attributes[name]
                per_mesh.append(block)
            optional["corner_attributes"] = _joined(per_mesh, np.float32)
        if any(d.texspace is not None for d in datas):
            unit = np.array([0, 0, 0, 1, 1, 1], np.float32)
            optional["mesh_texspace"] = np.stack([d.texspace if d.texspace is not None else unit for d in datas])
        return {
            **optional,
            **normals,
            "positions": _joined([d.positions for d in datas], np.float32),
            "triangles": _joined(triangles, np.uint32),
            "tri_smooth": _joined([d.smooth for d in datas], np.uint8),
            "tri_material": _joined([m for _, m in self.meshes], np.uint32),
            "mesh_tri_start": np.concatenate([[0], np.cumsum(tri_counts)]).astype(np.uint32),
            "instance_mesh": np.array(self.instance_mesh, np.uint32),
            "instance_transform": np.array(self.transforms, np.float32).reshape(-1, 4, 4),
            "instance_flags": np.array(self.flags, np.uint8),
            "instance_pass_index": np.array(self.pass_indices, np.uint32),
            "instance_color": np.array(self.colors, np.float32).reshape(-1, 4),
            "instance_random": np.array(self.randoms, np.float32),
            "instance_terminator": np.clip(np.array(self.terminators, np.float32), 0.0, 1.0),
        }


def _rot(x, k):
    return ((x << k) | (x >> (32 - k))) & 0xFFFFFFFF


def hash_uint2(kx, ky):
    """Bob Jenkins' lookup3 final mix of two words (public domain; the hash Cycles' textures use too)."""
    a = b = c = (0xdeadbeef + (2 << 2) + 13) & 0xFFFFFFFF
    b = (b + ky) & 0xFFFFFFFF
    a = (a + kx) & 0xFFFFFFFF
    c ^= b; c = (c - _rot(b, 14)) & 0xFFFFFFFF
    a ^= c; a = (a - _rot(c, 11)) & 0xFFFFFFFF
    b ^= a; b = (b - _rot(a, 25)) & 0xFFFFFFFF
    c ^= b; c = (c - _rot(b, 16)) & 0xFFFFFFFF
    a ^= c; a = (a - _rot(c, 4)) & 0xFFFFFFFF
    b ^= a; b = (b - _rot(a, 14)) & 0xFFFFFFFF
    c ^= b; c = (c - _rot(b, 24)) & 0xFFFFFFFF
    return c


def string_hash(text):
    """The 37-multiplier string hash (h = 37·h + byte) Cycles names objects' random numbers by."""
    h = 0
    for byte in text.encode("utf-8"):
        h = (h * 37 + byte) & 0xFFFFFFFF
    return h


def object_random(name):
    """Object Info > Random of an object that is not an instance: a hash of its name mapped to [0, 1], as Cycles 3.4
    (an instance's comes from Blender's per-instance random_id instead)."""
    return random_from_id(hash_uint2(string_hash(name), 0))


def random_from_id(random_id):
    return float(np.float32(random_id & 0xFFFFFFFF) * np.float32(1.0 / 0xFFFFFFFF))


def _joined(parts, dtype):
    """The parts concatenated as one C-contiguous array of `dtype` (no copy for a single part of that type)."""
    if len(parts) == 1:
        return np.ascontiguousarray(parts[0], dtype)
    return np.ascontiguousarray(np.concatenate(parts), dtype)
