// Object-space BVHs of meshes kept from one scene build to the next (the 3D viewport's scene updates): a
// scene built with a cache instances every mesh (none is flattened into world space), looks each mesh up by a
// hash of what its BVH depends on (its vertex positions, its triangles and the Embree filter settings) and
// builds only the meshes it does not find. Moving objects, editing materials or lights then rebuilds only the
// top-level BVH over the instances; an edited mesh gets a new key and is built again.
//
// The key is XXH3-64 (xxhash) of the mesh's bytes; the vertex and triangle counts are compared as well, so a
// wrong reuse needs a 64-bit collision between two meshes of the same size. Entries not used by the latest
// build are dropped after it (end_build), so memory follows the scene. The cache and the scenes built with it
// share one Embree device (a BVH can only be instanced by scenes of its own device); a scene keeps the BVHs it
// uses alive on its own, so dropping an entry never pulls one out from under a render.
//
// Not thread-safe: one viewport session's worker builds its scenes one after the other.
#pragma once

#include <cstdint>
#include <memory>
#include <unordered_map>

#include "scene/embree_device.h"

namespace candela {

class MeshBvhCache {
public:
    explicit MeshBvhCache(int threads);
    MeshBvhCache(const MeshBvhCache&) = delete;
    MeshBvhCache& operator=(const MeshBvhCache&) = delete;

    const std::shared_ptr<EmbreeDevice>& device() const { return m_device; }

    struct Key {
        uint64_t hash = 0;
        uint64_t vertices = 0, triangles = 0;
        bool operator==(const Key& o) const {
            return hash == o.hash && vertices == o.vertices && triangles == o.triangles;
        }
    };
    /// The key of a mesh: its vertices (3 floats each), triangles (3 local indices each) and `flags` (the
    /// Embree settings baked into its BVH: filter functions, scene flags).
    static Key key(const float* positions, size_t vertices, const uint32_t* triangles, size_t count,
                   uint32_t vertex_base, uint32_t flags);

    /// The cached BVH of the mesh with this key (marked as used by the current build), or null.
    std::shared_ptr<EmbreeScene> find(const Key& key);
    void insert(const Key& key, std::shared_ptr<EmbreeScene> scene);
    /// After a build: drops the entries it did not use.
    void end_build();

    size_t size() const { return m_entries.size(); }
    /// BVHs built (inserted) and reused (found) since the cache was made, for tests and statistics.
    size_t built() const { return m_built; }
    size_t reused() const { return m_reused; }

private:
    struct KeyHash {
        size_t operator()(const Key& k) const { return size_t(k.hash); }
    };
    struct Entry {
        std::shared_ptr<EmbreeScene> scene;
        bool used = false;
    };
    std::shared_ptr<EmbreeDevice> m_device;  // declared first: destroyed after the BVHs
    std::unordered_map<Key, Entry, KeyHash> m_entries;
    size_t m_built = 0, m_reused = 0;
};

}  // namespace candela
