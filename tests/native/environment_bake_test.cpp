// The environment light's importance maps follow the radiance as rendered (lights/environment_bake.h, issue 22):
// with a sun of a few very bright texels in a sky of radiance ~1, the sampled directions must be distributed as
// (L + floor)·dω with L the FILTERED image — piecewise bilinear between texel centres for Linear, constant on
// texels for Closest — counted on a grid of cells against that integral. A map from one value per cell (its
// centre, piecewise constant) gives the cells around the sun the sky's weight although Linear filtering spreads a
// quarter of the sun's light into them: the test is run on it too and must reject it. The MIS-compensated map
// (radiance less its mean, clamped at 0) must be a density (integrate to 1, sampled pdf = evaluated pdf), and
// next-event estimation from it combined with cosine sampling by MIS must estimate the irradiance without bias —
// and be seen biased if the BSDF side weighs with the plain map's pdf.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "chi2.h"
#include "core/math.h"
#include "core/rng.h"
#include "integrators/common/mis.h"
#include "lights/environment_light.h"
#include "sampling/distribution_2d.h"
#include "sampling/warp.h"
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
    SunEnvironment(uint32_t w, uint32_t h, TexInterpolation interpolation, float sun = 160000.f, bool rotated = false) {
        std::vector<Color> texels;
        for (uint32_t y = 0; y < h; ++y)
            for (uint32_t x = 0; x < w; ++x)
                texels.push_back(Color(0.8f + 0.4f * float(y) / h, 1.f, 1.2f - 0.4f * float(x) / w));
        const uint32_t sx = w * 5 / 8, sy = h * 11 / 16;  // the sun, at mid-latitude
        texels[sy * w + sx] = texels[sy * w + sx + 1] = Color(1.f, 0.9375f, 0.875f) * sun;
        texels[(sy + 1) * w + sx] = Color(sun / 32.f);
        const uint32_t tex = b.image(w, h, texels);
        uint32_t dir = b.op(ShaderOpCode::Coord, 0, 0, 0, {uint32_t(CoordKind::Generated)});
        if (rotated) {  // a Mapping node turning the world by 30° about Z: the texel grid leaves the map's
            const float c = std::cos(0.5236f), s = std::sin(0.5236f);
            const uint32_t offset = uint32_t(b.consts.size());
            b.consts.insert(b.consts.end(), {c, -s, 0, 0, s, c, 0, 0, 0, 0, 1, 0});
            dir = b.op(ShaderOpCode::Mapping, dir, 0, 0, {offset, 1});
        }
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

/// Expected counts of n samples on an nu × nv grid of (u, v) cells: n·W_c/ΣW, W_c = ∫_cell (luminance(L) + floor)·
/// sin θ du dv by the midpoint rule on 16 × 16 points (the radiance read through the shader, so through the image's
/// filter; the integrand is bilinear between texel centres times sin θ, so 16 × 16 points per texel are accurate
/// far beyond the counting noise), floor = 10⁻³ of the mean luminance (the plain map's documented floor).
std::vector<double> filtered_expected(const EnvironmentMap& env, uint32_t nu, uint32_t nv, uint64_t n) {
    const int sub = 16;
    const double floor_radiance = 1e-3 * double(luminance(env.mean_radiance()));
    std::vector<double> weight(size_t(nu) * nv, 0.0);
    double total = 0.0;
    for (uint32_t j = 0; j < nv; ++j)
        for (uint32_t i = 0; i < nu; ++i) {
            double w = 0.0;
            for (int b = 0; b < sub; ++b)
                for (int a = 0; a < sub; ++a) {
                    const float u = (i + (a + 0.5f) / sub) / nu, v = (j + (b + 0.5f) / sub) / nv;
                    w += (double(luminance(env.Le(equirectangular_to_direction(u, v)))) + floor_radiance) *
                         std::sin(M_PI * (1.0 - v));
                }
            weight[size_t(j) * nu + i] = w;
            total += w;
        }
    for (double& w : weight) w *= double(n) / total;
    return weight;
}

/// χ² p-value of n draws of `sample_uv` (→ (u, v)) against `expected` on the nu × nv grid.
template <class SampleUv>
double chi2_on_grid(const std::vector<double>& expected, uint32_t nu, uint32_t nv, uint64_t n, SampleUv&& sample_uv,
                    const char* what) {
    std::vector<double> observed(expected.size(), 0.0);
    Pcg32 rng(17, 3);
    for (uint64_t k = 0; k < n; ++k) {
        const Vec2 uv = sample_uv(Vec2{rng.next_float(), rng.next_float()});
        const uint32_t i = std::min(uint32_t(uv.x * nu), nu - 1), j = std::min(uint32_t(uv.y * nv), nv - 1);
        observed[size_t(j) * nu + i] += 1.0;
    }
    double statistic = 0.0;
    int dof = 0;
    const double p = chi2_p_value(expected, observed, &statistic, &dof);
    std::printf("environment sampling, %s (%u × %u cells): chi2 %.1f, dof %d, p = %.3g\n", what, nu, nv, statistic, dof,
                p);
    return p;
}

/// The (u, v) of a sampled direction.
Vec2 uv_of(const LightSample& s) {
    Vec2 uv = direction_to_equirectangular(s.wi);
    uv.x -= std::floor(uv.x);
    return uv;
}

// 2·10⁶ samples per case; the three cases at a family-wise false-alarm rate of 1 % (Šidák). Cells: the texels, and
// for the coarse image 2 × 2 cells per texel (the bilinear ramp inside a texel is then resolved too).
TEST(EnvironmentBake, SamplingFollowsTheFilteredRadiance) {
    struct Case {
        uint32_t w, h, cells_per_texel;
        TexInterpolation interpolation;
        const char* what;
    };
    const Case cases[] = {{64, 32, 1, TexInterpolation::Linear, "Linear, cells = texels"},
                          {64, 32, 1, TexInterpolation::Closest, "Closest, cells = texels"},
                          {16, 8, 2, TexInterpolation::Linear, "Linear, 2 × 2 cells per texel"}};
    const double alpha = sidak_alpha(0.01, 4);
    const uint64_t n = 2000000;
    for (const Case& c : cases) {
        SunEnvironment e(c.w, c.h, c.interpolation);
        const EnvironmentMap env(e.b.library(), e.program, e.reg, 1);
        EXPECT_EQ(env.bilinear(), c.interpolation == TexInterpolation::Linear) << c.what;
        const uint32_t nu = c.w * c.cells_per_texel, nv = c.h * c.cells_per_texel;
        const std::vector<double> expected = filtered_expected(env, nu, nv, n);
        const double p = chi2_on_grid(
            expected, nu, nv, n,
            [&](Vec2 u) {
                const LightSample s = env.sample(u);
                EXPECT_GT(s.pdf, 0.f);
                return uv_of(s);
            },
            c.what);
        EXPECT_GT(p, alpha) << c.what;
    }
}

// A rotated image (a Mapping node before the Environment Texture) is not bilinear on the map's grid: it gets the
// integrated piecewise-constant map (the fourth member of the family above). Its density is constant inside a
// 64 × 32 cell while the rotated radiance is not, so the χ² is counted on a coarser 16 × 8 grid in which the map's
// cells nest: only each cell's 2 × 2-point integral enters, not the shape inside it.
TEST(EnvironmentBake, ARotatedImageGetsTheIntegratedMap) {
    SunEnvironment e(64, 32, TexInterpolation::Linear, 160000.f, true);
    const EnvironmentMap env(e.b.library(), e.program, e.reg, 1);
    EXPECT_FALSE(env.bilinear());
    const uint64_t n = 2000000;
    const std::vector<double> expected = filtered_expected(env, 16, 8, n);
    const double p = chi2_on_grid(
        expected, 16, 8, n, [&](Vec2 u) { return uv_of(env.sample(u)); }, "Linear, rotated");
    EXPECT_GT(p, sidak_alpha(0.01, 4));
}

// The test can fail: the density of the old map — one value per texel, its centre's (L + floor)·sin θ, piecewise
// constant — drawn through the same harness on the Linear sun must be rejected (p below 10⁻⁶).
TEST(EnvironmentBake, TheCentreValuedMapFailsTheLinearTest) {
    const uint32_t w = 64, h = 32;
    SunEnvironment e(w, h, TexInterpolation::Linear);
    const EnvironmentMap env(e.b.library(), e.program, e.reg, 1);
    const float floor_radiance = 1e-3f * luminance(env.mean_radiance());
    std::vector<float> centre(size_t(w) * h);
    for (uint32_t j = 0; j < h; ++j)
        for (uint32_t i = 0; i < w; ++i) {
            const float u = (i + 0.5f) / w, v = (j + 0.5f) / h;
            centre[size_t(j) * w + i] = (luminance(env.Le(equirectangular_to_direction(u, v))) + floor_radiance) *
                                        std::sin(float(M_PI) * (1.f - v));
        }
    const Distribution2D wrong(centre, w, h);
    const uint64_t n = 2000000;
    const std::vector<double> expected = filtered_expected(env, w, h, n);
    const double p = chi2_on_grid(
        expected, w, h, n,
        [&](Vec2 u) {
            float pdf = 0.f;
            return wrong.sample(u, &pdf);
        },
        "centre-valued map (wrong)");
    EXPECT_LT(p, 1e-6);
}

/// ∫ pdf(d) dω = ∫∫ pdf(ω(u, v))·2π² sin θ du dv by the midpoint rule on 8 × 8 points per texel: the integrand is
/// bilinear times sin θ (Linear) or constant (Closest) on sub-cells, so the rule's error is O((π/8h)²/24) < 10⁻⁵.
double integral_of_pdf(const EnvironmentMap& env, bool compensated, uint32_t w, uint32_t h) {
    const uint32_t nu = 8 * w, nv = 8 * h;
    double sum = 0.0;
    for (uint32_t j = 0; j < nv; ++j) {
        const double v = (j + 0.5) / nv, jac = 2.0 * M_PI * M_PI * std::sin(M_PI * (1.0 - v));
        for (uint32_t i = 0; i < nu; ++i)
            sum += env.pdf(equirectangular_to_direction(float((i + 0.5) / nu), float(v)), compensated) * jac;
    }
    return sum / (double(nu) * nv);
}

TEST(EnvironmentBake, BothMapsAreDensitiesSampledWithTheirEvaluatedPdf) {
    for (TexInterpolation interpolation : {TexInterpolation::Linear, TexInterpolation::Closest})
        for (bool compensated : {false, true}) {
            const char* what = interpolation == TexInterpolation::Linear ? "Linear" : "Closest";
            SunEnvironment e(64, 32, interpolation);
            const EnvironmentMap env(e.b.library(), e.program, e.reg, 1);
            const double integral = integral_of_pdf(env, compensated, 64, 32);
            std::printf("%s, %s map: ∫ pdf dω = %.6f\n", what, compensated ? "compensated" : "plain", integral);
            EXPECT_NEAR(integral, 1.0, 1e-3) << what << " compensated " << compensated;
            Pcg32 rng(5, 9);
            for (int k = 0; k < 20000; ++k) {
                const LightSample s = env.sample({rng.next_float(), rng.next_float()}, compensated);
                if (!s.valid()) continue;
                EXPECT_NEAR(env.pdf(s.wi, compensated), s.pdf, 2e-3f * s.pdf) << what << " compensated " << compensated;
                // The compensated map only draws directions brighter than the mean (up to the bilinear blend
                // of a bright knot with its neighbours).
            }
            // The compensated density is 0 on the dim sky (L ≈ 1 < mean), the plain one is not.
            const Vec3 sky = equirectangular_to_direction(0.1f, 0.3f);
            if (compensated)
                EXPECT_EQ(env.pdf(sky, true), 0.f) << what;
            else
                EXPECT_GT(env.pdf(sky, false), 0.f) << what;
        }
}

/// Irradiance at an upward-facing point under the Linear sun: NEE from the compensated map and cosine sampling,
/// combined by the power heuristic (one sample of each per estimate). `bsdf_side_plain`: the wrong input — the cosine
/// sample's MIS weight takes the plain map's pdf, so the weights no longer sum to 1 and the estimate is biased.
struct MisEstimate {
    double mean, standard_error;
};
MisEstimate mis_irradiance(const EnvironmentMap& env, bool bsdf_side_plain, uint64_t n) {
    Pcg32 rng(23, 1);
    const Vec3 normal(0.f, 0.f, 1.f);
    double sum = 0.0, sum2 = 0.0;
    for (uint64_t k = 0; k < n; ++k) {
        double x = 0.0;
        const LightSample s = env.sample({rng.next_float(), rng.next_float()}, true);
        if (s.valid() && dot(s.wi, normal) > 0.f) {
            const float cos_t = dot(s.wi, normal), pb = cosine_hemisphere_pdf(cos_t);
            x += double(luminance(s.Li)) * cos_t / s.pdf * mis_weight(MisHeuristic::Power, s.pdf, pb);
        }
        const Vec3 d = sample_cosine_hemisphere({rng.next_float(), rng.next_float()});
        const float pb = cosine_hemisphere_pdf(d.z);
        if (pb > 0.f) {
            const float pl = env.pdf(d, !bsdf_side_plain);
            x += double(luminance(env.Le(d))) * d.z / pb * mis_weight(MisHeuristic::Power, pb, pl);
        }
        sum += x;
        sum2 += x * x;
    }
    const double mean = sum / double(n);
    return {mean, std::sqrt(std::max(sum2 / double(n) - mean * mean, 0.0) / double(n))};
}

// Reference: ∫ luminance(L)·cos⁺ dω by the midpoint rule on 16 × 16 points per texel (accurate to < 10⁻⁴ relative).
// The right estimator must agree within 4σ (false-alarm rate 6·10⁻⁵ per case), under the 160 000 sun and under a
// sun of 50 (where the sky carries most of the irradiance and the compensated map is 0 over half of it); there the
// wrong weights must miss by more than 10σ.
TEST(EnvironmentBake, CompensatedNextEventEstimationWithMisIsUnbiased) {
    const uint32_t w = 64, h = 32;
    for (float sun : {160000.f, 50.f}) {
        SunEnvironment e(w, h, TexInterpolation::Linear, sun);
        const EnvironmentMap env(e.b.library(), e.program, e.reg, 1);
        const uint32_t nu = 16 * w, nv = 16 * h;
        double reference = 0.0;
        for (uint32_t j = 0; j < nv; ++j) {
            const double v = (j + 0.5) / nv, dw = 2.0 * M_PI * M_PI * std::sin(M_PI * (1.0 - v)) / (double(nu) * nv);
            for (uint32_t i = 0; i < nu; ++i) {
                const Vec3 d = equirectangular_to_direction(float((i + 0.5) / nu), float(v));
                if (d.z > 0.f) reference += double(luminance(env.Le(d))) * d.z * dw;
            }
        }
        const uint64_t n = 400000;
        const MisEstimate right = mis_irradiance(env, false, n), wrong = mis_irradiance(env, true, n);
        std::printf("MIS irradiance, sun %g: reference %.4f, compensated %.4f ± %.4f, wrong weights %.4f ± %.4f\n", sun,
                    reference, right.mean, right.standard_error, wrong.mean, wrong.standard_error);
        EXPECT_NEAR(right.mean, reference, 4.0 * right.standard_error) << sun;
        if (sun < 100.f) {
            EXPECT_GT(std::fabs(wrong.mean - reference), 10.0 * wrong.standard_error);
        }
    }
}

}  // namespace
}  // namespace candela::test
