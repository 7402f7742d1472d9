// SPPM (integrators/photon_map/sppm.h; docs/photon-mapping.md, "SPPM", "Verification"):
//   - the hash grid over the visible points finds exactly the points brute force finds (ties at the radius,
//     duplicate points, the side check, points not in the grid);
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "agreement.h"
#include "core/rng.h"
#include "integrators/photon_map/visible_point_grid.h"
#include "reference_scenes.h"
#include "test_helpers.h"

namespace candela::test {
namespace {

// ---- the hash grid -----------------------------------------------------------------------------------------

/// Visible points on a slab with radii in [r_max/8, r_max]: a share on a lattice of step 1/8 with radius exactly
/// 1/16 (so photons on the lattice's half-steps lie exactly on their spheres: ties at the radius, in exact float
/// arithmetic), duplicates of earlier points, points not in the grid (radius 0), and side normals on half of them.
std::vector<GridPoint> random_points(size_t n, float r_max, uint64_t seed) {
    Pcg32 rng(seed, 3);
    std::vector<GridPoint> out(n);
    for (size_t i = 0; i < n; ++i) {
        GridPoint& g = out[i];
        const float u = rng.next_float();
        if (i > 0 && u < 0.1f) {
            g = out[size_t(rng.next_u32() % uint32_t(i))];
            continue;
        }
        g.p = Vec3(rng.next_float() * 4.f - 2.f, rng.next_float() * 4.f - 2.f, rng.next_float() * 0.5f);
        const float r = r_max * (0.125f + 0.875f * rng.next_float());
        g.radius2 = r * r;
        if (u < 0.3f) {
            g.p = Vec3(std::round(g.p.x * 8.f) / 8.f, std::round(g.p.y * 8.f) / 8.f, 0.f);
            g.radius2 = 1.f / 256.f;
        } else if (u < 0.33f) {
            g.radius2 = 0.f;
        }
        if (rng.next_float() < 0.5f)
            g.normal = normalize(Vec3(rng.next_float() - 0.5f, rng.next_float() - 0.5f, rng.next_float() - 0.5f));
    }
    return out;
}

/// Brute force, written independently of the grid: every point whose closed ball holds x and whose side (if any)
/// w comes from, in increasing index.
std::vector<uint32_t> brute_force(const std::vector<GridPoint>& points, const Vec3& x, const Vec3& w) {
    std::vector<uint32_t> out;
    for (uint32_t i = 0; i < uint32_t(points.size()); ++i) {
        const GridPoint& g = points[i];
        if (!(g.radius2 > 0.f)) continue;
        const float dx = x.x - g.p.x, dy = x.y - g.p.y, dz = x.z - g.p.z;
        if (!(dx * dx + dy * dy + dz * dz <= g.radius2)) continue;
        const bool sided = g.normal.x != 0.f || g.normal.y != 0.f || g.normal.z != 0.f;
        if (sided && !(g.normal.x * w.x + g.normal.y * w.y + g.normal.z * w.z > 0.f)) continue;
        out.push_back(i);
    }
    return out;
}

TEST(SppmGrid, QueriesEqualBruteForce) {
    const float r_max = 1.f / 16.f;
    const std::vector<GridPoint> points = random_points(20000, r_max, 5);
    VisiblePointGrid grid;
    grid.build(points);
    ASSERT_FALSE(grid.empty());
    Pcg32 rng(17, 9);
    size_t found = 0, ties = 0, side_rejected = 0;
    for (int q = 0; q < 20000; ++q) {
        Vec3 x(rng.next_float() * 4.4f - 2.2f, rng.next_float() * 4.4f - 2.2f, rng.next_float() * 0.7f - 0.1f);
        if (q % 4 == 0) {  // a lattice half-step: exactly at radius 1/16 from the lattice points on either side
            x = Vec3(std::round(x.x * 8.f) / 8.f + 1.f / 16.f, std::round(x.y * 8.f) / 8.f, 0.f);
        } else if (q % 4 == 1) {  // on a point, or near one
            const GridPoint& g = points[rng.next_u32() % uint32_t(points.size())];
            x = g.p + Vec3(rng.next_float() - 0.5f, rng.next_float() - 0.5f, rng.next_float() - 0.5f) *
                          (q % 8 == 1 ? 0.f : 0.15f);
        }
        const Vec3 w = normalize(Vec3(rng.next_float() - 0.5f, rng.next_float() - 0.5f, rng.next_float() - 0.5f));
        const std::vector<uint32_t> expected = brute_force(points, x, w);
        std::vector<uint32_t> got;
        grid.query(x, w, [&](uint32_t i) { got.push_back(i); });
        ASSERT_EQ(got, expected) << "query " << q;
        found += got.size();
        for (uint32_t i : got) {
            const Vec3 d = x - points[i].p;
            if (dot(d, d) == points[i].radius2) ++ties;
        }
        for (uint32_t i = 0; i < uint32_t(points.size()); ++i) {
            const Vec3 d = x - points[i].p;
            if (points[i].radius2 > 0.f && dot(d, d) <= points[i].radius2 && dot(points[i].normal, w) <= 0.f &&
                dot(points[i].normal, points[i].normal) > 0.f)
                ++side_rejected;
        }
    }
    std::printf("grid: %zu buckets, %zu entries, %zu points found (%zu at exactly the radius), %zu side-rejected\n",
                grid.buckets(), grid.entries(), found, ties, side_rejected);
    // The cases the test is for did occur.
    EXPECT_GT(ties, 100u);
    EXPECT_GT(side_rejected, 100u);
    EXPECT_GT(found, 10000u);
}

// Few points over a wide box: the grid hashes (more cells than buckets) and several cells share a bucket.
TEST(SppmGrid, HashedCellsEqualBruteForce) {
    std::vector<GridPoint> points = random_points(300, 0.01f, 8);
    for (GridPoint& g : points) g.p = g.p * 50.f;
    VisiblePointGrid grid;
    grid.build(points);
    Pcg32 rng(3, 1);
    size_t found = 0;
    for (int q = 0; q < 20000; ++q) {
        const GridPoint& g = points[rng.next_u32() % uint32_t(points.size())];
        const Vec3 x = g.p + Vec3(rng.next_float() - 0.5f, rng.next_float() - 0.5f, rng.next_float() - 0.5f) * 0.03f;
        const Vec3 w = normalize(Vec3(rng.next_float() - 0.5f, rng.next_float() - 0.5f, rng.next_float() - 0.5f));
        std::vector<uint32_t> got;
        grid.query(x, w, [&](uint32_t i) { got.push_back(i); });
        ASSERT_EQ(got, brute_force(points, x, w)) << "query " << q;
        found += got.size();
    }
    EXPECT_GT(found, 1000u);
}

}  // namespace
}  // namespace candela::test
