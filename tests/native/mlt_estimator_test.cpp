// The Metropolis estimators' own properties (docs/metropolis.md, native/integrators/mlt/bootstrap.h):
// 1. start-up bias: the mean of many very short runs (6 mutations per chain) from a small bootstrap equals PATH;
// 2. seed sweep: on the door scene 8 seeds with a small and 8 with a large bootstrap agree with each other and BDPT;
// 3. MMLT's strategy choice: its pmf sums to 1 at every depth and its frequencies pass χ²;
// 4. MMLT's per-depth b_k equal the per-depth BDPT image sums (BDPT's strategy images);
// 5. the glass caustic: MLT and MMLT equal BDPT;
// 6. the two chain populations' bootstraps are independent (their b differ by the spread of independent estimates).
// Comparisons of renders are by the spread over independent seeds (agreement.h, the method of mlt_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "agreement.h"
#include "chi2.h"
#include "core/rng.h"
#include "integrators/bdpt/strategy_images.h"
#include "integrators/mlt/mlt_integrator.h"
#include "integrators/mlt/path_space.h"
#include "mlt_scenes.h"
#include "reference_scenes.h"
#include "scene/scene.h"
#include "session/session.h"

namespace candela::test {
namespace {

struct MeanAndError {
    double mean = 0.0, standard_error = 0.0;
};
MeanAndError mean_and_error(const std::vector<double>& x) {
    MeanAndError r;
    for (double v : x) r.mean += v / double(x.size());
    double var = 0.0;
    for (double v : x) var += (v - r.mean) * (v - r.mean) / double(x.size() - 1);
    r.standard_error = std::sqrt(var / double(x.size()));
    return r;
}

TEST(MltEstimator, VeryShortRunsAfterBootstrapResamplingEqualPathTracing) {
    // Start-up bias (Veach 1997, §11.3.3): a chain started at a bootstrap state resampled ∝ I and weighted by that
    // bootstrap's b (per depth: b_k) gives an unbiased image however short the run. 48 runs of 1 mutation per pixel
    // (192 mutations over 32 chains: 6 per chain) from a small bootstrap (MLT 500 paths, MMLT 100 per depth: any
    // start-up bias, of order 1/n, is largest there) against 48 PATH runs of 16 samples per pixel. t with 94 dof:
    // mean within 4.5 standard errors (two-sided 2e-5), blocks within 6.5.
    const SceneArrays box = box_scene(false);
    for (const char* name : {"MLT", "MMLT"}) {
        Params p = base_params(name, 1);
        p.set("mlt_bootstrap", int64_t(std::string(name) == "MLT" ? 500 : 100));
        expect_agree(box, p, base_params("PATH", 16), std::string(name) + ", 6 mutations per chain vs PATH", 48);
    }
}

TEST(MltEstimator, SeedSweepOnTheDoorSceneAgreesForTwoBootstrapSizes) {
    // pbrt-v4 #525: Metropolis images that depend on the seed. The door scene (light only through a slit, after a
    // bounce), 8 seeds × a small and a large bootstrap, 64 mutations per pixel: each set equals BDPT and the two
    // sets equal each other (t, 14 dof: 4.5 → 5e-4 per mean, 6.5 → 1.5e-5 per block; 9 comparisons).
    const SceneArrays door = box_scene(true);
    const Params bdpt = base_params("BDPT", 32);
    for (const char* name : {"MLT", "MMLT"}) {
        const bool mlt = std::string(name) == "MLT";
        Params small = base_params(name, 64), large = small;
        small.set("mlt_bootstrap", int64_t(mlt ? 1000 : 200));
        large.set("mlt_bootstrap", int64_t(mlt ? 16000 : 3200));
        const std::vector<RenderResult> a = render_seeds(door, small, 8), b = render_seeds(door, large, 8);
        const std::vector<RenderResult> ref = render_seeds(door, bdpt, 8);
        struct Pair {
            const std::vector<RenderResult>*x, *y;
            const char* what;
        };
        for (const Pair& c : {Pair{&a, &b, "small vs large bootstrap"}, Pair{&a, &ref, "small bootstrap vs BDPT"},
                              Pair{&b, &ref, "large bootstrap vs BDPT"}}) {
            const Agreement g = compare_seed_sets(*c.x, *c.y, 4);
            std::printf("%s door seed sweep, %s: means %.5f vs %.5f, z %.2f, worst block z %.2f of %d\n", name, c.what,
                        g.mean_a, g.mean_b, g.mean_z, g.worst_block_z, g.blocks);
            EXPECT_LT(std::fabs(g.mean_z), 4.5) << name << ", " << c.what;
            EXPECT_LT(std::fabs(g.worst_block_z), 6.5) << name << ", " << c.what << ": block " << g.worst_block;
        }
    }
}

TEST(MltEstimator, MultiplexedStrategyPmfSumsToOneAndIsWhatTheChoiceDraws) {
    // At every depth the pmf over s sums to 1 (to 1e-6, float rounding), is 0 outside the depth's strategies, and
    // 10⁵ choices from uniform u have those frequencies: χ² over the strategies at significance 1e-4 per depth.
    for (int depth = 0; depth <= 13; ++depth) {
        const int n = mmlt_strategy_count(depth);
        EXPECT_EQ(n, depth + 2) << depth;  // s = 0 .. depth + 1 (depth 0: (0, 2) and (1, 1))
        double sum = 0.0;
        for (int s = -1; s <= depth + 2; ++s) sum += mmlt_strategy_pmf(depth, s);
        EXPECT_NEAR(sum, 1.0, 1e-6) << "depth " << depth;
        EXPECT_EQ(mmlt_strategy_pmf(depth, -1), 0.f);
        EXPECT_EQ(mmlt_strategy_pmf(depth, n), 0.f);
        Pcg32 rng(uint64_t(depth) + 1, 5);
        constexpr int k_draws = 100000;
        std::vector<double> count(size_t(n), 0.0);
        for (int i = 0; i < k_draws; ++i) {
            const StrategyChoice c = mmlt_choose_strategy(depth, rng.next_float());
            ASSERT_GE(c.s, 0);
            ASSERT_LT(c.s, n);
            ASSERT_EQ(c.pmf, mmlt_strategy_pmf(depth, c.s));
            count[size_t(c.s)] += 1.0;
        }
        double chi2 = 0.0;
        for (int s = 0; s < n; ++s) {
            const double expected = k_draws * double(mmlt_strategy_pmf(depth, s));
            chi2 += (count[size_t(s)] - expected) * (count[size_t(s)] - expected) / expected;
        }
        if (n > 1) {
            const double p = chi2_survival(chi2, n - 1);
            EXPECT_GT(p, 1e-4) << "depth " << depth << ": χ² " << chi2 << " with " << n - 1 << " dof";
        }
    }
}

TEST(MltEstimator, ChainPopulationsHaveIndependentBootstraps) {
    // The film's two noise replicates are the two chain populations; for their difference to include the error of
    // b, each has its own bootstrap. Over 32 seeds, with b_0, b_1 the populations' b (1 000 paths each, the Cornell
    // box): independent estimates of equal variance σ² give Var(b_0 − b_1) = 2σ² and Var((b_0 + b_1)/2) = σ²/2, so
    // F = Var(b_0 − b_1) / (4·Var((b_0 + b_1)/2)) is F(31, 31)-distributed: within [0.293, 3.41] (two-sided 1e-3).
    // One shared bootstrap gives F = 0; correlation ρ gives F ≈ (1 − ρ)/(1 + ρ).
    const SceneArrays box = cornell_box();
    for (const char* name : {"MLT", "MMLT"}) {
        std::vector<double> diff, mean;
        for (int seed = 1; seed <= 32; ++seed) {
            Params p = basic_params(16, 12, 1, 2);
            p.set("integrator", std::string(name));
            p.set("seed", int64_t(seed));
            p.set("mlt_bootstrap", int64_t(2000));
            const Scene scene(box, p, nullptr);
            const MltBootstrap boot = mlt_bootstrap(scene, p, 2);
            ASSERT_EQ(boot.b_population.size(), 2u);
            diff.push_back(boot.b_population[0] - boot.b_population[1]);
            mean.push_back(0.5 * (boot.b_population[0] + boot.b_population[1]));
        }
        const MeanAndError d = mean_and_error(diff), m = mean_and_error(mean);
        const double F = (d.standard_error * d.standard_error) / (4.0 * m.standard_error * m.standard_error);
        std::printf("%s: b %.5f ± %.5f, population difference %.5f ± %.5f, F %.3f\n", name, m.mean, m.standard_error,
                    d.mean, d.standard_error, F);
        EXPECT_GT(F, 0.293) << name << ": the populations' bootstraps are not independent";
        EXPECT_LT(F, 3.41) << name;
        EXPECT_LT(std::fabs(d.mean), 4.0 * d.standard_error) << name << ": the populations estimate different b";
    }
}

/// The Cornell box seen from further back (camera at z = 2): the frame's border, and the camera margin around it,
/// see only the black world, so every camera ray MMLT's bootstrap spreads over the widened frame and lands outside
/// the frame carries no light.
SceneArrays distant_cornell_box() {
    SceneArrays a = cornell_box();
    const std::vector<float> camera = look_at(Vec3(0.f, 0.f, 2.f), Vec3(0.f, 0.f, -3.f), Vec3(0.f, 1.f, 0.f));
    a.set("camera_to_world", ElemType::F32, {4, 4}, camera.data());
    return a;
}

TEST(MltEstimator, MultiplexedPerDepthBrightnessIsThePerDepthBdptImage) {
    // b_k = ∫ I_k(u) du over the widened frame of area A = (W + 1)(H + 1) (a one-pixel box filter: margin ½) is
    // Σ_j lum(image_k)_j / A, image_k the light of depth k — the sum over s of BDPT's weighted strategy images of that
    // depth; the border sees black, so the margin adds nothing. 8 seeds each (bootstrap 16 000 per depth; BDPT 32
    // samples per pixel), t with 14 dof per depth: 4.5 → 5e-4, 2.5e-3 over the 5 depths.
    constexpr int W = 20, H = 20, K = 2, runs = 8;  // max bounces 2: depths 0 … 3
    const SceneArrays box = distant_cornell_box();
    std::vector<std::vector<double>> mmlt(K + 2), bdpt(K + 2);
    for (int seed = 1; seed <= runs; ++seed) {
        Params p = basic_params(W, H, 1, K);
        p.set("seed", int64_t(seed));
        p.set("threads", int64_t(2));
        p.set("integrator", std::string("MMLT"));
        p.set("mlt_bootstrap", int64_t(16000));
        const Scene scene(box, p, nullptr);
        const MltBootstrap boot = mlt_bootstrap(scene, p, 2);
        ASSERT_EQ(boot.b_depth.size(), size_t(K + 2));
        for (int k = 0; k < K + 2; ++k) mmlt[size_t(k)].push_back(boot.b_depth[size_t(k)]);

        Params q = basic_params(W, H, 32, K);
        q.set("seed", int64_t(seed));
        q.set("threads", int64_t(2));
        q.set("integrator", std::string("BDPT"));
        q.set("bdpt_strategy_images", true);
        q.set("bdpt_strategy_depth", int64_t(K + 1));
        std::string passes;
        for (const StrategyId& id : StrategyImages::strategies(K + 1))
            passes += (passes.empty() ? "" : ",") + StrategyImages::name(id, false);
        q.set("passes", passes);
        Session s(box, std::move(q));
        s.start();
        s.join();
        ASSERT_FALSE(s.error()) << *s.error();
        std::vector<double> sum(K + 2, 0.0);
        for (const StrategyId& id : StrategyImages::strategies(K + 1)) {
            int ch = 0;
            const std::vector<float> rgb = s.get_pass(StrategyImages::name(id, false), &ch);
            ASSERT_EQ(ch, 3);
            for (size_t i = 0; i + 2 < rgb.size(); i += 3)
                sum[size_t(id.depth)] += 0.2126 * rgb[i] + 0.7152 * rgb[i + 1] + 0.0722 * rgb[i + 2];
        }
        for (int k = 0; k < K + 2; ++k) bdpt[size_t(k)].push_back(sum[size_t(k)] / double((W + 1) * (H + 1)));
    }
    for (int k = 0; k < K + 2; ++k) {
        const MeanAndError a = mean_and_error(mmlt[size_t(k)]), b = mean_and_error(bdpt[size_t(k)]);
        const double se = std::hypot(a.standard_error, b.standard_error);
        std::printf("depth %d: b_k %.5f ± %.5f, BDPT image sum / A %.5f ± %.5f\n", k, a.mean, a.standard_error, b.mean,
                    b.standard_error);
        EXPECT_GT(b.mean, 0.0) << "depth " << k;
        EXPECT_LT(std::fabs(a.mean - b.mean), 4.5 * se) << "depth " << k << ": b_k " << a.mean << ", BDPT " << b.mean;
    }
}

TEST(MltEstimator, EqualBdptOnTheGlassCaustic) {
    // The caustic light → glass → glass → floor under a small light (reference_scenes.h), max bounces 5, 16 × 12
    // pixels: MLT and MMLT (256 mutations per pixel) against BDPT (128 samples), 8 seeds each (expect_agree).
    const SceneArrays caustic = glass_caustic();
    const Params bdpt = base_params("BDPT", 128);
    expect_agree(caustic, base_params("MLT", 256), bdpt, "MLT, glass caustic");
    expect_agree(caustic, base_params("MMLT", 256), bdpt, "MMLT, glass caustic");
}

}  // namespace
}  // namespace candela::test
