// Motion blur (docs/light_paths.md, "Motion blur"): the transform interpolation, the scene's moving instances and
// camera, and the integrators that render it (all of them). The image of a moving scene is the time average of its
// still images over the shutter: a render with motion is compared, block by block, with the mean of still renders
// at evenly spaced times (the midpoint rule over the shutter), within statistical tolerances from both renders'
// noise estimates; the other integrators are compared with PATH on the moving scene.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "agreement.h"
#include "core/error.h"
#include "core/motion_transform.h"
#include "integrators/integrator.h"
#include "scene/scene.h"
#include "scene/shutter_time.h"
#include "scene/surface_sampler.h"
#include "session/session.h"
#include "test_helpers.h"

namespace candela::test {
namespace {

std::vector<float> rows_of(const Affine& a) {
    std::vector<float> r(16, 0.f);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j) r[4 * i + j] = a.m[i][j];
    r[15] = 1.f;
    return r;
}

Affine rotation_y(float angle, Vec3 t = Vec3(0.f)) {
    Affine a;
    a.m[0][0] = std::cos(angle);
    a.m[0][2] = std::sin(angle);
    a.m[2][0] = -std::sin(angle);
    a.m[2][2] = std::cos(angle);
    a.m[0][3] = t.x;
    a.m[1][3] = t.y;
    a.m[2][3] = t.z;
    return a;
}

Affine translation(Vec3 t) { return rotation_y(0.f, t); }

float max_difference(const Affine& a, const Affine& b) {
    float d = 0.f;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j) d = std::fmax(d, std::fabs(a.m[i][j] - b.m[i][j]));
    return d;
}

TEST(MotionTransform, DecompositionComposesBackToTheMatrix) {
    Affine m = rotation_y(0.7f, Vec3(1.f, -2.f, 3.f));
    m.m[0][1] = 0.3f;  // a shear
    for (int r = 0; r < 3; ++r) m.m[r][2] *= 2.5f;
    Affine mirrored = m;
    for (int r = 0; r < 3; ++r) mirrored.m[r][0] = -mirrored.m[r][0];
    EXPECT_LT(max_difference(DecomposedTransform::from(m).compose(), m), 1e-5f);
    EXPECT_LT(max_difference(DecomposedTransform::from(mirrored).compose(), mirrored), 1e-5f);
}

TEST(MotionTransform, RotationsInterpolateOnTheArc) {
    // A quarter turn over the shutter: at its middle an eighth turn (slerp), not the shrunken chord a linear blend
    // of the matrices gives; the translation moves linearly.
    const MotionTransform motion({rotation_y(0.f, Vec3(0.f)), rotation_y(1.5707963f, Vec3(2.f, 0.f, 0.f))});
    EXPECT_LT(max_difference(motion.at(0.5f), rotation_y(0.78539816f, Vec3(1.f, 0.f, 0.f))), 1e-5f);
    EXPECT_LT(max_difference(motion.at(0.25f), rotation_y(0.39269908f, Vec3(0.5f, 0.f, 0.f))), 1e-5f);
    EXPECT_LT(max_difference(motion.at(0.f), rotation_y(0.f)), 1e-6f);
    // Three samples: the second half follows the second pair.
    const MotionTransform three(
        {translation(Vec3(0.f)), translation(Vec3(1.f, 0.f, 0.f)), translation(Vec3(1.f, 4.f, 0.f))});
    EXPECT_LT(max_difference(three.at(0.75f), translation(Vec3(1.f, 2.f, 0.f))), 1e-6f);
}

