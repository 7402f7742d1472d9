// The octree the irradiance cache stores its records in (Ward, Rubinstein & Clear 1988, as the course prescribes):
// a record with validity radius ρ (docs/irradiance_cache.md: a·R_i) is stored at the node matching its radius —
// the deepest node containing its position whose side s is still ≥ 2·k_loose·ρ (≥ 2ρ keeps the validity sphere
// inside the node's cube grown by s/2 on every side, its "loose" cube; k_loose = 2 stores records a level higher,
// where a node's blocks hold more of them). A point query visits the nodes whose loose cube could
// contain the point — per depth at most two along each axis, whatever the number of records — and, tighter, keeps
// for each node the bounding box of its records' spheres and of its subtree's: it descends only where a sphere
// could hold the point. A range query (the records whose sphere comes within r of a point: neighbour clamping)
// grows those boxes by r. The root is the cube around the scene's bounding sphere; a record outside it is kept at
// the root, which every query visits.
//
// A node keeps its records' centres and radii in blocks of k_lanes, structure of arrays, so the sphere test
// ‖x − x_i‖² < (ρ_i + r)² runs over a block at once (AVX where the target has it; unused lanes hold NaN centres,
// which no comparison accepts) and the caller reads only the records that pass it. Records are referred to by
// index; a node's blocks keep its records in insertion order, so a query visits them in an order that depends only
// on the insertions.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#if defined(__AVX__)
#include <immintrin.h>
#endif

#include "core/vec.h"

namespace candela {

class IcOctree {
public:
    static constexpr int k_max_depth = 24;
    static constexpr int k_lanes = 8;
    static constexpr float k_loose = 2.f;  // 1: 1,420 instructions per Cornell-box lookup, 2: 1,190, 4: 1,220

    /// The root cube: centre ± half_size on every axis.
    IcOctree(const Vec3& center, float half_size);

    /// Stores record `index` (the next index: 0, 1, 2, …) at position p with validity radius `radius`.
    void insert(uint32_t index, const Vec3& p, float radius);
    /// Shrinks record `index`'s validity radius (neighbour clamping; a smaller sphere stays inside its node's loose
    /// cube and boxes, so the record does not move).
    void shrink_radius(uint32_t index, float radius) {
        const uint32_t s = m_slot[index];
        m_blocks[s / k_lanes].r[s % k_lanes] = radius;
    }

    /// Calls visit(index) for every record whose sphere comes within `range` of x — ‖x − x_i‖² < (ρ_i + range)²,
    /// exactly (range 0: the spheres that contain x).
    template <class Visit>
    void for_each_near(const Vec3& x, float range, Visit&& visit) const {
        visit_node(0, x, range, visit);
    }

    size_t node_count() const { return m_nodes.size(); }
    /// Bytes the octree holds per record (its block lane and slot, and about one node per record), for the memory
    /// estimate.
    static constexpr size_t k_bytes_per_record = 5 * sizeof(float) + sizeof(uint32_t) + 128;

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
    struct alignas(32) Block {
        float x[k_lanes], y[k_lanes], z[k_lanes], r[k_lanes];
        uint32_t index[k_lanes];
        int32_t count = 0;
        int32_t next = -1;  // the node's next block
        Block() {
            const float nan = std::numeric_limits<float>::quiet_NaN();
            for (int k = 0; k < k_lanes; ++k) x[k] = y[k] = z[k] = nan, r[k] = 0.f, index[k] = 0;
        }
    };
    struct Node {
        int32_t child[8] = {-1, -1, -1, -1, -1, -1, -1, -1};
        int32_t first = -1, last = -1;  // its blocks
        // Bounding boxes of the spheres of its own records and of its whole subtree's, as inserted (a radius only
        // shrinks afterwards, so they stay bounds): a query skips the records and the subtrees it cannot be in.
        Box own, subtree;
    };

    /// The lanes of block b whose sphere comes within `range` of x, as a bit mask. The same IEEE operations in
    /// the same order on every lane (no contraction: -ffp-contract=off), so the vector code and the scalar one
    /// give the same answer.
    static unsigned block_mask(const Block& b, const Vec3& x, float range) {
#if defined(__AVX__)
        const __m256 dx = _mm256_sub_ps(_mm256_load_ps(b.x), _mm256_set1_ps(x.x));
        const __m256 dy = _mm256_sub_ps(_mm256_load_ps(b.y), _mm256_set1_ps(x.y));
        const __m256 dz = _mm256_sub_ps(_mm256_load_ps(b.z), _mm256_set1_ps(x.z));
        const __m256 rr = _mm256_add_ps(_mm256_load_ps(b.r), _mm256_set1_ps(range));
        const __m256 d2 =
            _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(dx, dx), _mm256_mul_ps(dy, dy)), _mm256_mul_ps(dz, dz));
        return unsigned(_mm256_movemask_ps(_mm256_cmp_ps(d2, _mm256_mul_ps(rr, rr), _CMP_LT_OQ)));
#else
        unsigned mask = 0;
        for (int k = 0; k < k_lanes; ++k) {
            const float dx = b.x[k] - x.x, dy = b.y[k] - x.y, dz = b.z[k] - x.z, rr = b.r[k] + range;
            if (dx * dx + dy * dy + dz * dz < rr * rr) mask |= 1u << k;
        }
        return mask;
#endif
    }

    template <class Visit>
    void visit_node(int32_t node, const Vec3& x, float range, Visit& visit) const {
        const Node& nd = m_nodes[size_t(node)];
        if (nd.own.near(x, range))
            for (int32_t bi = nd.first; bi >= 0;) {
                const Block& b = m_blocks[size_t(bi)];
                for (unsigned m = block_mask(b, x, range); m; m &= m - 1) visit(b.index[__builtin_ctz(m)]);
                bi = b.next;
            }
        for (int c = 0; c < 8; ++c) {
            const int32_t ci = nd.child[c];
            if (ci >= 0 && m_nodes[size_t(ci)].subtree.near(x, range)) visit_node(ci, x, range, visit);
        }
    }

    Vec3 m_min;
    float m_half;
    std::vector<Node> m_nodes;     // [0] is the root
    std::vector<Block> m_blocks;   // every node's, in the order they were opened
    std::vector<uint32_t> m_slot;  // record index -> block · k_lanes + lane
};

}  // namespace candela
