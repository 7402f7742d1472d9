// The Nishita sky's sun disc as a sampling strategy of the environment light (lights/environment_light.h): the
// mixture of the disc's cone and the baked map must sample with the density it reports (sample/pdf estimates of
// known solid angles), and the disc must carry what it shows.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <vector>

#include "core/math.h"
#include "core/rng.h"
#include "lights/environment_light.h"
#include "shader_test_helpers.h"
#include "texture/sky.h"

namespace candela {
namespace {

using test::ProgramBuilder;

/// A world program: the Nishita sky of the view direction, sun at elevation 40°, rotation 30°, disc `size` wide.
struct SkyWorld {
    ProgramBuilder b;
    uint32_t program = 0, reg = 0;
    explicit SkyWorld(float size_deg, bool disc = true) {
        const uint32_t offset = uint32_t(b.consts.size());
        const float state[9] = {40.f * k_pi / 180.f, 30.f * k_pi / 180.f,     0.f, 1.f, 1.f, 1.f,
                                disc ? 1.f : 0.f,    size_deg * k_pi / 180.f, 1.f};
        b.consts.insert(b.consts.end(), state, state + 9);
        const uint32_t dir = b.op(ShaderOpCode::Coord, 0, 0, 0, {uint32_t(CoordKind::Generated)});
        reg = b.op(ShaderOpCode::Sky, dir, 0, 0, {offset, uint32_t(SkyModel::Nishita), 0, 0});
        program = b.end_program();
    }
};

TEST(SunDisc, ShaderLibraryReportsTheDiscOfAPlainSky) {
    SkyWorld w(4.f);
    const auto lib = w.b.library();
    Vec3 sun;
    float half = 0.f;
    ASSERT_TRUE(lib->sun_disc(w.program, &sun, &half));
    EXPECT_NEAR(half, 2.f * k_pi / 180.f, 1e-6f);
    EXPECT_NEAR(sun.z, std::sin(40.f * k_pi / 180.f), 1e-5f);
    EXPECT_NEAR(std::atan2(sun.x, sun.y), 30.f * k_pi / 180.f, 1e-5f);
    // The radiance inside the disc is the sun's, far above the sky just outside it.
    const Vec3 inside = test::eval(*lib, w.program, w.reg, ShadingInputs::world(sun));
    const Vec3 off = normalize(sun + Vec3(0.f, 0.f, 0.1f));
    const Vec3 outside = test::eval(*lib, w.program, w.reg, ShadingInputs::world(off));
    EXPECT_GT(luminance(inside), 100.f * luminance(outside));
    SkyWorld none(4.f, false);
    EXPECT_FALSE(none.b.library()->sun_disc(none.program, &sun, &half));
}

TEST(SunDisc, SampledPdfEqualsEvaluatedPdf) {
    SkyWorld w(3.f);
    const EnvironmentMap env(w.b.library(), w.program, w.reg, 1);
    Pcg32 rng(3, 9);
    int in_disc = 0;
    for (int k = 0; k < 4000; ++k) {
        const LightSample s = env.sample({rng.next_float(), rng.next_float()});
        ASSERT_GT(s.pdf, 0.f);
        EXPECT_NEAR(env.pdf(s.wi), s.pdf, 2e-3f * s.pdf);
        in_disc += luminance(s.Li) > 1e3f;
    }
    // The disc holds most of the power of a clear sky: most samples go there, not a share of cells.
    EXPECT_GT(in_disc, 2000);
}

TEST(SunDisc, SampleOverPdfMeasuresSolidAngles) {
    // For a sampler with density p, E[1_R(ω)/p(ω)] = |R| for every region R it covers. Regions around the disc
    // (the cone, two rings, the hemispheres) of known solid angle: each estimate within 4.4 standard errors
    // (false alarm 10⁻⁵ per region). (chi2.h's quadrature cannot follow the map's per-cell steps; the map alone
    // is χ²-tested in environment_test.cpp over its own (u, v) cells.)
    SkyWorld w(6.f);
    const EnvironmentMap env(w.b.library(), w.program, w.reg, 1);
    Vec3 sun;
    float half = 0.f;
    ASSERT_TRUE(w.b.library()->sun_disc(w.program, &sun, &half));
    auto cap = [](float angle) { return 2.0 * k_pi * (1.0 - std::cos(double(angle))); };
    struct Region {
        const char* name;
        std::function<bool(const Vec3&)> in;
        double solid_angle;
    };
    const std::vector<Region> regions = {
        {"disc", [&](const Vec3& d) { return dot(d, sun) >= std::cos(half); }, cap(half)},
        {"ring 1-2",
         [&](const Vec3& d) {
             const float c = dot(d, sun);
             return c < std::cos(half) && c >= std::cos(2.f * half);
         },
         cap(2.f * half) - cap(half)},
        {"ring 2-8",
         [&](const Vec3& d) {
             const float c = dot(d, sun);
             return c < std::cos(2.f * half) && c >= std::cos(8.f * half);
         },
         cap(8.f * half) - cap(2.f * half)},
        {"upper", [](const Vec3& d) { return d.z >= 0.f; }, 2.0 * k_pi},
        {"lower", [](const Vec3& d) { return d.z < 0.f; }, 2.0 * k_pi},
    };
    constexpr int n = 400000;
    std::vector<double> sum(regions.size(), 0.0), sum2(regions.size(), 0.0);
    Pcg32 rng(11, 4);
    for (int k = 0; k < n; ++k) {
        const LightSample s = env.sample({rng.next_float(), rng.next_float()});
        if (!(s.pdf > 0.f)) continue;
        for (size_t r = 0; r < regions.size(); ++r)
            if (regions[r].in(s.wi)) {
                sum[r] += 1.0 / s.pdf;
                sum2[r] += 1.0 / (double(s.pdf) * s.pdf);
            }
    }
    for (size_t r = 0; r < regions.size(); ++r) {
        const double mean = sum[r] / n, var = (sum2[r] / n - mean * mean) / n;
        std::printf("sun disc mixture, %-8s: %.6g (exact %.6g) ± %.2g\n", regions[r].name, mean, regions[r].solid_angle,
                    std::sqrt(var));
        EXPECT_NEAR(mean, regions[r].solid_angle, 4.4 * std::sqrt(var) + 1e-9) << regions[r].name;
    }
}

}  // namespace
}  // namespace candela
