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
    px[0].add(Color(1.f, 2.f, 3.f), 1.f, 0);
    px[0].add(Color(3.f, 2.f, 1.f), 0.f, 1);
    px[3].add(Color(4.f), 1.f, 0);
    film.add_tile(0, px);
    // A box filter of width 1: a splat at a pixel's centre lands in that pixel alone, with density 1.
    const PixelFilter box("BOX", 1.f);
    SplatBuffer s;
    s.add({1.5f, 1.5f}, Color(2.f), 0);
    const double samples[k_noise_replicates] = {1.0, 1.0};
    film.add_splats(s, box, samples);
    const std::vector<float> c = film.combined();
    EXPECT_FLOAT_EQ(c[0], 2.f);
    EXPECT_FLOAT_EQ(c[2], 2.f);
    EXPECT_FLOAT_EQ(c[3], 0.5f);  // alpha averages too
    EXPECT_FLOAT_EQ(c[12], 5.f);  // pixel 3: 4 + 2/2 (the splat over its two samples)
    EXPECT_FLOAT_EQ(c[4], 0.f);   // no samples yet
    EXPECT_FLOAT_EQ(c[7], 1.f);   // ... but splats have reached the film: an opaque pixel
}

// Noise estimates (film/noise_estimate.h) on hand-computed pixels. Grey samples: luminance = value.
// Pixel A: replicate 0 holds 1 and 3, replicate 1 holds 5. n = 3, mean 3, replicate means 2 and 5:
//   v = Σ n_r (m_r − m)² / ((B − 1) n) = (2·1 + 1·4) / 3 = 2;  s² = (4 + 0 + 4) / 2 = 4, s²/n = 4/3.
// Pixel B: replicate 0 holds 2, replicate 1 holds 4: v = (1 + 1) / 2 = 1;  s² = 2, s²/n = 1.
PixelAccum pixel_a() {
    PixelAccum p;
    p.add(Color(1.f), 1.f, 0);
    p.add(Color(5.f), 1.f, 1);
    p.add(Color(3.f), 1.f, 0);
    return p;
}
PixelAccum pixel_b() {
    PixelAccum p;
    p.add(Color(2.f), 1.f, 0);
    p.add(Color(4.f), 1.f, 1);
    return p;
}

TEST(FilmNoise, ReplicateVarianceIsTheBetweenReplicateSpread) {
    EXPECT_NEAR(replicate_variance_of_mean(pixel_a()), 2.0, 1e-5);
    EXPECT_NEAR(moment_variance_of_mean(pixel_a()), 4.0 / 3.0, 1e-5);
    EXPECT_NEAR(replicate_variance_of_mean(pixel_b()), 1.0, 1e-5);
    EXPECT_NEAR(moment_variance_of_mean(pixel_b()), 1.0, 1e-5);
}

TEST(FilmNoise, UnknownUntilEveryReplicateHasASample) {
    PixelAccum p;
    p.add(Color(1.f), 1.f, 0);
    p.add(Color(2.f), 1.f, 0);
    EXPECT_LT(replicate_variance_of_mean(p), 0.0);
    Film film(1, 1);
    film.add_tile(0, {p});
    const NoiseEstimate e = film.noise_estimate();
    EXPECT_TRUE(std::isinf(e.relative_rmse));
    EXPECT_TRUE(std::isinf(e.relative_rmse_bound));
    EXPECT_NEAR(e.moment_relative_rmse, std::sqrt(0.25) / 1.5, 1e-6);  // s² = 0.5, s²/n = 0.25, mean 1.5
    EXPECT_DOUBLE_EQ(e.calibration, 1.0);
}

TEST(FilmNoise, ImageFiguresAndTheCalibratedNoisePass) {
    Film film(2, 1);
    film.add_tile(0, {pixel_a(), pixel_b()});
    const NoiseEstimate e = film.noise_estimate();
    // Σ v = 3 over 2 pixels of mean luminance 3; Σ s²/n = 7/3; Σ v² = 5, so the bound adds 2·√(2·5/3).
    EXPECT_NEAR(e.mean_luminance, 3.0, 1e-5);
    EXPECT_NEAR(e.relative_rmse, std::sqrt(3.0 / 2.0) / 3.0, 1e-6);
    EXPECT_NEAR(e.moment_relative_rmse, std::sqrt(7.0 / 6.0) / 3.0, 1e-6);
    EXPECT_NEAR(e.relative_rmse_bound, std::sqrt((3.0 + 2.0 * std::sqrt(10.0 / 3.0)) / 2.0) / 3.0, 1e-6);
    EXPECT_NEAR(e.calibration, 9.0 / 7.0, 1e-6);
    // The pass: √(κ s²/n) per pixel, so its mean square is Σ v / pixels.
    const std::vector<float> noise = film.noise();
    EXPECT_NEAR(noise[0], std::sqrt(9.0 / 7.0 * 4.0 / 3.0), 1e-5);
    EXPECT_NEAR(noise[1], std::sqrt(9.0 / 7.0), 1e-5);
}

TEST(Film, RejectsEmptyFilm) { EXPECT_THROW(Film(0, 3), InvalidParameter); }

}  // namespace
}  // namespace candela
