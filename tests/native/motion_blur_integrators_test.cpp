// Motion blur in the integrators other than PATH (docs/light_paths.md, "Motion blur"): each renders the grey box
// moving before a grey emitting wall (motion_scenes.h) as PATH does — by blocks from the noise estimates where
// its error is independent between pixels, by independent runs where it is not — and the same image for any
// thread count; the cache integrators' shutter passes see a cancel in each of their stages.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include "agreement.h"
#include "motion_scenes.h"
#include "session/session.h"
#include "test_helpers.h"

namespace candela::test {
namespace {

/// The comparison by independent runs (agreement.h) of integrators whose error is correlated across pixels
/// (splats, shared light paths, Markov chains, photon maps and caches): `runs` against PATH's, each set of 8 seeds,
/// the image mean within 4.5 and every 4×4 block within 6.5 standard errors from the runs' spread (t with 14
/// degrees of freedom: false alarms 5e-4 per mean and 1.5e-5 per block, 1e-3 for the 64 blocks).
Agreement expect_runs_agree(const std::vector<RenderResult>& runs, const std::vector<RenderResult>& path,
                            const std::string& what) {
    const Agreement g = compare_seed_sets(runs, path, 4);
    std::printf("%s, moving box: means %.5f vs %.5f, z %.2f, worst block z %.2f of %d\n", what.c_str(), g.mean_a,
                g.mean_b, g.mean_z, g.worst_block_z, g.blocks);
    EXPECT_LT(std::fabs(g.mean_z), 4.5) << what;
    EXPECT_LT(std::fabs(g.worst_block_z), 6.5) << what << ": block " << g.worst_block;
    return g;
}

/// That the comparison can fail: `runs` of the still box at the shutter's middle — what an integrator that builds
/// its cache (or traces everything) at one time renders — are told apart from PATH's moving box.
void expect_one_time_fails(const std::vector<RenderResult>& runs, const std::vector<RenderResult>& path,
                           const std::string& what) {
    const Agreement g = compare_seed_sets(runs, path, 4);
    std::printf("%s at one time (the shutter's middle): worst block z %.1f of %d\n", what.c_str(), g.worst_block_z,
                g.blocks);
    EXPECT_GT(std::fabs(g.worst_block_z), 6.5) << what;
}

TEST(MotionBlur, LightAndBdptAgreeWithPathOnAMovingBox) {
    // The grey box before the grey emitting wall with two bounces: light paths (LIGHT's, BDPT's light subpaths)
    // leave the wall, light the box and come back, each at its path's (sample's) one shutter time. LIGHT's splats
    // make its error correlated across pixels: compared by independent runs.
    const SceneArrays scene = grey_moving_box();
    const std::vector<RenderResult> path = render_seeds(scene, grey_box_params("PATH", 64), 8);
    ASSERT_GT(seed_mean(path).mean, 0.5);  // the wall is seen
    for (const char* name : {"LIGHT", "BDPT"})
        expect_runs_agree(render_seeds(scene, grey_box_params(name, 64), 8), path, name);
    expect_one_time_fails(render_seeds(moving_box(0.f, 0.f, false, true, 0.5f), grey_box_params("BDPT", 64), 8), path,
                          "BDPT");
}

TEST(MotionBlur, PathGeneratorsAgreeWithPathOnAMovingBox) {
    // A grey box before a grey emitting wall (light between them: the generators' indirect estimates are
    // exercised: surface points, light paths and gathered rays all at the sample's one shutter time), each generator and
    // their MIS combination against PATH, block by block (expect_blocks_agree's 4.5 σ).
    const int b = 4;
    // Two bounces (motion_params has none), so paths wall → box → wall (the indirect term I) exist.
    Params path_params = motion_params("PATH", 256);
    path_params.set("max_bounces", int64_t(2));
    const Blocks path = blocks_of(render(moving_box(-1.f, 1.f, true, true, 0.5f), path_params), b);
    for (const char* name : {"SURFACE_SAMPLING", "SOURCE_SHOOTING", "RECEIVER_GATHERING"})
        for (bool mis : {false, true}) {
            Params p = motion_params(name, 256);
            p.set("max_bounces", int64_t(2));
            p.set("generators_mis", mis);
            const Blocks other = blocks_of(render(moving_box(-1.f, 1.f, true, true, 0.5f), p), b);
            expect_blocks_agree(other, path, 0.0, std::string(name) + (mis ? "_mis" : ""));
        }
}

TEST(MotionBlur, MltAndMmltAgreeWithPathOnAMovingBox) {
    // The shutter time is a coordinate of the chain's state. A Metropolis image's error is correlated across pixels,
    // so (as tests/native/mlt_test.cpp does) 8 independent runs per integrator are compared by their spread: mean
    // within 4.5 and 4×4 blocks within 6.5 standard errors (t with 14 dof: false alarms 5e-4 and 1.5e-5 per
    // comparison and block).
    const SceneArrays scene = moving_box(-1.f, 1.f, true, true, 0.5f);
    Params path = motion_params("PATH", 64);
    path.set("max_bounces", int64_t(2));
    for (const char* name : {"MLT", "MMLT"}) {
        Params p = motion_params(name, 256);
        p.set("max_bounces", int64_t(2));
        p.set("mlt_bootstrap", int64_t(4000));
        p.set("mlt_chains", int64_t(32));
        const Agreement g = compare_seed_sets(render_seeds(scene, p, 8), render_seeds(scene, path, 8), 4);
        std::printf("%s, moving box: means %.5f vs %.5f, z %.2f, worst block z %.2f of %d\n", name, g.mean_a, g.mean_b,
                    g.mean_z, g.worst_block_z, g.blocks);
        EXPECT_LT(std::fabs(g.mean_z), 4.5) << name;
        EXPECT_LT(std::fabs(g.worst_block_z), 6.5) << name << ": block " << g.worst_block;
    }
}

TEST(MotionBlur, SppmAgreesWithPathOnAMovingBox) {
    // One shutter time per iteration (camera pass, photons and statistics share it): the average over iterations
    // is the time average. 8 independent runs (seeds) compared by their spread as for MLT above: SPPM's error is
    // correlated across iterations through the shrinking radii. The grey box's indirect light (photons) is small
    // beside the direct light, so its radius bias stays far below the tolerance.
    const SceneArrays scene = moving_box(-1.f, 1.f, true, true, 0.5f);
    Params path = motion_params("PATH", 64);
    path.set("max_bounces", int64_t(2));
    Params p = motion_params("SPPM", 32);
    p.set("max_bounces", int64_t(2));
    const Agreement g = compare_seed_sets(render_seeds(scene, p, 8), render_seeds(scene, path, 8), 4);
    std::printf("SPPM, moving box: means %.5f vs %.5f, z %.2f, worst block z %.2f of %d\n", g.mean_a, g.mean_b,
                g.mean_z, g.worst_block_z, g.blocks);
    EXPECT_LT(std::fabs(g.mean_z), 4.5);
    EXPECT_LT(std::fabs(g.worst_block_z), 6.5) << "block " << g.worst_block;
}

/// The mean luminance of each 4×4 block (and, last, of the image) of each run of a set.
std::vector<std::vector<double>> block_means(const std::vector<RenderResult>& runs) {
    std::vector<std::vector<double>> out;
    for (const RenderResult& r : runs) {
        std::vector<double> m;
        double all = 0.0;
        for (int by = 0; by + 4 <= r.height; by += 4)
            for (int bx = 0; bx + 4 <= r.width; bx += 4) {
                double sum = 0.0;
                for (int y = by; y < by + 4; ++y)
                    for (int x = bx; x < bx + 4; ++x) {
                        const float* p = &r.rgba[4 * (size_t(y) * r.width + x)];
                        sum += 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
                    }
                m.push_back(sum / 16.0);
                all += sum / 16.0;
            }
        m.push_back(all / double(m.size()));
        out.push_back(m);
    }
    return out;
}

/// expect_runs_agree for the cache integrators, whose biases act on the light their caches hold: a block (and the
/// image mean) may differ from PATH's by `allowance` × its indirect light — PATH's value less that of PATH's direct
/// light only (`direct`, max_bounces 0) — and the excess beyond it is judged as there (z from the runs' spread:
/// mean within 4.5, blocks within 6.5). Returns the worst block's z (0 when within the allowance).
double expect_runs_agree_but_for_cache_bias(const std::vector<RenderResult>& runs,
                                            const std::vector<RenderResult>& path,
                                            const std::vector<RenderResult>& direct, double allowance,
                                            const std::string& what, bool expect = true) {
    const auto a = block_means(runs), b = block_means(path), d = block_means(direct);
    auto stats = [](const std::vector<std::vector<double>>& set, size_t k, double* var_of_mean) {
        double mu = 0.0, ss = 0.0;
        for (const auto& run : set) mu += run[k] / double(set.size());
        for (const auto& run : set) ss += (run[k] - mu) * (run[k] - mu);
        *var_of_mean = ss / double(set.size() - 1) / double(set.size());
        return mu;
    };
    double worst = 0.0, mean_z = 0.0;
    const size_t n = a.front().size();
    for (size_t k = 0; k < n; ++k) {
        double va, vb, vd;
        const double ma = stats(a, k, &va), mb = stats(b, k, &vb), md = stats(d, k, &vd);
        const double excess = std::fmax(0.0, std::fabs(ma - mb) - allowance * std::fmax(0.0, mb - md));
        const double z = std::copysign(excess / std::sqrt(std::fmax(va + vb, 1e-300)), ma - mb);
        if (k + 1 == n) {
            mean_z = z;
            std::printf("%s, moving box: means %.5f vs %.5f (indirect %.5f)", what.c_str(), ma, mb, mb - md);
        } else if (std::fabs(z) >= std::fabs(worst)) {
            worst = z;
        }
    }
    std::printf(", z %.2f beyond the allowance, worst block z %.2f of %zu\n", mean_z, worst, n - 1);
    if (expect) {
        EXPECT_LT(std::fabs(mean_z), 4.5) << what;
        EXPECT_LT(std::fabs(worst), 6.5) << what;
    }
    return worst;
}

TEST(MotionBlur, PhotonAndIrradianceCacheAgreeWithPathOnAMovingBox) {
    // One shutter pass per sample, each with a photon map or irradiance cache of its own time, used only by that
    // pass's camera paths (photon_integrator.cpp, ic_integrator.cpp): the average over passes is the time average.
    // Compared by independent runs, since a pass's map or cache correlates its error across pixels, but for their
    // bias on the light their caches hold: up to 30 % of each block's indirect light (here the light the box throws
    // back on the wall, 0.2–0.5 % of the wall's brightness). Measured beside PATH at 512 samples: PHOTON's density
    // estimates next to the small box's edges (a disc half off a face finds half its photons: also in the still
    // scene) and IRRADIANCE_CACHE's 64-ray pass gathers (a record whose few rays miss the box gets both a low E and
    // a long reach R; docs/irradiance_cache.md, "Motion blur") put the wall's indirect light 10–20 % low. The still
    // box at the shutter's middle — what both rendered before, one cache at one time — fails the same comparison.
    const SceneArrays scene = grey_moving_box();
    const SceneArrays middle = moving_box(0.f, 0.f, false, true, 0.5f);
    const std::vector<RenderResult> path = render_seeds(scene, grey_box_params("PATH", 64), 8);
    Params direct_only = grey_box_params("PATH", 64);
    direct_only.set("max_bounces", int64_t(0));
    const std::vector<RenderResult> direct = render_seeds(scene, direct_only, 8);
    for (const char* name : {"PHOTON", "IRRADIANCE_CACHE"}) {
        const Params p = grey_box_params(name, 16);
        expect_runs_agree_but_for_cache_bias(render_seeds(scene, p, 8), path, direct, 0.3, name);
        const double one_time = expect_runs_agree_but_for_cache_bias(render_seeds(middle, p, 8), path, direct, 0.3,
                                                                     std::string(name) + " at one time", false);
        EXPECT_GT(std::fabs(one_time), 6.5) << name;
    }
}

TEST(MotionBlur, CacheIntegratorsSeeACancelInALaterShutterPassesCacheStage) {
    // Each shutter pass builds its cache in stages of its own; a cancel while a later pass (work done ≥ 1) shoots its
    // photons, builds its kd-tree or runs its pre-pass ends the render cancelled, without error, before its samples.
    struct Case {
        const char* integrator;
        const char* stage;
    };
    for (const Case c : {Case{"PHOTON", "Tracing photons"}, Case{"PHOTON", "Building photon map"},
                         Case{"IRRADIANCE_CACHE", "Irradiance cache"}}) {
        Params p = grey_box_params(c.integrator, 64);
        p.set("global_photons", int64_t(8000000));  // 1.28 M paths per pass: stages long enough to be seen
        p.set("ic_gather_rays", int64_t(65536));    // 1,024 rays per record
        Session s(grey_moving_box(), p);
        s.start();
        bool seen = false;
        // Polled until seen (or the render ends): a deadline only against a hang, far beyond a pass's time even
        // under the sanitizers, never a measure of speed.
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(10);
        while (!seen && std::chrono::steady_clock::now() < deadline) {
            const SessionProgress pr = s.progress();
            if (pr.stage.name == c.stage && pr.work_done >= 1)
                seen = true;
            else if (pr.stop_reason != StopReason::Running)
                break;
            else
                std::this_thread::sleep_for(std::chrono::microseconds(100));
        }
        s.cancel();
        s.join();
        const std::string what = std::string(c.integrator) + ", " + c.stage;
        ASSERT_TRUE(seen) << what;
        const SessionProgress pr = s.progress();
        EXPECT_EQ(pr.stop_reason, StopReason::Cancelled) << what;
        EXPECT_LT(pr.work_done, 64) << what;
        EXPECT_FALSE(s.error().has_value()) << what;
    }
}

TEST(MotionBlur, ImagesDoNotDependOnTheThreadCount) {
    for (const char* name : {"PATH", "LIGHT", "BDPT", "SURFACE_SAMPLING", "SOURCE_SHOOTING", "RECEIVER_GATHERING",
                             "MLT", "MMLT", "SPPM", "PHOTON", "IRRADIANCE_CACHE"}) {
        // A grey box and wall with two bounces: every path generator's indirect estimate runs.
        Params p1 = motion_params(name, 8, 1), p2 = motion_params(name, 8, 2);
        p1.set("max_bounces", int64_t(2)), p2.set("max_bounces", int64_t(2));
        const RenderResult one = render(moving_box(-1.f, 1.f, true, true, 0.5f), p1);
        const RenderResult two = render(moving_box(-1.f, 1.f, true, true, 0.5f), p2);
        EXPECT_EQ(one.rgba, two.rgba) << name;
    }
}

}  // namespace
}  // namespace candela::test
