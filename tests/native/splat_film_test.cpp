// Splats on the film (film/film.h) and the machinery light-rooted integrators render through: the filter's
// splat density, the ordered parallel loop (core/parallel_ordered.h) and the progressive driver
// (integrators/progressive_driver.h), exercised by a synthetic integrator that splats a known image.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <thread>
#include <vector>

#include "core/parallel_ordered.h"
#include "core/rng.h"
#include "film/film.h"
#include "film/pixel_filter.h"
#include "integrators/progressive_driver.h"

namespace candela::test {
namespace {

struct FilterCase {
    const char* name;
    float width;
};
const FilterCase k_filters[] = {
    {"BOX", 1.f}, {"BOX", 2.5f}, {"GAUSSIAN", 1.5f}, {"BLACKMAN_HARRIS", 1.5f}, {"BLACKMAN_HARRIS", 3.f}};

// The splat density is normalised: ∫ pdf = 1 (midpoint rule on 20,000 steps; the density is piecewise constant
// on 4,096 intervals, so the rule's error is below 1e-4).
TEST(SplatFilter, DensityIntegratesToOne) {
    for (const FilterCase& c : k_filters) {
        const PixelFilter f(c.name, c.width);
        const int n = 20000;
        const double h = double(f.support()) / n;
        double sum = 0.0;
        for (int i = 0; i < n; ++i) sum += f.pdf(float(-0.5 * f.support() + (i + 0.5) * h)) * h;
        EXPECT_NEAR(sum, 1.0, 2e-4) << c.name << " " << c.width;
        EXPECT_EQ(f.pdf(0.5f * f.support() + 1e-3f), 0.f);
    }
}

// It is the density of the offsets filter importance sampling draws: a histogram of 10⁶ sample() offsets in 40
// bins matches ∫ pdf over each bin. Each bin count is binomial; every bin within 4.5σ (false alarm over the 200
// bins of the five filters about 0.07 %).
TEST(SplatFilter, DensityIsTheDensityOfTheSampledOffsets) {
    for (const FilterCase& c : k_filters) {
        const PixelFilter f(c.name, c.width);
        const int bins = 40, n = 1000000;
        std::vector<int> count(bins, 0);
        Pcg32 rng(7, 1);
        const float half = 0.5f * f.support();
        for (int i = 0; i < n; ++i) {
            const float x = f.sample({rng.next_float(), 0.5f}).x;
            ++count[std::clamp(int((x + half) / f.support() * bins), 0, bins - 1)];
        }
        for (int b = 0; b < bins; ++b) {
            double p = 0.0;
            const int steps = 500;
            const double lo = -half + double(b) * f.support() / bins, h = f.support() / bins / steps;
            for (int k = 0; k < steps; ++k) p += f.pdf(float(lo + (k + 0.5) * h)) * h;
            const double sigma = std::sqrt(n * p * (1 - p)) + 1.0;
            EXPECT_NEAR(count[b], n * p, 4.5 * sigma) << c.name << " " << c.width << " bin " << b;
        }
    }
}

// A splat's expectation over the film is the camera estimate: for an image L(x) and positions x uniform over
// the frame with value L(x), counted as (positions / frame area) samples per pixel, pixel j receives E = ∫ pdf(x − c_j) L(x) dx — what filter importance
// sampled camera samples of pixel j average. Here the splats sit on a fine regular grid (quadrature) and the
// camera side is a regular grid over the offset square: both sides are deterministic, and agree to the
// quadrature's error.
TEST(SplatFilter, SplatsEstimateWhatCameraSamplesEstimate) {
    const int w = 12, h = 10;
    auto image = [](float x, float y) { return 1.f + 0.5f * std::sin(0.7f * x) * std::cos(0.4f * y) + 0.05f * x; };
    for (const FilterCase& c : k_filters) {
        const PixelFilter f(c.name, c.width);
        Film film(w, h, 0, 0, 32);
        const int grid = 64;  // splat positions per pixel and axis
        SplatBuffer buffer;
        for (int j = 0; j < h * grid; ++j)
            for (int i = 0; i < w * grid; ++i) {
                const float x = (i + 0.5f) / grid, y = (j + 0.5f) / grid;
                buffer.add({x, y}, Color(image(x, y)), uint32_t((i + j) % 2));
            }
        const double per_pixel = double(grid) * grid;  // positions per unit of frame area
        const double samples[k_noise_replicates] = {per_pixel / 2, per_pixel / 2};
        film.add_splats(buffer, f, samples);
        const std::vector<float> out = film.combined();
        // Interior pixels only: near the border part of the footprint falls outside the frame on both sides.
        const int margin = int(std::ceil(0.5f * f.support()));
        for (int py = margin; py < h - margin; ++py)
            for (int px = margin; px < w - margin; ++px) {
                double camera = 0.0;
                const int m = 256;
                for (int b = 0; b < m; ++b)
                    for (int a = 0; a < m; ++a) {
                        const Vec2 o = f.sample({(a + 0.5f) / m, (b + 0.5f) / m});
                        camera += image(px + 0.5f + o.x, py + 0.5f + o.y);
                    }
                camera /= double(m) * m;
                EXPECT_NEAR(out[4 * (size_t(py) * w + px)], camera, 2e-3 * camera)
                    << c.name << " " << c.width << " pixel " << px << "," << py;
            }
    }
}

// A border film receives exactly the full frame's splats on its pixels.
TEST(SplatFilm, ABorderFilmEqualsTheSamePixelsOfTheFullFrame) {
    const PixelFilter f("BLACKMAN_HARRIS", 1.5f);
    Film full(20, 16, 0, 0, 8), crop(7, 5, 6, 4, 8);
    SplatBuffer buffer;
    Pcg32 rng(3, 1);
    for (int i = 0; i < 5000; ++i)
        buffer.add({20.f * rng.next_float(), 16.f * rng.next_float()}, Color(rng.next_float()), i % 2);
    const double samples[k_noise_replicates] = {3.0, 3.0};
    full.add_splats(buffer, f, samples);
    crop.add_splats(buffer, f, samples);
    const std::vector<float> a = full.combined(), b = crop.combined();
    for (int y = 0; y < 5; ++y)
        for (int x = 0; x < 7; ++x)
            for (int k = 0; k < 4; ++k)
                ASSERT_EQ(b[4 * (size_t(y) * 7 + x) + k], a[4 * (size_t(y + 4) * 20 + x + 6) + k]) << x << "," << y;
}

// Splat sums are double: a million contributions of 1e-9 on top of 1 are not lost (a float sum stays at 1).
TEST(SplatFilm, SumsInDoublePrecision) {
    const PixelFilter box("BOX", 1.f);
    Film film(1, 1, 0, 0, 8);
    SplatBuffer buffer;
    buffer.add({0.5f, 0.5f}, Color(1.f), 0);
    for (int i = 0; i < 1000000; ++i) buffer.add({0.5f, 0.5f}, Color(1e-9f), i % 2);
    const double samples[k_noise_replicates] = {0.5, 0.5};
    film.add_splats(buffer, box, samples);
    EXPECT_NEAR(film.splat(0, 0).r, 1.001, 1e-9);
}

// Alpha: a pixel only splats reached is opaque; where camera samples also ran (a transparent film's camera pass
// over the background), their alpha holds.
TEST(SplatFilm, AlphaOfSplatOnlyAndOfCameraPassPixels) {
    const PixelFilter box("BOX", 1.f);
    Film film(2, 1, 0, 0, 8);
    std::vector<PixelAccum> px(2);
    px[1].add(Color(0.f), 0.f, 0);  // the camera saw the background here (film_transparent)
    px[1].add(Color(0.f), 0.f, 1);
    film.add_tile(0, px);
    SplatBuffer buffer;
    buffer.add({0.5f, 0.5f}, Color(2.f), 0);
    buffer.add({1.5f, 0.5f}, Color(2.f), 1);
    const double samples[k_noise_replicates] = {1.0, 1.0};
    film.add_splats(buffer, box, samples);
    const std::vector<float> c = film.combined();
    EXPECT_FLOAT_EQ(c[0], 1.f);
    EXPECT_FLOAT_EQ(c[3], 1.f);
    EXPECT_FLOAT_EQ(c[4], 1.f);
    EXPECT_FLOAT_EQ(c[7], 0.f);
}

// The replicate variance of a splatted pixel, by hand: replicate 0 splatted 6 over 2 samples (mean 3), replicate 1
// 2 over 2 (mean 1); weights N_r = 2: m = 2, v = (2·1 + 2·1)/(1·4) = 1.
TEST(SplatFilm, ReplicateVarianceOfASplattedPixel) {
    PixelAccum p;
    SplatAccum s;
    s.r = s.g = s.b = 8.0;
    s.rep_lum[0] = 6.0;
    s.rep_lum[1] = 2.0;
    const double n[k_noise_replicates] = {2.0, 2.0};
    EXPECT_NEAR(replicate_variance_of_mean(p, s, n), 1.0, 1e-12);
    const double missing[k_noise_replicates] = {2.0, 0.0};
    EXPECT_LT(replicate_variance_of_mean(p, s, missing), 0.0);  // unknown until every replicate has samples
}

// --- the ordered parallel loop ---

TEST(ParallelOrdered, ConsumesInIndexOrderUnderRandomDelays) {
    std::vector<size_t> order;
    std::atomic<int> in_flight{0}, max_in_flight{0};
    parallel_ordered(
        4, 200, 3,
        [&](size_t i) {
            const int now = ++in_flight;
            int seen = max_in_flight.load();
            while (now > seen && !max_in_flight.compare_exchange_weak(seen, now)) {}
            std::this_thread::sleep_for(std::chrono::microseconds(hash_values(i, 1, 2) % 300));
            return i * 10;
        },
        [&](size_t i, size_t v) {
            --in_flight;
            EXPECT_EQ(v, i * 10);
            order.push_back(i);
        });
    ASSERT_EQ(order.size(), 200u);
    for (size_t i = 0; i < order.size(); ++i) EXPECT_EQ(order[i], i);
    // Tokens bound the items between produce and consume (a produced item waits for its turn).
    EXPECT_LE(max_in_flight.load(), 3);
}

TEST(ParallelOrdered, StopsStartingItemsOnCancelAndConsumesAPrefix) {
    CancelToken cancel;
    std::vector<size_t> order;
    parallel_ordered(
        2, 100000, 4, [&](size_t i) { return i; },
        [&](size_t i, size_t) {
            order.push_back(i);
            if (i == 50) cancel.cancel();
        },
        &cancel);
    ASSERT_GE(order.size(), 51u);
    EXPECT_LT(order.size(), 51u + 8u);  // at most the items already in flight follow
    for (size_t i = 0; i < order.size(); ++i) EXPECT_EQ(order[i], i);
}

TEST(ParallelOrdered, RethrowsTheFirstException) {
    EXPECT_THROW(parallel_ordered(
                     2, 100, 4,
                     [&](size_t i) {
                         if (i == 37) throw std::runtime_error("item 37");
                         return i;
                     },
                     [](size_t, size_t) {}),
                 std::runtime_error);
}

// --- the progressive driver, on a synthetic integrator ---

/// Splats a known image: each unit is one "light path per pixel"; the paths of a pass come in batches, each
/// batch seeded by (seed, batch index) and merged in batch order, positions uniform over the frame, value
/// L(x) = 1 + x/width times a noise factor of mean 1. Samples are counted as paths per pixel (paths / frame
/// area), so a splat's value is what a camera sample would return: pixel = (area/N) Σ pdf·L → ∫ pdf(x − c) L(x) dx.
struct SyntheticSplatter {
    int width = 24, height = 16;
    uint64_t seed = 5;
    int batch_paths = 97;

