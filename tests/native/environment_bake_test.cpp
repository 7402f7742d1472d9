// The environment light's importance map follows the radiance as rendered (lights/environment_light.h, issue 22):
// with a sun of a few very bright texels in a sky of radiance ~1, the probability the sampler gives each bake cell
// must be the cell's share of ∫ luminance(L)·dω of the FILTERED image (plus the documented floor), for Linear and
// Closest interpolation and for a bake finer than the image. A bake from one value per cell (its centre) gives
// the cells around the sun the sky's weight although Linear filtering spreads a quarter of the sun's light into
// them: that χ² is astronomically large, so this test fails for it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "chi2.h"
#include "core/math.h"
#include "core/rng.h"
#include "lights/environment_light.h"
#include "shader_test_helpers.h"
#include "test_helpers.h"
#include "texture/node_math.h"

namespace candela::test {
namespace {

/// A w × h equirectangular sky of radiance ~1 (a gentle gradient) with a 2 × 1-texel sun of 160 000 and a
/// single texel of 5 000 next to it, read through an Environment Texture with the given interpolation.
struct SunEnvironment {
    ProgramBuilder b;
    uint32_t program = 0, reg = 0;
    SunEnvironment(uint32_t w, uint32_t h, TexInterpolation interpolation) {
        std::vector<Color> texels;
        for (uint32_t y = 0; y < h; ++y)
            for (uint32_t x = 0; x < w; ++x)
                texels.push_back(Color(0.8f + 0.4f * float(y) / h, 1.f, 1.2f - 0.4f * float(x) / w));
        const uint32_t sx = w * 5 / 8, sy = h * 11 / 16;  // the sun, at mid-latitude
        texels[sy * w + sx] = texels[sy * w + sx + 1] = Color(160000.f, 150000.f, 140000.f);
        texels[(sy + 1) * w + sx] = Color(5000.f);
        const uint32_t tex = b.image(w, h, texels);
        const uint32_t dir = b.op(ShaderOpCode::Coord, 0, 0, 0, {uint32_t(CoordKind::Generated)});
        reg = b.op(
            ShaderOpCode::Image, dir, 0, 0,
            {tex, uint32_t(interpolation), uint32_t(TexExtension::Repeat), uint32_t(ImageProjection::Equirectangular)});
        program = b.end_program();
    }
};

/// Pearson's χ² of observed against expected counts, cells expected below 5 pooled (Cochran's rule).
double chi2_p_value(const std::vector<double>& expected, const std::vector<double>& observed, double* statistic,
                    int* dof) {
    double chi2 = 0.0, pool_e = 0.0, pool_o = 0.0;
    int cells = 0;
    for (size_t c = 0; c < expected.size(); ++c) {
        if (expected[c] < 5.0) {
            pool_e += expected[c];
            pool_o += observed[c];
            continue;
        }
        chi2 += (observed[c] - expected[c]) * (observed[c] - expected[c]) / expected[c];
        ++cells;
    }
    if (pool_e > 0.0) {
        chi2 += (pool_o - pool_e) * (pool_o - pool_e) / pool_e;
        ++cells;
    }
    *statistic = chi2;
    *dof = cells - 1;
    return chi2_survival(chi2, *dof);
}

// For each case: the expected count of every bake cell is n·(W_c + f)/Σ(W + f) with W_c = ∫_cell luminance(L)·
// sin θ du dv by the midpoint rule on 16 × 16 points (the radiance read through the shader, so through the image's
// filter; the integrand is bilinear between texel centres times sin θ, so 16 × 16 points are accurate far beyond
// the counting noise) and f the floor of 10⁻³ of the mean weight. 2·10⁶ samples; the three cases at a
// family-wise false-alarm rate of 1 % (Šidák).
TEST(EnvironmentBake, SamplingFollowsTheFilteredRadiance) {
    struct Case {
        uint32_t w, h;
        TexInterpolation interpolation;
        const char* what;
    };
    const Case cases[] = {{64, 32, TexInterpolation::Linear, "Linear, cells = texels"},
                          {64, 32, TexInterpolation::Closest, "Closest, cells = texels"},
                          {16, 8, TexInterpolation::Linear, "Linear, 2 × 2 cells per texel"}};
    const double alpha = sidak_alpha(0.01, 3);
    for (const Case& c : cases) {
        SunEnvironment e(c.w, c.h, c.interpolation);
        const EnvironmentMap env(e.b.library(), e.program, e.reg, 1);
        const uint32_t nu = env.width(), nv = env.height();
        ASSERT_GE(nu, c.w) << c.what;
        const int sub = 16;
        std::vector<double> weight(size_t(nu) * nv, 0.0);
        double total = 0.0;
        for (uint32_t j = 0; j < nv; ++j)
            for (uint32_t i = 0; i < nu; ++i) {
                double w = 0.0;
                for (int b = 0; b < sub; ++b)
                    for (int a = 0; a < sub; ++a) {
                        const float u = (i + (a + 0.5f) / sub) / nu, v = (j + (b + 0.5f) / sub) / nv;
                        w += double(luminance(env.Le(equirectangular_to_direction(u, v)))) * std::sin(M_PI * (1.0 - v));
                    }
                weight[size_t(j) * nu + i] = w / (sub * sub);
                total += weight[size_t(j) * nu + i];
            }
        const double floor_weight = 1e-3 * total / double(weight.size());
        const uint64_t n = 2000000;
        std::vector<double> expected(weight.size()), observed(weight.size(), 0.0);
        for (size_t k = 0; k < weight.size(); ++k)
            expected[k] = double(n) * (weight[k] + floor_weight) / (total + floor_weight * double(weight.size()));
        Pcg32 rng(17, 3);
        for (uint64_t k = 0; k < n; ++k) {
            const LightSample s = env.sample({rng.next_float(), rng.next_float()});
            ASSERT_GT(s.pdf, 0.f);
            Vec2 uv = direction_to_equirectangular(s.wi);
            uv.x -= std::floor(uv.x);
            const uint32_t i = std::min(uint32_t(uv.x * nu), nu - 1), j = std::min(uint32_t(uv.y * nv), nv - 1);
            observed[size_t(j) * nu + i] += 1.0;
        }
        double statistic = 0.0;
        int dof = 0;
        const double p = chi2_p_value(expected, observed, &statistic, &dof);
        std::printf("environment bake, %s (%u × %u cells): chi2 %.1f, dof %d, p = %.4f\n", c.what, nu, nv, statistic,
                    dof, p);
        EXPECT_GT(p, alpha) << c.what;
    }
}

}  // namespace
}  // namespace candela::test
