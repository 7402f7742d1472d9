#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "core/rng.h"
#include "film/film.h"
#include "film/pixel_filter.h"

namespace candela {
namespace {

// Filter importance sampling must reproduce the filter's distribution: mean offset 0 and the variance
// of the normalised 1-D profile (computed by quadrature here, independently of the sampling table).
void expect_filter_moments(const std::string& name, float width) {
    const PixelFilter f(name, width);
    double norm = 0, second = 0;
    const int q = 20000;
    for (int i = 0; i < q; ++i) {
        const double x = (i + 0.5) / q * f.support() - 0.5 * f.support();
        norm += f.evaluate(float(x));
        second += x * x * f.evaluate(float(x));
    }
    const double variance = second / norm;
    Pcg32 rng(5, 6);
    const int n = 200000;
    double sum = 0, sum_sq = 0;
    for (int i = 0; i < n; ++i) {
        const Vec2 o = f.sample({rng.next_float(), rng.next_float()});
        ASSERT_LE(std::fabs(o.x), 0.5f * f.support() + 1e-5f);
        sum += o.x;
        sum_sq += double(o.x) * o.x;
    }
    const double se_mean = std::sqrt(variance / n);
    EXPECT_NEAR(sum / n, 0.0, 5 * se_mean) << name;
    // Var of the sample variance ≈ (μ4 − σ⁴)/n ≤ 2σ⁴/n for these light-tailed profiles.
    EXPECT_NEAR(sum_sq / n, variance, 5 * variance * std::sqrt(2.0 / n) + 1e-4) << name;
}

TEST(PixelFilter, BoxMoments) { expect_filter_moments("BOX", 1.f); }
TEST(PixelFilter, GaussianMoments) { expect_filter_moments("GAUSSIAN", 1.5f); }
TEST(PixelFilter, BlackmanHarrisMoments) { expect_filter_moments("BLACKMAN_HARRIS", 1.5f); }
// Cycles' widths: the Gaussian spans 3x and Blackman–Harris 2x the user's width (film.cpp filter_table).
TEST(PixelFilter, SupportFollowsCyclesWidthConvention) {
    EXPECT_FLOAT_EQ(PixelFilter("BOX", 1.5f).support(), 1.5f);
    EXPECT_FLOAT_EQ(PixelFilter("GAUSSIAN", 1.5f).support(), 4.5f);
    EXPECT_FLOAT_EQ(PixelFilter("BLACKMAN_HARRIS", 1.5f).support(), 3.f);
    // exp(−2(6x/support)²) = exp(−x²/2σ²) with σ = width/4 in Cycles' parametrisation.
    const PixelFilter g("GAUSSIAN", 1.5f);
    EXPECT_NEAR(g.evaluate(0.375f) / g.evaluate(0.f), std::exp(-0.5), 1e-6);
}

TEST(PixelFilter, RejectsUnknownAndBadWidth) {
    EXPECT_THROW(PixelFilter("TENT", 1.f), InvalidParameter);
    EXPECT_THROW(PixelFilter("BOX", 0.f), InvalidParameter);
}

TEST(Film, TilesCoverEveryPixelOnce) {
    const Film film(70, 45, 0, 0, 32);
    std::vector<int> covered(70 * 45, 0);
    for (const Tile& t : film.tiles())
        for (int y = t.y0; y < t.y1; ++y)
            for (int x = t.x0; x < t.x1; ++x) ++covered[y * 70 + x];
    for (int c : covered) ASSERT_EQ(c, 1);
}

TEST(Film, CombinedAveragesSamplesAndAddsScaledSplats) {
    Film film(2, 2, 0, 0, 32);
    std::vector<PixelAccum> px(4);
    px[0].add(Color(1.f, 2.f, 3.f), 1.f);
    px[0].add(Color(3.f, 2.f, 1.f), 0.f);
    px[3].add(Color(4.f), 1.f);
    film.add_tile(0, px);
    SplatBuffer s;
    s.entries.push_back({3, Color(2.f)});
    film.add_splats({s});
    film.set_splat_scale(0.5);
    const std::vector<float> c = film.combined();
    EXPECT_FLOAT_EQ(c[0], 2.f);
    EXPECT_FLOAT_EQ(c[2], 2.f);
    EXPECT_FLOAT_EQ(c[3], 0.5f);  // alpha averages too
    EXPECT_FLOAT_EQ(c[12], 5.f);  // pixel 3: 4 + 0.5·2
    EXPECT_FLOAT_EQ(c[4], 0.f);   // no samples yet
}

TEST(Film, RejectsEmptyFilm) { EXPECT_THROW(Film(0, 3), InvalidParameter); }

}  // namespace
}  // namespace candela