    void render(Film& film, RenderContext& ctx, const ProgressivePlan& plan, const PixelFilter& filter) const {
        run_progressive(
            ctx, plan,
            [&](int64_t begin, int64_t end) {
                const int64_t paths = (end - begin) * width * height;
                const size_t batches = size_t((paths + batch_paths - 1) / batch_paths);
                parallel_ordered(
                    ctx.threads, batches, 8,
                    [&](size_t b) {
                        SplatBuffer buffer;
                        const int64_t first = begin * width * height + int64_t(b) * batch_paths;
                        const int64_t n = std::min<int64_t>(batch_paths, end * width * height - first);
                        for (int64_t k = 0; k < n; ++k) {
                            const uint64_t path = uint64_t(first + k);
                            Pcg32 rng(hash_values(seed, path, 17), 1);
                            const float x = width * rng.next_float(), y = height * rng.next_float();
                            const float L = (1.f + x / width) * (0.5f + rng.next_float());
                            buffer.add({x, y}, Color(L), uint32_t(path % 2));
                        }
                        return std::make_pair(buffer, n);
                    },
                    [&](size_t, std::pair<SplatBuffer, int64_t>&& item) {
                        const double per_pixel = double(item.second) / (2.0 * width * height);
                        const double samples[k_noise_replicates] = {per_pixel, per_pixel};
                        film.add_splats(item.first, filter, samples);
                    },
                    &ctx.cancel);
            },
            [&] { return film.noise_estimate(); });
    }
};

std::vector<float> render_synthetic(int threads, int units, StopReason* stop = nullptr, double* error = nullptr) {
    SyntheticSplatter s;
    Film film(s.width, s.height, 0, 0, 8);
    CancelToken cancel;
    RenderCounters counters;
    RenderContext ctx{cancel, counters, threads};
    ProgressivePlan plan;
    plan.total = units;
    s.render(film, ctx, plan, PixelFilter("BLACKMAN_HARRIS", 1.5f));
    if (stop) *stop = StopReason(counters.stop_reason.load());
    if (error) *error = counters.relative_error;
    return film.combined();
}

TEST(ProgressiveDriver, SplattedImagesAreTheSameForAnyThreadCount) {
    const std::vector<float> one = render_synthetic(1, 12), two = render_synthetic(2, 12),
                             four = render_synthetic(4, 12);
    for (size_t i = 0; i < one.size(); ++i) {
        ASSERT_EQ(one[i], two[i]) << i;
        ASSERT_EQ(one[i], four[i]) << i;
    }
}

// The splatted image converges to L (interior pixels, where the footprint lies inside the frame): the pixel
// mean over the interior is within 4 standard errors of the exact filtered image's (σ from the per-pixel
// spread), and the noise estimate is finite for a film made only of splats.
TEST(ProgressiveDriver, SplattedImageConvergesAndHasANoiseEstimate) {
    StopReason stop;
    double error = -1.0;
    const std::vector<float> img = render_synthetic(2, 64, &stop, &error);
    EXPECT_EQ(stop, StopReason::Samples);
    EXPECT_GT(error, 0.0);
    EXPECT_LT(error, 0.2);
    const SyntheticSplatter s;
    double sum = 0.0, sum_sq = 0.0, expected = 0.0;
    int n = 0;
    for (int y = 2; y < s.height - 2; ++y)
        for (int x = 2; x < s.width - 2; ++x) {
            const double v = img[4 * (size_t(y) * s.width + x)];
            sum += v;
            sum_sq += v * v;
            expected += 1.0 + (x + 0.5) / s.width;  // the filter is symmetric: a linear L filters to itself
            ++n;
        }
    const double mean = sum / n, var = (sum_sq / n - mean * mean) / n;
    EXPECT_NEAR(mean, expected / n, 4.0 * std::sqrt(var) + 1e-6);
}

// The noise estimate is honest for a splatted image: the estimated relative RMSE against the measured one (the
// image against its exact expectation, ∫ over the frame of pdf(x − c) L(x), by quadrature) is within 0.75–1.25.
// Both are sums over 384 pixels: the estimate (two replicates, χ²₁ per pixel) and the measured MSE each have a
// relative spread of about √(2/384) ≈ 7 %, about 5 % on their ratio's square root, so 0.75 is 5σ away.
TEST(ProgressiveDriver, TheNoiseEstimateOfASplattedImageIsHonest) {
    double estimate = -1.0;
    const std::vector<float> img = render_synthetic(2, 16, nullptr, &estimate);
    const SyntheticSplatter s;
    const PixelFilter f("BLACKMAN_HARRIS", 1.5f);
    double se = 0.0, mean = 0.0;
    for (int y = 0; y < s.height; ++y)
        for (int x = 0; x < s.width; ++x) {
            double expected = 0.0;
            const int m = 96;
            for (int b = 0; b < m; ++b)
                for (int a = 0; a < m; ++a) {
                    const Vec2 o = f.sample({(a + 0.5f) / m, (b + 0.5f) / m});
                    const float px = x + 0.5f + o.x, py = y + 0.5f + o.y;
                    if (px >= 0.f && px < s.width && py >= 0.f && py < s.height) expected += 1.0 + px / s.width;
                }
            expected /= double(m) * m;
            const double d = img[4 * (size_t(y) * s.width + x)] - expected;
            se += d * d;
            mean += expected;
        }
    const double pixels = double(s.width) * s.height;
    const double measured = std::sqrt(se / pixels) / (mean / pixels);
    const double rho = estimate / measured;
    EXPECT_GT(rho, 0.75) << estimate << " vs " << measured;
    EXPECT_LT(rho, 1.25) << estimate << " vs " << measured;
}

TEST(ProgressiveDriver, PassSizesDoubleFromOneUpToTheCap) {
    CancelToken cancel;
    RenderCounters counters;
    RenderContext ctx{cancel, counters, 1};
    ProgressivePlan plan;
    plan.total = 100;
    plan.max_pass = 16;
    std::vector<int64_t> sizes;
    int64_t expected_begin = 0;
    const StopReason stop = run_progressive(
        ctx, plan,
        [&](int64_t begin, int64_t end) {
            EXPECT_EQ(begin, expected_begin);
            expected_begin = end;
            sizes.push_back(end - begin);
        },
        NoiseSource());
    EXPECT_EQ(stop, StopReason::Samples);
    EXPECT_EQ(sizes, (std::vector<int64_t>{1, 1, 2, 4, 8, 16, 16, 16, 16, 16, 4}));
    EXPECT_EQ(counters.work_done.load(), 100);
    EXPECT_EQ(counters.relative_error.load(), -1.0);  // no noise source: unknown
}

TEST(ProgressiveDriver, StopsAtTheNoiseThresholdOnceEnoughUnitsAreDone) {
    CancelToken cancel;
    RenderCounters counters;
    RenderContext ctx{cancel, counters, 1};
    ProgressivePlan plan;
    plan.total = 1000;
    plan.noise_threshold = 0.05;
    int64_t done = 0;
    const StopReason stop = run_progressive(
        ctx, plan, [&](int64_t, int64_t end) { done = end; },
        [&] {
            NoiseEstimate e;  // a noise falling as 1/√units, bound 10 % above it
            e.relative_rmse = 0.5 / std::sqrt(double(done));
            e.relative_rmse_bound = 1.1 * e.relative_rmse;
            return e;
        });
    EXPECT_EQ(stop, StopReason::NoiseThreshold);
    // 0.55/√n ≤ 0.05 from n = 121 on; passes end at 1, 2, 4, 8, 16, 32, 48, 64, ... (16 at a time): 128.
    EXPECT_EQ(done, 128);
    EXPECT_NEAR(counters.relative_error.load(), 0.5 / std::sqrt(128.0), 1e-12);
}

TEST(ProgressiveDriver, WithoutAnHonestNoiseEstimateTheNoiseStopIsOffAndSaysSo) {
    CancelToken cancel;
    RenderCounters counters;
    MessageLog log;
    RenderContext ctx{cancel, counters, 1, nullptr, &log};
    ProgressivePlan plan;
    plan.total = 40;
    plan.noise_threshold = 0.05;
    EXPECT_EQ(run_progressive(
                  ctx, plan, [](int64_t, int64_t) {}, NoiseSource()),
              StopReason::Samples);
    const auto lines = log.take();
    ASSERT_EQ(lines.size(), 1u);
    EXPECT_NE(lines[0].find("noise threshold"), std::string::npos);
}

// The time limit ends the render between passes (each pass here takes ≥ 5 ms, the limit is 30 ms: far fewer than
// the 10⁶ units are done); no assertion on how long it took.
TEST(ProgressiveDriver, StopsAtTheTimeLimit) {
    CancelToken cancel;
    RenderCounters counters;
    RenderContext ctx{cancel, counters, 1};
    ProgressivePlan plan;
    plan.total = 1000000;
    plan.time_limit = 0.03;
    const StopReason stop = run_progressive(
        ctx, plan, [](int64_t, int64_t) { std::this_thread::sleep_for(std::chrono::milliseconds(5)); }, NoiseSource());
    EXPECT_EQ(stop, StopReason::TimeLimit);
    EXPECT_LT(counters.work_done.load(), 1000000);
}

TEST(ProgressiveDriver, ACancelInsideAPassStopsTheRender) {
    CancelToken cancel;
    RenderCounters counters;
    RenderContext ctx{cancel, counters, 1};
    ProgressivePlan plan;
    plan.total = 100;
    int passes = 0;
    const StopReason stop = run_progressive(
        ctx, plan,
        [&](int64_t, int64_t) {
            if (++passes == 3) cancel.cancel();
        },
        NoiseSource());
    EXPECT_EQ(stop, StopReason::Cancelled);
    EXPECT_EQ(passes, 3);
    EXPECT_EQ(counters.work_done.load(), 2);  // the cancelled pass is not counted as done
}

}  // namespace
}  // namespace candela::test
