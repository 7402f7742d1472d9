// Every integrator of issue 15 (LIGHT, BDPT and the three path generators, alone and combined by MIS) against PATH
// on the four reference scenes (reference_scenes.h): the Cornell box, Veach's MIS scene with two bounces, a glass
// sphere's caustic under a small light, and the low-poly smooth-shaded sphere. They all estimate the same image, so
// each must equal PATH within noise.
//
// Agreement (agreement.h): 12 seeds per integrator, t-statistics with 22 degrees of freedom; the image mean within 4
// (two-sided false alarm 6e-4 per comparison), every 4×4 block within 6 (5e-6 per block). This file makes 32
// comparisons of about 30 blocks each (~1000 blocks): a family-wise false-alarm rate of about 2.5 %.
//
// PATH is rendered once per scene; the cost of each integrator's sample differs, so each gets a sample
// count that keeps its noise comparable to PATH's.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "agreement.h"
#include "reference_scenes.h"
#include "scene/scene.h"

namespace candela::test {
namespace {

constexpr int k_seeds = 12;

struct Config {
    const char* integrator;
    bool generators_mis;
    int samples;
};

const Config k_configs[] = {
    {"LIGHT", false, 64},
    {"BDPT", false, 16},
    {"SURFACE_SAMPLING", false, 32},
    {"SOURCE_SHOOTING", false, 32},
    {"RECEIVER_GATHERING", false, 32},
    {"SURFACE_SAMPLING", true, 16},
    {"SOURCE_SHOOTING", true, 16},
    {"RECEIVER_GATHERING", true, 16},
};

struct Case {
    SceneArrays arrays;
    Params base;
};

Params room_params(int w, int h, int max_bounces) {
    Params p = basic_params(w, h, 0, max_bounces);
    p.set("threads", int64_t(2));
    p.set("pixel_filter", std::string("BLACKMAN_HARRIS"));
    p.set("filter_width", 1.5);
    p.set("rr_start_bounce", int64_t(2));
    return p;
}

Case make_case(const std::string& name) {
    if (name == "cornell") return {cornell_box(), room_params(20, 20, 5)};
    if (name == "caustic") return {glass_caustic(), room_params(24, 18, 6)};
    if (name == "lowpoly") return {smooth_lowpoly_sphere(), room_params(24, 18, 3)};
    std::vector<float> camera;
    SceneArrays arrays = veach_scene(&camera);
    Params p = veach_params(32, 18);
    p.set("max_bounces", int64_t(2));
    p.set("threads", int64_t(2));
    return {std::move(arrays), p};
}

/// Pixels that see no delta-scattering surface within `margin` pixels of their centre: LIGHT cannot render what the
/// camera sees only through mirrors and glass (a light path cannot connect to the camera through a delta lobe), so
/// it is compared with PATH elsewhere.
std::vector<uint8_t> no_specular_mask(const Case& c, int margin) {
    const PreparedScene prepared(c.arrays, c.base);
    const Scene& scene = prepared.scene();
    const int w = scene.camera().full_width(), h = scene.camera().full_height();
    std::vector<uint8_t> sees(size_t(w) * h, 0), mask(size_t(w) * h, 1);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            SurfaceHit hit;
            const Ray ray = scene.camera().generate_ray({x + 0.5f, y + 0.5f});
            sees[size_t(y) * w + x] =
                scene.intersect(ray, &hit) && (scene.material_flags(hit.material) & k_bsdf_specular);
        }
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int dy = -margin; dy <= margin; ++dy)
                for (int dx = -margin; dx <= margin; ++dx) {
                    const int sx = x + dx, sy = y + dy;
                    if (sx >= 0 && sy >= 0 && sx < w && sy < h && sees[size_t(sy) * w + sx])
                        mask[size_t(y) * w + x] = 0;
                }
    return mask;
}

class ReferenceScene : public ::testing::TestWithParam<std::string> {};

TEST_P(ReferenceScene, EveryIntegratorEqualsPathTracing) {
    const std::string scene = GetParam();
    const Case c = make_case(scene);
    Params ref = c.base;
    ref.set("integrator", std::string("PATH"));
    ref.set("samples", int64_t(64));
    const std::vector<RenderResult> path = render_seeds(c.arrays, ref, k_seeds);
    for (const Config& config : k_configs) {
        Params p = c.base;
        p.set("integrator", std::string(config.integrator));
        p.set("samples", int64_t(config.samples));
        if (config.generators_mis) p.set("generators_mis", true);
        const bool light_tracing = std::string(config.integrator) == "LIGHT";
        const std::vector<uint8_t> mask = light_tracing ? no_specular_mask(c, 2) : std::vector<uint8_t>();
        const Agreement g =
            compare_seed_sets(render_seeds(c.arrays, p, k_seeds), path, 4, light_tracing ? &mask : nullptr);
        const std::string what = scene + " " + config.integrator + (config.generators_mis ? " + MIS" : "");
        EXPECT_GT(g.mean_b, 0.0) << what;
        EXPECT_LT(std::fabs(g.mean_z), 4.0) << what << ": mean " << g.mean_a << ", PATH " << g.mean_b;
        EXPECT_LT(std::fabs(g.worst_block_z), 6.0) << what << ": block " << g.worst_block << " of " << g.blocks;
    }
}

INSTANTIATE_TEST_SUITE_P(Issue15, ReferenceScene, ::testing::Values("cornell", "veach", "caustic", "lowpoly"),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

}  // namespace
}  // namespace candela::test