/// A black box (half size 0.5; diffuse of `albedo` if given, and so is the emitting backdrop) 5 units in front of the camera against a white world,
/// moving from x0 to x1 over the shutter (a 2-step instance_motion), or still at x0 when x1 is not given.
SceneArrays moving_box(float x0, float x1, bool moves, bool emitter_backdrop = false, float albedo = 0.f) {
    MeshBuilder b;
    const uint32_t black = b.add_material(Color(albedo), Color(0.f));
    const uint32_t box = b.add_box(Vec3(0.5f), black);
    const std::vector<float> start = rows_of(translation(Vec3(x0, 0.f, -5.f)));
    b.add_instance(box, start.data());
    if (emitter_backdrop) {  // an emitting wall behind: light-rooted integrators then see the same image
        const uint32_t glow = b.add_material(Color(albedo), Color(1.f));  // reflecting the box's light if grey
        b.add_instance(b.add_quad_z(-6.f, 6.f, -6.f, 6.f, -8.f, glow));
    } else {
        b.world_color = {1.f, 1.f, 1.f};
    }
    SceneArrays a = b.arrays();
    if (moves) {
        const size_t instances = a.rows("instance_mesh");
        std::vector<float> motion;
        for (size_t i = 0; i < instances; ++i) {
            const float* still = a.get("instance_transform").data<float>() + 16 * i;
            const std::vector<float> end = rows_of(translation(Vec3(x1, 0.f, -5.f)));
            motion.insert(motion.end(), still, still + 16);
            const float* second = i == 0 ? end.data() : still;  // only the box moves
            motion.insert(motion.end(), second, second + 16);
        }
        a.set("instance_motion", ElemType::F32, {instances, 2, 4, 4}, motion.data());
    }
    return a;
}

/// Per-block means (b×b blocks, RGB mean) and their standard errors from the per-pixel noise estimates.
struct Blocks {
    std::vector<double> mean, sigma;
};
Blocks blocks_of(const RenderResult& r, int b) {
    Blocks out;
    for (int by = 0; by < r.height / b; ++by)
        for (int bx = 0; bx < r.width / b; ++bx) {
            double sum = 0.0, var = 0.0;
            for (int y = by * b; y < (by + 1) * b; ++y)
                for (int x = bx * b; x < (bx + 1) * b; ++x) {
                    const size_t i = size_t(y) * r.width + x;
                    sum += (r.rgba[4 * i] + r.rgba[4 * i + 1] + r.rgba[4 * i + 2]) / 3.0;
                    var += double(r.noise[i]) * r.noise[i];
                }
            out.mean.push_back(sum / (b * b));
            out.sigma.push_back(std::sqrt(var) / (b * b));
        }
    return out;
}

/// The mean of n still renders at the midpoints of n equal parts of the shutter (its σ combines theirs).
Blocks still_average(int n, int b, const std::function<RenderResult(float)>& render_at) {
    Blocks sum;
    for (int k = 0; k < n; ++k) {
        const Blocks one = blocks_of(render_at((float(k) + 0.5f) / float(n)), b);
        if (sum.mean.empty()) sum.mean.assign(one.mean.size(), 0.0), sum.sigma.assign(one.mean.size(), 0.0);
        for (size_t i = 0; i < one.mean.size(); ++i) {
            sum.mean[i] += one.mean[i] / n;
            sum.sigma[i] += one.sigma[i] * one.sigma[i] / (double(n) * n);
        }
    }
    for (double& s : sum.sigma) s = std::sqrt(s);
    return sum;
}

/// Every block agrees within 4.5 σ of the difference (two-sided false alarm ≈ 7e-6 per block, under 1e-3 for
/// the 64 blocks), plus `quadrature`: midpoint_bound's error of the still average.
void expect_blocks_agree(const Blocks& a, const Blocks& b, double quadrature, const std::string& what) {
    ASSERT_EQ(a.mean.size(), b.mean.size());
    double largest = 0.0;
    for (size_t i = 0; i < a.mean.size(); ++i) {
        const double sigma = std::sqrt(a.sigma[i] * a.sigma[i] + b.sigma[i] * b.sigma[i]);
        EXPECT_LE(std::fabs(a.mean[i] - b.mean[i]), 4.5 * sigma + quadrature)
            << what << ": block " << i << " " << a.mean[i] << " vs " << b.mean[i] << " (σ " << sigma << ")";
        largest = std::fmax(largest, std::fabs(a.mean[i] - b.mean[i]));
    }
    ::testing::Test::RecordProperty(what + "_largest_block_difference", std::to_string(largest));
}

/// The midpoint rule's error over the shutter for an edge of full contrast (1: black on white) sweeping `shift_px`
/// pixels across b×b blocks, with n still times. With the 1-pixel box filter a block's value is linear in the
/// edge's position while the edge crosses it and constant otherwise: piecewise linear in time with slope at most
/// s = shift_px/b per shutter, kinks where an edge enters or leaves (at most 4: two edges). The midpoint rule is
/// exact on linear pieces; a kink of slope jump s in a part of width h = 1/n costs at most s·h²/8.
double midpoint_bound(double shift_px, int n, int b) { return 4.0 * (shift_px / b) / (8.0 * n * n); }

