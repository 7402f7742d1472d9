// SPPM's hash grid over the visible points (Hachisuka & Jensen 2009, §4; docs/photon-mapping.md, "SPPM"): each
// iteration's photons look up the visible points whose spheres hold them, instead of every visible point searching
// a kd-tree over the photons (no tree to build per iteration; a photon's lookup reads one cell).
//
// Cells are cubes of side the largest radius R of the points in the grid, over the points' bounding box. A point of
// radius r ≤ R is listed in every cell its box [p − r, p + r] (r widened by a relative 10⁻⁴, so that a photon the
// float distance test accepts never lies in a cell the point is missing from) overlaps: at most 3 per axis (4 where the box's float ends round past a boundary). Cells
// are indexed directly while there are at most 8–16 per point, else hashed into a table of about twice as many buckets
// as points (a bucket may hold several cells: the distance test sorts them out, and a point two of whose cells share
// a bucket is listed there twice, next to itself), stored as one array of point indices per bucket, ascending.
//
// A photon at x arriving from direction w (unit, toward where it came from) is accepted by point i if
//     |x − p_i|² ≤ r_i²   and, for a point with a side normal n_i (a surface that does not transmit), w·n_i > 0,
// the sphere with the side check of the kd-tree lookup (photon_map.h's PhotonFilter with flatten 0). query()
// visits the accepting points in increasing index, so whatever a caller sums per photon is in a fixed order.
#pragma once

#include <cstdint>
#include <vector>

#include "core/vec.h"

namespace candela {

struct GridPoint {
    Vec3 p{0.f};
    float radius2 = 0.f;  // r²; ≤ 0 (or not finite): the point is not in the grid
    Vec3 normal{0.f};     // unit side normal; zero: no side check
};

class VisiblePointGrid {
public:
    /// Builds the grid over `points` (copied; indices are positions in it).
    void build(const std::vector<GridPoint>& points);

    /// Whether point i accepts a photon at x arriving from w (the rule above).
    bool accepts(uint32_t i, const Vec3& x, const Vec3& w) const {
        const GridPoint& g = m_points[i];
        const Vec3 d = x - g.p;
        if (!(dot(d, d) <= g.radius2)) return false;
        const bool side_check = g.normal.x != 0.f || g.normal.y != 0.f || g.normal.z != 0.f;
        return !side_check || dot(w, g.normal) > 0.f;
    }

    /// Calls visit(i) for every point i accepting a photon at x arriving from w, in increasing i.
    template <class Visit>
    void query(const Vec3& x, const Vec3& w, Visit&& visit) const {
        if (m_entries.empty()) return;
        int c[3];
        if (!cell_of(x, c)) return;
        const uint32_t b = bucket(c);
        uint32_t last = UINT32_MAX;
        for (uint32_t k = m_start[b], end = m_start[b + 1]; k < end; ++k) {
            const uint32_t i = m_entries[k];
            if (i == last) continue;  // listed twice: two of its cells share the bucket
            last = i;
            if (accepts(i, x, w)) visit(i);
        }
    }

    bool empty() const { return m_entries.empty(); }
    float cell_size() const { return m_cell; }
    size_t buckets() const { return m_start.empty() ? 0 : m_start.size() - 1; }
    size_t entries() const { return m_entries.size(); }
    double memory_bytes() const {
        return double(m_points.capacity() * sizeof(GridPoint) + m_start.capacity() * sizeof(uint32_t) +
                      m_entries.capacity() * sizeof(uint32_t));
    }

private:
    bool cell_of(const Vec3& x, int* c) const;
    uint32_t bucket(const int* c) const;

    std::vector<GridPoint> m_points;
    std::vector<uint32_t> m_start;    // bucket b's points: m_entries[m_start[b] .. m_start[b + 1])
    std::vector<uint32_t> m_entries;  // point indices
    Vec3 m_lo{0.f};
    float m_cell = 0.f, m_inv_cell = 0.f;
    int m_dims[3] = {0, 0, 0};
    bool m_direct = false;  // few enough cells: bucket = linear cell index (no hashing)
    uint32_t m_mask = 0;    // hashed: buckets − 1 (a power of two)
};

}  // namespace candela
