// The irradiance cache: records in an octree (ic_octree.h), Ward's interpolation (ic_error.h) with or without the
// gradients, and the insertion rules that keep the records well spaced:
//   - a record is inserted only where no record already in the cache is usable (so a pass's candidates, merged one
//     after the other, do not pile up where they overlap);
//   - neighbour clamping (Křivánek et al. 2006): the harmonic mean distance changes by at most the distance moved,
//     so for overlapping records i and j, R_i ≤ R_j + ‖x_i − x_j‖ and R_j ≤ R_i + ‖x_i − x_j‖; a record whose gather
//     missed a nearby occluder (a contact shadow, a corner) gets the smaller radius of its neighbours, which did see
//     it. Neither goes below its minimum spacing (Tabellion & Lamorlette 2004), applied when the record was made.
//   - a capacity (the memory estimate's): beyond it candidates are not stored (the render uses them where they were
//     computed, and logs once).
// The cache is read by many threads and changed by one: insertions happen only between passes, when no one reads
// (the pass-frozen cache of docs/irradiance_cache.md), so lookups need no lock and see the same records whatever
// the thread count.
#pragma once

#include <cstddef>
#include <vector>

#include "integrators/irradiance_cache/ic_octree.h"
#include "integrators/irradiance_cache/ic_record.h"
#include "scene/scene.h"

namespace candela {

struct IcCacheRules {
    float a = 0.15f;        // Ward's error a
    bool gradients = true;  // interpolate with the gradients
    bool neighbour_clamping = true;
    size_t capacity = 1u << 20;  // records stored at most
};

class IcCache {
public:
    IcCache(const SceneSphere& bounds, const IcCacheRules& rules);

    /// The interpolated irradiance at (x, n) from the usable records (ε_i < a, not in front); false (E untouched)
    /// if there is none. `records_used`, if given, receives how many were.
    bool interpolate(const Vec3& x, const Vec3& n, Color* E, int* records_used = nullptr) const {
        return interpolate(x, n, m_rules.gradients, E, records_used);
    }
    /// The same with or without the gradient terms (whatever the rules say: tests compare both on one record set).
    bool interpolate(const Vec3& x, const Vec3& n, bool gradients, Color* E, int* records_used = nullptr) const;
    /// The records whose validity sphere comes within `range` of `anchor`, in the order the octree visits them
    /// (appended to *out). For a point x closer than `range` to `anchor` they include every record whose sphere
    /// holds x, in the same order as a query at x visits them: interpolate_among(them, x, …) is interpolate(x, …).
    void candidates_near(const Vec3& anchor, float range, std::vector<uint32_t>* out) const {
        m_octree.for_each_near(anchor, range, [&](uint32_t i) { out->push_back(i); });
    }
    /// interpolate(x, n, E) over those candidates (each tested against its sphere as the octree does).
    bool interpolate_among(const std::vector<uint32_t>& candidates, const Vec3& x, const Vec3& n, Color* E) const;
    /// The same interpolation over a list of records outside the cache (a pixel's own records of this pass:
    /// ic_tracer.cpp), with these rules.
    static bool interpolate_list(const std::vector<IcRecord>& records, const IcCacheRules& rules, const Vec3& x,
                                 const Vec3& n, Color* E);
    /// Whether some record is usable at (x, n).
    bool covered(const Vec3& x, const Vec3& n) const;

    /// Inserts the record unless a stored one is usable at its position or the cache is full (neighbour clamping
    /// first, if on). Returns whether it was stored.
    bool insert(IcRecord record);

    const std::vector<IcRecord>& records() const { return m_records; }
    size_t size() const { return m_records.size(); }
    bool full() const { return m_records.size() >= m_rules.capacity; }
    const IcCacheRules& rules() const { return m_rules; }
    /// Every record whose validity sphere contains x, in index order (the octree's answer, for tests against brute
    /// force).
    std::vector<uint32_t> records_containing(const Vec3& x) const { return records_near(x, 0.f); }
    /// Every record whose validity sphere comes within `range` of x, in index order.
    std::vector<uint32_t> records_near(const Vec3& x, float range) const;

private:
    float validity_radius(const IcRecord& r) const { return m_rules.a * r.R; }
    void clamp_neighbours(IcRecord& r);

    IcCacheRules m_rules;
    std::vector<IcRecord> m_records;
    IcOctree m_octree;
};

/// Bytes one stored record takes (the record, its octree entry): the memory estimate's unit.
inline constexpr size_t k_ic_bytes_per_record = sizeof(IcRecord) + IcOctree::k_bytes_per_record;

}  // namespace candela
