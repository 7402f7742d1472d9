// The octree the irradiance cache stores its records in (Ward, Rubinstein & Clear 1988, as the course prescribes):
// a record with validity radius ρ (docs/irradiance_cache.md: a·R_i) is stored at the node matching its radius —
// the deepest node containing its position whose side s is still ≥ 2ρ — so its validity sphere lies inside that
// node's cube grown by s/2 on every side (its "loose" cube). A point query visits the nodes whose loose cube could
// contain the point — per depth at most two along each axis, whatever the number of records — and, tighter, keeps
// for each node the bounding box of its records' spheres and of its subtree's: it descends only where a sphere
// could hold the point. A range query (the records whose sphere comes within r of a point: neighbour clamping)
// grows those boxes by r. The root is the cube around the scene's bounding sphere; a
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
        visit_node(0, x, range, visit);
    }

    size_t node_count() const { return m_nodes.size(); }
    /// Bytes the octree holds (nodes and index lists), for the memory estimate's per-record figure.
    static constexpr size_t k_bytes_per_record = sizeof(uint32_t) + 128;  // an index, and about one node per record

private:
    struct Box {
        Vec3 lo{1e30f}, hi{-1e30f};
        bool near(const Vec3& x, float r) const {
            return x.x >= lo.x - r && x.x <= hi.x + r && x.y >= lo.y - r && x.y <= hi.y + r && x.z >= lo.z - r &&
                   x.z <= hi.z + r;
        }
        void add(const Vec3& p, float radius) {
            lo = vmin(lo, p - Vec3(radius));
            hi = vmax(hi, p + Vec3(radius));
        }
    };
    struct Node {
        int32_t child[8] = {-1, -1, -1, -1, -1, -1, -1, -1};
        std::vector<uint32_t> records;
        // Bounding boxes of the spheres of its own records and of its whole subtree's, as inserted (a radius only
        // shrinks afterwards, so they stay bounds): a query skips the records and the subtrees it cannot be in.
        Box own, subtree;
    };

    template <class Visit>
    void visit_node(int32_t node, const Vec3& x, float range, Visit& visit) const {
        const Node& nd = m_nodes[size_t(node)];
        if (nd.own.near(x, range))
            for (uint32_t i : nd.records) visit(i);
        for (int c = 0; c < 8; ++c) {
            const int32_t ci = nd.child[c];
            if (ci >= 0 && m_nodes[size_t(ci)].subtree.near(x, range)) visit_node(ci, x, range, visit);
        }
    }

    Vec3 m_min;
    float m_half;
    std::vector<Node> m_nodes;  // [0] is the root
};

}  // namespace candela
