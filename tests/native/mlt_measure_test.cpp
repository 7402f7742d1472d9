// A measurement, not a test (disabled: run it with --gtest_also_run_disabled_tests --gtest_filter='MltFloor*'):
// the error of MLT and MMLT on the door scene (mlt_scenes.h, 24 × 18 pixels, max bounces 5) against a BDPT reference,
// as the mutations grow, for two bootstrap sizes — whether the bootstrap's error in b is the floor — and the film's
// own noise estimate beside it (docs/metropolis.md). The reference is two independent BDPT halves; its own noise
// (a quarter of their squared difference, per pixel) is subtracted from every mean squared error. Every figure is the
// mean over 8 seeds (± its standard error from their spread, by the delta method); times are wall clock on whatever
// the machine does. Environment: MLT_FLOOR_SEEDS (8), MLT_FLOOR_FIRST_SEED (1), MLT_FLOOR_ONLY ("MMLT 20000": one
// configuration).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "mlt_scenes.h"

namespace candela::test {
namespace {

int env_int(const char* name, int fallback) {
    const char* v = std::getenv(name);
    return v ? std::atoi(v) : fallback;
}

double lum(const RenderResult& x, size_t i) {
    return 0.2126 * x.rgba[4 * i] + 0.7152 * x.rgba[4 * i + 1] + 0.0722 * x.rgba[4 * i + 2];
}

TEST(MltFloor, DISABLED_DoorSceneErrorAgainstMutationsAndBootstrap) {
    const SceneArrays door = box_scene(true);
    Params base = base_params("BDPT", 4096);
    base.set("width", int64_t(24));
    base.set("height", int64_t(18));
    RenderResult half[2];
    for (int h = 0; h < 2; ++h) {
        Params p = base;
        p.set("seed", int64_t(99 + h));
        half[h] = render(door, p);
    }
    const size_t n = size_t(half[0].width) * half[0].height;
    std::vector<double> ref(n);
    double mean_ref = 0.0, ref_noise = 0.0;
    for (size_t i = 0; i < n; ++i) {
        ref[i] = 0.5 * (lum(half[0], i) + lum(half[1], i));
        mean_ref += ref[i] / double(n);
        ref_noise += 0.25 * std::pow(lum(half[0], i) - lum(half[1], i), 2) / double(n);
    }
    std::printf("reference: BDPT 2 x 4096 spp, mean %.5f, its own relative RMSE %.4f\n", mean_ref,
                std::sqrt(ref_noise) / mean_ref);
    struct Config {
        const char* integrator;
        int bootstrap;
    };
    const char* only = std::getenv("MLT_FLOOR_ONLY");  // e.g. "MMLT 20000"
    for (const Config& c : {Config{"BDPT", 0}, Config{"MLT", 20000}, Config{"MLT", 160000}, Config{"MMLT", 20000},
                            Config{"MMLT", 160000}}) {
        if (only && std::string(only) != std::string(c.integrator) + " " + std::to_string(c.bootstrap)) continue;
        for (int samples : {64, 256, 1024}) {
            double mse = 0.0, mse2 = 0.0, secs = 0.0, estimate = 0.0;
            const int k_seeds = env_int("MLT_FLOOR_SEEDS", 8), first = env_int("MLT_FLOOR_FIRST_SEED", 1);
            for (int seed = first; seed < first + k_seeds; ++seed) {
                Params p = base;
                p.set("integrator", std::string(c.integrator));
                p.set("samples", int64_t(samples));
                p.set("seed", int64_t(seed));
                if (c.bootstrap > 0) {
                    p.set("mlt_bootstrap", int64_t(c.bootstrap));
                    p.set("mlt_chains", int64_t(100));
                }
                const auto t0 = std::chrono::steady_clock::now();
                const RenderResult x = render(door, p);
                secs += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / k_seeds;
                double se = 0.0;
                for (size_t i = 0; i < n; ++i) se += (lum(x, i) - ref[i]) * (lum(x, i) - ref[i]) / double(n);
                mse += (se - ref_noise) / k_seeds;
                mse2 += (se - ref_noise) * (se - ref_noise) / k_seeds;
                estimate += x.relative_error * x.relative_error / k_seeds;
            }
            const double rmse = std::sqrt(std::max(mse, 1e-30));
            const double se_mse = std::sqrt(std::max(mse2 - mse * mse, 0.0) / (k_seeds - 1));
            std::printf(
                "door %-4s bootstrap %6d, %4d per pixel: rel. RMSE %.4f ± %.4f (film's estimate %.4f), %.2f s\n",
                c.integrator, c.bootstrap, samples, rmse / mean_ref, se_mse / (2.0 * rmse) / mean_ref,
                std::sqrt(estimate), secs);
        }
    }
}

}  // namespace
}  // namespace candela::test
