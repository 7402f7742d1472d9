// The light tree's build: the split search over occupied buckets must choose what the search over every
// bucket boundary chooses (same tree, hence the same pmf bit for bit), and acos_clamped must equal libm's acos.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "core/math.h"
#include "core/rng.h"
#include "lights/light.h"
#include "lights/light_bounds.h"
#include "lights/light_sampler.h"

namespace candela {
namespace {

uint32_t bits(float f) {
    uint32_t u;
    std::memcpy(&u, &f, 4);
    return u;
}

TEST(LightBoundsAcos, MatchesLibm) {
    std::vector<float> cs = {0.f,
                             -0.f,
                             1.f,
                             -1.f,
                             1.5f,
                             -1.5f,
                             std::numeric_limits<float>::infinity(),
                             -std::numeric_limits<float>::infinity()};
    for (float c : {0.f, 1.f, -1.f})
        for (int k = 0; k < 64; ++k) {  // the floats next to the special points
            float up = c, down = c;
            for (int s = 0; s <= k; ++s) {
                up = std::nextafter(up, 2.f);
                down = std::nextafter(down, -2.f);
            }
            cs.push_back(up);
            cs.push_back(down);
        }
    Pcg32 rng(7, 3);
    for (int i = 0; i < 100000; ++i) cs.push_back(2.4f * rng.next_float() - 1.2f);
    for (float c : cs) ASSERT_EQ(bits(acos_clamped(c)), bits(std::acos(clamp(c, -1.f, 1.f)))) << c;
    EXPECT_TRUE(std::isnan(acos_clamped(std::numeric_limits<float>::quiet_NaN())));
}

// ---- reference split search: every boundary s of the 12 buckets, each half folded anew -------------------

float ref_cone_measure(float cos_o, float cos_e) {  // pbrt-v4's M_Ω, as in light_sampler.cpp
    const float theta_o = std::acos(clamp(cos_o, -1.f, 1.f)), theta_e = std::acos(clamp(cos_e, -1.f, 1.f));
    const float theta_w = std::min(theta_o + theta_e, k_pi);
    const float sin_o = std::sin(theta_o);
    return 2.f * k_pi * (1.f - cos_o) +
           k_pi / 2.f * (2.f * theta_w * sin_o - std::cos(theta_o - 2.f * theta_w) - 2.f * theta_o * sin_o + cos_o);
}

float ref_saoh(const LightBounds& b, const Vec3& ext, int axis) {
    const float m = max_component(ext), e = axis == 0 ? ext.x : axis == 1 ? ext.y : ext.z;
    return b.phi * ref_cone_measure(b.cos_theta_o, b.cos_theta_e) * (e > 0.f ? m / e : 1.f) *
           std::max(b.bounds.surface_area(), 1e-20f);
}

float comp(const Vec3& v, int a) { return a == 0 ? v.x : a == 1 ? v.y : v.z; }

/// The (axis, bucket) the full search picks for the root over `items` (-1, -1: none).
std::pair<int, int> reference_root_split(const std::vector<LightBounds>& items) {
    Bounds3 box, centroids;
    for (const auto& it : items) {
        box.extend(it.bounds);
        centroids.extend(it.bounds.centroid());
    }
    const Vec3 extent = box.diagonal(), cext = centroids.diagonal();
    float best = std::numeric_limits<float>::infinity();
    std::pair<int, int> out{-1, -1};
    for (int a = 0; a < 3; ++a) {
        const float lo = comp(centroids.lo, a), ext = comp(cext, a);
        if (!(ext > 0.f)) continue;
        LightBounds buckets[12];
        for (const auto& it : items) {
            const int b = std::clamp(int(12 * ((comp(it.bounds.centroid(), a) - lo) / ext)), 0, 11);
            buckets[b] = union_bounds(buckets[b], it);
        }
        for (int s = 0; s < 11; ++s) {
            LightBounds below, above;
            for (int b = 0; b <= s; ++b) below = union_bounds(below, buckets[b]);
            for (int b = s + 1; b < 12; ++b) above = union_bounds(above, buckets[b]);
            if (!(below.phi > 0.f) || !(above.phi > 0.f)) continue;
            const float cost = ref_saoh(below, extent, a) + ref_saoh(above, extent, a);
            if (cost < best) {
                best = cost;
                out = {a, s};
            }
        }
    }
    return out;
}

TEST(LightTreeBuild, RootSplitMatchesTheSearchOverEveryBucketBoundary) {
    Pcg32 rng(42, 5);
    auto rnd = [&](float lo, float hi) { return lo + (hi - lo) * rng.next_float(); };
    int compared = 0;
    for (int trial = 0; trial < 300; ++trial) {
        // Few lights, clumped, so most buckets are empty and many boundaries tie; some with equal flux and
        // equal normals (the exact ties the strict '<' must break toward the lowest boundary).
        const int n = 2 + int(rng.next_float() * 30.f);
        const bool same_shape = trial % 3 == 0;
        LightSet set;
        std::vector<LightBounds> items;
        for (int i = 0; i < n; ++i) {
            const float cl = float(int(rnd(0.f, 4.f)));
            const Vec3 c(cl * 10.f + rnd(-0.5f, 0.5f), rnd(-3, 3) * (trial % 2), rnd(-3, 3));
            TriangleLight t;
            t.p0 = c;
            t.p1 = same_shape ? c + Vec3(0.3f, 0.f, 0.f) : c + Vec3(rnd(-1, 1), rnd(-1, 1), rnd(-1, 1));
            t.p2 = same_shape ? c + Vec3(0.f, 0.3f, 0.f) : c + Vec3(rnd(-1, 1), rnd(-1, 1), rnd(-1, 1));
            const Vec3 nn = cross(t.p1 - t.p0, t.p2 - t.p0);
            if (!(length(nn) > 1e-6f)) continue;
            t.area = 0.5f * length(nn);
            t.normal = normalize(nn);
            t.radiance = Color(same_shape ? 1.f : rnd(0.5f, 3.f));
            set.add(t);
        }
        set.finalize(10.f);
        if (set.size() < 2) continue;
        for (uint32_t i = 0; i < set.size(); ++i) items.push_back(*light_bounds(set[i]));
        const LightSampler ls = make_light_sampler("TREE", set);
        const auto& nodes = ls.tree()->nodes();
        ASSERT_FALSE(nodes[0].leaf);
        // The root's first child holds the lights the reference split puts at or below its bucket.
        const auto [axis, bucket] = reference_root_split(items);
        if (axis < 0) continue;  // the build halves by count then: not the split search
        Bounds3 centroids;
        for (const auto& it : items) centroids.extend(it.bounds.centroid());
        const float lo = comp(centroids.lo, axis), ext = comp(centroids.diagonal(), axis);
        std::vector<uint32_t> expected, got;
        for (uint32_t i = 0; i < items.size(); ++i)
            if (std::clamp(int(12 * ((comp(items[i].bounds.centroid(), axis) - lo) / ext)), 0, 11) <= bucket)
                expected.push_back(i);
        const auto& first = nodes[1];
        for (uint32_t r = 0; r < (first.leaf ? 1u : first.leaf_count); ++r) {
            for (uint32_t k = 0; k < nodes.size(); ++k)
                if (nodes[k].leaf && nodes[k].first_leaf == first.first_leaf + r) got.push_back(nodes[k].index);
        }
        std::sort(got.begin(), got.end());
        ASSERT_EQ(got, expected) << "trial " << trial;
        ++compared;
    }
    EXPECT_GT(compared, 150);
}

}  // namespace
}  // namespace candela