Params motion_params(const std::string& integrator, int samples, int threads = 2) {
    Params p = basic_params(32, 32, samples, 0);
    p.set("integrator", integrator);
    p.set("threads", int64_t(threads));
    p.set("sampler", std::string("RANDOM"));
    return p;
}

// The camera (basic_params: a 36 mm sensor behind a 50 mm lens, 32 px) sees 1 unit at the box's front face
// (z = −4.5) as 32/(4.5·0.72) ≈ 9.9 px: moving the box 2 units sweeps ~20 px.
constexpr double k_shift_px = 20.0;

TEST(MotionBlur, MovingBoxIsTheTimeAverageOfStillBoxes) {
    const int n = 16, b = 4;
    const RenderResult moving = render(moving_box(-1.f, 1.f, true), motion_params("PATH", 512));
    const Blocks still = still_average(
        n, b, [&](float t) { return render(moving_box(-1.f + 2.f * t, 0.f, false), motion_params("PATH", 64)); });
    expect_blocks_agree(blocks_of(moving, b), still, midpoint_bound(k_shift_px, n, b), "PATH");
    // And it is not the still box at the shutter's middle: the blur is there.
    const Blocks middle = blocks_of(render(moving_box(0.f, 0.f, false), motion_params("PATH", 64)), b);
    double largest = 0.0;
    const Blocks m = blocks_of(moving, b);
    for (size_t i = 0; i < m.mean.size(); ++i) largest = std::fmax(largest, std::fabs(m.mean[i] - middle.mean[i]));
    EXPECT_GT(largest, 0.2);
}

