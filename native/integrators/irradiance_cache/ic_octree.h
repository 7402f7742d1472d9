// The octree the irradiance cache stores its records in (Ward, Rubinstein & Clear 1988, as the course prescribes):
// a record with validity radius ρ (docs/irradiance_cache.md: a·R_i) is stored at the node matching its radius —
// the deepest node containing its position whose side s is still ≥ 2ρ — so its validity sphere lies inside that
// node's cube grown by s/2 on every side (its "loose" cube). A point query therefore visits exactly the nodes whose
// loose cube contains the point: per depth at most two along each axis, eight in all, whatever the number of
// records. A range query (the records whose sphere comes within r of a point: neighbour clamping) visits the nodes
// whose loose cube grown by r contains the point. The root is the cube around the scene's bounding sphere; a
// record outside it is kept at the root, which every query visits. Records are referred to by index; each node
// keeps its records in insertion order, so a query visits them in an order that depends only on the insertions.
#pragma once

#include <cstdint>
#include <vector>

#include "core/vec.h"

namespace candela {

class IcOctree {
public:
    static constexpr int k_max_depth = 24;

    /// The root cube: centre ± half_size on every axis.
    IcOctree(const Vec3& center, float half_size);

    /// Stores record `index` at position p with validity radius `radius`.
    void insert(uint32_t index, const Vec3& p, float radius);

    /// Calls visit(index) for every record stored where its sphere could come within `range` of x (range 0: could
    /// contain x). A superset: the caller tests each record's own sphere.
    template <class Visit>
    void for_each_near(const Vec3& x, float range, Visit&& visit) const {
        visit_node(0, m_min, 2.f * m_half, x, range, visit);
    }

    size_t node_count() const { return m_nodes.size(); }
    /// Bytes the octree holds (nodes and index lists), for the memory estimate's per-record figure.
    static constexpr size_t k_bytes_per_record = sizeof(uint32_t) + 40;  // an index, and about one node per record

private:
    struct Node {
        int32_t child[8] = {-1, -1, -1, -1, -1, -1, -1, -1};
        std::vector<uint32_t> records;
    };

    template <class Visit>
    void visit_node(int32_t node, const Vec3& lo, float side, const Vec3& x, float range, Visit& visit) const {
        const Node& nd = m_nodes[size_t(node)];
        for (uint32_t i : nd.records) visit(i);
        const float half = 0.5f * side;
        // A child of side `half` at corner c holds records whose spheres stay within half/2 of it.
        const float grow = 0.5005f * half + range;  // its loose margin, with room for rounding
        for (int c = 0; c < 8; ++c) {
            const int32_t ci = nd.child[c];
            if (ci < 0) continue;
            const Vec3 clo(lo.x + ((c & 1) ? half : 0.f), lo.y + ((c & 2) ? half : 0.f), lo.z + ((c & 4) ? half : 0.f));
            if (x.x < clo.x - grow || x.x > clo.x + half + grow || x.y < clo.y - grow || x.y > clo.y + half + grow ||
                x.z < clo.z - grow || x.z > clo.z + half + grow)
                continue;
            visit_node(ci, clo, half, x, range, visit);
        }
    }

    Vec3 m_min;
    float m_half;
    std::vector<Node> m_nodes;  // [0] is the root
};

}  // namespace candela
