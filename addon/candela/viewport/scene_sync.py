"""What a viewport update must re-export, from `depsgraph.updates` (Cycles' BlenderSync::sync_recalc rules):

- an object whose geometry changed (edit mode, modifiers, its mesh): its mesh is read again;
- any other change to objects (transform, visibility of its shading), materials, lights, the world, images, node
  trees or collections: the scene is exported again, but every mesh that did not change comes from the
  MeshCache (no Blender mesh reads) and keeps its BVH on the native side (scene/mesh_bvh_cache.h), and every
  image that did not change comes from the ImageCache (no pixel reads), so a transform-only edit rebuilds
  nothing but the top-level BVH;
- the Scene alone (render settings, colour management, frame, selection): no export; the render settings are
  compared with the last ones and only a real change restarts the render (update_settings). Colour management is
  applied when drawing and never restarts. A Scene update that changes which objects are visible (hiding an
  object, excluding a collection) is caught by the instance signature.
"""

import bpy

from ..export.common import Warnings
from ..export.mesh import read_mesh

# Datablocks whose change needs a new export (besides objects, handled by their flags).
EXPORT_TYPES = (bpy.types.Material, bpy.types.Light, bpy.types.World, bpy.types.Image, bpy.types.NodeTree,
                bpy.types.Texture, bpy.types.Collection)
GEOMETRY_TYPES = (bpy.types.Mesh, bpy.types.Curve, bpy.types.MetaBall)


class Changes:
    """The outcome of classify(): export (bool), the names whose meshes must be read again, the images whose
    pixels must be read again, scene (bool)."""

    def __init__(self):
        self.export = False
        self.geometry = set()   # object and datablock names
        self.images = set()     # image names
        self.scene = False

    def __repr__(self):
        return f"Changes(export={self.export}, geometry={sorted(self.geometry)}, scene={self.scene})"


def classify(updates):
    """Changes from an iterable of DepsgraphUpdate (or stand-ins with .id and the three is_updated_* flags)."""
    changes = Changes()
    for update in updates:
        block = update.id
        if isinstance(block, bpy.types.Object):
            if update.is_updated_geometry:
                changes.geometry.add(block.name)
                changes.export = True
            elif update.is_updated_transform or update.is_updated_shading:
                changes.export = True
            # No flag: selection or other base flags; nothing Candela draws depends on them.
        elif isinstance(block, GEOMETRY_TYPES):
            changes.geometry.add(block.name)
            changes.export = True
        elif isinstance(block, EXPORT_TYPES):
            changes.export = True
            if isinstance(block, bpy.types.Image):
                changes.images.add(block.name)
        elif isinstance(block, bpy.types.Scene):
            changes.scene = True
    return changes


def instance_signature(depsgraph):
    """Which objects the scene shows (names, in depsgraph order): a Scene update that changes it (an object or
    collection hidden) needs a new export."""
    out = []
    for inst in depsgraph.object_instances:
        ob = inst.object
        if ob.type in {'MESH', 'CURVE', 'SURFACE', 'FONT', 'META', 'LIGHT'}:
            out.append((ob.name, inst.is_instance, inst.show_self))
    return tuple(out)


class MeshCache:
    """Triangle data of the evaluated objects (export/mesh.py MeshData) kept between viewport exports.

    Keyed by the object's name, its evaluated data block (pointer, valid while its geometry is not re-evaluated)
    and what its materials need from it (UVs, tangents, texture space), so a changed material that needs UVs
    reads the mesh again. invalidate() drops the entries of changed geometry; entries the latest export did not
    use are dropped after it."""

    def __init__(self):
        self._entries = {}   # key -> (MeshData or None, warnings the read produced, data name)
        self._used = set()
        self.reads = 0       # meshes read from Blender (tests count them)

    @staticmethod
    def _key(ob, uses):
        data = ob.data if ob.type == 'MESH' and ob.data is not None else None
        pointer = data.as_pointer() if data is not None else ob.as_pointer()
        return ob.name, pointer, frozenset(uses)

    def read(self, ob, uses, warnings):
        """export/geometry.py's mesh reader, through the cache."""
        key = self._key(ob, uses)
        self._used.add(key)
        entry = self._entries.get(key)
        if entry is None:
            recorded = Warnings()
            data = read_mesh(ob, uses, recorded)
            self.reads += 1
            entry = self._entries[key] = (data, list(recorded.messages),
                                          ob.data.name if getattr(ob, "data", None) is not None else "")
        if warnings is not None:
            for message in entry[1]:
                warnings.add(message)
        return entry[0]

    def invalidate(self, names):
        if not names:
            return
        for key in [k for k, (_, _, data_name) in self._entries.items() if k[0] in names or data_name in names]:
            del self._entries[key]

    def end_export(self):
        for key in [k for k in self._entries if k not in self._used]:
            del self._entries[key]
        self._used.clear()

    def clear(self):
        self._entries.clear()
        self._used.clear()


class ImageCache(dict):
    """Loaded image texels kept between viewport exports (export/shader_tables.py reads an image only when its
    key is missing); images updated in Blender are dropped by invalidate(), unused ones after each export."""

    def __init__(self):
        super().__init__()
        self._used = set()

    def get(self, key, default=None):
        self._used.add(key)
        return super().get(key, default)

    def __setitem__(self, key, value):
        self._used.add(key)
        super().__setitem__(key, value)

    def invalidate(self, names):
        for key in [k for k in self if k[0] in names]:
            del self[key]

    def end_export(self):
        for key in [k for k in self if k not in self._used]:
            del self[key]
        self._used.clear()
