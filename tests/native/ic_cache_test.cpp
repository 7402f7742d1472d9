// The irradiance cache's error metric, weights, interpolation and insertion rules against values computed by hand
// (docs/irradiance_cache.md, "Expected values"), and its octree against a brute-force search.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/rng.h"
#include "integrators/irradiance_cache/ic_cache.h"
#include "integrators/irradiance_cache/ic_error.h"
#include "integrators/irradiance_cache/ic_octree.h"

namespace candela::test {
namespace {

IcRecord record(Vec3 p, Vec3 n, float R, Color E) {
    IcRecord r;
    r.p = p;
    r.n = n;
    r.R = R;
    r.E = E;
    return r;
}

const Vec3 k_up(0.f, 0.f, 1.f);

TEST(IcError, MetricAndWeightByHand) {
    const IcRecord r = record(Vec3(0.f), k_up, 2.f, Color(1.f, 2.f, 3.f));
    // ‖(0.3, 0.4, 0)‖/2 = 0.25, same normal: ε = 0.25, w = 4.
    EXPECT_NEAR(ic_error(r, Vec3(0.3f, 0.4f, 0.f), k_up), 0.25f, 1e-6f);
    EXPECT_NEAR(ic_weight(0.25f), 4.f, 1e-6f);
    // A normal with n·n_i = 0.96 adds √0.04 = 0.2: at 0.2 away (0.1 of R), ε = 0.3, w = 10/3.
    const Vec3 tilted(0.f, std::sqrt(1.f - 0.96f * 0.96f), 0.96f);
    EXPECT_NEAR(ic_error(r, Vec3(0.2f, 0.f, 0.f), tilted), 0.3f, 1e-5f);
    EXPECT_NEAR(ic_weight(0.3f), 10.f / 3.f, 1e-5f);
    EXPECT_TRUE(std::isinf(ic_weight(0.f)));
    float err;
    EXPECT_TRUE(ic_usable(r, Vec3(0.3f, 0.4f, 0.f), k_up, 0.3f, &err));   // ε = 0.25 < a = 0.3: w = 4 > 1/a
    EXPECT_FALSE(ic_usable(r, Vec3(0.3f, 0.4f, 0.f), k_up, 0.2f, &err));  // ε = 0.25 ≥ 0.2
}

TEST(IcError, RecordsInFrontAreNotUsed) {
    // a = 0.3, R = 2: in front when (x − x_i)·(n + n_i)/2 < −0.1·a·R = −0.06.
    const IcRecord r = record(Vec3(0.f), k_up, 2.f, Color(1.f));
    float err;
    EXPECT_TRUE(ic_in_front(r, Vec3(0.f, 0.f, -0.1f), k_up, 0.3f));  // the record 0.1 above x
    EXPECT_FALSE(ic_usable(r, Vec3(0.f, 0.f, -0.1f), k_up, 0.3f, &err));
    EXPECT_FALSE(ic_in_front(r, Vec3(0.f, 0.f, -0.05f), k_up, 0.3f));  // 0.05: within the tolerance
    EXPECT_TRUE(ic_usable(r, Vec3(0.f, 0.f, -0.05f), k_up, 0.3f, &err));
    EXPECT_NEAR(err, 0.025f, 1e-6f);
    EXPECT_FALSE(ic_in_front(r, Vec3(0.f, 0.f, 0.1f), k_up, 0.3f));  // behind: fine
}

TEST(IcError, ExtrapolationByTheGradientsByHand) {
    IcRecord r = record(Vec3(0.f), k_up, 1.f, Color(1.f, 1.f, 1.f));
    r.grad_t[0] = Vec3(1.f, 0.f, 0.f);
    r.grad_r[0] = Vec3(0.f, 2.f, 0.f);
    r.grad_t[1] = Vec3(-20.f, 0.f, 0.f);  // channel 1 would go negative: clamped to 0
    const Vec3 n = normalize(Vec3(0.1f, 0.f, 1.f));
    // n_i × n = (0, n.x, 0): the rotation term is 2·n.x; the translation term 0.1·1.
    const Color e = ic_extrapolate(r, Vec3(0.1f, 0.f, 0.f), n, true);
    EXPECT_NEAR(e.x, 1.f + 2.f * n.x + 0.1f, 1e-6f);
    EXPECT_EQ(e.y, 0.f);
    EXPECT_NEAR(e.z, 1.f, 1e-6f);
    EXPECT_EQ(ic_extrapolate(r, Vec3(0.1f, 0.f, 0.f), n, false).x, 1.f);
}

TEST(IcCache, InterpolatesWithWardsWeightsByHand) {
    IcCacheRules rules;
    rules.a = 0.15f;
    rules.gradients = false;
    IcCache cache(SceneSphere{Vec3(0.f), 10.f}, rules);
    ASSERT_TRUE(cache.insert(record(Vec3(0.f), k_up, 1.f, Color(1.f))));
    ASSERT_TRUE(cache.insert(record(Vec3(0.2f, 0.f, 0.f), k_up, 1.f, Color(3.f))));  // ε = 0.2 from the first
    // At x = 0.06: ε = 0.06 and 0.14, E = (1/0.06 + 3/0.14)/(1/0.06 + 1/0.14) = (0.14 + 0.18)/0.2 = 1.6.
    Color E;
    int used = 0;
    ASSERT_TRUE(cache.interpolate(Vec3(0.06f, 0.f, 0.f), k_up, &E, &used));
    EXPECT_EQ(used, 2);
    EXPECT_NEAR(E.x, 1.6f, 1e-5f);
    // At x = 0.03 the second record's ε = 0.17 ≥ a: the first alone.
    ASSERT_TRUE(cache.interpolate(Vec3(0.03f, 0.f, 0.f), k_up, &E, &used));
    EXPECT_EQ(used, 1);
    EXPECT_NEAR(E.x, 1.f, 1e-6f);
    // At the record itself its own value (w = ∞), and nothing where no record is usable.
    ASSERT_TRUE(cache.interpolate(Vec3(0.2f, 0.f, 0.f), k_up, &E));
    EXPECT_EQ(E.x, 3.f);
    EXPECT_FALSE(cache.interpolate(Vec3(1.f, 0.f, 0.f), k_up, &E));
    EXPECT_FALSE(cache.interpolate(Vec3(0.f), -k_up, &E));  // the other side of the surface
    // A record where one is already usable is not inserted.
    EXPECT_FALSE(cache.insert(record(Vec3(0.05f, 0.f, 0.f), k_up, 1.f, Color(9.f))));
    EXPECT_EQ(cache.size(), 2u);
}

TEST(IcCache, NeighbourClampingByHand) {
    // a = 0.3. Record 1: R = 10 at the origin; record 2 at distance 1 with R = 0.5 and a normal tilted so that
    // √(1 − n·n_i) = 0.25: ε = 0.1 + 0.25 ≥ a, so it is inserted, and its sphere overlaps record 1's
    // (1 < a·(10 + 0.5)). Then R_2 = min(0.5, 10 + 1) = 0.5 and R_1 = min(10, 0.5 + 1) = 1.5, raised to R_min = 2.
    for (bool clamping : {true, false}) {
        IcCacheRules rules;
        rules.a = 0.3f;
        rules.neighbour_clamping = clamping;
        IcCache cache(SceneSphere{Vec3(0.f), 10.f}, rules);
        IcRecord r1 = record(Vec3(0.f), k_up, 10.f, Color(1.f));
        r1.R_min = 2.f;
        ASSERT_TRUE(cache.insert(r1));
        const float c = 1.f - 0.0625f;
        ASSERT_TRUE(cache.insert(record(Vec3(1.f, 0.f, 0.f), Vec3(std::sqrt(1.f - c * c), 0.f, c), 0.5f, Color(1.f))));
        EXPECT_NEAR(cache.records()[0].R, clamping ? 2.f : 10.f, 1e-6f);
        EXPECT_NEAR(cache.records()[1].R, 0.5f, 1e-6f);
    }
    // Without a minimum: 1.5.
    IcCacheRules rules;
    rules.a = 0.3f;
    IcCache cache(SceneSphere{Vec3(0.f), 10.f}, rules);
    ASSERT_TRUE(cache.insert(record(Vec3(0.f), k_up, 10.f, Color(1.f))));
    const float c = 1.f - 0.0625f;
    ASSERT_TRUE(cache.insert(record(Vec3(1.f, 0.f, 0.f), Vec3(std::sqrt(1.f - c * c), 0.f, c), 0.5f, Color(1.f))));
    EXPECT_NEAR(cache.records()[0].R, 1.5f, 1e-6f);
    // A new record with R = 5 next to a record of R = 0.5 at distance 1 (normals alike; overlapping: 1 < 0.3·5.5;
    // not usable there: ε = 1/0.5 ≥ a) gets R = 0.5 + 1 = 1.5; the old one keeps min(0.5, 1.5 + 1) = 0.5.
    IcCache cache2(SceneSphere{Vec3(0.f), 10.f}, rules);
    ASSERT_TRUE(cache2.insert(record(Vec3(0.f), k_up, 0.5f, Color(1.f))));
    ASSERT_TRUE(cache2.insert(record(Vec3(1.f, 0.f, 0.f), k_up, 5.f, Color(1.f))));
    EXPECT_NEAR(cache2.records()[1].R, 1.5f, 1e-6f);
    EXPECT_NEAR(cache2.records()[0].R, 0.5f, 1e-6f);
    // At distance 2 they do not overlap (2 ≥ 0.3·5.5): no clamping.
    IcCache cache3(SceneSphere{Vec3(0.f), 10.f}, rules);
    ASSERT_TRUE(cache3.insert(record(Vec3(0.f), k_up, 0.5f, Color(1.f))));
    ASSERT_TRUE(cache3.insert(record(Vec3(2.f, 0.f, 0.f), k_up, 5.f, Color(1.f))));
    EXPECT_NEAR(cache3.records()[1].R, 5.f, 1e-6f);
}

TEST(IcCache, CapacityIsRespected) {
    IcCacheRules rules;
    rules.capacity = 2;
    IcCache cache(SceneSphere{Vec3(0.f), 10.f}, rules);
    for (int i = 0; i < 5; ++i) cache.insert(record(Vec3(float(i), 0.f, 0.f), k_up, 1.f, Color(1.f)));
    EXPECT_EQ(cache.size(), 2u);
    EXPECT_TRUE(cache.full());
}

// The octree's answers equal a brute-force search, for records of radii R over three decades, some outside the root
// cube, and for point and range queries; with neighbour clamping on, after the radii it shrinks (the octree's own
// copies of the radii must follow). The sphere test is the octree's: ‖x − x_i‖² < (a·R_i + range)².
void expect_octree_equals_brute_force(bool clamping) {
    Pcg32 rng(7, 11);
    auto uniform = [&](float lo, float hi) { return lo + (hi - lo) * rng.next_float(); };
    const float a = 0.25f;
    IcCacheRules rules;
    rules.a = a;
    rules.neighbour_clamping = clamping;
    IcCache cache(SceneSphere{Vec3(0.5f, -0.5f, 0.f), 4.f}, rules);
    for (int i = 0; i < 4000; ++i) {
        // Random normals: an insertion is refused only where a stored record is usable, rare with random normals.
        const Vec3 n = normalize(Vec3(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)));
        cache.insert(record(Vec3(uniform(-5, 6), uniform(-6, 5), uniform(-5, 5)), n, std::pow(10.f, uniform(-2.f, 1.f)),
                            Color(1.f)));
    }
    const std::vector<IcRecord>& all = cache.records();
    ASSERT_GT(all.size(), 2000u);
    auto inside = [&](const Vec3& x, const IcRecord& r, float range) {
        const Vec3 d = r.p - x;
        const float rr = a * r.R + range;
        return d.x * d.x + d.y * d.y + d.z * d.z < rr * rr;
    };
    size_t nonempty = 0;
    for (int q = 0; q < 4000; ++q) {
        const Vec3 x(uniform(-6, 7), uniform(-7, 6), uniform(-6, 6));
        std::vector<uint32_t> brute;
        for (uint32_t i = 0; i < all.size(); ++i)
            if (inside(x, all[i], 0.f)) brute.push_back(i);
        const std::vector<uint32_t> tree = cache.records_containing(x);
        ASSERT_EQ(tree, brute) << "query " << q;
        nonempty += !brute.empty();
        // Range queries: every record whose sphere comes within `range` of x is visited.
        const float range = std::pow(10.f, uniform(-2.f, 0.5f));
        std::vector<uint32_t> near;
        for (uint32_t i = 0; i < all.size(); ++i)
            if (inside(x, all[i], range)) near.push_back(i);
        ASSERT_EQ(cache.records_near(x, range), near) << "query " << q;
    }
    // The test exercises real hits, not only empty answers (clamping shrinks the radii: fewer).
    EXPECT_GT(nonempty, clamping ? 200u : 1000u);
}

TEST(IcOctree, QueriesEqualBruteForce) { expect_octree_equals_brute_force(false); }

TEST(IcOctree, QueriesEqualBruteForceAfterNeighbourClamping) { expect_octree_equals_brute_force(true); }

}  // namespace
}  // namespace candela::test
