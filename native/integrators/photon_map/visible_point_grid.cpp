#include "integrators/photon_map/visible_point_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"

namespace candela {

namespace {

bool in_grid(const GridPoint& g) { return g.radius2 > 0.f && std::isfinite(g.radius2); }

// The box a point is listed over: its radius widened by a relative 1e-4 (see the header).
float listed_radius(const GridPoint& g) { return std::sqrt(g.radius2) * 1.0001f; }

}  // namespace

bool VisiblePointGrid::cell_of(const Vec3& x, int* c) const {
    const float v[3] = {(x.x - m_lo.x) * m_inv_cell, (x.y - m_lo.y) * m_inv_cell, (x.z - m_lo.z) * m_inv_cell};
    for (int a = 0; a < 3; ++a) {
        if (!(v[a] >= 0.f)) return false;  // below the box, or NaN
        const float f = std::floor(v[a]);
        if (!(f < float(m_dims[a]))) return false;
        c[a] = int(f);
    }
    return true;
}

uint32_t VisiblePointGrid::bucket(const int* c) const {
    if (m_direct) return uint32_t((int64_t(c[2]) * m_dims[1] + c[1]) * m_dims[0] + c[0]);
    const uint32_t h = uint32_t(c[0]) * 73856093u ^ uint32_t(c[1]) * 19349663u ^ uint32_t(c[2]) * 83492791u;
    return h & m_mask;
}

void VisiblePointGrid::build(const std::vector<GridPoint>& points) {
    m_points = points;
    m_start.clear();
    m_entries.clear();
    if (points.size() >= size_t(UINT32_MAX)) throw InvalidParameter("too many visible points for the SPPM grid");
    Vec3 lo(std::numeric_limits<float>::infinity()), hi(-std::numeric_limits<float>::infinity());
    float max_r = 0.f;
    size_t n = 0;
    for (const GridPoint& g : m_points) {
        if (!in_grid(g)) continue;
        const float r = listed_radius(g);
        lo = vmin(lo, g.p - Vec3(r));
        hi = vmax(hi, g.p + Vec3(r));
        max_r = std::max(max_r, r);
        ++n;
    }
    if (n == 0 || !(max_r > 0.f)) return;
    m_lo = lo;
    // Cells of the largest radius, but at most 2²⁰ per axis (a degenerate spread of radii: then the cells are
    // coarser than the radius, which costs time, not correctness).
    const Vec3 extent = hi - lo;
    m_cell = std::max(max_r, max_component(extent) * 0x1p-20f);
    m_inv_cell = 1.f / m_cell;
    double cells = 1.0;
    const float ext[3] = {extent.x, extent.y, extent.z};
    for (int a = 0; a < 3; ++a) {
        m_dims[a] = int(std::floor(double(ext[a]) * m_inv_cell)) + 1;
        cells *= double(m_dims[a]);
    }
    uint32_t size = 1;
    while (size < 2 * n) size <<= 1;
    m_direct = cells <= 4.0 * double(size);  // at most 4 bucket starts per hashed bucket: no hashing
    const size_t buckets = m_direct ? size_t(cells) : size_t(size);
    m_mask = size - 1;

    // Each point's buckets counted, then filled in increasing point index. A box spans 2r ≤ 2 cells
    // per axis, but its float ends can round past a cell boundary: up to 4 cells per axis, 64 in all.
    auto buckets_of = [&](const GridPoint& g, uint32_t* out) {
        const float r = listed_radius(g);
        int c0[3], c1[3];
        const Vec3 a = (g.p - Vec3(r) - m_lo) * m_inv_cell, b = (g.p + Vec3(r) - m_lo) * m_inv_cell;
        const float av[3] = {a.x, a.y, a.z}, bv[3] = {b.x, b.y, b.z};
        for (int k = 0; k < 3; ++k) {
            c0[k] = std::clamp(int(std::floor(av[k])), 0, m_dims[k] - 1);
            c1[k] = std::clamp(int(std::floor(bv[k])), 0, m_dims[k] - 1);
        }
        int count = 0;
        int c[3];
        for (c[2] = c0[2]; c[2] <= c1[2]; ++c[2])
            for (c[1] = c0[1]; c[1] <= c1[1]; ++c[1])
                for (c[0] = c0[0]; c[0] <= c1[0]; ++c[0]) out[count++] = bucket(c);
        // Hashed, two of the cells may share a bucket: the point is then listed twice there, next to itself (a
        // bucket's points are in increasing index), and query() skips the repeat.
        return count;
    };
    m_start.assign(buckets + 1, 0u);
    uint32_t list[64];
    for (const GridPoint& g : m_points) {
        if (!in_grid(g)) continue;
        const int k = buckets_of(g, list);
        for (int j = 0; j < k; ++j) ++m_start[list[j] + 1];
    }
    for (size_t b = 0; b < buckets; ++b) m_start[b + 1] += m_start[b];
    m_entries.resize(m_start[buckets]);
    std::vector<uint32_t> fill(m_start.begin(), m_start.end() - 1);
    for (uint32_t i = 0; i < uint32_t(m_points.size()); ++i) {
        if (!in_grid(m_points[i])) continue;
        const int k = buckets_of(m_points[i], list);
        for (int j = 0; j < k; ++j) m_entries[fill[list[j]]++] = i;
    }
}

}  // namespace candela
