// The Metropolis integrators MLT (PSSMLT over BDPT) and MMLT (multiplexed) against PATH and closed forms
// (docs/metropolis.md): a Cornell box and a hard scene (light that reaches the room only through a slit after a
// bounce), the furnace (where b and the image's mean are known), b of MLT and MMLT alike, MLT with p_large = 1
// against BDPT, determinism for any thread count, cancel, and bad settings.
//
// Method: a Metropolis image's error is correlated across pixels and passes (a chain's splats, one bootstrap b for
// all chains), so per-pixel variances mean nothing. Every comparison renders m independent runs per integrator
// (seeds 1..m: own bootstrap, own chains) and compares the image mean and 4×4 block means in units of their
// standard error estimated from the spread over the runs (agreement.h), a t statistic with about 2m − 2 degrees of
// freedom: with m = 8 (14 dof) a mean within 4.5 has a two-sided false-alarm rate of 5e-4, a block within 6.5 of
// 1.5e-5. Over the ~10 comparisons and ~60 blocks here the family-wise rate is under 1 %. Runs are few thousand
// mutations per chain after resampling from the bootstrap, so start-up bias is part of what is tested.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <thread>

#include "agreement.h"
#include "core/error.h"
#include "integrators/integrator.h"
#include "integrators/mlt/mlt_integrator.h"
#include "mlt_scenes.h"
#include "scene/scene.h"
#include "session/session.h"

namespace candela::test {
namespace {

constexpr int k_runs = 8;

TEST(Mlt, EqualsPathTracingOnTheCornellBox) {
    const SceneArrays box = box_scene(false);
    const Params path = base_params("PATH", 128);
    expect_agree(box, base_params("MLT", 128), path, "MLT, Cornell box");
    expect_agree(box, base_params("MMLT", 128), path, "MMLT, Cornell box");
}

TEST(Mlt, EqualsPathTracingOnTheDoorScene) {
    const SceneArrays door = box_scene(true);
    const Params path = base_params("PATH", 512);
    expect_agree(door, base_params("MLT", 256), path, "MLT, door");
    expect_agree(door, base_params("MMLT", 256), path, "MMLT, door");
}

TEST(Mlt, WithOnlyLargeStepsEqualsBdpt) {
    // p_large = 1: every proposal an independent path (an independence sampler over the bootstrap's b).
    Params mlt = base_params("MLT", 64);
    mlt.set("mlt_large_step", 1.0);
    expect_agree(box_scene(false), mlt, base_params("BDPT", 32), "MLT p_large = 1 vs BDPT");
}

TEST(Mlt, FurnaceImageAndBootstrapBrightnessAreTheClosedForm) {
    // The emissive closed sphere: every camera ray sees L = Le·(1 − ρ^(K+2))/(1 − ρ), so b — the mean of I over the
    // spread area — is that luminance, and so is every pixel of the image (the film's normalisation by b and by the
    // mutations per pixel). 8 runs each: mean within 5 standard errors of the spread (t, 7 dof: 1.6e-3).
    const SceneArrays sphere = furnace_scene(FurnaceScene::EmissiveSphere, 64, 32);
    const double expected = furnace_expected(FurnaceScene::EmissiveSphere, 3);
    for (const char* name : {"MLT", "MMLT"}) {
        Params p = base_params(name, 256);
        p.set("mlt_bootstrap", int64_t(4000));
        p.set("max_bounces", int64_t(3));
        p.set("width", int64_t(8));
        p.set("height", int64_t(6));
        const SeedMean image = seed_mean(render_seeds(sphere, p, k_runs));
        std::printf("%s furnace: image mean %.5f ± %.5f, expected %.5f\n", name, image.mean, image.standard_error,
                    expected);
        EXPECT_NEAR(image.mean, expected, 5.0 * image.standard_error + 1e-6) << name;
        std::vector<double> bs;
        for (int seed = 1; seed <= k_runs; ++seed) {
            Params q = p;
            q.set("seed", int64_t(seed));
            const Scene scene(sphere, q, nullptr);
            bs.push_back(mlt_bootstrap(scene, q, 2).b);
        }
        double m = 0.0, v = 0.0;
        for (double x : bs) m += x / double(bs.size());
        for (double x : bs) v += (x - m) * (x - m) / double(bs.size() - 1) / double(bs.size());
        std::printf("%s furnace: b %.5f ± %.5f\n", name, m, std::sqrt(v));
        EXPECT_NEAR(m, expected, 5.0 * std::sqrt(v) + 1e-6) << name;
    }
}

TEST(Mlt, MultiplexedPerDepthBrightnessSumsToTheWholeSamplesB) {
    // Σ_k b_k of MMLT (one strategy per depth, ×(k + 2)) and b of PSSMLT (the whole bidirectional sample) estimate
    // the same integral; every b_k is non-negative. 8 bootstrap runs each, t with 14 dof: 4.5 → 5e-4.
    const SceneArrays box = box_scene(false);
    std::vector<double> pss, mm;
    for (int seed = 1; seed <= k_runs; ++seed) {
        for (const char* name : {"MLT", "MMLT"}) {
            Params p = base_params(name, 1);
            p.set("seed", int64_t(seed));
            const Scene scene(box, p, nullptr);
            const MltBootstrap boot = mlt_bootstrap(scene, p, 2);
            (std::string(name) == "MLT" ? pss : mm).push_back(boot.b);
            if (std::string(name) == "MMLT") {
                EXPECT_EQ(boot.b_depth.size(), size_t(5 + 2));
                for (double bk : boot.b_depth) EXPECT_GE(bk, 0.0);
            }
        }
    }
    auto stats = [](const std::vector<double>& x, double* mean, double* var_mean) {
        *mean = 0.0;
        for (double v : x) *mean += v / double(x.size());
        *var_mean = 0.0;
        for (double v : x) *var_mean += (v - *mean) * (v - *mean) / double(x.size() - 1) / double(x.size());
    };
    double ma, va, mb, vb;
    stats(pss, &ma, &va);
    stats(mm, &mb, &vb);
    std::printf("Cornell box b: PSSMLT %.5f ± %.5f, MMLT %.5f ± %.5f\n", ma, std::sqrt(va), mb, std::sqrt(vb));
    EXPECT_GT(ma, 0.0);
    EXPECT_LT(std::fabs(ma - mb), 4.5 * std::sqrt(va + vb)) << "PSSMLT b " << ma << ", MMLT Σ b_k " << mb;
}

TEST(Mlt, DeterministicForAnyThreadCount) {
    const SceneArrays box = box_scene(false);
    for (const char* name : {"MLT", "MMLT"}) {
        Params p = base_params(name, 8);
        p.set("seed", int64_t(3));
        std::vector<float> first;
        for (int threads : {1, 2, 3}) {
            p.set("threads", int64_t(threads));
            const RenderResult r = render(box, p);
            if (first.empty())
                first = r.rgba;
            else
                EXPECT_EQ(r.rgba, first) << name << ", " << threads << " threads";
        }
    }
}

TEST(Mlt, CancelStopsTheRenderWithAFiniteImage) {
    for (const char* name : {"MLT", "MMLT"})
        for (int cancel_ms : {1, 1500}) {
            Params p = base_params(name, 1000000);
            p.set("width", int64_t(64));
            p.set("height", int64_t(48));
            Session s(box_scene(false), p);
            s.start();
            // Once during the bootstrap (a stage of the render), once during the chains' passes.
            std::this_thread::sleep_for(std::chrono::milliseconds(cancel_ms));
            s.cancel();
            s.join();
            ASSERT_FALSE(s.error()) << *s.error();
            EXPECT_EQ(s.progress().stop_reason, StopReason::Cancelled)
                << name << ", cancel after " << cancel_ms << " ms";
            int channels = 0;
            for (float v : s.get_pass("Combined", &channels)) ASSERT_TRUE(std::isfinite(v)) << name;
        }
}

TEST(Mlt, BadSettingsAreRejectedByName) {
    const std::vector<std::pair<std::string, Params::Value>> bad = {
        {"mlt_large_step", 1.5},    {"mlt_sigma", 0.0},         {"mlt_bootstrap", int64_t(0)},
        {"mlt_chains", int64_t(3)}, {"mlt_chains", int64_t(0)}, {"max_bounces", int64_t(-1)}};
    for (const char* name : {"MLT", "MMLT"}) {
        for (const auto& [key, value] : bad) {
            Params p = base_params(name, 4);
            p.set(key, value);
            try {
                make_integrator(p);
                ADD_FAILURE() << name << ": " << key << " accepted";
            } catch (const InvalidParameter& e) {
                EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
            }
        }
    }
}

}  // namespace
}  // namespace candela::test