/// The grey box before the grey emitting wall that the integrator comparisons below use, moving 2 units over the
/// shutter, and the params of `integrator` there: two bounces (motion_params has none), so paths wall → box → wall
/// (the indirect light between them) exist and every integrator's indirect estimate runs.
SceneArrays grey_moving_box() { return moving_box(-1.f, 1.f, true, true, 0.5f); }
Params grey_box_params(const std::string& integrator, int samples, int threads = 2) {
    Params p = motion_params(integrator, samples, threads);
    p.set("max_bounces", int64_t(2));
    return p;
}

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
        for (int i = 0; i < 400000 && !seen; ++i) {
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

TEST(MotionBlur, ShutterPassesAreStratifiedAndEveryPrefixSpreads) {
    // stratified_shutter_time: n passes hold one time in each 1/n of the shutter, and the first j of them leave no
    // gap over 4/j + 2/n (their strata's largest gap is under 4/j: shutter_time.h).
    for (uint64_t n : {1u, 2u, 3u, 7u, 16u, 40u, 64u, 100u, 257u}) {
        std::vector<int> hits(n, 0);
        std::vector<float> times;
        for (uint64_t j = 0; j < n; ++j) {
            const float t = stratified_shutter_time(99, j, n);
            ASSERT_GE(t, 0.f);
            ASSERT_LT(t, 1.f);
            ++hits[std::min<uint64_t>(n - 1, uint64_t(double(t) * double(n)))];
            times.push_back(t);
            if (j < 1) continue;
            std::vector<float> sorted(times);
            std::sort(sorted.begin(), sorted.end());
            double gap = 1.0 - sorted.back() + sorted.front();
            for (size_t i = 1; i < sorted.size(); ++i) gap = std::fmax(gap, sorted[i] - sorted[i - 1]);
            EXPECT_LE(gap, 4.0 / double(j + 1) + 2.0 / double(n)) << n << " passes, prefix " << j + 1;
        }
        for (uint64_t k = 0; k < n; ++k) EXPECT_EQ(hits[k], 1) << n << " passes, stratum " << k;
        // Another key jitters differently within the same strata.
        EXPECT_NE(stratified_shutter_time(99, 0, n), stratified_shutter_time(100, 0, n)) << n;
    }
}

TEST(MotionBlur, SurfacePointsAreWhereRaysFindThemAtTheirTime) {
    // Scene::surface_point (the surface sampler's points) of a moving box under a ShutterScope is the point a ray
    // traced at that time hits: the box's front face centre moves from x = −1 to x = 1.
    const PreparedScene prepared(moving_box(-1.f, 1.f, true), basic_params(4, 4, 1, 0));
    const Scene& scene = prepared.scene();
    ASSERT_TRUE(scene.object_moves(0));
    for (float t : {0.f, 0.25f, 1.f}) {
        const ShutterScope scope(t);
        const SurfaceSampler surfaces(scene);
        Vec3 lo(1e30f), hi(-1e30f);
        float pdf_sum = 0.f;
        for (int k = 0; k < 64; ++k) {
            const SurfaceSample s = surfaces.sample((k + 0.5f) / 64.f, Vec2{0.3f, 0.3f});
            if (s.hit.object != 0) continue;
            lo.x = std::min(lo.x, s.hit.p.x), hi.x = std::max(hi.x, s.hit.p.x);
            EXPECT_NEAR(surfaces.pdf(s.hit), s.pdf_area, 1e-6f * s.pdf_area);
            pdf_sum += s.pdf_area;
        }
        ASSERT_GT(pdf_sum, 0.f);
        // The box's points span its extent around its centre at time t (camera-world space: x is unchanged by the
        // scene's offset, which only translates).
        const float x = -1.f + 2.f * t;
        EXPECT_GT(hi.x - lo.x, 0.5f) << t;
        EXPECT_LE(hi.x - x, 0.5f + 1e-4f) << t;
        EXPECT_GE(lo.x - x, -0.5f - 1e-4f) << t;
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

/// The camera turning 10° about its vertical axis over the shutter (a pan) in front of a still box.
SceneArrays panning_camera(float t0, float t1) {
    SceneArrays a = moving_box(0.f, 0.f, false);
    const MotionTransform pan({rotation_y(0.f), rotation_y(0.17453293f)});
    const std::vector<float> start = rows_of(pan.at(t0)), end = rows_of(pan.at(t1));
    a.set("camera_to_world", ElemType::F32, {4, 4}, start.data());
    if (t0 != t1) {
        std::vector<float> motion(start);
        motion.insert(motion.end(), end.begin(), end.end());
        a.set("camera_motion", ElemType::F32, {2, 4, 4}, motion.data());
    }
    return a;
}

TEST(MotionBlur, CameraPanIsTheTimeAverageOfStillCameras) {
    // 10° of a 39.6° field over 32 px: the image slides ~8 px (9 taken for the bound: perspective stretches it).
    const int n = 16, b = 4;
    for (const char* name : {"PATH", "BDPT"}) {
        const RenderResult moving = render(panning_camera(0.f, 1.f), motion_params(name, 512));
        const Blocks still =
            still_average(n, b, [&](float t) { return render(panning_camera(t, t), motion_params(name, 64)); });
        expect_blocks_agree(blocks_of(moving, b), still, midpoint_bound(9.0, n, b), name);
    }
}

TEST(MotionBlur, ShadingUsesTheTransformAtTheRaysTime) {
    // A box turning a quarter turn about y: a ray down −z at time t meets its front face turned by t·90°, and the
    // hit's normal is that face's normal then (Embree's motion and the shading transform agree).
    MeshBuilder b;
    const uint32_t grey = b.add_material(Color(0.5f), Color(0.f));
    b.add_instance(b.add_box(Vec3(0.5f), grey), rows_of(translation(Vec3(0.f, 0.f, -5.f))).data());
    b.world_color = {1.f, 1.f, 1.f};
    SceneArrays a = b.arrays();
    std::vector<float> motion = rows_of(rotation_y(0.f, Vec3(0.f, 0.f, -5.f)));
    const std::vector<float> end = rows_of(rotation_y(1.5707963f, Vec3(0.f, 0.f, -5.f)));
    motion.insert(motion.end(), end.begin(), end.end());
    a.set("instance_motion", ElemType::F32, {1, 2, 4, 4}, motion.data());
    a.validate();
    const Scene scene(a, basic_params(8, 8, 1, 0), nullptr);
    ASSERT_TRUE(scene.has_motion());
    for (float t : {0.1f, 0.3f}) {  // the +z face faces the camera (within 45°)
        const ShutterScope scope(t);
        Ray ray;
        ray.o = Vec3(0.f, 0.f, 0.f);
        ray.d = Vec3(0.f, 0.f, -1.f);
        SurfaceHit hit;
        ASSERT_TRUE(scene.intersect(ray, &hit));
        const float angle = t * 1.5707963f;
        const Vec3 expected(std::sin(angle), 0.f, std::cos(angle));
        EXPECT_NEAR(dot(hit.ng, expected), 1.f, 1e-4f) << t;
        // The front face's distance: its centre is at 0.5 along the turned normal from the box's centre.
        EXPECT_NEAR(hit.t, 5.f - 0.5f / std::cos(angle), 1e-3f) << t;
    }
}

TEST(MotionBlur, BadMotionArraysAreNamed) {
    SceneArrays a = moving_box(-1.f, 1.f, false);
    const std::vector<float> one(16 * 3, 0.f);
    a.set("instance_motion", ElemType::F32, {3, 1, 4, 4}, one.data());
    try {
        a.validate();
        FAIL() << "no error";
    } catch (const InvalidScene& e) {
        EXPECT_NE(std::string(e.what()).find("instance_motion"), std::string::npos) << e.what();
    }
    SceneArrays c = moving_box(-1.f, 1.f, false);
    std::vector<float> nan(32, 0.f);
    nan[5] = std::nanf("");
    c.set("camera_motion", ElemType::F32, {2, 4, 4}, nan.data());
    EXPECT_THROW(c.validate(), InvalidScene);
}

TEST(MotionBlur, MovingEmittersStayStillAndSaySo) {
    // The box emits: its triangles are lights at fixed places, so it is not moved (in any integrator) and the
    // session's note says so, even for PATH.
    MeshBuilder b;
    const uint32_t glow = b.add_material(Color(0.f), Color(1.f));
    b.add_instance(b.add_box(Vec3(0.5f), glow), rows_of(translation(Vec3(-1.f, 0.f, -5.f))).data());
    SceneArrays a = b.arrays();
    std::vector<float> motion = rows_of(translation(Vec3(-1.f, 0.f, -5.f)));
    const std::vector<float> end = rows_of(translation(Vec3(1.f, 0.f, -5.f)));
    motion.insert(motion.end(), end.begin(), end.end());
    a.set("instance_motion", ElemType::F32, {1, 2, 4, 4}, motion.data());
    const PreparedScene scene(a, basic_params(4, 4, 1, 0));
    EXPECT_TRUE(scene.scene().has_still_moving_emitters());
    EXPECT_FALSE(scene.scene().has_motion());
    EXPECT_NE(unhonoured_features_note("PATH", ~0u, scene.scene()).find("moving emitting objects"), std::string::npos);
}

TEST(MotionBlur, EveryIntegratorRendersItAndOneThatDidNotWouldSaySo) {
    const PreparedScene scene(moving_box(-1.f, 1.f, true), basic_params(4, 4, 1, 0));
    // Every integrator of the registry renders motion blur (PHOTON and IRRADIANCE_CACHE by shutter passes with a
    // cache each): none gets the note.
    for (const IntegratorEntry& e : integrator_registry())
        EXPECT_TRUE(unhonoured_features_note(e.name, make_integrator(motion_params(e.name, 1))->honoured_features(),
                                             scene.scene())
                        .find("motion blur") == std::string::npos)
            << e.name;
    // One that did not would say so, and a still scene gets no note.
    EXPECT_NE(unhonoured_features_note("X", 0, scene.scene()).find("motion blur is not rendered"), std::string::npos);
    const PreparedScene still(moving_box(-1.f, 1.f, false), basic_params(4, 4, 1, 0));
    EXPECT_TRUE(unhonoured_features_note("X", 0, still.scene()).empty());
}

TEST(MotionBlur, AutoNotesWhatItsChoiceDoesNotRender) {
    // AUTO renders with the integrator it chose: a note (if any) is that integrator's, logged after the choice,
    // never one for AUTO itself; every choice renders motion blur, so no motion-blur note is logged.
    Params p = motion_params("AUTO", 2);
    Session s(moving_box(-1.f, 1.f, true), p);
    s.start();
    s.join();
    ASSERT_FALSE(s.error().has_value()) << *s.error();
    const std::vector<std::string> log = s.take_log();
    std::string chosen;
    for (const std::string& l : log)
        if (l.rfind("Auto: chose ", 0) == 0) chosen = l.substr(12, l.find(' ', 12) - 12);
    ASSERT_FALSE(chosen.empty());
    int notes = 0;
    for (const std::string& l : log) {
        EXPECT_NE(l.rfind("AUTO: ", 0), 0u) << l;
        if (l.find("motion blur is not rendered") != std::string::npos) {
            ++notes;
            EXPECT_EQ(l.rfind(chosen + ": ", 0), 0u) << l;
        }
    }
    EXPECT_EQ(notes, 0) << "AUTO chose " << chosen;  // every choice renders it
}

}  // namespace
}  // namespace candela::test
