#include "integrators/irradiance_cache/ic_cache.h"

#include <algorithm>
#include <cmath>

#include "core/math.h"
#include "integrators/irradiance_cache/ic_error.h"

namespace candela {

IcCache::IcCache(const SceneSphere& bounds, const IcCacheRules& rules)
    : m_rules(rules), m_octree(bounds.center, std::max(bounds.radius, 1e-6f) * 1.001f) {}

namespace {

/// Ward's Σ w_i E_i(x, n) / Σ w_i over the usable records among those for_each visits (each inside its validity
/// sphere), summed in double in the visiting order, so the value does not depend on the thread that asks.
template <class ForEach>
bool ward_interpolate(ForEach&& for_each, float a, bool gradients, const Vec3& x, const Vec3& n, Color* E,
                      int* records_used) {
    double sum[3] = {0, 0, 0}, wsum = 0.0;
    int used = 0;
    const IcRecord* exact = nullptr;
    for_each([&](const IcRecord& r) {
        float err;
        if (!ic_usable(r, x, n, a, &err)) return;
        ++used;
        if (!(err > 0.f)) {  // at the record itself: its own value (w = ∞)
            if (!exact) exact = &r;
            return;
        }
        const double w = 1.0 / double(err);
        const Color e = ic_extrapolate(r, x, n, gradients);
        for (int c = 0; c < 3; ++c) sum[c] += w * double(e[c]);
        wsum += w;
    });
    if (records_used) *records_used = used;
    if (exact) {
        *E = ic_extrapolate(*exact, x, n, gradients);
        return true;
    }
    if (!(wsum > 0.0)) return false;
    *E = Color(float(sum[0] / wsum), float(sum[1] / wsum), float(sum[2] / wsum));
    return true;
}

}  // namespace

bool IcCache::interpolate(const Vec3& x, const Vec3& n, bool gradients, Color* E, int* records_used) const {
    // The octree visits exactly the records whose validity sphere holds x, in an order fixed by the insertions.
    return ward_interpolate([&](auto&& use) { m_octree.for_each_near(x, 0.f, [&](uint32_t i) { use(m_records[i]); }); },
                            m_rules.a, gradients, x, n, E, records_used);
}

bool IcCache::interpolate_among(const std::vector<uint32_t>& candidates, const Vec3& x, const Vec3& n, Color* E) const {
    return ward_interpolate(
        [&](auto&& use) {
            for (uint32_t i : candidates) {
                // The octree's test, the same operations in the same order (IcOctree::block_mask).
                const IcRecord& r = m_records[i];
                const float dx = r.p.x - x.x, dy = r.p.y - x.y, dz = r.p.z - x.z, rr = validity_radius(r) + 0.f;
                if (dx * dx + dy * dy + dz * dz < rr * rr) use(r);
            }
        },
        m_rules.a, m_rules.gradients, x, n, E, nullptr);
}

bool IcCache::interpolate_list(const std::vector<IcRecord>& records, const IcCacheRules& rules, const Vec3& x,
                               const Vec3& n, Color* E) {
    return ward_interpolate(
        [&](auto&& use) {
            for (const IcRecord& r : records)
                if (length_squared(x - r.p) < sqr(rules.a * r.R)) use(r);
        },
        rules.a, rules.gradients, x, n, E, nullptr);
}

bool IcCache::covered(const Vec3& x, const Vec3& n) const {
    bool found = false;
    m_octree.for_each_near(x, 0.f, [&](uint32_t i) {
        const IcRecord& r = m_records[i];
        if (found) return;
        float err;
        if (ic_usable(r, x, n, m_rules.a, &err)) found = true;
    });
    return found;
}

void IcCache::clamp_neighbours(IcRecord& rec) {
    // Records whose validity spheres overlap the new one's: ‖x_i − x_j‖ < a(R_i + R_j). The octree finds those
    // whose sphere comes within a·R_i of x_i.
    const float range = validity_radius(rec);
    std::vector<uint32_t> overlapping;
    m_octree.for_each_near(rec.p, range, [&](uint32_t j) {
        const IcRecord& r = m_records[j];
        if (dot(r.n, rec.n) <= 0.f) return;  // another side of a surface: not a neighbour
        if (length(r.p - rec.p) < m_rules.a * (rec.R + r.R)) overlapping.push_back(j);
    });
    // First the new record from all its neighbours, then each neighbour from the clamped new one.
    for (uint32_t j : overlapping) {
        const IcRecord& r = m_records[j];
        rec.R = std::min(rec.R, r.R + length(r.p - rec.p));
    }
    rec.R = std::max(rec.R, rec.R_min);
    for (uint32_t j : overlapping) {
        IcRecord& r = m_records[j];
        r.R = std::max(std::min(r.R, rec.R + length(r.p - rec.p)), r.R_min);
        m_octree.shrink_radius(j, validity_radius(r));  // a smaller sphere: it stays in its octree node
    }
}

bool IcCache::insert(IcRecord record) {
    if (full() || !(record.R > 0.f) || !std::isfinite(record.R)) return false;
    if (covered(record.p, record.n)) return false;
    if (m_rules.neighbour_clamping) clamp_neighbours(record);
    const uint32_t index = uint32_t(m_records.size());
    m_records.push_back(record);
    m_octree.insert(index, record.p, validity_radius(record));
    return true;
}

std::vector<uint32_t> IcCache::records_near(const Vec3& x, float range) const {
    std::vector<uint32_t> out;
    m_octree.for_each_near(x, range, [&](uint32_t i) { out.push_back(i); });
    std::sort(out.begin(), out.end());
    return out;
}

}  // namespace candela