namespace candela::test {
namespace {

// A measurement, not a test (disabled: run it with --gtest_also_run_disabled_tests --gtest_filter='MltMeasure*'):
// relative RMSE against a PATH reference and wall time for PATH, BDPT, MLT and MMLT on the door scene and the Cornell
// box (24 × 18, max bounces 5), for docs/metropolis.md. Times are wall clock of one run on whatever the machine does.
TEST(MltMeasure, DISABLED_ErrorAndTimeOnTheDoorSceneAndTheCornellBox) {
    for (bool door : {true, false}) {
        const SceneArrays arrays = box_scene(door);
        Params ref = base_params("PATH", door ? 16384 : 4096);
        ref.set("width", int64_t(24));
        ref.set("height", int64_t(18));
        ref.set("seed", int64_t(99));
        const RenderResult r = render(arrays, ref);
        auto lum = [](const RenderResult& x, size_t i) {
            return 0.2126 * x.rgba[4 * i] + 0.7152 * x.rgba[4 * i + 1] + 0.0722 * x.rgba[4 * i + 2];
        };
        double mean_ref = 0.0;
        const size_t n = size_t(r.width) * r.height;
        for (size_t i = 0; i < n; ++i) mean_ref += lum(r, i) / double(n);
        for (const char* name : {"PATH", "BDPT", "MLT", "MMLT"}) {
            for (int samples : {16, 64, 256}) {
                Params p = ref;
                p.set("integrator", std::string(name));
                p.set("samples", int64_t(samples));
                p.set("seed", int64_t(1));
                if (std::string(name) == "MLT" || std::string(name) == "MMLT") {
                    p.set("mlt_bootstrap", int64_t(20000));
                    p.set("mlt_chains", int64_t(100));
                }
                const auto t0 = std::chrono::steady_clock::now();
                const RenderResult x = render(arrays, p);
                const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
                double se = 0.0;
                for (size_t i = 0; i < n; ++i) se += (lum(x, i) - lum(r, i)) * (lum(x, i) - lum(r, i)) / double(n);
                std::printf("%s %-5s %4d: rel. RMSE %.4f, %.3f s\n", door ? "door   " : "cornell", name, samples,
                            std::sqrt(se) / mean_ref, secs);
            }
        }
    }
}

}  // namespace
}  // namespace candela::test
