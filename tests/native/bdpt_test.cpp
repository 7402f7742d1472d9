// BDPT (bidirectional path tracing, integrators/bdpt/) against PATH: the same image within noise on scenes with every
// light type, delta lobes (a glass caustic, a mirror), tilted shading normals and an orthographic camera without a
// light-tracing strategy; the closed-sphere furnaces against their closed forms (docs/verification.md §1).
//
// Agreement (agreement.h): 12 seeds per integrator, t-statistics with 22 degrees of freedom; the image mean within
// 4 (two-sided false alarm 6e-4 per comparison), every 4×4 block within 6 (5e-6 per block). Over this file's ~12
// comparisons and ~300 blocks the family-wise false-alarm rate is below 1 %.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "agreement.h"
#include "core/math.h"
#include "lights/light.h"
#include "reference_scenes.h"

namespace candela::test {
namespace {

constexpr int k_seeds = 12;

Params base_params(int w, int h) {
    Params p = basic_params(w, h, 0, 5);
    p.set("threads", int64_t(2));
    p.set("pixel_filter", std::string("BLACKMAN_HARRIS"));
    p.set("filter_width", 1.5);
    p.set("rr_start_bounce", int64_t(2));
    return p;
}

void expect_agree(const SceneArrays& arrays, const Params& base, const std::string& what, int bdpt_samples = 24,
                  int path_samples = 48) {
    Params a = base, b = base;
    a.set("integrator", std::string("BDPT"));
    a.set("samples", int64_t(bdpt_samples));
    b.set("integrator", std::string("PATH"));
    b.set("samples", int64_t(path_samples));
    const Agreement g = compare_seed_sets(render_seeds(arrays, a, k_seeds), render_seeds(arrays, b, k_seeds), 4);
    EXPECT_GT(g.mean_b, 0.0) << what;
    EXPECT_LT(std::fabs(g.mean_z), 4.0) << what << ": BDPT mean " << g.mean_a << ", PATH " << g.mean_b;
    EXPECT_LT(std::fabs(g.worst_block_z), 6.0) << what << ": block " << g.worst_block << " of " << g.blocks;
}

TEST(Bdpt, EqualsPathTracingWithPointSpotAndSoftPointLights) {
    expect_agree(lit_room(1 | 2 | 4, false), base_params(24, 18), "points");
}
TEST(Bdpt, EqualsPathTracingWithSuns) {
    expect_agree(lit_room(8 | 16 | 256, false), base_params(24, 18), "suns and world");
}
TEST(Bdpt, EqualsPathTracingWithAreaLightsAndEmissiveTriangles) {
    // Hittable lights: PATH finds the caustics through the glass and the mirror too.
    expect_agree(lit_room(32 | 64 | 128 | 256, true), base_params(24, 18), "area lights, a triangle, glass, a mirror");
}
TEST(Bdpt, EqualsPathTracingWithAThinLensAndAnOrthographicCamera) {
    Params lens = base_params(20, 16);
    lens.set("use_dof", true);
    lens.set("focus_distance", 2.f);
    lens.set("aperture_fstop", 0.8f);
    lens.set("aperture_blades", int64_t(6));
    expect_agree(lit_room(1 | 32, false), lens, "thin lens");
    Params ortho = base_params(20, 16);
    ortho.set("camera_type", std::string("ORTHO"));  // no t = 1 strategy: the others carry everything
    ortho.set("ortho_scale", 4.f);
    expect_agree(lit_room(1 | 32, false), ortho, "orthographic pinhole");
}

TEST(Bdpt, ClosedSphereFurnaces) {
    // 12 seeds: the spread of their means gives the standard error (t with 11 degrees of freedom: 5 has a two-sided
    // false-alarm probability of 4e-4).
    for (FurnaceScene kind : {FurnaceScene::EmissiveSphere, FurnaceScene::PointLight}) {
        Params p = basic_params(8, 6, 64, 5);
        p.set("integrator", std::string("BDPT"));
        p.set("rr_mode", std::string("OFF"));
        p.set("threads", int64_t(2));
        const SeedMean m = seed_mean(render_seeds(furnace_scene(kind, 128, 64), p, 12));
        // The UV sphere's area is below the true sphere's: the point light's answer scales with it (test_helpers.h).
        const double expected =
            furnace_expected(kind, 5) * (kind == FurnaceScene::PointLight ? 1.0 + furnace_facet_bias(128, 64) : 1.0);
        EXPECT_NEAR(m.mean, expected, 5.0 * m.standard_error + 1e-6) << int(kind);
    }
}

}  // namespace
}  // namespace candela::test
