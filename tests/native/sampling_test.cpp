#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "core/math.h"
#include "core/rng.h"
#include "sampling/distribution_1d.h"
#include "sampling/sampler.h"
#include "sampling/warp.h"

namespace candela {
namespace {

// pbrt-v3 Distribution1D.Discrete (docs/verification.md §4.5): f = {0, 1, 0, 3}.
TEST(Distribution1D, DiscreteMatchesPbrtTable) {
    const Distribution1D d({0.f, 1.f, 0.f, 3.f});
    float pmf, u;
    EXPECT_FLOAT_EQ(d.pmf(0), 0.f);
    EXPECT_FLOAT_EQ(d.pmf(1), 0.25f);
    EXPECT_FLOAT_EQ(d.pmf(3), 0.75f);
    EXPECT_EQ(d.sample_discrete(0.f, &pmf), 1u);
    EXPECT_FLOAT_EQ(pmf, 0.25f);
    EXPECT_EQ(d.sample_discrete(0.125f, &pmf, &u), 1u);
    EXPECT_NEAR(u, 0.5f, 1e-6f);
    EXPECT_EQ(d.sample_discrete(0.24999f), 1u);
    EXPECT_EQ(d.sample_discrete(0.250001f), 3u);
    EXPECT_EQ(d.sample_discrete(0.625f, &pmf, &u), 3u);
    EXPECT_NEAR(u, 0.5f, 1e-6f);
    EXPECT_EQ(d.sample_discrete(k_one_minus_epsilon), 3u);
    EXPECT_EQ(d.sample_discrete(1.f), 3u);
    // Zero bins are never chosen, even right at their edges.
    for (float v = 0.25f - 20e-8f; v < 0.25f + 20e-8f; v = std::nextafter(v, 1.f)) EXPECT_NE(d.sample_discrete(v), 2u);
}

TEST(Distribution1D, ContinuousMatchesPbrtTable) {
    const Distribution1D d({1.f, 1.f, 2.f, 4.f, 8.f});
    float pdf;
    EXPECT_FLOAT_EQ(d.sample_continuous(0.f, &pdf), 0.f);
    EXPECT_NEAR(pdf, 5.f / 16.f, 1e-6f);
    EXPECT_NEAR(d.sample_continuous(0.5f), 0.8f, 1e-6f);
    EXPECT_NEAR(d.sample_continuous(0.75f, &pdf), 0.9f, 1e-6f);
    EXPECT_NEAR(pdf, 5.f * 8.f / 16.f, 1e-5f);
}

TEST(Distribution1D, RejectsNegativeWeights) { EXPECT_THROW(Distribution1D({1.f, -1.f}), InvalidScene); }

// Monte Carlo checks of warps against their densities: E[g(X)/pdf(X)] = ∫g. The tolerance is 5 standard
// errors of the estimator, measured from the same samples.
template <typename Sample, typename Pdf, typename G>
void expect_integral(Sample sample, Pdf pdf, G g, double expected) {
    Pcg32 rng(1, 2);
    const int n = 200000;
    double sum = 0, sum_sq = 0;
    for (int i = 0; i < n; ++i) {
        const Vec3 w = sample(Vec2{rng.next_float(), rng.next_float()});
        const double v = g(w) / pdf(w);
        sum += v;
        sum_sq += v * v;
    }
    const double mean = sum / n, se = std::sqrt(std::max(0.0, sum_sq / n - mean * mean) / n);
    EXPECT_NEAR(mean, expected, 5 * se + 1e-6 * std::fabs(expected));  // float rounding when the estimator is exact
}

TEST(Warp, CosineHemisphereIntegratesCosine) {
    // ∫ cos θ dω over the hemisphere = π; ∫ cos² θ dω = 2π/3 (a non-trivial moment).
    expect_integral(
        sample_cosine_hemisphere, [](Vec3 w) { return cosine_hemisphere_pdf(w.z); },
        [](Vec3 w) { return double(w.z) * w.z; }, 2.0 * M_PI / 3.0);
}

TEST(Warp, UniformSphereIntegratesSolidAngle) {
    expect_integral(
        sample_uniform_sphere, [](Vec3) { return uniform_sphere_pdf(); },
        [](Vec3 w) { return w.z > 0 ? double(w.z) : 0.0; }, M_PI);
}

TEST(Warp, UniformConeCoversItsSolidAngle) {
    const float cos_max = 0.8f;
    expect_integral([&](Vec2 u) { return sample_uniform_cone(u, cos_max); },
                    [&](Vec3) { return uniform_cone_pdf(cos_max); }, [](Vec3) { return 1.0; },
                    2.0 * M_PI * (1.0 - cos_max));
}

TEST(Warp, TriangleBarycentricsAreUniform) {
    Pcg32 rng(3, 4);
    double mean0 = 0, mean1 = 0;
    const int n = 100000;
    for (int i = 0; i < n; ++i) {
        const Vec2 b = sample_uniform_triangle({rng.next_float(), rng.next_float()});
        ASSERT_GE(b.x, 0.f);
        ASSERT_GE(b.y, 0.f);
        ASSERT_LE(b.x + b.y, 1.f + 1e-6f);
        mean0 += b.x;
        mean1 += b.y;
    }
    // Each barycentric has mean 1/3 and standard deviation √(1/18) for a uniform point.
    const double tol = 5 * std::sqrt(1.0 / 18.0 / n);
    EXPECT_NEAR(mean0 / n, 1.0 / 3.0, tol);
    EXPECT_NEAR(mean1 / n, 1.0 / 3.0, tol);
}

TEST(Sampler, ValuesDependOnlyOnPixelAndSampleIndex) {
    Sampler a = make_sampler("RANDOM", 9, 16), b = make_sampler("RANDOM", 9, 16);
    start_pixel_sample(a, 3, 4, 5);
    const float a0 = get_1d(a);
    const Vec2 a1 = get_2d(a);
    start_pixel_sample(b, 7, 7, 0);
    get_1d(b);
    start_pixel_sample(b, 3, 4, 5);
    EXPECT_EQ(get_1d(b), a0);
    const Vec2 b1 = get_2d(b);
    EXPECT_EQ(b1.x, a1.x);
    EXPECT_EQ(b1.y, a1.y);
}

TEST(Sampler, UnknownNameThrows) { EXPECT_THROW(make_sampler("NOPE", 0, 1), InvalidParameter); }

}  // namespace
}  // namespace candela
