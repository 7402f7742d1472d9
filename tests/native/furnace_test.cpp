// Closed-enclosure furnaces (docs/verification.md §1): the camera inside a closed diffuse sphere.
// Tolerance 0.02 as in pbrt's analytic tests; each test also checks that the sample count makes the
// statistical error small enough (4σ < 0.02) for that tolerance to mean something.
#include <gtest/gtest.h>

#include "test_helpers.h"

namespace candela::test {
namespace {

// L = Le/(1−ρ): with ρ = 0.5, Le = 0.5 every pixel converges to 1 (truncated: furnace_expected).
TEST(Furnace, EmissiveSphereConvergesToOne) {
    const int K = 40;
    const RenderResult r = render(furnace_scene(FurnaceScene::EmissiveSphere), basic_params(16, 16, 256, K));
    const double expected = furnace_expected(FurnaceScene::EmissiveSphere, K);
    EXPECT_LT(4.0 * r.standard_error, 0.02) << "too few samples for the tolerance";
    EXPECT_NEAR(r.mean_rgb, expected, 0.02);
    // Every pixel sees the same value: no pixel may stray far (catches per-pixel bias like seams).
    for (size_t i = 0; i < r.rgba.size() / 4; ++i) ASSERT_NEAR(r.rgba[4 * i], expected, 0.35) << "pixel " << i;
}

// A point light of intensity I = π (Blender power 4π² W) at the centre of a sphere of albedo 0.5:
// L = ρI/(π(1−ρ)) = 1 (pbrt S1). NEE sees the light at vertices 0..K: L_K = 1 − ρ^(K+1).
TEST(Furnace, PointLightInSphereConvergesToOne) {
    const int K = 40;
    const RenderResult r = render(furnace_scene(FurnaceScene::PointLight), basic_params(16, 16, 256, K));
    EXPECT_LT(4.0 * r.standard_error, 0.02);
    EXPECT_NEAR(r.mean_rgb, furnace_expected(FurnaceScene::PointLight, K), 0.02);
}

// pbrt S2 with unequal powers: four coincident lights sharing the power — exercises the light-selection pmf.
TEST(Furnace, FourPointLightsInSphereConvergeToOne) {
    const RenderResult r = render(furnace_scene(FurnaceScene::FourPointLights), basic_params(16, 16, 256, 40));
    EXPECT_NEAR(r.mean_rgb, furnace_expected(FurnaceScene::FourPointLights, 40), 0.02);
}

// Direct lighting only (max_bounces = 0) truncates to exactly the first term: emission + one bounce of
// direct light: Le·(1 + ρ) = 0.75 — a test of the bounce-count convention shared with Cycles.
TEST(Furnace, MaxBouncesZeroIsDirectLightOnly) {
    const RenderResult r = render(furnace_scene(FurnaceScene::EmissiveSphere), basic_params(16, 16, 256, 0));
    EXPECT_NEAR(r.mean_rgb, 0.75, 4.0 * r.standard_error + 1e-3);
}

}  // namespace
}  // namespace candela::test
