// Closed-enclosure furnaces (verification-cases.md §1, §2A): the camera inside a closed diffuse sphere.
// Tolerance 0.02 as in pbrt's analytic tests; each test also checks that the sample count makes the
// statistical error small enough (4σ < 0.02) for that tolerance to mean something.
#include <gtest/gtest.h>

#include <cmath>

#include "core/math.h"
#include "test_helpers.h"

namespace candela::test {
namespace {

// L = Le/(1−ρ): with ρ = 0.5, Le = 0.5 every pixel converges to 1. With max_bounces K the path sees
// emission at vertices 0..K+1, so the truncated value is Le·(1 − ρ^(K+2))/(1 − ρ).
TEST(Furnace, EmissiveSphereConvergesToOne) {
    MeshBuilder b;
    const uint32_t m = b.add_material(Color(0.5f), Color(0.5f));
    b.add_instance(b.add_sphere(1.f, 128, 64, m));
    const int K = 40;
    const RenderResult r = render(b.arrays(), basic_params(16, 16, 256, K));
    const double expected = 0.5 * (1.0 - std::pow(0.5, K + 2)) / 0.5;
    EXPECT_LT(4.0 * r.standard_error, 0.02) << "too few samples for the tolerance";
    EXPECT_NEAR(r.mean_rgb, expected, 0.02);
    // Every pixel sees the same value: no pixel may stray far (catches per-pixel bias like seams).
    for (size_t i = 0; i < r.rgba.size() / 4; ++i) ASSERT_NEAR(r.rgba[4 * i], expected, 0.35) << "pixel " << i;
}

// A point light of intensity I = π (Blender power 4π² W) at the centre of a sphere of albedo 0.5:
// L = ρI/(π(1−ρ)) = 1 (pbrt S1). NEE sees the light at vertices 0..K: L_K = 1 − ρ^(K+1).
TEST(Furnace, PointLightInSphereConvergesToOne) {
    MeshBuilder b;
    const uint32_t m = b.add_material(Color(0.5f), Color(0.f));
    b.add_instance(b.add_sphere(1.f, 128, 64, m));
    b.add_point_light(Vec3(0.f), Color(4.f * k_pi * k_pi));
    const int K = 40;
    const RenderResult r = render(b.arrays(), basic_params(16, 16, 256, K));
    EXPECT_LT(4.0 * r.standard_error, 0.02);
    EXPECT_NEAR(r.mean_rgb, 1.0 - std::pow(0.5, K + 1), 0.02);
}

// pbrt S2: four coincident lights of a quarter of the power each — exercises the light-selection pmf.
TEST(Furnace, FourPointLightsInSphereConvergeToOne) {
    MeshBuilder b;
    const uint32_t m = b.add_material(Color(0.5f), Color(0.f));
    b.add_instance(b.add_sphere(1.f, 128, 64, m));
    for (int i = 0; i < 4; ++i) b.add_point_light(Vec3(0.f), Color(k_pi * k_pi));
    const RenderResult r = render(b.arrays(), basic_params(16, 16, 256, 40));
    EXPECT_NEAR(r.mean_rgb, 1.0, 0.02);
}

// Direct lighting only (max_bounces = 0) truncates to exactly the first term: emission + one bounce of
// direct light: Le·(1 + ρ) = 0.75 — a test of the bounce-count convention shared with Cycles.
TEST(Furnace, MaxBouncesZeroIsDirectLightOnly) {
    MeshBuilder b;
    const uint32_t m = b.add_material(Color(0.5f), Color(0.5f));
    b.add_instance(b.add_sphere(1.f, 128, 64, m));
    const RenderResult r = render(b.arrays(), basic_params(16, 16, 256, 0));
    EXPECT_NEAR(r.mean_rgb, 0.75, 4.0 * r.standard_error + 1e-3);
}

}  // namespace
}  // namespace candela::test
