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
        for (int depth = 0; depth < k_max_depth && 0.5f * side >= k_loose * 2.f * radius; ++depth) {
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
    nd.own.add(p, radius);
    if (nd.last < 0 || m_blocks[size_t(nd.last)].count == k_lanes) {
        const int32_t b = int32_t(m_blocks.size());
        m_blocks.emplace_back();
        (nd.last < 0 ? nd.first : m_blocks[size_t(nd.last)].next) = b;
        nd.last = b;
    }
    Block& blk = m_blocks[size_t(nd.last)];
    const int k = blk.count++;
    blk.x[k] = p.x;
    blk.y[k] = p.y;
    blk.z[k] = p.z;
    blk.r[k] = radius;
    blk.index[k] = index;
    if (m_slot.size() <= index) m_slot.resize(size_t(index) + 1, 0);
    m_slot[index] = uint32_t(nd.last) * k_lanes + uint32_t(k);
}

}  // namespace candela
