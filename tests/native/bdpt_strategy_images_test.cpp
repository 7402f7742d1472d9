// BDPT's strategy images (integrators/bdpt/strategy_images.h, option bdpt_strategy_images):
// 1. the weighted images of every depth sum to the render, pixel by pixel (a one-pixel box filter, so the render's
//    camera samples and splats land in the same pixels as the images'; the sums differ only by rounding);
// 2. each unweighted image of a strategy that can produce every path of its depth estimates all of that depth's
//    light on its own: on the Cornell box (diffuse, a hittable emissive panel, a perspective camera) the image means
//    of (0, 3), (1, 2) and (2, 1) at depth 1 equal the weighted depth-1 total within 4 standard errors (12 seeds:
//    t with 11 degrees of freedom, two-sided false alarm 1.6e-3 each, 1 % over this file's 6 comparisons);
// 3. names and bad settings: the passes are named "BDPT d<depth> s<s> t<t>[ unweighted]", an unknown one is refused.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "agreement.h"
#include "core/error.h"
#include "integrators/bdpt/strategy_images.h"
#include "reference_scenes.h"
#include "session/session.h"

namespace candela::test {
namespace {

std::string all_strategy_passes(int max_depth) {
    std::string passes;
    for (const StrategyId& id : StrategyImages::strategies(max_depth))
        for (bool unweighted : {false, true})
            passes += (passes.empty() ? "" : ",") + StrategyImages::name(id, unweighted);
    return passes;
}

struct StrategyRender {
    std::vector<float> combined;
    std::vector<std::pair<StrategyId, std::vector<float>>> weighted, unweighted;
};

StrategyRender render_strategies(const SceneArrays& arrays, int max_bounces, int depth, int seed, int samples) {
    Params p = basic_params(20, 20, samples, max_bounces);
    p.set("integrator", std::string("BDPT"));
    p.set("pixel_filter", std::string("BOX"));
    p.set("filter_width", 1.0);
    p.set("threads", int64_t(2));
    p.set("seed", int64_t(seed));
    p.set("bdpt_strategy_images", true);
    p.set("bdpt_strategy_depth", int64_t(depth));
    p.set("passes", all_strategy_passes(depth));
    Session s(arrays, std::move(p));
    s.start();
    s.join();
    if (auto e = s.error()) throw std::runtime_error(*e);
    StrategyRender r;
    int ch = 0;
    r.combined = s.get_pass("Combined", &ch);
    for (const StrategyId& id : StrategyImages::strategies(depth)) {
        r.weighted.emplace_back(id, s.get_pass(StrategyImages::name(id, false), &ch));
        EXPECT_EQ(ch, 3);
        r.unweighted.emplace_back(id, s.get_pass(StrategyImages::name(id, true), &ch));
    }
    return r;
}

double mean_of(const std::vector<float>& rgb) {
    double sum = 0.0;
    for (float v : rgb) sum += v;
    return sum / double(rgb.size());
}

TEST(BdptStrategyImages, WeightedImagesSumToTheRender) {
    // max_bounces 2: paths of depth 0..3 (at most three scattering vertices), all recorded.
    const StrategyRender r = render_strategies(cornell_box(), 2, 3, 1, 8);
    const size_t n = r.combined.size() / 4;
    double worst = 0.0, total = 0.0;
    for (size_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) {
            double sum = 0.0;
            for (const auto& [id, img] : r.weighted) sum += img[3 * i + c];
            worst = std::max(worst, std::fabs(sum - r.combined[4 * i + c]));
            total += r.combined[4 * i + c];
        }
    EXPECT_GT(total, 0.0);
    EXPECT_LT(worst, 1e-4 * (total / double(3 * n)) + 1e-6) << "largest per-pixel difference " << worst;
}

TEST(BdptStrategyImages, EachUnweightedStrategyEstimatesAllLightOfItsDepth) {
    constexpr int k_seeds = 12;
    std::vector<double> total(k_seeds), single[3];
    for (int seed = 1; seed <= k_seeds; ++seed) {
        const StrategyRender r = render_strategies(cornell_box(), 3, 1, seed, 16);
        double t = 0.0;
        for (const auto& [id, img] : r.weighted)
            if (id.depth == 1) t += mean_of(img);
        total[seed - 1] = t;
        for (const auto& [id, img] : r.unweighted)
            if (id.depth == 1) single[id.s].push_back(mean_of(img));
    }
    auto stats = [](const std::vector<double>& v, double* m, double* se) {
        double s = 0.0, s2 = 0.0;
        for (double x : v) s += x, s2 += x * x;
        *m = s / double(v.size());
        *se = std::sqrt(std::max(0.0, (s2 - double(v.size()) * *m * *m) / double(v.size() - 1)) / double(v.size()));
    };
    double m_total, se_total;
    stats(total, &m_total, &se_total);
    EXPECT_GT(m_total, 0.0);
    for (int s = 0; s <= 2; ++s) {
        double m, se;
        stats(single[s], &m, &se);
        std::printf("depth 1, (s, t) = (%d, %d): unweighted mean %.5f ± %.5f; all strategies weighted %.5f ± %.5f\n", s,
                    3 - s, m, se, m_total, se_total);
        EXPECT_NEAR(m, m_total, 4.0 * std::sqrt(se * se + se_total * se_total)) << "strategy s = " << s;
    }
}

TEST(BdptStrategyImages, NamesAndBadPassesAreChecked) {
    EXPECT_EQ(StrategyImages::name({1, 1, 2}, false), "BDPT d1 s1 t2");
    EXPECT_EQ(StrategyImages::name({2, 3, 1}, true), "BDPT d2 s3 t1 unweighted");
    EXPECT_EQ(StrategyImages::strategies(0).size(), 2u);  // (0, 2), (1, 1)
    EXPECT_EQ(StrategyImages::strategies(2).size(), 2u + 3u + 4u);
    Params p = basic_params(4, 4, 1, 2);
    p.set("integrator", std::string("BDPT"));
    p.set("passes", std::string("BDPT d1 s3 t2"));  // s + t ≠ d + 2
    EXPECT_THROW(Session(cornell_box(), std::move(p)), InvalidParameter);
}

}  // namespace
}  // namespace candela::test
