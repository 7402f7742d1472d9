#include "scene/mesh_bvh_cache.h"

#include <xxhash.h>

#include <algorithm>
#include <vector>

#include "core/error.h"

namespace candela {

MeshBvhCache::MeshBvhCache(int threads) : m_device(std::make_shared<EmbreeDevice>(threads)) {}

MeshBvhCache::Key MeshBvhCache::key(const float* positions, size_t vertices, const uint32_t* triangles, size_t count,
                                    uint32_t vertex_base, uint32_t flags) {
    XXH3_state_t* state = XXH3_createState();
    if (!state) throw InternalError("xxhash: cannot allocate a hash state");
    XXH3_64bits_reset(state);
    XXH3_64bits_update(state, &flags, sizeof(flags));
    XXH3_64bits_update(state, positions, vertices * 3 * sizeof(float));
    // Indices relative to the mesh's first vertex, so the key does not depend on where the mesh sits in the
    // scene's shared arrays. Hashed in blocks to keep the copy small.
    constexpr size_t k_block = 4096;
    std::vector<uint32_t> local(3 * k_block);
    for (size_t t = 0; t < count; t += k_block) {
        const size_t n = std::min(k_block, count - t);
        for (size_t i = 0; i < 3 * n; ++i) local[i] = triangles[3 * t + i] - vertex_base;
        XXH3_64bits_update(state, local.data(), 3 * n * sizeof(uint32_t));
    }
    Key k;
    k.hash = XXH3_64bits_digest(state);
    XXH3_freeState(state);
    k.vertices = vertices;
    k.triangles = count;
    return k;
}

std::shared_ptr<EmbreeScene> MeshBvhCache::find(const Key& key) {
    const auto it = m_entries.find(key);
    if (it == m_entries.end()) return nullptr;
    it->second.used = true;
    ++m_reused;
    return it->second.scene;
}

void MeshBvhCache::insert(const Key& key, std::shared_ptr<EmbreeScene> scene) {
    Entry& e = m_entries[key];
    e.scene = std::move(scene);
    e.used = true;
    ++m_built;
}

void MeshBvhCache::end_build() {
    for (auto it = m_entries.begin(); it != m_entries.end();) {
        if (!it->second.used) {
            it = m_entries.erase(it);
        } else {
            it->second.used = false;
            ++it;
        }
    }
}

}  // namespace candela
