// The closed-enclosure furnaces of furnace_test.cpp for every pixel sampler: whatever the sampler, the
// estimate must converge to the analytic value (docs/verification.md §1). Deep paths (K = 40 bounces,
// 6 dimensions per bounce) also exercise the samplers' high-dimension fallbacks.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/math.h"
#include "sampling/sampler.h"
#include "test_helpers.h"

namespace candela::test {
namespace {

class SamplerFurnace : public ::testing::TestWithParam<std::string> {};

// Emissive sphere, ρ = 0.5, Le = 0.5: L = Le(1 − ρ^(K+2))/(1 − ρ) → 1.
TEST_P(SamplerFurnace, EmissiveSphereConvergesToOne) {
    const int K = 40;
    Params p = basic_params(16, 16, 256, K);
    p.set("sampler", GetParam());
    const RenderResult r = render(furnace_scene(FurnaceScene::EmissiveSphere, 64, 32), p);
    const double expected = furnace_expected(FurnaceScene::EmissiveSphere, K);
    EXPECT_LT(4.0 * r.standard_error, 0.02) << "too few samples for the tolerance";
    EXPECT_NEAR(r.mean_rgb, expected, 0.02);
    for (size_t i = 0; i < r.rgba.size() / 4; ++i) ASSERT_NEAR(r.rgba[4 * i], expected, 0.35) << "pixel " << i;
}

// Point light of intensity π at the centre of a sphere of albedo 0.5: L = 1 − ρ^(K+1) (NEE every bounce).
TEST_P(SamplerFurnace, PointLightInSphereConvergesToOne) {
    const int K = 40;
    Params p = basic_params(16, 16, 128, K);
    p.set("sampler", GetParam());
    const RenderResult r = render(furnace_scene(FurnaceScene::PointLight, 64, 32), p);
    EXPECT_NEAR(r.mean_rgb, furnace_expected(FurnaceScene::PointLight, K), 0.02);
}

// A sample count that is neither a square nor a power of two (strata fallbacks, Hammersley with N = 27).
TEST_P(SamplerFurnace, OddSampleCount) {
    Params p = basic_params(16, 16, 27, 12);
    p.set("sampler", GetParam());
    const RenderResult r = render(furnace_scene(FurnaceScene::EmissiveSphere, 64, 32), p);
    const double expected = furnace_expected(FurnaceScene::EmissiveSphere, 12);
    EXPECT_NEAR(r.mean_rgb, expected, std::max(4.0 * r.standard_error, 0.01));
}

// Images are a pure function of (seed, pixel, sample index, dimension): thread count and tile size do not
// change a single value, for every sampler.
TEST_P(SamplerFurnace, SameImageForAnyThreadCountAndTileSize) {
    MeshBuilder b;
    const uint32_t grey = b.add_material(Color(0.7f, 0.5f, 0.3f), Color(0.f));
    const uint32_t lamp = b.add_material(Color(0.f), Color(4.f, 3.f, 2.f));
    b.add_instance(b.add_sphere(2.f, 32, 16, grey));
    b.add_instance(b.add_quad_z(-0.3f, 0.3f, -0.3f, 0.3f, -1.5f, lamp));
    b.add_point_light(Vec3(0.5f, 0.5f, -1.f), Color(20.f), 0.1f);
    auto run = [&](int threads, int tile) {
        Params p = basic_params(24, 20, 12, 8);
        p.set("sampler", GetParam());
        p.set("threads", int64_t(threads));
        p.set("tile_size", int64_t(tile));
        p.set("seed", int64_t(3));
        p.set("pixel_filter", std::string("BLACKMAN_HARRIS"));
        p.set("filter_width", 1.5);
        return render(b.arrays(), p);
    };
    const RenderResult a = run(1, 32), c = run(2, 8);
    ASSERT_EQ(a.rgba.size(), c.rgba.size());
    for (size_t i = 0; i < a.rgba.size(); ++i) ASSERT_EQ(a.rgba[i], c.rgba[i]) << "value " << i;
}

INSTANTIATE_TEST_SUITE_P(AllSamplers, SamplerFurnace, ::testing::ValuesIn(sampler_names()),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

}  // namespace
}  // namespace candela::test
