#include "integrators/irradiance_cache/ic_octree.h"

namespace candela {

IcOctree::IcOctree(const Vec3& center, float half_size)
    : m_min(center - Vec3(half_size)), m_half(half_size > 0.f ? half_size : 1.f) {
    m_nodes.emplace_back();
}

void IcOctree::insert(uint32_t index, const Vec3& p, float radius) {
    float side = 2.f * m_half;
    Vec3 lo = m_min;
    const bool inside =
        p.x >= lo.x && p.y >= lo.y && p.z >= lo.z && p.x <= lo.x + side && p.y <= lo.y + side && p.z <= lo.z + side;
    int32_t node = 0;
    m_nodes[0].subtree.add(p, radius);
    if (inside) {
        // Descend while the child (side/2) is still at least the sphere's diameter.
        for (int depth = 0; depth < k_max_depth && 0.5f * side >= 2.f * radius; ++depth) {
            const float half = 0.5f * side;
            const int c = (p.x >= lo.x + half ? 1 : 0) | (p.y >= lo.y + half ? 2 : 0) | (p.z >= lo.z + half ? 4 : 0);
            const Vec3 clo(lo.x + ((c & 1) ? half : 0.f), lo.y + ((c & 2) ? half : 0.f), lo.z + ((c & 4) ? half : 0.f));
            int32_t child = m_nodes[size_t(node)].child[c];
            if (child < 0) {
                child = int32_t(m_nodes.size());
                m_nodes.emplace_back();  // may move m_nodes: index again below
                m_nodes[size_t(node)].child[c] = child;
            }
            node = child;
            m_nodes[size_t(node)].subtree.add(p, radius);
            lo = clo;
            side = half;
        }
    }
    Node& nd = m_nodes[size_t(node)];
    nd.records.push_back(index);
    nd.own.add(p, radius);
}

}  // namespace candela
